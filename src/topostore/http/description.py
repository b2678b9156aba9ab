"""SPARQL 1.1 Service Description of a reference's endpoint.

As the Service Description recommendation asks, a GET on the endpoint without
a query answers an RDF description of the service: its endpoint, the
languages it accepts (queries; updates only with ``--allow-update``), the
result formats, and its dataset — one default graph, the union of what is
asserted and what is inferred, with its size.  Clients and tools (YASGUI,
Comunica, rdflib) read it to find out what the endpoint can do.
"""

from __future__ import annotations

from pyoxigraph import BlankNode, Literal, NamedNode, Triple
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import Response

from ..armor.reference import Reference
from ..rdf.vocab import ASSERTED, FORMATS, RDF, RDFS, SD, TYPE, VOID, XSD
from ..sparql.results import choose_format, render_graph

#: W3C format IRIs of the result formats the endpoint offers (sparql/results.py).
RESULT_FORMATS = ("SPARQL_Results_JSON", "SPARQL_Results_XML", "SPARQL_Results_CSV", "SPARQL_Results_TSV",
                  "Turtle", "N-Triples", "RDF_XML", "JSON-LD")


def _sd(name: str) -> NamedNode:
    return NamedNode(SD + name)


def description(endpoint: str, ref: Reference, allow_update: bool) -> list[Triple]:
    """The service description triples of ``ref``'s endpoint at ``endpoint``."""
    service, dataset, graph = NamedNode(endpoint), BlankNode(), BlankNode()
    with ref.lock:
        size = sum(ref.ontology.store.count(g) for g in ref.ontology.visible_graphs())
    out = [
        Triple(service, TYPE, _sd("Service")),
        Triple(service, _sd("endpoint"), service),
        Triple(service, _sd("supportedLanguage"), _sd("SPARQL11Query")),
        Triple(service, _sd("feature"), _sd("UnionDefaultGraph")),
        Triple(service, _sd("defaultDataset"), dataset),
        Triple(service, NamedNode(RDFS + "comment"), Literal(
            f"Reference {ref.name!r}: the default graph is what is asserted and what topostore infers from it "
            "(OWL 2 RL, cardinalities, SWRL rules, as Pellet does). Graph Store: "
            f"{endpoint.rsplit('/', 1)[0]}/data")),
        Triple(dataset, TYPE, _sd("Dataset")),
        Triple(dataset, _sd("defaultGraph"), graph),
        Triple(graph, TYPE, _sd("Graph")),
        Triple(graph, NamedNode(VOID + "triples"), Literal(str(size), datatype=NamedNode(XSD + "integer"))),
        Triple(graph, NamedNode(RDFS + "seeAlso"), ASSERTED),
    ]
    if allow_update:
        out.append(Triple(service, _sd("supportedLanguage"), _sd("SPARQL11Update")))
    out += [Triple(service, _sd("resultFormat"), NamedNode(FORMATS + f)) for f in RESULT_FORMATS]
    return out


async def describe_service(request: Request, ref: Reference, allow_update: bool) -> Response:
    """The description in the RDF syntax the client accepts (Turtle by default)."""
    endpoint = str(request.url.replace(query=""))
    fmt = choose_format(request.headers.get("accept"), graph=True, explicit=request.query_params.get("format"))
    triples = await run_in_threadpool(description, endpoint, ref, allow_update)
    body = render_graph(triples, fmt, {"sd": SD, "void": VOID, "rdf": RDF, "rdfs": RDFS, "xsd": XSD})
    return Response(body, media_type=fmt.content_type, headers={"Vary": "Accept"})


__all__ = ["description", "describe_service", "SD"]
