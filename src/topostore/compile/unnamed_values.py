"""What an existential's unnamed value implies beyond its own restriction, found for the profile report.

topostore names no individual for the value of an existential (``A ⊑ ∃p.F``), so what follows only through
that value is drawn only where a value is told: a chain through it, a named individual its class links it to
(``F ⊑ ∃q.{i}``), the domains of its own existentials that a restriction on the left reads.  Each is a notice
of :class:`.profile.ProfileReport` (existential with consequences for an unnamed value).
"""

from __future__ import annotations

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
        self.report = report
        #: :meth:`implied`'s answers by class
        self._implied: dict[NamedNode, set[NamedNode]] = {}

    def sides(self, p: Prop) -> list:
        """:func:`.property_hierarchy.subject_classes` of ``p`` in the report's TBox."""
        return subject_classes(self.report.tb, self.report.supers, p)

    def used_left(self, props: set[Prop] | tuple[Prop, ...]) -> list[Expr]:
        """The restrictions on ``props`` used negatively (membership derived from them)."""
        on = self.report.on
        return [m for q in props for m, positive in on.get(q, ()) if not positive]

    def links_back(self, e: Expr, filler: NamedNode, axiom: str) -> None:
        """The unnamed value of ``e`` is in ``filler``, whose told ``(q value i)`` links it to the named ``i``:
        what ``i`` gains by that link (a range of ``q``, a restriction on an inverse of ``q``) is not drawn."""
        for c in self.report.told(filler):
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
        """Each named class's told existential restrictions (superclasses or definitions)."""
        return self._told(lambda e: e.prop is not None and (e.kind == "some" or (e.kind in ("min", "exact")
                                                                                 and e.n >= 1)))

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

    def chain_links(self, e: Expr, axiom: str, links: set[Prop]) -> None:
        """A chain whose conclusion passes through the unnamed value ``u`` of ``e`` (``x p u``; ``links``:
        ``p`` and its super-expressions) and is not drawn, since no fact of ``u`` is stored.  ``x p u`` is
        the chain's k-th link read forwards (``p`` ⊑ its k-th property) or backwards (``p`` ⊑ its inverse);
        the chain then either ends at ``u`` (its named end gains a link by the chain's property to a value no
        one named: missed where that link has consequences at the named end), or goes on from ``u`` by the
        next link, which only ``u``'s classes can give it (a told value: a link to a named individual is
        missed; an existential: missed where the chain's property has consequences).  A chain that ``x p u``
        can serve but that cannot go on from ``u`` concludes nothing through it, and is not named."""
        restrictions: list[Expr] | None = None
        for t, chain in self.report.tb.chains:
            for k, q in enumerate(chain):
                if q in links:  # x q u: the chain goes on from u by its next property
                    onward = chain[k + 1] if k + 1 < len(chain) else None
                    end = Prop(t)  # ...or ends at u: the start x' gains x' t u
                elif inverse(q) in links:  # u q x: the chain comes to u by the inverse of its previous property
                    onward = inverse(chain[k - 1]) if k > 0 else None
                    end = inverse(Prop(t))  # ...or starts at u: the end x' gains u t x'
                else:
                    continue
                if onward is None:
                    missed = self.subject_consequences(end)
                else:
                    if restrictions is None:
                        restrictions = self.restrictions_of_value(e, links)
                    link = self.link_by(restrictions, onward)
                    missed = link == "value" or (link == "some" and self.has_consequences(Prop(t)))
                if missed:
                    self.report.note_existential(axiom, f"the unnamed value of {describe(e)} completes the chain "
                                                 f"of {_name(t)}, whose conclusion through it is not drawn")
                    return

    def subject_consequences(self, t: Prop) -> bool:
        """A subject of ``t`` gains a class by the link alone: a domain of ``t`` or of a super-expression,
        or a restriction on one of them used on the left."""
        return bool(self.sides(t) or self.used_left((t, *self.report.supers.get(t, ()))))

    def restrictions_of_value(self, e: Expr, links: set[Prop]) -> list[Expr]:
        """The restrictions the unnamed value of ``e`` is told to satisfy: its filler's own (an anonymous
        filler, or an intersection's members) and those of its named classes (the filler's and the range's
        told superclasses, with the domains of their existentials)."""
        found: list[Expr] = []
        named: set[NamedNode] = set()
        filler = e.filler
        if filler is not None:
            for m in (filler, *filler.members) if filler.kind == "and" else (filler,):
                if m.is_named:
                    named |= self.implied(m.node)
                else:
                    found.append(m)
        for q in links:
            for _, c in subject_classes(self.report.tb, self.report.supers, inverse(q)):
                if c.is_named:
                    named |= self.implied(c.node)
        for c in named:
            found += self.told_existentials.get(c, ())
            found += self.told_values.get(c, ())
        return found

    def link_by(self, restrictions: list[Expr], r: Prop) -> str | None:
        """How ``restrictions`` give a link by ``r`` (on ``r`` or a sub-property of it): "value" for a told
        named value, "some" for an unnamed one, None for none."""
        supers = self.report.supers
        on_r = [m for m in restrictions if m.prop is not None and (m.prop == r or r in supers.get(m.prop, ()))]
        if any(m.kind == "value" and isinstance(m.value, NamedNode) for m in on_r):
            return "value"
        if any(m.kind == "some" or (m.kind in ("min", "exact") and m.n >= 1) for m in on_r):
            return "some"
        return None

    def has_consequences(self, t: Prop) -> bool:
        """Some class follows from a link by ``t``: a domain or range of it or of a super-expression, or a
        restriction on one of them."""
        supers = self.report.supers
        wanted = {t, inverse(t), *supers.get(t, ()), *supers.get(inverse(t), ())}
        return bool(self.sides(t) or self.sides(inverse(t)) or any(self.report.on.get(q) for q in wanted))


__all__ = ["UnnamedValues"]
