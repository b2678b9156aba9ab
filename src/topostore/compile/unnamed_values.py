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
        """A chain through the unnamed value of ``e`` links its ends by the chain's property, whose
        consequences (a domain, a range, restrictions on it) are then drawn only through told values."""
        both = links | {inverse(q) for q in links}
        for t, chain in self.report.tb.chains:
            if both.intersection(chain) and self.has_consequences(Prop(t)):
                self.report.note_existential(axiom, f"the unnamed value of {describe(e)} may complete the chain "
                                             f"of {_name(t)}, whose consequences are drawn only through told values")

    def has_consequences(self, t: Prop) -> bool:
        """Some class follows from a link by ``t``: a domain or range of it or of a super-expression, or a
        restriction on one of them."""
        supers = self.report.supers
        wanted = {t, inverse(t), *supers.get(t, ()), *supers.get(inverse(t), ())}
        return bool(self.sides(t) or self.sides(inverse(t)) or any(self.report.on.get(q) for q in wanted))


__all__ = ["UnnamedValues"]
