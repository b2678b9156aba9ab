"""REPLACE's short lane (armor/one_value.py) against the general path: the same replies, asserted graph (with
the spellings written), ledger record and reasoner answers, whatever the command sequence."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode, Triple
from support import IRI, SHARED

from topostore.armor import ArmorService, lanes, one_value
from topostore.armor.reference import Reference
from topostore.ontology.ledger import ChangeLedger
from topostore.rdf.vocab import ASSERTED, INFERRED
from topostore.stores.base import Store

INDIVIDUALS = ["Robot1", "R1", "R2", "C1", "D1", "Nobody"]
OBJECT_PROPS = ["isIn", "canReach", "connectedTo", "hasDoor", "unknownProp"]
DATA_PROPS = ["now", "visitedAt", "urgencyThreshold", "isIn", "unknownData"]
TYPES = ["LONG", "INTEGER", "FLOAT", "STRING", "BOOLEAN", "DOUBLE"]
RDFS_SEE_ALSO = "http://www.w3.org/2000/01/rdf-schema#seeAlso"
TEXTS = ["7", "07", "+7", "7.0", "8", "1", "true", "false", "0", "x", "1.5E0", "-3"]


def _service(buffered_reasoner: bool) -> ArmorService:
    service = ArmorService()
    reply = service.call({"reference_name": "ref", "command": "LOAD", "primary_command_spec": "FILE",
                          "args": [str(SHARED / "topological_map_abox.owl"), IRI, "false", "PELLET",
                                   str(buffered_reasoner).lower()]})
    assert reply.success, reply
    return service


def _request(command: str, primary: str, secondary: str, args: list[str]) -> dict:
    return {"reference_name": "ref", "command": command, "primary_command_spec": primary,
            "secondary_command_spec": secondary, "args": args}


names, texts, types = st.sampled_from(INDIVIDUALS), st.sampled_from(TEXTS), st.sampled_from(TYPES)
commands = st.one_of(
    st.tuples(st.just("REPLACE"), st.just("OBJECTPROP"), st.just("IND"),
              st.lists(st.sampled_from(OBJECT_PROPS), min_size=1, max_size=1).flatmap(
                  lambda p: st.tuples(st.just(p[0]), names, names, names).map(list))),
    st.tuples(st.just("REPLACE"), st.just("DATAPROP"), st.just("IND"),
              st.tuples(st.sampled_from(DATA_PROPS), names, types, texts, texts).map(list)),
    st.tuples(st.sampled_from(["ADD", "REMOVE"]), st.just("DATAPROP"), st.just("IND"),
              st.tuples(st.sampled_from(DATA_PROPS), names, types, texts).map(list)),
    st.tuples(st.sampled_from(["ADD", "REMOVE"]), st.just("OBJECTPROP"), st.just("IND"),
              st.tuples(st.sampled_from(OBJECT_PROPS), names, names).map(list)),
    st.tuples(st.just("REASON"), st.just(""), st.just(""), st.just([])),
    st.tuples(st.just("QUERY"), st.sampled_from(["OBJECTPROP", "DATAPROP"]), st.just("IND"),
              st.tuples(st.sampled_from(["isIn", "canReach", "now", "visitedAt"]), names).map(list)),
    st.tuples(st.just("QUERY"), st.just("IND"), st.just("CLASS"), st.sampled_from([["URGENT"], ["ROBOT"]])),
)


def _named(triples) -> frozenset:
    """The triples naming no blank node (each load names the map's axioms' nodes afresh; no REPLACE touches them)."""
    return frozenset(t for t in triples if not any(str(term).startswith("<urn:topostore:bnode:") for term in t))


def _state(service: ArmorService) -> tuple:
    """The asserted graph with each literal as written, the inferred graph, the ledger's record and the literal
    forms (each fact's, and how many facts write each spelling of a value)."""
    onto = service.reference("ref").ontology
    store = onto.store
    asserted = _named(
        (t.subject, t.predicate,
         store.original_literal(ASSERTED, t.subject, t.predicate, t.object) if isinstance(t.object, Literal)
         else t.object)
        for t in store.triples(graph=ASSERTED))
    ledger, forms = onto.ledger, store.forms
    counts = {key: dict(spellings) for key, spellings in forms._value_forms.items() if spellings}
    return (asserted, _named(store.triples(graph=INFERRED)), dict(ledger.added), dict(ledger.removed),
            dict(ledger.held), ledger.incremental, onto.dirty, _named_forms(forms._literal_forms), counts)


def _named_forms(kept: dict) -> dict:
    """The literal forms of facts of named subjects (see :func:`_named`)."""
    return {key: lit for key, lit in kept.items() if not str(key[1]).startswith("<urn:topostore:bnode:")}


def _call(service: ArmorService, request: dict, lane: bool, monkeypatch: pytest.MonkeyPatch) -> dict:
    monkeypatch.setattr(one_value, "ENABLED", lane)
    monkeypatch.setattr(lanes, "ENABLED", lane)
    return service.call(request).to_dict()


#: the aRMOR type that spells each datatype back (an old value given as it is held)
_TYPE_OF = {"long": "LONG", "integer": "INTEGER", "float": "FLOAT", "string": "STRING", "boolean": "BOOLEAN",
            "double": "DOUBLE"}


def _held_replace(service: ArmorService, data: st.DataObject) -> dict | None:
    """A REPLACE whose old value is one the service holds (as held, or in another spelling), or None."""
    prop = data.draw(st.sampled_from(OBJECT_PROPS[:4] + DATA_PROPS[:3]))
    ind = data.draw(st.sampled_from(INDIVIDUALS[:5]))
    onto = service.reference("ref").ontology
    held = list(onto.store.triples(onto.iri(ind), onto.iri(prop), None, ASSERTED))
    if not held:
        return None
    old = data.draw(st.sampled_from(held)).object
    kind = "DATAPROP" if isinstance(old, Literal) else "OBJECTPROP"
    if kind == "OBJECTPROP":
        return _request("REPLACE", kind, "IND", [prop, ind, data.draw(names), old.value.rsplit("#", 1)[-1]])
    spelled = _TYPE_OF.get(old.datatype.value.rsplit("#", 1)[-1], "STRING")
    kind_of_old = data.draw(st.sampled_from([spelled] * 6 + TYPES))
    new_type = data.draw(st.sampled_from([kind_of_old] * 6 + TYPES))
    return _request("REPLACE", kind, "IND", [prop, ind, new_type, data.draw(texts), old.value])


@settings(max_examples=property_examples(100), deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data(), buffered=st.booleans(), size=st.integers(1, 12))
def test_lane_and_general_path_agree(monkeypatch: pytest.MonkeyPatch, data: st.DataObject, buffered: bool,
                                     size: int) -> None:
    """Every reply, the asserted graph as written, the inferred graph and the ledger are the same with the lane
    on and off, after every command of a random sequence (the two services share their history); half the
    REPLACEs name an old value the reference holds."""
    on, off = _service(buffered), _service(buffered)
    for _ in range(size):
        request = _held_replace(on, data) if data.draw(st.booleans()) else None
        if request is None:
            request = _request(*data.draw(commands))
        assert _call(on, request, True, monkeypatch) == _call(off, request, False, monkeypatch), request
        assert _state(on) == _state(off), request
    reasoned = _request("REASON", "", "", [])
    assert _call(on, reasoned, True, monkeypatch) == _call(off, reasoned, False, monkeypatch)
    assert _state(on) == _state(off)


def test_the_robot_step_takes_the_lane(monkeypatch: pytest.MonkeyPatch) -> None:
    """The plain REPLACEs of a robot step never reach the general path (the lane is not dead code), nor the
    store's transaction or a unit of work: they are written straight."""
    service = _service(buffered_reasoner=True)

    def general(self, *args, **kwargs):
        raise AssertionError("general path taken")

    monkeypatch.setattr(Reference, "applied", general)
    monkeypatch.setattr(Store, "_begin", general)
    monkeypatch.setattr(ChangeLedger, "undoable", general)
    replies = [service.call(_request("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1", "C1"])),
               service.call(_request("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1700000001",
                                                                     "1665579740"]))]
    assert [(r.success, r.error_description) for r in replies] == [(True, ""), (True, "")]


@pytest.mark.parametrize("args", [
    ["isIn", "Robot1", "R1", "R2"],  # the old value is not held
    ["isIn", "Robot1", "C1", "C1"],  # the new value is the old one
    [f"<{RDFS_SEE_ALSO}>", "Robot1", "R1", "C1"],  # a property of a schema vocabulary (its triple held)
])
def test_not_the_plain_case_goes_the_general_path(monkeypatch: pytest.MonkeyPatch, args: list[str]) -> None:
    """A REPLACE the lane cannot do plainly changes nothing there and is the general path's."""
    service = _service(buffered_reasoner=True)
    onto = service.reference("ref").ontology
    onto.add(Triple(onto.iri("Robot1"), NamedNode(RDFS_SEE_ALSO), onto.iri("C1")))
    taken = []
    original = Reference.applied

    def general(self, changes, reason=None):
        taken.append([c.description for c in changes])
        return original(self, changes, reason)

    monkeypatch.setattr(Reference, "applied", general)
    assert service.call(_request("REPLACE", "OBJECTPROP", "IND", args)).success
    assert taken == [["REPLACE OBJECTPROP IND"]]


@pytest.mark.parametrize("buffered", [True, False])
@pytest.mark.parametrize("sequence", [
    # a data value replaced on an object property: the general path's note
    [("ADD", "DATAPROP", "IND", ["isIn", "Robot1", "LONG", "7"]),
     ("REPLACE", "DATAPROP", "IND", ["isIn", "Robot1", "LONG", "8", "7"])],
    # the robot's step: its room and its clock
    [("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1", "C1"]),
     ("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"]),
     ("REASON", "", "", []), ("QUERY", "IND", "CLASS", ["URGENT"])],
    # the old value in another spelling, the new one in its own
    [("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "INTEGER", "+0012", "01665579740"]),
     ("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "FLOAT", "1.5E0", "12"])],
])
def test_lane_and_general_path_agree_on(monkeypatch: pytest.MonkeyPatch, buffered: bool, sequence: list) -> None:
    """The cases the lane must tell from the plain one, and the plain one, with each reasoner setting."""
    on, off = _service(buffered), _service(buffered)
    for command in sequence:
        request = _request(*command)
        assert _call(on, request, True, monkeypatch) == _call(off, request, False, monkeypatch), request
        assert _state(on) == _state(off), request


class _AddFails:
    """An in-memory engine whose next ``extend`` fails (after the removal the same write made)."""

    def __init__(self, inner) -> None:
        self.inner, self.armed = inner, True

    def __getattr__(self, name: str):
        return getattr(self.inner, name)

    def __iter__(self):
        return iter(self.inner)

    def __len__(self) -> int:
        return len(self.inner)

    def __contains__(self, quad) -> bool:
        return quad in self.inner

    def extend(self, quads) -> None:
        if self.armed:
            self.armed = False
            raise OSError("no space left (injected)")
        self.inner.extend(quads)


@pytest.mark.parametrize("lane", [True, False], ids=["lane", "general"])
def test_a_write_failing_half_way_changes_nothing(monkeypatch: pytest.MonkeyPatch, lane: bool) -> None:
    """The engine removes, then adds: where the addition fails, the REPLACE is refused, the old value is held
    again and the next REASON answers as one from scratch, on the lane as on the general path."""
    monkeypatch.setattr(one_value, "ENABLED", lane)
    svc = _service(True)
    onto = svc.reference("ref").ontology
    robot, is_in = onto.iri("Robot1"), onto.iri("isIn")
    before = set(onto.store.triples(robot, is_in, None, ASSERTED))
    engine = onto.store._ox
    onto.store._ox = _AddFails(engine)
    try:
        reply = svc.call(_request("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1", "C1"]))
    finally:
        onto.store._ox = engine
    assert not reply.success and "undone" in reply.error_description
    assert set(onto.store.triples(robot, is_in, None, ASSERTED)) == before
    assert svc.call(_request("REASON", "", "", [])).success
    inferred = set(onto.store.triples(graph=INFERRED))
    onto.reason(mode="full")
    assert set(onto.store.triples(graph=INFERRED)) == inferred


@pytest.mark.parametrize("lane", [True, False])
def test_a_clock_replaced_every_step_keeps_no_count_of_its_past_values(monkeypatch: pytest.MonkeyPatch,
                                                                        lane: bool) -> None:
    """The literal forms count the spellings of each value some fact writes; a value none writes any more is
    dropped, in the lane and on the general path (a clock writes a new value every step: its past ones would
    otherwise stay behind as empty counts, one a step)."""
    monkeypatch.setattr(one_value, "ENABLED", lane)
    service = _service(buffered_reasoner=True)
    forms = service.reference("ref").ontology.store.forms
    assert service.call(_request("ADD", "DATAPROP", "IND", ["tick", "Clock1", "LONG", "0"])).success
    counted = len(forms._value_forms)
    for t in range(1, 40):
        reply = service.call(_request("REPLACE", "DATAPROP", "IND", ["tick", "Clock1", "LONG", str(t), str(t - 1)]))
        assert reply.success and not reply.error_description, reply
    assert len(forms._value_forms) <= counted + 1  # the clock's one value now, whether or not "0" was counted
    assert forms.restore(Literal("39", datatype=NamedNode("http://www.w3.org/2001/XMLSchema#integer"))) == \
        Literal("39", datatype=NamedNode("http://www.w3.org/2001/XMLSchema#long"))


def _sparql_replace(onto, old: str, new: str) -> None:
    """The clock's value replaced by a SPARQL update naming the asserted graph (another path than the lane's)."""
    long = "<http://www.w3.org/2001/XMLSchema#long>"
    robot, now = onto.iri("Robot1"), onto.iri("now")
    onto.store.update(f'DELETE DATA {{ GRAPH {ASSERTED} {{ {robot} {now} "{old}"^^{long} }} }} ; '
                      f'INSERT DATA {{ GRAPH {ASSERTED} {{ {robot} {now} "{new}"^^{long} }} }}')


def _api_replace(onto, old: str, new: str) -> None:
    """The clock's value replaced through the Python API (a store transaction)."""
    long = NamedNode("http://www.w3.org/2001/XMLSchema#long")
    robot, now = onto.iri("Robot1"), onto.iri("now")
    onto.remove(Triple(robot, now, Literal(old, datatype=long)))
    onto.add(Triple(robot, now, Literal(new, datatype=long)))


@pytest.mark.parametrize("between", [_sparql_replace, _api_replace], ids=["sparql", "api"])
def test_a_value_another_path_changed_is_read_again(monkeypatch: pytest.MonkeyPatch, between) -> None:
    """The lane keeps the fact it wrote for the next REPLACE of the same value (no read before the write); a
    write of any other path in between makes it read the store again: a REPLACE naming the value the lane
    wrote, since replaced by another, is answered and leaves the graph as on the general path."""
    services = {lane: _service(True) for lane in (True, False)}
    for lane, service in services.items():
        onto = service.reference("ref").ontology
        first = _request("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "100", "1665579740"])
        assert _call(service, first, lane, monkeypatch)["success"]
        between(onto, "100", "200")
    again = _request("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "300", "100"])
    assert _call(services[True], again, True, monkeypatch) == _call(services[False], again, False, monkeypatch)
    assert _state(services[True]) == _state(services[False])
    held = services[True].reference("ref").ontology
    assert {t.object.value for t in held.store.triples(held.iri("Robot1"), held.iri("now"), None, ASSERTED)} == \
        {t.object.value for t in services[False].reference("ref").ontology.store.triples(
            held.iri("Robot1"), held.iri("now"), None, ASSERTED)}
