"""The closure of the tutorial map, hand-written, for :mod:`benchmarks.full_floor` to time.

Two forms of the same closure, both over a bare pyoxigraph ``Store`` that holds the map file in its
default graph, both writing the conclusions into that default graph (three index entries a triple,
the least the store can do) and helper facts into a graph of their own:

* :data:`RULES`: the fewest SPARQL updates that reach the fixpoint — the three SWRL rules of
  ``ontology/topological_map.ttl`` and the axioms of its TBox that fire on a map (domain and range,
  ``ROOM ≡ LOCATION ⊓ ∃hasDoor.DOOR``, ``CORRIDOR ≡ LOCATION ⊓ ≥2 hasDoor.DOOR``, the datatype
  hierarchy of the data ranges), the difference of SWRL's ``DifferentFrom`` and of the minimum
  cardinality read from the ``owl:AllDifferent`` lists through one helper fact per member;
  :data:`CLOSING` asks whether the rules that feed an earlier one (the domain and range of the
  derived properties, ``URGENT ⊑ LOCATION``) would add anything, and :data:`CHECKS` asks for the
  inconsistencies topostore's full REASON looks for;
* :func:`python_closure`: the same conclusions computed in Python from the store's facts (no
  SPARQL), to be written with ``Store.extend``: the absolute floor of writing the closure.

This is a measuring tool for this one ontology, not a reasoner: what it does not model (two places
of one robot, ``owl:sameAs``, ``owl:differentFrom``) it refuses with :class:`OutsideModel` instead
of answering.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable

from pyoxigraph import DefaultGraph, Literal, NamedNode, Quad, Store, Triple

MAP = "http://bnc/exp-rob-lab/2022-23#"
RDF = "http://www.w3.org/1999/02/22-rdf-syntax-ns#"
RDFS = "http://www.w3.org/2000/01/rdf-schema#"
OWL = "http://www.w3.org/2002/07/owl#"
XSD = "http://www.w3.org/2001/XMLSchema#"
#: the graph of the helper facts (one AllDifferent group per member); never part of the closure
HELPER = NamedNode("urn:full-floor:helper")
GROUP = NamedNode("urn:full-floor:group")

#: every numeric datatype with its strict supertypes (XSD 1.1 and OWL 2's owl:rational, owl:real):
#: a data range ``xsd:long`` entails the ranges of all its supertypes, as topostore's full REASON does
DATATYPE_SUPERS: dict[str, list[str]] = {
    "xsd:decimal": ["owl:rational", "owl:real"],
    "xsd:integer": ["xsd:decimal", "owl:rational", "owl:real"],
    "xsd:long": ["xsd:integer", "xsd:decimal", "owl:rational", "owl:real"],
    "xsd:int": ["xsd:long", "xsd:integer", "xsd:decimal", "owl:rational", "owl:real"],
    "xsd:short": ["xsd:int", "xsd:long", "xsd:integer", "xsd:decimal", "owl:rational", "owl:real"],
    "xsd:byte": ["xsd:short", "xsd:int", "xsd:long", "xsd:integer", "xsd:decimal", "owl:rational", "owl:real"],
    "xsd:nonNegativeInteger": ["xsd:integer", "xsd:decimal", "owl:rational", "owl:real"],
    "xsd:nonPositiveInteger": ["xsd:integer", "xsd:decimal", "owl:rational", "owl:real"],
    "xsd:positiveInteger": ["xsd:nonNegativeInteger", "xsd:integer", "xsd:decimal", "owl:rational", "owl:real"],
    "xsd:negativeInteger": ["xsd:nonPositiveInteger", "xsd:integer", "xsd:decimal", "owl:rational", "owl:real"],
    "owl:rational": ["owl:real"],
}

PREFIXES = (f"PREFIX : <{MAP}> PREFIX rdf: <{RDF}> PREFIX rdfs: <{RDFS}> PREFIX owl: <{OWL}> "
            f"PREFIX xsd: <{XSD}> PREFIX h: <urn:full-floor:> ")
_VALUES = " ".join(f"({sub} {sup})" for sub, sups in DATATYPE_SUPERS.items() for sup in sups)

#: the rules in the order of their dependencies, one update request each (name, SPARQL update)
RULES: list[tuple[str, str]] = [
    ("datatype ranges", f"INSERT {{ ?p rdfs:range ?sup }} WHERE {{ VALUES (?dt ?sup) {{ {_VALUES} }} ?p rdfs:range ?dt }}"),
    ("AllDifferent groups (helper)",
     "INSERT { GRAPH <urn:full-floor:helper> { ?m h:group ?g } } WHERE { ?g rdf:type owl:AllDifferent . "
     "{ ?g owl:distinctMembers ?list } UNION { ?g owl:members ?list } ?list rdf:rest*/rdf:first ?m }"),
    ("domain/range: LOCATION",
     "INSERT { ?l rdf:type :LOCATION } WHERE { "
     "SELECT DISTINCT ?l { { ?l :hasDoor ?d } UNION { ?l :visitedAt ?v } UNION { ?r :isIn ?l } } }"),
    ("domain/range: DOOR", "INSERT { ?d rdf:type :DOOR } WHERE { SELECT DISTINCT ?d { ?l :hasDoor ?d } }"),
    ("domain/range: ROBOT",
     "INSERT { ?r rdf:type :ROBOT } WHERE { "
     "SELECT DISTINCT ?r { { ?r :isIn ?l } UNION { ?r :now ?t } UNION { ?r :urgencyThreshold ?h } } }"),
    ("ROOM (LOCATION with a DOOR)",
     "INSERT { ?l rdf:type :ROOM } WHERE { SELECT DISTINCT ?l { "
     "?l rdf:type :LOCATION ; :hasDoor ?d . ?d rdf:type :DOOR } }"),
    ("CORRIDOR (two different DOORs)",
     "INSERT { ?l rdf:type :CORRIDOR } WHERE { SELECT DISTINCT ?l { "
     "?l :hasDoor ?d1 , ?d2 . FILTER(!sameTerm(?d1, ?d2)) "
     "GRAPH <urn:full-floor:helper> { ?d1 h:group ?g . ?d2 h:group ?g } "
     "?d1 rdf:type :DOOR . ?d2 rdf:type :DOOR . ?l rdf:type :LOCATION } }"),
    ("Connectability",
     "INSERT { ?l1 :connectedTo ?l2 } WHERE { "
     "?l1 :hasDoor ?d . ?l2 :hasDoor ?d . FILTER(!sameTerm(?l1, ?l2)) "
     "GRAPH <urn:full-floor:helper> { ?l1 h:group ?g . ?l2 h:group ?g } "
     "?d rdf:type :DOOR . ?l1 rdf:type :LOCATION . ?l2 rdf:type :LOCATION }"),
    ("Urgency",
     "INSERT { ?l rdf:type :URGENT } WHERE { ?r rdf:type :ROBOT ; :now ?t ; :urgencyThreshold ?h . "
     "?l :visitedAt ?v . FILTER(?t - ?v > ?h) ?l rdf:type :LOCATION }"),
    ("Reachability",
     "INSERT { ?r :canReach ?l2 } WHERE { ?r rdf:type :ROBOT ; :isIn ?l1 . ?l1 :connectedTo ?l2 . "
     "FILTER(!sameTerm(?l1, ?l2)) GRAPH <urn:full-floor:helper> { ?l1 h:group ?g . ?l2 h:group ?g } "
     "?l1 rdf:type :LOCATION . ?l2 rdf:type :LOCATION }"),
]

#: the rules that write what an earlier rule reads; the fixpoint is reached when they add nothing
CLOSING: tuple[str, str] = (
    "closing: domain/range of the derived, URGENT ⊑ LOCATION",
    "INSERT { ?x rdf:type ?c } WHERE { "
    "{ { ?x :connectedTo ?y } UNION { ?y :connectedTo ?x } UNION { ?y :canReach ?x } UNION { ?x rdf:type :URGENT } "
    "BIND(:LOCATION AS ?c) } UNION { ?x :canReach ?y BIND(:ROBOT AS ?c) } "
    "FILTER NOT EXISTS { ?x rdf:type ?c } }",
)

#: what topostore's full REASON checks on these maps; one ASK each (name, query); all must be false
CHECKS: list[tuple[str, str]] = [
    ("disjoint DOOR, LOCATION, ROBOT",
     "ASK { { ?x rdf:type :DOOR , :LOCATION } UNION { ?x rdf:type :DOOR , :ROBOT } "
     "UNION { ?x rdf:type :LOCATION , :ROBOT } }"),
    ("visitedAt exactly 1: two values", "ASK { ?x :visitedAt ?a , ?b . FILTER(?a != ?b) }"),
]

#: what the floor does not model; each a reason to refuse the map (name, ASK)
OUTSIDE: list[tuple[str, str]] = [
    ("a robot in two places (isIn is functional: owl:sameAs)", "ASK { ?r :isIn ?a , ?b . FILTER(!sameTerm(?a, ?b)) }"),
    ("owl:sameAs or owl:differentFrom", "ASK { { ?a owl:sameAs ?b } UNION { ?a owl:differentFrom ?b } }"),
]


class OutsideModel(ValueError):
    """The map holds something the hand-written closure does not model: it is refused, not answered."""


def refuse_outside(store: Store) -> None:
    """Raise :class:`OutsideModel` when the map needs what the floor does not do."""
    for name, ask in OUTSIDE:
        if store.query(PREFIXES + ask):
            raise OutsideModel(f"the hand-written closure does not model {name}")


def _iri(name: str) -> NamedNode:
    prefix, _, local = name.partition(":")
    return NamedNode({"xsd": XSD, "owl": OWL}[prefix] + local)


def _subjects(store: Store, p: str) -> Iterable[tuple[object, object]]:
    for q in store.quads_for_pattern(None, NamedNode(p), None, DefaultGraph()):
        yield q.subject, q.object


def read_facts(store: Store) -> dict[str, list[tuple[object, object]]]:
    """The asserted facts the closure reads, by predicate (the Python form's input, read from the store)."""
    preds = {"hasDoor": MAP + "hasDoor", "visitedAt": MAP + "visitedAt", "isIn": MAP + "isIn", "now": MAP + "now",
             "urgencyThreshold": MAP + "urgencyThreshold", "type": RDF + "type", "range": RDFS + "range",
             "distinctMembers": OWL + "distinctMembers", "members": OWL + "members",
             "first": RDF + "first", "rest": RDF + "rest", "connectedTo": MAP + "connectedTo",
             "canReach": MAP + "canReach"}
    return {k: list(_subjects(store, p)) for k, p in preds.items()}


def _groups(facts: dict[str, list[tuple[object, object]]]) -> dict[object, set[object]]:
    """Each member of an owl:AllDifferent with the groups (list heads) it belongs to."""
    first = dict(facts["first"])
    rest = dict(facts["rest"])
    all_different = {s for s, o in facts["type"] if o == NamedNode(OWL + "AllDifferent")}
    member_of: dict[object, set[object]] = defaultdict(set)
    for group, head in facts["distinctMembers"] + facts["members"]:
        if group not in all_different:
            continue
        cell, seen = head, set()
        while cell in first and cell not in seen:
            seen.add(cell)
            member_of[first[cell]].add(group)
            cell = rest.get(cell)
    return member_of


def _number(term: object) -> int | float:
    if not isinstance(term, Literal):
        raise OutsideModel(f"a time that is not a literal: {term}")
    text = term.value
    return int(text) if text.lstrip("+-").isdigit() else float(text)


def python_closure(facts: dict[str, list[tuple[object, object]]]) -> list[Triple]:
    """The closure's new triples, computed in Python: the same conclusions as :data:`RULES`."""
    def cls(name: str) -> NamedNode:
        return NamedNode(MAP + name)

    def different(a: object, b: object) -> bool:
        return a != b and bool(groups.get(a, set()) & groups.get(b, set()))

    groups = _groups(facts)
    asserted_types = {(s, o) for s, o in facts["type"]}
    doors_of: dict[object, list[object]] = defaultdict(list)
    for loc, door in facts["hasDoor"]:
        doors_of[loc].append(door)
    door_cls = {d for _, d in facts["hasDoor"]} | {s for s, o in asserted_types if o == cls("DOOR")}
    # derived connectedTo and canReach only join LOCATIONs and ROBOTs already typed: one pass is the fixpoint
    location = ({s for s, _ in facts["hasDoor"]} | {s for s, _ in facts["visitedAt"]} | {o for _, o in facts["isIn"]}
                | {t for pair in facts["connectedTo"] for t in pair} | {o for _, o in facts["canReach"]}
                | {s for s, o in asserted_types if o in (cls("LOCATION"), cls("URGENT"))})
    robot = ({s for s, _ in facts["isIn"]} | {s for s, _ in facts["now"]} | {s for s, _ in facts["urgencyThreshold"]}
             | {s for s, _ in facts["canReach"]} | {s for s, o in asserted_types if o == cls("ROBOT")})
    locs_of: dict[object, list[object]] = defaultdict(list)
    for loc, door in facts["hasDoor"]:
        if loc in location and door in door_cls:
            locs_of[door].append(loc)
    connected = {(a, b) for locs in locs_of.values() for a in locs for b in locs if different(a, b)}
    asserted_links = set(facts["connectedTo"])
    room = {loc for loc, doors in doors_of.items() if loc in location and any(d in door_cls for d in doors)}
    corridor = {loc for loc, doors in doors_of.items() if loc in location
                and any(different(a, b) for a in doors if a in door_cls for b in doors if b in door_cls)}
    now = {r: _number(t) for r, t in facts["now"]}
    threshold = {r: _number(h) for r, h in facts["urgencyThreshold"]}
    urgent = {loc for r in robot if r in now and r in threshold
              for loc, v in facts["visitedAt"] if loc in location and now[r] - _number(v) > threshold[r]}
    neighbours: dict[object, list[object]] = defaultdict(list)
    for a, b in connected | asserted_links:
        neighbours[a].append(b)
    reach = {(r, b) for r, a in facts["isIn"] if r in robot and a in location
             for b in neighbours.get(a, []) if b in location and different(a, b)}
    out = [Triple(a, NamedNode(MAP + "connectedTo"), b) for a, b in connected - asserted_links]
    out += [Triple(r, NamedNode(MAP + "canReach"), b) for r, b in reach - set(facts["canReach"])]
    typed = [("LOCATION", location), ("DOOR", door_cls), ("ROBOT", robot), ("ROOM", room), ("CORRIDOR", corridor),
             ("URGENT", urgent)]
    rdf_type = NamedNode(RDF + "type")
    out += [Triple(s, rdf_type, cls(name)) for name, members in typed for s in members
            if (s, cls(name)) not in asserted_types]
    ranges = {(p, o) for p, o in facts["range"]}
    supers = {_iri(sub): [_iri(s) for s in sups] for sub, sups in DATATYPE_SUPERS.items()}
    rng = NamedNode(RDFS + "range")
    out += [Triple(p, rng, s) for p, o in ranges for s in supers.get(o, []) if (p, s) not in ranges]
    return out


def as_quads(triples: list[Triple]) -> list[Quad]:
    """The triples as quads of the default graph (what ``Store.extend`` takes)."""
    return [Quad(t.subject, t.predicate, t.object, DefaultGraph()) for t in triples]
