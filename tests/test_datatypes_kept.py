"""A literal keeps the datatype it was written with on every path that writes it back or reads it again.

Oxigraph stores ``"5"^^xsd:long`` as ``"5"^^xsd:integer``; the literal forms remember the written one.  A path
that writes a value back from what the store holds (the canonical term) instead of the form kept for it shows
``xsd:integer`` where a user wrote ``xsd:long``: a revert of the change ledger once did (its removal of the
spelling the undone changes left and its addition of the one held before, keyed by value in one transaction,
cancelled, and the graph kept the later spelling), and a SPARQL update did (its delta is computed on a scratch
Oxigraph store).  Each path is given a value held as ``xsd:long`` (beside the same
numbers held as ``xsd:integer`` by another individual, so that no one spelling of a value answers for both, where
the ontology is this module's) and must show each as written.
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path

import pytest
from http_support import config, in_process
from pyoxigraph import Literal, NamedNode, Triple

from topostore import Ontology, OntologyWarning
from topostore.armor import ArmorService
from topostore.armor.reference import Reference
from topostore.rdf.vocab import XSD
from topostore.sparql.execute import Job, run_update
from topostore.stores import open_store

NS = "http://example.org/kept#"
HEAD = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
:now a owl:DatatypeProperty, owl:FunctionalProperty . :count a owl:DatatypeProperty .
:r a owl:NamedIndividual ; :now "5"^^xsd:long . :q a owl:NamedIndividual ; :now 6 ; :count 5 .
"""
R, Q, NOW = NamedNode(NS + "r"), NamedNode(NS + "q"), NamedNode(NS + "now")


def long(n: int) -> Literal:
    return Literal(str(n), datatype=NamedNode(XSD + "long"))


def integer(n: int) -> Literal:
    return Literal(str(n), datatype=NamedNode(XSD + "integer"))


def ontology(store=None) -> Ontology:
    o = Ontology() if store is None else Ontology(store=store)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(HEAD, "turtle")
    assert o.reason().consistent
    return o


def assert_as_written(o: Ontology, r_now: Literal) -> None:
    assert o.data_values(NOW, R) == [r_now]
    assert o.data_values(NOW, Q) == [integer(6)]
    assert o.data_values(NamedNode(NS + "count"), Q) == [integer(5)]


class Failed(Exception):
    pass


def test_a_failed_reasons_revert_gives_the_value_back_as_written() -> None:
    o = ontology()
    o.replace(R, NOW, long(6))
    assert_as_written(o, long(6))
    o.ledger.revert(o.store)
    assert_as_written(o, long(5))


def test_a_failed_manipulations_undo_gives_the_value_back_as_written() -> None:
    o = ontology()
    with pytest.raises(Failed), o.ledger.undoable(o):
        o.replace(R, NOW, long(6))
        o.replace(R, NOW, integer(5))
        raise Failed
    assert_as_written(o, long(5))


def test_replace_keeps_each_value_as_written() -> None:
    o = ontology()
    o.replace(R, NOW, long(6))
    assert_as_written(o, long(6))
    o.replace(R, NOW, long(5))
    assert_as_written(o, long(5))
    assert o.reason().consistent
    assert_as_written(o, long(5))


UPDATES = {
    "delete_insert_by_iri": (f'DELETE {{ <{NS}r> <{NS}now> ?v }} INSERT {{ <{NS}r> <{NS}now> "6"^^<{XSD}long> }} '
                             f'WHERE {{ <{NS}r> <{NS}now> ?v }}'),
    "insert_data_by_prefixed_name": (f'PREFIX xsd: <{XSD}> PREFIX k: <{NS}>\nDELETE DATA {{ k:r k:now "5"^^xsd:long }} ;\n'
                                     'INSERT DATA { k:r k:now "06"^^xsd:long }'),
}


@pytest.mark.parametrize("name", list(UPDATES))
def test_a_sparql_update_keeps_each_value_as_written(name: str) -> None:
    """The update's delta is computed on a scratch Oxigraph store, which keeps numbers canonical: the literal
    the text typed is what the graph keeps."""
    o = ontology()
    run_update(Reference("ref", o, NS), UPDATES[name], Job(time.monotonic() + 60), 60.0)
    written = long(6) if name.startswith("delete") else Literal("06", datatype=NamedNode(XSD + "long"))
    assert_as_written(o, written)
    assert o.reason().consistent
    assert_as_written(o, written)


def test_armor_replace_and_query_keep_the_datatype(tmp_path: Path) -> None:
    path = tmp_path / "kept.ttl"
    path.write_text(HEAD)
    svc = ArmorService()

    def ok(command: str, spec1: str, spec2: str, *args: str) -> list[str]:
        res = svc.call({"client_name": "c", "reference_name": "ref", "command": command,
                        "primary_command_spec": spec1, "secondary_command_spec": spec2, "args": list(args)})
        assert res.success, res
        return res.queried_objects

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        ok("LOAD", "FILE", "", str(path), NS.rstrip("#"), "false", "PELLET", "false")
    ok("REPLACE", "DATAPROP", "IND", "now", "r", "LONG", "6", "5")
    ok("REASON", "", "")
    assert ok("QUERY", "DATAPROP", "IND", "now", "r") == ['"6"^^xsd:long']
    ok("REPLACE", "DATAPROP", "IND", "now", "r", "LONG", "5", "6")
    ok("REASON", "", "")
    assert ok("QUERY", "DATAPROP", "IND", "now", "r") == ['"5"^^xsd:long']
    assert ok("QUERY", "DATAPROP", "IND", "now", "q") == ['"6"^^xsd:integer']


def test_http_armor_requests_keep_the_datatype(tmp_path: Path) -> None:
    with in_process(config(tmp_path / "data")) as s:
        s.ok("LOAD", "FILE", "", ["topological_map.owl", "http://bnc/exp-rob-lab/2022-23", "false", "PELLET", "false"])
        s.ok("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "5", "1665579740"])
        s.ok("REASON")
        assert s.ok("QUERY", "DATAPROP", "IND", ["now", "Robot1"])["queried_objects"] == ['"5"^^xsd:long']
        s.ok("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579740", "5"])
        s.ok("REASON")
        assert s.ok("QUERY", "DATAPROP", "IND", ["now", "Robot1"])["queried_objects"] == ['"1665579740"^^xsd:long']


def test_a_durable_store_reopened_keeps_each_value_as_written(tmp_path: Path) -> None:
    o = ontology(open_store(tmp_path, reference="kept"))
    o.replace(R, NOW, long(6))
    o.replace(R, NOW, long(5))
    assert o.reason().consistent
    o.store.close()
    again = Ontology(store=open_store(tmp_path, reference="kept"))
    try:
        assert_as_written(again, long(5))
        assert Triple(R, NOW, long(5)) in again.triples()
    finally:
        again.store.close()
