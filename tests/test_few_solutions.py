"""A full REASON's one-atom evaluation with few solutions against a large head extent keeps its known
heads out by a look-up per solution (reason/few_solutions.py) instead of reading the whole extent: the
same closure, and the look-up form only where it is cheap."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from support import closure, full_run_updates, map_or_text

from topostore.rdf.vocab import INFERRED
from topostore.reason import few_solutions, materialize

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the benchmarks package lives beside src/
from benchmarks.cardinality import PREFIXES  # noqa: E402

#: a range over two links into a class of 300 members, and a range over 300 links into a class of 300
SMALL_INTO_LARGE = PREFIXES + "\n".join(
    [":reaches a owl:ObjectProperty ; rdfs:range :Place . :holds a owl:ObjectProperty ; rdfs:range :Thing .",
     ":Place rdfs:subClassOf :Spot .", ":r :reaches :p0 , :p1 ."]
    + [f":p{i} a :Place . :box :holds :t{i} . :t{i} a :Thing ." for i in range(300)])


def test_a_range_over_few_links_looks_each_up(monkeypatch):
    onto = map_or_text(SMALL_INTO_LARGE)
    onto.reason()
    texts = full_run_updates(onto, monkeypatch)
    reaches = [t for t in texts if "reaches> ?y" in t and "Place>" in t and "INSERT" in t]
    assert reaches and all("FILTER NOT EXISTS" in t and "MINUS" not in t for t in reaches)
    # 300 links into 300 members: the extent is read once (MINUS), as before
    holds = [t for t in texts if "holds> ?y" in t and "Thing>" in t and "INSERT" in t]
    assert holds and not any("FILTER NOT EXISTS" in t for t in holds)
    assert {onto.short(i) for i in onto.instances("Spot")} >= {"p0", "p1", "p299"}


@pytest.mark.parametrize("text", [SMALL_INTO_LARGE, None], ids=["small-into-large", "map-200"])
def test_the_same_closure_with_and_without_the_look_ups(text, monkeypatch):
    onto = map_or_text(text)  # one store: its blank nodes (and the group keys made of them) stay the same
    onto.reason(mode="full")
    with_few = closure(onto)
    monkeypatch.setattr(few_solutions, "FEW", -1)  # no evaluation has few solutions
    onto.reason(mode="full")
    assert with_few == closure(onto)
    assert with_few[INFERRED.value]


def test_a_key_a_queued_evaluation_writes_is_not_counted():
    onto = map_or_text(SMALL_INTO_LARGE)
    onto.reason()
    runner = materialize.Materializer(onto.store, onto.rules)
    rule = next(r for r in runner.rules if len(r.body) == 1 and "reaches" in r.body[0].read_key()[1]
                and r.head is not None and "Place" in r.head.o)
    assert few_solutions.few_solutions(runner.store, rule, runner._queued)
    runner._queued.add(rule.body[0].read_key())  # an evaluation writing reaches waits in the queue
    assert not few_solutions.few_solutions(runner.store, rule, runner._queued)
    runner._flush()
    assert few_solutions.few_solutions(runner.store, rule, runner._queued)


def test_a_store_over_http_is_not_asked(monkeypatch):
    onto = map_or_text(SMALL_INTO_LARGE)
    onto.reason()
    runner = materialize.Materializer(onto.store, onto.rules)
    rule = next(r for r in runner.rules if len(r.body) == 1 and "reaches" in r.body[0].read_key()[1]
                and r.head is not None and "Place" in r.head.o)
    monkeypatch.setattr(type(onto.store), "round_trips", True)
    assert not few_solutions.few_solutions(runner.store, rule, runner._queued)
