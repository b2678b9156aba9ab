"""Deferred asks started early in a worker thread (topostore.reason.early_asks): the same closure as
asking them at the first stratum's fixpoint, their early answer used only while it holds."""

from __future__ import annotations

import threading
from collections import Counter

import pytest
from test_incremental import new_map

from topostore.rdf.vocab import ASSERTED, AUX, ENTAILED, INFERRED
from topostore.reason import early_asks
from topostore.reason.early_asks import EarlyAsks, ask_form


def _graphs(onto) -> Counter:
    """The asserted, inferred, helper and entailed-only graphs."""
    return Counter((g, t) for g in (ASSERTED, INFERRED, AUX, ENTAILED) for t in onto.store.triples(graph=g))


def _logged(monkeypatch) -> list[tuple]:
    """Every early start and answer of the runs that follow."""
    log: list[tuple] = []
    after, answer = EarlyAsks.after, EarlyAsks.answer

    def logged_after(self, c):
        started = list(self._start_after.get(c, ()))
        after(self, c)
        log.extend(("start", i) for i in started if i in self._started)

    def logged_answer(self, i):
        got = answer(self, i)
        log.append(("answer", i, got))
        return got

    monkeypatch.setattr(EarlyAsks, "after", logged_after)
    monkeypatch.setattr(EarlyAsks, "answer", logged_answer)
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
    monkeypatch.setattr(early_asks, "ENABLED", False)
    late = new_map(12, 3, grouped)
    late.reason(mode="full")
    assert _graphs(early) == _graphs(late)
    assert early.reason(mode="full").stats.derived == late.reason(mode="full").stats.derived


def test_an_early_answer_is_not_used_once_a_key_it_reads_is_written(monkeypatch):
    after = EarlyAsks.after
    dropped = []

    def after_then_write(self, c):
        after(self, c)
        for i in list(self._started):
            self.wrote(self.run.rules[i].unless_known.read_key())  # as if a later rule wrote its conclusion
            dropped.append(i)

    monkeypatch.setattr(EarlyAsks, "after", after_then_write)
    log = _logged(monkeypatch)
    onto = new_map(12, 3, False)
    before = set(threading.enumerate())
    onto.reason(mode="full")
    assert dropped and all(e[2] is None for e in log if e[0] == "answer")
    assert set(threading.enumerate()) == before
    monkeypatch.setattr(early_asks, "ENABLED", False)
    late = new_map(12, 3, False)
    late.reason(mode="full")
    assert _graphs(onto) == _graphs(late)


def test_no_early_ask_without_the_second_thread(monkeypatch):
    monkeypatch.setattr(early_asks, "ENABLED", False)
    log = _logged(monkeypatch)
    new_map(12, 3, True).reason(mode="full")
    assert not [e for e in log if e[0] == "start"]
