"""Small ontologies on what the unnamed value of an existential is (its property's ranges, the universals told of
its subject), each with the memberships and subsumptions Pellet 2.3.1 finds and those it does not.

``p rdfs:range R``, ``E ⊑ ∃p.D`` and ``C ≡ ∃p.R`` put every ``E`` in ``C`` and ``E`` under ``C``; so do a
super-property's or an equivalent property's range, an inverse's domain, a universal on the property or a
super-property told of ``E`` or of another class of the individual, a data range, a minimum cardinality.  The
mirror images (a sub-property's range, a universal on a sub-property, a domain used for the value) give nothing.
Read by tests/test_existential_values.py (topostore alone) and tests/test_fidelity_pellet.py (against Pellet).
"""

from __future__ import annotations

from dataclasses import dataclass

#: the namespace of each case: BASE + its name + "#"
BASE = "http://example.org/ev/"

PREFIXES = """@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
"""


def some(p: str, f: str) -> str:
    return f"[ a owl:Restriction ; owl:onProperty {p} ; owl:someValuesFrom {f} ]"


def only(p: str, f: str) -> str:
    return f"[ a owl:Restriction ; owl:onProperty {p} ; owl:allValuesFrom {f} ]"


def at_least(n: int, p: str, f: str | None = None) -> str:
    if f is None:
        return f'[ a owl:Restriction ; owl:onProperty {p} ; owl:minCardinality "{n}"^^xsd:nonNegativeInteger ]'
    return (f'[ a owl:Restriction ; owl:onProperty {p} ; owl:minQualifiedCardinality "{n}"^^xsd:nonNegativeInteger ; '
            f'owl:onClass {f} ]')


CLASSES = ":D a owl:Class . :R a owl:Class . :G a owl:Class . :K a owl:Class . :U a owl:Class .\n"


@dataclass(frozen=True)
class Case:
    """A Turtle body (``:`` is the case's namespace), what Pellet derives and what it does not (short names)."""

    body: str
    members: tuple[tuple[str, str], ...] = ()
    subclasses: tuple[tuple[str, str], ...] = ()
    not_members: tuple[tuple[str, str], ...] = ()
    not_subclasses: tuple[tuple[str, str], ...] = ()


def _defined(filler: str, p: str = ":p") -> str:
    return f":C a owl:Class ; owl:equivalentClass {some(p, filler)} .\n:x a owl:NamedIndividual , :E .\n"


CASES: dict[str, Case] = {
    "own_range": Case(
        f":p a owl:ObjectProperty ; rdfs:range :R .\n:E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} .\n"
        + _defined(":R") + f":E2 a owl:Class ; rdfs:subClassOf {some(':p', 'owl:Thing')} .\n"
        ":x2 a owl:NamedIndividual , :E2 .\n",
        members=(("x", "C"), ("x2", "C")), subclasses=(("E", "C"), ("E2", "C"))),
    "min_cardinality_range": Case(
        f":p a owl:ObjectProperty ; rdfs:range :R .\n:E a owl:Class ; rdfs:subClassOf {at_least(1, ':p')} .\n"
        + _defined(":R") + f":E2 a owl:Class ; rdfs:subClassOf {at_least(2, ':p', ':D')} .\n"
        f":C2 a owl:Class ; owl:equivalentClass {at_least(2, ':p', ':R')} .\n:x2 a owl:NamedIndividual , :E2 .\n",
        members=(("x", "C"), ("x2", "C2"), ("x2", "C")), subclasses=(("E", "C"), ("E2", "C2")),
        not_members=(("x", "C2"),)),
    "universal_same_class": Case(
        f":p a owl:ObjectProperty .\n:E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} , {only(':p', ':G')} .\n"
        + _defined(":G"), members=(("x", "C"),), subclasses=(("E", "C"),)),
    "super_range": Case(
        ":q a owl:ObjectProperty ; rdfs:range :R . :p a owl:ObjectProperty ; rdfs:subPropertyOf :q .\n"
        f":E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} .\n" + _defined(":R"),
        members=(("x", "C"),), subclasses=(("E", "C"),)),
    "inverse_domain": Case(
        ":p a owl:ObjectProperty . :pi a owl:ObjectProperty ; owl:inverseOf :p ; rdfs:domain :K .\n"
        f":E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} .\n" + _defined(":K"),
        members=(("x", "C"),), subclasses=(("E", "C"),)),
    "super_universal": Case(
        ":q a owl:ObjectProperty . :p a owl:ObjectProperty ; rdfs:subPropertyOf :q .\n"
        f":E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} , {only(':q', ':G')} .\n" + _defined(":G"),
        members=(("x", "C"),), subclasses=(("E", "C"),)),
    "equivalent_range": Case(
        ":p a owl:ObjectProperty ; owl:equivalentProperty :q . :q a owl:ObjectProperty ; rdfs:range :R .\n"
        f":E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} .\n" + _defined(":R"),
        members=(("x", "C"),), subclasses=(("E", "C"),)),
    "universal_of_another_class": Case(
        f":p a owl:ObjectProperty .\n:E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} .\n"
        f":U rdfs:subClassOf {only(':p', ':G')} .\n" + _defined(":G") + ":x a :U .\n:y a owl:NamedIndividual , :U .\n",
        members=(("x", "C"),), not_members=(("y", "C"),), not_subclasses=(("E", "C"), ("U", "C"))),
    "data_range": Case(
        ":d a owl:DatatypeProperty ; rdfs:range xsd:integer .\n"
        f":E a owl:Class ; rdfs:subClassOf {some(':d', 'rdfs:Literal')} .\n" + _defined("xsd:integer", ":d"),
        members=(("x", "C"),), subclasses=(("E", "C"),)),
    "range_and_filler_meet": Case(
        ":p a owl:ObjectProperty ; rdfs:range :R .\n:X a owl:Class ; owl:equivalentClass "
        "[ a owl:Class ; owl:intersectionOf ( :D :R ) ] .\n"
        f":E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} .\n" + _defined(":X"),
        members=(("x", "C"),), subclasses=(("E", "C"),)),
    "filler_and_universal_meet": Case(
        f":p a owl:ObjectProperty .\n:E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} .\n"
        f":U rdfs:subClassOf {only(':p', ':G')} .\n"
        + ":X a owl:Class ; owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :D :G ) ] .\n"
        + _defined(":X") + ":x a :U .\n"
        f":E2 a owl:Class ; rdfs:subClassOf {some(':p', ':D')} , {only(':p', ':G')} .\n:x2 a owl:NamedIndividual , :E2 .\n",
        members=(("x", "C"), ("x2", "C")), subclasses=(("E2", "C"),), not_subclasses=(("E", "C"), ("U", "C"))),
    "has_value_classified": Case(
        ":p a owl:ObjectProperty . :a a owl:NamedIndividual , :K .\n"
        ":E a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :a ] .\n"
        ":C a owl:Class ; owl:equivalentClass " + some(":p", ":K") + " .\n:x a owl:NamedIndividual , :E .\n",
        members=(("x", "C"),), subclasses=(("E", "C"),)),
    "mirrors": Case(
        ":p a owl:ObjectProperty . :q a owl:ObjectProperty ; rdfs:subPropertyOf :p ; rdfs:range :R .\n"
        f":E a owl:Class ; rdfs:subClassOf {some(':p', ':D')} , {only(':q', ':G')} .\n"
        f":C1 a owl:Class ; owl:equivalentClass {some(':p', ':R')} .\n"
        f":C2 a owl:Class ; owl:equivalentClass {some(':p', ':G')} .\n:x a owl:NamedIndividual , :E .\n"
        f":p2 a owl:ObjectProperty ; rdfs:domain :K .\n:E2 a owl:Class ; rdfs:subClassOf {some(':p2', ':D')} .\n"
        f":C3 a owl:Class ; owl:equivalentClass {some(':p2', ':K')} .\n:x2 a owl:NamedIndividual , :E2 .\n"
        f":E4 a owl:Class ; rdfs:subClassOf {some(':p', ':D')} .\n:E4b a owl:Class ; rdfs:subClassOf "
        f"{only(':p', ':G')} .\n:y a owl:NamedIndividual , :E4 .\n:z a owl:NamedIndividual , :E4b .\n",
        members=(("x2", "K"),),
        not_members=(("x", "C1"), ("x", "C2"), ("x2", "C3"), ("y", "C2"), ("z", "C2")),
        not_subclasses=(("E", "C1"), ("E", "C2"), ("E2", "C3"), ("E4", "C2"), ("E4b", "C2"))),
}


def namespace(name: str) -> str:
    return f"{BASE}{name}#"


def document(name: str) -> str:
    """The Turtle document of one case."""
    return f"{PREFIXES}@prefix : <{namespace(name)}> .\n{CLASSES}{CASES[name].body}"


def all_cases() -> str:
    """Every case in one document, each in its own namespace (Turtle lets ``:`` be declared again)."""
    return PREFIXES + "".join(f"@prefix : <{namespace(n)}> .\n{CLASSES}{c.body}" for n, c in CASES.items())
