"""Whether a change's list cells belong to a list the TBox reads.

A triple's predicate alone says whether it changes the rules (:func:`.files.is_schema_triple`), except for
the cells of RDF lists (``rdf:first`` / ``rdf:rest``) and the member links of the n-ary axioms
(``owl:members`` / ``owl:distinctMembers``): the same cells spell a union's members (the rules are compiled
from them) and an ``owl:AllDifferent``'s individuals (a fact the rules read, which a robot's map adds and
edits on the incremental path).  So a cell's change is a TBox change when its list is named by a schema
triple (``owl:unionOf``, ``owl:propertyChainAxiom``, ``swrl:body``, ...) or is the members of an axiom that
is not an ``owl:AllDifferent`` (``owl:AllDisjointClasses``, ``owl:AllDisjointProperties``).  The list is
found by walking from the cell to its head, through the store and through the change itself: a list added
with its axiom in one change is not in the store yet when a load decides, and a list removed with its axiom
is no longer there when the change is noted.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Iterable, Sequence

from pyoxigraph import Triple

from ..rdf.vocab import ASSERTED, FIRST, REST, TYPE, owl
from ..stores.base import Store

_CELL_LINKS = frozenset({FIRST, REST})
_MEMBER_LINKS = frozenset({owl("members"), owl("distinctMembers")})
_ABOX_GROUP = owl("AllDifferent")


#: the predicates whose triples :func:`list_change_is_schema` decides
LIST_LINKS = _CELL_LINKS | _MEMBER_LINKS


def list_change_is_schema(store: Store, triples: Sequence[Triple], is_schema: Callable[[Triple], bool]) -> bool:
    """Whether one of ``triples`` (a change, in the store or about to be; none of them a schema triple by
    ``is_schema``, the caller's per-triple test) edits a list the TBox reads.

    The change is searched first: a cell the change itself names (a list added or removed whole) asks the
    store nothing, so a map's AllDifferent of thousands of cells is decided without a look-up per cell."""
    cells = [t for t in triples if t.predicate in _CELL_LINKS]
    members = [t for t in triples if t.predicate in _MEMBER_LINKS]
    if not cells and not members:
        return False
    walk = _ListWalk(store, triples, is_schema)
    return any(walk.axiom_group(t.subject) for t in members) or any(walk.read_by_tbox(t.subject) for t in cells)


class _ListWalk:
    """The walk from list cells up to the triples naming their heads, remembering the cells already passed."""

    def __init__(self, store: Store, change: Iterable[Triple], is_schema: Callable[[Triple], bool]) -> None:
        self.store = store
        self.is_schema = is_schema
        #: the change's links by object (its other triples name no list the TBox reads: none is a schema triple)
        self.naming: defaultdict[object, list[Triple]] = defaultdict(list)
        self.groups: set[object] = set()  # the change's nodes typed owl:AllDifferent
        for t in change:
            p = t.predicate
            if p in LIST_LINKS:
                self.naming[t.object].append(t)
            elif p == TYPE and t.object == _ABOX_GROUP:
                self.groups.add(t.subject)
        self.seen: set[object] = set()

    def axiom_group(self, node: object) -> bool:
        """Whether ``node``, the subject of a members link, is a TBox axiom: anything but an owl:AllDifferent
        (an untyped group included: reading the rules again is the safe side)."""
        if node in self.groups:
            return False
        return next(self.store.triples(node, TYPE, _ABOX_GROUP, ASSERTED), None) is None

    def read_by_tbox(self, cell: object) -> bool:
        """Whether the list with ``cell`` (or a list it is nested in) is named by a schema triple."""
        todo = [cell]
        while todo:
            node = todo.pop()
            if node in self.seen:
                continue
            self.seen.add(node)
            for t in self._named_by(node):
                if t.predicate in _CELL_LINKS:
                    todo.append(t.subject)  # the previous cell, or the cell of a list this one is a member of
                elif t.predicate in _MEMBER_LINKS:
                    if self.axiom_group(t.subject):
                        return True
                elif self.is_schema(t):
                    return True
        return False

    def _named_by(self, node: object) -> list[Triple]:
        """The triples whose object is ``node``: the change's when it names the node (a well-formed cell has
        one previous cell or naming triple), else the store's."""
        found = self.naming.get(node)
        if found:
            return found
        return list(self.store.triples(None, None, node, ASSERTED))


__all__ = ["LIST_LINKS", "list_change_is_schema"]
