"""N-ary OWL axioms written as RDF lists: building them and finding the whole axiom again.

``owl:AllDifferent`` and ``owl:AllDisjointClasses`` name their members through
an RDF collection (``rdf:first``/``rdf:rest`` cells).  Adding such an axiom
means writing the group node, its list and every cell; removing a member
(REMOVE IND, :meth:`topostore.ontology.facade.Ontology.remove_individual`) means
removing the *whole* axiom, because a list with a cell cut out is no longer
an axiom anyone can read.  Both the Python API and the aRMOR commands use
these functions, so the two always write and remove the same triples.
"""

from __future__ import annotations

from collections.abc import Sequence

from pyoxigraph import NamedNode, Triple

from ..rdf.skolem import fresh_skolem
from ..rdf.terms import Term
from ..rdf.vocab import ASSERTED, FIRST, NIL, REST, TYPE, is_skolem, owl, swrl
from ..stores.base import Store

#: the predicates that tie an n-ary axiom's group node to its list of members
MEMBER_LISTS = (owl("distinctMembers"), owl("members"))


def rdf_list(items: Sequence[Term]) -> tuple[Term, list[Triple]]:
    """An RDF collection of ``items``: (head node, triples); ``rdf:nil`` and no triples when empty."""
    if not items:
        return NIL, []
    nodes = [fresh_skolem() for _ in items]
    triples: list[Triple] = []
    for i, (node, item) in enumerate(zip(nodes, items, strict=True)):
        triples.append(Triple(node, FIRST, item))
        triples.append(Triple(node, REST, nodes[i + 1] if i + 1 < len(nodes) else NIL))
    return nodes[0], triples


def _group(kind: str, link: str, members: Sequence[NamedNode]) -> list[Triple]:
    group = fresh_skolem()
    head, triples = rdf_list(members)
    return [Triple(group, TYPE, owl(kind)), Triple(group, owl(link), head)] + triples


def all_different(members: Sequence[NamedNode]) -> list[Triple]:
    """ONE owl:AllDifferent over ``members``: linear in their number, never n² owl:differentFrom pairs."""
    return _group("AllDifferent", "distinctMembers", members)


def all_disjoint_classes(members: Sequence[NamedNode]) -> list[Triple]:
    """ONE owl:AllDisjointClasses over ``members`` (an n-ary DisjointClasses axiom)."""
    return _group("AllDisjointClasses", "members", members)


def _list_head(store: Store, node: Term, graph: NamedNode) -> Term:
    """The first cell of the list ``node`` is a cell of (walking rdf:rest links backwards)."""
    head = node
    while True:
        previous = store.subjects(REST, head, graph)
        if not previous:
            return head
        head = previous[0]


def axiom_of_list_node(store: Store, node: Term, graph: NamedNode = ASSERTED) -> list[Triple]:
    """Every triple of the n-ary axiom(s) whose member list has the cell ``node``: group node and whole list.

    Empty when the list belongs to no AllDifferent / AllDisjointClasses axiom
    (e.g. a SWRL atom's argument list), so other lists are never touched.
    """
    head = _list_head(store, node, graph)
    out: list[Triple] = []
    for link in MEMBER_LISTS:
        for owner in store.subjects(link, head, graph):
            out += store.triples(owner, None, None, graph)
            cell = head
            while cell != NIL:
                out += store.triples(cell, None, None, graph)
                rest = store.objects(cell, REST, graph)
                cell = rest[0] if rest else NIL
    return out


def individual_triples(store: Store, individual: NamedNode, graph: NamedNode = ASSERTED) -> list[Triple]:
    """What removing ``individual`` removes: every triple naming it, every n-ary axiom listing it whole, and
    every axiom naming it from an anonymous node whole (a class expression, a negative property assertion,
    a SWRL rule), as aRMOR's REMOVE IND (OWL API's entity remover) removes every axiom mentioning it."""
    doomed = list(store.triples(individual, None, None, graph)) + list(store.triples(None, None, individual, graph))
    for t in list(doomed):
        whole = axiom_of_list_node(store, t.subject, graph) if t.predicate == FIRST else []
        if not whole and t.subject != individual and is_skolem(t.subject):
            whole = enclosing_axiom(store, t.subject, graph)
        doomed += whole
    return list(dict.fromkeys(doomed))


def enclosing_axiom(store: Store, node: Term, graph: NamedNode = ASSERTED) -> list[Triple]:
    """Every triple of the axiom the anonymous ``node`` is part of: the SWRL rule it is in (named or not),
    else the topmost anonymous node above it with all below it and the triples naming it (``C
    owl:equivalentClass _:r``); nothing when that node is neither named nor typed (no axiom holds it).

    Why whole: a restriction without its value, a list without a cell or an atom without an argument is no
    axiom anyone can read (a rule missing an argument no longer compiles, so no REASON could run)."""
    top, seen = node, {node}
    while True:
        parents = list(store.triples(None, None, top, graph))
        rule = next((t.subject for t in parents if store.contains(Triple(t.subject, TYPE, swrl("Imp")), graph)), None)
        if rule is not None:
            return _below(store, rule, graph)
        above = next((t.subject for t in parents if is_skolem(t.subject) and t.subject not in seen), None)
        if above is None:
            naming = [t for t in parents if not is_skolem(t.subject)]
            if not naming and not list(store.triples(top, TYPE, None, graph)):
                return []  # a structure no axiom holds (a bare list): only the triples naming the individual go
            return naming + _below(store, top, graph)
        top = above
        seen.add(top)


def _below(store: Store, root: Term, graph: NamedNode) -> list[Triple]:
    """The triples of ``root`` and of every anonymous node reached from it."""
    out: list[Triple] = []
    todo, seen = [root], {root}
    while todo:
        for t in store.triples(todo.pop(), None, None, graph):
            out.append(t)
            if is_skolem(t.object) and t.object not in seen:
                seen.add(t.object)
                todo.append(t.object)
    return out


__all__ = [
    "rdf_list",
    "all_different",
    "all_disjoint_classes",
    "axiom_of_list_node",
    "individual_triples",
    "enclosing_axiom",
    "MEMBER_LISTS",
]
