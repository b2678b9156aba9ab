"""A full REASON's rules: the instantiations of a large schema table run as one generic rule.

The compiled rule set holds one rule per axiom of the kinds with a schema row (:mod:`.schema`): what the robot
step needs, and cheap while a kind has few axioms.  A full REASON over a TBox with many axioms of a
kind pays for each of those rules in every round (a text to plan, an update to run); the generic rule
of ``rules/owl/`` does the same work in one evaluation, joining the rows written into its schema
graph.  :func:`full_program` makes that choice per rule: above :data:`GENERIC_ROWS` instantiations,
they are replaced by the generic rule over their rows.

The rows are read back from the compiled rules (:meth:`.SchemaRule.row_of`), not from the TBox: what
the passes after compilation did (a class folded into its anonymous equivalent, a rule dropped as a
duplicate) is kept, and the generic rule over those rows is, by construction, the union of the rules
it replaces.  A chaining rule's rows (cax-sco, prp-spo1) are closed first: the hierarchy is then
one row deep, and its closure takes one evaluation instead of one round per level.

The pairs of disjoint classes are not compiled rules at all: the rule set holds them as rows
(:mod:`.disjointness`), and the program takes them from there (the generic ``different-disjoint`` above
the threshold, else its instantiations); the told pairs' check runs over the rows in
:func:`..reason.consistency.check_consistency`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from pyoxigraph import NamedNode

from ..stores.base import Store
from .disjointness import DIFFERENT
from .rule import Rule, RuleSet
from .schema import Row, SchemaRule, schema_rules, template_of

#: A rule kind with more instantiations than this runs as its generic rule in a full REASON.
#: Measured (docs/benchmarks-history.md, "Generic OWL rules"): on the tutorial-style TBox of 100 and 400
#: classes, and on the 10,000-location map, whose kinds have at most a handful of rows.
GENERIC_ROWS = 16

#: rows per INSERT DATA request when the schema graphs are written
_CHUNK = 2_000


@dataclass
class GenericProgram:
    """The rule set a full REASON runs, and the rows its generic rules read."""

    rules: RuleSet
    #: per generic rule, its rows (closed for a chaining rule)
    rows: dict[str, list[Row]] = field(default_factory=dict)

    def graphs(self) -> list[NamedNode]:
        return [schema_rules()[name].graph for name in self.rows]

    def write(self, store: Store) -> None:
        """Write each generic rule's rows into its schema graph (replacing what a failed run left)."""
        if not self.rows:
            return
        self.drop(store)
        for name, rows in self.rows.items():
            generic = schema_rules()[name]
            if not store.round_trips:  # in process: one bulk write of terms, no text to parse
                store.add_scratch(generic.triple_terms(rows), generic.graph)
                continue
            triples = [t for row in rows for t in generic.triples(row)]
            for start in range(0, len(triples), _CHUNK):
                store.update(f"INSERT DATA {{ GRAPH {generic.graph} {{ {' '.join(triples[start:start + _CHUNK])} }} }}")

    def drop(self, store: Store) -> None:
        if self.rows:
            store.drop_graphs(self.graphs())


def closed(rows: list[Row]) -> list[Row]:
    """The transitive closure of two-term rows (a pair ``(a, a)`` says nothing and is left out).

    A start's walk stops at a node whose closure an earlier start found, taking that set whole:
    closing rows that are already nearly closed (the compiler's restriction subsumption, tens of
    thousands of rows) then costs set unions, not a walk per start over every reachable row."""
    succ: dict[str, list[str]] = {}
    for a, b in rows:
        succ.setdefault(a, []).append(b)
    found: dict[str, set[str]] = {}
    for start, first in succ.items():
        seen: set[str] = set()
        todo = list(first)
        while todo:
            node = todo.pop()
            if node in seen:
                continue
            seen.add(node)
            if node in found:  # everything it reaches is reached, and needs no walk of its own
                seen |= found[node]
            else:
                todo.extend(succ.get(node, ()))
        found[start] = seen
    return [(start, node) for start in succ for node in sorted(found[start] - {start})]


def _instances(rules: list[Rule]) -> dict[str, list[tuple[int, Row]]]:
    """Per generic inference rule (its file's name), the compiled rules that are its instantiations: (index, row).

    A check is left as it is: a full REASON runs the checks after the materialisation, once the
    schema graphs are dropped (the told pairs of disjoint classes, held as rows, are checked there
    in one query over the pairs whose classes have members)."""
    found: dict[str, list[tuple[int, Row]]] = {}
    for i, rule in enumerate(rules):
        if rule.is_check:
            continue
        template = template_of(rule)
        row = template.row_of(rule) if template is not None else None
        if row is not None:
            found.setdefault(template.key, []).append((i, row))
    return found


def _evaluables(generic: SchemaRule, rows: list[Row]) -> list[Rule]:
    """The generic rule once per head graph its rows' instantiations write (inferred, helper, or both)."""
    r = generic.rule
    if r.aux_head is not None or r.head is None:  # one graph whatever the row (different-disjoint's helper)
        return [generic.evaluable(bool(r.aux_head))]
    graphs = {generic.row_aux(row) for row in rows}
    return [generic.evaluable(aux) for aux in (False, True) if aux in graphs]


def rows_threshold(generic: SchemaRule) -> int:
    """Above how many instantiations a full REASON runs ``generic`` generically: its file's
    ``# generic-rows:`` header, else :data:`GENERIC_ROWS`."""
    return GENERIC_ROWS if generic.generic_rows is None else generic.generic_rows


def full_program(ruleset: RuleSet, threshold: int | None = None) -> GenericProgram:
    """``ruleset`` with every generic rule of more than ``threshold`` instantiations run generically
    (None: each rule's own, :func:`rows_threshold`).

    Derived once per rule set (:meth:`.RuleSet.derived`): reading the rows back from tens of thousands
    of instantiations and closing the hierarchies took most of a full REASON's own time on a large TBox.
    The program is read, never changed, by the REASONs that run it."""
    return ruleset.derived(("full-program", threshold), lambda: _full_program(ruleset, threshold))


def _full_program(ruleset: RuleSet, threshold: int | None) -> GenericProgram:
    rules = ruleset.compiled_rules()  # the schema tables' rows bound, then generic where large
    program = GenericProgram(ruleset)
    replaced: dict[int, list[Rule]] = {}
    held = _held_rows(ruleset, threshold, program)
    for name, found in _instances(rules).items():
        generic = schema_rules()[name]
        if len(found) <= (rows_threshold(generic) if threshold is None else threshold):
            continue
        rows = list(dict.fromkeys(row for _, row in found))
        program.rows[name] = closed(rows) if generic.chains else rows
        first = found[0][0]
        replaced[first] = _evaluables(generic, rows)
        replaced.update({i: [] for i, _ in found[1:]})
    if replaced or ruleset.disjointness is not None or ruleset.tables is not None:
        new = [r for i, rule in enumerate(rules) for r in replaced.get(i, [rule])]
        # the rows held apart join as the other tables' rules do; the checks stay the rule set's
        # (:func:`..reason.consistency.check_consistency` runs the told pairs' check generically)
        program.rules = replace(ruleset, rules=new + held, disjointness=None, tables=None)
    return program


def _held_rows(ruleset: RuleSet, threshold: int | None, program: GenericProgram) -> list[Rule]:
    """The inference rules of the rows the rule set holds apart (:mod:`.disjointness`): the generic
    rule over them (its rows recorded in ``program``) above the threshold, else their instantiations."""
    table = ruleset.disjointness
    if table is None or not table.different:
        return []
    generic = schema_rules()[DIFFERENT]
    rows = list(table.different)
    if len(rows) <= (rows_threshold(generic) if threshold is None else threshold):
        return table.rules()[0]
    program.rows[DIFFERENT] = rows
    return _evaluables(generic, rows)


__all__ = ["GENERIC_ROWS", "GenericProgram", "closed", "full_program", "rows_threshold"]
