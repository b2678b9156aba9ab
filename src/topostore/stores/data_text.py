"""Quads as SPARQL update text: what a store that commits through SPARQL (on disk, remote) sends."""

from __future__ import annotations

from pyoxigraph import Quad


def quad_data(quads: list[Quad]) -> str:
    """``GRAPH g { s p o . }`` blocks for INSERT/DELETE DATA, from pyoxigraph terms (escaped by pyoxigraph)."""
    by_graph: dict[str, list[str]] = {}
    for q in quads:
        by_graph.setdefault(str(q.graph_name), []).append(f"{q.subject} {q.predicate} {q.object} .")
    return " ".join(f"GRAPH {g} {{ {' '.join(lines)} }}" for g, lines in by_graph.items())


def data_update(adds: list[Quad], removes: list[Quad]) -> str:
    """One update request removing then adding quads (empty text when there is nothing to do)."""
    ops = []
    if removes:
        ops.append(f"DELETE DATA {{ {quad_data(removes)} }}")
    if adds:
        ops.append(f"INSERT DATA {{ {quad_data(adds)} }}")
    return " ;\n".join(ops)


__all__ = ["quad_data", "data_update"]
