"""Vocabulary constants shared by every layer.

Kept in one module so that no other module spells an IRI by hand: a typo in a
namespace would silently make a rule never fire.
"""

from __future__ import annotations

from pyoxigraph import NamedNode

RDF = "http://www.w3.org/1999/02/22-rdf-syntax-ns#"
RDFS = "http://www.w3.org/2000/01/rdf-schema#"
OWL = "http://www.w3.org/2002/07/owl#"
XSD = "http://www.w3.org/2001/XMLSchema#"
SWRL = "http://www.w3.org/2003/11/swrl#"
SWRLB = "http://www.w3.org/2003/11/swrlb#"
SWRLA = "http://swrl.stanford.edu/ontologies/3.3/swrla.owl#"
#: Protégé's SWRL namespaces (swrla, swrlx, ...) all start here; they describe rules, not facts.
STANFORD_SWRL = "http://swrl.stanford.edu/"
#: SWRLTab's SQWRL built-ins (``.../3.4/sqwrl.owl#select``) live under this prefix.
SQWRL_PREFIX = "http://sqwrl.stanford.edu/ontologies/built-ins/"
XML = "http://www.w3.org/XML/1998/namespace"
#: The namespaces of the SPARQL 1.1 Service Description (http/description.py).
SD = "http://www.w3.org/ns/sparql-service-description#"
VOID = "http://rdfs.org/ns/void#"
FORMATS = "http://www.w3.org/ns/formats/"
#: Namespace of the example topological map (ontology/, mapgen.py).
MAP_NS = "http://bnc/exp-rob-lab/2022-23#"
#: Namespace of SWRL variables written in Protégé's text syntax (compile/swrl_text.py).
SWRL_VARIABLE_NS = "urn:swrl:var#"

#: Namespace of every IRI topostore invents (graphs, anonymous class ids, helper
#: predicates).  Nothing in this namespace is ever shown to a user as a class.
INTERNAL = "urn:topostore:"

#: Graph holding the facts users asserted (loaded files and manipulations).
ASSERTED = NamedNode(INTERNAL + "graph:asserted")
#: Graph holding the entailed facts users may see (types, property values, sameAs).
INFERRED = NamedNode(INTERNAL + "graph:inferred")
#: Graph holding helper facts of the reasoner (membership of anonymous class
#: expressions, membership of AllDifferent groups); never shown to users.
AUX = NamedNode(INTERNAL + "graph:aux")
#: Scratch graphs of the fixpoint loop.
DELTA = NamedNode(INTERNAL + "graph:delta")
NEW_INFERRED = NamedNode(INTERNAL + "graph:new-inferred")
NEW_AUX = NamedNode(INTERNAL + "graph:new-aux")
#: Prefix of the graphs holding the schema rows a full REASON's generic OWL rules join (``rules/owl/``),
#: one graph per rule (``graph:schema:cax-sco``), written for that run only.
SCHEMA_PREFIX = INTERNAL + "graph:schema:"

#: aux predicate indexing owl:AllDifferent axioms in linear size (never n²
#: pairs): member ``m`` of member list ``g`` of an AllDifferent node gets ``k ts:differentKeyOf m`` with
#: ``k = urn:topostore:key:<md5(g)>:<md5(m)>`` (the group is the list: a node with two lists is two
#: groups, as OWL 2 RL's eq-diff2/eq-diff3 read them), or ``k = m`` where the asserted graph holds one
#: member list (compile/key_form.py: its group part is empty for every key); two individuals holding
#: different keys with the same group part are declared different.  The key is the
#: subject and the individual the object: a join looks the key up from the individual,
#: and the store walks a term's quads to do so, which an individual has far fewer of as an
#: object than as a subject (the connecting rule's join at 100,000 locations 1.56 -> 1.02 s,
#: docs/benchmarks-history.md).
DIFFERENT_KEY_OF = NamedNode(INTERNAL + "differentKeyOf")
#: the same index written the other way (``m ts:differentKey k``) by earlier versions: a durable
#: store whose helper graph still holds it is rebuilt when it is opened (ontology/state.py)
LEGACY_DIFFERENT_KEY = NamedNode(INTERNAL + "differentKey")
#: aux predicates of the difference check.  A rule that needs "a and b are
#: different" first derives ``a ts:differenceCandidate b`` for the pairs its body
#: can produce; generic rules then derive ``a ts:different b`` for the candidates
#: that are different (same AllDifferent group, owl:differentFrom, disjoint
#: classes).  Both are plain joins, so difference costs no more than the pairs
#: that are actually asked about.
DIFFERENCE_CANDIDATE = NamedNode(INTERNAL + "differenceCandidate")
#: plainly different: declared (one owl:AllDifferent, owl:differentFrom) or members
#: of disjoint classes; what a SWRL DifferentFrom atom fires rules on, as in Pellet
DECLARED_DIFFERENT = NamedNode(INTERNAL + "declaredDifferent")
#: entailed different: plainly different, or equality would be inconsistent (two
#: distinct values of a property allowing at most one)
DIFFERENT = NamedNode(INTERNAL + "different")

#: Conclusions of SWRL rules whose DifferentIndividuals atom holds only by
#: entailment (not by declaration nor by disjoint classes).  A tableau reasoner such as Pellet reports
#: them (they are entailed) but, having found them by refutation, never uses
#: them to fire other rules; topostore derives them in the helper graph under
#: ``ENTAILED_PREFIX + predicate`` so that no rule reads them, and publishes
#: them in the ENTAILED graph that queries see.
ENTAILED_PREFIX = INTERNAL + "entailed:"
ENTAILED = NamedNode(INTERNAL + "graph:entailed")
#: Prefix of the ids given to anonymous class expressions.
EXPR_PREFIX = INTERNAL + "expr:"
#: Blank nodes are skolemised on load to IRIs under this prefix (stores/base.py): the rule
#: compiler must name class expressions and SWRL atoms inside SPARQL text.
SKOLEM_PREFIX = INTERNAL + "bnode:"
#: Prefix of the AllDifferent membership keys (see DIFFERENT_KEY_OF).
KEY_PREFIX = INTERNAL + "key:"
#: how the one-list AllDifferent key rule's file names its list (``rules/one-list/all-different-key.rq``),
#: replaced by the asserted graph's one member list when the rule is compiled (``compile/key_form.py``)
ONE_MEMBER_LIST = NamedNode(INTERNAL + "the-one-member-list")
#: Prefix of topostore's SPARQL extension functions; user SPARQL may not call them.
FUNCTION_PREFIX = INTERNAL + "fn:"
#: swrlb:pow with a non-constant exponent (SPARQL 1.1 has no power function).
POW_FUNCTION = NamedNode(FUNCTION_PREFIX + "pow")
#: Prototype individuals of classification (reason/classify.py), one per class.
PROTOTYPE_PREFIX = INTERNAL + "prototype:"
#: Entity namespace of an ontology that declares no owl:Ontology IRI.
DEFAULT_PREFIX = INTERNAL + "default#"
#: Placeholder subject and predicate for parsing one RDF term as an N-Triples line.
PLACEHOLDER_SUBJECT = NamedNode(INTERNAL + "placeholder:s")
PLACEHOLDER_PREDICATE = NamedNode(INTERNAL + "placeholder:p")


def rdf(name: str) -> NamedNode:
    return NamedNode(RDF + name)


def rdfs(name: str) -> NamedNode:
    return NamedNode(RDFS + name)


def owl(name: str) -> NamedNode:
    return NamedNode(OWL + name)


def xsd(name: str) -> NamedNode:
    return NamedNode(XSD + name)


def swrl(name: str) -> NamedNode:
    return NamedNode(SWRL + name)


TYPE = rdf("type")
FIRST = rdf("first")
REST = rdf("rest")
NIL = rdf("nil")
SAME_AS = owl("sameAs")
DIFFERENT_FROM = owl("differentFrom")
THING = owl("Thing")
NOTHING = owl("Nothing")
NAMED_INDIVIDUAL = owl("NamedIndividual")
HAS_VALUE = owl("hasValue")

#: The annotation properties OWL 2 builds in: an axiom about one (a domain, a range, a super-property) and an
#: assertion of one have no logical meaning, as for a declared owl:AnnotationProperty.
BUILTIN_ANNOTATION_PROPERTIES = frozenset(
    [rdfs(n) for n in ("label", "comment", "seeAlso", "isDefinedBy")]
    + [owl(n) for n in ("versionInfo", "priorVersion", "backwardCompatibleWith", "incompatibleWith", "deprecated")])

#: Types that say what kind of entity a node is, not which class it belongs to.
DECLARATION_TYPES = frozenset(
    OWL + n
    for n in (
        "Class", "ObjectProperty", "DatatypeProperty", "AnnotationProperty", "NamedIndividual",
        "Ontology", "Restriction", "AllDifferent", "AllDisjointClasses", "AllDisjointProperties",
        "FunctionalProperty", "InverseFunctionalProperty", "TransitiveProperty", "SymmetricProperty",
        "AsymmetricProperty", "ReflexiveProperty", "IrreflexiveProperty", "NegativePropertyAssertion",
        "Axiom", "DeprecatedClass", "DeprecatedProperty", "OntologyProperty", "Thing",
    )
) | frozenset({RDFS + "Class", RDFS + "Datatype", RDF + "Property", RDF + "List"}) | frozenset(
    SWRL + n
    for n in (
        "Imp", "Variable", "AtomList", "ClassAtom", "IndividualPropertyAtom", "DatavaluedPropertyAtom",
        "SameIndividualAtom", "DifferentIndividualsAtom", "DataRangeAtom", "BuiltinAtom", "Builtin",
    )
)


def is_internal(term: object) -> bool:
    """True for IRIs topostore invented; they never leave the library."""
    return isinstance(term, NamedNode) and term.value.startswith(INTERNAL)


def is_skolem(term: object) -> bool:
    """True for a skolemised blank node (a NamedNode, or an IRI string, under SKOLEM_PREFIX)."""
    value = term.value if isinstance(term, NamedNode) else term
    return isinstance(value, str) and value.startswith(SKOLEM_PREFIX)
