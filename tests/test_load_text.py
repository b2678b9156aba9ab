"""The first document written through pyoxigraph's N-Triples text gives what the quad-by-quad pass gives.

A document in RDF/XML, Turtle or N-Triples is serialised by pyoxigraph as it parses, and the text is changed as
bytes (:mod:`topostore.rdf.ntriples_text`): blank nodes renamed, the literal lines read as terms, the pieces
indexed in a second thread (:mod:`topostore.stores.text_writer`).  The pass it replaced
(:func:`topostore.ontology.streamed.written_triples`, still used for JSON-LD and N3) is the reference: the same
store content quad for quad (blank node names aside), the same literal forms, counts, predicates, notices,
SAVE output (its order too), and the same errors mid-document leaving nothing behind.  Pieces are made tiny
here so that every document crosses many of them and the worker thread runs.
"""

from __future__ import annotations

import os
import re
import threading
import warnings
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pyoxigraph import BlankNode, CanonicalizationAlgorithm, Dataset, Literal, NamedNode, Quad, RdfFormat, Triple
from pyoxigraph import serialize as ox_serialize
from test_load_streamed import DOCUMENT, PREFIXES

from topostore import InvalidValueError, LoadError, Ontology
from topostore.demo import mapgen
from topostore.errors import TopostoreError
from topostore.ontology import streamed
from topostore.rdf.ntriples_text import PLACE, literal_lines, named_blank_nodes, predicates, put_back
from topostore.rdf.skolem import unskolem
from topostore.rdf.vocab import ASSERTED, SKOLEM_PREFIX
from topostore.resources import default_ontology
from topostore.stores import text_writer
from topostore.stores.cores import CoreWatch, busy_cores, cpu_times, spare
from topostore.stores.text_writer import TextWriter

ROOT = Path(__file__).resolve().parents[1]
FILES = sorted([*(ROOT / "tests" / "data").iterdir(), *(ROOT / "ontology").iterdir()])
A = "http://e.org/a#"

#: what the serialiser's text may hold that a careless rewrite would break: IRIs holding ``_:``, literals holding
#: spaces, ``_:``, quotes, newlines, a NUL and ``<<(``; blank subjects of literals, respelled and repeated values
EDGES = PREFIXES + r"""
<http://e.org/a_:b> <http://e.org/p_:q> <http://e.org/c_:d> , _:n1 .
_:n1 :label " _:x <y> . \"quoted\" \n second line\t_:z\u0000 " ;
     :at "01"^^xsd:int , "1"^^xsd:int , "1"^^xsd:integer , "2"^^xsd:long ;
     :note "<b  c='2' a='1'/>"^^rdf:XMLLiteral ;
     :tag "X"@en-GB , "x"@EN-gb .
:r a [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :C ] .
:é :p "日本" , "\U0001F916"@ja , "1e3"^^xsd:double , "1E3"^^xsd:double , "true"^^xsd:boolean , "1"^^xsd:boolean .
:last :p "<<( :a :b :c )>> in a literal: its piece is read as terms" .
"""
#: RDF 1.2 triple terms, with a blank node and a literal inside
TRIPLE_TERMS = PREFIXES + """
:a :p <<( :s :q _:b )>> . :a :p <<( :s :q "v" )>> . _:c :p <<( :s :q :o )>> . :a :n "1"^^xsd:long .
"""


@pytest.fixture(autouse=True)
def small_pieces(monkeypatch: pytest.MonkeyPatch) -> None:
    """Pieces of five triples: every document crosses several, and the worker thread runs (as on a machine
    with a core free)."""
    monkeypatch.setattr(streamed, "TEXT_CHUNK", 5)
    monkeypatch.setattr(text_writer, "_SETTING", "1")


def through_text(load) -> Ontology:
    """An ontology loaded by ``load(onto)`` through the N-Triples text (the default for these formats)."""
    onto = Ontology()
    with warnings.catch_warnings(record=True):
        warnings.simplefilter("always")
        onto.n = load(onto)  # type: ignore[attr-defined]
    return onto


def through_quads(load, monkeypatch: pytest.MonkeyPatch) -> Ontology:
    """The same load through the quad-by-quad pass (as JSON-LD and N3 are read)."""
    with monkeypatch.context() as patch:
        patch.setattr(streamed, "TEXT_FORMATS", frozenset())
        return through_text(load)


def content(onto: Ontology) -> Dataset:
    """Every quad of the store and every literal form kept, skolem IRIs as blank nodes, canonicalised: equal
    for two ontologies exactly when their stores and forms are equal up to the names of blank nodes."""
    quads = [Quad(unskolem(q.subject), q.predicate, unskolem(q.object), q.graph_name)
             for q in onto.store._match(None, None, None, None)]
    forms = [Quad(unskolem(s), p, lit, NamedNode("urn:test:forms:" + graph))
             for (graph, s, p, _), lit in onto.store.forms._literal_forms.items()]
    dataset = Dataset([*quads, *forms])
    dataset.canonicalize(CanonicalizationAlgorithm.UNSTABLE)
    return dataset


def saved(onto: Ontology) -> list[str]:
    """SAVE's N-Triples in its order, blank node names replaced by their order of first appearance."""
    names: dict[str, str] = {}
    text = onto.serialize("ntriples").decode()
    return re.sub(r"_:\w+", lambda m: names.setdefault(m.group(0), f"_:b{len(names)}"), text).splitlines()


def assert_same(text: Ontology, quads: Ontology) -> None:
    assert text.n == quads.n  # type: ignore[attr-defined]
    assert content(text) == content(quads)
    assert text.store.forms._value_forms == quads.store.forms._value_forms
    assert saved(text) == saved(quads)
    assert text.notices == quads.notices and text.load_notices == quads.load_notices
    assert sorted(re.sub(r"bnode:[0-9a-f]+", "b", r.sparql()) for r in text.rules.rules) == \
        sorted(re.sub(r"bnode:[0-9a-f]+", "b", r.sparql()) for r in quads.rules.rules)


def rdf_xml_map(tmp_path: Path) -> Path:
    """A generated map with the shipped TBox and its rules, as RDF/XML (the shape of the benchmark maps)."""
    onto = Ontology.from_file(default_ontology())
    onto.add(*mapgen.generate(40, seed=3).triples())
    return onto.save(tmp_path / "map.owl")


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_the_project_files_load_the_same_both_ways(path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    assert_same(through_text(lambda o: o.load(path)), through_quads(lambda o: o.load(path), monkeypatch))


def test_a_generated_map_in_rdf_xml_loads_the_same_both_ways(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = rdf_xml_map(tmp_path)
    text = through_text(lambda o: o.load(path))
    assert_same(text, through_quads(lambda o: o.load(path), monkeypatch))
    assert any(q.subject.value.startswith(SKOLEM_PREFIX) for q in text.store._match(None, None, None, ASSERTED))
    assert not any(isinstance(q.subject, BlankNode) or isinstance(q.object, BlankNode)
                   for q in text.store._match(None, None, None, None))


@pytest.mark.parametrize("document", [DOCUMENT, EDGES, TRIPLE_TERMS], ids=["document", "edges", "triple terms"])
@pytest.mark.parametrize("fmt", ["turtle", "ntriples", "xml"])
def test_documents_load_the_same_both_ways(document: str, fmt: str, monkeypatch: pytest.MonkeyPatch) -> None:
    if fmt == "turtle":
        data = document
    else:
        parsed = Ontology()
        parsed.load_data(document, "turtle")
        if fmt == "xml" and document is TRIPLE_TERMS:
            pytest.skip("RDF/XML writes no triple term")
        data = parsed.serialize("xml" if fmt == "xml" else "ntriples").decode()
    assert_same(through_text(lambda o: o.load_data(data, fmt)),
                through_quads(lambda o: o.load_data(data, fmt), monkeypatch))


def test_edge_terms_are_kept_as_written() -> None:
    onto = through_text(lambda o: o.load_data(EDGES, "turtle"))
    odd = NamedNode("http://e.org/a_:b")
    (target,) = [t.object for t in onto.store.triples(odd, NamedNode("http://e.org/p_:q"), None, ASSERTED)
                 if isinstance(t.object, NamedNode) and t.object.value == "http://e.org/c_:d"]
    assert target == NamedNode("http://e.org/c_:d")
    labels = [t.object for t in onto.store.triples(None, NamedNode(A + "label"), None, ASSERTED)]
    assert labels == [Literal(' _:x <y> . "quoted" \n second line\t_:z\x00 ')]
    values = {t.object.value for t in onto.store.triples(None, NamedNode(A + "at"), None, ASSERTED)}
    assert values == {"1", "2"}  # one quad per value: "01"^^xsd:int written, its other spellings skipped
    ordinary = Ontology()
    ordinary.files._streaming_possible = lambda: False  # type: ignore[method-assign]
    assert onto.n == ordinary.load_data(EDGES, "turtle") == 17  # type: ignore[attr-defined]  # every fact stored


@pytest.mark.parametrize("fmt", ["ntriples", "turtle"])
def test_a_later_spelling_written_twice_is_said_once_and_a_repeated_triple_stored_once(
        fmt: str, monkeypatch: pytest.MonkeyPatch) -> None:
    lines = [f'<{A}s> <{A}at> "{v}"^^<http://www.w3.org/2001/XMLSchema#{t}> .' for v, t in
             [("1", "int"), ("01", "int"), ("7", "long"), ("01", "int"), ("1", "int"), ("07", "long")] * 3]
    document = "\n".join(lines) + "\n"  # N-Triples, Turtle as well
    text = through_text(lambda o: o.load_data(document, fmt))
    quads = through_quads(lambda o: o.load_data(document, fmt), monkeypatch)
    assert_same(text, quads)
    assert text.files.spelling_notes == quads.files.spelling_notes
    assert len(text.files.spelling_notes) == 2  # "01" after "1", "07" after "7": each said once
    assert {t.object.value for t in text.store.triples(None, NamedNode(A + "at"), None, ASSERTED)} == {"1", "7"}


def test_a_syntax_error_after_many_pieces_leaves_nothing_behind(monkeypatch: pytest.MonkeyPatch) -> None:
    document = PREFIXES + "".join(f':i{n} :p :i{n + 1} ; :v "{n}"^^xsd:long .\n' for n in range(200)) + ":x :p"
    onto = Ontology()
    with pytest.raises(LoadError) as text_error:
        onto.load_data(document, "turtle")
    assert onto.store.count(ASSERTED) == 0 and onto.store.forms._literal_forms == {}
    assert not [t for t in threading.enumerate() if t.name == "topostore-text-load"]
    ordinary = Ontology()
    ordinary.files._streaming_possible = lambda: False  # type: ignore[method-assign]
    with pytest.raises(LoadError) as ordinary_error:
        ordinary.load_data(document, "turtle")
    assert str(text_error.value) == str(ordinary_error.value)
    assert re.match(r"<data>:\d+: not valid", str(text_error.value))


def test_an_invalid_value_after_many_pieces_leaves_nothing_behind() -> None:
    document = PREFIXES + "".join(f":i{n} :p :i{n + 1} .\n" for n in range(200)) + ':x :v "ten"^^xsd:long .'
    onto = Ontology()
    with pytest.raises(InvalidValueError, match="ten"):
        onto.load_data(document, "turtle")
    assert onto.store.count(ASSERTED) == 0 and onto.store.forms._literal_forms == {}
    assert onto.load_data(PREFIXES + ':a :p "5"^^xsd:long .', "turtle") == 1


def test_progress_is_told_at_each_multiple_across_pieces(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(streamed, "TEXT_CHUNK", 3000)
    told: list[int] = []
    document = PREFIXES + " ".join(f":i{n} :p :i{n + 1} ." for n in range(12_000))
    onto = Ontology()
    found = streamed.stream_into_empty(onto.store, document, RdfFormat.TURTLE, None, "<data>", told.append)
    assert found.triples == 12_000 and told == [5000, 10000]


# ------------------------------------------------------------------------------------- the text, as bytes
def nt(*triples: Triple) -> bytes:
    return ox_serialize(list(triples), None, RdfFormat.N_TRIPLES)


S, P, O = NamedNode("http://e.org/s"), NamedNode("http://e.org/p"), NamedNode("http://e.org/o")
ODD = NamedNode("http://e.org/x_:y")


@pytest.mark.parametrize("text", [
    b"", nt(Triple(S, P, O)), nt(Triple(S, P, Literal("a"))), nt(Triple(S, P, Literal("a")), Triple(S, P, O)),
    nt(Triple(S, P, O), Triple(S, P, Literal("a \"b\" _:c")), Triple(S, P, Literal("d")), Triple(ODD, P, O)),
])
def test_literal_lines_and_put_back_give_the_text_again(text: bytes) -> None:
    plain, lines = literal_lines(text)
    assert all(b'"' in line and line.endswith(b"\n") for line in lines)
    assert b'"' not in plain and plain.count(PLACE) == len(lines)
    assert put_back(plain, lines) == text


def test_blank_nodes_are_named_and_iris_holding_their_mark_are_not() -> None:
    b1, b2 = BlankNode("e1"), BlankNode("f2")
    text = nt(Triple(b1, P, b2), Triple(ODD, P, b1), Triple(b2, P, ODD), Triple(S, ODD, O))
    named = named_blank_nodes(text, SKOLEM_PREFIX)
    sk1, sk2 = (f"<{SKOLEM_PREFIX}{b.value}>".encode() for b in (b1, b2))
    assert named.splitlines() == [sk1 + b" <http://e.org/p> " + sk2 + b" .",
                                  b"<http://e.org/x_:y> <http://e.org/p> " + sk1 + b" .",
                                  sk2 + b" <http://e.org/p> <http://e.org/x_:y> .",
                                  b"<http://e.org/s> <http://e.org/x_:y> <http://e.org/o> ."]
    assert named_blank_nodes(nt(Triple(S, P, O)), SKOLEM_PREFIX) == nt(Triple(S, P, O))


def test_predicates_are_read_from_the_lines_without_a_literal() -> None:
    plain, _ = literal_lines(nt(Triple(S, P, Literal("a b c")), Triple(BlankNode("e1"), ODD, O),
                                Triple(S, P, Literal("x")), Triple(S, S, BlankNode("e2"))))
    assert predicates(plain) == {b"<http://e.org/x_:y>", b"<http://e.org/s>"}


IRIS = st.sampled_from(["http://e.org/a", "http://e.org/b_:c", "http://e.org/é", "urn:x:_:y", "http://e.org/p"])
LEXICAL = st.one_of(st.text(max_size=12), st.sampled_from(["01", "1", " _:x ", '"', "<<( x )>>", "a b"]))
DATATYPES = st.sampled_from(["string", "long", "int", "integer", "boolean", "anyURI"])
TERMS = st.one_of(IRIS.map(NamedNode), st.sampled_from(["e1", "f2", "a3"]).map(BlankNode))


@st.composite
def documents(draw) -> bytes:
    """N-Triples of up to 30 triples over a few IRIs (some holding ``_:``), blank nodes and literals."""
    triples = []
    for _ in range(draw(st.integers(0, 30))):
        s = draw(TERMS)
        if draw(st.booleans()):
            dt = draw(DATATYPES)
            value = draw(LEXICAL) if dt in ("string", "anyURI") else draw(st.sampled_from(["1", "01", "+1", "true"]))
            o = Literal(value, datatype=NamedNode("http://www.w3.org/2001/XMLSchema#" + dt))
        else:
            o = draw(TERMS)
        triples.append(Triple(s, NamedNode(draw(IRIS)), o))
    return nt(*triples)


def outcome(document: bytes) -> Ontology | str:
    """The ontology a document loads to, or the error it is refused with (the graph then left empty)."""
    try:
        return through_text(lambda o: o.load_data(document, "ntriples"))
    except TopostoreError as exc:
        return f"{type(exc).__name__}: {exc}"


@settings(deadline=None)  # each example loads a document twice: seconds on a busy machine
@given(documents())
def test_any_small_document_loads_the_same_both_ways(document: bytes) -> None:
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(streamed, "TEXT_CHUNK", 4)
        text = outcome(document)
        patch.setattr(streamed, "TEXT_FORMATS", frozenset())
        quads = outcome(document)
    if isinstance(text, str) or isinstance(quads, str):
        assert text == quads
    else:
        assert_same(text, quads)


# ------------------------------------------------------------------------------------ the worker thread
def test_a_lone_piece_is_loaded_in_the_calling_thread() -> None:
    loaded: list[tuple[bytes, str]] = []
    with TextWriter(lambda t: loaded.append((t, threading.current_thread().name))) as writer:
        writer.write(b"one")
        assert loaded == []
    assert loaded == [(b"one", threading.current_thread().name)]


def test_pieces_are_loaded_in_order_by_the_worker_before_the_end() -> None:
    loaded: list[tuple[bytes, str]] = []
    with TextWriter(lambda t: loaded.append((t, threading.current_thread().name)), lambda: True) as writer:
        for n in range(20):
            writer.write(str(n).encode())
    assert [t for t, _ in loaded] == [str(n).encode() for n in range(20)]
    assert {name for _, name in loaded} == {"topostore-text-load"}


def test_the_workers_failure_is_raised_in_the_caller_and_stops_the_loads() -> None:
    loaded: list[bytes] = []

    def load(text: bytes) -> None:
        if text == b"2":
            raise OSError("disk full")
        loaded.append(text)

    with pytest.raises(OSError, match="disk full"):
        with TextWriter(load, lambda: True) as writer:
            for n in range(10):
                writer.write(str(n).encode())
    assert loaded == [b"0", b"1"]
    assert not [t for t in threading.enumerate() if t.name == "topostore-text-load"]


def test_a_failing_caller_waits_for_the_worker_and_loads_no_piece_still_queued() -> None:
    started, release = threading.Event(), threading.Event()
    loaded: list[bytes] = []

    def load(text: bytes) -> None:
        started.set()
        release.wait(5)
        loaded.append(text)

    with pytest.raises(RuntimeError, match="parse failed"):
        with TextWriter(load, lambda: True) as writer:
            writer.write(b"0")
            writer.write(b"1")  # the worker starts on "0"
            started.wait(5)
            writer.write(b"2")  # queued behind "0"
            release.set()
            raise RuntimeError("parse failed")
    assert loaded[:1] == [b"0"] and b"2" not in loaded
    assert not [t for t in threading.enumerate() if t.name == "topostore-text-load"]


@pytest.mark.parametrize(("answers", "inline"), [([False] * 9, 10), ([None, None, True], 2), ([None] * 9, 10)])
def test_the_worker_starts_only_once_a_core_is_known_to_be_free(answers: list, inline: int) -> None:
    """Busy cores (False) or not yet known (None): each piece loaded in the calling thread, in order; from
    the first True on, by the worker."""
    loaded: list[tuple[bytes, str]] = []
    asked = iter(answers)
    with TextWriter(lambda t: loaded.append((t, threading.current_thread().name)), lambda: next(asked)) as writer:
        for n in range(10):
            writer.write(str(n).encode())
    assert [t for t, _ in loaded] == [str(n).encode() for n in range(10)]
    here = threading.current_thread().name
    assert [name == here for _, name in loaded] == [True] * inline + [False] * (10 - inline)


def test_a_free_core_is_read_from_the_machines_counters_less_this_process() -> None:
    cores = os.cpu_count() or 1
    idle, busy = [0, 0, 0, 100 * cores, 0, 0, 0], [100 * cores, 0, 0, 0, 0, 0, 0]
    assert busy_cores([0] * 7, idle) == 0.0 and busy_cores([0] * 7, busy) == cores
    assert spare(0.4) == (cores >= 2) and not spare(cores - 1.0)
    assert CoreWatch().free() is (None if cpu_times() is not None else False)  # no window read yet, or no counters


def test_a_busy_spell_says_busy_for_its_own_window_only(monkeypatch: pytest.MonkeyPatch) -> None:
    """A second of every core busy, then a second of every core idle: the first answer is busy, the second
    free (a window from the creation on still read one core busy of two, and said busy to the end)."""
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    readings = iter([[0, 0, 0, 0, 0], [200, 0, 0, 0, 0], [200, 0, 0, 200, 0], [400, 0, 0, 200, 0]])
    clock = iter([0.0, 1.0, 2.0, 3.0])
    watch = CoreWatch(lambda: next(readings), lambda: next(clock), lambda: 0.0)
    assert [watch.free(), watch.free(), watch.free()] == [False, True, False]
