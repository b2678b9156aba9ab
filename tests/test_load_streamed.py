"""A document written into the empty asserted graph as it is parsed gives what the ordinary load gives.

The first document of an empty in-memory ontology is streamed (:mod:`topostore.ontology.streamed`);
every other goes through the triple list (:meth:`OntologyFiles._add_document`).  Both must store the
same triples, keep the same literal spellings (the first of a value), count the same triples, report the
same notices and refuse the same documents, leaving the ontology as it was."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import pytest
from pyoxigraph import BlankNode, Literal, NamedNode, Triple

from topostore import InvalidValueError, LoadError, Ontology, RuleCompileError
from topostore.ontology import files as files_module
from topostore.ontology import streamed
from topostore.rdf.vocab import ASSERTED, is_skolem

A = "http://e.org/a#"
PREFIXES = f"""@prefix : <{A}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
@prefix swrl: <http://www.w3.org/2003/11/swrl#> .
"""
#: a schema, a rule, blank nodes, two spellings of one value, a repeated triple, XML literals (one not well-formed)
DOCUMENT = PREFIXES + """
:Room rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :door ; owl:minCardinality "1"^^xsd:nonNegativeInteger ] .
:door a owl:ObjectProperty . :at a owl:DatatypeProperty .
:r1 a :Room ; :door :d1 ; :at "01"^^xsd:int , "1"^^xsd:int , "7"^^xsd:long , "x" , "x"@en ;
    :note "<b   a='1'  c=\\"2\\"></b>"^^rdf:XMLLiteral , "<open>"^^rdf:XMLLiteral .
:r1 :door :d1 .
:r2 a :Room ; :at "7"^^xsd:long ; :door [ :at "2"^^xsd:integer ] .
[ a swrl:Imp ; swrl:body [ a swrl:AtomList ; rdf:first [ a swrl:ClassAtom ; swrl:classPredicate :Room ;
      swrl:argument1 :x ] ; rdf:rest rdf:nil ] ;
  swrl:head [ a swrl:AtomList ; rdf:first [ a swrl:ClassAtom ; swrl:classPredicate :Place ;
      swrl:argument1 :x ] ; rdf:rest rdf:nil ] ] .
:x a swrl:Variable .
"""
DATA = Path(__file__).parent / "data"


def ordinary(onto: Ontology) -> Ontology:
    """``onto`` made to load every document through the triple list."""
    onto.files._streaming_possible = lambda: False  # type: ignore[method-assign]
    return onto


def loaded(text: str, stream: bool, **kwargs) -> tuple[Ontology, int, list[str]]:
    onto = Ontology(**kwargs) if stream else ordinary(Ontology(**kwargs))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        n = onto.load_data(text, "turtle")
    return onto, n, [str(w.message) for w in caught]


def named(t: Triple) -> Triple | None:
    """``t`` when neither end is a blank node (blank nodes are named afresh by each parse)."""
    return None if isinstance(t.subject, BlankNode) or isinstance(t.object, BlankNode) else t


def shape(onto: Ontology) -> tuple:
    """What a load leaves, blank node names aside: the triples as saved, the literal forms and the counts."""
    triples = onto.files.triples()
    forms = {k[1:]: v for k, v in onto.store.forms._literal_forms.items() if not is_skolem(k[1])}
    blank_forms = sorted(str(v) for k, v in onto.store.forms._literal_forms.items() if is_skolem(k[1]))
    return ({t for t in map(named, triples) if t is not None}, len(triples), forms, blank_forms)


def uses_stream(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Count the documents streamed."""
    calls: list[int] = []
    real = files_module.stream_into_empty

    def counted(*args, **kwargs):
        calls.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(files_module, "stream_into_empty", counted)
    return calls


def test_streamed_and_ordinary_loads_leave_the_same_ontology(monkeypatch: pytest.MonkeyPatch) -> None:
    calls = uses_stream(monkeypatch)
    fast, n_fast, said_fast = loaded(DOCUMENT, stream=True)
    slow, n_slow, said_slow = loaded(DOCUMENT, stream=False)
    assert calls == [1]
    assert n_fast == n_slow
    assert shape(fast) == shape(slow)
    assert said_fast == said_slow and any("XMLLiteral" in s for s in said_fast)
    assert fast.notices == slow.notices and fast.dirty and fast.load_notices == slow.load_notices
    assert sorted(re.sub(r"bnode:[0-9a-f]+", "b", r.sparql()) for r in fast.rules.rules) == \
        sorted(re.sub(r"bnode:[0-9a-f]+", "b", r.sparql()) for r in slow.rules.rules)
    assert fast.reason().consistent and slow.reason().consistent
    place = NamedNode(A + "Place")
    assert fast.instances(place) == slow.instances(place) == [NamedNode(A + "r1"), NamedNode(A + "r2")]


def test_the_first_spelling_of_a_value_is_the_one_kept() -> None:
    onto, n, _ = loaded(PREFIXES + ':a :p "01"^^xsd:int , "1"^^xsd:int , "1"^^xsd:integer , "01"^^xsd:int .',
                        stream=True)
    assert n == 1  # one fact, counted once whatever its spellings, as the ordinary load counts it
    assert onto.data_values(NamedNode(A + "p"), NamedNode(A + "a")) == \
        [Literal("01", datatype=NamedNode("http://www.w3.org/2001/XMLSchema#int"))]


def test_a_canonical_xml_literal_is_stored() -> None:
    onto, _, said = loaded(PREFIXES + """:a :p "<b c='2'   a='1'/>"^^rdf:XMLLiteral .""", stream=True)
    (value,) = onto.data_values(NamedNode(A + "p"), NamedNode(A + "a"))
    assert value.value == '<b a="1" c="2"></b>' and said == []


@pytest.mark.parametrize(("text", "error", "message"), [
    (PREFIXES + ':a :p "abc"^^xsd:integer . :b :q :c .', InvalidValueError, "abc"),
    (PREFIXES + ":a :p :b .\n:a :p", LoadError, r"<data>:\d+: not valid Turtle"),
    (PREFIXES + ":p rdfs:domain :D . :C owl:equivalentClass [ a owl:Class ; owl:intersectionOf ({}) ] ."
     .format(" ".join(f":A{i}" for i in range(300))), RuleCompileError, "too large"),
])
def test_a_refused_first_document_leaves_nothing_behind(text: str, error: type, message: str) -> None:
    onto = Ontology()
    dirty = onto.dirty
    with pytest.raises(error, match=message):
        onto.load_data(text, "turtle")
    assert onto.store.count(ASSERTED) == 0 and onto.store.forms._literal_forms == {} and onto.dirty == dirty
    assert onto.load_data(PREFIXES + ':a :p "5"^^xsd:long .', "turtle") == 1
    assert onto.data_values(NamedNode(A + "p"), NamedNode(A + "a"))[0].datatype.value.endswith("long")


#: RDF/XML declaring an external entity (refused before a byte is parsed, in process and in a child)
ENTITY_DOCUMENT = ('<?xml version="1.0"?><!DOCTYPE rdf:RDF [<!ENTITY e SYSTEM "file:///etc/hostname">]>'
                   '<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#">'
                   '<rdf:Description rdf:about="http://e.org/a#a"><rdf:value>&e;</rdf:value></rdf:Description>'
                   '</rdf:RDF>')


def test_entity_declarations_are_refused_before_anything_is_written(tmp_path: Path) -> None:
    path = tmp_path / "entities.owl"
    path.write_text(ENTITY_DOCUMENT)
    onto = Ontology()
    with pytest.raises(LoadError, match="external or parameter entity 'e' refused"):
        onto.load(path)
    assert onto.store.count(ASSERTED) == 0


def test_rules_that_need_repair_take_the_ordinary_load(monkeypatch: pytest.MonkeyPatch) -> None:
    saved = DATA / "saved_nested_rules.owl"
    checked: list[bool] = []
    real = streamed.needs_repair

    def watched(*args) -> bool:
        checked.append(real(*args))
        return checked[-1]

    monkeypatch.setattr(streamed, "needs_repair", watched)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fast = Ontology()
        fast.load(saved)
        slow = ordinary(Ontology())
        slow.load(saved)
    assert checked == [True]
    assert [n.kind for n in fast.notices] == [n.kind for n in slow.notices] and fast.load_notices
    assert len(fast.files.triples()) == len(slow.files.triples())
    assert {t for t in map(named, fast.files.triples()) if t} == {t for t in map(named, slow.files.triples()) if t}
    assert len([w for w in caught if "repaired" in str(w.message)]) == 2
    assert all(w.filename == __file__ for w in caught)  # warnings point at the caller of load


def test_a_second_document_and_a_recording_ontology_take_the_ordinary_load(monkeypatch: pytest.MonkeyPatch) -> None:
    calls = uses_stream(monkeypatch)
    onto = Ontology()
    onto.load_data(PREFIXES + ":a :p :b .", "turtle")
    onto.load_data(PREFIXES + ":b :p :c .", "turtle")
    assert calls == [1] and onto.store.count(ASSERTED) == 2
    recording = Ontology()
    recording.reason()  # from the first REASON on, each change is recorded (the ledger needs every triple)
    assert recording.ledger.tracking
    recording.load_data(PREFIXES + ":a :p :b .", "turtle")
    assert calls == [1] and recording.store.count(ASSERTED) == 1


def test_progress_is_told_as_the_document_is_parsed(tmp_path: Path) -> None:
    path = tmp_path / "big.ttl"
    path.write_text(PREFIXES + " ".join(f":i{n} :p :i{n + 1} ." for n in range(12_000)))
    told: list[int] = []
    assert Ontology().load(path, progress=told.append) == 12_000
    assert told == [5000, 10000]


def test_the_count_asked_of_the_graph_is_the_count_the_store_gains() -> None:
    """A store that cannot tell what it gained (a durable one) has the graph counted by a query instead: the
    facts stored, one per value whatever its spellings, as the store's gain counts them."""
    onto, n, _ = loaded(PREFIXES + ':a :p "01"^^xsd:int , "1"^^xsd:int , "x" ; :q :b , :b .', stream=True)
    assert n == 3  # :a :p 1, :a :p "x", :a :q :b
    assert onto.store.count(ASSERTED) == n
