"""Standard RDF interfaces mounted into the HTTP service (app.py).

:mod:`.gsp` is the SPARQL 1.1 Graph Store HTTP Protocol on each reference
(read and write the asserted graph, upload ontology files), :mod:`.description`
the SPARQL 1.1 Service Description of each endpoint.
"""

from .description import describe_service
from .gsp import GraphStore

__all__ = ["GraphStore", "describe_service"]
