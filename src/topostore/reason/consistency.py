"""Consistency: every match of a check rule is an inconsistency, reported with
the axiom it violates and the individuals involved."""

from __future__ import annotations

from dataclasses import dataclass, field

from pyoxigraph import Literal, NamedNode

from ..compile.generic import PREFIXES
from ..compile.rule import Rule, RuleSet
from ..rdf.vocab import ASSERTED, AUX, INFERRED
from ..stores.base import Store, unskolem

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


def check_text(rule: Rule) -> str:
    proj = " ".join(rule.violation)
    return f"SELECT DISTINCT {proj} WHERE {{\n  {rule.where()}\n}} LIMIT {MAX_REPORTED}"


def _message(rule: Rule, row: dict) -> str:
    text = rule.message or f"{rule.name} violated"
    for var, value in row.items():
        text = text.replace("{" + var + "}", short(value))
    return text


def check_consistency(store: Store, rules: RuleSet) -> list[Violation]:
    """All violations of the check rules over asserted ∪ inferred knowledge."""
    found: list[Violation] = []
    seen: set = set()
    graphs = [ASSERTED, INFERRED, AUX]
    for rule in rules.checks:
        rows = [{v[1:]: solution[v[1:]] for v in rule.violation if solution[v[1:]] is not None}
                for solution in store.query(check_text(rule), graphs=graphs, prefixes=PREFIXES)]
        # sorted, so that the report does not depend on evaluation order
        for row in sorted(rows, key=lambda r: [str(v) for v in r.values()]):
            key = (rule.name, rule.origin, frozenset(row.values()))
            if key in seen:  # the same violation found with its variables swapped
                continue
            seen.add(key)
            found.append(Violation(rule.name, rule.origin, {k: unskolem(v) for k, v in row.items()}, _message(rule, row)))
    return found
