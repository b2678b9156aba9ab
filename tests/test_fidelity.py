"""Answers that must not depend on how an ontology reached the store, nor on the path a change took.

Each test compares topostore with itself along two paths that must agree (the order axioms were written
in, a streamed LOAD and an ordinary one, SAVE and reload, a REASON after removals and one from scratch,
aRMOR commands and the Python API, a remote store and memory); where the expected answer is stated, it
is what Pellet 2.3.1 answers for the same file (tests/test_fidelity_pellet.py runs Pellet on them).
"""

from __future__ import annotations

import random
import warnings
from pathlib import Path
from unittest import mock

import pytest
from fidelity_cases import CASES, document, namespace
from pyoxigraph import (
    BlankNode,
    CanonicalizationAlgorithm,
    Dataset,
    DefaultGraph,
    Literal,
    NamedNode,
    Quad,
    RdfFormat,
    Triple,
    parse,
    serialize,
)
from support import ABOX_OWL, NS, quiet_turtle, types_of
from test_incremental import from_scratch, tbox_triples

from topostore import Ontology, OntologyWarning
from topostore.armor import ArmorService
from topostore.armor.types import ArmorResponse
from topostore.demo.mapgen import generate
from topostore.rdf.declarations import missing_declarations
from topostore.rdf.terms import value_key
from topostore.rdf.vocab import (
    ASSERTED,
    DIFFERENT_FROM,
    ENTAILED,
    INFERRED,
    OWL,
    SAME_AS,
    TYPE,
    XSD,
    is_skolem,
    owl,
)
from topostore.reason import flips

EX = "http://example.org/fidelity#"
HEAD = f"""@prefix : <{EX}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
"""
TWO = ':Two owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; ' \
      'owl:minQualifiedCardinality "2"^^xsd:nonNegativeInteger ; owl:onClass :F ] .\n'
THREE = TWO.replace(":Two", ":Three").replace('"2"', '"3"')
FILLERS = """:p a owl:ObjectProperty . :F a owl:Class .
:b :p :g1, :g2, :g3 . :g1 a :F . :g2 a :F . :g3 a :F .
:g1 owl:differentFrom :g2 . :g2 owl:differentFrom :g3 . :g1 owl:differentFrom :g3 .
"""


def ex_types(o: Ontology, name: str) -> set[str]:
    return {t.value.removeprefix(EX) for t in o.types(NamedNode(EX + name))}


def test_minima_of_two_and_three_alike_are_reasoned_in_either_order() -> None:
    """Two minimum cardinalities whose fillers are written alike share one rule asking whether two fillers
    are different; joining the minimum of two's difference into its rule must not leave the minimum of three
    unasked when its axiom came first (a document or a saved file writing Three first gave Two alone)."""
    for axioms in (TWO + THREE, THREE + TWO):
        o = quiet_turtle(HEAD + axioms + FILLERS)
        assert o.reason().consistent
        assert ex_types(o, "b") == {"Two", "Three"}, axioms


def test_a_map_class_of_three_doors_defined_before_the_tutorial_file() -> None:
    """A map's own class of locations with three different doors, in a document loaded before the tutorial's
    (CORRIDOR is its minimum of two doors): C1 with three different doors is in both."""
    hub = HEAD.replace(EX, NS) + (':HUB a owl:Class ; owl:equivalentClass [ a owl:Restriction ; '
                                  'owl:onProperty :hasDoor ; owl:minQualifiedCardinality "3"^^xsd:nonNegativeInteger ; '
                                  'owl:onClass :DOOR ] .\n')
    for hub_first in (True, False):
        o = Ontology()
        with warnings.catch_warnings():  # HUB's unnamed doors are LOCATIONs' doors only when told: said
            warnings.simplefilter("ignore", OntologyWarning)
            if hub_first:
                o.load_data(hub)
            o.load(ABOX_OWL)
            if not hub_first:
                o.load_data(hub)
        o.add_fact("C1", "hasDoor", "D3")
        o.add_all_different(["D1", "D2", "D3"])
        assert o.reason().consistent
        assert types_of(o, "C1") == {"LOCATION", "ROOM", "CORRIDOR", "HUB"}, hub_first


# ---------------------------------------------------------------- one ontology, several ways into the store

def answers(o: Ontology, ns: str) -> dict:
    """Consistency, and each individual of namespace ``ns``: its classes and its values of each property of
    ``ns`` (data values by OWL value, a blank node's value as ``_``)."""
    if not o.reason().consistent:
        return {"consistent": False}
    asserted = list(o.store.triples(graph=ASSERTED))
    names = {t for triple in asserted for t in (triple.subject, triple.object)
             if isinstance(t, NamedNode) and t.value.startswith(ns)}
    props = {t.predicate for t in asserted if t.predicate.value.startswith(ns)}
    out = {}
    for name in sorted(names, key=str):
        facts: dict = {"types": sorted(t.value for t in o.types(name) if t.value.startswith(ns))}
        for p in sorted(props, key=str):
            values = sorted(_value(v) for v in o.reads._objects(name, p))
            if values:
                facts[p.value] = values
        out[name.value] = facts
    return {"consistent": True, "individuals": out}


def _value(term) -> str:
    if isinstance(term, Literal):
        return repr(value_key(term))
    return "_" if is_skolem(term.value) else term.value


def canonical(o: Ontology, graph: NamedNode) -> set[Triple]:
    """The triples of ``graph`` with skolem IRIs as blank nodes, canonically named (RDFC-1.0)."""
    def blank(t):
        return BlankNode(t.value.rsplit(":", 1)[1]) if isinstance(t, NamedNode) and is_skolem(t.value) else t

    dataset = Dataset([Quad(blank(t.subject), t.predicate, blank(t.object), DefaultGraph())
                       for t in o.store.triples(graph=graph)])
    dataset.canonicalize(CanonicalizationAlgorithm.RDFC_1_0)
    return {Triple(q.subject, q.predicate, q.object) for q in dataset}


@pytest.mark.parametrize("name", list(CASES))
def test_answers_do_not_depend_on_the_order_of_triples(name: str) -> None:
    """The same triples in another order (a saved file writes them in store order) give the same answers."""
    triples = list(parse(document(name).encode(), format=RdfFormat.TURTLE))
    expected = answers(quiet_turtle(document(name)), namespace(name))
    for seed in range(3):
        shuffled = random.Random(seed).sample(triples, len(triples))
        o = quiet_turtle(serialize(shuffled, format=RdfFormat.N_TRIPLES).decode())
        assert answers(o, namespace(name)) == expected, seed


@pytest.mark.parametrize("name", [*CASES, "literals"])
def test_streamed_ordinary_and_saved_loads_agree(name: str, tmp_path: Path) -> None:
    """A document streamed into an empty ontology, the same document added to a non-empty one (the ordinary
    load), and what SAVE wrote of it read back (Turtle, RDF/XML, N-Triples) hold the same asserted graph up to
    blank node names, and answer the same."""
    text = document(name, LITERALS if name == "literals" else None)
    ns = namespace(name)
    streamed = quiet_turtle(text)
    ordinary = Ontology()
    other = Triple(NamedNode("urn:x:other"), TYPE, NamedNode(OWL + "Thing"))
    ordinary.add(other)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        ordinary.load_data(text)
    ordinary.remove(other)
    expected = answers(streamed, ns)
    assert answers(ordinary, ns) == expected
    assert canonical(ordinary, ASSERTED) == canonical(streamed, ASSERTED)
    for suffix in ("ttl", "owl", "nt"):
        path = streamed.save(tmp_path / f"saved.{suffix}")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OntologyWarning)
            again = Ontology.from_file(path)
        declared = set(missing_declarations(streamed.triples()))  # SAVE writes the declarations the graph lacks
        assert canonical(again, ASSERTED) == canonical(streamed, ASSERTED) | declared, suffix
        assert answers(again, ns) == expected, suffix


#: literal forms a load must keep as written, blank nodes as values and as subjects
LITERALS = """
:d a owl:DatatypeProperty . :k a owl:DatatypeProperty, owl:FunctionalProperty . :o a owl:ObjectProperty .
:x :d "01"^^xsd:integer, "1.0E0"^^xsd:double, "a"@en, "b", "0005"^^xsd:long, "2.50"^^xsd:decimal, "1"^^xsd:boolean .
:y :k "0005"^^xsd:long, "5"^^xsd:int .
:z :o _:n1 . :z :o [ :k "7"^^xsd:long ] . _:n1 :k "-0"^^xsd:int .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :k ; owl:hasValue "5"^^xsd:long ] .
"""


def test_literal_forms_are_saved_as_written() -> None:
    """What SAVE writes shows each literal as the document wrote it (the store keeps numbers canonical)."""
    o = quiet_turtle(document("literals", LITERALS))
    saved = o.serialize("ntriples").decode()
    for form in ('"01"^^<http://www.w3.org/2001/XMLSchema#integer>', '"0005"^^<http://www.w3.org/2001/XMLSchema#long>',
                 '"2.50"^^<http://www.w3.org/2001/XMLSchema#decimal>', '"-0"^^<http://www.w3.org/2001/XMLSchema#int>',
                 '"1"^^<http://www.w3.org/2001/XMLSchema#boolean>', '"1.0E0"^^<http://www.w3.org/2001/XMLSchema#double>'):
        assert form in saved, form
    assert answers(o, namespace("literals"))["individuals"][namespace("literals") + "y"]["types"] == \
        [namespace("literals") + "C"]


# ---------------------------------------------------------------- removals, then REASON: the same as from scratch

def assert_as_from_scratch(o: Ontology, context: object) -> None:
    """The inferred and entailed-only graphs and the verdict of ``o``'s last REASON are a full REASON's of the
    same asserted graph (the helper graph may hold more: the asks a full REASON leaves out)."""
    inferred, _aux, entailed, consistent = from_scratch(o)
    assert o.report.consistent == consistent, context
    assert set(o.store.triples(graph=INFERRED)) == inferred, (context, o.report.stats.mode)
    assert set(o.store.triples(graph=ENTAILED)) == entailed, (context, o.report.stats.mode)


def _asserted(o: Ontology, s=None, p=None, obj=None) -> list[Triple]:
    return list(o.store.triples(s, p, obj, ASSERTED))


def map_change(o: Ontology, m, rng: random.Random) -> tuple:
    """One random change of a generated map, most of them removals: (description, change)."""
    loc, door, robot = rng.choice([*m.locations, "X1"]), rng.choice([*m.doors, "DX"]), rng.choice(list(m.robots))
    t, pick = rng.randint(1665579600, 1665579900), rng.randrange(1000)
    iri = o.iri

    def one(triples: list[Triple]) -> list[Triple]:
        return triples[pick % len(triples):][:1] if triples else []

    changes = {
        "move": lambda: o.replace(robot, "isIn", loc),
        "clock": lambda: o.replace(robot, "now", o.value(t, "long")),
        "threshold": lambda: o.replace(robot, "urgencyThreshold", o.value(t % 130 - 5, "long")),
        "visit": lambda: o.replace(loc, "visitedAt", o.value(t, "long")),
        "forget a visit": lambda: o.remove(*_asserted(o, iri(loc), iri("visitedAt"))),
        "remove a door link": lambda: o.remove(*one(_asserted(o, None, iri("hasDoor")))),
        "add a door link": lambda: o.add_fact(loc, "hasDoor", door),
        "remove a location": lambda: o.remove_individual(loc),
        "remove a door": lambda: o.remove_individual(door),
        "type told": lambda: o.add_type(loc, rng.choice(["CORRIDOR", "ROOM", "URGENT"])),
        "remove a told type": lambda: o.remove(*one([x for x in _asserted(o, None, TYPE)
                                                       if x.object.value.startswith(NS)])),
        "stop the clock": lambda: o.remove(*_asserted(o, iri(robot), iri("now"))),
        "robot nowhere": lambda: o.remove(*_asserted(o, iri(robot), iri("isIn"))),
        "sameAs": lambda: o.add(Triple(iri(loc), SAME_AS, iri(rng.choice(m.locations)))),
        "differentFrom": lambda: o.add(Triple(iri(loc), DIFFERENT_FROM, iri(rng.choice(m.locations)))),
        "remove a sameAs or differentFrom": lambda: o.remove(*one(_asserted(o, None, SAME_AS)
                                                                 + _asserted(o, None, DIFFERENT_FROM))),
        "connectedTo told": lambda: o.add_fact(loc, "connectedTo", rng.choice(m.locations)),
        "remove a told link": lambda: o.remove(*one(_asserted(o, None, iri("connectedTo"))
                                                    + _asserted(o, None, iri("canReach")))),
        "remove an AllDifferent": lambda: o.remove(*one(_asserted(o, None, TYPE, owl("AllDifferent")))),
    }
    name = rng.choice(sorted(changes))
    return (name, loc, door, robot, t), changes[name]


@pytest.mark.parametrize("seed", range(4))
def test_removals_on_generated_maps_equal_a_full_reason(seed: int) -> None:
    """Maps of 8 to 50 locations, one or two robots, declared different or not; batches of changes, most of
    them removals (of visits, doors, individuals, told types, clocks, sameAs/differentFrom, AllDifferent), the
    clock moved back and forth and the threshold changed: each REASON equals a full one from scratch."""
    rng = random.Random(seed)
    m = generate(rng.randint(8, 50), seed=seed, robots=rng.randint(1, 2))
    o = Ontology()
    o.add(*tbox_triples())
    o.add(*m.triples(all_different=seed % 3 != 0))
    o.max_change_share = 1.0
    o.reason()
    done = []
    with mock.patch.object(flips, "WINDOW_MIN", 0 if seed % 2 else flips.WINDOW_MIN):
        for _ in range(10):
            for _ in range(rng.randint(1, 3)):
                what, change = map_change(o, m, rng)
                change()
                done.append(what)
            o.reason()
            assert_as_from_scratch(o, done)


#: a TBox with most of what the map's TBox lacks, for changes beyond the map's
TOGGLED = """
:p a owl:ObjectProperty ; owl:inverseOf :pi . :pi a owl:ObjectProperty ; rdfs:domain :E .
:s a owl:ObjectProperty, owl:SymmetricProperty . :t a owl:ObjectProperty, owl:TransitiveProperty .
:p rdfs:subPropertyOf :t . :ch a owl:ObjectProperty ; owl:propertyChainAxiom ( :p :s ) .
:f a owl:ObjectProperty, owl:FunctionalProperty . :d a owl:DatatypeProperty . :k a owl:DatatypeProperty, owl:FunctionalProperty .
:A a owl:Class . :B a owl:Class ; owl:hasKey ( :k ) . :D a owl:Class ; owl:disjointWith :A . :E a owl:Class .
:HV owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :v0 ] .
:HD owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:hasValue 7 ] .
:S owl:equivalentClass [ a owl:Restriction ; owl:onProperty :s ; owl:someValuesFrom :A ] .
:T2 owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality "2"^^xsd:nonNegativeInteger ;
    owl:onClass :B ] .
:T3 owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:minCardinality "3"^^xsd:nonNegativeInteger ] .
:AV rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :B ] .
:M1 rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :pi ; owl:maxCardinality "1"^^xsd:nonNegativeInteger ] .
:I owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :B :E ) ] .
:Big owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom [ a rdfs:Datatype ;
    owl:onDatatype xsd:integer ; owl:withRestrictions ( [ xsd:minInclusive 10 ] ) ] ] .
"""


def owl_fact(ns: str, rng: random.Random) -> Triple:
    """A random ABox fact over :data:`TOGGLED`'s vocabulary."""
    def n(x: str) -> NamedNode:
        return NamedNode(ns + x)

    a, b = n(f"i{rng.randrange(7)}"), rng.choice([n(f"i{rng.randrange(7)}"), n("v0")])
    kind = rng.randrange(9)
    if kind < 3:
        return Triple(a, n(rng.choice(["p", "pi", "s", "t", "f", "ch"])), b)
    if kind < 5:
        return Triple(a, TYPE, n(rng.choice(["A", "B", "D", "E", "AV", "M1", "HV", "S"])))
    if kind == 5:
        return Triple(a, n("d"), Literal(str(rng.choice([3, 7, 10, 12])), datatype=NamedNode(XSD + "long")))
    if kind == 6:
        return Triple(a, n("k"), Literal(str(rng.randrange(3)), datatype=NamedNode(XSD + "integer")))
    return Triple(a, rng.choice([SAME_AS, DIFFERENT_FROM]), b)


@pytest.mark.parametrize("seed", range(5))
def test_owl_facts_added_and_removed_equal_a_full_reason(seed: int) -> None:
    """Inverse, symmetric, transitive, chained, functional properties, keys, hasValue, cardinalities, a
    universal, a maximum, a datatype restriction: random facts added and removed, each REASON as from scratch."""
    rng = random.Random(seed)
    o = quiet_turtle(document("toggled", TOGGLED))
    o.max_change_share = 1.0
    held = [owl_fact(namespace("toggled"), rng) for _ in range(rng.randint(3, 15))]
    o.add(*held)
    o.reason()
    done = []
    for _ in range(12):
        for _ in range(rng.randint(1, 3)):
            if held and rng.random() < 0.5:
                fact = held.pop(rng.randrange(len(held)))
                o.remove(fact)
                done.append(("-", str(fact)))
            else:
                fact = owl_fact(namespace("toggled"), rng)
                o.add(fact)
                held.append(fact)
                done.append(("+", str(fact)))
        o.reason()
        assert_as_from_scratch(o, done)


# ---------------------------------------------------------------- the same changes as aRMOR commands

def armor_command(service: ArmorService, ref: str, command: str, spec1: str, spec2: str, args: list) -> ArmorResponse:
    return service.call({"client_name": "c", "reference_name": ref, "command": command, "primary_command_spec": spec1,
                         "secondary_command_spec": spec2, "args": [str(a) for a in args]})


def armor_change(o: Ontology, m, rng: random.Random) -> tuple:
    """One random aRMOR manipulation of a generated map's reference ``o`` (removals most of them)."""
    loc, door, robot = rng.choice([*m.locations, "X1"]), rng.choice([*m.doors, "DX"]), rng.choice(list(m.robots))
    t = rng.randint(1665579600, 1665579900)

    def told(subject: str, prop: str, default: object) -> object:
        values = o.data_values(prop, subject) or o.object_values(prop, subject)
        return values[0].value if values and hasattr(values[0], "value") else (values[0] if values else default)

    return rng.choice([
        ("REPLACE", "OBJECTPROP", "IND", ["isIn", robot, loc, told(robot, "isIn", "C1")]),
        ("REPLACE", "DATAPROP", "IND", ["now", robot, "LONG", t, told(robot, "now", t)]),
        ("REPLACE", "DATAPROP", "IND", ["visitedAt", loc, "LONG", t, told(loc, "visitedAt", t)]),
        ("REMOVE", "DATAPROP", "IND", ["visitedAt", loc, "LONG", told(loc, "visitedAt", 1)]),
        ("REMOVE", "DATAPROP", "IND", ["urgencyThreshold", robot, "LONG", told(robot, "urgencyThreshold", 7)]),
        ("ADD", "DATAPROP", "IND", ["urgencyThreshold", robot, "LONG", rng.randint(-5, 100)]),
        ("REMOVE", "OBJECTPROP", "IND", ["hasDoor", loc, door]),
        ("ADD", "OBJECTPROP", "IND", ["hasDoor", loc, door]),
        ("REMOVE", "IND", "", [rng.choice([loc, door])]),
        ("ADD", "IND", "CLASS", [loc, rng.choice(["CORRIDOR", "ROOM", "URGENT"])]),
        ("REMOVE", "IND", "CLASS", [loc, rng.choice(["CORRIDOR", "ROOM", "URGENT"])]),
        ("DISJOINT", "IND", "", rng.sample([*m.locations, *m.doors], rng.randint(2, 4))),
    ])


def armor_walk(seed: int, tmp_path: Path, store: str | None = None, steps: int = 8) -> None:
    """LOAD a generated map through aRMOR (buffered reasoner), change it with aRMOR commands, REASON: each time
    the reference's closure is a full REASON's, and the class and canReach queries answer what the reference
    holds."""
    rng = random.Random(seed)
    m = generate(rng.randint(8, 40), seed=seed, robots=rng.randint(1, 2))
    onto = Ontology()
    onto.add(*tbox_triples())
    onto.add(*m.triples(all_different=seed % 2 == 0))
    path = onto.save(tmp_path / f"map{seed}.owl")
    ref = f"fidelity{seed}-{rng.randrange(10**6)}"
    service = ArmorService(store=store)
    try:
        loaded = armor_command(service, ref, "LOAD", "FILE", "", [path, NS.rstrip("#"), "false", "PELLET", "true"])
        assert loaded.success, loaded.error_description
        o = service.reference(ref).ontology
        done = []
        for _ in range(steps):
            for _ in range(rng.randint(1, 3)):
                command = armor_change(o, m, rng)
                done.append((command, armor_command(service, ref, *command).exit_code))
            assert armor_command(service, ref, "REASON", "", "", []).success
            assert_as_from_scratch(o, done)
            if not o.report.consistent:
                continue
            for cls in ("LOCATION", "ROOM", "CORRIDOR", "URGENT"):
                reply = armor_command(service, ref, "QUERY", "IND", "CLASS", [cls])
                assert sorted(reply.queried_objects) == sorted(f"<{v.value}>" for v in o.reads._instances(o.iri(cls)))
            for robot in m.robots:
                reply = armor_command(service, ref, "QUERY", "OBJECTPROP", "IND", ["canReach", robot])
                assert sorted(reply.queried_objects) == sorted(f"<{NS}{v}>" for v in o.object_values("canReach", robot))
    finally:
        service.close()


@pytest.mark.parametrize("seed", range(2))
def test_armor_removals_equal_a_full_reason(seed: int, tmp_path: Path) -> None:
    armor_walk(seed, tmp_path)


def test_armor_removals_on_a_remote_store_equal_a_full_reason(oxigraph_url: str, tmp_path: Path) -> None:
    """The same through ``oxigraph serve``: the store's reads and writes go over SPARQL."""
    armor_walk(7, tmp_path, store=oxigraph_url, steps=5)


def test_swrl_string_functions_give_strings_without_a_language_tag() -> None:
    """swrlb:lowerCase, upperCase and substring are fn:lower-case, fn:upper-case and fn:substring, whose
    result is an xs:string: "Hello"@en lower-cased equals "hello" (Pellet 2.3.1 concludes all three)."""
    o = Ontology(prefix=EX)
    o.load_data(HEAD + ':s a owl:DatatypeProperty . :Lower a owl:Class . :Upper a owl:Class . :Middle a owl:Class . '
                       ':en :s "Hello"@en . :plain :s "Hello" .')
    o.add_rule('s(?x, ?v) ^ swrlb:lowerCase(?l, ?v) ^ swrlb:equal(?l, "hello") -> Lower(?x)', "Lower")
    o.add_rule('s(?x, ?v) ^ swrlb:upperCase(?u, ?v) ^ swrlb:equal(?u, "HELLO") -> Upper(?x)', "Upper")
    o.add_rule('s(?x, ?v) ^ swrlb:substring(?m, ?v, 2, 3) ^ swrlb:equal(?m, "ell") -> Middle(?x)', "Middle")
    assert o.reason().consistent
    assert ex_types(o, "en") == ex_types(o, "plain") == {"Lower", "Upper", "Middle"}


def test_datatypes_of_an_existential_hold_only_their_values() -> None:
    """An existential on a datatype topostore does not check makes no member of a value outside it (it took
    any literal: 9 and "hello" were values of an undeclared datatype of the ontology's own); the string types
    derived by their characters hold the strings whose characters they allow (Pellet 2.3.1: "hello" is an
    xsd:token, not "a  b", 5 or "x"@en)."""
    o = quiet_turtle(HEAD + '''
:d a owl:DatatypeProperty . :Small a rdfs:Datatype .
:SomeSmall owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom :Small ] .
:T owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom xsd:token ] .
:N owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom xsd:normalizedString ] .
:S owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom xsd:string ] .
:L owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom xsd:language ] .
:a :d "hello" . :b :d "a  b" . :c :d "a\\tb" . :e :d "en-GB" . :f :d "x"@en . :g :d "ab"^^xsd:token . :h :d 9 .
''')
    assert o.reason().consistent
    assert {name: ex_types(o, name) for name in "abcefgh"} == {
        "a": {"S", "N", "T", "L"}, "b": {"S", "N"}, "c": {"S"}, "e": {"S", "N", "T", "L"}, "f": set(),
        "g": {"S", "N", "T", "L"}, "h": set()}


def test_a_value_outside_a_string_range_is_inconsistent() -> None:
    ranged = HEAD + ":d a owl:DatatypeProperty ; rdfs:range xsd:token . "
    assert not quiet_turtle(ranged + ':a :d "a  b" .').reason().consistent
    assert quiet_turtle(ranged + ':a :d "ab" .').reason().consistent
    assert quiet_turtle(HEAD + ':d a owl:DatatypeProperty ; rdfs:range xsd:string . :a :d "ab"^^xsd:token .'
                        ).reason().consistent


def test_data_values_are_matched_by_value() -> None:
    """A data hasValue and a negative data property assertion compare values, not RDF terms: 3.0 and
    "3"^^xsd:long are 3, .5 is 0.50, 14:00+02:00 is 12:00Z; "3" (a string) and an instant without a time
    zone are not (Pellet 2.3.1 gives the same classes, and finds the assertion of 5.0 after "not 5"
    inconsistent)."""
    o = quiet_turtle(document("values_by_value"))
    assert o.reason().consistent
    ns = namespace("values_by_value")
    assert {n: {t.value.removeprefix(ns) for t in o.types(NamedNode(ns + n))} for n in "xyzwuv"} == {
        "x": {"Three"}, "y": {"Three"}, "z": {"Half"}, "w": set(), "u": {"Noon"}, "v": set()}
    o.load_data(HEAD + '[] a owl:NegativePropertyAssertion ; owl:sourceIndividual :x ; owl:assertionProperty :d ; '
                       'owl:targetValue 5 . :x :d "5.0"^^xsd:decimal .')
    assert not o.reason().consistent


def test_removing_an_individual_removes_every_axiom_naming_it() -> None:
    """aRMOR's REMOVE IND removes every axiom mentioning the individual (OWL API's entity remover), so the
    asserted graph holds no part of an axiom that named it (a restriction without its value, a one-of list
    without its first cell and an assertion without its source stayed, and SAVE wrote them)."""
    o = quiet_turtle(HEAD + """:p a owl:ObjectProperty . :w a owl:NamedIndividual . :b :p :w .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :v ] .
:O owl:equivalentClass [ a owl:Class ; owl:oneOf ( :v :w ) ] .
[] a owl:NegativePropertyAssertion ; owl:sourceIndividual :v ; owl:assertionProperty :p ; owl:targetIndividual :w .
""")
    kept = HEAD + ":p a owl:ObjectProperty . :w a owl:NamedIndividual . :b :p :w ."
    o.remove_individual(NamedNode(EX + "v"))
    assert canonical(o, ASSERTED) == canonical(quiet_turtle(kept), ASSERTED)


def test_removing_an_individual_a_rule_names_removes_the_rule(tmp_path: Path) -> None:
    """REMOVE IND of an individual a SWRL rule names removes the rule with it: the rule's atom lost its
    argument, no REASON could compile the rules any more, and each reverted the removal."""
    path = tmp_path / "named.ttl"
    path.write_text(HEAD + ":p a owl:ObjectProperty . :C a owl:Class . :v a owl:NamedIndividual . :a :p :v .")
    service = ArmorService()
    try:
        assert armor_command(service, "r", "LOAD", "FILE", "", [path, EX.rstrip("#"), "false", "PELLET", "true"]).success
        assert armor_command(service, "r", "ADD", "SWRL", "", ["Named", "p(?x, v) -> C(?x)"]).success
        assert armor_command(service, "r", "REASON", "", "", []).success
        assert armor_command(service, "r", "QUERY", "IND", "CLASS", ["C"]).queried_objects == [f"<{EX}a>"]
        assert armor_command(service, "r", "REMOVE", "IND", "", ["v"]).success
        assert armor_command(service, "r", "REASON", "", "", []).success
        assert armor_command(service, "r", "QUERY", "IND", "CLASS", ["C"]).queried_objects == []
        assert armor_command(service, "r", "QUERY", "SWRL", "", []).queried_objects == []
    finally:
        service.close()
