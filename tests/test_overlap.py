"""The one module that runs a second thread (topostore.stores.overlap) and its user: a full REASON's
census and checks beside its publication, its asserted graph counted beside its rules."""

from __future__ import annotations

import threading
from collections import Counter

import pytest
from pyoxigraph import Literal, NamedNode, Quad

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, SKOLEM_PREFIX
from topostore.reason import closing, early_reads
from topostore.stores import memory_store
from topostore.stores.overlap import Beside, Reader

EX = "http://example.org/o#"


def _threads() -> set[threading.Thread]:
    return set(threading.enumerate())


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


def _shape(onto: Ontology, graph) -> Counter:
    """The triples of ``graph`` (None: every graph), each skolem IRI (named apart per document) as one
    placeholder."""
    def term(t):
        return "_:b" if isinstance(t, NamedNode) and t.value.startswith(SKOLEM_PREFIX) else t
    return Counter((term(t.subject), t.predicate, term(t.object)) for t in onto.store.triples(graph=graph))


def test_a_full_reason_with_checks_beside_equals_the_sequential_one(tmp_path, monkeypatch):
    path = tmp_path / "chain.ttl"
    path.write_text(_chain(200) + "\n:p3 a :Door .")  # a Place that is a Door: one violation
    answers = []
    for overlap in (False, True):
        monkeypatch.setattr(closing, "Beside", lambda read, overlap=True, _o=overlap: Beside(read, overlap and _o))
        monkeypatch.setattr(early_reads, "ENABLED", overlap)
        onto = Ontology()
        onto.load(path)
        report = onto.reason(mode="full")
        answers.append((report.stats.derived, [str(v) for v in report.violations],
                        onto._reasoner.state.asserted_size, _shape(onto, None)))
    assert answers[0] == answers[1]
    assert answers[0][1], "the disjointness violation is found"


def test_a_full_reason_reads_in_a_worker_thread_and_joins_it(tmp_path, monkeypatch):
    path = tmp_path / "chain.ttl"
    path.write_text(_chain(50))
    onto = Ontology()
    onto.load(path)
    where = []
    checks = closing.check_consistency
    monkeypatch.setattr(closing, "check_consistency",
                        lambda *a: where.append(threading.current_thread()) or checks(*a))
    before = _threads()
    onto.reason(mode="full")
    assert where and where[0] is not threading.current_thread()
    assert _threads() == before


def test_a_failing_check_in_the_worker_fails_the_reason(tmp_path, monkeypatch):
    path = tmp_path / "chain.ttl"
    path.write_text(_chain(50))
    onto = Ontology()
    onto.load(path)

    def broken(*args):
        raise RuntimeError("check failed")

    monkeypatch.setattr(closing, "check_consistency", broken)
    before = _threads()
    with pytest.raises(RuntimeError, match="check failed"):
        onto.reason(mode="full")
    assert _threads() == before
    monkeypatch.undo()
    assert onto.reason(mode="full").consistent  # the next REASON recomputes from scratch


def test_a_shared_read_is_run_by_the_caller_waiting_for_the_one_ahead_of_it():
    """While the worker is on a long read, the caller about to wait runs the shared reads queued behind it
    itself, once each; a cancelled one is run by neither; one left untaken is dropped with the reader."""
    release = threading.Event()
    ran: list[tuple[str, threading.Thread]] = []

    def read(name):
        ran.append((name, threading.current_thread()))
        return name

    with Reader() as reader:
        long = reader.submit(lambda: release.wait(5) and read("long"))
        shared = reader.submit(lambda: read("shared"), shared=True)
        dropped = reader.submit(lambda: read("dropped"), shared=True)
        assert dropped.cancel()
        reader.help()
        assert shared.result(timeout=0) == "shared"
        release.set()
        assert long.result(timeout=5) == "long"
    assert [name for name, _ in ran] == ["shared", "long"]
    assert ran[0][1] is threading.current_thread() and ran[1][1] is not threading.current_thread()
    later = threading.Event()
    with Reader() as reader:
        reader.submit(lambda: later.wait(5))
        untaken = reader.submit(lambda: read("behind"), shared=True)
        threading.Timer(0.2, later.set).start()
    assert untaken.cancelled() and len(ran) == 2


def test_a_shared_read_failing_in_the_caller_raises_where_it_is_read():
    with Reader() as reader:
        reader.submit(lambda: threading.Event().wait(0.2))
        failing = reader.submit(lambda: 1 / 0, shared=True)
        reader.help()
        with pytest.raises(ZeroDivisionError):
            failing.result(timeout=0)
