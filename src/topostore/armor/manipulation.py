"""The aRMOR manipulation commands: ADD, REMOVE, DISJOINT, REPLACE, RENAME, MAKE EQUIVALENT, APPLY, REASON.

Each handler builds :class:`~topostore.armor.reference.Change` objects; a
change whose triples depend on the ontology at application time (buffered
manipulation) carries a ``plan`` that reads the ontology then.  N-ary axioms
and individual removal are written by :mod:`topostore.ontology.nary`, as in the Python API.
"""

from __future__ import annotations

from pyoxigraph import Literal, NamedNode, Triple

from ..errors import InvalidValueError, TopostoreError
from ..ontology.facade import Ontology
from ..ontology.named_queries import render_jena
from ..ontology.nary import all_different, all_disjoint_classes, individual_triples, rdf_list
from ..rdf import terms
from ..rdf.vocab import ASSERTED, OWL, RDF, RDFS, STANFORD_SWRL, SWRL, SWRLB, THING, TYPE, XSD, is_internal, owl, rdfs
from ..stores.base import fresh_skolem
from . import codes, one_value
from .codes import CommandError
from .context import Context, Handler, Reply, asserted, fixed, hidden, subclasses
from .reference import Change, Delta

SUBCLASS_OF = rdfs("subClassOf")
EQUIVALENT_CLASS = owl("equivalentClass")
#: namespaces whose terms give the ontology its meaning; RENAME refuses them
_VOCABULARIES = (RDF, RDFS, OWL, XSD, SWRL, SWRLB, STANFORD_SWRL)


def _distinct(ctx: Context, what: str) -> list[NamedNode]:
    """Every argument as an IRI, de-duplicated; at least two are needed for an n-ary axiom."""
    members = list(dict.fromkeys(ctx.iri(i, what) for i in range(len(ctx.args))))
    if len(members) < 2:
        raise CommandError(
            codes.INVALID_ARGUMENT, f"DISJOINT needs at least two different {what} names, got {len(members)}"
        )
    return members


def add_ind(ctx: Context) -> Reply:
    ind = ctx.iri(0, "individual")
    return ctx.submit(fixed("ADD IND", add=[Triple(ind, TYPE, THING)]))


def add_class(ctx: Context) -> Reply:
    cls = ctx.iri(0, "class")
    return ctx.submit(fixed("ADD CLASS", add=[Triple(cls, SUBCLASS_OF, THING)]))


def add_ind_class(ctx: Context) -> Reply:
    ind, cls = ctx.iri(0, "individual"), ctx.iri(1, "class")
    return ctx.submit(fixed("ADD IND CLASS", add=[Triple(ind, TYPE, cls)]))


def add_class_class(ctx: Context) -> Reply:
    sub, sup = ctx.iri(0, "subclass"), ctx.iri(1, "superclass")
    return ctx.submit(fixed("ADD CLASS CLASS", add=[Triple(sub, SUBCLASS_OF, sup)]))


def add_dataprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "data property"), ctx.iri(1, "individual")
    value = ctx.literal(3, 2)
    key = terms.value_key(value)

    def plan(onto: Ontology) -> Delta:
        present = any(terms.value_key(t.object) == key for t in asserted(onto, ind, prop))
        return Delta(add=[] if present else [terms.triple(ind, prop, value)],
                     warning="" if present else _object_property_note(onto, prop, "ADD DATAPROP IND"))

    return ctx.submit(Change("ADD DATAPROP IND", plan))


def _object_property_note(onto: Ontology, prop: NamedNode, description: str) -> str:
    """What a data value given to a declared object property does ("" for any other property): aRMOR's
    OWL API would make the property a data property as well, which OWL 2 DL forbids; here the value is
    stored, queried as given, and no rule joins on it as an individual."""
    try:  # the compiled rules' schema (compiled already for the REASON that follows): no store read
        rules = onto.rules
    except TopostoreError:  # a schema that does not compile is said by the REASON
        return ""
    if prop not in rules.object_properties or prop in rules.data_properties:
        return ""
    return (f"{description}: {prop.value} is an object property: the data value is stored and answered as "
            "given; what reads the property's values as individuals (its range, the rules joining through it) "
            "skips it")


def _data_property_note(onto: Ontology, prop: NamedNode, description: str) -> str:
    """What an individual given to a declared data property does ("" for any other property), the reverse of
    :func:`_object_property_note`: stored and answered as given, never checked against the data range (Pellet
    reads the two uses as two properties)."""
    try:
        rules = onto.rules
    except TopostoreError:
        return ""
    if prop not in rules.data_properties or prop in rules.object_properties:
        return ""
    return (f"{description}: {prop.value} is a data property: the individual is stored and answered as given; "
            "what reads the property's values as data values (its range, the rules comparing them) skips it")


def _note_for(value: object) -> one_value.Note:
    """The note a value given to a property of the other kind earns: a data value to an object property, an
    individual to a data property."""
    return note_for_kind(isinstance(value, Literal))


def note_for_kind(literal: bool) -> one_value.Note:
    """:func:`_note_for` of a literal (``literal``) or of an individual."""
    return _object_property_note if literal else _data_property_note


def add_objectprop_ind(ctx: Context) -> Reply:
    prop, ind, value = ctx.iri(0, "object property"), ctx.iri(1, "individual"), ctx.iri(2, "value individual")
    triple = Triple(ind, prop, value)
    return ctx.submit(Change("ADD OBJECTPROP IND", lambda onto: Delta(
        add=[triple], warning=_data_property_note(onto, prop, "ADD OBJECTPROP IND"))))


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
    return ctx.submit(fixed("ADD CARDINALITY MIN", add=triples))


def disjoint_ind(ctx: Context) -> Reply:
    members = _distinct(ctx, "individual")
    return ctx.submit(fixed("DISJOINT IND", add=all_different(members)))


def disjoint_class(ctx: Context) -> Reply:
    members = _distinct(ctx, "class")
    return ctx.submit(fixed("DISJOINT CLASS", add=all_disjoint_classes(members)))


def disjoint_ind_class(ctx: Context) -> Reply:
    cls = ctx.iri(0, "class")

    def plan(onto: Ontology) -> Delta:
        members = sorted((i for i in onto.instances(cls) if not hidden(i)), key=lambda n: n.value)
        if len(members) < 2:
            return Delta(warning=f"{cls.value} has {len(members)} instance(s); no axiom added")
        return Delta(add=all_different(members))

    return ctx.submit(Change("DISJOINT IND CLASS", plan))


def disjoint_class_class(ctx: Context) -> Reply:
    cls = ctx.iri(0, "class")

    def plan(onto: Ontology) -> Delta:
        members = [c for c in subclasses(onto, cls) if c != cls]  # a told SubClassOf(cls cls): not disjoint with itself
        if len(members) < 2:
            return Delta(warning=f"{cls.value} has {len(members)} subclass(es); no axiom added")
        return Delta(add=all_disjoint_classes(members))

    return ctx.submit(Change("DISJOINT CLASS CLASS", plan))


def make_equivalent_class(ctx: Context) -> Reply:
    cls = ctx.iri(0, "class")

    def plan(onto: Ontology) -> Delta:
        links = asserted(onto, cls, SUBCLASS_OF)
        supers = [t.object for t in links if t.object != cls]
        if not supers:
            return Delta(warning=f"{cls.value} has no asserted superclass; nothing made equivalent")
        if len(supers) == 1:
            return Delta(add=[Triple(cls, EQUIVALENT_CLASS, supers[0])], remove=links)
        node = fresh_skolem()
        head, items = rdf_list(supers)
        add = [
            Triple(node, TYPE, owl("Class")),
            Triple(node, owl("intersectionOf"), head),
            Triple(cls, EQUIVALENT_CLASS, node),
        ]
        return Delta(add=add + items, remove=links)

    return ctx.submit(Change("MAKE EQUIVALENT CLASS", plan))


def remove_ind(ctx: Context) -> Reply:
    """REMOVE IND: every asserted triple naming the individual, and whole n-ary axioms (AllDifferent) listing it."""
    ind = ctx.iri(0, "individual")
    return ctx.submit(Change("REMOVE IND", lambda onto: Delta(remove=individual_triples(onto.store, ind))))


def remove_class(ctx: Context) -> Reply:
    """Undo of ADD CLASS: removes only ``SubClassOf(cls owl:Thing)``; the class's other axioms stay."""
    cls = ctx.iri(0, "class")
    return ctx.submit(fixed("REMOVE CLASS", remove=[Triple(cls, SUBCLASS_OF, THING)]))


def remove_ind_class(ctx: Context) -> Reply:
    ind, cls = ctx.iri(0, "individual"), ctx.iri(1, "class")
    return ctx.submit(fixed("REMOVE IND CLASS", remove=[Triple(ind, TYPE, cls)]))


def remove_class_class(ctx: Context) -> Reply:
    sub, sup = ctx.iri(0, "subclass"), ctx.iri(1, "superclass")
    return ctx.submit(fixed("REMOVE CLASS CLASS", remove=[Triple(sub, SUBCLASS_OF, sup)]))


def _matching_values(onto: Ontology, ind: NamedNode, prop: NamedNode, value) -> list[Triple]:
    """Asserted ``prop(ind, v)`` whose v is the same data value (or the same individual) as ``value``."""
    key = terms.value_key(value)
    return [t for t in asserted(onto, ind, prop) if terms.value_key(t.object) == key]


def remove_dataprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "data property"), ctx.iri(1, "individual")
    value = ctx.literal(3, 2)
    return ctx.submit(
        Change("REMOVE DATAPROP IND", lambda onto: Delta(remove=_matching_values(onto, ind, prop, value)))
    )


def remove_objectprop_ind(ctx: Context) -> Reply:
    prop, ind, value = ctx.iri(0, "object property"), ctx.iri(1, "individual"), ctx.iri(2, "value individual")
    return ctx.submit(fixed("REMOVE OBJECTPROP IND", remove=[Triple(ind, prop, value)]))


def _replace(ind: NamedNode, prop: NamedNode, new, old, description: str) -> Change:
    """Remove ``prop(ind, old)`` (matched by data value), add ``prop(ind, new)``; warn if old was absent."""

    old_key, new_key = terms.value_key(old), terms.value_key(new)

    def plan(onto: Ontology) -> Delta:
        # read once (on a remote store each read is a round trip) as facts: each value keyed once, and the
        # removed ones go on to the store and the ledger with their keys
        facts = onto.store.read_facts(ind, prop, ASSERTED)
        olds, held = one_value.values(facts, old, old_key, new, new_key)
        # the new value stays if it is there already, unless it is the old value (removed, then added)
        present = held and not (olds and new_key == old_key)
        warning = (
            ""
            if olds
            else (
                f"{description}: old value {render_jena(old)} of {prop.value} for {ind.value} was not asserted; "
                "the new value was added and the existing values were kept"
            )
        )
        if not present:
            warning = "; ".join(filter(None, [warning, _note_for(new)(onto, prop, description)]))
        # the value read absent is noted so in the transaction: its addition asks the store nothing again
        added = [] if present else [onto.store.unread_fact(ind, prop, new, ASSERTED)]
        return Delta(add=added, remove=olds, warning=warning)

    return Change(description, plan)


def replace_dataprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "data property"), ctx.iri(1, "individual")
    new, old = ctx.literal(3, 2), ctx.literal(4, 2)
    return _replace_one(ctx, ind, prop, new, old, "REPLACE DATAPROP IND")


def replace_objectprop_ind(ctx: Context) -> Reply:
    prop, ind = ctx.iri(0, "object property"), ctx.iri(1, "individual")
    new, old = ctx.iri(2, "new value"), ctx.iri(3, "old value")
    return _replace_one(ctx, ind, prop, new, old, "REPLACE OBJECTPROP IND")


def _replace_one(ctx: Context, ind: NamedNode, prop: NamedNode, new, old, description: str) -> Reply:
    """A REPLACE through the short lane where it is the plain case (:mod:`.one_value`), else the general path."""
    warnings = one_value.replace(ctx.reference, ind, prop, new, old, description, _note_for(new))
    if warnings is not None:
        return Reply(warnings=warnings)
    return ctx.submit(_replace(ind, prop, new, old, description))


def rename(kind: str) -> Handler:
    """RENAME <kind>: the IRI ``old`` becomes ``new`` in every asserted triple."""

    def handler(ctx: Context) -> Reply:
        old, new = ctx.iri(0, f"old {kind} name"), ctx.iri(1, f"new {kind} name")
        for position, term in ((1, old), (2, new)):
            if term.value.startswith(_VOCABULARIES) or is_internal(term):
                raise CommandError(
                    codes.INVALID_ARGUMENT,
                    f"argument {position}: {term.value} belongs to the RDF, "
                    "RDFS, OWL, XSD or SWRL vocabulary (or to topostore); it cannot be renamed",
                )

        def plan(onto: Ontology) -> Delta:

            def sub(term):
                return new if term == old else term

            hits = list(
                dict.fromkeys(asserted(onto, old) + asserted(onto, None, old) + asserted(onto, None, None, old))
            )
            if not hits:
                return Delta(warning=f"{old.value} does not occur in the ontology; nothing renamed")
            adds = []
            for t in hits:
                obj = (
                    onto.store.original_literal(ASSERTED, t.subject, t.predicate, t.object)
                    if isinstance(t.object, Literal)
                    else sub(t.object)
                )
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
        ref.ontology.reason()
    except (TopostoreError, OSError) as exc:  # reasoning, the store or its files failed
        # the buffered changes that broke it are dropped too, or every later REASON would fail the same way
        dropped = ref.discard_buffer()
        note = f"; {dropped} buffered change(s) were discarded" if dropped else ""
        # the ontology is back at its last good state (its last successful REASON, or as reopened), or,
        # where there is none or it cannot be reasoned either, holds its asserted facts only
        outcome = ("the changes since the last successful REASON were undone"
                   if ref.ontology.ledger.last_failure == "undone" else
                   "the ontology could not be brought back to a reasoned state: its asserted facts were kept "
                   "and its inferred ones cleared (REASON again once the cause is removed)")
        raise CommandError(codes.REASONER_OR_QUERY_FAILURE, f"reasoning failed and {outcome}: {exc}{note}") from exc
    return Reply(warnings=warnings)

