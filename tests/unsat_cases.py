"""Ontologies with a class no individual can be a member of, by clashes among unnamed values, and satisfiable
look-alikes: read by tests/test_unsatisfiable.py, and given to Pellet by tests/test_fidelity_pellet.py."""

from __future__ import annotations

NS = "http://e.org/u#"
PREFIXES = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
:p a owl:ObjectProperty . :q a owl:ObjectProperty . :A a owl:Class . :B a owl:Class . :C a owl:Class .
:D a owl:Class . :E a owl:Class .
"""


def some(p: str, filler: str) -> str:
    return f"[ a owl:Restriction ; owl:onProperty :{p} ; owl:someValuesFrom {filler} ]"


def only(p: str, filler: str) -> str:
    return f"[ a owl:Restriction ; owl:onProperty :{p} ; owl:allValuesFrom {filler} ]"


def card(kind: str, n: int, p: str, filler: str = "") -> str:
    on = f" ; owl:onClass {filler}" if filler else ""
    name = f"{kind}QualifiedCardinality" if filler else f"{kind}Cardinality"
    return f'[ a owl:Restriction ; owl:onProperty :{p} ; owl:{name} "{n}"^^xsd:nonNegativeInteger{on} ]'


#: name -> TBox in which :C has no member (its member :x is an inconsistency), and the check that says so
EMPTY = {
    "minimum above a functional property": (f":p a owl:FunctionalProperty . :C owl:equivalentClass {card('min', 3, 'p')} .",
                                            "cls-unsat"),
    "minimum above a maximum": (f":C rdfs:subClassOf {card('min', 2, 'p')} , {card('max', 1, 'p')} .", "cls-unsat"),
    "qualified minimum under a wider maximum": (f":A rdfs:subClassOf :B . :C rdfs:subClassOf {card('min', 2, 'p', ':A')} "
                                                f", {card('max', 1, 'p', ':B')} .", "cls-unsat"),
    "existential meets a universal": (f":A owl:disjointWith :B . :C rdfs:subClassOf {some('p', ':A')} , "
                                      f"{only('p', ':B')} .", "cls-unsat"),
    "existential of an empty class": (f":A rdfs:subClassOf owl:Nothing . :C rdfs:subClassOf {some('p', ':A')} .",
                                      "cls-unsat"),
    "existential of an intersection of disjoint classes": (
        f":A owl:disjointWith :B . :C rdfs:subClassOf {some('p', '[ owl:intersectionOf ( :A :B ) ]')} .", "cls-unsat"),
    "two existentials of disjoint classes on a functional property": (
        f":p a owl:FunctionalProperty . :A owl:disjointWith :B . :C rdfs:subClassOf {some('p', ':A')} , "
        f"{some('p', ':B')} .", "cls-unsat"),
    "existential of an empty class found empty in turn": (
        f":q a owl:FunctionalProperty . :A owl:equivalentClass {card('min', 2, 'q')} . "
        f":C rdfs:subClassOf {some('p', ':A')} .", "cls-unsat"),
    "existential nested in a universal's filler": (
        f":A owl:disjointWith :B . :D rdfs:subClassOf {some('q', ':A')} . :E rdfs:subClassOf {only('q', ':B')} . "
        f":C rdfs:subClassOf {some('p', ':D')} , {only('p', ':E')} .", "cls-unsat"),
    "maximum of none": (f":C rdfs:subClassOf {some('p', ':A')} , {card('max', 0, 'p')} .", "cls-unsat"),
    "functional data property with a value outside the existential's datatype": (
        ":d a owl:DatatypeProperty, owl:FunctionalProperty . "
        ":C rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom xsd:string ] . :x :d 5 .",
        "cls-svf-fp"),
    **{f"two existentials of {a} and {b} on a functional data property": (
        f":d a owl:DatatypeProperty, owl:FunctionalProperty . :C rdfs:subClassOf {some('d', a)} , {some('d', b)} .",
        "cls-unsat") for a, b in (("xsd:boolean", "xsd:integer"), ("xsd:double", "owl:real"),
                                  ("xsd:string", "rdf:langString"), ("xsd:anyURI", "xsd:string"),
                                  ("xsd:negativeInteger", "xsd:nonNegativeInteger"), ("xsd:float", "xsd:double"),
                                  ("xsd:hexBinary", "xsd:base64Binary"), ("xsd:token", "rdf:langString"))},
    "minimum above the inverse of an inverse-functional property": (
        f":p a owl:InverseFunctionalProperty ; owl:inverseOf :q . :C rdfs:subClassOf {card('min', 2, 'q')} .",
        "cls-unsat"),
}

#: name -> TBox in which :C has members: no violation, no notice
SATISFIABLE = {
    "minimum within the maximum": f":C rdfs:subClassOf {card('min', 2, 'p')} , {card('max', 2, 'p')} .",
    "existential within the universal": f":A rdfs:subClassOf :B . :C rdfs:subClassOf {some('p', ':A')} , {only('p', ':B')} .",
    "existential of classes not disjoint": f":C rdfs:subClassOf {some('p', ':A')} , {only('p', ':B')} .",
    "minimum outside the qualified maximum": (f":A owl:disjointWith :B . :C rdfs:subClassOf {card('min', 2, 'p', ':A')} "
                                              f", {card('max', 1, 'p', ':B')} ."),
    "a cycle of existentials": f":C rdfs:subClassOf {some('p', ':C')} , {only('p', ':C')} .",
    "two existentials on a functional property that may meet": (
        f":p a owl:FunctionalProperty . :C rdfs:subClassOf {some('p', ':A')} , {some('p', ':B')} ."),
    "functional data property with a value inside the datatype": (
        ":d a owl:DatatypeProperty, owl:FunctionalProperty . "
        ":C rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom xsd:string ] . :x :d \"5\" ."),
    "minimum on the inverse of a functional property": (
        f":p a owl:FunctionalProperty ; owl:inverseOf :q . :C rdfs:subClassOf {card('min', 2, 'q')} ."),
    **{f"two existentials of {a} and {b} on a functional data property": (
        f":d a owl:DatatypeProperty, owl:FunctionalProperty . :C rdfs:subClassOf {some('d', a)} , {some('d', b)} .")
       for a, b in (("xsd:byte", "xsd:unsignedInt"), ("xsd:string", "xsd:token"), ("xsd:dateTime", "xsd:dateTimeStamp"),
                    ("xsd:integer", "xsd:decimal"), ("rdf:PlainLiteral", "xsd:string"))},
    "functional data property with a derived string as a plain literal": (
        ":d a owl:DatatypeProperty, owl:FunctionalProperty . :C rdfs:subClassOf [ a owl:Restriction ; "
        "owl:onProperty :d ; owl:someValuesFrom rdf:PlainLiteral ] . :x :d \"ab\"^^xsd:normalizedString ."),
}
