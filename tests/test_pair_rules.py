"""The rules per pair of disjoint classes a robot step maintains, built cheaply (compile/schema.py's
instantiation from a prototype, topostore.rdf.collector): each is the rule the dataclass builds from the
substituted template, field for field, with the same derived reads, filters and graph of its head."""

from __future__ import annotations

import gc

import pytest

from topostore.compile import condition as cond
from topostore.compile.disjointness import CHECK, DIFFERENT
from topostore.compile.rule import Rule
from topostore.compile.schema import schema_rule, schema_rules
from topostore.rdf.collector import collector_paused
from topostore.rdf.vocab import INTERNAL, SKOLEM_PREFIX
from topostore.reason.flip import filter_variables

ROWS = [("<http://example.org/A>", "<http://example.org/B>"),
        (f"<{SKOLEM_PREFIX}x1>", "<http://example.org/B>"),  # a class expression (skolemised)
        (f"<{INTERNAL}helper>", f"<{SKOLEM_PREFIX}x2>")]


def ordinary(name: str, row: tuple[str, ...], origin: str, labels: tuple[str, ...] | None) -> Rule:
    """The instantiation built the ordinary way: every schema variable substituted, through Rule()."""
    template = schema_rule(name)
    bound = dict(zip(template.variables, row))
    r = template.rule

    def put(a):
        return type(a)(bound.get(a.s, a.s), bound.get(a.p, a.p), bound.get(a.o, a.o), a.aux)

    message = r.message
    for var, label in zip(template.variables, labels or ()):
        message = message.replace("{" + var[1:] + "}", label)
    return Rule(r.name, origin, tuple(put(a) for a in r.body), put(r.head) if r.head is not None else None,
                r.conditions, r.filter_reads, template.reported, message, r.aux_head, r.stratum)


def same(made: Rule, expected: Rule) -> None:
    assert made == expected and hash(made) == hash(expected)
    assert made.origin == expected.origin and made.message == expected.message
    assert made.reads() == expected.reads() and made.writes() == expected.writes()
    assert made.filters == expected.filters and made.head_aux() == expected.head_aux()
    assert made.sparql() == expected.sparql()


@pytest.mark.parametrize("row", ROWS)
@pytest.mark.parametrize("name", [DIFFERENT, CHECK])
def test_a_pair_rule_is_the_ordinary_instantiation(name: str, row: tuple[str, str]) -> None:
    labels = ("A", "B") if name == CHECK else None
    same(schema_rule(name).instantiate(row, "o", labels), ordinary(name, row, "o", labels))


def test_every_template_instantiates_as_the_ordinary_way() -> None:
    """Templates whose head names a schema variable decide its graph per row; the others once."""
    for name, template in schema_rules().items():
        row = tuple(f"<http://example.org/t{i}>" for i in range(len(template.variables)))
        same(template.instantiate(row, "o"), ordinary(name, row, "o", tuple(t[1:-1].rsplit("/", 1)[-1] for t in row)))
        internal = tuple(f"<{INTERNAL}t{i}>" for i in range(len(template.variables)))
        same(template.instantiate(internal, "o", ["x"] * len(internal)), ordinary(name, internal, "o", ("x",) * len(internal)))


def test_instantiations_leave_the_template_and_each_other_alone() -> None:
    template = schema_rule(DIFFERENT)
    before = (template.rule, template.rule.body, template.rule.origin)
    a, b = (template.instantiate(row, f"o{i}") for i, row in enumerate(ROWS[:2]))
    assert a.body != b.body and a.head == b.head and (a.origin, b.origin) == ("o0", "o1")
    assert (template.rule, template.rule.body, template.rule.origin) == before
    assert all("?c" not in (x.s, x.o) and "?d" not in (x.s, x.o) for x in a.body)


def test_filter_variables_of_rules_with_and_without_filters() -> None:
    plain = schema_rule(DIFFERENT).instantiate(ROWS[0], "o")
    assert filter_variables(plain) == frozenset()
    filtered = Rule("r", "o", plain.body, plain.head, (cond.parse("FILTER(?a != ?b)"),))
    assert filter_variables(filtered) == {"a", "b"}


def test_the_collector_is_paused_in_the_block_and_restored_after() -> None:
    assert gc.isenabled()
    with collector_paused():
        assert not gc.isenabled()
        with collector_paused():
            assert not gc.isenabled()
        assert not gc.isenabled()  # an inner block leaves the collector as it found it: off
    assert gc.isenabled()
    with pytest.raises(RuntimeError), collector_paused():
        raise RuntimeError("a failed build")
    assert gc.isenabled()
