"""A big first document parsed in a child process gives what the in-process stream gives.

:mod:`topostore.ontology.streamed_child` is taken for documents of ``CHILD_FROM`` bytes or more; here the
threshold is lowered so that small documents take it.  Both ways must store the same triples, keep the same
literal spellings, count and report the same, refuse the same documents with the same messages leaving
nothing behind, and leave no child process running.
"""

from __future__ import annotations

import logging
import re
import subprocess
import sys
from pathlib import Path

import pytest
from pyoxigraph import NamedNode
from test_load_streamed import DOCUMENT, ENTITY_DOCUMENT, PREFIXES, loaded, shape

from topostore import InvalidValueError, LoadError, Ontology
from topostore.ontology import files as files_module
from topostore.ontology import streamed_child
from topostore.rdf.vocab import ASSERTED

A = "http://e.org/a#"


@pytest.fixture
def children(monkeypatch: pytest.MonkeyPatch) -> list[subprocess.Popen]:
    """Every document through the child; the children started, to see that none is left running."""
    started: list[subprocess.Popen] = []
    real = subprocess.Popen

    def popen(*args, **kwargs) -> subprocess.Popen:
        started.append(real(*args, **kwargs))
        return started[-1]

    monkeypatch.setattr(streamed_child, "CHILD_FROM", 0)
    monkeypatch.setattr(streamed_child, "ENABLED", True)
    monkeypatch.setattr(streamed_child, "core_free", lambda: True)
    monkeypatch.setattr(streamed_child.subprocess, "Popen", popen)
    return started


def all_ended(started: list[subprocess.Popen]) -> bool:
    return all(p.returncode is not None for p in started)


def test_child_and_in_process_streams_leave_the_same_ontology(children, monkeypatch: pytest.MonkeyPatch) -> None:
    by_child, n_child, said_child = loaded(DOCUMENT, stream=True)
    assert len(children) == 1 and all_ended(children)
    monkeypatch.setattr(streamed_child, "ENABLED", False)
    here, n_here, said_here = loaded(DOCUMENT, stream=True)
    assert len(children) == 1
    assert n_child == n_here
    assert shape(by_child) == shape(here)
    assert said_child == said_here and any("XMLLiteral" in s for s in said_child)
    assert by_child.notices == here.notices and by_child.load_notices == here.load_notices
    assert by_child.serialize("turtle").count(b"\n") == here.serialize("turtle").count(b"\n")
    place = NamedNode(A + "Place")
    assert by_child.reason().consistent
    assert by_child.instances(place) == [NamedNode(A + "r1"), NamedNode(A + "r2")]


def saved_lines(onto: Ontology, path: Path) -> list[str]:
    """The N-Triples SAVE writes, blank node names aside."""
    onto.save(path)
    return sorted(re.sub(r"_:\w+", "_:b", line) for line in path.read_text().splitlines())


def test_saved_literal_spellings_are_the_first_ones_written(children, monkeypatch: pytest.MonkeyPatch,
                                                            tmp_path: Path) -> None:
    text = (PREFIXES + ':a :p "01"^^xsd:int , "1"^^xsd:int , "1"^^xsd:integer , "01"^^xsd:int ; '
            ':q "0.50"^^xsd:decimal , "x"@en , "x" . _:b :p "002"^^xsd:integer ; :q "1e0"^^xsd:double .')
    onto, n, _ = loaded(text, stream=True)
    assert len(children) == 1 and n == 6  # the facts stored: a value once, whatever its spellings
    assert len(onto.files.spelling_notes) == 2 and all("01" in note for note in onto.files.spelling_notes)
    by_child = saved_lines(onto, tmp_path / "child.nt")
    xsd = "<http://www.w3.org/2001/XMLSchema#"
    for spelled in ('"01"^^' + xsd + "int>", '"0.50"^^' + xsd + "decimal>", '"002"^^' + xsd + "integer>",
                    '"1e0"^^' + xsd + "double>"):
        assert any(spelled in line for line in by_child), spelled
    assert not any('"1"^^' + xsd + "int>" in line for line in by_child)
    monkeypatch.setattr(streamed_child, "ENABLED", False)
    here, _, _ = loaded(text, stream=True)
    assert saved_lines(here, tmp_path / "here.nt") == by_child
    assert here.files.spelling_notes == onto.files.spelling_notes  # the child's later spellings are said alike


@pytest.mark.parametrize(("text", "error", "message"), [
    (PREFIXES + ':a :p "abc"^^xsd:integer . :b :q :c .', InvalidValueError, "abc"),
    (PREFIXES + "".join(f":i{n} :p :i{n + 1} .\n" for n in range(20_000)) + ":a :p", LoadError,
     r"<data>:20005: not valid Turtle"),
    (PREFIXES + "".join(f":i{n} :p [ :q {n} ] .\n" for n in range(20_000)) + ':z :p "1"^^xsd:nope nope .',
     LoadError, r"<data>:20005: not valid Turtle"),
])
def test_a_refused_document_gives_the_same_error_and_leaves_nothing(children, text: str, error: type,
                                                                    message: str) -> None:
    onto = Ontology()
    with pytest.raises(error, match=message):
        onto.load_data(text, "turtle")
    assert len(children) == 1 and all_ended(children)
    assert onto.store.count(ASSERTED) == 0 and onto.store.forms._literal_forms == {}
    assert onto.load_data(PREFIXES + ':a :p "5"^^xsd:long .', "turtle") == 1


def test_entity_declarations_are_refused_in_the_child(children, tmp_path: Path) -> None:
    path = tmp_path / "entities.owl"
    path.write_text(ENTITY_DOCUMENT)
    onto = Ontology()
    with pytest.raises(LoadError, match="external or parameter entity 'e' refused"):
        onto.load(path)
    assert len(children) == 1 and all_ended(children) and onto.store.count(ASSERTED) == 0


@pytest.mark.parametrize("script", [
    "import sys; sys.stdout.write('<http://e.org/a#a> <http://e.org/a#p'); sys.stdout.flush(); sys.exit(3)",
    "import sys; sys.exit(0)",
    "import os, signal; os.kill(os.getpid(), signal.SIGKILL)",
])
def test_a_child_that_dies_leaves_the_document_to_the_ordinary_load(children, monkeypatch: pytest.MonkeyPatch,
                                                                     caplog: pytest.LogCaptureFixture,
                                                                     script: str) -> None:
    monkeypatch.setattr(streamed_child, "_command", lambda *args: [sys.executable, "-c", script])
    with caplog.at_level(logging.WARNING, logger=streamed_child.__name__):
        onto, n, _ = loaded(DOCUMENT, stream=True)
    assert len(children) == 1 and all_ended(children)
    here, n_here, _ = loaded(DOCUMENT, stream=False)
    assert n == n_here and shape(onto) == shape(here)
    assert "parsed the ordinary way" in caplog.text


def test_no_child_process_to_start_leaves_the_document_to_the_ordinary_load(monkeypatch: pytest.MonkeyPatch,
                                                                           caplog: pytest.LogCaptureFixture) -> None:
    def refuse(*args, **kwargs):
        raise OSError("no processes left")

    monkeypatch.setattr(streamed_child, "CHILD_FROM", 0)
    monkeypatch.setattr(streamed_child, "ENABLED", True)
    monkeypatch.setattr(streamed_child, "core_free", lambda: True)
    monkeypatch.setattr(streamed_child.subprocess, "Popen", refuse)
    with caplog.at_level(logging.WARNING, logger=streamed_child.__name__):
        onto, n, _ = loaded(DOCUMENT, stream=True)
    here, n_here, _ = loaded(DOCUMENT, stream=False)
    assert n == n_here and shape(onto) == shape(here) and "no processes left" in caplog.text


def test_progress_is_told_as_the_child_writes(children, tmp_path: Path) -> None:
    path = tmp_path / "big.ttl"
    path.write_text(PREFIXES + " ".join(f":i{n} :p :i{n + 1} ." for n in range(12_000)))
    told: list[int] = []
    assert Ontology().load(path, progress=told.append) == 12_000
    assert told and told == sorted(told) and all(n % 5000 == 0 for n in told) and told[-1] == 10_000
    assert len(children) == 1


def test_small_documents_and_other_stores_stay_in_process(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    taken: list[int] = []
    monkeypatch.setattr(files_module, "stream_through_child", lambda *a, **k: taken.append(1))
    onto = Ontology()
    onto.load_data(PREFIXES + ":a :p :b .", "turtle")
    assert taken == [] and onto.store.count(ASSERTED) == 1
    big = PREFIXES + " " * streamed_child.CHILD_FROM
    for free in (True, False):
        monkeypatch.setattr(streamed_child, "core_free", lambda free=free: free)
        assert streamed_child.child_wanted(Ontology().store, big) == (streamed_child.ENABLED and free)
    monkeypatch.setattr(streamed_child, "core_free", lambda: True)
    assert not streamed_child.child_wanted(Ontology().store, big[:streamed_child.CHILD_FROM - 1])
    from topostore.stores import open_store

    durable = open_store(str(tmp_path / "db"))
    assert not streamed_child.child_wanted(durable, big)


#: terms whose N-Triples text must read back as they were: escapes, a NUL, an astral character, a line
#: separator, an empty language string, an unknown datatype, a triple term, a base direction, IRI escapes
ODD_TERMS = [
    PREFIXES + ':a :p "x\\u0000y\\ttab\\nnl \\\\ back \\"q\\" \\U0001F600" , ""@en , "ab"@en-GB , '
               '"5"^^<http://e.org/dt> , "a\\u2028b" .',
    PREFIXES + ":a :p <<( :s :p :o )>> .",
    PREFIXES + ':a :p "x"@en--ltr .',
    PREFIXES + "<http://e.org/a#%20x> :p <http://e.org/\u00e9> .",
]


@pytest.mark.parametrize("text", ODD_TERMS)
def test_odd_terms_read_back_through_the_text_as_the_ordinary_load_keeps_them(
        children, monkeypatch: pytest.MonkeyPatch, text: str) -> None:
    """Both the child and the in-process stream write N-Triples text the store reads back."""
    by_child, n_child, _ = loaded(text, stream=True)
    assert len(children) == 1
    here, n, _ = loaded(text, stream=False)
    assert n_child == n and shape(by_child) == shape(here)
    monkeypatch.setattr(streamed_child, "ENABLED", False)
    in_process, n_in_process, _ = loaded(text, stream=True)
    assert len(children) == 1 and n_in_process == n and shape(in_process) == shape(here)


def test_a_free_core_is_seen_from_the_other_processes_work(monkeypatch: pytest.MonkeyPatch) -> None:
    """core_free reads the machine's CPU counters while this process sleeps: its own busy minute (a map
    just made, a document just read), which the load average would count, does not take the child away."""
    monkeypatch.setattr(streamed_child.os, "cpu_count", lambda: 2)
    monkeypatch.setattr(streamed_child.time, "sleep", lambda s: None)
    reads = iter([[100, 0, 100, 800, 0, 0, 0], [110, 0, 100, 990, 0, 0, 0]])
    monkeypatch.setattr(streamed_child, "_cpu_times", lambda: next(reads))
    assert streamed_child.core_free()  # 10 of 200 ticks busy: 0.1 of a core
    reads = iter([[0, 0, 0, 100, 0], [90, 0, 0, 110, 0]])  # 90 of 100 ticks busy: 1.8 cores
    monkeypatch.setattr(streamed_child, "_cpu_times", lambda: next(reads))
    assert not streamed_child.core_free()
    monkeypatch.setattr(streamed_child, "_cpu_times", lambda: None)
    monkeypatch.setattr(streamed_child.os, "getloadavg", lambda: (1.2, 1.0, 1.0))
    assert streamed_child.core_free()  # no counters: the load average less this process's own core


def test_a_child_that_hangs_is_killed_at_its_deadline(children, monkeypatch: pytest.MonkeyPatch, tmp_path: Path,
                                                     caplog: pytest.LogCaptureFixture) -> None:
    """A stopped child (SIGSTOP: it neither writes nor ends) is killed at its deadline, and the document is
    loaded the ordinary way: LOAD is bounded in time."""
    import os
    import signal

    real = streamed_child.subprocess.Popen

    def stopped(*args, **kwargs) -> subprocess.Popen:
        proc = real(*args, **kwargs)
        os.kill(proc.pid, signal.SIGSTOP)
        return proc

    assert streamed_child.child_deadline(100_000_000) == pytest.approx(130.0)  # 100 MB: minutes, not hours
    monkeypatch.setattr(streamed_child.subprocess, "Popen", stopped)
    monkeypatch.setattr(streamed_child, "CHILD_MIN_SECONDS", 0.5)
    monkeypatch.setattr(streamed_child, "CHILD_SECONDS_PER_MB", 0.0)
    path = tmp_path / "h.nt"
    path.write_text("".join(f'<{A}s{i}> <{A}p> "v{i}" .\n' for i in range(1000)))
    with caplog.at_level(logging.WARNING, logger=streamed_child.__name__):
        onto = Ontology(prefix=A)
        onto.load(path)
    assert len(list(onto.store.triples(graph=ASSERTED))) == 1000
    assert any("did not finish" in r.getMessage() for r in caplog.records)


@pytest.mark.parametrize(("setting", "enabled"), [(None, False), ("0", False), ("auto", True), ("1", True)])
def test_the_child_is_off_unless_asked_for(setting: str | None, enabled: bool) -> None:
    """On two cores the child lost to the in-process load (7.6-8.1 against 5.8-6.1 s at 100,000 locations):
    it is taken only when ``TOPOSTORE_LOAD_CHILD`` asks for it."""
    import os

    env = {k: v for k, v in os.environ.items() if k != "TOPOSTORE_LOAD_CHILD"}
    if setting is not None:
        env["TOPOSTORE_LOAD_CHILD"] = setting
    out = subprocess.run([sys.executable, "-c", "from topostore.ontology import streamed_child as c; print(c.ENABLED)"],
                         env=env, capture_output=True, text=True, timeout=60, check=True)
    assert out.stdout.strip() == str(enabled)
