"""The one module that runs a second thread (topostore.stores.overlap) and its two users: a streamed load
written chunk by chunk while the next chunk is parsed, and a full REASON's checks beside its publication."""

from __future__ import annotations

import threading
from collections import Counter

import pytest
from pyoxigraph import Literal, NamedNode, Quad

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, INFERRED, SKOLEM_PREFIX
from topostore.reason import closing
from topostore.stores import memory_store
from topostore.stores.overlap import Beside, pipelined_extend

EX = "http://example.org/o#"


def _threads() -> set[threading.Thread]:
    return set(threading.enumerate())


def test_pipelined_extend_writes_every_quad_in_order_one_at_a_time():
    written: list[list[int]] = []
    busy = threading.Lock()

    def write(batch: list[int]) -> None:
        assert busy.acquire(blocking=False), "two writes at once"
        try:
            written.append(batch)
        finally:
            busy.release()

    before = _threads()
    pipelined_extend(write, iter(range(10)), chunk=3)
    assert [x for b in written for x in b] == list(range(10))
    assert [len(b) for b in written] == [3, 3, 3, 1]
    assert _threads() == before


@pytest.mark.parametrize("n", [0, 1, 3])
def test_pipelined_extend_of_one_chunk_stays_in_the_callers_thread(n):
    caller = threading.current_thread()
    seen = []
    pipelined_extend(lambda b: seen.append((threading.current_thread(), b)), range(n), chunk=3)
    assert seen == ([(caller, list(range(n)))] if n else [])


def test_pipelined_extend_propagates_an_error_of_the_input_and_joins_its_thread():
    written: list[int] = []

    def quads():
        yield from range(7)
        raise ValueError("bad literal")

    before = _threads()
    with pytest.raises(ValueError, match="bad literal"):
        pipelined_extend(written.extend, quads(), chunk=3)
    # whole chunks made before the error, in order (the caller empties the graph)
    assert written == list(range(len(written))) and len(written) % 3 == 0
    assert _threads() == before


def test_pipelined_extend_propagates_an_error_of_a_write():
    def write(batch):
        if batch[0] == 3:
            raise OSError("disk full")

    before = _threads()
    with pytest.raises(OSError, match="disk full"):
        pipelined_extend(write, range(10), chunk=3)
    assert _threads() == before


def test_beside_runs_in_another_thread_and_joins_it():
    caller = threading.current_thread()
    before = _threads()
    with Beside(lambda: threading.current_thread()) as side:
        pass
    assert side.result() is not caller
    assert _threads() == before


def test_beside_without_overlap_runs_first_in_the_callers_thread():
    order = []
    with Beside(lambda: order.append("read") or threading.current_thread(), overlap=False) as side:
        order.append("write")
    assert order == ["read", "write"]
    assert side.result() is threading.current_thread()


def test_beside_propagates_the_readers_error_and_the_callers_error_wins():
    with Beside(lambda: 1 / 0) as side:
        pass
    with pytest.raises(ZeroDivisionError):
        side.result()
    before = _threads()
    with pytest.raises(KeyError):
        with Beside(lambda: 1 / 0):
            raise KeyError("the write failed")
    assert _threads() == before


def test_beside_result_is_read_after_the_block():
    with Beside(lambda: 1) as side:
        with pytest.raises(RuntimeError, match="after its with block"):
            side.result()
    assert side.result() == 1


def test_a_store_overlaps_in_memory_only_outside_a_transaction():
    store = memory_store()
    assert store.overlaps
    with store.transaction():
        store.add([Quad(NamedNode(EX + "a"), NamedNode(EX + "p"), Literal("1"), ASSERTED).triple], ASSERTED)
        assert not store.overlaps
    assert store.overlaps


def _chain(n: int) -> str:
    lines = [f"@prefix : <{EX}> .", "@prefix owl: <http://www.w3.org/2002/07/owl#> .",
             "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .",
             "@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .",
             ":next a owl:ObjectProperty ; rdfs:domain :Place ; rdfs:range :Place .",
             ":Door owl:disjointWith :Place .", ":hasDoor rdfs:range :Door ."]
    for i in range(n):
        lines.append(f":p{i} :next :p{i + 1} ; :label \"{i:02d}\"^^xsd:integer ; :hasDoor [ :width {i} ] .")
    return "\n".join(lines)


def test_a_streamed_load_of_many_chunks_equals_one_write(tmp_path, monkeypatch):
    path = tmp_path / "chain.ttl"
    path.write_text(_chain(200))
    one = Ontology()
    monkeypatch.setattr("topostore.stores.overlap.CHUNK", 10**9)
    n_one = one.load(path)
    monkeypatch.undo()
    monkeypatch.setattr("topostore.stores.oxigraph.pipelined_extend",
                        lambda write, quads: pipelined_extend(write, quads, chunk=50))
    many = Ontology()
    n_many = many.load(path)
    assert n_one == n_many
    assert _shape(many, ASSERTED) == _shape(one, ASSERTED)
    one.reason()
    many.reason()
    assert _shape(many, INFERRED) == _shape(one, INFERRED)


def _shape(onto: Ontology, graph) -> Counter:
    """The triples of ``graph``, each skolem IRI (named apart per document) as one placeholder."""
    def term(t):
        return "_:b" if isinstance(t, NamedNode) and t.value.startswith(SKOLEM_PREFIX) else t
    return Counter((term(t.subject), t.predicate, term(t.object)) for t in onto.store.triples(graph=graph))


def test_a_streamed_load_failing_in_a_later_chunk_leaves_nothing(tmp_path, monkeypatch):
    text = _chain(200) + '\n:bad :label "x"^^xsd:integer .'
    path = tmp_path / "bad.ttl"
    path.write_text(text)
    monkeypatch.setattr("topostore.stores.oxigraph.pipelined_extend",
                        lambda write, quads: pipelined_extend(write, quads, chunk=50))
    onto = Ontology()
    before = _threads()
    with pytest.raises(Exception, match="(?i)integer|invalid"):
        onto.load(path)
    assert next(iter(onto.store.triples(graph=ASSERTED)), None) is None
    assert _threads() == before


def test_a_full_reason_with_checks_beside_equals_the_sequential_one(tmp_path, monkeypatch):
    path = tmp_path / "chain.ttl"
    path.write_text(_chain(200) + "\n:p3 a :Door .")  # a Place that is a Door: one violation
    answers = []
    for overlap in (False, True):
        monkeypatch.setattr(closing, "Beside", lambda read, overlap=True, _o=overlap: Beside(read, overlap and _o))
        onto = Ontology()
        onto.load(path)
        report = onto.reason(mode="full")
        answers.append((report.stats.derived, [str(v) for v in report.violations],
                        onto._reasoner.state.asserted_size, _shape(onto, None)))
    assert answers[0] == answers[1]
    assert answers[0][1], "the disjointness violation is found"
