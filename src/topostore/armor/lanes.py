"""One short path per command shape a robot sends every step, taken before the command table.

Why: the general path (:meth:`ArmorService._dispatch`: the table, a :class:`~.context.Context`, the handler, its
helpers, a reply built from a :class:`~.context.Reply`) serves every command, and a robot pays its layers five
times a step for four shapes: REPLACE DATAPROP IND, REPLACE OBJECTPROP IND, QUERY OBJECTPROP IND and QUERY IND
CLASS.  Here each shape is one function: read the arguments, decide the plain case, do the one store read or
write, answer.

What depends on the reference and the shape only is decided once and kept (:class:`Shapes`): whether a
property names facts only and earns no note for a value of the kind the command gives (both read the compiled
rules, so kept while the reference's compiled rules are the same object: a LOAD makes another reference, a TBox
change, a raw SPARQL update naming the schema or an HTTP change of it drops the rules, and a recompilation makes
new ones).  Names and literals are the general path's, from its caches (:func:`.context.entity_named`,
:func:`.context.literal_named`).

A lane answers only the plain case, and decides that before it changes anything: anything else (an argument the
general path refuses, a reference mounted by another client, a durable or buffered reference, one never
reasoned, a value not held) returns None, and the general path runs the command from the start, with its own
checks and its own errors.  The one write a lane makes is :func:`.one_value.replace_plain`'s, the general
path's short lane, so the asserted graph, the literal forms and the ledger are the same.  No lane reasons, so
none has a warning to answer (the general path's ``answered`` block).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial

from pyoxigraph import NamedNode

from ..errors import TopostoreError
from ..ontology.changes import fact_property
from ..ontology.facade import Ontology
from . import one_value
from .context import answer_texts, entity_named, literal_named
from .manipulation import note_for_kind
from .types import ArmorRequest, ArmorResponse

#: whether the service takes the lanes (off: every command goes through the command table)
ENABLED = True

#: a lane: (service, request) → the response, or None for the general path (nothing changed)
Lane = Callable[[object, ArmorRequest], "ArmorResponse | None"]


class Shapes:
    """What the commands' shapes decide on one reference, kept while its compiled rules stand."""

    __slots__ = ("rules", "plain")

    def __init__(self) -> None:
        self.rules: object | None = None
        #: (property, whether the value is a literal) → whether the property names facts only and gives
        #: such a value no note
        self.plain: dict[tuple[NamedNode, bool], bool] = {}

    def plain_property(self, onto: Ontology, prop: NamedNode, literal: bool) -> bool:
        """Whether a value (a literal or an individual) of ``prop`` is a plain fact (see the module docstring);
        False while the rules are not compiled (the general path compiles them)."""
        rules = onto._rules
        if rules is None:
            return False
        if rules is not self.rules:
            self.rules = rules
            self.plain.clear()
        key = (prop, literal)
        found = self.plain.get(key)
        if found is None:
            note = note_for_kind(literal)
            found = self.plain[key] = fact_property(prop) and not note(onto, prop, "")
        return found


def _manipulated(service, req: ArmorRequest):  # noqa: ANN001, ANN202 - ArmorService, Reference | None
    """The reference a manipulation lane may change: loaded, in memory, unmounted or mounted by this client."""
    if service.durable is not None:
        return None
    ref = service._references.get(req.reference_name)
    if ref is None or (ref.owner is not None and ref.owner != req.client_name):
        return None
    return ref


def _replace(service, req: ArmorRequest, data: bool) -> ArmorResponse | None:  # noqa: ANN001 - ArmorService
    """REPLACE DATAPROP IND (``data``) or REPLACE OBJECTPROP IND of one held value by another."""
    args = req.args
    if len(args) != (5 if data else 4) or not one_value.ENABLED:
        return None
    ref = _manipulated(service, req)
    if ref is None:
        return None
    with ref.lock:
        onto = ref.ontology
        if onto._report is None or not one_value.plain_reference(ref):
            return None  # never reasoned: its reply's consistency would reason (the general path answers that)
        prefix = onto.prefix
        try:
            prop, ind = entity_named(args[0], prefix), entity_named(args[1], prefix)
            if data:
                new, old = literal_named(args[3], args[2]), literal_named(args[4], args[2])
            else:
                new, old = entity_named(args[2], prefix), entity_named(args[3], prefix)
        except TopostoreError:  # the general path says which argument, and how
            return None
        shapes = ref.shapes
        if shapes is None:
            shapes = ref.shapes = Shapes()
        if not shapes.plain_property(onto, prop, data):
            return None
        if one_value.replace_plain(ref, ind, prop, new, old) is None:
            return None
        return _answer(service, req, ref, [])


def _query(service, req: ArmorRequest, arity: int, answer: Callable) -> ArmorResponse | None:  # noqa: ANN001
    """A query lane: its ``arity`` arguments name entities, which ``answer`` (the renderer, the ontology, the
    entities) turns into the reply's objects; None (the general path answers, with its own errors) where the
    arity differs, the reference is not loaded or never reasoned, or a name is refused."""
    args = req.args
    if len(args) != arity:
        return None
    ref = service._references.get(req.reference_name)
    if ref is None:
        return None
    with ref.lock:
        onto = ref.ontology
        if onto._report is None:
            return None
        prefix = onto.prefix
        try:
            names = [entity_named(a, prefix) for a in args]
        except TopostoreError:
            return None
        return _answer(service, req, ref, answer(service.renderer, onto, *names))


def _values(renderer, onto: Ontology, prop: NamedNode, ind: NamedNode) -> list[str]:  # noqa: ANN001 - Renderer
    """QUERY OBJECTPROP IND: the individuals a property relates one to."""
    return answer_texts(renderer, onto, onto.reads.individual_values(prop, ind))


def _members(renderer, onto: Ontology, cls: NamedNode) -> list[str]:  # noqa: ANN001 - Renderer
    """QUERY IND CLASS: the members of a class (kept as a view between REASONs)."""
    return onto.reads.rendered_instances(cls, ("armor", renderer.short_names), renderer.member)


def _answer(service, req: ArmorRequest, ref, objects: list[str]) -> ArmorResponse:  # noqa: ANN001
    """The success reply (its reference's lock held): as :meth:`ArmorService._reply` builds it."""
    return ArmorResponse(True, 0, "", service.reply_consistency(req, ref), False, objects, [])


#: the lanes by command key, as a robot spells them (another spelling takes the command table)
LANES: dict[tuple[str, str, str], Lane] = {
    ("REPLACE", "DATAPROP", "IND"): partial(_replace, data=True),
    ("REPLACE", "OBJECTPROP", "IND"): partial(_replace, data=False),
    ("QUERY", "OBJECTPROP", "IND"): partial(_query, arity=2, answer=_values),
    ("QUERY", "IND", "CLASS"): partial(_query, arity=1, answer=_members),
}


__all__ = ["ENABLED", "LANES", "Lane", "Shapes"]
