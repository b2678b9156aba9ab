"""OWL restrictions → rules: cardinality, someValuesFrom and allValuesFrom, with their fillers.

A named part of :class:`~.owl.OwlCompiler` (``compiler.restrictions``) that needs several fillers of one
property and asks whether they are pairwise different: what a tableau
reasoner concludes from ``≥ n``, ``≤ n`` and ``= n`` restrictions beyond
OWL 2 RL (see :mod:`.owl`).
"""

from __future__ import annotations

import weakref
from itertools import combinations
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode

from ..rdf.terms import sparql
from ..rdf.vocab import DIFFERENT, SAME_AS, THING, TYPE
from . import condition as cond
from . import data_ranges
from .condition import Condition
from .counting import PAIRWISE_MAX, UNREACHABLE, count_at_least, counting_notice
from .model import Expr
from .property_hierarchy import name as prop_name
from .rule import Atom
from .schema_rows import filler_row

if TYPE_CHECKING:
    from .owl import OwlCompiler
from .snippets import (
    NOT_DIFFERENT_READS,
    candidate_atom,
    different_atom,
    distinct_values,
    in_datatype,
    known_different,
    not_different,
    surely_in_datatype,
)

T = str(TYPE)
#: filter reads of a rule testing known differences in FILTER EXISTS
DIFFERENT_READS = frozenset({("p", str(DIFFERENT))})


def term_before(a: str, b: str) -> str:
    """SPARQL test: term ``a`` sorts strictly before term ``b`` (a total order on IRIs and literals)."""
    return (f"STR({a}) < STR({b}) || (STR({a}) = STR({b}) && (isLiteral({a}) && isLiteral({b})) && "
            f"(STR(DATATYPE({a})) < STR(DATATYPE({b})) || "
            f"(STR(DATATYPE({a})) = STR(DATATYPE({b})) && LANG({a}) < LANG({b}))))")


def nm(term: NamedNode) -> str:
    """Short name of an IRI for messages (local part after # or /)."""
    v = term.value
    if v.startswith(data_ranges.PREFIX):
        return data_ranges.readable(term)
    return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]


class RestrictionRules:
    """Rules of restrictions with fillers, emitted through the compiler that owns this part.

    The compiler provides the TBox (``tb``), ``emit()``, the notices list and its helpers
    ``member()``, ``prop_atom()``, ``is_data()``, ``all_expressions()`` and ``filler_subsumed()``.
    """

    def __init__(self, compiler: OwlCompiler) -> None:
        # a weak reference: the compiler holds this part, and a cycle would keep both (and the whole
        # TBox) alive past the compilation, until a full collection (tests/test_compile_cycles.py)
        self.compiler = weakref.proxy(compiler)

    @staticmethod
    def counts(n: int) -> bool:
        """Whether ``n`` values are asked for by counting rather than pairwise: above PAIRWISE_MAX.
        Up to it the pairwise form is cheap and sees every kind of difference; the rules of small
        cardinalities (a map's "exactly one visitedAt") stay as they were."""
        return n > PAIRWISE_MAX

    def _counted(self, e: Expr, x: str, n: int) -> tuple[list[Atom], list[Condition]]:
        """Body atoms and conditions: ``x`` has at least ``n`` values of ``e`` known different, counted."""
        v = "?v"
        data = self.compiler.is_data(e.prop, e)
        more, test = self._filler_test(v, e)
        values = [self.compiler.prop_atom(x, e.prop, v)] + more
        tests = [test] if test is not None else []
        extra, conditions = count_at_least(x, values, tests, v, n, data)
        if not data:
            notice = counting_notice(str(e))
            if notice not in self.compiler.notices:
                self.compiler.notices.append(notice)
        return values + extra, tests + conditions

    def require_different(self, pairs: list[tuple[str, str]], body: list[Atom], filters: list[Condition],
                          origin: str) -> tuple[list[Atom], list[Condition], frozenset]:
        """(body, filters, filter reads) requiring every pair to be known different.

        One pair is a join atom.  Several pairs are tested with ``FILTER EXISTS``
        once the fillers are bound: as join atoms, the optimizer may start from
        the "different" relation, which holds for every pair of an AllDifferent
        group, and enumerate all n-cliques of the map's individuals."""
        if len(pairs) <= 1:
            return body + self.ask_different(pairs, body, filters, origin), filters, frozenset()
        self.ask_different(pairs, body, filters, origin)
        tests = [known_different(a, b) for a, b in pairs]
        return body, filters + tests, DIFFERENT_READS

    def ask_different(self, pairs: list[tuple[str, str]], body: list[Atom], filters: list[Condition],
                      origin: str) -> list[Atom]:
        """Atoms requiring each pair to be known different, after emitting the
        candidate rule that makes the difference rules look at these pairs.

        Every pair of fillers has the same shape, so one candidate rule over two
        fillers (the atoms and filters that mention neither other filler) asks
        about all of them, in both orders: its cost is k² for k fillers, where a
        candidate rule over the whole n-filler body cost kⁿ."""
        if pairs:
            a, b = pairs[0]
            others = {y for pair in pairs for y in pair} - {a, b}
            pair_body = [t for t in body if not (t.variables() & others)]
            pair_filters = [f for f in filters if not (f.variables & others)]
            self.compiler.emit("different-candidate", origin, pair_body, candidate_atom(a, b),
                      pair_filters + [cond.test(f"!sameTerm({a}, {b})")])
        return [different_atom(a, b) for a, b in pairs]

    def _filler_test(self, var: str, e: Expr) -> tuple[list[Atom], Condition | None]:
        if e.datatype is not None:
            return [], cond.test(surely_in_datatype(var, e.datatype))
        if self.compiler.is_data(e.prop, e):
            return [], cond.test(f"isLiteral({var})")
        return self.compiler.member(var, e.filler), None

    def _fillers(self, e: Expr, x: str, n: int) -> tuple[list[Atom], list[Condition], list[tuple[str, str]], list[str]]:
        """Body atoms and filters for ``n`` fillers of restriction ``e`` on ``x``, and
        the pairs that must be different (object fillers) — data fillers get a
        distinct-values filter instead."""
        ys = [f"?y{i}" for i in range(1, n + 1)]
        atoms: list[Atom] = []
        filters: list[Condition] = []
        for y in ys:
            atoms.append(self.compiler.prop_atom(x, e.prop, y))
            more, test = self._filler_test(y, e)
            atoms += more
            if test is not None:
                filters.append(test)
        pairs = list(combinations(ys, 2))
        if self.compiler.is_data(e.prop, e):
            filters += [cond.test(distinct_values(a, b)) for a, b in pairs]
            pairs = []
        # n pairwise different fillers can always be listed in increasing term order: asking for that
        # order finds each set of fillers once instead of once per permutation (n! times)
        filters += [cond.test(term_before(a, b)) for a, b in zip(ys, ys[1:], strict=False)]
        return atoms, filters, pairs, ys

    def lower_bound_rules(self, e: Expr, node: str, origin: str) -> None:
        x = "?x"
        n = 1 if e.kind == "some" else e.n
        if n == 0 or n >= UNREACHABLE:
            return
        if e.kind == "some" and self.compiler.instantiate(filler_row(e, self.compiler.is_data(e.prop, e)), origin,
                                                          "cls-svf1"):
            return
        if self.counts(n):
            atoms, filters = self._counted(e, x, n)
            reads: frozenset = frozenset()
        else:
            atoms, filters, pairs, _ = self._fillers(e, x, n)
            atoms, filters, reads = self.require_different(pairs, atoms, filters, origin)
        name = {"some": "cls-svf1", "min": "ext-min-card"}.get(e.kind, "ext-exact-card")
        if e.kind != "exact":
            self.compiler.emit(name, origin, atoms, Atom(x, T, node), filters, reads)
            return
        # exact: the minimum is met; a maximum must be known too
        told = self.compiler.single_valued.get(e.prop) if e.n == 1 else None
        if told is not None:
            why = "functional property" if told == e.prop else f"at most one value, as {prop_name(told)} is functional"
            self.compiler.emit(name, origin + f" ({why})", atoms, Atom(x, T, node), filters, reads)
        for m in self.compiler.all_expressions():
            if m.node != e.node and m.kind in ("max", "exact") and m.prop == e.prop and m.n <= e.n \
                    and self.compiler.filler_subsumed(e, m):
                self.compiler.emit(name, origin + f" (maximum known from {m})", atoms + [Atom(x, T, sparql(m.node))],
                          Atom(x, T, node), filters, reads)

    def upper_bound_rules(self, e: Expr, node: str, origin: str) -> None:
        x = "?x"
        data = self.compiler.is_data(e.prop, e)
        member = [Atom(x, T, node)]
        if e.n == 0:
            atoms, filters, _, _ = self._fillers(e, x, 1)
            self.compiler.emit("cls-maxqc2" if e.filler or e.datatype else "cls-maxc1", origin, member + atoms,
                      filters=filters, violation=(x, "?y1"),
                      message=f"{{x}} has a value of {nm(e.prop.iri)} but is in {e}")
            return
        name = "cls-maxqc3" if e.filler or e.datatype else "cls-maxc2"
        message = f"{{x}} has more than {e.n} different values of {nm(e.prop.iri)} but is in {e}"
        if e.n + 1 >= UNREACHABLE:
            return  # no store holds that many values (and e.n > 1: no sameAs rule below)
        if self.counts(e.n + 1):
            atoms, filters = self._counted(e, x, e.n + 1)
            self.compiler.emit(name, origin, member + atoms, filters=filters, violation=(x,), message=message)
        else:
            atoms, filters, pairs, ys = self._fillers(e, x, e.n + 1)
            atoms, filters, reads = self.require_different(pairs, member + atoms, filters, origin)
            self.compiler.emit(name, origin, atoms, filters=filters, reads=reads, violation=(x, *ys), message=message)
        if e.n == 1 and not data:
            # two values that are not known different are the same individual
            atoms, filters, _, _ = self._fillers(e, x, 2)
            self.compiler.emit("cls-maxqc4" if e.filler else "cls-maxc2", origin, member + atoms,
                      Atom("?y1", str(SAME_AS), "?y2"),
                      filters + [cond.test("!sameTerm(?y1, ?y2) && isIRI(?y1) && isIRI(?y2)"),
                                 not_different("?y1", "?y2")],
                      NOT_DIFFERENT_READS, stratum=1)

    def all_rules(self, e: Expr, node: str, origin: str) -> None:
        x, y = "?x", "?y"
        body = [Atom(x, T, node), self.compiler.prop_atom(x, e.prop, y)]
        if e.datatype is not None:
            test = in_datatype(y, e.datatype)
            if test:
                self.compiler.emit("cls-avf", origin, body, filters=[cond.test(f"!({test})")], violation=(x, y),
                          message=f"{{x}} has a value outside {nm(e.datatype)} for {nm(e.prop.iri)}")
        elif not self.compiler.instantiate(filler_row(e, self.compiler.is_data(e.prop, e)), origin, "cls-avf") \
                and e.filler is not None and e.filler.node != THING:
            self.compiler.emit("cls-avf", origin, body, Atom(y, T, sparql(e.filler.node)))


__all__ = ["DIFFERENT_READS", "RestrictionRules", "nm", "term_before"]
