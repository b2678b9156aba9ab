"""A SPARQL update writing one value at one subject and property in several spellings keeps the first written,
as a load of the same triples does, and says each other one once; the spellings counted are those its
evaluation wrote (a VALUES row or a FILTER decides which reach a triple), in order across its operations, a
DELETE, CLEAR or DROP between starting the count again; a value the graph held in another spelling and written
again is said to be in the graph already, as a change says it."""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

import pytest
from http_support import config, in_process
from pyoxigraph import Literal, NamedNode
from support import reasoned_turtle

from topostore import Ontology, OntologyWarning
from topostore.armor.reference import Reference
from topostore.ontology.spellings import AGAIN_IN_CHANGE, HELD, REMOVED_AND_ADDED, TAG_KEPT
from topostore.rdf.vocab import ASSERTED, XSD
from topostore.sparql.execute import Job, run_update, update_delta

NS = "http://example.org/spelled#"
HEAD = (f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . "
        ":battery a owl:DatatypeProperty . :level a owl:DatatypeProperty .\n")
PROLOGUE = f"PREFIX xsd: <{XSD}> PREFIX k: <{NS}> "
HELD_7 = f'<{NS}r> <{NS}battery> "7"^^<{XSD}long> .'


def ontology(data: str = "") -> Ontology:
    return reasoned_turtle(HEAD + data)


def update(o: Ontology, text: str) -> list[str]:
    """The update's warnings."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        return run_update(Reference("ref", o, NS), PROLOGUE + text, Job(time.monotonic() + 60), 60.0).warnings


def battery(o: Ontology, subject: str = "r") -> list[Literal]:
    return o.data_values(NamedNode(NS + "battery"), NamedNode(NS + subject))


def long(lexical: str) -> Literal:
    return Literal(lexical, datatype=NamedNode(XSD + "long"))


def named(spelling: str, subject: str = "r") -> str:
    """How a note writes the triple ``subject`` battery ``spelling`` (an xsd:long)."""
    return f'<{NS}{subject}> <{NS}battery> "{spelling}"^^<{XSD}long>'


def notes_of(warned: list[str]) -> list[str]:
    """Each note of the update's warnings (one warning may join several)."""
    return [note for line in warned for note in line.split("; ")]


def said(warned: list[str], kept: str, other: str, why: str = AGAIN_IN_CHANGE, subject: str = "r") -> int:
    """How many notes say ``other`` was not stored, ``kept`` staying, for ``why``."""
    note = f"{named(kept, subject)} stays as written: {named(other, subject)} is the same value, {why}"
    return notes_of(warned).count(note)


def names(warned: list[str], spelling: str, subject: str = "r") -> bool:
    return any(named(spelling, subject) in note for note in notes_of(warned))


@pytest.mark.parametrize("text", [
    'INSERT DATA { k:r k:battery "007"^^xsd:long , "7"^^xsd:long }',
    'INSERT { k:r k:battery "007"^^xsd:long . k:r k:battery "7"^^xsd:long } WHERE { }',
    'INSERT { k:r k:battery ?v . k:r k:battery "7"^^xsd:long } WHERE { BIND("007"^^xsd:long AS ?v) }',
    'INSERT DATA { k:r k:battery "007"^^xsd:long } ; INSERT DATA { k:r k:battery "7"^^xsd:long }',
    'INSERT { k:r k:battery "007"^^xsd:long } WHERE { } ; INSERT DATA { k:r k:battery "7"^^xsd:long }',
    'INSERT DATA { k:r k:battery "007"^^xsd:long } ; DELETE DATA { k:r k:battery "8"^^xsd:long } ; '
    'INSERT DATA { k:r k:battery "7"^^xsd:long }',
    'INSERT DATA { k:r k:battery "007"^^xsd:long } ; DELETE { k:r k:battery ?v } WHERE { k:r k:battery ?v '
    'FILTER(?v > 100) } ; INSERT DATA { k:r k:battery "7"^^xsd:long }',
    'INSERT DATA { k:r k:battery "007"^^xsd:long } ; CLEAR SILENT GRAPH k:g ; INSERT DATA { k:r k:battery "7"^^xsd:long }',
    'INSERT DATA { k:r k:battery "007"^^xsd:long } ; DELETE DATA { GRAPH k:g { k:r k:battery 7 } } ; '
    'INSERT DATA { k:r k:battery "7"^^xsd:long }',
])
def test_the_first_spelling_written_stays_and_the_other_is_said(text: str) -> None:
    o = ontology()
    warned = update(o, text)
    assert battery(o) == [long("007")]
    assert said(warned, "007", "7") == 1


def test_a_load_of_the_same_triples_keeps_the_same_spelling() -> None:
    o = ontology()
    update(o, 'INSERT DATA { k:r k:battery "7"^^xsd:int , 7.0 , "07"^^xsd:int }')
    loaded = ontology(f'<{NS}r> <{NS}battery> "7"^^<{XSD}int> , 7.0 , "07"^^<{XSD}int> .')
    assert battery(o) == battery(loaded) == [Literal("7", datatype=NamedNode(XSD + "int"))]


def test_a_blank_nodes_value_keeps_its_first_spelling() -> None:
    o = ontology()
    warned = update(o, 'INSERT DATA { k:r k:level [ k:battery "007"^^xsd:long , "7"^^xsd:long ] }')
    held = [o.store.original_literal(ASSERTED, t.subject, t.predicate, t.object)
            for t in o.store.triples(None, NamedNode(NS + "battery"), None, ASSERTED)]
    assert held == [long("007")]
    assert any(f'<{NS}battery> "7"^^<{XSD}long> is the same value, {AGAIN_IN_CHANGE}' in n for n in notes_of(warned))


@pytest.mark.parametrize("text", [
    # the rows cross: k:a is given "007", k:r "7" and (every row) "07"
    'INSERT { ?s k:battery ?v . k:r k:battery "07"^^xsd:long } '
    'WHERE { VALUES (?s ?v) { (k:a "007"^^xsd:long) (k:r "7"^^xsd:long) } }',
    # the FILTER keeps k:q's row: "007" is never written at k:r
    'INSERT { ?s k:battery "007"^^xsd:long . k:r k:battery "07"^^xsd:long . k:r k:battery "7"^^xsd:long } '
    'WHERE { VALUES ?s { k:r k:q } FILTER(?s = k:q) }',
    # a row with UNDEF writes nothing at k:r from it
    'INSERT { ?s k:battery ?v . k:r k:battery "07"^^xsd:long } '
    'WHERE { VALUES (?s ?v) { (k:r UNDEF) (UNDEF "007"^^xsd:long) (k:a "007"^^xsd:long) (k:r "7"^^xsd:long) } }',
])
def test_values_rows_and_filters_choose_the_spelling_written_at_a_triple(text: str) -> None:
    o = ontology()
    warned = update(o, text)
    assert battery(o) == [long("07")]
    assert said(warned, "07", "7") == 1
    assert not names(warned, "007")


def test_a_spelling_a_filter_reads_is_never_said_written() -> None:
    """Oxigraph filters the canonical value (``str`` of both rows is "7"): which row the written spelling lets
    through is not shown, so neither is said."""
    o = ontology()
    warned = update(o, 'INSERT { k:r k:battery ?v . k:r k:battery "07"^^xsd:long } '
                       'WHERE { VALUES ?v { "007"^^xsd:long "7"^^xsd:long } FILTER(str(?v) = "7") }')
    assert not names(warned, "007")
    assert len(battery(o)) == 1


@pytest.mark.parametrize("between", ["CLEAR DEFAULT", "CLEAR SILENT ALL", "DROP ALL", "DROP SILENT DEFAULT",
                                     "DELETE DATA { k:r k:battery 7 }", "DELETE WHERE { k:r k:battery ?v }",
                                     "DELETE { ?s k:battery ?v } WHERE { ?s k:battery ?v }"])
def test_a_removal_between_starts_the_count_again(between: str) -> None:
    o = ontology()
    warned = update(o, f'INSERT DATA {{ k:r k:battery "007"^^xsd:long }} ; {between} ; '
                       'INSERT DATA { k:r k:battery "7"^^xsd:long , "07"^^xsd:long }')
    assert battery(o) == [long("7")]
    assert said(warned, "7", "07") == 1
    assert not names(warned, "007")


def test_each_other_spelling_is_said_once() -> None:
    o = ontology()
    warned = update(o, 'INSERT DATA { k:r k:battery "007"^^xsd:long , "7"^^xsd:long } ; '
                       'INSERT { k:r k:battery "7"^^xsd:long } WHERE { VALUES ?x { 1 2 } }')
    assert battery(o) == [long("007")]
    assert said(warned, "007", "7") == 1
    assert len(notes_of(warned)) == 1


@pytest.mark.parametrize("text", ['INSERT DATA { k:r k:battery "07"^^xsd:long }',
                                  'INSERT { k:r k:battery "07"^^xsd:long } WHERE { }',
                                  'INSERT DATA { k:r k:battery "7"^^xsd:long , "07"^^xsd:long }'])
def test_a_value_held_in_another_spelling_is_said_already_in_the_graph(text: str) -> None:
    o = ontology(HELD_7)
    warned = update(o, text)
    assert battery(o) == [long("7")]
    assert said(warned, "7", "07", HELD) == 1


@pytest.mark.parametrize("removal", ["DELETE DATA { k:r k:battery 7 } ;", "DELETE WHERE { k:r k:battery ?v } ;",
                                     "CLEAR DEFAULT ;", "DELETE { k:r k:battery ?v }"])
def test_a_held_value_removed_and_written_again_is_said_so_not_held(removal: str) -> None:
    """The update removed the value and wrote it again: it nets out, as a change's removal and addition of one
    value does, and is said as such (the advice to remove it first would name what the update did)."""
    o = ontology(HELD_7)
    where = " WHERE { k:r k:battery ?v }" if removal.startswith("DELETE {") else ""
    warned = update(o, f'{removal} INSERT {"" if where else "DATA "}{{ k:r k:battery "07"^^xsd:long }}{where}')
    assert battery(o) == [long("7")]
    assert said(warned, "7", "07", REMOVED_AND_ADDED) == 1
    assert not any(HELD in note for note in notes_of(warned))


def test_the_sparql_endpoint_says_the_spelling_not_stored(tmp_path: Path) -> None:
    head = (f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . "
            f"<{NS}onto> a owl:Ontology . :battery a owl:DatatypeProperty . ")
    with in_process(config(tmp_path / "data", allow_update=True)) as server:
        server.request("/references/spelled/data?default", head.encode(), {"Content-Type": "text/turtle"}, "PUT")
        text = (f'INSERT {{ <{NS}r> <{NS}battery> ?v }} WHERE {{ VALUES ?v {{ "007"^^<{XSD}long> }} }} ; '
                f'INSERT DATA {{ <{NS}r> <{NS}battery> "7"^^<{XSD}long> }}')
        status, _, reply = server.request("/references/spelled/sparql", text.encode(),
                                          {"Content-Type": "application/sparql-update"}, "POST")
        assert status == 200, reply
        answer = json.loads(reply)
        _, _, body = server.request("/references/spelled/data?default", None, {"Accept": "application/n-triples"})
    assert answer["added"] == 1
    assert said(answer["warnings"], "007", "7") == 1
    assert f'{named("007")} .' in body.decode()


def _lines(n: int) -> int:
    """The lines of topostore run to compute the delta of an INSERT DATA of ``n`` values then a DELETE DATA of
    ``n`` others (every triple a typed literal, so each is read for its spelling)."""
    ins = " ".join(f'k:s{i} k:battery "{i}"^^xsd:long .' for i in range(n))
    dels = " ".join(f'k:s{i} k:level "{i}"^^xsd:long .' for i in range(n))
    text = PROLOGUE + f"INSERT DATA {{ {ins} }} ; DELETE DATA {{ {dels} }}"
    count = 0

    def trace(frame, event, _arg):  # type: ignore[no-untyped-def]
        nonlocal count
        if "topostore" not in frame.f_code.co_filename:
            return None
        if event == "line":
            count += 1
        return trace

    previous = sys.gettrace()  # a coverage run's tracer, put back after
    sys.settrace(trace)
    try:
        delta = update_delta([], text)
    finally:
        sys.settrace(previous)
    assert len(delta.add) == n
    return count


def test_an_insert_then_a_delete_costs_work_linear_in_the_triples() -> None:
    """Twice the triples, about twice the lines run (a removal looking through every value written would be
    four times)."""
    _lines(50)  # the caches and first imports warmed
    small, large = _lines(400), _lines(800)
    assert large < 2.4 * small, (small, large)  # measured ≈ 2.0; a quadratic removal ≈ 3.3 (at 400) and growing


NAME = f"<{NS}name> a <http://www.w3.org/2002/07/owl#DatatypeProperty> . "
R_NAME = f"<{NS}r> <{NS}name>"


@pytest.mark.parametrize(("held", "text", "document", "kept", "other"), [
    ("", 'INSERT DATA { k:r k:name "a"@EN , "a"@en }', f'{R_NAME} "a"@EN , "a"@en .', "EN", "en"),
    ("", 'INSERT DATA { k:r k:name "a"@en } ; INSERT DATA { k:r k:name "a"@EN }', f'{R_NAME} "a"@en , "a"@EN .',
     "en", "EN"),
    (f'{R_NAME} "a"@en .', 'INSERT DATA { k:r k:name "a"@EN }', f'{R_NAME} "a"@EN .', "en", "EN"),
])
def test_a_tag_spelled_otherwise_is_said_as_a_load_says_it(held: str, text: str, document: str, kept: str,
                                                           other: str) -> None:
    """``document``: the same triples as a load reads them."""
    note = f'{R_NAME} "a"@{kept} stays as written: {R_NAME} "a"@{other} is the same value, {TAG_KEPT}'
    assert notes_of(update(ontology(NAME + held), text)) == [note]
    loaded = ontology(NAME + held)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        loaded.load_data(document, "turtle")
    assert [str(w.message).removeprefix("<data>: ") for w in caught if TAG_KEPT in str(w.message)] == [note]


@pytest.mark.parametrize("between", ["DELETE DATA { k:r k:name \"a\"@en }", "DELETE WHERE { k:r k:name ?n }",
                                     "CLEAR DEFAULT"])
def test_a_tag_removed_between_or_after_is_not_said(between: str) -> None:
    """A removal between two writes starts their count again (a load of the writes alone would say one)."""
    o = ontology(NAME)
    assert update(o, 'INSERT DATA { k:r k:name "a"@en } ; INSERT DATA { k:r k:name "a"@EN } ; '
                     'DELETE DATA { k:r k:name "a"@en }') == []
    assert update(o, f'INSERT DATA {{ k:r k:name "a"@EN }} ; {between} ; INSERT DATA {{ k:r k:name "a"@eN }}') == []


@pytest.mark.parametrize("text", [
    'INSERT DATA { _:b k:battery "7"^^xsd:long } ; INSERT DATA { _:b k:level 1 }',
    'INSERT DATA { _:b k:battery 7 } ; INSERT DATA { _:b k:level 1 }',
    f'INSERT DATA {{ k:r k:battery "07"^^xsd:long }} ; PREFIX z: <{NS}> INSERT DATA {{ z:r z:level 1 }}',
    f'INSERT DATA {{ k:r k:battery 7 }} ; PREFIX z: <{NS}> INSERT DATA {{ z:r z:level 1 }}',
])
def test_a_request_refused_as_a_whole_is_refused_whatever_its_spellings(text: str) -> None:
    """Each operation of these runs alone, but the request does not (a blank node label shared by two blocks, a
    prologue after ``;``): refused with nothing changed, whether or not it writes a spelling to keep."""
    o = ontology(HELD_7)
    before = sorted(map(str, o.store.triples(graph=ASSERTED)))
    with pytest.raises(Exception, match="SPARQL update"):
        update(o, text)
    assert sorted(map(str, o.store.triples(graph=ASSERTED))) == before
