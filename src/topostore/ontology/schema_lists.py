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

from collections.abc import Callable, Iterable, Sequence

from pyoxigraph import Triple

from ..rdf.skolem import skolem
from ..rdf.terms import sparql
from ..rdf.vocab import ASSERTED, FIRST, REST, TYPE, owl
from ..stores.base import Store

_MEMBER_LINKS = frozenset({owl("members"), owl("distinctMembers")})
_ABOX_GROUP = owl("AllDifferent")
#: what the one pass over a change reads, by predicate (a member link is itself)
_KINDS = {REST: REST, FIRST: FIRST, TYPE: TYPE, **{p: p for p in _MEMBER_LINKS}}
#: the predicates that start a walk: a change with none of them (a robot's REPLACE) edits no list
_CELL_LINKS = frozenset({REST, FIRST, *_MEMBER_LINKS})


def list_change_is_schema(store: Store, triples: Sequence[Triple], is_schema: Callable[[Triple], bool]) -> bool:
    """Whether one of ``triples`` (a change, in the store or about to be; none of them a schema triple by
    ``is_schema``, the caller's per-triple test) edits a list the TBox reads.

    One pass over the change finds its cells and the cells its rdf:rest links lead to; only the others (the
    first cells of what it adds or removes) are walked up, through the store.  A chain of the change's links
    ends at one of them, and a head the change names is named by a schema triple (the caller's answer) or
    by a member link (its group is tested here): so a map's AllDifferent of thousands of cells, added with
    its group, asks the store about its first cell only.  A change with no cell or member link (every
    change of a robot's step) answers before any walk is set up."""
    for t in triples:  # a loop, not any() over a generator: a manipulation changes one or two triples
        if t.predicate in _CELL_LINKS:
            break
    else:
        return False
    walk = _ListWalk(store, is_schema)
    firsts = walk.read(triples)
    return any(walk.axiom_group(t.subject) for t in walk.member_links) or any(map(walk.read_by_tbox, firsts))


class _ListWalk:
    """The walk from list cells up to the triples naming their heads, remembering the cells already passed."""

    def __init__(self, store: Store, is_schema: Callable[[Triple], bool]) -> None:
        self.store = store
        self.is_schema = is_schema
        self.member_links: list[Triple] = []  # the change's owl:members and owl:distinctMembers
        self.groups: set[object] = set()  # the change's nodes typed owl:AllDifferent
        self.seen: set[object] = set()

    def read(self, change: Iterable[Triple]) -> list[object]:
        """Index ``change`` (one pass): its cells no rdf:rest link of the change leads to.  Cells are keyed
        by their IRI or blank node id (hashing a str is cheaper than hashing a term, and a map's change has
        tens of thousands of cells); an IRI always has a colon, a blank node id never."""
        cells: dict[str, object] = {}
        following: set[str] = set()
        for t in change:
            kind = _KINDS.get(t.predicate)  # one look-up for the many triples that are none of these
            if kind is None:
                continue
            if kind is REST or kind is FIRST:
                cell = t.subject
                cells[cell.value] = cell
                if kind is REST:
                    following.add(t.object.value)
            elif kind is TYPE:
                if t.object == _ABOX_GROUP:
                    self.groups.add(t.subject)
            else:
                self.member_links.append(t)
        return [cell for key, cell in cells.items() if key not in following]

    def axiom_group(self, node: object) -> bool:
        """Whether ``node``, the subject of a members link, is a TBox axiom: anything but an owl:AllDifferent
        (an untyped group included: reading the rules again is the safe side)."""
        if node in self.groups:
            return False
        return next(self.store.triples(skolem(node), TYPE, _ABOX_GROUP, ASSERTED), None) is None

    def read_by_tbox(self, cell: object) -> bool:
        """Whether the list with ``cell`` (or a list it is nested in) is named, in the store, by a schema
        triple or a TBox axiom's member link.  The store's rdf:rest links are followed back by one query
        per list (a property path): a cell near the end of an AllDifferent of thousands is one request."""
        todo = [cell]
        while todo:
            node = todo.pop()
            if node in self.seen:
                continue
            self.seen.add(node)
            for t in self._naming(node):
                if t.predicate == FIRST:
                    todo.append(t.subject)  # the cell of a list this one is a member of
                elif t.predicate in _MEMBER_LINKS:
                    if self.axiom_group(t.subject):
                        return True
                elif self.is_schema(t):
                    return True
        return False

    def _naming(self, node: object) -> list[Triple]:
        """The store's triples naming ``node`` or a cell before it in its list, rdf:rest links aside."""
        rows = self.store.query(f"SELECT ?s ?p ?h WHERE {{ GRAPH {ASSERTED} {{ ?h {REST}* {sparql(skolem(node))} . "
                                f"?s ?p ?h . FILTER(?p != {REST}) }} }}")
        return [Triple(row["s"], row["p"], row["h"]) for row in rows]


__all__ = ["list_change_is_schema"]
