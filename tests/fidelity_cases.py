"""Small ontologies beyond the tutorial's OWL, each in its own namespace, that the fidelity tests load along
several paths (tests/test_fidelity.py) and give Pellet (tests/test_fidelity_pellet.py).

Each case is Turtle with ``:`` bound to its namespace; :func:`document` adds the prefixes.  The cases are
consistent and fully reasoned by topostore (no notice), so every answer Pellet gives is one topostore must
give: inverse, symmetric and transitive properties, chains, sameAs chains, hasValue, keys, qualified
cardinalities with AllDifferent groups, datatype restrictions, punning, self restrictions, negative
property assertions, literal forms, xsd:dateTimeStamp, strings of the types derived from xsd:string (one value
with the plain string), datatypes topostore does not check (a user's own, xsd:token), the domain
of an existential's subject through inverse, sub-, equivalent and symmetric properties, inverse-functional
properties merging their subjects (a functional object property's values Owlready2 reports as one).
"""

from __future__ import annotations

BASE = "http://example.org/fidelity/"

CASES: dict[str, str] = {
    "properties": """
:p a owl:ObjectProperty ; owl:inverseOf :q . :q a owl:ObjectProperty .
:s a owl:ObjectProperty, owl:SymmetricProperty . :t a owl:ObjectProperty, owl:TransitiveProperty .
:ts a owl:ObjectProperty ; rdfs:subPropertyOf :t .
:a :p :b ; :s :c ; :t :b . :b :t :c . :c :t :d . :d :ts :e .
:a a owl:NamedIndividual . :b a owl:NamedIndividual . :c a owl:NamedIndividual . :d a owl:NamedIndividual .
:e a owl:NamedIndividual .
""",
    "chains": """
:hasParent a owl:ObjectProperty . :hasBrother a owl:ObjectProperty .
:hasUncle a owl:ObjectProperty ; owl:propertyChainAxiom ( :hasParent :hasBrother ) .
:greatGrandParent a owl:ObjectProperty ; owl:propertyChainAxiom ( :hasParent :hasParent :hasParent ) .
:sibling a owl:ObjectProperty ; owl:propertyChainAxiom ( :hasParent [ owl:inverseOf :hasParent ] ) .
:a :hasParent :b . :b :hasBrother :c ; :hasParent :x . :x :hasParent :y . :z :hasParent :b .
:a a owl:NamedIndividual . :b a owl:NamedIndividual . :c a owl:NamedIndividual . :x a owl:NamedIndividual .
:y a owl:NamedIndividual . :z a owl:NamedIndividual .
""",
    "same_as_chain": """
:A a owl:Class . :p a owl:ObjectProperty . :d a owl:DatatypeProperty .
:a a owl:NamedIndividual, :A ; owl:sameAs :b . :b a owl:NamedIndividual ; owl:sameAs :c .
:c a owl:NamedIndividual ; :p :z ; :d 5 . :z a owl:NamedIndividual . :e a owl:NamedIndividual ; owl:differentFrom :a .
""",
    "has_value": """
:p a owl:ObjectProperty . :d a owl:DatatypeProperty .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :v ] .
:D owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:hasValue "3"^^xsd:integer ] .
:v a owl:NamedIndividual . :a a owl:NamedIndividual ; :p :v . :b a owl:NamedIndividual, :C .
:c a owl:NamedIndividual ; :d "03"^^xsd:integer . :e a owl:NamedIndividual, :D . :f a owl:NamedIndividual ; :d "3"^^xsd:long .
""",
    "keys": """
:Person a owl:Class ; owl:hasKey ( :ssn ) . :ssn a owl:DatatypeProperty . :p a owl:ObjectProperty .
:a a owl:NamedIndividual, :Person ; :ssn "1"^^xsd:integer ; :p :o . :o a owl:NamedIndividual .
:b a owl:NamedIndividual, :Person ; :ssn "1.0"^^xsd:decimal . :c a owl:NamedIndividual, :Person ; :ssn "01"^^xsd:byte .
:e a owl:NamedIndividual, :Person ; :ssn "2"^^xsd:integer .
""",
    "cardinalities": """
:p a owl:ObjectProperty . :F a owl:Class .
:Three owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ;
    owl:minQualifiedCardinality "3"^^xsd:nonNegativeInteger ; owl:onClass :F ] .
:Two owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ;
    owl:minQualifiedCardinality "2"^^xsd:nonNegativeInteger ; owl:onClass :F ] .
:a a owl:NamedIndividual ; :p :f1, :f2, :f3, :f4 . :f1 a :F . :f2 a :F . :f3 a :F . :f4 a owl:NamedIndividual .
[] a owl:AllDifferent ; owl:distinctMembers ( :f1 :f2 :f3 :f4 ) .
:b a owl:NamedIndividual ; :p :g1, :g2, :g3 . :g1 a :F . :g2 a :F . :g3 a :F .
:g1 owl:differentFrom :g2 . :g2 owl:differentFrom :g3 . :g1 owl:differentFrom :g3 .
:c a owl:NamedIndividual ; :p :h1, :h2, :h3 . :h1 a :F . :h2 a :F . :h3 a :F .
[] a owl:AllDifferent ; owl:distinctMembers ( :h1 :h2 ) . [] a owl:AllDifferent ; owl:distinctMembers ( :h2 :h3 ) .
[] a owl:AllDifferent ; owl:distinctMembers ( :h1 :h3 ) .
:e a owl:NamedIndividual ; :p :k1, :k2 . :k1 a :F . :k2 a :F .
:d a owl:NamedIndividual ; :p :m1, :m2 . :m1 a :F . :m2 a :F . :m3 a owl:NamedIndividual . :m4 a owl:NamedIndividual .
[] a owl:AllDifferent ; owl:members ( :m1 :m3 ) ; owl:distinctMembers ( :m2 :m4 ) .
""",
    "maximum_merges": """
:p a owl:ObjectProperty . :q a owl:ObjectProperty .
:M rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:maxCardinality "1"^^xsd:nonNegativeInteger ] .
:a a owl:NamedIndividual, :M ; :p :u, :v . :u a owl:NamedIndividual . :v a owl:NamedIndividual ; :q :w .
:w a owl:NamedIndividual .
""",
    "datatype_restrictions": """
:age a owl:DatatypeProperty .
:Adult owl:equivalentClass [ a owl:Restriction ; owl:onProperty :age ; owl:someValuesFrom [ a rdfs:Datatype ;
    owl:onDatatype xsd:integer ; owl:withRestrictions ( [ xsd:minInclusive 18 ] ) ] ] .
:Teen owl:equivalentClass [ a owl:Restriction ; owl:onProperty :age ; owl:someValuesFrom [ a rdfs:Datatype ;
    owl:onDatatype xsd:integer ; owl:withRestrictions ( [ xsd:minInclusive 13 ] [ xsd:maxExclusive 20 ] ) ] ] .
:a a owl:NamedIndividual ; :age 18 . :b a owl:NamedIndividual ; :age "17"^^xsd:long .
:c a owl:NamedIndividual ; :age "19.0"^^xsd:decimal . :e a owl:NamedIndividual ; :age "20"^^xsd:short .
""",
    "punning_and_self": """
:Eagle a owl:Class, owl:NamedIndividual ; :status :Endangered . :status a owl:ObjectProperty .
:Endangered a owl:NamedIndividual . :Bird a owl:Class . :Eagle rdfs:subClassOf :Bird . :e1 a :Eagle .
:likes a owl:ObjectProperty . :Narcissist owl:equivalentClass [ a owl:Restriction ; owl:onProperty :likes ;
    owl:hasSelf true ] .
:n1 a owl:NamedIndividual ; :likes :n1 . :n2 a owl:NamedIndividual ; :likes :n1 .
""",
    "inverse_restrictions": """
:p a owl:ObjectProperty . :q a owl:ObjectProperty ; owl:inverseOf :p . :D a owl:Class .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty [ owl:inverseOf :p ] ; owl:someValuesFrom :D ] .
:A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :D ] .
:x a :D ; :p :y . :y a owl:NamedIndividual . :z a owl:NamedIndividual ; :q :x . :u a :A ; :p :w .
:w a owl:NamedIndividual .
""",
    "values_by_value": """
:d a owl:DatatypeProperty . :k a owl:DatatypeProperty .
:Three owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:hasValue "3"^^xsd:integer ] .
:Half owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:hasValue "0.50"^^xsd:decimal ] .
:Noon owl:equivalentClass [ a owl:Restriction ; owl:onProperty :k ;
    owl:hasValue "2020-01-01T12:00:00Z"^^xsd:dateTime ] .
:x a owl:NamedIndividual ; :d "3.0"^^xsd:decimal . :y a owl:NamedIndividual ; :d "3"^^xsd:long .
:z a owl:NamedIndividual ; :d ".5"^^xsd:decimal . :w a owl:NamedIndividual ; :d "3"^^xsd:string .
:u a owl:NamedIndividual ; :k "2020-01-01T14:00:00+02:00"^^xsd:dateTime .
:v a owl:NamedIndividual ; :k "2020-01-01T12:00:00"^^xsd:dateTime .
""",
    # xsd:dateTimeStamp is an xsd:dateTime with a time zone (the store keeps it as an xsd:dateTime)
    "date_time_stamps": """
:t a owl:DatatypeProperty ; rdfs:range xsd:dateTimeStamp . :u a owl:DatatypeProperty .
:Stamped owl:equivalentClass [ a owl:Restriction ; owl:onProperty :u ; owl:someValuesFrom xsd:dateTimeStamp ] .
:Only rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :u ; owl:allValuesFrom xsd:dateTimeStamp ] .
:c a owl:NamedIndividual ; :t "2021-05-01T00:00:00Z"^^xsd:dateTimeStamp ; :u "2021-05-01T00:00:00Z"^^xsd:dateTimeStamp .
:e a owl:NamedIndividual, :Only ; :t "2019-05-01T00:00:00+02:00"^^xsd:dateTime ; :u "2019-05-01T00:00:00Z"^^xsd:dateTime .
:n a owl:NamedIndividual ; :u "2019-05-01T00:00:00+01:00"^^xsd:dateTime .
""",
    # the value spaces of xsd:string's derived types are subsets of its own: "a"^^xsd:token is the string "a"
    "derived_strings": """
:t a owl:DatatypeProperty . :d a owl:DatatypeProperty . :m a owl:ObjectProperty .
:A owl:equivalentClass [ a owl:Restriction ; owl:onProperty :t ; owl:hasValue "a" ] .
:Two owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:minCardinality "2"^^xsd:nonNegativeInteger ] .
:Four owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:minCardinality "4"^^xsd:nonNegativeInteger ] .
:K a owl:Class ; owl:hasKey ( :t ) .
:x a owl:NamedIndividual, :K ; :t "a"^^xsd:token ; :m :x1 . :y a owl:NamedIndividual ; :t "a"^^xsd:normalizedString .
:w a owl:NamedIndividual, :K ; :t "a" ; :m :w1 . :x1 a owl:NamedIndividual . :w1 a owl:NamedIndividual .
:z a owl:NamedIndividual ; :d "a", "a"^^xsd:token, "a"^^xsd:Name . :z2 a owl:NamedIndividual ; :d "a", "b"^^xsd:NCName .
:z4 a owl:NamedIndividual ; :d "a", "a"^^xsd:token, "a"^^xsd:Name, "b", "b"^^xsd:language, "c"^^xsd:NCName .
:z5 a owl:NamedIndividual ; :d "a", "a"^^xsd:token, "b"^^xsd:normalizedString, "c", "d"^^xsd:language .
""",
    "datatypes_not_checked": """
:d a owl:DatatypeProperty . :Small a rdfs:Datatype .
:SomeSmall owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom :Small ] .
:SomeToken owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom xsd:token ] .
:x a owl:NamedIndividual ; :d 9 . :y a owl:NamedIndividual ; :d "hello" . :z a owl:NamedIndividual ; :d "ab"^^xsd:token .
""",
    "property_hierarchy": """
:F a owl:Class . :G a owl:Class . :H a owl:Class . :K a owl:Class . :M a owl:Class . :N a owl:Class .
:D a owl:Class . :S a owl:Class . :U a owl:Class . :V a owl:Class . :W a owl:Class . :X a owl:Class .
:q a owl:ObjectProperty . :p a owl:ObjectProperty ; rdfs:domain :F ; owl:inverseOf :q ; rdfs:subPropertyOf :q .
:D owl:equivalentClass [ a owl:Restriction ; owl:onProperty :q ; owl:minQualifiedCardinality "2"^^xsd:nonNegativeInteger ;
    owl:onClass :D ] .
:i3 a owl:NamedIndividual, :D .
:r a owl:ObjectProperty ; rdfs:range :G . :ri a owl:ObjectProperty ; owl:inverseOf :r .
:S rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :ri ; owl:someValuesFrom owl:Thing ] . :s1 a owl:NamedIndividual, :S .
:top a owl:ObjectProperty ; rdfs:domain :H . :mid a owl:ObjectProperty ; rdfs:subPropertyOf :top .
:U rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :mid ; owl:someValuesFrom :F ] . :u1 a owl:NamedIndividual, :U .
:low a owl:ObjectProperty ; rdfs:subPropertyOf [ owl:inverseOf :up ] . :up a owl:ObjectProperty ; rdfs:range :K .
:V rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :low ; owl:someValuesFrom owl:Thing ] . :v1 a owl:NamedIndividual, :V .
:sym a owl:ObjectProperty, owl:SymmetricProperty ; rdfs:range :M .
:W rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :sym ; owl:minCardinality "1"^^xsd:nonNegativeInteger ] .
:w1 a owl:NamedIndividual, :W .
:dd a owl:DatatypeProperty ; rdfs:domain :N . :de a owl:DatatypeProperty ; owl:equivalentProperty :dd .
:X rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :de ; owl:someValuesFrom xsd:integer ] . :x1 a owl:NamedIndividual, :X .
""",
    "functional_properties": """
:g a owl:ObjectProperty, owl:InverseFunctionalProperty . :q a owl:ObjectProperty . :C a owl:Class .
:d a owl:DatatypeProperty, owl:FunctionalProperty .
:m a owl:NamedIndividual, :C ; :g :o ; :d 5 . :n a owl:NamedIndividual ; :g :o ; :q :w . :o a owl:NamedIndividual .
:w a owl:NamedIndividual ; :g :z ; :d 5 . :z a owl:NamedIndividual . :k a owl:NamedIndividual ; :g :z ; :q :m .
""",
    # a one-of of a single individual: its instance is that individual (x ∈ {b} ⇒ x sameAs b), by a type, a
    # range, a universal, a named class defined as {b}, and a subclass of a one-of of one individual twice
    "single_individual_one_of": """
:p a owl:ObjectProperty . :r a owl:ObjectProperty ; rdfs:range [ a owl:Class ; owl:oneOf ( :e ) ] .
:C a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom [ a owl:Class ; owl:oneOf ( :b ) ] ] .
:B a owl:Class ; owl:oneOf ( :b ) . :D a owl:Class ; rdfs:subClassOf [ a owl:Class ; owl:oneOf ( :h :h ) ] .
:a a owl:NamedIndividual, :C ; :p :c . :b a owl:NamedIndividual . :c a owl:NamedIndividual ; :r :f .
:e a owl:NamedIndividual . :f a owl:NamedIndividual . :g a owl:NamedIndividual, :B ; :p :e .
:h a owl:NamedIndividual . :k a owl:NamedIndividual, :D, [ a owl:Class ; owl:oneOf ( :m ) ] ; :p :a . :m a owl:NamedIndividual .
""",
    # an existential into a one-of of one individual (a one-of of one literal) is a hasValue: ∃p.{b} ≡ p value b,
    # on the sub and the super side, in an equivalence, inside an intersection, a union and another existential,
    # on an inverse (∃p⁻.{g} ⇒ p(g, x)), into a named class told to be {e}, as a qualified minimum of one, and for
    # a data property (∃d.{"v"} ≡ d value "v")
    "existential_into_a_single_individual_one_of": """
:p a owl:ObjectProperty . :q a owl:ObjectProperty . :r a owl:ObjectProperty . :d a owl:DatatypeProperty .
:C a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom [ a owl:Class ; owl:oneOf ( :b ) ] ] .
:E a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom [ a owl:Class ; owl:oneOf ( :b ) ] ] .
:F a owl:Class ; owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :C [ a owl:Restriction ;
  owl:onProperty [ owl:inverseOf :p ] ; owl:someValuesFrom [ a owl:Class ; owl:oneOf ( :g ) ] ] ) ] .
:G a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty [ owl:inverseOf :q ] ;
  owl:someValuesFrom [ a owl:Class ; owl:oneOf ( :h ) ] ] .
:H a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom [ a owl:Restriction ;
  owl:onProperty :q ; owl:someValuesFrom [ a owl:Class ; owl:oneOf ( :b :b ) ] ] ] .
:M a owl:Class . [ a owl:Class ; owl:unionOf ( [ a owl:Restriction ; owl:onProperty :r ; owl:someValuesFrom
  [ a owl:Class ; owl:oneOf ( :e ) ] ] :G ) ] rdfs:subClassOf :M .
:K a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom [ a rdfs:Datatype ; owl:oneOf ( "v" ) ] ] .
:N a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ;
  owl:someValuesFrom [ a rdfs:Datatype ; owl:oneOf ( "v" ) ] ] .
:B a owl:Class ; owl:equivalentClass [ a owl:Class ; owl:oneOf ( :e ) ] . :P a owl:Class ; rdfs:subClassOf [ a owl:Restriction ;
  owl:onProperty :q ; owl:someValuesFrom :B ] , [ a owl:Restriction ; owl:onProperty :r ;
  owl:minQualifiedCardinality "1"^^xsd:nonNegativeInteger ; owl:onClass [ a owl:Class ; owl:oneOf ( :h ) ] ] .
:t a owl:NamedIndividual, :P .
:a a owl:NamedIndividual, :C . :b a owl:NamedIndividual . :c a owl:NamedIndividual ; :q :b . :e a owl:NamedIndividual .
:g a owl:NamedIndividual ; :p :m . :h a owl:NamedIndividual . :k a owl:NamedIndividual, :G . :m a owl:NamedIndividual, :C .
:n a owl:NamedIndividual ; :p :c . :s a owl:NamedIndividual ; :r :e . :x a owl:NamedIndividual, :K . :y a owl:NamedIndividual ; :d "v" .
""",
    # a property under a functional one (sub-, equivalent, inverse of an inverse-functional) has at most one
    # value, so exactly one is known from one; a functional property's super-property has no maximum
    "functional_super_properties": """
:p a owl:ObjectProperty, owl:FunctionalProperty . :q a owl:ObjectProperty ; rdfs:subPropertyOf :p . :D a owl:Class .
:r a owl:ObjectProperty . :p rdfs:subPropertyOf :r .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :q ; owl:qualifiedCardinality "1"^^xsd:nonNegativeInteger ;
    owl:onClass :D ] .
:R owl:equivalentClass [ a owl:Restriction ; owl:onProperty :r ; owl:qualifiedCardinality "1"^^xsd:nonNegativeInteger ;
    owl:onClass :D ] .
:e a owl:DatatypeProperty, owl:FunctionalProperty . :d a owl:DatatypeProperty ; rdfs:subPropertyOf :e .
:CD owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:qualifiedCardinality "1"^^xsd:nonNegativeInteger ;
    owl:onDataRange xsd:integer ] .
:f a owl:ObjectProperty, owl:FunctionalProperty . :g a owl:ObjectProperty ; owl:equivalentProperty :f .
:CE owl:equivalentClass [ a owl:Restriction ; owl:onProperty :g ; owl:qualifiedCardinality "1"^^xsd:nonNegativeInteger ;
    owl:onClass :D ] .
:h a owl:ObjectProperty, owl:FunctionalProperty . :hi a owl:ObjectProperty ; owl:inverseOf :h .
:CI owl:equivalentClass [ a owl:Restriction ; owl:onProperty [ owl:inverseOf :hi ] ;
    owl:qualifiedCardinality "1"^^xsd:nonNegativeInteger ; owl:onClass :D ] .
:a a owl:NamedIndividual ; :q :b . :b a owl:NamedIndividual, :D . :c a owl:NamedIndividual ; :d 5 .
:k a owl:NamedIndividual ; :g :b . :m a owl:NamedIndividual ; :h :b . :n a owl:NamedIndividual ; :r :b .
""",
    # data ranges built of others (compile/data_ranges.py): a one-of of literals (named by a datatype definition, or
    # written in the restriction), a complement, a union, an intersection, as an existential's and a qualified
    # minimum's filler, a range and a universal's filler; a value matched by value ("1"^^xsd:int, 1.0 in {1, 2, 3};
    # "1.0"^^xsd:float not), "a"@en outside {"a", "b"}
    "data_ranges": """
:d a owl:DatatypeProperty . :r a owl:DatatypeProperty ; rdfs:range [ a rdfs:Datatype ; owl:oneOf ( 1 2 3 "x" ) ] .
:Small a rdfs:Datatype ; owl:equivalentClass [ a rdfs:Datatype ; owl:oneOf ( 1 2 3 ) ] .
:Pick a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom [ a rdfs:Datatype ;
  owl:oneOf ( "a" "b" ) ] ] .
:NotInt a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom [ a rdfs:Datatype ;
  owl:datatypeComplementOf xsd:integer ] ] .
:IntOrBool a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom [ a rdfs:Datatype ;
  owl:unionOf ( xsd:integer xsd:boolean ) ] ] .
:BigSmall a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom [ a rdfs:Datatype ;
  owl:intersectionOf ( :Small [ a rdfs:Datatype ; owl:onDatatype xsd:integer ; owl:withRestrictions ( [ xsd:minInclusive 2 ] ) ] ) ] ] .
:SmallOne a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom :Small ] .
:TwoSmall a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ;
  owl:minQualifiedCardinality "2"^^xsd:nonNegativeInteger ; owl:onDataRange :Small ] .
:NotSmall a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom [ a rdfs:Datatype ;
  owl:datatypeComplementOf :Small ] ] .
:Ranged a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :r ; owl:someValuesFrom xsd:string ] .
:Only a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; owl:allValuesFrom [ a rdfs:Datatype ;
  owl:unionOf ( :Small [ a rdfs:Datatype ; owl:datatypeComplementOf xsd:decimal ] ) ] ] .
:a a owl:NamedIndividual ; :d 1 . :b a owl:NamedIndividual, :Only ; :d "1"^^xsd:int ; :r 2 . :c a owl:NamedIndividual ; :d "a" .
:e a owl:NamedIndividual, :Only ; :d true . :f a owl:NamedIndividual ; :d 2.5 .
:g a owl:NamedIndividual ; :d "b"^^xsd:string , 3, "2"^^xsd:long ; :r "x" . :h a owl:NamedIndividual ; :d "1.0"^^xsd:decimal .
:i a owl:NamedIndividual ; :d "1.0"^^xsd:float . :j a owl:NamedIndividual ; :d "a"@en .
""",
}


def namespace(name: str) -> str:
    return f"{BASE}{name}#"


def document(name: str, body: str | None = None) -> str:
    """The Turtle of case ``name`` (or of ``body`` in that case's namespace), prefixes included."""
    return (f"@prefix : <{namespace(name)}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
            "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . "
            "@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .\n" + (CASES[name] if body is None else body))


def random_horn(seed: int, ns: str) -> str:
    """A small random ontology of namespace ``ns`` (N-Triples-style IRIs, no prefix needed): four properties
    linked by inverses, sub-, equivalent and symmetric properties, domains and ranges, a chain, existential,
    minimum, hasValue and self restrictions, a few facts.  Horn, so consistent, and OWL 2 DL (the chain's
    property has a fresh super-property).  Left out, as Pellet 2.3.1 answers them wrongly (tests of
    tests/test_fidelity_pellet.py show it): a self restriction used as a subclass, a domain on a chain."""
    import random

    rng = random.Random(seed)
    props = [f"<{ns}p{i}>" for i in range(4)]
    classes = [f"<{ns}A{i}>" for i in range(4)]
    names = [f"<{ns}i{i}>" for i in range(4)]
    out = [f"{p} a owl:ObjectProperty ." for p in props] + [f"{c} a owl:Class ." for c in classes]
    out += [f"{i} a owl:NamedIndividual ." for i in names]

    def prop() -> str:
        p = rng.choice(props)
        return f"[ owl:inverseOf {p} ]" if rng.random() < 0.2 else p

    def restriction(left: bool) -> str:
        k = rng.random()
        if k < 0.6:
            return f"[ a owl:Restriction ; owl:onProperty {prop()} ; owl:someValuesFrom {rng.choice(classes)} ]"
        if k < 0.7 and not left:
            return f"[ a owl:Restriction ; owl:onProperty {rng.choice(props)} ; owl:hasSelf true ]"
        if k < 0.85:
            return f"[ a owl:Restriction ; owl:onProperty {prop()} ; owl:hasValue {rng.choice(names)} ]"
        return (f"[ a owl:Restriction ; owl:onProperty {rng.choice(props)} ; owl:minQualifiedCardinality "
                f"\"1\"^^xsd:nonNegativeInteger ; owl:onClass {rng.choice(classes)} ]")

    chain = False
    for _ in range(rng.randint(3, 7)):
        k = rng.random()
        a, b = rng.sample(props, 2)
        if k < 0.15:
            out.append(f"{a} owl:inverseOf {b} .")
        elif k < 0.4:
            out.append(f"{a} rdfs:subPropertyOf {b} .")
        elif k < 0.47:
            out.append(f"{a} owl:equivalentProperty {b} .")
        elif k < 0.55:
            out.append(f"{a} a owl:SymmetricProperty .")
        elif k < 0.72:
            out.append(f"{a} rdfs:domain {rng.choice(classes)} .")
        elif k < 0.88:
            out.append(f"{a} rdfs:range {rng.choice(classes)} .")
        elif not chain:
            chain = True
            out.append(f"<{ns}c0> a owl:ObjectProperty ; owl:propertyChainAxiom ( {a} {b} ) ; "
                       f"rdfs:subPropertyOf <{ns}top> . <{ns}top> a owl:ObjectProperty .")
    for _ in range(rng.randint(2, 5)):
        c = rng.choice(classes)
        if rng.random() < 0.4:
            out.append(f"{c} owl:equivalentClass {restriction(True)} .")
        elif rng.random() < 0.5:
            out.append(f"{c} rdfs:subClassOf {restriction(False)} .")
        else:
            out.append(f"{restriction(True)} rdfs:subClassOf {c} .")
    for _ in range(rng.randint(2, 6)):
        if rng.random() < 0.5:
            out.append(f"{rng.choice(names)} a {rng.choice(classes)} .")
        else:
            out.append(f"{rng.choice(names)} {rng.choice(props)} {rng.choice(names)} .")
    return "\n".join(out) + "\n"
