"""A change's triples as facts (``stores/facts.py``): the keys and forms each layer reads are those the
layers computed for themselves before, and a REPLACE that fails, or whose write fails, leaves the
store, the ledger and the literal forms as they were (each literal as its user wrote it)."""

from __future__ import annotations

import pytest
from pyoxigraph import Literal, NamedNode, Quad, Triple
from support import names, typed

from topostore import Ontology
from topostore.armor import ArmorService
from topostore.armor.reference import Change, Delta, Reference
from topostore.errors import InvalidValueError, StoreError
from topostore.rdf import terms
from topostore.rdf.vocab import ASSERTED, TYPE, XSD

EX = "http://example.org/facts#"
n = names(EX)
TBOX = f"""@prefix : <{EX}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
<{EX.rstrip('#')}> a owl:Ontology .
:Robot a owl:Class . :speed a owl:DatatypeProperty . :at a owl:ObjectProperty .
:r1 a :Robot ; :speed "07"^^<http://www.w3.org/2001/XMLSchema#long> ; :at :a .
"""


@pytest.fixture
def onto() -> Ontology:
    o = Ontology(prefix=EX)
    o.load_data(TBOX)
    o.reason()
    return o


def test_a_fact_carries_the_keys_the_store_and_the_ledger_compute(onto: Ontology) -> None:
    store = onto.store
    t = Triple(n("r1"), n("speed"), typed("8", "long"))
    f = store.fact(t, ASSERTED)
    q = Quad(t.subject, t.predicate, t.object, ASSERTED)
    assert f.triple == t and f.quad == q and f.key == store._key(q) and f.value == terms.value_key(t.object)
    assert f.written == t and f.stored is None  # the stored form is asked when the ledger records it
    iri = store.fact(Triple(n("r1"), n("at"), n("b")), ASSERTED)
    assert iri.key == iri.quad and iri.value is None and iri.stored == iri.triple == iri.written


def test_read_facts_are_the_triples_read_with_their_written_forms_asked_once(onto: Ontology) -> None:
    store = onto.store
    with store.transaction():
        facts = store.read_facts(n("r1"), n("speed"), ASSERTED)
        assert [f.triple for f in facts] == list(store.triples(n("r1"), n("speed"), None, ASSERTED))
        (f,) = facts
        assert f.key == store._key(f.quad) and f.stored == store.stored_form(f.triple)
        assert f.written is None
        assert store.written_fact(f) == Triple(n("r1"), n("speed"), typed("07", "long")) == f.written
        # a pending addition is read too, a pending removal is not
        store.toggle_facts([store.fact(Triple(n("r1"), n("speed"), typed("9", "long")), ASSERTED)], True)
        store.toggle_facts([f], False)
        assert [str(g.triple.object) for g in store.read_facts(n("r1"), n("speed"), ASSERTED)] == [
            str(typed("9", "long"))]


def test_toggling_facts_reports_only_what_changed_and_one_value_is_one_write(onto: Ontology) -> None:
    store = onto.store
    present = store.fact(Triple(n("r1"), n("speed"), typed("7", "integer")), ASSERTED)  # another spelling
    absent = store.fact(Triple(n("r1"), n("speed"), typed("8", "long")), ASSERTED)
    with store.transaction():
        assert store.toggle_facts([present, absent], True) == [absent]
        assert store.toggle_facts([absent], True) == []
        assert store.toggle_facts([absent], False) == [absent]  # the pending addition cancelled
    assert [str(t.object) for t in store.triples(n("r1"), n("speed"), None, ASSERTED)] == [
        str(typed("7", "integer"))]


def test_replace_records_the_stored_and_written_forms_and_back_cancels(onto: Ontology) -> None:
    added, removed = onto.change([Triple(n("r1"), n("speed"), typed("8", "long"))],
                                 onto.store.read_facts(n("r1"), n("speed"), ASSERTED))
    assert [str(t.object) for t in added] == [str(typed("8", "long"))] and len(removed) == 1
    assert set(onto.ledger.added) == {Triple(n("r1"), n("speed"), typed("8", "integer"))}
    assert list(onto.ledger.removed.values()) == [Triple(n("r1"), n("speed"), typed("07", "long"))]
    onto.change([Triple(n("r1"), n("speed"), typed("7", "long"))],
                onto.store.read_facts(n("r1"), n("speed"), ASSERTED))
    assert onto.ledger.net_changes() == ([], [])


def test_a_failed_armor_change_restores_the_literal_as_written() -> None:
    service = ArmorService()
    ref_onto = Ontology(prefix=EX)
    ref_onto.load_data(TBOX)
    ref_onto.reason()
    ref = Reference("ref", ref_onto, EX.rstrip("#"))
    service.add_reference(ref)

    def broken(_onto: Ontology) -> Delta:
        raise InvalidValueError("this change cannot be planned")

    replace_plan = Change("REPLACE", lambda o: Delta(add=[Triple(n("r1"), n("speed"), typed("8", "long"))],
                                                      remove=o.store.read_facts(n("r1"), n("speed"), ASSERTED)))
    with pytest.raises(InvalidValueError):
        ref.run([replace_plan, Change("broken", broken)])
    assert [str(v) for v in ref_onto.data_values("speed", "r1")] == [str(typed("07", "long"))]
    assert ref_onto.ledger.net_changes() == ([], [])
    reply = service.call({"reference_name": "ref", "command": "QUERY", "primary_command_spec": "DATAPROP",
                          "secondary_command_spec": "IND", "args": ["speed", "r1"]})
    assert reply.success and reply.queried_objects == ['"07"^^xsd:long']


def test_a_write_that_fails_leaves_the_literal_forms_as_they_were(onto: Ontology,
                                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    store = onto.store

    def failing(adds, removes, undo=None) -> None:
        raise StoreError("the disk is full")

    monkeypatch.setattr(store, "_write", failing)
    with pytest.raises(StoreError):
        onto.change([Triple(n("r1"), n("speed"), typed("8", "long"))],
                    [Triple(n("r1"), n("speed"), typed("7", "integer"))])
    monkeypatch.undo()
    assert store.original_literal(ASSERTED, n("r1"), n("speed"), typed("7", "integer")) == typed("07", "long")
    assert store.restore(typed("8", "integer")) == typed("8", "integer")  # the new form is not remembered
    assert [str(v) for v in onto.data_values("speed", "r1")] == [str(typed("07", "long"))]


def test_a_typed_argument_is_known_valid_and_an_invalid_literal_is_still_refused() -> None:
    made = terms.typed_literal("123456789", "LONG")
    assert made in terms._VALID
    terms.check_literal(made)
    with pytest.raises(InvalidValueError):
        terms.check_literal(typed("fast", "long"))
    terms.check_literal(Literal("1999", datatype=NamedNode(XSD + "gYear")))  # not validated: kept as written
    assert terms.literal_of("5", "long") == typed("5", "long")
    with pytest.raises(ValueError):
        terms.literal_of("5", "no such type")  # the datatype IRI is refused by pyoxigraph, as before


def test_type_facts_touch_the_rules(onto: Ontology) -> None:
    onto.rules  # noqa: B018 - compiled
    onto.change([Triple(n("Drone"), TYPE, NamedNode("http://www.w3.org/2002/07/owl#Class"))], [])
    assert onto._rules is None


def test_a_removal_writes_the_literal_as_its_user_wrote_it(onto: Ontology, monkeypatch: pytest.MonkeyPatch) -> None:
    """A store that keeps literals as written (a remote one) must be sent the form it holds, even where the
    value was read in Oxigraph's stored form."""
    store = onto.store
    written: list[tuple[list[Quad], list[Quad]]] = []
    commit = store._commit
    monkeypatch.setattr(store, "_commit", lambda adds, removes: (written.append((adds, removes)), commit(adds, removes)))
    onto.change([Triple(n("r1"), n("speed"), typed("8", "long"))], store.read_facts(n("r1"), n("speed"), ASSERTED))
    (adds, removes), = written
    assert Quad(n("r1"), n("speed"), typed("07", "long"), ASSERTED) in removes
    assert Quad(n("r1"), n("speed"), typed("8", "long"), ASSERTED) in adds
    assert [str(t.object) for t in store.triples(n("r1"), n("speed"), None, ASSERTED)] == [str(typed("8", "integer"))]


def test_a_fact_with_no_form_kept_is_removed_as_read_not_in_another_subjects_spelling(onto: Ontology) -> None:
    """:r2's speed reached the store without a form kept (another writer of a shared store); :r1's
    "07"^^xsd:long is the one spelling of the value 7 the forms know.  Removing :r2's speed must name
    it as the store holds it, and must not count :r1's form away."""
    store = onto.store
    r2 = Quad(n("r2"), n("speed"), typed("7", "integer"), ASSERTED)
    store._ox.add(r2)  # behind the literal forms' back
    with store.transaction():
        (f,) = store.read_facts(n("r2"), n("speed"), ASSERTED)
        assert store._removal_quad(f) == f.quad
        store.toggle_facts([f], add=False)
    assert r2 not in store._ox
    assert store.written_fact(store.read_facts(n("r1"), n("speed"), ASSERTED)[0]).object == typed("07", "long")
    assert store.forms.restore(typed("7", "integer")) == typed("07", "long")  # :r1's form still counted


def _replace_reply(service: ArmorService, *args: str) -> None:
    reply = service.call({"reference_name": "ref", "command": "REPLACE", "primary_command_spec": args[0],
                          "secondary_command_spec": "IND", "args": list(args[1:])})
    assert reply.success, reply.error_description


def _service() -> tuple[ArmorService, Ontology]:
    service, onto = ArmorService(), Ontology(prefix=EX)
    onto.load_data(TBOX)
    onto.reason()
    service.add_reference(Reference("ref", onto, EX.rstrip("#"), buffered_reasoner=True))  # as a robot runs
    return service, onto


def test_a_replace_asks_no_presence_of_the_value_its_read_did_not_find(monkeypatch: pytest.MonkeyPatch) -> None:
    # the plan read every value of (r1, speed): a new value not among them is absent from the store in
    # every spelling, so the unit of work asks no presence look-up of it (as written, nor in a kept spelling)
    service, onto = _service()
    asked: list[Quad] = []
    has = type(onto.store)._has
    monkeypatch.setattr(type(onto.store), "_has", lambda store, q: asked.append(q) or has(store, q))
    _replace_reply(service, "DATAPROP", "speed", "r1", "LONG", "9", "7")
    _replace_reply(service, "OBJECTPROP", "at", "r1", "b", "a")
    assert asked == []
    assert onto.ledger.net_changes()[0] == [Triple(n("r1"), n("speed"), typed("9", "integer")),
                                            Triple(n("r1"), n("at"), n("b"))]
    onto.reason()  # a buffered reasoner answers the replaced value too until REASON (spec §2.5)
    assert [str(v) for v in onto.data_values("speed", "r1")] == [str(typed("9", "long"))]


def test_a_value_read_present_stays_present_when_noted_unread(onto: Ontology) -> None:
    # an earlier change of the same unit removed the value: the read does not list it, the committed store
    # holds it, and adding it back cancels the pending removal (no change at all)
    store = onto.store
    with store.transaction():
        facts = store.read_facts(n("r1"), n("speed"), ASSERTED)
        assert [f.triple for f in store.toggle_facts(facts, False)] == [f.triple for f in facts]
        assert store.read_facts(n("r1"), n("speed"), ASSERTED) == []
        back = store.unread_fact(n("r1"), n("speed"), typed("7", "long"), ASSERTED)
        assert store.toggle_facts([back], True) == [back]
        assert store._pending == {}
    assert [str(v) for v in onto.data_values("speed", "r1")] == [str(typed("07", "long"))]


@pytest.mark.parametrize("lit", [typed("007", "long"), typed("1.50", "decimal"), typed("+3", "int"),
                                 typed("1.0E1", "double"), Literal("chat", language="FR"), Literal("plain")])
def test_the_probe_given_a_changes_quad_finds_the_stored_form_it_finds_alone(lit: Literal) -> None:
    from topostore.stores import literal_forms

    literal_forms._STORED.clear()
    alone = literal_forms.stored_literal(lit)
    literal_forms._STORED.clear()
    assert literal_forms.stored_literal(lit, Quad(n("r1"), n("speed"), lit, ASSERTED)) == alone
    literal_forms._STORED.clear()
    t = Triple(n("r1"), n("speed"), lit)
    assert Ontology(prefix=EX).store.stored_form(t, Quad(n("r1"), n("speed"), lit, ASSERTED)) == \
        Triple(n("r1"), n("speed"), alone)


@pytest.mark.parametrize(("lit", "kept"), [(typed("0042", "long"), True), (typed("2.50", "decimal"), True),
                                           (typed("1", "boolean"), True), (typed("1.0E1", "double"), True),
                                           (Literal("chat", language="FR"), False), (Literal("plain"), False)])
def test_a_probed_numbers_stored_form_keeps_the_value_key_of_the_written_one(lit: Literal, kept: bool) -> None:
    # a REPLACE reads back, a step later, the stored form of the value it wrote: a number's key is known then
    from topostore.stores import literal_forms

    literal_forms._STORED.clear()
    terms._VALUE_KEYS.clear()
    terms.value_key(lit)
    stored = literal_forms.stored_literal(lit)
    noted = terms._VALUE_KEYS.get(stored)
    assert (noted is not None) == (kept or stored == lit)
    if noted is not None:
        assert noted == terms._literal_key(stored)


@pytest.mark.parametrize("o", [typed("08", "long"), n("b"), Literal("x", language="en")])
def test_a_fact_made_from_its_quad_is_the_fact_of_its_triple(o) -> None:
    from topostore.stores.facts import fact_of, fact_written

    t = Triple(n("r1"), n("speed"), o)
    made, given = fact_written(Quad(t.subject, t.predicate, o, ASSERTED)), fact_of(t, ASSERTED)
    assert (made.triple, made.quad, made.key, made.value, made.stored, made.written) == \
        (given.triple, given.quad, given.key, given.value, given.stored, given.written)
    assert terms.triple(t.subject, t.predicate, o) == t
