"""What the unnamed value of an existential is, drawn as the existentials its subject is then in.

topostore names no individual for the value of ``≥n p.D`` (n ≥ 1, ``∃p.D`` as ``≥1 p.D``), yet every
such value is in more than ``D``: in each range of ``p`` and of its super-property expressions (an
equivalent property's, the domain of an inverse's: :func:`.property_hierarchy.subject_classes` of
``p⁻``), and in the filler of each universal ``∀q.G`` with ``p ⊑ q`` (or ``p = q``) its subject is in.
So the subject is in every ``≥m p'.X`` with ``p ⊑ p'`` (or ``p = p'``), ``m ≤ n`` and ``X`` told to hold
every value that is in all of those classes, as a tableau reasoner finds (Pellet: ``p rdfs:range R``,
``E ⊑ ∃p.D`` and ``C ≡ ∃p.R`` put every ``E`` in ``C``, and ``E`` under ``C``).  Two kinds of rule:

* from the filler and the ranges alone, a subsumption between two restrictions (``∃p.D ⊑ ∃p'.R``): a
  row of ext-restriction-sub, read as the told ones;
* with a universal, ``x ∈ ≥n p.D`` and ``x ∈ ∀q.G`` ⇒ ``x ∈ ≥m p'.X`` (ext-some-all): a rule per such
  triple of restrictions, over the types of one individual, so that the universal may be told of another
  class of it (``x a U``, ``U ⊑ ∀p.G``); classification's prototypes (a class told both) find the class
  under ``≥m p'.X`` by the same rule.

Only told subsumption is read (:class:`.fillers.Subsumption`, datatype subsumption for a data range):
``X`` named and above one of the value's classes, or an intersection whose members each are (or a class
defined as one).  What goes
the other way (a sub-property's range, a universal on a sub-property, a domain of ``p``) says nothing
of the value, and gives nothing.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from pyoxigraph import NamedNode

from ..rdf.terms import sparql
from ..rdf.vocab import TYPE
from .datatypes import implied_ranges
from .fillers import Subsumption
from .model import Expr, Prop, TBox, describe
from .property_hierarchy import inverse, name, subject_classes
from .rule import Atom, Rule
from .schema import schema_rule

#: What a value is told to be: its named classes with their told superclasses, its class expressions,
#: its datatypes.
Value = tuple[frozenset[NamedNode], tuple[Expr, ...], tuple[NamedNode, ...]]


def lower_bound(e: Expr) -> int:
    """How many values of its property ``e`` gives each member (0: not an existential)."""
    if e.prop is None:
        return 0
    if e.kind == "some":
        return 1
    return e.n if e.kind in ("min", "exact") else 0


class ExistentialValues:
    """The existentials each existential's unnamed value makes its subject a member of."""

    def __init__(self, tb: TBox, told: Subsumption, supers: dict[Prop, frozenset[Prop]],
                 exprs: Iterable[Expr]) -> None:
        self.tb = tb
        self.told = told
        self.supers = supers
        self.exprs = list(exprs)
        #: the existentials a subject may be found in (an exact cardinality is also a maximum: not here),
        #: by property, then by named filler (None: any other filler)
        self.wanted: dict[Prop, dict[NamedNode | None, list[Expr]]] = {}
        for b in self.exprs:
            if b.kind != "exact" and lower_bound(b) >= 1:
                key = b.filler.node if b.filler is not None and b.filler.is_named and b.datatype is None else None
                self.wanted.setdefault(b.prop, {}).setdefault(key, []).append(b)
        #: :meth:`ranges`' answers
        self._ranges: dict[Prop, Value] = {}
        #: :meth:`helping`'s answers
        self._helping: dict[tuple[Prop, NamedNode], list[tuple[Expr, frozenset[int]]]] = {}
        #: :meth:`candidates`' answers
        self._candidates: dict[tuple[Prop, Prop], list[Expr]] = {}
        #: :meth:`members_held`'s answers
        self._held: dict[tuple[NamedNode, NamedNode], frozenset[int]] = {}
        #: the named classes defined as an intersection (``X ≡ A ⊓ B``): a value in ``A`` and in ``B`` is an ``X``
        #: (those an existential above is into: no other is looked up)
        fillers = {node for by_filler in self.wanted.values() for node in by_filler}
        self.defined: dict[NamedNode, list[Expr]] = {}
        for x, y in tb.equivalent:
            for named, d in ((x, y), (y, x)):
                if named.is_named and named.node in fillers and d.kind == "and" and d.members:
                    self.defined.setdefault(named.node, []).append(d)
        #: the existentials a value holds only by two of its classes at once (an intersection, a data range,
        #: a class defined as an intersection) or that need more than one value, by property
        self.joint: dict[Prop, list[Expr]] = {}
        for q, by_filler in self.wanted.items():
            self.joint[q] = [b for bs in by_filler.values() for b in bs
                             if lower_bound(b) >= 2 or b.datatype is not None or b.filler is None
                             or b.filler.kind == "and" or b.filler.node in self.defined]

    def ranges(self, p: Prop) -> Value:
        """What every value of ``p`` is: the ranges of ``p`` and of its super-expressions, the domains of
        its inverses; the data ranges of a data property and of its super-properties."""
        found = self._ranges.get(p)
        if found is None:
            classes = tuple(c for _, c in subject_classes(self.tb, self.supers, inverse(p)))
            props = {p, *self.supers.get(p, ())}
            datatypes = tuple(dt for q, dt in self.tb.data_range if Prop(q) in props)
            found = self._ranges[p] = (self._named(classes), classes, datatypes)
        return found

    def filler(self, e: Expr) -> Value:
        """What the filler of restriction ``e`` tells its values to be."""
        classes = (e.filler,) if e.filler is not None else ()
        return self._named(classes), classes, (e.datatype,) if e.datatype is not None else ()

    def _named(self, classes: Iterable[Expr]) -> frozenset[NamedNode]:
        return frozenset().union(*(self.told.named_supers(c) for c in classes))

    @staticmethod
    def join(*values: Value) -> Value:
        """A value that is all of ``values`` at once."""
        return (frozenset().union(*(v[0] for v in values)), tuple(c for v in values for c in v[1]),
                tuple(dt for v in values for dt in v[2]))

    def holds(self, value: Value, b: Expr) -> bool:
        """Told: every value that is ``value`` is in ``b``'s filler (None: any)."""
        if b.datatype is not None:
            return bool(value[2]) and (b.datatype in value[2] or b.datatype in implied_ranges(value[2]))
        return b.filler is None or self._class_holds(value, b.filler)

    def _class_holds(self, value: Value, f: Expr, seen: frozenset[NamedNode] = frozenset()) -> bool:
        if f.is_named:  # told under one of the value's classes (their named superclasses), or defined
            return f.node in value[0] or (f.node not in seen and any(
                self._class_holds(value, d, seen | {f.node}) for d in self.defined.get(f.node, ())))
        if any(self.told.classes(c, f) for c in value[1]):
            return True
        return f.kind == "and" and bool(f.members) and all(self._class_holds(value, m, seen) for m in f.members)

    def _named_holding(self, value: Value) -> set[NamedNode]:
        """The named classes every value that is ``value`` is told to be in: its own, and those defined as an
        intersection it meets."""
        return {*value[0], *(x for x in self.defined if x not in value[0] and self._class_holds(value, Expr(x, "named")))}

    def reached(self, a: Expr, value: Value, beside: Callable[[Expr], bool]) -> list[Expr]:
        """The existentials ``≥m p'.X`` a member of ``a`` is in when ``a``'s value is ``value`` (``p'`` a
        super-expression of ``a``'s property or itself, ``m`` at most ``a``'s bound), leaving out
        ``a`` itself and those ``beside`` says are reached already."""
        n = lower_bound(a)
        named = self._named_holding(value)
        found: list[Expr] = []
        for q in (a.prop, *sorted(self.supers.get(a.prop, ()), key=str)):
            by_filler = self.wanted.get(q, {})
            candidates = [b for node in named for b in by_filler.get(node, ())] + by_filler.get(None, [])
            for b in candidates:
                if b.node != a.node and lower_bound(b) <= n and b not in found and not beside(b) \
                        and self.holds(value, b):
                    found.append(b)
        return found

    def subsumed_by_ranges(self) -> list[tuple[Expr, Expr]]:
        """The pairs (``a``, ``b``) of existentials with ``a ⊑ b`` through the ranges of ``a``'s property or a
        class defined as an intersection, not through ``a``'s filler's told subsumption alone (those are
        ext-card-sub's and ext-restriction-sub's already)."""
        pairs = []
        for a in self.exprs:
            if lower_bound(a) < 1:
                continue
            value = self.join(self.filler(a), self.ranges(a.prop))
            pairs += [(a, b) for b in self.reached(a, value, lambda b, a=a: self.told.fillers(a, b))]
        return pairs

    def universals(self) -> dict[Prop, list[Expr]]:
        """The universals with a filler, by property."""
        found: dict[Prop, list[Expr]] = {}
        for u in self.exprs:
            if u.kind == "all" and u.prop is not None and (u.filler is not None or u.datatype is not None):
                found.setdefault(u.prop, []).append(u)
        return found

    def by_universal(self, u: Expr) -> list[Expr]:
        """The existentials ``∃p'.X`` (a bound of one) with ``p'`` ``u``'s property or a super-expression of it
        and ``X`` told to hold ``u``'s filler with the ranges of its property: a member of ``u`` with any value
        of that property is in them, whatever the existential that gave the value (ext-all-value)."""
        ranges = self.ranges(u.prop)
        probe = Expr(u.node, "some", prop=u.prop)
        # what the ranges give alone, every existential below gives already (ext-restriction-sub)
        return [b for b in self.reached(probe, self.join(self.filler(u), ranges), lambda b: self.holds(ranges, b))
                if lower_bound(b) == 1]

    def with_universals(self) -> tuple[list[tuple[Expr, Prop]], list[tuple[Expr, Expr]], list[tuple[Expr, Expr, Expr]]]:
        """What a universal says of an existential's value: the rows of ext-some-value (an existential, a
        property its value is a value of) and of ext-all-value (a universal, an existential it gives with any
        value, :meth:`by_universal`), for named properties; and the triples (``a``, ``u``, ``b``) the rest
        needs: a member of ``a`` and ``u`` is in ``b`` where ``b`` needs ``a``'s value and ``u``'s filler at
        once (an intersection, a bound above one), or ``u`` is on an inverse property."""
        universals = self.universals()
        gives: list[tuple[Expr, Expr]] = []
        alone: dict[Expr, set[NamedNode]] = {}
        for us in universals.values():
            for u in us:
                found = self.by_universal(u)
                alone[u] = {b.node for b in found}
                if not u.prop.inverse:
                    gives += [(u, b) for b in found]
        by_value = {u.prop for u, _ in gives}
        values: list[tuple[Expr, Prop]] = []
        triples: list[tuple[Expr, Expr, Expr]] = []
        for a in self.exprs:
            if lower_bound(a) < 1:
                continue
            props = (a.prop, *sorted(self.supers.get(a.prop, ()), key=str))
            values += [(a, q) for q in props if q in by_value]
            if not any(q in universals for q in props):
                continue
            base = self.join(self.filler(a), self.ranges(a.prop))
            for q in props:
                for u in universals.get(q, ()) if q.inverse else ():
                    triples += [(a, u, b) for b in self.reached(a, self.join(base, self.filler(u)),
                                                              lambda b, base=base: self.holds(base, b))]
                if q in universals and not q.inverse:
                    triples += [(a, u, b) for u, b in self.needs_both(a, q, universals[q], base, alone)]
        return values, gives, triples

    def needs_both(self, a: Expr, q: Prop, us: list[Expr], base: Value,
                   alone: dict[Expr, set[NamedNode]]) -> list[tuple[Expr, Expr]]:
        """The pairs (``u``, ``b``) of a universal ``u`` of ``us`` (on ``q``) and an existential ``b`` a member of
        ``a`` (whose value is ``base``) and of ``u`` is in, that neither gives alone (``alone``:
        :meth:`by_universal`'s): only those :attr:`joint` holds, or on a property ``q`` is not under, can be."""
        n = lower_bound(a)
        found: list[tuple[Expr, Expr]] = []
        for b in self.candidates(a.prop, q):
            if b.node == a.node or lower_bound(b) > n:
                continue
            if b.datatype is None and b.filler is not None and b.filler.kind == "and":
                # member by member, each decided once per existential and once per universal: a TBox of pizzas
                # asks it of every topping's existential with every pizza's closure
                by_a, size = self.members_held(a, lambda: base, b.filler), len(b.filler.members)
                if len(by_a) < size:
                    found += [(u, b) for u, by_u in self.helping(q, us, b)
                              if b.node not in alone[u] and len(by_a | by_u) == size]
            elif not self.holds(base, b):
                found += [(u, b) for u in us
                          if b.node not in alone[u] and self.holds(self.join(base, self.filler(u)), b)]
        return found

    def helping(self, q: Prop, us: list[Expr], b: Expr) -> list[tuple[Expr, frozenset[int]]]:
        """The universals of ``us`` (on ``q``) whose filler, with ``q``'s ranges, holds a member of ``b``'s
        intersection, with those members; found once per property and existential."""
        key = (q, b.node)
        found = self._helping.get(key)
        if found is None:
            found = self._helping[key] = [
                (u, held) for u in us
                if (held := self.members_held(u, lambda u=u: self.join(self.filler(u), self.ranges(u.prop)), b.filler))]
        return found

    def candidates(self, p: Prop, q: Prop) -> list[Expr]:
        """The existentials a member of an existential on ``p`` and a universal on ``q`` may be in by both
        at once: on ``p`` or a super-expression, among :attr:`joint` where ``q`` is under that property, any
        there otherwise; found once per pair of properties."""
        found = self._candidates.get((p, q))
        if found is None:
            above_q = {q, *self.supers.get(q, ())}
            found = self._candidates[(p, q)] = [
                b for r in (p, *sorted(self.supers.get(p, ()), key=str))
                for b in (self.joint.get(r, []) if r in above_q
                          else [b for bs in self.wanted.get(r, {}).values() for b in bs])]
        return found

    def members_held(self, e: Expr, value: Callable[[], Value], f: Expr) -> frozenset[int]:
        """Which members of intersection ``f`` the value of restriction ``e`` (``value()``) is told to be in."""
        key = (e.node, f.node)
        held = self._held.get(key)
        if held is None:
            known = value()
            held = self._held[key] = frozenset(i for i, m in enumerate(f.members) if self._class_holds(known, m))
        return held


def existential_value_rules(tb: TBox, told: Subsumption, supers: dict[Prop, frozenset[Prop]],
                            exprs: Iterable[Expr], subsume: Callable[[Expr, Expr, str], None]) -> list[Rule]:
    """The memberships an existential's unnamed value gives its subject (see the module): the pairs
    through ranges handed to ``subsume`` (a row of ext-restriction-sub, with its origin), and the
    ext-some-all rules of a universal, returned."""
    values = ExistentialValues(tb, told, supers, exprs)
    for a, b in values.subsumed_by_ranges():
        subsume(a, b, f"{describe(a)} is subsumed by {describe(b)}: its value is in the ranges of its property")
    values_by, gives, triples = values.with_universals()
    rules = [schema_rule("ext-some-value").instantiate((a.term, sparql(q.iri)),
                                                        f"a member of {describe(a)} has a value of {name(q)}")
             for a, q in values_by]
    rules += [schema_rule("ext-all-value").instantiate((u.term, sparql(u.prop.iri), b.term),
                                                        f"a member of {describe(u)} with a value is in {describe(b)}")
              for u, b in gives]
    t = str(TYPE)
    return rules + [Rule("ext-some-all", f"a member of {describe(a)} and {describe(u)} is in {describe(b)}",
                         (Atom("?x", t, a.term), Atom("?x", t, u.term)), Atom("?x", t, b.term))
                    for a, u, b in triples]


__all__ = ["ExistentialValues", "existential_value_rules", "lower_bound"]
