"""Deferred asks started early in a worker thread (topostore.reason.early_reads): the same closure as
asking them at the first stratum's fixpoint, their early answer used only while it holds."""

from __future__ import annotations

import threading
from collections import Counter

import pytest
from test_incremental import new_map

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, AUX, ENTAILED, INFERRED
from topostore.reason import closing, early_reads, incremental
from topostore.reason.early_reads import EarlyReads, ask_form


def _graphs(onto) -> Counter:
    """The asserted, inferred, helper and entailed-only graphs."""
    return Counter((g, t) for g in (ASSERTED, INFERRED, AUX, ENTAILED) for t in onto.store.triples(graph=g))


def _logged(monkeypatch) -> list[tuple]:
    """Every early start and answer of the runs that follow."""
    log: list[tuple] = []
    after, answer = EarlyReads.after, EarlyReads.answer

    def logged_after(self, c):
        started = list(self._asks_after.get(c, ()))
        after(self, c)
        log.extend(("start", i) for i in started if i in self._asked)

    def logged_answer(self, i):
        got = answer(self, i)
        log.append(("answer", i, got))
        return got

    monkeypatch.setattr(EarlyReads, "after", logged_after)
    monkeypatch.setattr(EarlyReads, "answer", logged_answer)
    return log


def test_ask_form_of_an_evaluation_text():
    text = "INSERT { GRAPH <g:i> { ?x a <c:C> } }\nUSING <g:a> USING NAMED <g:x>\nWHERE {\n  ?x <p:p> ?y\n}"
    assert ask_form(text) == "ASK FROM <g:a> FROM NAMED <g:x>\nWHERE {\n  ?x <p:p> ?y\n}"
    with pytest.raises(ValueError):
        ask_form("SELECT * WHERE { ?s ?p ?o }\nx\nWHERE {}")


@pytest.mark.parametrize("grouped", [True, False])
def test_an_early_ask_gives_the_closure_of_a_late_one(monkeypatch, grouped):
    """Grouped: every link declared, the ask finds nothing and is skipped; plain: it finds pairs and its
    insert is sent.  Both equal a run without the second thread."""
    log = _logged(monkeypatch)
    early = new_map(12, 3, grouped)
    early.reason(mode="full")
    answers = [e for e in log if e[0] == "answer"]
    assert ("start", answers[0][1]) in log and answers[0][2] is (not grouped)
    monkeypatch.setattr(early_reads, "ENABLED", False)
    late = new_map(12, 3, grouped)
    late.reason(mode="full")
    assert _graphs(early) == _graphs(late)
    assert early.reason(mode="full").stats.derived == late.reason(mode="full").stats.derived


def test_an_early_answer_is_not_used_once_a_key_it_reads_is_written(monkeypatch):
    after = EarlyReads.after
    dropped = []

    def after_then_write(self, c):
        after(self, c)
        for i in list(self._asked):
            self.wrote(self.run.rules[i].unless_known.read_key())  # as if a later rule wrote its conclusion
            dropped.append(i)

    monkeypatch.setattr(EarlyReads, "after", after_then_write)
    log = _logged(monkeypatch)
    onto = new_map(12, 3, False)
    before = set(threading.enumerate())
    onto.reason(mode="full")
    assert dropped and all(e[2] is None for e in log if e[0] == "answer")
    assert set(threading.enumerate()) == before
    monkeypatch.setattr(early_reads, "ENABLED", False)
    late = new_map(12, 3, False)
    late.reason(mode="full")
    assert _graphs(onto) == _graphs(late)


def test_no_early_ask_without_the_second_thread(monkeypatch):
    monkeypatch.setattr(early_reads, "ENABLED", False)
    log = _logged(monkeypatch)
    new_map(12, 3, True).reason(mode="full")
    assert not [e for e in log if e[0] == "start"]


_TTL = """@prefix : <http://example.org/o#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
:next a owl:ObjectProperty ; rdfs:domain :Place ; rdfs:range :Place .
:hasDoor a owl:ObjectProperty ; rdfs:range :Door .
:Door owl:disjointWith :Place .
:visitedAt a owl:DatatypeProperty, owl:FunctionalProperty .
:p0 :next :p1 ; :hasDoor :p2 ; :visitedAt 1, 2 .
:p1 :next :p2 .
:p3 a :Door .
"""


def _reasoned(tmp_path, monkeypatch, seen: list) -> tuple[list[str], dict]:
    """The violations of a full REASON of :data:`_TTL`, and the checks' matches found beside its rules."""
    path = tmp_path / "doors.ttl"
    path.write_text(_TTL)
    close = closing.close_full

    def close_full(*args):
        seen.append(dict(args[4] or {}))
        return close(*args)

    monkeypatch.setattr(incremental, "close_full", close_full)
    onto = Ontology()
    onto.load(path)
    report = onto.reason(mode="full")
    return sorted(str(v) for v in report.violations), seen[-1]


def test_checks_run_beside_the_rules_find_what_late_ones_find(tmp_path, monkeypatch):
    early, checked = _reasoned(tmp_path, monkeypatch, [])
    assert checked, "some checks ran beside the rules"
    assert any("p2" in v for v in early) and any("visitedAt" in v or "p0" in v for v in early)
    monkeypatch.setattr(early_reads, "ENABLED", False)
    late, none = _reasoned(tmp_path, monkeypatch, [])
    assert not none and late == early


def test_a_check_whose_key_is_written_after_its_start_runs_again(tmp_path, monkeypatch):
    after = EarlyReads.after

    def after_then_write(self, c):
        after(self, c)
        for j in list(self._checking):
            for key in self._check_reads[j]:
                self.wrote(key)

    monkeypatch.setattr(EarlyReads, "after", after_then_write)
    before = set(threading.enumerate())
    early, checked = _reasoned(tmp_path, monkeypatch, [])
    assert not checked and set(threading.enumerate()) == before
    monkeypatch.setattr(early_reads, "ENABLED", False)
    late, _ = _reasoned(tmp_path, monkeypatch, [])
    assert late == early and early


def test_what_a_write_touches():
    from topostore.reason.order import TYPE_KEY
    from topostore.reason.read_keys import touches as _touches

    door, place, link = ("t", "<c:Door>"), ("t", "<c:Place>"), ("p", "<p:link>")
    assert _touches(door, {door}) and not _touches(door, {place, link})
    assert _touches(door, {("p", TYPE_KEY)})  # ?x a ?c reads every class
    assert _touches(("p", TYPE_KEY), {place}) and not _touches(("p", TYPE_KEY), {link})
    assert _touches(("*",), {link}) and _touches(link, {("*",)}) and not _touches(None, {link})


def test_the_writes_index_answers_as_every_writer_asked_in_turn():
    """`_Writes.last` (indexed by key) gives the last writer `_touches` finds by asking each writer."""
    import random

    from topostore.reason.order import TYPE_KEY
    from topostore.reason.read_keys import ANY as _ANY
    from topostore.reason.read_keys import Writes as _Writes
    from topostore.reason.read_keys import touches as _touches

    keys = [("t", f"<c:{n}>") for n in range(4)] + [("p", f"<p:{n}>") for n in range(3)] + [("p", TYPE_KEY)]
    rng = random.Random(7)
    for _ in range(400):
        written = [(rng.randrange(6), rng.choice([*keys, None, ("*",)])) for _ in range(rng.randrange(8))]
        reads = set(rng.sample([*keys, _ANY], rng.randrange(1, 4)))
        expected = max((pos for pos, key in written if _touches(key, reads)), default=-1)
        assert _Writes(written).last(reads) == expected, (written, reads)


def test_past_the_bound_every_check_runs_after_the_run(tmp_path, monkeypatch):
    """With more checks than EARLY_CHECKS none starts early, and the violations are the same."""
    monkeypatch.setattr(early_reads, "EARLY_CHECKS", 0)
    bounded, checked = _reasoned(tmp_path, monkeypatch, [])
    assert not checked and bounded
    monkeypatch.setattr(early_reads, "ENABLED", False)
    late, _ = _reasoned(tmp_path, monkeypatch, [])
    assert late == bounded


def test_checks_the_worker_has_not_started_are_run_by_the_waiting_thread(monkeypatch):
    """The worker held on the AllDifferent keys: the thread waiting for them runs the checks queued behind
    them that read nothing an early evaluation writes, and the REASON finds what it finds without that."""
    from support import closure, map_or_text

    from topostore.reason import early_rules

    evaluate, checks = early_rules._evaluate, early_reads.check_rows
    ran: list[tuple[str, bool]] = []

    def slow(store, query, graph):
        threading.Event().wait(0.3)  # the keys, as at 100,000 locations, still under way at their turn
        return evaluate(store, query, graph)

    def check_rows(store, rule, keys):
        ran.append((rule.name, threading.current_thread() is threading.main_thread()))
        return checks(store, rule, keys)

    monkeypatch.setattr(early_rules, "_evaluate", slow)
    monkeypatch.setattr(early_reads, "check_rows", check_rows)
    onto = map_or_text()
    report = onto.reason(mode="full")
    assert any(main for _, main in ran), ran
    shared = closure(onto), sorted(map(str, report.violations))
    monkeypatch.setattr(early_reads.EarlyReads, "_shared", lambda self, reads: False)
    ran.clear()
    report = onto.reason(mode="full")
    assert not any(main for _, main in ran), ran
    assert (closure(onto), sorted(map(str, report.violations))) == shared
