"""What is a row of a file of ``rules/owl/`` (topostore.compile.schema.SchemaRule.row_of) and what is not.

A rule carrying a setting no instantiation has (its body as written, a known conclusion that makes its
asks idle) is no row: the rule set keeps it as it is, and a full REASON runs it as it is instead of the
generic rule over the table, which would drop the setting.
"""

from __future__ import annotations

from dataclasses import replace

from topostore.compile.condition import test as condition_test
from topostore.compile.rule import Atom, RuleSet
from topostore.compile.schema import schema_rule
from topostore.compile.schema_program import full_program
from topostore.compile.schema_tables import hold_tables

TYPE = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>"


def _subclass_rules(n: int) -> list:
    sco = schema_rule("cax-sco")
    return [sco.instantiate((f"<urn:c{i}>", f"<urn:c{i + 1}>"), f"c{i} SubClassOf c{i + 1}") for i in range(n)]


def test_a_rule_with_settings_of_its_own_is_no_row() -> None:
    sco = schema_rule("cax-sco")
    rule = _subclass_rules(1)[0]
    assert sco.row_of(rule) == ("<urn:c0>", "<urn:c1>")
    written = rule.body + (Atom("?x", TYPE, "<urn:implied>"),)
    own = [replace(rule, written=written), replace(rule, written_conditions=(condition_test("!isLiteral(?x)"),)),
           replace(rule, unless_known=rule.head), replace(rule, value_range=("<urn:p>", "<urn:d>"))]
    assert [sco.row_of(r) for r in own] == [None] * len(own)


def test_the_rule_set_and_a_full_reason_keep_such_a_rule_as_it_is() -> None:
    """Twenty subclass rows run generically in a full REASON; the one whose body as written differs and
    the one asking only where its conclusion is unknown stay rules of their own, settings included."""
    rules = _subclass_rules(20)
    premises = rules[3].body + (Atom("?x", TYPE, "<urn:implied>"),)
    rules[3] = replace(rules[3], written=premises)
    rules[7] = replace(rules[7], unless_known=rules[7].head)
    kept, tables = hold_tables(rules)
    assert kept == [rules[3], rules[7]] and tables is not None and len(tables) == 18
    program = full_program(RuleSet(rules=kept, tables=tables), threshold=0)
    assert "cax-sco" in program.rows and ("<urn:c3>", "<urn:c4>") not in program.rows["cax-sco"]
    run = program.rules.rules
    assert [r.written for r in run if r.written] == [premises]
    assert [r.unless_known for r in run if r.unless_known is not None] == [rules[7].head]
