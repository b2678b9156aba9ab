"""The aRMOR query commands (spec §3.4-3.5): QUERY IND/CLASS/DATAPROP/OBJECTPROP/RESTRICTIONS and QUERY SPARQL.

Answers read asserted ∪ inferred knowledge (asserted only while the ontology
is inconsistent) and are sorted, so the same ontology always gives the same
reply.  QUERY SPARQL runs under the service's time limit (:func:`run_select`).
"""

from __future__ import annotations

import threading

from pyoxigraph import NamedNode, Triple

from ..errors import QueryError
from ..ontology.facade import Ontology
from ..ontology.named_queries import QueryItem, render_jena
from ..rdf.vocab import (
    DIFFERENT_FROM,
    FIRST,
    INTERNAL,
    NAMED_INDIVIDUAL,
    OWL,
    RDF,
    RDFS,
    REST,
    SAME_AS,
    SWRL,
    THING,
    TYPE,
    owl,
)
from . import codes
from .codes import CommandError
from .context import (
    Context,
    Reply,
    answered_classification,
    hidden,
    hierarchy_warnings,
    subclasses,
    told_subclasses,
)
from .render import short_name

#: namespaces whose properties are schema, not facts of an individual (owl:sameAs and owl:differentFrom aside)
_SCHEMA = (RDF, RDFS, OWL, SWRL, INTERNAL)
#: the types that make their subject an individual although in OWL's namespace
_INDIVIDUAL_TYPES = (THING, NAMED_INDIVIDUAL)


def _fact(predicate: NamedNode) -> bool:
    """Whether a triple of ``predicate`` states a fact of its individuals (not a schema axiom)."""
    return predicate in (SAME_AS, DIFFERENT_FROM) or not predicate.value.startswith(_SCHEMA)


def _typed(t: Triple) -> bool:
    """Whether ``t`` (an rdf:type triple) types an individual: with owl:Thing, owl:NamedIndividual or a class."""
    return t.object in _INDIVIDUAL_TYPES or not (
        isinstance(t.object, NamedNode) and t.object.value.startswith((RDF, RDFS, OWL)))


def _occurs(onto: Ontology, ind: NamedNode) -> bool:
    """Whether ``ind`` occurs as an individual: typed, holding or held by a property value, named in an
    equality, a difference or an AllDifferent, as the reasoner aRMOR asks knows its individuals.  A class
    or property named in axioms only is none (aRMOR answers ``success=false`` for it)."""
    for graph in onto.visible_graphs():
        for t in onto.store.triples(ind, None, None, graph):
            if (_typed(t) if t.predicate == TYPE else _fact(t.predicate)):
                return True
        for t in onto.store.triples(None, None, ind, graph):
            if _fact(t.predicate) or (t.predicate == FIRST and _in_all_different(onto, t.subject, graph)):
                return True
    return False


def _in_all_different(onto: Ontology, cell, graph: NamedNode) -> bool:
    """Whether the list cell ``cell`` belongs to the member list of an owl:AllDifferent (walked back to its
    head; a list that loops is left at its first repeated cell)."""
    seen = set()
    while cell not in seen:
        seen.add(cell)
        if any(onto.store.triples(None, p, cell, graph) for p in (owl("distinctMembers"), owl("members"))):
            return True
        before = next(onto.store.triples(None, REST, cell, graph), None)
        if before is None:
            return False
        cell = before.subject
    return False


def query_ind(ctx: Context) -> Reply:
    """QUERY IND: classes of an individual; ``[owl:Thing]`` if it has none (spec §7 item 11)."""
    ind = ctx.iri(0, "individual")
    if not _occurs(ctx.onto, ind):
        return Reply(success=False, warnings=[f"individual {ind.value} does not occur in the ontology"])
    classes = ctx.render(ctx.onto.types(ind))
    return Reply(queried_objects=classes or [ctx.service.renderer.term(THING)])


def query_ind_class(ctx: Context) -> Reply:
    """QUERY IND CLASS: the members, as :meth:`Context.render` writes them (kept as a view between REASONs)."""
    renderer = ctx.service.renderer
    return Reply(queried_objects=ctx.onto.reads.rendered_instances(  # keyed by the renderer's one setting (a tuple
        ctx.iri(0, "class"), ("armor", renderer.short_names),  # hashes in C, the frozen dataclass in Python)
        renderer.member))


def query_dataprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "data property"), ctx.iri(1, "individual")
    return Reply(queried_objects=ctx.render(ctx.onto.data_values(prop, ind)))


def query_objectprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "object property"), ctx.iri(1, "individual")
    return Reply(queried_objects=ctx.render(ctx.onto.reads.individual_values(prop, ind)))


def most_specific(onto: Ontology, classes: list[NamedNode]) -> list[NamedNode]:
    """Classes with no strict subclass among ``classes`` (equivalent classes all stay).  The subclasses are read
    from the classification QUERY CLASS CLASS answers (:func:`.context.answered_classification`: a buffered
    reasoner's as of its last REASON, until the next one), equivalents included, with the told ones added, so
    that both commands answer from one classification."""
    kept = answered_classification(onto)
    below = {c: onto.reasoning.subclasses(c, kept) | told_subclasses(onto, c) for c in classes}
    return [c for c in classes if not any(d in below[c] and c not in below[d] for d in classes if d != c)]


def query_class_ind(ctx: Context) -> Reply:
    """QUERY CLASS IND [ind, bottom?]: all classes, or the most specific ones as sorted short names."""
    ind = ctx.iri(0, "individual")
    bottom = ctx.java_boolean(1) if len(ctx.args) > 1 else False
    classes = [c for c in ctx.onto.types(ind) if not hidden(c)]
    if not bottom:
        return Reply(queried_objects=ctx.render(classes))
    return Reply(queried_objects=sorted({short_name(c) for c in most_specific(ctx.onto, classes)}))


def query_class_class(ctx: Context) -> Reply:
    """QUERY CLASS CLASS: :func:`.context.subclasses`; an unsatisfiable class among them is named in the
    reply, never listed under every class without a word."""
    found = subclasses(ctx.onto, ctx.iri(0, "class"))
    return Reply(queried_objects=ctx.render(found), warnings=hierarchy_warnings(ctx.onto, found))


def query_ind_dataprop(ctx: Context) -> Reply:
    return Reply(queried_objects=ctx.render(ctx.onto.properties_of(ctx.iri(0, "individual"), data=True)))


def query_ind_objectprop(ctx: Context) -> Reply:
    return Reply(queried_objects=ctx.render(ctx.onto.properties_of(ctx.iri(0, "individual"), data=False)))


def run_select(onto: Ontology, text: str, timeout: float | None) -> tuple[list[str], list[list], bool]:
    """(variables, rows, timed_out) of a SELECT over asserted ∪ inferred.

    The query is created and iterated in one worker thread (pyoxigraph result
    iterators must stay on the thread that created them), and the caller waits
    at most ``timeout`` seconds, keeping the rows obtained so far.
    """
    state: dict = {"variables": [], "rows": [], "error": None}
    stop = threading.Event()
    done = threading.Event()

    def worker() -> None:
        try:
            result = onto.sparql(text)
            if not hasattr(result, "variables"):
                raise QueryError("only SELECT queries are supported (got ASK, CONSTRUCT or DESCRIBE)")
            names = [v.value for v in result.variables]
            state["variables"] = names
            for solution in result:
                if stop.is_set():
                    break
                state["rows"].append([solution[v] for v in names])
        except Exception as exc:  # reported by the caller, as text: the traceback would keep the result alive
            state["error"] = f"{type(exc).__name__}: {exc}" if not isinstance(exc, QueryError) else str(exc)
        finally:
            result = None  # pyoxigraph results must be freed on the thread that made them  # noqa: F841
            done.set()

    if timeout is None:  # direct callers only; commands always pass a limit (_query_limit)
        worker()
    else:
        threading.Thread(target=worker, name="armor-sparql", daemon=True).start()
        if not done.wait(timeout):
            stop.set()
            return list(state["variables"]), list(state["rows"]), True
    if state["error"] is not None:
        raise CommandError(codes.REASONER_OR_QUERY_FAILURE, f"SPARQL query failed: {state['error']}")
    return state["variables"], state["rows"], False


def _sparql_args(ctx: Context) -> tuple[str, float | None]:
    """Query text and timeout (seconds or None) from 1-4 args (spec §3.5)."""
    args = ctx.args
    text = args[0] if len(args) in (1, 2) else "".join(args[:3])
    raw = args[1] if len(args) == 2 else args[3] if len(args) == 4 else None
    if raw is None:
        return text, None
    try:
        millis = int(raw.strip())
    except ValueError:
        raise CommandError(
            codes.INVALID_ARGUMENT, f"timeout must be an integer number of milliseconds, got {raw[:40]!r}"
        ) from None
    return text, (millis / 1000.0 if millis > 0 else None)


def _query_limit(ctx: Context, asked: float | None) -> float:
    """The time a query may run: what the client asked, never more than the service's maximum.

    No timeout (or one <= 0) used to mean "unlimited" while the reference's
    lock was held; now it means the maximum (``ArmorService.max_query_seconds``).
    """
    maximum = ctx.service.max_query_seconds
    return maximum if asked is None else min(asked, maximum)


def query_sparql(ctx: Context) -> Reply:
    """QUERY SPARQL: one string ``{x=v, y=w}, {...}``; every projected variable per row, values unmodified."""
    text, timeout = _sparql_args(ctx)
    variables, rows, timed_out = run_select(ctx.onto, text, _query_limit(ctx, timeout))
    render = lambda t: render_jena(t, ctx.onto.store.restore)  # noqa: E731
    flat = ", ".join(
        "{" + ", ".join(f"{v}={render(x)}" for v, x in zip(variables, row, strict=True)) + "}" for row in rows
    )
    return Reply(queried_objects=[flat], timeout=timed_out)


def query_sparql_formatted(ctx: Context) -> Reply:
    """QUERY SPARQL FORMATTED: one QueryItem per projected variable per row ("" when unbound)."""
    text, timeout = _sparql_args(ctx)
    variables, rows, timed_out = run_select(ctx.onto, text, _query_limit(ctx, timeout))
    items = [
        QueryItem(v, render_jena(x, ctx.onto.store.restore))
        for row in rows
        for v, x in zip(variables, row, strict=True)
    ]
    return Reply(sparql_queried_objects=items, timeout=timed_out)


__all__ = ["run_select", "most_specific"]
