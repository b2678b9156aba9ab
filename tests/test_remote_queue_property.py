"""Random robot runs on ``oxigraph serve`` with refused requests: the remote store's queue stays exact.

Writes wait in the remote store's queue, values read once are kept by the store's own writes, and
the server may refuse (or not answer) any update.  Whatever the order, after every operation:

* what the store answers from its listings is what the server holds;
* the change ledger holds exactly the difference between the server's asserted graph now and at
  the last successful REASON (so rollback and incremental REASON start from the truth);
* after a REASON, the answers equal a from-scratch REASON of the server's asserted graph.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode, Quad, Triple

from topostore import Ontology
from topostore.errors import QueryError, StoreError, TopostoreError
from topostore.rdf.vocab import ASSERTED, XSD
from topostore.stores import open_store
from topostore.stores.remote import RemoteStore

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
NS = "http://bnc/exp-rob-lab/2022-23#"
NOW = 1665579740
PLACES = ("C1", "R1", "R2")
_names = itertools.count()

op = st.one_of(
    st.tuples(st.just("move"), st.sampled_from(PLACES), st.booleans()),
    st.tuples(st.just("clock"), st.integers(-20, 40)),
    st.tuples(st.just("visit"), st.sampled_from(PLACES), st.integers(-40, 40)),
    st.tuples(st.just("door"), st.sampled_from(PLACES), st.booleans()),
    st.tuples(st.just("reason")),
    st.tuples(st.just("query")),
    st.tuples(st.just("refuse"), st.sampled_from(["refused", "no answer"]), st.integers(1, 2)),
)


def n(name: str) -> NamedNode:
    return NamedNode(NS + name)


def long(v: int) -> Literal:
    return Literal(str(v), datatype=NamedNode(XSD + "long"))


class Server:
    """Reads of the server itself (a store of its own: nothing kept, nothing queued) and refusals."""

    def __init__(self, store: RemoteStore, monkeypatch: pytest.MonkeyPatch) -> None:
        self.store = store
        self.check = RemoteStore(store.url, reference=store.reference)
        self.refusals: list[Exception] = []
        real = store._post

        def post(url: str, data: dict, accept: str | None = None):
            if url == store.update_url and self.refusals:
                raise self.refusals.pop()
            return real(url, data, accept)

        monkeypatch.setattr(store, "_post", post)

    def values(self, s: NamedNode, p: NamedNode) -> set:
        return {self.check._key(q) for q in self.check._match(s, p, None, ASSERTED)}

    def asserted(self) -> set[Triple]:
        return {Triple(q.subject, q.predicate, q.object) for q in self.check._match(None, None, None, ASSERTED)}

    def settled(self) -> bool:
        """No refusal armed and no queued write of the asserted graph (what the server holds is the state)."""
        return not self.refusals and not any(q.touches({ASSERTED}, None) for q in self.store._queue)


def apply(onto: Ontology, state: dict, step: tuple) -> None:
    kind = step[0]
    if kind == "move":
        _, to, right = step
        old = state["place"] if right else next(p for p in PLACES if p != state["place"])
        onto.replace("Robot1", "isIn", to, old)
        state["place"] = to if right else state["place"]
    elif kind == "clock":
        new = state["now"] + step[1]
        onto.replace("Robot1", "now", long(new), long(state["now"]))
        state["now"] = new
    elif kind == "visit":
        _, place, dt = step
        onto.replace(place, "visitedAt", long(state["now"] + dt), long(state["visits"][place]))
        state["visits"][place] = state["now"] + dt
    elif kind == "door":
        fact = Triple(n(step[1]), n("hasDoor"), n("D9"))
        (onto.add if step[2] else onto.remove)(fact)
    elif kind == "reason":
        onto.reason()
    elif kind == "query":
        onto.object_values("canReach", "Robot1")


def from_scratch(asserted: set[Triple]) -> tuple:
    fresh = Ontology()
    fresh.add(*asserted)
    report = fresh.reason()
    return (report.consistent, sorted(fresh.object_values("canReach", "Robot1")) if report.consistent else None,
            sorted(fresh.instances("URGENT")) if report.consistent else None)


def answers(onto: Ontology) -> tuple:
    consistent = onto.report.consistent
    return (consistent, sorted(onto.object_values("canReach", "Robot1")) if consistent else None,
            sorted(onto.instances("URGENT")) if consistent else None)


def check(onto: Ontology, server: Server, last_good: set[Triple]) -> None:
    store = onto.store
    for s, p in [(n("Robot1"), n("isIn")), (n("Robot1"), n("now"))] + [(n(x), n("visitedAt")) for x in PLACES]:
        assert {store._key(Quad(t.subject, t.predicate, t.object, ASSERTED)) for t in store.triples(s, p, None, ASSERTED)} \
            == server.values(s, p), f"the store's values of {s} {p} differ from the server's"
    now = {store.stored_form(t) for t in server.asserted()}
    added, removed = list(onto.ledger.added), list(onto.ledger.removed)
    assert set(added) == now - last_good and set(removed) == last_good - now, "the ledger is not the difference"


@settings(max_examples=property_examples(12), deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(steps=st.lists(op, min_size=1, max_size=12))
# a refused write sent by the first read of the ontology's namespace: the namespace must not fall back
# to the default for good (every name then missed its entity)
@example(steps=[("door", "C1", True), ("refuse", "refused", 1), ("clock", 0), ("reason",)])
def test_queue_listings_and_ledger_stay_exact(steps: list[tuple], oxigraph_url: str,
                                               monkeypatch: pytest.MonkeyPatch, tmp_path_factory) -> None:
    path = tmp_path_factory.getbasetemp() / "map.ttl"
    if not path.exists():
        path.write_text("\n".join((ROOT / "ontology" / f).read_text()
                                  for f in ("topological_map.ttl", "topological_map_abox.ttl")))
    store = open_store(oxigraph_url, reference=f"property-{next(_names)}")
    with monkeypatch.context() as patch:
        server = Server(store, patch)
        onto = Ontology.from_file(path, store=store)
        onto.reason()
        state = {"place": "C1", "now": NOW, "visits": {"C1": NOW, "R1": NOW - 30, "R2": NOW - 5}}
        last_good = {store.stored_form(t) for t in server.asserted()}
        for step in steps:
            if step[0] == "refuse":
                error = QueryError("refused (503)") if step[1] == "refused" else StoreError("no answer")
                server.refusals = [error] * step[2]
                continue
            try:
                apply(onto, state, step)
            except TopostoreError:
                server.refusals.clear()
                state = believed(onto)  # the next old values: what the ontology holds now
            if server.settled():
                if step[0] == "reason" and onto.report is not None and not onto.dirty:
                    last_good = {store.stored_form(t) for t in server.asserted()}
                    assert answers(onto) == from_scratch(server.asserted())
                check(onto, server, last_good)
        server.refusals.clear()
        store.close()
        server.check.close()


def believed(onto: Ontology) -> dict:
    """The robot's place, clock and visits as the ontology holds them (after a refused change)."""
    def one(s: str, p: str) -> NamedNode | Literal | None:
        values = sorted((t.object for t in onto.store.triples(n(s), n(p), None, ASSERTED)), key=str)
        return values[0] if values else None

    place = one("Robot1", "isIn")
    return {"place": place.value[len(NS):] if place is not None else "C1",
            "now": int(one("Robot1", "now").value),
            "visits": {x: int(one(x, "visitedAt").value) for x in PLACES}}
