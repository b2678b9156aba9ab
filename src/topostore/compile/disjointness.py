"""The pairs of disjoint classes of a TBox, held once as rows instead of a rule per pair.

Why
---
Protégé's "make siblings disjoint" writes one axiom per pair of siblings: a tutorial-style TBox of
400 classes has 11,228 told pairs, 22,458 ordered pairs of disjoint class expressions.  Compiled a
rule per pair (``different-disjoint`` both ways, the check ``cax-dw`` per told pair), they were 94 %
of the rule set: every pass after compilation (folding, the difference joins, simplification, the
guard) read them one by one, and LOAD grew with the square of the siblings.

Here the compiler records the rows (:class:`Disjointness`) and emits no rule for them.  What needs a
rule per pair gets the instantiations, made once when first asked (:meth:`Disjointness.rules`): the
maintained rules and checks of a robot step (:attr:`.rule.RuleSet.inference_rules`,
:attr:`.rule.RuleSet.checks`).  A full REASON runs the generic rule over the rows
(:mod:`.schema_program`) and the generic check over the rows whose classes both have members, one
query (:func:`check_query`); both name the row's axiom exactly as its instantiation would.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

from ..rdf.collector import collector_paused
from ..rdf.terms import sparql
from ..rdf.vocab import TYPE
from .model import Expr
from .rule import Rule
from .schema import Row, SchemaRule, schema_rule

#: the generic rules the rows instantiate
DIFFERENT, CHECK = "different-disjoint", "cax-dw"


@dataclass(frozen=True, slots=True)
class ToldPair:
    """A told pair of disjoint classes (``cax-dw``): its row and the two class expressions of the axiom
    (the axiom and the violation's message name them; written only when asked: a TBox of thousands
    of siblings has hundreds of thousands of pairs, few ever violated)."""

    row: Row
    a: Expr
    b: Expr

    @property
    def origin(self) -> str:
        return f"{self.a} DisjointWith {self.b}"

    @property
    def labels(self) -> tuple[str, str]:
        return str(self.a), str(self.b)


@dataclass
class Disjointness:
    """The rows of disjointness: ordered pairs for ``different-disjoint`` (members of disjoint classes
    are different), told pairs for the check ``cax-dw``."""

    #: (C, D) with C and D disjoint class expressions, both orders, each once: row -> the expressions
    different: dict[Row, tuple[Expr, Expr]] = field(default_factory=dict)
    #: the told pairs, each once (one axiom each way is one pair: its check was one rule), by the
    #: pair's terms in sorted order
    told: dict[Row, ToldPair] = field(default_factory=dict)
    _rules: tuple[list[Rule], list[Rule]] | None = field(default=None, init=False, repr=False, compare=False)

    def add_different(self, row: Row | None, a: Expr, b: Expr) -> bool:
        """Record an ordered pair of disjoint expressions; False when there is no row (owl:Thing)."""
        if row is None:
            return False
        self.different.setdefault(row, (a, b))
        self._rules = None
        return True

    def add_told(self, row: Row | None, a: Expr, b: Expr) -> bool:
        """Record a told pair for the check; False when there is no row (owl:Thing: a check of one class)."""
        if row is None:
            return False
        self.told.setdefault(tuple(sorted(row)), ToldPair(row, a, b))
        self._rules = None
        return True

    def __len__(self) -> int:
        return len(self.different) + len(self.told)

    def renamed(self, names: Mapping[str, str]) -> Disjointness:
        """The rows with each class of ``names`` replaced by its name there (an anonymous class folded
        into its one named equivalent, as :mod:`.fold` does in the rules); rows that become one are one."""
        rows = [*self.different, *(pair.row for pair in self.told.values())]
        if not names or not any(c in names for row in rows for c in row):
            return self  # no row names a folded class (a class disjoint with itself is a told row only)
        out = Disjointness()
        for (a, b), exprs in self.different.items():
            out.add_different((names.get(a, a), names.get(b, b)), *exprs)
        for pair in self.told.values():
            a, b = pair.row
            out.add_told((names.get(a, a), names.get(b, b)), pair.a, pair.b)
        return out

    def rules(self) -> tuple[list[Rule], list[Rule]]:
        """(the ``different-disjoint`` rules, the ``cax-dw`` checks): one per row, made once."""
        if self._rules is None:
            different, check = schema_rule(DIFFERENT), schema_rule(CHECK)
            with collector_paused():  # tens of thousands of rules on a large TBox: see ..rdf.collector
                self._rules = ([different.instantiate(row, f"{a} and {b} are disjoint")
                                for row, (a, b) in self.different.items()],
                               [_check(check, p) for p in self.told.values()])
        return self._rules

    def representatives(self) -> list[Rule]:
        """One ``different-disjoint`` rule and one check per class of the rows, on that class alone: their
        body keys are the keys every instantiation reads (a row's keys are its classes' keys), found
        without making a rule per pair."""
        different, check = schema_rule(DIFFERENT), schema_rule(CHECK)
        classes = sorted({c for row in self.different for c in row})
        return [r for c in classes for r in (different.instantiate((c, c), ""), check.instantiate((c, c), ""))]

    def classes(self) -> set[str]:
        """Every class a told pair names (the keys the generic check reads)."""
        return {c for pair in self.told.values() for c in pair.row}

    def told_among(self, with_members: Iterable[str]) -> list[ToldPair]:
        """The told pairs whose two classes both have members: the only ones the check can match."""
        have = set(with_members)
        return [p for p in self.told.values() if p.row[0] in have and p.row[1] in have]


def _check(check: SchemaRule, pair: ToldPair) -> Rule:
    """The ``cax-dw`` check of one told pair (each expression written once: its label names it in the
    origin too)."""
    labels = pair.labels
    return check.instantiate(pair.row, f"{labels[0]} DisjointWith {labels[1]}", labels)


def check_query(pairs: list[ToldPair], limit: int) -> str:
    """The generic check over ``pairs`` (one query): an individual in both classes of a pair."""
    values = " ".join(f"({a} {b})" for a, b in (p.row for p in pairs))
    t = sparql(TYPE)
    return (f"SELECT DISTINCT ?x ?c ?d WHERE {{\n  VALUES (?c ?d) {{ {values} }}\n  ?x {t} ?c .\n  ?x {t} ?d .\n}}"
            f" LIMIT {limit}")


__all__ = ["CHECK", "DIFFERENT", "Disjointness", "ToldPair", "check_query"]
