"""Blank-node class expressions and data ranges written without their type triple, in the places the OWL API
3.4.3 under Pellet 2.3.1 reads them and those it does not (tests/test_untyped_expressions.py checks topostore's
reading and notices, tests/test_fidelity_pellet.py gives Pellet the same files).

Each case: (Turtle body, whether the axiom with the untyped node is read, the individual and class that
tell).  ``:`` is the case's namespace; :func:`document` adds the prefixes and the declarations every case
shares (individuals a–d, the object property p, the data property dp, the classes A and B).
"""

from __future__ import annotations

BASE = "http://example.org/fidelity/untyped/"  # under the fidelity tests' namespace: their answers read it

_SOME = "[ owl:onProperty :p ; owl:someValuesFrom :A ]"
_TYPED_SOME = "[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :A ]"
_FACETS = 'owl:onDatatype xsd:integer ; owl:withRestrictions ( [ xsd:minInclusive 10 ] )'

#: name -> (body, read, (individual, class)): the individual is in the class exactly when the axiom is read
CASES: dict[str, tuple[str, bool, tuple[str, str]]] = {
    # an equivalence with a name known only from it: no class to the OWL API, the axiom is not there
    "eq_restriction_undeclared": (f":S owl:equivalentClass {_SOME} . :a :p :b . :b a :A .", False, ("a", "S")),
    "eq_hasvalue_undeclared": (":V owl:equivalentClass [ owl:onProperty :p ; owl:hasValue :c ] . :d :p :c .",
                               False, ("d", "V")),
    "eq_intersection_undeclared": (":I owl:equivalentClass [ owl:intersectionOf ( :A :B ) ] . :a a :A, :B .",
                                   False, ("a", "I")),
    "eq_oneof_undeclared": (":E owl:equivalentClass [ owl:oneOf ( :a ) ] .", False, ("a", "E")),
    "eq_names_only": (f":S owl:equivalentClass :T . :S owl:equivalentClass {_SOME} . :a :p :b . :b a :A .",
                      False, ("a", "S")),
    # the other side known as a class: declared, used as a type, in a subclass triple, a typed expression
    "eq_declared": (f":S a owl:Class ; owl:equivalentClass {_SOME} . :a :p :b . :b a :A .", True, ("a", "S")),
    "eq_declared_rdfs": (f":S a rdfs:Class ; owl:equivalentClass {_SOME} . :a :p :b . :b a :A .", True, ("a", "S")),
    "eq_reversed": (f":S a owl:Class . {_SOME} owl:equivalentClass :S . :a :p :b . :b a :A .", True, ("a", "S")),
    "eq_used_as_type": (f":S owl:equivalentClass {_SOME} . :a :p :b . :b a :A . :d a :S .", True, ("a", "S")),
    "eq_in_subclass": (f":S rdfs:subClassOf {_TYPED_SOME} ; owl:equivalentClass [ owl:intersectionOf ( :A :B ) ] . "
                       ":a a :A, :B .", True, ("a", "S")),
    # read wherever they stand: a subclass side, a type, a range, nested in a typed expression
    "subclass_untyped": (f"{_SOME} rdfs:subClassOf :S . :a :p :b . :b a :A .", True, ("a", "S")),
    "type_untyped": (":a a [ owl:onProperty :p ; owl:allValuesFrom :A ] ; :p :b .", True, ("b", "A")),
    "range_untyped": (":p rdfs:range [ owl:intersectionOf ( :A :B ) ] . :a :p :b .", True, ("b", "B")),
    "nested_filler": (":S a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; "
                      "owl:someValuesFrom [ owl:intersectionOf ( :A :B ) ] ] . :a :p :b . :b a :A, :B .", True, ("a", "S")),
    "nested_member": (":U a owl:Class ; owl:equivalentClass [ a owl:Class ; owl:unionOf ( :A "
                      "[ owl:onProperty :p ; owl:hasValue :c ] ) ] . :a :p :c .", True, ("a", "U")),
    # never read as a domain
    "domain_untyped": (":q a owl:ObjectProperty ; rdfs:domain [ owl:intersectionOf ( :A :B ) ] . :a :q :b .",
                       False, ("a", "A")),
    "domain_typed": (":q a owl:ObjectProperty ; rdfs:domain [ a owl:Class ; owl:intersectionOf ( :A :B ) ] . "
                     ":a :q :b .", True, ("a", "A")),
    # data ranges: typed rdfs:Datatype, or the definition of a declared datatype
    "data_filler_untyped": (f":S a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :dp ; "
                            f"owl:someValuesFrom [ {_FACETS} ] ] . :a :dp 15 .", False, ("a", "S")),
    "data_filler_typed": (f":S a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :dp ; "
                          f"owl:someValuesFrom [ a rdfs:Datatype ; {_FACETS} ] ] . :a :dp 15 .", True, ("a", "S")),
    "data_filler_owl1": (f":S a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :dp ; "
                         f"owl:someValuesFrom [ a owl:DataRange ; {_FACETS} ] ] . :a :dp 15 .", True, ("a", "S")),
    "data_definition_declared": (f":Big a rdfs:Datatype ; owl:equivalentClass [ {_FACETS} ] . "
                                 ":S a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :dp ; "
                                 "owl:someValuesFrom :Big ] . :a :dp 15 .", True, ("a", "S")),
    "data_definition_undeclared": (f":Big owl:equivalentClass [ {_FACETS} ] . "
                                   ":S a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :dp ; "
                                   "owl:someValuesFrom :Big ] . :a :dp 15 .", False, ("a", "S")),
}

_SHARED = """:a a owl:NamedIndividual . :b a owl:NamedIndividual . :c a owl:NamedIndividual . :d a owl:NamedIndividual .
:p a owl:ObjectProperty . :dp a owl:DatatypeProperty . :A a owl:Class . :B a owl:Class .
"""


#: cases the OWL API reads and topostore sets aside with its notice: a name known as a class only because an
#: individual has it as a type (the OWL API's parser counts that; topostore reads the schema from schema
#: triples alone, so that an ABox type added or removed later cannot change which axioms there are)
SET_ASIDE_HERE = frozenset({"eq_used_as_type"})


def read_here(name: str) -> bool:
    """Whether topostore reads the axiom of case ``name`` (as the OWL API does, but for :data:`SET_ASIDE_HERE`)."""
    return CASES[name][1] and name not in SET_ASIDE_HERE


def namespace(name: str) -> str:
    return f"{BASE}{name}#"


def document(name: str) -> str:
    """The Turtle of case ``name``, prefixes and shared declarations included."""
    return (f"@prefix : <{namespace(name)}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
            "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . "
            "@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .\n" + _SHARED + CASES[name][0] + "\n")
