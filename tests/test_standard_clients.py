"""Real SPARQL/RDF clients against `topostore serve`: SPARQLWrapper, rdflib's SPARQLStore and
SPARQLUpdateStore, rdflib reading the Graph Store, plain HTTP for the Graph Store writes and the
service description.  The server runs in a subprocess on a free loopback port."""

from __future__ import annotations

import json
import shutil
import urllib.parse
from collections.abc import Iterator
from pathlib import Path

import pytest
import rdflib
from http_support import IRI, NS, TBOX, config, in_process, threaded
from http_support import Live as Server
from rdflib.graph import DATASET_DEFAULT_GRAPH_ID
from rdflib.plugins.stores.sparqlstore import SPARQLStore, SPARQLUpdateStore
from SPARQLWrapper import CSV, JSON, JSONLD, N3, POST, RDFXML, TSV, TURTLE, XML, SPARQLWrapper
from support import ABOX_OWL as ABOX

SD = rdflib.Namespace("http://www.w3.org/ns/sparql-service-description#")
CORRIDORS = f"SELECT ?c WHERE {{ ?c a <{NS}CORRIDOR> }}"
CONSTRUCT = f"CONSTRUCT {{ ?r <{NS}canReach> ?l }} WHERE {{ ?r <{NS}canReach> ?l }}"


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    data = tmp_path_factory.mktemp("data")
    shutil.copy(ABOX, data / ABOX.name)
    with threaded(config(data, allow_update=True)) as s:  # uvicorn in a thread: a real socket for the clients
        s.ok("LOAD", "FILE", "", [ABOX.name, IRI, "false", "PELLET", "false"], ref="tutorial")
        s.ok("LOAD", "FILE", "", ["topological_map.owl", IRI, "false", "PELLET", "false"], ref="writable")
        yield s


def endpoint(server: Server, ref: str = "tutorial") -> str:
    return f"{server.url}/references/{ref}/sparql"


def wrapper(server: Server, query: str, fmt: str, method: str = "GET") -> SPARQLWrapper:
    w = SPARQLWrapper(endpoint(server))
    w.setQuery(query)
    w.setReturnFormat(fmt)
    w.setMethod(method)
    return w


@pytest.mark.parametrize("method", ["GET", POST])
def test_sparqlwrapper_select_in_every_format(server: Server, method: str) -> None:
    c1 = f"{NS}C1"
    rows = wrapper(server, CORRIDORS, JSON, method).query().convert()
    assert [b["c"]["value"] for b in rows["results"]["bindings"]] == [c1]
    xml = wrapper(server, CORRIDORS, XML, method).query().convert()
    assert [n.firstChild.data for n in xml.getElementsByTagName("uri")] == [c1]
    assert wrapper(server, CORRIDORS, CSV, method).query().convert().decode().split() == ["c", c1]
    assert wrapper(server, CORRIDORS, TSV, method).query().convert().decode().split() == ["?c", f"<{c1}>"]
    ask = wrapper(server, f"ASK {{ <{c1}> a <{NS}ROOM> }}", JSON, method).query().convert()
    assert ask["boolean"] is True


@pytest.mark.parametrize("method", ["GET", POST])
@pytest.mark.parametrize("fmt", [TURTLE, N3, XML, RDFXML, JSONLD])
def test_sparqlwrapper_construct_in_every_format(server: Server, method: str, fmt: str) -> None:
    """N3 over GET used to get 406: ?format=n3 overrode an Accept header the server could satisfy."""
    result = wrapper(server, CONSTRUCT, fmt, method).query()
    graph = result.convert()
    if not isinstance(graph, rdflib.Graph):  # SPARQLWrapper returns Turtle/N3/JSON-LD as bytes
        ctype = result.info()["content-type"].split(";")[0]
        graph = rdflib.Graph().parse(data=graph, format={"application/ld+json": "json-ld"}.get(ctype, "turtle"))
    assert set(graph) == {(rdflib.URIRef(f"{NS}Robot1"), rdflib.URIRef(f"{NS}canReach"), rdflib.URIRef(f"{NS}{r}"))
                          for r in ("R1", "R2")}


def test_format_parameter_and_accept(server: Server) -> None:
    query = urllib.parse.quote(CONSTRUCT)
    status, headers, _ = server.request(f"/references/tutorial/sparql?query={query}&format=jsonld")
    assert status == 200 and headers["content-type"].split(";")[0] == "application/ld+json"
    # an explicit Accept the format= value does not fit wins over it
    status, headers, _ = server.request(f"/references/tutorial/sparql?query={query}&format=n3",
                                        headers={"Accept": "application/n-triples"})
    assert status == 200 and headers["content-type"].startswith("application/n-triples")
    status, _, body = server.request(f"/references/tutorial/sparql?query={query}&format=n3",
                                     headers={"Accept": "image/png"})
    assert status == 406 and b"text/turtle" in body
    status, _, body = server.request(f"/references/tutorial/sparql?query={query}&format=yaml")
    assert status == 406 and b"use one of turtle, ntriples, rdfxml, jsonld" in body


def test_rdflib_sparqlstore_and_updatestore(server: Server) -> None:
    store = SPARQLStore(endpoint(server, "writable"), returnFormat="json")
    graph = rdflib.Graph(store)
    assert [str(r.c) for r in graph.query(CORRIDORS)] == []
    update = SPARQLUpdateStore(endpoint(server, "writable"), endpoint(server, "writable"))
    g = rdflib.Graph(update, identifier=DATASET_DEFAULT_GRAPH_ID)  # the asserted graph is the default graph
    n = rdflib.Namespace(NS)
    for room, door in (("C9", "D91"), ("C9", "D92"), ("R9", "D91")):
        g.add((n[room], n.hasDoor, n[door]))
    g.add((n.D91, rdflib.OWL.differentFrom, n.D92))  # a CORRIDOR needs two *different* doors
    g.add((n.R9, rdflib.OWL.differentFrom, n.C9))  # and connectedTo two different locations
    assert {str(r.c) for r in graph.query(CORRIDORS)} == {f"{NS}C9"}
    assert {str(r.o) for r in graph.query(f"SELECT ?o WHERE {{ <{NS}R9> <{NS}connectedTo> ?o }}")} == {f"{NS}C9"}
    g.remove((n.C9, n.hasDoor, n.D92))
    assert [str(r.c) for r in graph.query(CORRIDORS)] == []
    with pytest.raises(Exception, match="400"):  # writes to other graphs are refused, not lost
        rdflib.Graph(update, identifier=rdflib.URIRef("http://example.org/g")).add((n.C9, n.hasDoor, n.D93))
    update.close()
    status, _, body = server.request("/references/writable/sparql", b"INSERT DATA { GRAPH <http://example.org/g> "
                                     b"{ <http://a/x> <http://a/p> <http://a/y> } }",
                                     {"Content-Type": "application/sparql-update"})
    assert status == 400 and b"named graph(s) http://example.org/g" in body


def gsp(server: Server, ref: str, method: str, body: bytes | None = None, media: str | None = None,
        query: str = "default", accept: str | None = None) -> tuple[int, dict[str, str], bytes]:
    headers = {}
    if media:
        headers["Content-Type"] = media
    if accept:
        headers["Accept"] = accept
    return server.request(f"/references/{ref}/data?{query}", body, headers, method)


def asserted_count(server: Server, ref: str) -> int:
    status, _, body = server.request("/references")
    return next(r["triples_asserted"] for r in json.loads(body)["references"] if r["name"] == ref)


def test_graph_store_upload_read_merge_replace_delete(server: Server) -> None:
    # upload an OWL file (RDF/XML as Protégé writes it): a PUT to a new reference creates it
    status, headers, body = gsp(server, "uploaded", "PUT", TBOX.read_bytes(), "application/rdf+xml")
    assert status == 201, body
    assert headers["location"] == "/references/uploaded/data?default"
    assert json.loads(body)["iri"] == IRI  # from the document's owl:Ontology
    tbox_triples = asserted_count(server, "uploaded")
    # rdflib reads the graph store (GET with content negotiation)
    g = rdflib.Graph().parse(f"{server.url}/references/uploaded/data?default", format="turtle")
    assert len(g) == tbox_triples
    assert (rdflib.URIRef(f"{NS}Robot1"), rdflib.URIRef(f"{NS}now"), None) in g
    # merge the example environment as Turtle: reasoning follows, like an aRMOR manipulation
    abox = rdflib.Graph().parse(ABOX).serialize(format="turtle").encode()
    status, _, body = gsp(server, "uploaded", "POST", abox, "text/turtle")
    assert status == 200 and json.loads(body)["is_consistent"] is True
    status, _, body = gsp(server, "uploaded", "GET", query=f"graph={urllib.parse.quote('urn:topostore:graph:inferred')}",
                          accept="application/ld+json")
    inferred = rdflib.Graph().parse(data=body, format="json-ld")
    assert set(inferred.objects(rdflib.URIRef(f"{NS}Robot1"), rdflib.URIRef(f"{NS}canReach"))) == \
        {rdflib.URIRef(f"{NS}R1"), rdflib.URIRef(f"{NS}R2")}
    # the asserted graph also answers to the ontology's IRI; N-Triples on request
    status, headers, body = gsp(server, "uploaded", "GET", query="graph=" + urllib.parse.quote(IRI),
                                accept="application/n-triples")
    assert status == 200 and len(body.decode().strip().splitlines()) == asserted_count(server, "uploaded")
    # replace with the TBox only: the environment and its inferences go
    status, _, body = gsp(server, "uploaded", "PUT", TBOX.read_bytes(), "application/rdf+xml")
    assert status == 200, body
    assert asserted_count(server, "uploaded") == tbox_triples
    assert b"canReach" not in gsp(server, "uploaded", "GET", query="graph=urn:topostore:graph:inferred",
                                  accept="text/turtle")[2].replace(b"canReach>", b"")  # no canReach facts left
    status, _, _ = gsp(server, "uploaded", "DELETE")
    assert status == 200 and asserted_count(server, "uploaded") == 0


def test_graph_store_refusals(server: Server) -> None:
    assert gsp(server, "tutorial", "GET", query="")[0] == 400  # neither ?default nor ?graph=
    assert gsp(server, "tutorial", "GET", query="default&graph=x")[0] == 400
    assert gsp(server, "tutorial", "GET", query="graph=http://nowhere/g")[0] == 404
    assert gsp(server, "nobody", "GET")[0] == 404
    assert gsp(server, "nobody", "POST", b"", "text/turtle")[0] == 404
    assert gsp(server, "tutorial", "PUT", b"<a> <b> <c> .", "text/turtle",
               query="graph=urn:topostore:graph:inferred")[0] == 405
    status, _, body = gsp(server, "tutorial", "POST", b"x", "application/owl+xml")
    assert status == 415 and b"application/rdf+xml" in body
    before = asserted_count(server, "tutorial")
    status, _, body = gsp(server, "tutorial", "POST", b"<http://a> <http://b> .", "text/turtle")
    assert status == 400 and b"the graph was not stored" in body
    assert asserted_count(server, "tutorial") == before
    status, _, body = gsp(server, "fresh", "PUT", b"<http://a/x> <http://a/p> <http://a/y> .", "application/n-triples")
    assert status == 400 and b"?iri=" in body
    status, _, _ = gsp(server, "fresh", "PUT", b"<http://a/x> <http://a/p> <http://a/y> .", "application/n-triples",
                       query="default&iri=http://a")
    assert status == 201


def test_graph_store_writes_need_allow_update(tmp_path: Path) -> None:
    with in_process(config(tmp_path / "data")) as s:
        status, _, body = gsp(s, "new", "PUT", TBOX.read_bytes(), "application/rdf+xml")
        assert status == 403 and b"--allow-update" in body
        status, _, body = s.request("/references/new/data?default")
        assert status == 404


def test_service_description(server: Server) -> None:
    status, headers, body = server.request("/references/tutorial/sparql")
    assert status == 200 and headers["content-type"].startswith("text/turtle")
    g = rdflib.Graph().parse(data=body, format="turtle")
    service = rdflib.URIRef(endpoint(server))
    assert (service, rdflib.RDF.type, SD.Service) in g
    assert (service, SD.endpoint, service) in g
    assert set(g.objects(service, SD.supportedLanguage)) == {SD.SPARQL11Query, SD.SPARQL11Update}
    assert rdflib.URIRef("http://www.w3.org/ns/formats/JSON-LD") in set(g.objects(service, SD.resultFormat))
    status, headers, body = server.request("/references/tutorial/sparql", headers={"Accept": "application/ld+json"})
    assert status == 200 and headers["content-type"].split(";")[0] == "application/ld+json"
    assert len(rdflib.Graph().parse(data=body, format="json-ld")) == len(g)
