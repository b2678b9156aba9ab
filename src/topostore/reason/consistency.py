"""Consistency: every match of a check rule is an inconsistency, reported with
the axiom it violates and the individuals involved.

A check reads the default dataset (asserted, inferred, helper graphs), where each pattern is looked
up in every graph.  Before the checks run, one query finds which graphs hold facts of each key their
bodies read (:func:`.present.key_graphs`): a check with a key that has no fact cannot match and is not
run, and an atom whose key lies in one graph is read in that graph, as a full REASON's rules are
(:func:`.order.single_graphs`).  Filters still read the whole dataset.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pyoxigraph import Literal, NamedNode

from ..compile.generic import PREFIXES
from ..compile.rule import ReadKey, Rule, RuleSet
from ..rdf.vocab import ASSERTED, AUX, INFERRED
from ..stores.base import Store, unskolem
from .present import KeyGraphs, key_graphs

#: How many matches of one check are reported (one is enough to be inconsistent).
MAX_REPORTED = 20


def short(term) -> str:
    term = unskolem(term)
    if isinstance(term, Literal):
        return str(term)
    if isinstance(term, NamedNode):
        v = term.value
        return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]
    return str(term)


@dataclass(frozen=True)
class Violation:
    """One inconsistency: the rule, the axiom it was compiled from, the individuals."""

    rule: str
    axiom: str
    individuals: dict = field(default_factory=dict)
    message: str = ""

    def __str__(self) -> str:
        return f"{self.message} [{self.rule}: {self.axiom}]"


#: The graphs the checks read, as their default dataset
GRAPHS = [ASSERTED, INFERRED, AUX]


def check_text(rule: Rule, graphs: dict[ReadKey, NamedNode] | None = None) -> str:
    """The query of a check; ``graphs``: the one graph holding every fact of some read keys."""
    proj = " ".join(rule.violation)
    return f"SELECT DISTINCT {proj} WHERE {{\n  {rule.where(graphs=graphs)}\n}} LIMIT {MAX_REPORTED}"


def check_keys(rules: RuleSet) -> set[ReadKey]:
    """The read keys of the checks' body atoms."""
    return {atom.read_key() for rule in rules.checks for atom in rule.body}


def one_graphs(rule: Rule, found: KeyGraphs) -> dict[ReadKey, NamedNode] | None:
    """The one graph of each key of ``rule`` whose facts lie in one graph; None when a key the rule
    needs has no fact (the check cannot match)."""
    out: dict[ReadKey, NamedNode] = {}
    for atom in rule.body:
        where = found.get(atom.read_key())
        if where is None:  # a variable predicate: the whole dataset
            continue
        if not where:
            return None
        if len(where) == 1:
            out[atom.read_key()] = next(iter(where))
    return out


def _message(rule: Rule, row: dict) -> str:
    text = rule.message or f"{rule.name} violated"
    for var, value in row.items():
        text = text.replace("{" + var + "}", short(value))
    return text


def check_consistency(store: Store, rules: RuleSet, keys: KeyGraphs | None = None) -> list[Violation]:
    """All violations of the check rules over asserted ∪ inferred knowledge.

    ``keys``: the graphs of :data:`GRAPHS` holding facts of each key the checks read
    (:func:`.present.key_graphs`, asked here when not given)."""
    if not rules.checks:
        return []
    if keys is None:
        keys = key_graphs(store, check_keys(rules), GRAPHS)
    found: list[Violation] = []
    seen: set = set()
    for rule in rules.checks:
        graphs = one_graphs(rule, keys)
        if graphs is None:
            continue
        rows = [{v[1:]: solution[v[1:]] for v in rule.violation if solution[v[1:]] is not None}
                for solution in store.query(check_text(rule, graphs), graphs=GRAPHS, prefixes=PREFIXES)]
        # sorted, so that the report does not depend on evaluation order
        for row in sorted(rows, key=lambda r: [str(v) for v in r.values()]):
            key = (rule.name, rule.origin, frozenset(row.values()))
            if key in seen:  # the same violation found with its variables swapped
                continue
            seen.add(key)
            found.append(Violation(rule.name, rule.origin, {k: unskolem(v) for k, v in row.items()}, _message(rule, row)))
    return found
