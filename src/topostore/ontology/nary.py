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
from ..rdf.vocab import ASSERTED, FIRST, NIL, REST, SWRL, TYPE, XSD, is_skolem, owl, rdf, rdfs, swrl
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


#: the types of an anonymous node that is part of an axiom's structure, never an individual
STRUCTURE_TYPES = frozenset(
    [owl(n) for n in ("Class", "Restriction", "NegativePropertyAssertion", "AllDifferent", "AllDisjointClasses",
                      "AllDisjointProperties", "Axiom", "Annotation")]
    + [rdfs("Datatype"), rdf("List")]
)
#: the predicates of an anonymous node that is part of an axiom's structure (class expressions, data ranges,
#: inverse properties, negative property assertions, n-ary groups, reified axioms), besides SWRL's and facets
STRUCTURE_PREDICATES = frozenset(
    [FIRST, REST]
    + [owl(n) for n in (
        "onProperty", "onProperties", "someValuesFrom", "allValuesFrom", "hasValue", "hasSelf", "cardinality",
        "minCardinality", "maxCardinality", "qualifiedCardinality", "minQualifiedCardinality",
        "maxQualifiedCardinality", "onClass", "onDataRange", "unionOf", "intersectionOf", "complementOf", "oneOf",
        "inverseOf", "onDatatype", "withRestrictions", "datatypeComplementOf", "sourceIndividual",
        "assertionProperty", "targetIndividual", "targetValue", "members", "distinctMembers", "annotatedSource",
        "annotatedProperty", "annotatedTarget",
    )]
)


def is_structure(store: Store, node: Term, graph: NamedNode = ASSERTED) -> bool:
    """True for an anonymous node that is part of an axiom (a class expression, a list cell, a restriction, a
    negative property assertion, a SWRL rule or atom, ...); False for an anonymous individual.

    Why: an anonymous individual is an entity with axioms of its own (``_:b a :C``, ``_:b :q :c``); an axiom
    that only names it (``_:b :p :a``) is one assertion, and removing that axiom must leave its other facts."""
    if not is_skolem(node):
        return False
    for t in store.triples(node, None, None, graph):
        if t.predicate in STRUCTURE_PREDICATES or _in_namespace(t.predicate, (SWRL, XSD)):
            return True
        if t.predicate == TYPE and (t.object in STRUCTURE_TYPES or _in_namespace(t.object, (SWRL,))):
            return True
    return False


def _in_namespace(term: Term, namespaces: tuple[str, ...]) -> bool:
    return isinstance(term, NamedNode) and term.value.startswith(namespaces)


def individual_triples(store: Store, individual: NamedNode, graph: NamedNode = ASSERTED) -> list[Triple]:
    """What removing ``individual`` removes: every triple naming it, every n-ary axiom listing it whole, and
    every axiom naming it from an anonymous structure whole (a class expression, a negative property
    assertion, a SWRL rule), as aRMOR's REMOVE IND (OWL API's entity remover) removes every axiom mentioning
    it, with the class expression of an assertion about it (``:a a [ owl:Restriction ... ]``).  A triple of
    an anonymous *individual* naming it (``_:b :p :a``) is one assertion: it goes alone."""
    doomed = list(store.triples(individual, None, None, graph)) + list(store.triples(None, None, individual, graph))
    for t in list(doomed):
        whole = axiom_of_list_node(store, t.subject, graph) if t.predicate == FIRST else []
        if not whole and t.subject != individual and is_structure(store, t.subject, graph):
            whole = enclosing_axiom(store, t.subject, graph)
        elif t.subject == individual and is_structure(store, t.object, graph):
            whole = _below(store, t.object, graph)  # ``:a a [ owl:Restriction ... ]``: the assertion's expression
        doomed += whole
    return _keep_shared(store, list(dict.fromkeys(doomed)), graph)


def enclosing_axiom(store: Store, node: Term, graph: NamedNode = ASSERTED) -> list[Triple]:
    """Every triple of each axiom the anonymous structure ``node`` is part of: the SWRL rule it is in (named
    or not), else each topmost anonymous structure above it with all the structure below it and the triples
    naming any of them (``C owl:equivalentClass _:r``; a node shared by two axioms is in both, and both go;
    a topmost one typed or recognised by its structural predicates is an axiom of its own, e.g. a general
    class axiom's untyped restriction); nothing when no axiom holds it (a bare, untyped list naming no one).

    Why whole: a restriction without its value, a list without a cell or an atom without an argument is no
    axiom anyone can read (a rule missing an argument no longer compiles, so no REASON could run).  The walk
    stops at anonymous individuals: ``_:b a [ owl:Restriction ... ]`` takes that one triple, not ``_:b``."""
    out: list[Triple] = []
    todo, seen = [node], {node}
    while todo:
        current = todo.pop()
        parents = list(store.triples(None, None, current, graph))
        structural = [t for t in parents if is_structure(store, t.subject, graph)]
        naming = [t for t in parents if t not in structural]
        rule = next((t.subject for t in parents if store.contains(Triple(t.subject, TYPE, swrl("Imp")), graph)), None)
        if rule is not None:
            out += _below(store, rule, graph)
            continue
        held = naming or (not structural and _axiom_root(store, current, graph))
        if held:
            out += naming + _below(store, current, graph)
        for t in structural:
            if t.subject not in seen:
                seen.add(t.subject)
                todo.append(t.subject)
    return out


#: the structural predicates that make a topmost anonymous node an axiom of its own even when untyped (a list
#: cell's rdf:first / rdf:rest alone do not: a bare list is no axiom)
_AXIOM_PREDICATES = STRUCTURE_PREDICATES - {FIRST, REST}


def _axiom_root(store: Store, node: Term, graph: NamedNode) -> bool:
    """True when the topmost anonymous ``node`` is an axiom by itself: it has a type, or it is recognised by
    its structural predicates (``[ owl:onProperty :p ; owl:hasValue :a ] rdfs:subClassOf :C``, an untyped
    owl:Axiom or owl:NegativePropertyAssertion).

    Why: OWL's RDF mapping lets a parser read these without their ``rdf:type``; counting only typed roots left
    half an axiom behind (``_:r owl:onProperty :p ; rdfs:subClassOf :C``) when an individual it names went."""
    return any(t.predicate == TYPE or t.predicate in _AXIOM_PREDICATES
               for t in store.triples(node, None, None, graph))


def _below(store: Store, root: Term, graph: NamedNode) -> list[Triple]:
    """The triples of ``root`` and of every anonymous structure reached from it (never of an anonymous
    individual it only names)."""
    out: list[Triple] = []
    todo, seen = [root], {root}
    while todo:
        for t in store.triples(todo.pop(), None, None, graph):
            out.append(t)
            if t.object not in seen and is_structure(store, t.object, graph):
                seen.add(t.object)
                todo.append(t.object)
    return out


def _keep_shared(store: Store, doomed: list[Triple], graph: NamedNode) -> list[Triple]:
    """``doomed`` without the structure an axiom that stays still uses: a sub-expression that does not name
    the individual yet is shared with another axiom keeps its triples (else that axiom would lose a part)."""
    gone = set(doomed)
    changed = True
    while changed:
        changed = False
        for node in {t.subject for t in gone if is_skolem(t.subject)}:
            kept_parent = any(p not in gone for p in store.triples(None, None, node, graph))
            if kept_parent and is_structure(store, node, graph):
                gone -= set(store.triples(node, None, None, graph))
                changed = True
    return [t for t in doomed if t in gone]


__all__ = [
    "rdf_list",
    "all_different",
    "all_disjoint_classes",
    "axiom_of_list_node",
    "individual_triples",
    "enclosing_axiom",
    "is_structure",
    "MEMBER_LISTS",
]
