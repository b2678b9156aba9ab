"""What every aRMOR command handler works with: the call's context, its reply and the table entry.

A handler gets a :class:`Context` (the service, the request and, for commands
on a reference, that reference), validates *all* its arguments before touching
anything (:meth:`Context.iri`, :meth:`Context.literal`, :meth:`Context.flag`
raise :class:`~topostore.armor.codes.CommandError` with the argument's
position), and either answers with a :class:`Reply` or hands
:class:`~topostore.armor.reference.Change` objects to :meth:`Context.submit`.
The handler families live in :mod:`.manipulation`, :mod:`.query` and
:mod:`.admin`; :mod:`.commands` assembles the table.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Triple

from ..errors import InvalidNameError, InvalidValueError, TopostoreError, UnknownTypeError
from ..ontology.facade import Ontology
from ..ontology.named_queries import QueryItem
from ..rdf import terms
from ..rdf.vocab import ASSERTED, INFERRED, rdfs
from ..reason.classify import unsatisfiable_text
from . import codes
from .codes import CommandError
from .reference import Change, Delta, Reference
from .render import Renderer, hidden

if TYPE_CHECKING:  # pragma: no cover
    from .service import ArmorService
    from .types import ArmorRequest


#: entity IRIs of recent (name, namespace) arguments: a robot names the same few entities every step, and
#: validating a name and building its IRI costs more than the rest of reading its arguments
_entity = lru_cache(maxsize=4096)(terms.entity)
#: literals of recent (text, type name) arguments (a robot's old value is the new value of its previous step)
_literal = lru_cache(maxsize=4096)(terms.typed_literal)


def entity_named(name: str, prefix: str) -> NamedNode:
    """The IRI of the entity ``name`` in ``prefix`` (:func:`~topostore.rdf.terms.entity`), from the recent
    ones; :class:`InvalidNameError` for an illegal name.  Every command's names, on either path."""
    return _entity(name, prefix)


def literal_named(text: str, type_name: str) -> Literal:
    """The literal of ``text`` as aRMOR type ``type_name`` (:func:`~topostore.rdf.terms.typed_literal`), from
    the recent ones; :class:`UnknownTypeError` or :class:`InvalidValueError` as that says.  Every command's
    values, on either path."""
    return _literal(text, type_name)


def answer_texts(renderer: Renderer, onto: Ontology, items: list) -> list[str]:
    """``items`` as a reply lists them: rendered in the renderer's mode (none :func:`hidden`), with the
    language tags as the loaded documents spell them, sorted so answers are reproducible."""
    rendered = renderer.answer(items)
    tags = onto.store.forms.tags
    if not tags or renderer.short_names:  # a short name shows a literal's bare value: no tag to spell
        return sorted(rendered)
    return sorted(tags.rendered(text) for text in rendered)


@dataclass
class Reply:
    """What a handler answers; the service adds ``is_consistent`` and wraps it in a response."""

    queried_objects: list[str] = field(default_factory=list)
    sparql_queried_objects: list[QueryItem] = field(default_factory=list)
    timeout: bool = False
    warnings: list[str] = field(default_factory=list)
    success: bool = True
    exit_code: int = codes.SUCCESS


class Context:
    """One call being executed: the service, the request and (when needed) its reference.

    A plain class with slots: every command makes one, and its handler reads ``args`` a few times."""

    __slots__ = ("service", "request", "ref", "args", "prefix")

    def __init__(self, service: ArmorService, request: ArmorRequest, ref: Reference | None = None) -> None:
        self.service = service
        self.request = request
        self.ref = ref
        self.args: list[str] = request.args
        #: the reference's namespace for entity names, read at the first name (a handler reads every
        #: argument before it changes anything)
        self.prefix: str | None = None

    def __repr__(self) -> str:
        return f"Context({self.request!r}, ref={None if self.ref is None else self.ref.name!r})"

    @property
    def reference(self) -> Reference:
        assert self.ref is not None, "command registered without needs_ref"
        return self.ref

    @property
    def onto(self) -> Ontology:
        return self.reference.ontology

    def iri(self, position: int, what: str) -> NamedNode:
        """Entity IRI of ``args[position]``; 208 with the reason when the name is illegal."""
        prefix = self.prefix
        if prefix is None:
            ref = self.ref
            assert ref is not None, "command registered without needs_ref"
            prefix = self.prefix = ref.ontology.prefix
        try:
            return entity_named(self.args[position], prefix)
        except InvalidNameError as exc:
            raise CommandError(codes.INVALID_ARGUMENT, f"argument {position + 1} ({what}): {exc}") from None

    def literal(self, value_pos: int, type_pos: int) -> Literal:
        """Typed literal of ``args[value_pos]`` with type name ``args[type_pos]`` (spec §2.3)."""
        try:
            return literal_named(self.args[value_pos], self.args[type_pos])
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
        raise CommandError(
            codes.INVALID_ARGUMENT,
            f"argument {position + 1} ({what}) must be true or false, got {self.args[position]!r}",
        )

    def java_boolean(self, position: int) -> bool:
        """A boolean argument read as aRMOR's Java reads it (``Boolean.parseBoolean``): ``true`` in any case
        is true, anything else (``1``, ``yes``, `` true``) false, never refused."""
        return self.args[position].lower() == "true"

    def render(self, items: list) -> list[str]:
        """Render terms in the service's mode; sorted so answers are reproducible."""
        return answer_texts(self.service.renderer, self.onto, items)

    def submit(self, *changes: Change) -> Reply:
        """Apply (or queue) manipulations; a failure of the reasoner undoes them (209)."""
        ref = self.reference
        if changes and ref.buffered_manipulation:  # the request that made them, kept so that a
            changes[0].origin = self.request.to_dict()  # durable store can persist the buffer they wait in
        try:
            warnings = ref.submit(list(changes))
        except (TopostoreError, OSError) as exc:  # reasoning, the store or its files failed; a bug surfaces as one
            raise CommandError(
                codes.REASONER_OR_QUERY_FAILURE, f"the change was undone because reasoning failed: {exc}"
            ) from exc
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


def fixed(description: str, add: Sequence[Triple] = (), remove: Sequence[Triple] = ()) -> Change:
    """A change whose triples do not depend on the state at application time."""
    to_add, to_remove = list(add), list(remove)
    return Change(description, lambda onto: Delta(add=to_add, remove=to_remove))


def asserted(onto: Ontology, s=None, p=None, o=None) -> list[Triple]:
    """The asserted triples matching a pattern (what manipulations and restriction queries read)."""
    return list(onto.store.triples(s, p, o, ASSERTED))


def answered_classification(onto: Ontology) -> dict | None:
    """The classification a class-hierarchy answer reads: a buffered reasoner's as of its last REASON while
    changes wait (``OntologyReasoning.kept``, made on this first read from the rules and value types that REASON
    had), else None (the current one). Its members and its warning of unsatisfiable classes come from the same
    one."""
    if not (onto.dirty and onto.reads.answers_removed):
        return None
    return onto.reasoning.kept_classification()


#: said with a class-hierarchy answer a buffered reasoner cannot give as of its last REASON
NOT_KEPT = ("the class hierarchy of the last REASON is not known (a durable store reopened without it, or a failed "
            "REASON that cleared the inferred facts): the current one is answered until the next REASON")


def hierarchy_warnings(onto: Ontology, found: Sequence[NamedNode]) -> list[str]:
    """What a class-hierarchy answer listing ``found`` says beside it: the unsatisfiable classes among them, read
    from the classification it answers, and :data:`NOT_KEPT` where a buffered reasoner's is not known."""
    said = [NOT_KEPT] if onto.dirty and onto.reads.answers_removed and onto.reasoning.kept is None else []
    empty = [c for c in onto.reasoning.unsatisfiable(answered_classification(onto)) if c in found]
    return [unsatisfiable_text(empty), *said] if empty else said


def told_subclasses(onto: Ontology, cls: NamedNode) -> set[NamedNode]:
    """The named X of a told ``SubClassOf(X cls)``: what aRMOR adds to the reasoner's subclasses (spec §2.5)."""
    return {t.subject for t in asserted(onto, None, rdfs("subClassOf"), cls) if isinstance(t.subject, NamedNode)}


def subclasses(onto: Ontology, cls: NamedNode) -> list[NamedNode]:
    """The subclasses aRMOR answers for ``cls`` (QUERY CLASS CLASS, DISJOINT CLASS CLASS), sorted: the
    reasoner's ``getSubClasses(cls, false)``, which leaves out the classes equivalent to ``cls`` (its own
    node), with the told ``SubClassOf(X cls)`` of a named X added (the union of spec §2.5: ``cls`` itself
    when ``SubClassOf(cls cls)`` is told); the told ones only while the ontology is inconsistent (aRMOR
    asks the reasoner nothing then, as for every query); never owl:Nothing or an internal class (spec §7
    item 6).  An unsatisfiable class is under every class.  A buffered reasoner's answer is its classification
    as of the last REASON, until the next one (:func:`answered_classification`)."""
    told = told_subclasses(onto, cls)
    if INFERRED in onto.visible_graphs():  # consistent (or not reasoned yet): the reasoner's answer too
        kept = answered_classification(onto)
        above = onto.reasoning.superclasses(cls, kept)
        told |= {c for c in onto.reasoning.subclasses(cls, kept) if c not in above}
    return sorted((c for c in told if not hidden(c)), key=lambda n: n.value)


__all__ = ["Reply", "Context", "entity_named", "literal_named", "answer_texts",
           "Command", "Handler", "hidden", "fixed", "asserted", "subclasses", "answered_classification",
           "hierarchy_warnings", "told_subclasses", "NOT_KEPT"]
