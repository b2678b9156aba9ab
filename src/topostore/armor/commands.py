"""The aRMOR command table: every COMMAND/SPEC1/SPEC2 of spec §3 and its handler.

Each handler validates *all* its arguments before touching anything and then
either answers a query or hands :class:`~topostore.armor.reference.Change`
objects to the reference, which applies them (or queues them under
manipulation buffering) all or nothing.  Failures are raised as
:class:`~topostore.armor.codes.CommandError` with a documented exit code and a
message that says what to fix; the service turns them into replies.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Triple

from .. import terms
from ..errors import InvalidNameError, InvalidValueError, QueryError, TopostoreError, UnknownTypeError
from ..ontology import Ontology
from ..queries import QueryItem, render_jena
from ..store import fresh_skolem
from ..vocab import (
    ASSERTED, FIRST, NIL, NOTHING, OWL, RDF, RDFS, REST, STANFORD_SWRL, SWRL, SWRLB, THING, TYPE, XSD, is_internal, owl,
    rdfs,
)
from . import codes
from .codes import CommandError
from .reference import REASONERS, Change, Delta, Reference
from .render import short_name

if TYPE_CHECKING:  # pragma: no cover
    from .service import ArmorService
    from .types import ArmorRequest

SUBCLASS_OF = rdfs("subClassOf")
#: namespaces whose terms give the ontology its meaning; RENAME refuses them
_VOCABULARIES = (RDF, RDFS, OWL, XSD, SWRL, SWRLB, STANFORD_SWRL)
EQUIVALENT_CLASS = owl("equivalentClass")


@dataclass
class Reply:
    """What a handler answers; the service adds ``is_consistent`` and wraps it in a response."""

    queried_objects: list[str] = field(default_factory=list)
    sparql_queried_objects: list[QueryItem] = field(default_factory=list)
    timeout: bool = False
    warnings: list[str] = field(default_factory=list)
    success: bool = True
    exit_code: int = codes.SUCCESS


@dataclass
class Context:
    """One call being executed: the service, the request and (when needed) its reference."""

    service: "ArmorService"
    request: "ArmorRequest"
    ref: Reference | None = None

    @property
    def args(self) -> list[str]:
        return self.request.args

    @property
    def reference(self) -> Reference:
        assert self.ref is not None, "command registered without needs_ref"
        return self.ref

    @property
    def onto(self) -> Ontology:
        return self.reference.ontology

    def iri(self, position: int, what: str) -> NamedNode:
        """Entity IRI of ``args[position]``; 208 with the reason when the name is illegal."""
        try:
            return terms.entity(self.args[position], self.reference.prefix)
        except InvalidNameError as exc:
            raise CommandError(codes.INVALID_ARGUMENT, f"argument {position + 1} ({what}): {exc}") from None

    def literal(self, value_pos: int, type_pos: int) -> Literal:
        """Typed literal of ``args[value_pos]`` with type name ``args[type_pos]`` (spec §2.3)."""
        try:
            return terms.typed_literal(self.args[value_pos], self.args[type_pos])
        except UnknownTypeError as exc:
            raise CommandError(codes.UNKNOWN_TYPE, f"argument {type_pos + 1}: {exc}") from None
        except InvalidValueError as exc:
            raise CommandError(codes.INVALID_ARGUMENT, f"argument {value_pos + 1} (value): {exc}") from None

    def flag(self, position: int, what: str) -> bool:
        """A boolean argument: ``true``/``false`` in any case (aRMOR's convention)."""
        text = self.args[position].strip().lower()
        if text in ("true", "1"):
            return True
        if text in ("false", "0", ""):
            return False
        raise CommandError(codes.INVALID_ARGUMENT, f"argument {position + 1} ({what}) must be true or false, got {self.args[position]!r}")

    def render(self, items: list) -> list[str]:
        """Render terms in the service's mode; sorted so answers are reproducible."""
        return sorted(self.service.renderer.terms([t for t in items if not _hidden(t)]))

    def submit(self, *changes: Change) -> Reply:
        """Apply (or queue) manipulations; a failure of the reasoner undoes them (209)."""
        if changes:  # the request that made them, so a durable store can persist a buffer
            changes[0].origin = self.request.to_dict()
        try:
            warnings = self.reference.submit(list(changes))
        except (TopostoreError, OSError) as exc:  # reasoning, the store or its files failed; a bug surfaces as one
            raise CommandError(codes.REASONER_OR_QUERY_FAILURE, f"the change was undone because reasoning failed: {exc}") from exc
        return Reply(warnings=warnings)


Handler = Callable[[Context], Reply]


@dataclass(frozen=True)
class Command:
    """A table entry: handler, accepted argument count and how the call is gated."""

    handler: Handler
    args: tuple[str, ...]  # names of the arguments, for error messages
    min_args: int
    max_args: int | None  # None: variadic
    needs_ref: bool = True
    manipulation: bool = False

    def check_arity(self, n: int) -> None:
        if n < self.min_args or (self.max_args is not None and n > self.max_args):
            if self.max_args is None:
                expected = f"at least {self.min_args}"
            elif self.min_args == self.max_args:
                expected = str(self.min_args)
            else:
                expected = f"{self.min_args} to {self.max_args}"
            names = ", ".join(self.args) if self.args else "none"
            raise CommandError(codes.INVALID_ARGUMENT, f"expected {expected} argument(s) [{names}], got {n}")


def _hidden(term: object) -> bool:
    """Terms never shown in answers: internal IRIs, owl:Thing and owl:Nothing (spec §7 item 6)."""
    return is_internal(term) or term in (THING, NOTHING)


# ----------------------------------------------------------------- RDF builders

def rdf_list(items: list[NamedNode]) -> tuple[NamedNode, list[Triple]]:
    """An RDF collection of ``items``: (head node, triples)."""
    if not items:
        return NIL, []
    nodes = [fresh_skolem() for _ in items]
    triples: list[Triple] = []
    for i, (node, item) in enumerate(zip(nodes, items)):
        triples.append(Triple(node, FIRST, item))
        triples.append(Triple(node, REST, nodes[i + 1] if i + 1 < len(nodes) else NIL))
    return nodes[0], triples


def all_different(members: list[NamedNode]) -> list[Triple]:
    """ONE owl:AllDifferent over ``members`` (linear size, same shape as Ontology.add_all_different)."""
    group = fresh_skolem()
    head, triples = rdf_list(members)
    return [Triple(group, TYPE, owl("AllDifferent")), Triple(group, owl("distinctMembers"), head)] + triples


def all_disjoint_classes(members: list[NamedNode]) -> list[Triple]:
    """ONE owl:AllDisjointClasses over ``members`` (an n-ary DisjointClasses axiom)."""
    group = fresh_skolem()
    head, triples = rdf_list(members)
    return [Triple(group, TYPE, owl("AllDisjointClasses")), Triple(group, owl("members"), head)] + triples


def _fixed(description: str, add: Sequence[Triple] = (), remove: Sequence[Triple] = ()) -> Change:
    """A change whose triples do not depend on the state at application time."""
    to_add, to_remove = list(add), list(remove)
    return Change(description, lambda onto: Delta(add=to_add, remove=to_remove))


def _asserted(onto: Ontology, s=None, p=None, o=None) -> list[Triple]:
    return list(onto.store.triples(s, p, o, ASSERTED))


def _distinct(ctx: Context, what: str) -> list[NamedNode]:
    """Every argument as an IRI, de-duplicated; at least two are needed for an n-ary axiom."""
    members = list(dict.fromkeys(ctx.iri(i, what) for i in range(len(ctx.args))))
    if len(members) < 2:
        raise CommandError(codes.INVALID_ARGUMENT, f"DISJOINT needs at least two different {what} names, got {len(members)}")
    return members


# ----------------------------------------------------------------- manipulations

def add_ind(ctx: Context) -> Reply:
    ind = ctx.iri(0, "individual")
    return ctx.submit(_fixed("ADD IND", add=[Triple(ind, TYPE, THING)]))


def add_class(ctx: Context) -> Reply:
    cls = ctx.iri(0, "class")
    return ctx.submit(_fixed("ADD CLASS", add=[Triple(cls, SUBCLASS_OF, THING)]))


def add_ind_class(ctx: Context) -> Reply:
    ind, cls = ctx.iri(0, "individual"), ctx.iri(1, "class")
    return ctx.submit(_fixed("ADD IND CLASS", add=[Triple(ind, TYPE, cls)]))


def add_class_class(ctx: Context) -> Reply:
    sub, sup = ctx.iri(0, "subclass"), ctx.iri(1, "superclass")
    return ctx.submit(_fixed("ADD CLASS CLASS", add=[Triple(sub, SUBCLASS_OF, sup)]))


def add_dataprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "data property"), ctx.iri(1, "individual")
    value = ctx.literal(3, 2)
    key = terms.value_key(value)

    def plan(onto: Ontology) -> Delta:
        present = any(terms.value_key(t.object) == key for t in _asserted(onto, ind, prop))
        return Delta(add=[] if present else [Triple(ind, prop, value)])

    return ctx.submit(Change("ADD DATAPROP IND", plan))


def add_objectprop_ind(ctx: Context) -> Reply:
    prop, ind, value = ctx.iri(0, "object property"), ctx.iri(1, "individual"), ctx.iri(2, "value individual")
    return ctx.submit(_fixed("ADD OBJECTPROP IND", add=[Triple(ind, prop, value)]))


def add_cardinality_min(ctx: Context) -> Reply:
    cls, prop = ctx.iri(0, "class"), ctx.iri(1, "object property")
    try:
        count = terms.literal_of(ctx.args[2], "nonNegativeInteger")
    except InvalidValueError as exc:
        raise CommandError(codes.INVALID_ARGUMENT, f"argument 3 (cardinality): {exc}") from None
    filler = ctx.iri(3, "value class")
    node = fresh_skolem()
    triples = [
        Triple(node, TYPE, owl("Restriction")),
        Triple(node, owl("onProperty"), prop),
        Triple(node, owl("minQualifiedCardinality"), count),
        Triple(node, owl("onClass"), filler),
        Triple(cls, SUBCLASS_OF, node),
    ]
    return ctx.submit(_fixed("ADD CARDINALITY MIN", add=triples))


def disjoint_ind(ctx: Context) -> Reply:
    members = _distinct(ctx, "individual")
    return ctx.submit(_fixed("DISJOINT IND", add=all_different(members)))


def disjoint_class(ctx: Context) -> Reply:
    members = _distinct(ctx, "class")
    return ctx.submit(_fixed("DISJOINT CLASS", add=all_disjoint_classes(members)))


def disjoint_ind_class(ctx: Context) -> Reply:
    cls = ctx.iri(0, "class")

    def plan(onto: Ontology) -> Delta:
        members = sorted((i for i in onto.instances(cls) if not _hidden(i)), key=lambda n: n.value)
        if len(members) < 2:
            return Delta(warning=f"{cls.value} has {len(members)} instance(s); no axiom added")
        return Delta(add=all_different(members))

    return ctx.submit(Change("DISJOINT IND CLASS", plan))


def disjoint_class_class(ctx: Context) -> Reply:
    cls = ctx.iri(0, "class")

    def plan(onto: Ontology) -> Delta:
        members = sorted((c for c in onto.subclasses(cls) if not _hidden(c)), key=lambda n: n.value)
        if len(members) < 2:
            return Delta(warning=f"{cls.value} has {len(members)} subclass(es); no axiom added")
        return Delta(add=all_disjoint_classes(members))

    return ctx.submit(Change("DISJOINT CLASS CLASS", plan))


def make_equivalent_class(ctx: Context) -> Reply:
    cls = ctx.iri(0, "class")

    def plan(onto: Ontology) -> Delta:
        links = _asserted(onto, cls, SUBCLASS_OF)
        supers = [t.object for t in links if t.object != cls]
        if not supers:
            return Delta(warning=f"{cls.value} has no asserted superclass; nothing made equivalent")
        if len(supers) == 1:
            return Delta(add=[Triple(cls, EQUIVALENT_CLASS, supers[0])], remove=links)
        node = fresh_skolem()
        head, items = rdf_list(supers)
        add = [Triple(node, TYPE, owl("Class")), Triple(node, owl("intersectionOf"), head), Triple(cls, EQUIVALENT_CLASS, node)]
        return Delta(add=add + items, remove=links)

    return ctx.submit(Change("MAKE EQUIVALENT CLASS", plan))


def remove_ind(ctx: Context) -> Reply:
    ind = ctx.iri(0, "individual")

    def plan(onto: Ontology) -> Delta:
        doomed = _asserted(onto, ind) + _asserted(onto, None, None, ind)
        for t in list(doomed):
            if t.predicate == FIRST:  # whole n-ary axioms (AllDifferent) containing it
                doomed += onto._axiom_of_list_node(t.subject)
        return Delta(remove=list(dict.fromkeys(doomed)))

    return ctx.submit(Change("REMOVE IND", plan))


def remove_class(ctx: Context) -> Reply:
    """Undo of ADD CLASS: removes only ``SubClassOf(cls owl:Thing)``; the class's other axioms stay."""
    cls = ctx.iri(0, "class")
    return ctx.submit(_fixed("REMOVE CLASS", remove=[Triple(cls, SUBCLASS_OF, THING)]))


def remove_ind_class(ctx: Context) -> Reply:
    ind, cls = ctx.iri(0, "individual"), ctx.iri(1, "class")
    return ctx.submit(_fixed("REMOVE IND CLASS", remove=[Triple(ind, TYPE, cls)]))


def remove_class_class(ctx: Context) -> Reply:
    sub, sup = ctx.iri(0, "subclass"), ctx.iri(1, "superclass")
    return ctx.submit(_fixed("REMOVE CLASS CLASS", remove=[Triple(sub, SUBCLASS_OF, sup)]))


def _matching_values(onto: Ontology, ind: NamedNode, prop: NamedNode, value) -> list[Triple]:
    """Asserted ``prop(ind, v)`` whose v is the same data value (or the same individual) as ``value``."""
    key = terms.value_key(value)
    return [t for t in _asserted(onto, ind, prop) if terms.value_key(t.object) == key]


def remove_dataprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "data property"), ctx.iri(1, "individual")
    value = ctx.literal(3, 2)
    return ctx.submit(Change("REMOVE DATAPROP IND", lambda onto: Delta(remove=_matching_values(onto, ind, prop, value))))


def remove_objectprop_ind(ctx: Context) -> Reply:
    prop, ind, value = ctx.iri(0, "object property"), ctx.iri(1, "individual"), ctx.iri(2, "value individual")
    return ctx.submit(_fixed("REMOVE OBJECTPROP IND", remove=[Triple(ind, prop, value)]))


def _replace(ind: NamedNode, prop: NamedNode, new, old, description: str) -> Change:
    """Remove ``prop(ind, old)`` (matched by data value), add ``prop(ind, new)``; warn if old was absent."""

    def plan(onto: Ontology) -> Delta:
        olds = _matching_values(onto, ind, prop, old)
        new_key = terms.value_key(new)
        present = any(terms.value_key(t.object) == new_key for t in _asserted(onto, ind, prop)) and not any(
            terms.value_key(t.object) == new_key for t in olds)
        warning = "" if olds else (
            f"{description}: old value {render_jena(old)} of {prop.value} for {ind.value} was not asserted; "
            "the new value was added and the existing values were kept")
        return Delta(add=[] if present else [Triple(ind, prop, new)], remove=olds, warning=warning)

    return Change(description, plan)


def replace_dataprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "data property"), ctx.iri(1, "individual")
    new, old = ctx.literal(3, 2), ctx.literal(4, 2)
    return ctx.submit(_replace(ind, prop, new, old, "REPLACE DATAPROP IND"))


def replace_objectprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "object property"), ctx.iri(1, "individual")
    new, old = ctx.iri(2, "new value"), ctx.iri(3, "old value")
    return ctx.submit(_replace(ind, prop, new, old, "REPLACE OBJECTPROP IND"))


def rename(kind: str) -> Handler:
    """RENAME <kind>: the IRI ``old`` becomes ``new`` in every asserted triple."""

    def handler(ctx: Context) -> Reply:
        old, new = ctx.iri(0, f"old {kind} name"), ctx.iri(1, f"new {kind} name")
        for position, term in ((1, old), (2, new)):
            if term.value.startswith(_VOCABULARIES) or is_internal(term):
                raise CommandError(codes.INVALID_ARGUMENT, f"argument {position}: {term.value} belongs to the RDF, "
                                   "RDFS, OWL, XSD or SWRL vocabulary (or to topostore); it cannot be renamed")

        def plan(onto: Ontology) -> Delta:
            sub = (lambda term: new if term == old else term)
            hits = list(dict.fromkeys(_asserted(onto, old) + _asserted(onto, None, old) + _asserted(onto, None, None, old)))
            if not hits:
                return Delta(warning=f"{old.value} does not occur in the ontology; nothing renamed")
            adds = []
            for t in hits:
                obj = onto.store.original_literal(ASSERTED, t.subject, t.predicate, t.object) if isinstance(t.object, Literal) else sub(t.object)
                adds.append(Triple(sub(t.subject), sub(t.predicate), obj))
            return Delta(add=adds, remove=hits)

        return ctx.submit(Change(f"RENAME {kind}", plan))

    handler.__name__ = f"rename_{kind.lower()}"
    handler.__doc__ = f"RENAME {kind} [old, new]."
    return handler


def apply_buffer(ctx: Context) -> Reply:
    """APPLY: run the queued manipulations; a buffered reasoner is not synchronised."""
    try:
        return Reply(warnings=ctx.reference.flush())
    except (TopostoreError, OSError) as exc:  # reasoning, the store or its files failed
        raise CommandError(codes.REASONER_OR_QUERY_FAILURE, f"APPLY failed and changed nothing: {exc}") from exc


def reason(ctx: Context) -> Reply:
    """REASON: apply pending changes and bring the inferences up to date (incrementally), also after an inconsistency."""
    ref = ctx.reference
    try:
        warnings = ref.flush(reason=False)
        ref.ontology.reason()  # on failure the ontology is back at its last successful REASON
    except (TopostoreError, OSError) as exc:  # reasoning, the store or its files failed
        # the buffered changes that broke it are dropped too, or every later REASON would fail the same way
        dropped, ref.buffer = len(ref.buffer), []
        note = f"; {dropped} buffered change(s) were discarded" if dropped else ""
        raise CommandError(codes.REASONER_OR_QUERY_FAILURE, f"reasoning failed and the changes since the last "
                           f"successful REASON were undone: {exc}{note}") from exc
    return Reply(warnings=warnings)


# ----------------------------------------------------------------- queries

def _occurs(onto: Ontology, ind: NamedNode) -> bool:
    for graph in onto.visible_graphs():
        if next(onto.store.triples(ind, None, None, graph), None) or next(onto.store.triples(None, None, ind, graph), None):
            return True
    return False


def query_ind(ctx: Context) -> Reply:
    """QUERY IND: classes of an individual; ``[owl:Thing]`` if it has none (spec §7 item 11)."""
    ind = ctx.iri(0, "individual")
    if not _occurs(ctx.onto, ind):
        return Reply(success=False, warnings=[f"individual {ind.value} does not occur in the ontology"])
    classes = ctx.render(ctx.onto.types(ind))
    return Reply(queried_objects=classes or [ctx.service.renderer.term(THING)])


def query_ind_class(ctx: Context) -> Reply:
    return Reply(queried_objects=ctx.render(ctx.onto.instances(ctx.iri(0, "class"))))


def query_dataprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "data property"), ctx.iri(1, "individual")
    return Reply(queried_objects=ctx.render(ctx.onto.data_values(prop, ind)))


def query_objectprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "object property"), ctx.iri(1, "individual")
    return Reply(queried_objects=ctx.render(ctx.onto.object_values(prop, ind, names=False)))


def most_specific(onto: Ontology, classes: list[NamedNode]) -> list[NamedNode]:
    """Classes with no strict subclass among ``classes`` (equivalent classes all stay)."""
    result = []
    for c in classes:
        below = onto.subclasses(c)
        if not any(d in below and c not in onto.subclasses(d) for d in classes if d != c):
            result.append(c)
    return result


def query_class_ind(ctx: Context) -> Reply:
    """QUERY CLASS IND [ind, bottom?]: all classes, or the most specific ones as sorted short names."""
    ind = ctx.iri(0, "individual")
    bottom = ctx.flag(1, "bottom") if len(ctx.args) > 1 else False
    classes = [c for c in ctx.onto.types(ind) if not _hidden(c)]
    if not bottom:
        return Reply(queried_objects=ctx.render(classes))
    return Reply(queried_objects=sorted({short_name(c) for c in most_specific(ctx.onto, classes)}))


def query_class_class(ctx: Context) -> Reply:
    return Reply(queried_objects=ctx.render(list(ctx.onto.subclasses(ctx.iri(0, "class")))))


def query_ind_dataprop(ctx: Context) -> Reply:
    return Reply(queried_objects=ctx.render(ctx.onto.properties_of(ctx.iri(0, "individual"), data=True)))


def query_ind_objectprop(ctx: Context) -> Reply:
    return Reply(queried_objects=ctx.render(ctx.onto.properties_of(ctx.iri(0, "individual"), data=False)))


_CARDINALITIES = (
    ("MIN", ("minQualifiedCardinality", "minCardinality")),
    ("MAX", ("maxQualifiedCardinality", "maxCardinality")),
    ("EXACT", ("qualifiedCardinality", "cardinality")),
)


def _is_data_restriction(onto: Ontology, prop, filler) -> bool:
    if onto.store.contains(Triple(prop, TYPE, owl("DatatypeProperty")), ASSERTED):
        return True
    return isinstance(filler, NamedNode) and (filler.value.startswith(XSD) or filler == rdfs("Literal") or
                                             onto.store.contains(Triple(filler, TYPE, rdfs("Datatype")), ASSERTED))


def _one(onto: Ontology, node, name: str):
    values = onto.store.objects(node, owl(name), ASSERTED)
    return values[0] if values else None


def restriction_item(onto: Ontology, subject: str, node) -> str | None:
    """One restriction in aRMOR's grammar, e.g. ``C-DEFINITION_MIN_OBJECT : CORRIDOR -> hasDoor 2(DOOR)``."""
    prop = _one(onto, node, "onProperty")
    if prop is None:
        return None
    for kind, names in _CARDINALITIES:
        for name in names:
            count = _one(onto, node, name)
            if count is not None:
                filler = _one(onto, node, "onClass") or _one(onto, node, "onDataRange")
                data = _is_data_restriction(onto, prop, filler)
                filler = filler or (rdfs("Literal") if data else THING)
                return (f"C-DEFINITION_{kind}_{'DATA' if data else 'OBJECT'} : {subject} -> "
                        f"{short_name(prop)} {count.value}({short_name(filler)})")
    for kind, name in (("SOME", "someValuesFrom"), ("ALL", "allValuesFrom")):
        filler = _one(onto, node, name)
        if filler is not None:
            data = _is_data_restriction(onto, prop, filler)
            return f"C-DEFINITION_{kind}_{'DATA' if data else 'OBJECT'} : {subject} -> {short_name(prop)}({short_name(filler)})"
    return None


def restriction_items(onto: Ontology, cls: NamedNode, expression) -> list[str]:
    """Items of one class expression: named classes and restrictions, intersections flattened."""
    subject = short_name(cls)
    if isinstance(expression, NamedNode) and not is_internal(expression):
        return [] if expression in (cls, THING) else [f"C-DEFINITION_CLASS : {subject} -> ({short_name(expression)})"]
    operands = onto.store.objects(expression, owl("intersectionOf"), ASSERTED)
    if operands:
        return [item for member in onto.store.list_items(operands[0], ASSERTED) for item in restriction_items(onto, cls, member)]
    item = restriction_item(onto, subject, expression)
    return [item] if item else []


def query_class_restrictions(ctx: Context) -> Reply:
    """QUERY CLASS RESTRICTIONS: one element per SubClassOf/EquivalentClasses axiom with a restriction."""
    onto, cls = ctx.onto, ctx.iri(0, "class")
    expressions = ([t.object for t in _asserted(onto, cls, SUBCLASS_OF)] +
                   [t.object for t in _asserted(onto, cls, EQUIVALENT_CLASS)] +
                   [t.subject for t in _asserted(onto, None, EQUIVALENT_CLASS, cls)])
    answers = []
    for expression in dict.fromkeys(expressions):
        items = restriction_items(onto, cls, expression)
        if any(not i.startswith("C-DEFINITION_CLASS") for i in items):
            answers.append("[" + ", ".join(sorted(items)) + "]")  # sorted: reproducible answers
    return Reply(queried_objects=sorted(answers))


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
        raise CommandError(codes.INVALID_ARGUMENT, f"timeout must be an integer number of milliseconds, got {raw[:40]!r}") from None
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
    flat = ", ".join("{" + ", ".join(f"{v}={render(x)}" for v, x in zip(variables, row)) + "}" for row in rows)
    return Reply(queried_objects=[flat], timeout=timed_out)


def query_sparql_formatted(ctx: Context) -> Reply:
    """QUERY SPARQL FORMATTED: one QueryItem per projected variable per row ("" when unbound)."""
    text, timeout = _sparql_args(ctx)
    variables, rows, timed_out = run_select(ctx.onto, text, _query_limit(ctx, timeout))
    items = [QueryItem(v, render_jena(x, ctx.onto.store.restore)) for row in rows for v, x in zip(variables, row)]
    return Reply(sparql_queried_objects=items, timeout=timed_out)


# ----------------------------------------------------------------- utilities

def _mount(ref: Reference, client: str) -> Reply:
    """Mount ``client`` on ``ref`` unless another client holds it (203)."""
    if ref.owner is not None and ref.owner != client:
        raise CommandError(codes.CANNOT_MOUNT, f"reference {ref.name!r} is mounted by client {ref.owner!r}; it must UNMOUNT first")
    already = ref.owner == client
    ref.owner = client
    ref.save_state()
    return Reply(warnings=[f"client {client!r} was already mounted on {ref.name!r}"] if already else [])


def mount(ctx: Context) -> Reply:
    return _mount(ctx.reference, ctx.request.client_name)


def unmount(ctx: Context) -> Reply:
    """UNMOUNT: only the mounted client can unmount; anyone else gets a warning (success, as in aRMOR)."""
    ref, client = ctx.reference, ctx.request.client_name
    if ref.owner == client:
        ref.owner = None
        ref.save_state()
        return Reply()
    holder = "nobody" if ref.owner is None else f"client {ref.owner!r}"
    return Reply(warnings=[f"client {client!r} is not mounted on {ref.name!r} ({holder} is); nothing changed"])


def load(source: str, mounted: bool) -> Handler:
    """LOAD FILE|WEB [MOUNTED] [location, iri, buffered manipulation, reasoner, buffered reasoner]."""

    def handler(ctx: Context) -> Reply:
        req = ctx.request
        try:
            base = terms.iri(ctx.args[1])
        except InvalidNameError as exc:
            raise CommandError(codes.INVALID_ARGUMENT, f"argument 2 (ontology IRI): {exc}") from None
        buffered_manipulation = ctx.flag(2, "buffered manipulation")
        reasoner = ctx.args[3].strip().upper()
        if reasoner not in REASONERS:
            raise CommandError(codes.INVALID_ARGUMENT, f"argument 4: unknown reasoner {ctx.args[3]!r}; use one of "
                               + ", ".join(repr(r) for r in sorted(REASONERS)))
        buffered_reasoner = ctx.flag(4, "buffered reasoner")
        ref, created = ctx.service.load_reference(
            req.reference_name, source, ctx.args[0], base.value, buffered_manipulation, reasoner or "PELLET", buffered_reasoner)
        ctx.ref = ref
        warnings = [] if created else [f"reference {ref.name!r} already exists and was reused as is; "
                                       "the LOAD arguments were ignored (DROP it first to reload)"]
        if mounted:
            with ref.lock:
                warnings += _mount(ref, req.client_name).warnings
        return Reply(warnings=warnings)

    handler.__name__ = f"load_{source.lower()}{'_mounted' if mounted else ''}"
    return handler


def save(inferred: bool) -> Handler:
    """SAVE [path] / SAVE INFERENCE [path]: write the applied ontology; the reference is unchanged."""

    def handler(ctx: Context) -> Reply:
        ref = ctx.reference
        if ctx.args[0] == "":
            if ref.source is None:
                raise CommandError(codes.INVALID_ARGUMENT, "argument 1 (path) is empty and the reference has no source file to overwrite")
            target = ref.source
        else:
            target = ctx.service.resolve_path(ctx.args[0])
        ctx.service.note_ontology_file(target)
        try:
            ref.ontology.save(target, inferred=inferred)
        except OSError as exc:
            raise CommandError(codes.FILE_ERROR, f"cannot write {target}: {exc.strerror or exc}") from None
        pending = len(ref.buffer)
        return Reply(warnings=[f"{pending} buffered manipulation(s) not applied yet were not saved"] if pending else [])

    handler.__name__ = "save_inference" if inferred else "save"
    return handler


def get_all_refs(ctx: Context) -> Reply:
    return Reply(queried_objects=sorted(ctx.service.reference_names()))


def get_ref_client(ctx: Context) -> Reply:
    """GET REF CLIENT [ref]: the mounted client of ``args[0]``, ``none`` when unmounted."""
    ref = ctx.service.reference(ctx.args[0])
    return Reply(queried_objects=["none" if ref.owner is None else ref.owner])


def drop(ctx: Context) -> Reply:
    dropped = ctx.service.drop_reference(ctx.request.reference_name)
    return Reply(warnings=[] if dropped else [f"reference {ctx.request.reference_name!r} was not loaded; nothing dropped"])


def log_file_on(ctx: Context) -> Reply:
    """LOG FILE ON [path]: copy the service log to a file; ``none`` switches file logging off."""
    if ctx.args[0].strip().lower() == "none":
        ctx.service.log_to_file(None)
    else:
        ctx.service.log_to_file(ctx.service.resolve_path(ctx.args[0]))
    return Reply()


def log_file_off(ctx: Context) -> Reply:
    ctx.service.log_to_file(None)
    return Reply()


def log_screen(on: bool) -> Handler:
    def handler(ctx: Context) -> Reply:
        ctx.service.log_to_screen(on)
        return Reply()

    handler.__name__ = f"log_screen_{'on' if on else 'off'}"
    return handler


def invalid_command(ctx: Context) -> Reply:
    raise CommandError(codes.UNKNOWN_COMMAND, "INVALID COMMAND is registered only to be refused")


# ----------------------------------------------------------------- table


def _table() -> dict[tuple[str, str, str], Command]:
    """Key (COMMAND, SPEC1, SPEC2), upper case → command.  Tuples, so a ``_`` in a field cannot fake a key."""
    m = dict(needs_ref=True, manipulation=True)
    q = dict(needs_ref=True, manipulation=False)
    table = {
        ("ADD", "IND", ""): Command(add_ind, ("individual",), 1, 1, **m),
        ("ADD", "CLASS", ""): Command(add_class, ("class",), 1, 1, **m),
        ("ADD", "IND", "CLASS"): Command(add_ind_class, ("individual", "class"), 2, 2, **m),
        ("ADD", "CLASS", "CLASS"): Command(add_class_class, ("subclass", "superclass"), 2, 2, **m),
        ("ADD", "DATAPROP", "IND"): Command(add_dataprop_ind, ("property", "individual", "type", "value"), 4, 4, **m),
        ("ADD", "OBJECTPROP", "IND"): Command(add_objectprop_ind, ("property", "individual", "value"), 3, 3, **m),
        ("ADD", "CARDINALITY", "MIN"): Command(add_cardinality_min, ("class", "property", "n", "value class"), 4, 4, **m),
        ("ADD", "MIN", "CARDINALITY"): Command(add_cardinality_min, ("class", "property", "n", "value class"), 4, 4, **m),
        ("DISJOINT", "IND", ""): Command(disjoint_ind, ("individual", "individual", "..."), 2, None, **m),
        ("DISJOINT", "CLASS", ""): Command(disjoint_class, ("class", "class", "..."), 2, None, **m),
        ("DISJOINT", "IND", "CLASS"): Command(disjoint_ind_class, ("class",), 1, 1, **m),
        ("DISJOINT", "CLASS", "CLASS"): Command(disjoint_class_class, ("class",), 1, 1, **m),
        ("MAKE", "EQUIVALENT", "CLASS"): Command(make_equivalent_class, ("class",), 1, 1, **m),
        ("REMOVE", "IND", ""): Command(remove_ind, ("individual",), 1, 1, **m),
        ("REMOVE", "CLASS", ""): Command(remove_class, ("class",), 1, 1, **m),
        ("REMOVE", "IND", "CLASS"): Command(remove_ind_class, ("individual", "class"), 2, 2, **m),
        ("REMOVE", "CLASS", "CLASS"): Command(remove_class_class, ("subclass", "superclass"), 2, 2, **m),
        ("REMOVE", "DATAPROP", "IND"): Command(remove_dataprop_ind, ("property", "individual", "type", "value"), 4, 4, **m),
        ("REMOVE", "OBJECTPROP", "IND"): Command(remove_objectprop_ind, ("property", "individual", "value"), 3, 3, **m),
        ("REPLACE", "DATAPROP", "IND"): Command(replace_dataprop_ind, ("property", "individual", "type", "new", "old"), 5, 5, **m),
        ("REPLACE", "OBJECTPROP", "IND"): Command(replace_objectprop_ind, ("property", "individual", "new", "old"), 4, 4, **m),
        ("APPLY", "", ""): Command(apply_buffer, (), 0, 0, **m),
        ("REASON", "", ""): Command(reason, (), 0, 0, **m),
        ("QUERY", "IND", ""): Command(query_ind, ("individual",), 1, 1, **q),
        ("QUERY", "IND", "CLASS"): Command(query_ind_class, ("class",), 1, 1, **q),
        ("QUERY", "DATAPROP", "IND"): Command(query_dataprop_ind, ("property", "individual"), 2, 2, **q),
        ("QUERY", "OBJECTPROP", "IND"): Command(query_objectprop_ind, ("property", "individual"), 2, 2, **q),
        ("QUERY", "CLASS", "IND"): Command(query_class_ind, ("individual", "bottom"), 1, 2, **q),
        ("QUERY", "CLASS", "CLASS"): Command(query_class_class, ("class",), 1, 1, **q),
        ("QUERY", "CLASS", "RESTRICTIONS"): Command(query_class_restrictions, ("class",), 1, 1, **q),
        ("QUERY", "IND", "DATAPROP"): Command(query_ind_dataprop, ("individual",), 1, 1, **q),
        ("QUERY", "IND", "OBJECTPROP"): Command(query_ind_objectprop, ("individual",), 1, 1, **q),
        ("QUERY", "SPARQL", ""): Command(query_sparql, ("query", "timeout ms"), 1, 4, **q),
        ("QUERY", "SPARQL", "FORMATTED"): Command(query_sparql_formatted, ("query", "timeout ms"), 1, 4, **q),
        ("INVALID", "COMMAND", ""): Command(invalid_command, (), 0, None, needs_ref=False),
        ("MOUNT", "", ""): Command(mount, (), 0, 0),
        ("UNMOUNT", "", ""): Command(unmount, (), 0, 0),
        ("SAVE", "", ""): Command(save(False), ("path",), 1, 1),
        ("SAVE", "INFERENCE", ""): Command(save(True), ("path",), 1, 1),
        ("GET", "ALL", "REFS"): Command(get_all_refs, (), 0, 0, needs_ref=False),
        ("GET", "REF", "CLIENT"): Command(get_ref_client, ("reference",), 1, 1, needs_ref=False),
        ("DROP", "", ""): Command(drop, (), 0, 0, needs_ref=False),
        ("LOG", "FILE", "ON"): Command(log_file_on, ("path",), 1, 1, needs_ref=False),
        ("LOG", "FILE", "OFF"): Command(log_file_off, (), 0, 0, needs_ref=False),
        ("LOG", "SCREEN", "ON"): Command(log_screen(True), (), 0, 0, needs_ref=False),
        ("LOG", "SCREEN", "OFF"): Command(log_screen(False), (), 0, 0, needs_ref=False),
    }
    load_args = ("path or url", "ontology iri", "buffered manipulation", "reasoner", "buffered reasoner")
    for source in ("FILE", "WEB"):
        table[("LOAD", source, "")] = Command(load(source, False), load_args, 5, 5, needs_ref=False)
        table[("LOAD", source, "MOUNTED")] = Command(load(source, True), load_args, 5, 5, needs_ref=False)
    for kind in ("IND", "CLASS", "DATAPROP", "OBJECTPROP"):
        table[("RENAME", kind, "")] = Command(rename(kind), ("old", "new"), 2, 2, **m)
    return table


COMMANDS: dict[tuple[str, str, str], Command] = _table()

from .live_commands import live_commands  # noqa: E402  (QUERY EXPLAIN, ADD/REMOVE/QUERY SWRL)

COMMANDS.update(live_commands())

__all__ = ["Command", "Context", "Reply", "Handler", "COMMANDS", "run_select", "most_specific"]
