"""Editing the RDF list of a TBox axiom (a union's members, a property chain) changes the rules.

Why: the cells of a list (``rdf:first`` / ``rdf:rest``) are the same triples whether the list spells a
union's members or an owl:AllDifferent's individuals, so the predicate alone cannot say which.  A member
replaced, appended or cut must give what reasoning from scratch gives, after an incremental REASON and after
a full one; a map's AllDifferent list edited stays a fact (no recompilation, the incremental path).
"""

from __future__ import annotations

import warnings

import pyoxigraph as ox
import pytest
from pyoxigraph import Triple

from topostore import IncompleteOntologyError, Ontology
from topostore.rdf.vocab import FIRST, NIL, REST, owl

NS = "http://example.org/t#"
PREFIXES = (f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . "
            "@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .\n")
#: a list of three members X1 X2 X3, its cells named so that an edit can name them
LIST = ":l1 rdf:first :X1 ; rdf:rest :l2 . :l2 rdf:first :X2 ; rdf:rest :l3 . :l3 rdf:first :X3 ; rdf:rest rdf:nil ."

#: (the axiom naming :l1, the facts whose conclusions depend on the list's members, the member the edits bring);
#: a rule's body is a list too
AXIOMS = {
    "union": (":U owl:equivalentClass [ a owl:Class ; owl:unionOf :l1 ] .",
              ":a a :X1 . :b a :X2 . :c a :X3 . :d a :Y .", ":Y"),
    "intersection": (":I owl:equivalentClass [ a owl:Class ; owl:intersectionOf :l1 ] .",
                     ":w a :X1 , :X2 , :X3 . :z a :X1 , :X2 , :Y . :v a :X1 , :X2 . :u a :X1 , :X2 , :X3 , :Y .", ":Y"),
    "oneOf": (":O owl:equivalentClass [ a owl:Class ; owl:oneOf :l1 ] . :X1 :tag :t . :Y :tag :t .", "", ":Y"),
    "chain": (":p owl:propertyChainAxiom :l1 . :X1 a owl:ObjectProperty . :X2 a owl:ObjectProperty . "
              ":X3 a owl:ObjectProperty . :Y a owl:ObjectProperty .",
              ":i0 :X1 :i1 . :i1 :X2 :i2 . :i2 :X3 :i3 . :i3 :Y :i4 . :i2 :Y :i5 .", ":Y"),
    "swrl body": ("@prefix swrl: <http://www.w3.org/2003/11/swrl#> . :v a swrl:Variable ."
                  ":r a swrl:Imp ; swrl:body :l1 ; swrl:head ( [ a swrl:ClassAtom ; swrl:classPredicate :H ;"
                  " swrl:argument1 :v ] ) ."
                  + " ".join(f":{atom} a swrl:ClassAtom ; swrl:classPredicate :{cls} ; swrl:argument1 :v ."
                             for atom, cls in (("X1", "P1"), ("X2", "P2"), ("X3", "P3"), ("Y", "P4"))),
                  ":w a :P1 , :P2 , :P3 . :z a :P1 , :P2 , :P4 . :v2 a :P1 , :P2 . :u a :P1 , :P2 , :P3 , :P4 .",
                  ":Y"),
}

#: (removed, added) in one change
EDITS = {
    "replace": (":l3 rdf:first :X3 .", ":l3 rdf:first {new} ."),
    "append": (":l3 rdf:rest rdf:nil .", ":l3 rdf:rest :l4 . :l4 rdf:first {new} ; rdf:rest rdf:nil ."),
    "cut": (":l2 rdf:rest :l3 .", ":l2 rdf:rest rdf:nil ."),
}


def parsed(text: str) -> list[Triple]:
    return [q.triple if hasattr(q, "triple") else q for q in ox.parse(PREFIXES + text, format=ox.RdfFormat.TURTLE)]


def conclusions(onto: Ontology) -> set[tuple[str, str, str]]:
    """The inferred facts between named nodes of the test's namespace (the skolem nodes of the expressions
    are left out: a fresh ontology may name them otherwise)."""
    out = set()
    for t in onto.triples(inferred=True):
        terms = (str(t.subject), str(t.predicate), str(t.object))
        if terms[0].startswith(f"<{NS}") and terms[2].startswith(f"<{NS}"):
            out.add(terms)
    return out


def from_scratch(onto: Ontology) -> set[tuple[str, str, str]]:
    fresh = Ontology()
    fresh.add(*onto.triples())
    fresh.reason(mode="full")
    return conclusions(fresh)


def reasoned(text: str) -> Ontology:
    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        onto.load_data(PREFIXES + text, "turtle")
        onto.reason()
    return onto


@pytest.mark.parametrize("mode", ["auto", "full"])
@pytest.mark.parametrize("edit", sorted(EDITS))
@pytest.mark.parametrize("axiom", sorted(AXIOMS))
def test_a_tbox_list_edited_gives_what_from_scratch_gives(axiom: str, edit: str, mode: str) -> None:
    head, facts, new = AXIOMS[axiom]
    onto = reasoned(f"{head}\n{LIST}\n{facts}")
    before = conclusions(onto)
    removed, added = EDITS[edit]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        onto.change(parsed(added.format(new=new)), parsed(removed))
        onto.reason(mode=mode)
        expected = from_scratch(onto)
    assert expected != before  # the edit matters
    assert conclusions(onto) == expected


def test_a_list_added_and_removed_with_its_axiom_changes_the_rules() -> None:
    """The walk from a cell to its head reads the change itself: the axiom is not in the store yet when a
    load decides, and no longer there once a removal is noted."""
    onto = reasoned(":a a :X1 .")
    axiom = parsed(f"{AXIOMS['union'][0]}\n{LIST}")
    cells = [t for t in axiom if str(t.predicate).endswith("#first>") or str(t.predicate).endswith("#rest>")]
    onto.add(*axiom)
    onto.reason()
    assert (f"<{NS}a>", "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>", f"<{NS}U>") in conclusions(onto)
    onto.rules  # noqa: B018 - compiled
    onto.remove(*cells)
    assert onto._rules is None


def test_an_all_different_list_edited_stays_a_fact() -> None:
    """A map's AllDifferent list (members, cells) is read by the rules, not compiled into them."""
    filler = " ".join(f":e{i} :near :e{i + 1} ." for i in range(200))  # a small change among many facts
    onto = reasoned(f"{filler} :U owl:equivalentClass [ a owl:Class ; owl:unionOf ( :A :B ) ] . :a a :A . :b a :A . :c a :A ."
                    "[] a owl:AllDifferent ; owl:distinctMembers :m1 ."
                    ":m1 rdf:first :a ; rdf:rest :m2 . :m2 rdf:first :b ; rdf:rest rdf:nil .")
    onto.rules  # noqa: B018 - compiled
    onto.change(parsed(":m2 rdf:rest :m3 . :m3 rdf:first :c ; rdf:rest rdf:nil ."), parsed(":m2 rdf:rest rdf:nil ."))
    assert onto._rules is not None
    assert onto.reason().stats.mode == "incremental"
    assert conclusions(onto) == from_scratch(onto)


def test_an_all_disjoint_classes_list_edited_changes_the_rules() -> None:
    onto = reasoned("[] a owl:AllDisjointClasses ; owl:members :m1 ."
                    ":m1 rdf:first :A ; rdf:rest :m2 . :m2 rdf:first :B ; rdf:rest rdf:nil . :x a :A , :C .")
    assert onto.is_consistent
    onto.change(parsed(":m2 rdf:first :C ."), parsed(":m2 rdf:first :B ."))
    assert onto._rules is None
    onto.reason()
    assert not onto.is_consistent


def test_a_document_editing_a_tbox_list_is_compiled_before_it_is_added() -> None:
    """A strict ontology refuses a document whose list cells make an axiom incomplete, and keeps nothing of it."""
    onto = Ontology(strict=True)
    onto.load_data(PREFIXES + "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> ."
                   "[ owl:unionOf :l1 ] rdfs:subClassOf :U . :l1 rdf:first :A ; rdf:rest :l2 ."
                   ":l2 rdf:first :B ; rdf:rest rdf:nil . :a a :A .")
    onto.reason()
    onto.remove(*parsed(":l2 rdf:first :B ."))
    before = set(onto.triples())
    with pytest.raises(IncompleteOntologyError, match="literal"):
        onto.load_data(PREFIXES + ':l2 rdf:first "x" .')
    assert set(onto.triples()) == before


def test_a_union_added_with_blank_nodes_then_cut_changes_the_rules() -> None:
    """Cells a user adds as blank nodes are the skolem IRIs a load gives them; the walk finds them so."""
    onto = reasoned(":a a :X1 . :b a :X2 .")
    head, second = ox.BlankNode(), ox.BlankNode()
    union = ox.NamedNode(NS + "U")
    cells = [Triple(head, FIRST, ox.NamedNode(NS + "X1")), Triple(head, REST, second),
             Triple(second, FIRST, ox.NamedNode(NS + "X2")), Triple(second, REST, NIL)]
    onto.add(Triple(union, owl("equivalentClass"), ox.BlankNode("u")), Triple(ox.BlankNode("u"), owl("unionOf"), head),
             *cells)
    onto.reason()
    onto.rules  # noqa: B018 - compiled
    onto.change([Triple(head, REST, NIL)], [Triple(head, REST, second)])
    assert onto._rules is None
    onto.reason()
    assert conclusions(onto) == from_scratch(onto)


#: a datatype restricted by a facet, read by a class (someValuesFrom) and by a range; its facet node is named
#: so that an edit can name it
FACETED = (PREFIXES + "@prefix xsd: <http://www.w3.org/2001/XMLSchema#> . @prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n"
           ":v a owl:DatatypeProperty . :w a owl:DatatypeProperty ; rdfs:range :small .\n"
           ":small a rdfs:Datatype ; owl:equivalentClass [ a rdfs:Datatype ; owl:onDatatype xsd:integer ;"
           " owl:withRestrictions ( :f ) ] . :f xsd:maxInclusive 10 .\n"
           ":S owl:equivalentClass [ a owl:Restriction ; owl:onProperty :v ; owl:someValuesFrom :small ] .\n"
           ":a :v 5 . :b :v 12 . :c :v 15 . :d :w 9 .\n")

#: (removed, added): the facet's value or kind edited
FACET_EDITS = {
    "raised": (":f xsd:maxInclusive 10 .", ":f xsd:maxInclusive 13 ."),
    "lowered": (":f xsd:maxInclusive 10 .", ":f xsd:maxInclusive 4 ."),
    "kind": (":f xsd:maxInclusive 10 .", ":f xsd:minInclusive 11 ."),
}


@pytest.mark.parametrize("mode", ["auto", "incremental"])
@pytest.mark.parametrize("edit", sorted(FACET_EDITS))
def test_a_datatype_facet_edited_changes_the_rules(edit: str, mode: str) -> None:
    """A facet (``_:f xsd:maxInclusive 10`` in a datatype restriction's ``owl:withRestrictions`` list) is
    TBox: its triple is neither a list cell nor in a schema vocabulary's namespace but XSD's, and an edit of
    it must compile the rules again, for the class it defines the members and for the range the
    consistency of reasoning from scratch."""
    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        onto.load_data(FACETED, "turtle")
        assert onto.reason().consistent
        before = conclusions(onto)
        removed, added = FACET_EDITS[edit]
        onto.change(parsed("@prefix xsd: <http://www.w3.org/2001/XMLSchema#> . " + added),
                    parsed("@prefix xsd: <http://www.w3.org/2001/XMLSchema#> . " + removed))
        report = onto.reason(mode=mode)
        fresh = Ontology()
        fresh.add(*onto.triples())
        expected = fresh.reason(mode="full")
    assert not expected.consistent or conclusions(fresh) != before  # the edit matters
    assert report.consistent == expected.consistent
    assert conclusions(onto) == conclusions(fresh)


#: (removed, added): an AllDifferent member list made malformed by a change of its cells (facts)
MALFORMING = {
    "two firsts": ("", ":m2 rdf:first :c ."),
    "cut short": (":m1 rdf:rest :m2 .", ""),
    "loop": (":m2 rdf:rest rdf:nil .", ":m2 rdf:rest :m1 ."),
}


def _list_notices(onto: Ontology) -> list[str]:
    return sorted(n.subject for n in onto.report.incomplete if "list" in n.subject)


@pytest.mark.parametrize("edit", sorted(MALFORMING))
def test_an_all_different_list_made_malformed_and_mended_is_said_as_from_scratch(edit: str) -> None:
    """Its cells are facts, so an edit compiles no rules; but a malformed member list is said (not reasoned
    completely), as a load of the same graph says it, and no longer once it is mended."""
    filler = " ".join(f":e{i} :near :e{i + 1} ." for i in range(200))
    onto = reasoned(f"{filler} :a a :A . :b a :A . [] a owl:AllDifferent ; owl:distinctMembers :m1 ."
                    ":m1 rdf:first :a ; rdf:rest :m2 . :m2 rdf:first :b ; rdf:rest rdf:nil .")
    assert _list_notices(onto) == []
    removed, added = MALFORMING[edit]
    for change, said in (((parsed(added), parsed(removed)), True), ((parsed(removed), parsed(added)), False)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            onto.change(*change)
            onto.reason()
            fresh = reasoned(onto.serialize("turtle").decode())
        assert bool(_list_notices(fresh)) is said  # malformed, then mended
        assert _list_notices(onto) == _list_notices(fresh)


def test_only_the_facets_of_the_xsd_namespace_are_schema_predicates() -> None:
    """A datatype restriction's facet is a schema triple; a data property a user named in the XSD namespace is a
    fact property (its value changes compile no rules and take the REPLACE short lane)."""
    from pyoxigraph import Literal, NamedNode, Triple

    from topostore.ontology.changes import fact_property
    from topostore.ontology.files import is_schema_triple
    from topostore.rdf.vocab import XSD

    node, value = NamedNode("urn:x:f"), Literal("10", datatype=NamedNode(XSD + "integer"))
    for facet in ("minInclusive", "maxExclusive", "pattern", "length", "fractionDigits"):
        assert is_schema_triple(Triple(node, NamedNode(XSD + facet), value)) and not fact_property(NamedNode(XSD + facet))
    level = NamedNode(XSD + "level")
    assert not is_schema_triple(Triple(node, level, value)) and fact_property(level)
