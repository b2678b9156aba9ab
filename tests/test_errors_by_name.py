"""Errors are caught by name: what can happen is reported, anything else (a bug) surfaces."""

from __future__ import annotations

import pytest
from pyoxigraph import Literal, NamedNode, Triple

from topostore import InvalidValueError, Ontology
from topostore.armor_api.armor_client import ArmorClient
from topostore.armor_api.armor_exceptions import ArmorServiceCallError
from topostore.armor_api.http_transport import _error_text
from topostore.rdf.vocab import MAP_NS, xsd

R1, URL = NamedNode(MAP_NS + "R1"), NamedNode(MAP_NS + "homepage")


def test_a_literal_of_a_datatype_topostore_does_not_validate_is_kept_as_written() -> None:
    onto = Ontology(prefix=MAP_NS)
    value = Literal("http://example.org/r1", datatype=xsd("anyURI"))
    assert onto.add(Triple(R1, URL, value)) == 1
    assert onto.data_values("homepage", "R1") == [value]


def test_an_invalid_value_of_a_known_datatype_is_refused_and_changes_nothing() -> None:
    onto = Ontology(prefix=MAP_NS)
    with pytest.raises(InvalidValueError, match="not a valid xsd:long"):
        onto.add(Triple(R1, NamedNode(MAP_NS + "visitedAt"), Literal("soon", datatype=xsd("long"))))
    assert onto.triples() == []


class Unreachable:
    def call(self, request):
        raise ConnectionRefusedError("connection refused")

    def call_many(self, requests):
        raise ConnectionRefusedError("connection refused")


class Buggy:
    def call(self, request):
        raise KeyError("a bug in the transport")

    def call_many(self, requests):
        raise KeyError("a bug in the transport")


def test_an_unreachable_service_is_a_call_error_and_a_bug_surfaces_as_itself() -> None:
    with pytest.raises(ArmorServiceCallError, match="connection refused"):
        ArmorClient("c", "ref", transport=Unreachable()).query.check_ind_exists("R1")
    with pytest.raises(ArmorServiceCallError, match="serialized service call failed: connection refused"):
        ArmorClient("c", "ref", transport=Unreachable()).call_serialized([("APPLY", "", "", [])])
    with pytest.raises(KeyError, match="a bug in the transport"):
        ArmorClient("c", "ref", transport=Buggy()).query.check_ind_exists("R1")
    with pytest.raises(KeyError, match="a bug in the transport"):
        ArmorClient("c", "ref", transport=Buggy()).call_serialized([("APPLY", "", "", [])])


def test_an_http_error_page_is_described_by_its_json_error_or_its_status_line() -> None:
    page = b'{"error": "reference map is mounted by robot"}'
    assert _error_text(page, "Conflict") == "reference map is mounted by robot"
    assert _error_text(b"<html>Bad Gateway</html>", "Bad Gateway") == "Bad Gateway"
    assert _error_text(b'["not", "an", "object"]', "Bad Gateway") == "Bad Gateway"
    assert _error_text(b"\xff\xfe", "Bad Gateway") == "Bad Gateway"
