"""A full run leaves the known-head anti-join out of an evaluation whose head's key has no fact in any
graph yet (reason/insert_text.py ``bare``, reason/materialize.py ``Materializer.bare``): the same closure,
and the anti-join kept once the asserted graph holds a fact of the key."""

from __future__ import annotations

import pytest
from pyoxigraph import NamedNode, Triple
from support import full_run_updates, map_or_text, same_closure_without

from topostore.rdf.vocab import ASSERTED, INFERRED
from topostore.reason.materialize import Materializer

CONNECTED = NamedNode("http://bnc/exp-rob-lab/2022-23#connectedTo")


def _evaluations(texts: list[str], head: str) -> list[str]:
    """The evaluations among ``texts`` (requests of one or more) whose head names ``head``."""
    parts = [p for t in texts for p in t.split(" ;\n")]
    return [p for p in parts if p.startswith("INSERT") and head in p.split("\n", 1)[0]]


def test_heads_of_keys_without_facts_are_not_anti_joined(monkeypatch: pytest.MonkeyPatch) -> None:
    onto = map_or_text()
    texts = full_run_updates(onto, monkeypatch)
    for head in ("differentKeyOf", "connectedTo"):
        found = _evaluations(texts, head)
        assert found, head
        assert not any("MINUS" in t or "NOT EXISTS" in t for t in found), head


def test_an_asserted_fact_of_the_key_keeps_the_anti_join(monkeypatch: pytest.MonkeyPatch) -> None:
    onto = map_or_text()
    onto.reason()
    told = next(iter(onto.store.triples(None, CONNECTED, None, INFERRED)))
    onto.add(Triple(told.subject, CONNECTED, told.object))
    texts = full_run_updates(onto, monkeypatch)
    assert any(f"GRAPH {ASSERTED} {{ ?l1 <{CONNECTED.value}> ?l2 . }}" in t
               for t in _evaluations(texts, "connectedTo"))
    assert Triple(told.subject, CONNECTED, told.object) not in set(onto.store.triples(None, CONNECTED, None, INFERRED))


@pytest.mark.parametrize("told", [False, True])
def test_a_full_reason_reaches_the_same_closure_with_and_without_bare_heads(
        told: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    onto = map_or_text()
    if told:
        onto.reason()
        t = next(iter(onto.store.triples(None, CONNECTED, None, INFERRED)))
        onto.add(Triple(t.subject, CONNECTED, t.object))
    same_closure_without(onto, monkeypatch, Materializer, "bare", lambda self, index: False)
