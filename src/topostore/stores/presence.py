"""Whether a fact is in a store, by value: the one presence look-up of the unit of work (:mod:`.work`).

A pending write is keyed by its value (``1`` = ``"01"^^xsd:int``), and so is presence: a literal not found
as written is looked up in the spelling the literal forms keep for its fact, where the store keeps that as
another term (``"1.0"^^xsd:decimal`` beside a held ``"1"^^xsd:int``: Oxigraph keeps every integer type as
one ``xsd:integer`` term, a decimal as a term of its own).  One value is then one fact, stored in the
spelling written first, whatever the path that writes it (a load, a change, a SPARQL update, a Graph Store
write) and however many calls it takes.
Functions of the store, bound as its methods as those of :mod:`.work` are.
"""

from __future__ import annotations

from collections.abc import Hashable
from typing import TYPE_CHECKING

from pyoxigraph import Literal, Quad

from ..rdf.terms import quad, value_key

if TYPE_CHECKING:
    from .base import Store


def key(store: Store, quad: Quad) -> Hashable:
    """What identifies a quad: itself, or with a literal object its value (``1`` = ``"01"^^xsd:int``)."""
    o = quad.object
    if isinstance(o, Literal):
        return (quad.subject, quad.predicate, value_key(o), quad.graph_name)
    return quad


def present(store: Store, quads: list[Quad], keys: list[tuple] | None = None) -> list[bool]:
    """Whether each quad is in the store as the open transaction sees it (``keys``: their :meth:`_key`)."""
    if store._pending is None and store.listings is None and not any(isinstance(q.object, Literal) for q in quads):
        return store._has_many(quads)  # no transaction, no value keys: each quad is its own key
    pending, known, listings = store._pending or {}, store._known, store.listings
    keys = keys if keys is not None else [store._key(q) for q in quads]
    answers: list[bool | None] = []
    unknown: list[int] = []  # positions neither the transaction nor the listings can answer
    for i, k in enumerate(keys):
        entry = pending.get(k)
        if entry is not None:
            answers.append(entry[1])
            continue
        present = known.get(k)
        if present is None and listings is not None:
            present = listings.presence(quads[i], k)
            if present is not None and store._pending is not None:
                known[k] = present
        if present is None:
            unknown.append(i)
        answers.append(present)
    if len(unknown) == 1:  # a manipulation's one new triple
        i = unknown[0]
        answers[i] = has_values(store, [quads[i]])[0]
        if store._pending is not None:
            known[keys[i]] = answers[i]
    elif unknown:  # one batch (one request on a remote store); a value asked twice takes the last answer
        found = dict(zip((keys[i] for i in unknown), has_values(store, [quads[i] for i in unknown]), strict=True))
        if store._pending is not None:
            known.update(found)
        for i in unknown:
            answers[i] = found[keys[i]]
    return answers  # type: ignore[return-value] - every position is answered by now


def has_values(store: Store, quads: list[Quad]) -> list[bool]:
    """Whether the committed store holds each quad's fact, by value: the one presence look-up of the unit
    of work.  A literal quad absent as written is asked again in the spelling the literal forms keep for
    its fact (:func:`kept_quad`), where that is another term."""
    found = store._has_many(quads)
    kept: list[tuple[int, Quad]] = []
    for i, (q, there) in enumerate(zip(quads, found, strict=True)):
        if not there and (held := kept_quad(store, q, None)) is not None:
            kept.append((i, held))
    if kept:  # one more batch (one request on a remote store)
        for (i, _), there in zip(kept, store._has_many([q for _, q in kept]), strict=True):
            found[i] = there
    return found


def has_value(store: Store, q: Quad, value: tuple | None) -> bool:
    """:func:`has_values` of one quad (a manipulation's usual change, ``value``: its literal's value key
    where known), without a batch."""
    if store._has(q):
        return True
    held = kept_quad(store, q, value)
    return held is not None and store._has(held)


def kept_quad(store: Store, q: Quad, value: tuple | None) -> Quad | None:
    """The quad of ``q``'s fact in the spelling kept for it (the literal forms: one per graph, subject,
    predicate and value) where that is another literal than ``q``'s, else None.

    Why: Oxigraph keeps every integer type as one ``xsd:integer`` term but a decimal as a term of its own
    (``"1"^^xsd:int`` and ``"1.0"^^xsd:decimal`` are one OWL value, two terms), and a store that keeps
    literals as written (a remote one) keeps every spelling apart: the quad as written finds only its own
    term.  A dictionary look-up, asked only when that quad was not found."""
    o = q.object
    if type(o) is not Literal:
        return None
    kept = store.forms.recorded(q.graph_name, q.subject, q.predicate, value if value is not None else value_key(o))
    if kept is None or kept == o:
        return None
    return quad(q.subject, q.predicate, kept, q.graph_name)


__all__ = ["has_value", "has_values", "kept_quad", "key", "present"]
