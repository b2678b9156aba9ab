"""What an existential's unnamed value implies beyond its own restriction, found for the profile report.

topostore names no individual for the value of an existential (``A ⊑ ∃p.F``), so what follows only through
that value is drawn only where a value is told: a chain through it, a named individual its class links it to
(``F ⊑ ∃q.{i}``), the domains of its own existentials that a restriction on the left reads.  Each is a notice
of :class:`.profile.ProfileReport` (existential with consequences for an unnamed value).
"""

from __future__ import annotations

import weakref
from functools import cached_property
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode

from .model import Expr, Prop, describe
from .property_hierarchy import inverse, subject_classes

if TYPE_CHECKING:
    from .profile import ProfileReport


def _name(t: NamedNode) -> str:
    v = t.value
    return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]


class UnnamedValues:
    """The checks of an existential's unnamed value, on the report's TBox and hierarchy."""

    def __init__(self, report: ProfileReport) -> None:
        # weakly: the report holds this part, and a cycle would keep the report's uses (two per disjoint
        # pair) alive past the LOAD (see :class:`.owl_restrictions.RestrictionRules`)
        self.report = weakref.proxy(report)
        #: :meth:`implied`'s answers by class
        self._implied: dict[NamedNode, set[NamedNode]] = {}

    def sides(self, p: Prop) -> list:
        """:func:`.property_hierarchy.subject_classes` of ``p`` in the report's TBox."""
        return subject_classes(self.report.tb, self.report.supers, p)

    def used_left(self, props: set[Prop] | tuple[Prop, ...]) -> list[Expr]:
        """The restrictions on ``props`` used negatively (membership derived from them)."""
        on = self.report.on
        return [m for q in props for m, positive in on.get(q, ()) if not positive]

    def links_back(self, e: Expr, classes: set[NamedNode], axiom: str) -> None:
        """The unnamed value of ``e`` is in ``classes`` (:meth:`value_classes`), whose told ``(q value i)``
        links it to the named ``i``: what ``i`` gains by that link (a range of ``q``, a restriction on an
        inverse of ``q``) is not drawn."""
        for c in classes:
            for v in self.told_values.get(c, ()):
                q = inverse(v.prop)
                if self.sides(q) or self.used_left((q, *self.report.supers.get(q, ()))):
                    i = _name(v.value)
                    self.report.note_existential(axiom, f"the unnamed value of {describe(e)} is in {describe(v)}, "
                                                 f"a link to {i}: what {i} gains by it is drawn only through a told "
                                                 "value")

    def wider_filler(self, e: Expr, filler: NamedNode, axiom: str, links: set[Prop]) -> None:
        """The unnamed value of ``e`` is in the domains of its class's own existentials (``A0 ⊑ ∃p1.A0``,
        ``p1`` of domain ``A3``: ``A0 ⊑ A3``), which restrictions are not compared by: a restriction into
        such a class on the left (``∃p2.A3 ⊑ A0``) is not reached from ``e`` (``∃p2.A0``)."""
        wider = self.implied(filler) - self.report.told(filler)
        if wider and any(m.kind in ("some", "min") and m.filler is not None and m.filler.is_named
                         and m.filler.node in wider for m in self.used_left(links)):
            self.report.note_existential(axiom, f"the unnamed value of {describe(e)} is in the domain of an "
                                         f"existential of {_name(filler)}: a restriction into that domain is "
                                         "reached only through a told value")

    def gives_back(self, e: Expr, classes: set[NamedNode], axiom: str) -> None:
        """The unnamed value ``u`` of ``e`` (``x p u``) is in ``classes``, one of which tells a restriction on
        the inverse of ``p`` (``F ⊑ ∀p⁻.D``): what it says of ``x`` is not drawn."""
        back = self.back_restriction(classes, e.prop)
        if back is not None:
            self.report.note_existential(axiom, f"the unnamed value of {describe(e)} is in {describe(back)}, "
                                         "which says more of the individual linked to it: not drawn")

    def defined_filler(self, e: Expr, classes: set[NamedNode], axiom: str, links: set[Prop]) -> None:
        """The unnamed value of ``e`` is in ``classes``, told restrictions of their own: an existential on the
        left into a named class defined otherwise than as an intersection of named classes (``X ≡ ∃q.F``) may hold
        it by those restrictions, which only a told value's facts show (told subsumption compares names)."""
        if not any(self.told_restrictions.get(c) for c in classes):
            return
        for m in self.used_left(links):
            f = m.filler
            if m.kind in ("some", "min") and f is not None and f.is_named and f.node not in classes \
                    and f.node in self.defined:
                self.report.note_existential(axiom, f"the unnamed value of {describe(e)} has restrictions of its "
                                             f"own: whether it is in {_name(f.node)}, defined by "
                                             f"{describe(self.defined[f.node])}, is drawn only through a told value")
                return

    @cached_property
    def defined(self) -> dict[NamedNode, Expr]:
        """The named classes defined by an expression that is not an intersection of named classes."""
        found: dict[NamedNode, Expr] = {}
        for a, b in self.report.tb.equivalent:
            for named, d in ((a, b), (b, a)):
                if named.is_named and not d.is_named and not (d.kind == "and" and all(m.is_named for m in d.members)):
                    found.setdefault(named.node, d)
        return found

    def back_restriction(self, classes: set[NamedNode], t: Prop) -> Expr | None:
        """A restriction told of one of ``classes`` (the classes of the value ``u`` of a link ``x t u``) that
        bears on ``x``: on the inverse of ``t`` or a super-expression of it, of any kind but an existential
        (``x`` may not be the value it asks for)."""
        props = {inverse(t), *self.report.supers.get(inverse(t), ())}
        for c in classes:
            for m in self.told_restrictions.get(c, ()):
                if m.prop in props and m.kind not in ("some", "min"):
                    return m
        return None

    def value_classes(self, e: Expr, links: set[Prop], subject: NamedNode | None) -> set[NamedNode]:
        """The named classes the unnamed value of ``e`` is told to be in, with their told superclasses and
        the domains of their existentials (:meth:`implied`): the filler's named members, the ranges of
        ``links`` (``e``'s property and its super-expressions), and the named fillers of universals on
        ``links`` told of ``subject``'s classes (of any class where the subject is not named: an expression
        nested in another, a rule atom, a typed individual)."""
        named: set[NamedNode] = set()
        fillers = [e.filler] if e.filler is not None else []
        fillers += [m.filler for m in self.universals(links, subject) if m.filler is not None]
        for f in fillers:
            for m in (f, *f.members) if f.kind == "and" else (f,):
                if m.is_named:
                    named |= self.implied(m.node)
        for q in links:
            for _, c in subject_classes(self.report.tb, self.report.supers, inverse(q)):
                if c.is_named:
                    named |= self.implied(c.node)
        return named

    def universals(self, links: set[Prop], subject: NamedNode | None) -> list[Expr]:
        """The universals on ``links`` told of ``subject``'s classes (every positive one where not named)."""
        if subject is None:
            return [m for q in links for m, positive in self.report.on.get(q, ()) if positive and m.kind == "all"]
        return [m for c in self.report.told(subject) for m in self.told_restrictions.get(c, ())
                if m.kind == "all" and m.prop in links]

    def implied(self, c: NamedNode) -> set[NamedNode]:
        """``c``'s told superclasses with the domains of their existentials (and so on), found once."""
        found = self._implied.get(c)
        if found is None:
            found = set(self.report.told(c))
            todo = list(found)
            while todo:
                for r in self.told_existentials.get(todo.pop(), ()):
                    for _, d in self.sides(r.prop):
                        if d.is_named:
                            new = self.report.told(d.node) - found
                            found |= new
                            todo += new
            self._implied[c] = found
        return found

    @cached_property
    def told_existentials(self) -> dict[NamedNode, list[Expr]]:
        """Each named class's told existential restrictions (superclasses or definitions), a ``Self`` one
        among them (a link, to the individual itself)."""
        return self._told(lambda e: e.prop is not None and (e.kind in ("some", "self")
                                                            or (e.kind in ("min", "exact") and e.n >= 1)))

    @cached_property
    def told_restrictions(self) -> dict[NamedNode, list[Expr]]:
        """Each named class's told restrictions of every kind (superclasses or definitions)."""
        return self._told(lambda e: e.prop is not None)

    @cached_property
    def told_values(self) -> dict[NamedNode, list[Expr]]:
        """Each named class's told object ``hasValue`` restrictions (superclasses or definitions)."""
        return self._told(lambda e: e.kind == "value" and isinstance(e.value, NamedNode)
                          and not self.report.owl.is_data(e.prop, e))

    def _told(self, wanted) -> dict[NamedNode, list[Expr]]:  # noqa: ANN001 - a test of an expression
        found: dict[NamedNode, list[Expr]] = {}
        for e, positive, _, subject in self.report.uses:
            if positive and subject is not None and wanted(e):
                found.setdefault(subject, []).append(e)
        return found

    def chain_links(self, e: Expr, axiom: str, links: set[Prop], subject: NamedNode | None) -> None:
        """A chain whose conclusion passes through the unnamed value ``u`` of ``e`` (``x p u``; ``links``:
        ``p`` and its super-expressions) and is not drawn, since no fact of ``u`` is stored.  A transitive
        property ``t`` is the chain ``t ∘ t``.  ``x p u`` is the chain's k-th link read forwards (``p`` ⊑ its
        k-th property) and, where ``p`` is also below the inverse (a symmetric one), backwards; the chain then
        either ends at ``u`` (its named end gains a link by the chain's property to a value no one named), or
        goes on from ``u`` by the next link, which only ``u``'s classes (or the link back to ``x``) can give
        it: a link to a named individual is missed; one to another unnamed value (or to ``u`` itself, a
        ``Self``) is missed unless the chain ends there and the conclusion is shown to carry nothing
        (:meth:`conclusion_inert`, with the classes of the value the conclusion reaches).  A chain that
        ``x p u`` can serve but that cannot go on from ``u`` concludes nothing through it, and is not named.
        ``subject``: the class ``e`` is told of (None where not named), whose universals give ``u`` classes."""
        restrictions: list[Expr] | None = None
        classes: set[NamedNode] = set()
        for t, chain in self.chains:
            for k, q in enumerate(chain):
                for onward, end, last in self._readings(t, chain, k, q, links):
                    if restrictions is None:
                        classes = self.value_classes(e, links, subject)
                        restrictions = self.restrictions_of_value(e, links, subject, classes)
                    if onward is None:  # the named side is linked to it by the chain's first (last) property
                        first = chain[0] if end == Prop(t) else inverse(chain[-1])
                        linked = len(chain) > 1 and (first == end or end in self.report.supers.get(first, ()))
                        missed = not self.conclusion_inert(end, linked, restrictions, classes)
                    else:
                        link = "value" if inverse(onward) in links else self.link_by(restrictions, onward)
                        missed = link == "value" or (link == "some" and not (last and self.conclusion_inert(
                            end, False, None, self.onward_classes(restrictions, onward, classes))))
                    if missed:
                        self.report.note_existential(axiom, f"the unnamed value of {describe(e)} completes the "
                                                     f"chain of {_name(t)}, whose conclusion through it is not "
                                                     "drawn")
                        return

    @staticmethod
    def _readings(t: NamedNode, chain: tuple[Prop, ...], k: int, q: Prop,
                  links: set[Prop]) -> list[tuple[Prop | None, Prop, bool]]:
        """How ``x p u`` serves the chain's k-th link: (the link the chain needs next from ``u``, None where
        the chain ends or starts at ``u``; the conclusion's property read from the named side; whether that
        next link is the chain's last, so the conclusion ends at the value it reaches)."""
        found = []
        if q in links:  # x q u: the chain goes on from u by its next property, or ends at u
            onward = chain[k + 1] if k + 1 < len(chain) else None
            found.append((onward, Prop(t), k + 2 == len(chain)))
        if inverse(q) in links:  # u q x: the chain comes to u by the inverse of its previous one, or starts at u
            found.append((inverse(chain[k - 1]) if k > 0 else None, inverse(Prop(t)), k == 1))
        return found

    @cached_property
    def chains(self) -> list[tuple[NamedNode, tuple[Prop, ...]]]:
        """The TBox's property chains, with ``t ∘ t`` for each transitive property ``t``."""
        transitive = sorted(self.report.tb.characteristics.get("TransitiveProperty", ()), key=str)
        return [*self.report.tb.chains, *((t, (Prop(t), Prop(t))) for t in transitive)]

    def conclusion_inert(self, t: Prop, linked: bool, restrictions: list[Expr] | None,
                         classes: set[NamedNode] | None) -> bool:
        """Whether a link by ``t`` from a named individual to an unnamed value is shown to entail nothing:
        no class of the subject (a domain, unless ``linked``: the subject has a stored link by a
        sub-property of ``t`` already, which gave it; a restriction used on the left, whose filler the value
        may satisfy), no class of the value that says more of it (:meth:`value_inert`), nothing from ``t``'s
        characteristics and chains (:meth:`property_inert`; ``restrictions``: what the value is told, None
        where not known), no restriction of the value's own ``classes`` that bears back on the subject
        (:meth:`back_restriction`; ``classes`` None where they are not known: never shown inert)."""
        if (self.sides(t) and not linked) or self.used_left((t, *self.report.supers.get(t, ()))):
            return False
        if classes is None or self.back_restriction(classes, t) is not None:
            return False
        return self.value_inert(t) and self.property_inert(t, restrictions)

    def value_inert(self, t: Prop) -> bool:
        """Whether the value of ``t`` gains nothing that says more of it: no restriction on the inverse of
        ``t`` (or a super-expression) used on the left, and the classes it is told to be in (the range of
        ``t`` and its super-expressions, their told superclasses) plain names: no restriction or other
        expression told of them (a universal on the inverse brings a class back to the subject), no
        disjointness, no use inside an expression on the left (a member, a filler)."""
        if self.used_left((inverse(t), *self.report.supers.get(inverse(t), ()))):
            return False
        named: set[NamedNode] = set()
        for _, c in subject_classes(self.report.tb, self.report.supers, inverse(t)):
            if not c.is_named:
                return False
            named |= self.report.told(c.node)
        if not named:
            return True
        if any(c in self.report.disjoint_with for c in named):
            return False
        told, inside = self.expression_uses
        return named.isdisjoint(told) and named.isdisjoint(inside)

    @cached_property
    def expression_uses(self) -> tuple[set[NamedNode | None], set[NamedNode]]:
        """The TBox's uses of expressions, read once (every existential asks: a scan per ask made a 400-class
        TBox's LOAD quadratic): the named classes told an expression, and those read inside an expression
        on the left (a member, a filler)."""
        told: set[NamedNode | None] = set()
        inside: set[NamedNode] = set()
        for e, positive, _, subject in self.report.uses:
            if e.is_named:
                continue
            if positive:
                told.add(subject)
            else:
                inside.update(m.node for m in (*e.members, e.filler) if m is not None and m.is_named)
        return told, inside

    def property_inert(self, t: Prop, restrictions: list[Expr] | None) -> bool:
        """Whether neither ``t`` nor a super-expression has a characteristic, takes part in a chain or a key,
        or is told disjoint with another property (each could make the new link say more).  A transitive
        one is no exception only where the value is told no link by it (``restrictions``: what it is told;
        None where not known): a link onwards from it is what transitivity would carry back."""
        tb = self.report.tb
        props = (t, *self.report.supers.get(t, ()))
        iris = {q.iri for q in props}
        for kind, found in tb.characteristics.items():
            if iris.isdisjoint(found):
                continue
            if kind != "TransitiveProperty" or restrictions is None:
                return False
            if any(self.link_by(restrictions, q) is not None for q in props if q.iri in found):
                return False
        if any(a in iris or b in iris for a, b in tb.disjoint_props):
            return False
        if any(q.iri in iris for _, chain in tb.chains for q in chain):
            return False
        return not any(q.iri in iris for _, props in tb.keys for q in props)

    def subject_consequences(self, t: Prop) -> bool:
        """A subject of ``t`` gains a class by the link alone: a domain of ``t`` or of a super-expression,
        or a restriction on one of them used on the left."""
        return bool(self.sides(t) or self.used_left((t, *self.report.supers.get(t, ()))))

    def restrictions_of_value(self, e: Expr, links: set[Prop], subject: NamedNode | None,
                              classes: set[NamedNode]) -> list[Expr]:
        """The restrictions the unnamed value of ``e`` is told to satisfy: its filler's own and those of the
        universals on ``links`` told of ``subject`` (an anonymous filler, or an intersection's members), and
        those of its named ``classes`` (:meth:`value_classes`)."""
        found: list[Expr] = []
        fillers = [e.filler] if e.filler is not None else []
        fillers += [m.filler for m in self.universals(links, subject) if m.filler is not None]
        for f in fillers:
            found += [m for m in ((f, *f.members) if f.kind == "and" else (f,)) if not m.is_named]
        for c in classes:
            found += self.told_existentials.get(c, ())
            found += self.told_values.get(c, ())
        return found

    def onward_classes(self, restrictions: list[Expr], onward: Prop, classes: set[NamedNode]) -> set[NamedNode] | None:
        """The named classes of the value ``v`` that ``restrictions`` (told of ``u``, whose named ``classes``
        are given) link ``u`` to by ``onward``: their named fillers (``u``'s own classes for a ``Self``) and
        the range of ``onward``, with their told superclasses; None where one is anonymous (not known)."""
        supers = self.report.supers
        named: set[NamedNode] = set()
        for m in restrictions:
            if m.prop is None or not (m.prop == onward or onward in supers.get(m.prop, ())):
                continue
            if m.kind == "self":
                named |= classes
            elif m.filler is not None:
                for f in (m.filler, *m.filler.members) if m.filler.kind == "and" else (m.filler,):
                    if not f.is_named:
                        return None
                    named |= self.implied(f.node)
        for _, c in subject_classes(self.report.tb, supers, inverse(onward)):
            if not c.is_named:
                return None
            named |= self.implied(c.node)
        return named

    def link_by(self, restrictions: list[Expr], r: Prop) -> str | None:
        """How ``restrictions`` give a link by ``r`` (on ``r`` or a sub-property of it): "value" for a told
        named value, "some" for an unnamed one (``u`` itself for a ``Self``), None for none."""
        supers = self.report.supers
        on_r = [m for m in restrictions if m.prop is not None and (m.prop == r or r in supers.get(m.prop, ()))]
        if any(m.kind == "value" and isinstance(m.value, NamedNode) for m in on_r):
            return "value"
        if any(m.kind in ("some", "self") or (m.kind in ("min", "exact") and m.n >= 1) for m in on_r):
            return "some"  # a Self links u to itself: unnamed as well
        return None


__all__ = ["UnnamedValues"]
