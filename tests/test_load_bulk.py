"""The bulk path of a big first load: blank nodes skolemised, literals remembered as written,
nothing remembered of a write that failed, and the cycle collector left as it was found."""

from __future__ import annotations

import gc

import pytest
from pyoxigraph import BlankNode, Literal, NamedNode, Triple

from topostore import LoadError, Ontology
from topostore.rdf.vocab import ASSERTED, SKOLEM_PREFIX
from topostore.stores import memory_store
from topostore.stores.work import BULK_ADD

XSD = "http://www.w3.org/2001/XMLSchema#"
PREFIXES = f"@prefix : <http://e.org/a#> . @prefix xsd: <{XSD}> .\n"
FACTS = " ".join(f":i{n} :p :i{n + 1} ." for n in range(BULK_ADD))
P = NamedNode("http://e.org/a#p")


def test_a_bulk_load_skolemises_blank_nodes_and_keeps_each_literal_as_written() -> None:
    onto = Ontology()
    onto.load_data(PREFIXES + FACTS + ' :s :v "01"^^xsd:int , "1"^^xsd:int . [ :p :s ; :q "7"^^xsd:long ] .')
    stored = list(onto.store.triples(graph=ASSERTED))
    assert not any(isinstance(t.subject, BlankNode) or isinstance(t.object, BlankNode) for t in stored)
    anonymous = [t for t in stored if t.subject.value.startswith(SKOLEM_PREFIX)]
    assert len(anonymous) == 2 and len({t.subject for t in anonymous}) == 1  # one blank node, one IRI
    written = {t.object for t in onto.triples() if isinstance(t.object, Literal)}
    assert written == {Literal("01", datatype=NamedNode(XSD + "int")), Literal("7", datatype=NamedNode(XSD + "long"))}


def test_a_failed_bulk_write_remembers_no_literal_form(monkeypatch: pytest.MonkeyPatch) -> None:
    store = memory_store()
    triples = [Triple(NamedNode(f"http://e.org/x{i}"), P, Literal(f"0{i}", datatype=NamedNode(XSD + "int")))
               for i in range(BULK_ADD)]

    def failing(quads, extra) -> None:
        list(quads)  # everything made and recorded, then the store refuses
        raise RuntimeError("disk full")

    monkeypatch.setattr(store, "_commit_stream", failing)
    with pytest.raises(RuntimeError, match="disk full"):
        store.add(triples, ASSERTED)
    assert store.forms.original_literal(ASSERTED, triples[5].subject, P, Literal("5", datatype=NamedNode(
        XSD + "int"))) == Literal("5", datatype=NamedNode(XSD + "int"))  # not "05": that form was forgotten
    monkeypatch.undo()
    assert store.add(triples, ASSERTED) == BULK_ADD
    assert store.forms.original_literal(ASSERTED, triples[5].subject, P, Literal("5", datatype=NamedNode(
        XSD + "int"))) == triples[5].object


def test_a_distinct_add_counts_as_one_that_removes_repeats() -> None:
    triples = [Triple(NamedNode(f"http://e.org/x{i}"), P, NamedNode("http://e.org/y")) for i in range(BULK_ADD)]
    assert memory_store().add([*triples, *triples[:7]], ASSERTED) == BULK_ADD
    assert memory_store().add(triples, ASSERTED, distinct=True) == BULK_ADD


@pytest.mark.parametrize("enabled", [True, False])
def test_the_cycle_collector_is_left_as_a_load_found_it(enabled: bool) -> None:
    was = gc.isenabled()
    try:
        (gc.enable if enabled else gc.disable)()
        onto = Ontology()
        onto.load_data(PREFIXES + FACTS)
        assert gc.isenabled() == enabled
        with pytest.raises(LoadError):
            onto.load_data(PREFIXES + ":a :p .")
        assert gc.isenabled() == enabled
    finally:
        (gc.enable if was else gc.disable)()
