"""The literal forms users wrote, remembered beside a store that canonicalises numbers.

Oxigraph keeps numbers in canonical form (``"7"^^xsd:long`` is stored as
``"7"^^xsd:integer``).  :class:`LiteralForms`, a part every
:class:`~topostore.stores.base.Store` holds (``store.forms``), remembers the lexical form and datatype of each
asserted literal, so that answers and saved files show what the user wrote; a
durable store persists them in the ``FORMS`` graph.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Collection, Iterable
from typing import TYPE_CHECKING

import pyoxigraph as ox
from pyoxigraph import Literal, NamedNode, Quad, RdfFormat, Triple

from ..rdf.terms import Term, note_stored_value, parse_term, triple, value_key
from ..rdf.vocab import INTERNAL
from .language_tags import LanguageTags
from .meta import META

if TYPE_CHECKING:
    from .base import Store

#: Graph of the persisted literal forms.
FORMS = NamedNode(INTERNAL + "graph:forms")

#: a scratch store that shows how a literal is stored (see LiteralForms.stored_form)
_PROBE = ox.Store()
_PROBE_LOCK = threading.Lock()
#: probes a probe store serves before a fresh one takes its place: Oxigraph's memory store keeps each removed
#: quad in its index, so one store serving every probe slows down as a robot runs (≈ 6 → 17 µs a probe over
#: 100,000 probes); a fresh store costs ≈ 0.7 µs
_PROBE_RENEW = 256
_probes = 0
_PROBE_GRAPH = NamedNode(INTERNAL + "graph:probe")


class LiteralForms:
    """How each committed literal was written: a part of one :class:`~topostore.stores.base.Store`.

    It reads its store's ``durable`` flag at each write (an implementation sets it after the base
    is built) and persists through the store's ``_write``/``_match`` primitives.
    """

    def __init__(self, store: Store) -> None:
        self._store = store
        # (graph, subject, predicate, value key) -> literal as the user wrote it
        self._literal_forms: dict[tuple, Literal] = {}
        # value key -> {literal as written: number of asserted triples using it}
        self._value_forms: dict[tuple, dict[Literal, int]] = {}
        #: the language tags' spellings (pyoxigraph lowers every tag)
        self.tags = LanguageTags()

    def learn_tags(self, data: bytes | str, fmt: RdfFormat | None,
                   only: Collection[tuple[str, str]] | None = None) -> list[str]:
        """Remember how a loaded document (or a change's text: ``only`` its added literals' tags, see
        :meth:`LanguageTags.learn`) spells its language tags (persisted on a durable store); the new ones."""
        new = self.tags.learn(data, fmt, only)
        self._persist_tags(new)
        return new

    def adopt_tags(self, tags: Iterable[str]) -> list[str]:
        """Remember language tags spelled as given (the first spelling wins; persisted on a durable store);
        the new ones."""
        new = self.tags.adopt(tags)
        self._persist_tags(new)
        return new

    def forget_tags(self, tags: Iterable[str]) -> None:
        """Drop spellings :meth:`adopt_tags` took (their literals were reverted), on a durable store too."""
        dropped = self.tags.forget(tags)
        if dropped and self._store.durable:
            self._store._write([], self.tags.quads(dropped, FORMS))

    def _persist_tags(self, new: list[str]) -> None:
        if new and self._store.durable:
            self._store._write(self.tags.quads(new, FORMS), [])

    def record(self, adds: list[Quad], removes: list[Quad], undo: bool = False) -> tuple[list[Quad], list[Quad]]:
        """Remember (or forget) how committed literals were written; the quads persisting that on a durable store."""
        forms_add, forms_remove, _undo = self.record_keyed([(q, None) for q in adds], [(q, None) for q in removes], undo)
        return forms_add, forms_remove

    def record_keyed(self, adds: list[tuple[Quad, object]], removes: list[tuple[Quad, object]],
                     undo: bool = False) -> tuple[list[Quad], list[Quad], Callable[[], None]]:
        """:meth:`record` of (quad, store key) pairs: a literal's value key is read from its store key
        (``Store._key``: subject, predicate, value key, graph) where the caller has one, not computed
        again.  Returns the quads persisting the forms on a durable store, and what takes the record back
        should the write fail (the removed literals remembered again as their users wrote them)."""
        forms_add: list[Quad] = []
        forms_remove: list[Quad] = []
        persist = self._store.durable and not undo
        literal_forms, count = self._literal_forms, self._count_form
        # (value key, form counted, form an undo restores, graph name, subject, predicate) of each removal
        popped: list[tuple[tuple, Literal, Literal, str, Term, NamedNode]] = []
        for q, k in removes:  # each term read once: pyoxigraph makes a new object at every read
            o = q.object
            if isinstance(o, Literal) and not _is_scratch(graph := q.graph_name):
                s, p = q.subject, q.predicate
                key = k[2] if type(k) is tuple else value_key(o)
                name = graph.value
                found = literal_forms.pop((name, s, p, key), None)
                # a fact with no form kept for it was never counted: its removal changes no count
                if found is not None:
                    popped.append((key, found, found, name, s, p))
        for key, counted, _, name, s, p in popped:
            count(key, counted, -1)
            if persist:
                forms_remove.append(_form_quad(name, s, p, counted))
        added: list[tuple[tuple, Literal, str, Term, NamedNode]] = []
        for q, k in adds:
            o = q.object
            if isinstance(o, Literal) and not _is_scratch(graph := q.graph_name):
                s, p = q.subject, q.predicate
                key = k[2] if type(k) is tuple else value_key(o)
                name = graph.value
                literal_forms[(name, s, p, key)] = o
                count(key, o, +1)
                added.append((key, o, name, s, p))
                if persist:
                    forms_add.append(_form_quad(name, s, p, o))

        def take_back() -> None:
            for key, o, name, s, p in added:
                literal_forms.pop((name, s, p, key), None)
                count(key, o, -1)
            for key, _, written, name, s, p in popped:
                literal_forms[(name, s, p, key)] = written
                count(key, written, +1)

        return forms_add, forms_remove, take_back

    def replaced(self, graph: NamedNode, s: Term, p: NamedNode, old_value: tuple | None, new: Term,
                 new_value: tuple | None) -> None:
        """:meth:`record_keyed` of one removed fact (``old_value``: its value key, None for no literal) and
        one added (``new``, of value key ``new_value``) of (s, p) in ``graph``, committed on a store that
        persists no forms: the removed form forgotten and uncounted, the new one kept and counted."""
        name, literal_forms = graph.value, self._literal_forms
        if old_value is not None:
            found = literal_forms.pop((name, s, p, old_value), None)
            if found is not None:  # a fact with no form kept for it was never counted
                self._count_form(old_value, found, -1)
        if new_value is not None:
            literal_forms[(name, s, p, new_value)] = new  # type: ignore[assignment] - a literal
            self._count_form(new_value, new, +1)  # type: ignore[arg-type]

    def record_loaded(self, graph: NamedNode, spelled: list[tuple[tuple, Literal]]) -> list[Quad]:
        """Remember the literals of a bulk load into ``graph`` (``spelled``: ((subject, predicate,
        value key), literal) each, keys computed once by the caller): :meth:`record` without a quad
        made or a key computed per literal; the quads persisting that on a durable store."""
        if _is_scratch(graph):
            return []
        name = graph.value
        literal_forms, value_forms = self._literal_forms, self._value_forms
        for (s, p, key), lit in spelled:  # _count_form(key, lit, +1) inline: no dict made per literal
            literal_forms[(name, s, p, key)] = lit
            forms = value_forms.get(key)
            if forms is None:
                value_forms[key] = {lit: 1}
            else:
                forms[lit] = forms.get(lit, 0) + 1
        if not self._store.durable:
            return []
        return [_form_quad(name, s, p, lit) for (s, p, _), lit in spelled]

    def _count_form(self, key: tuple, lit: Literal, delta: int) -> None:
        """Count ``delta`` more uses of the form ``lit`` of the value ``key``; a value no form counts any
        more is dropped (a clock writes a new value every step: its old ones are not kept as empty entries)."""
        value_forms = self._value_forms
        forms = value_forms.get(key)
        if forms is None:
            if delta <= 0:
                return
            value_forms[key] = {lit: delta}
            return
        n = forms.get(lit, 0) + delta
        if n > 0:
            forms[lit] = n
            return
        forms.pop(lit, None)
        if not forms:
            del value_forms[key]

    def _rebuild_value_forms(self) -> None:
        self._value_forms = {}
        for (_, _, _, key), lit in self._literal_forms.items():
            self._count_form(key, lit, +1)

    def load(self) -> None:
        """Read the persisted literal forms back (a durable store opened again)."""
        self._literal_forms = {}
        for q in self._store._match(None, None, None, FORMS):
            if self.tags.restore(q):
                continue
            graph, _, text = q.object.value.partition(" ")
            lit = _parse_literal(text)
            if lit is not None:
                self._literal_forms[(graph, q.subject, q.predicate, value_key(lit))] = lit
        self._rebuild_value_forms()

    def original_literal(self, graph: NamedNode, s: Term, p: NamedNode, o: Literal) -> Literal:
        """The literal as the user asserted it (lexical form and datatype)."""
        found = self._literal_forms.get((graph.value, s, p, value_key(o)))
        return found if found is not None else self.restore(o)

    def recorded(self, graph: NamedNode, s: Term, p: NamedNode, value: tuple | None) -> Literal | None:
        """The form kept for this one fact (``value``: its value key), None when none is: a removal
        names the fact as the store holds it, never another subject's spelling of the value."""
        if value is None:
            return None
        return self._literal_forms.get((graph.value, s, p, value))

    def written(self, graph: NamedNode, s: Term, p: NamedNode, o: Term, value: tuple | None) -> Term:
        """:meth:`original_literal` of ``o`` whose value key is ``value`` (None: ``o`` is no literal,
        its own form)."""
        if value is None:
            return o
        found = self._literal_forms.get((graph.value, s, p, value))
        return found if found is not None else self.restore(o)

    def restore(self, term: Term) -> Term:
        """A literal as users wrote it, when that value was written in one form only."""
        if not isinstance(term, Literal):
            return term
        forms = self._value_forms.get(value_key(term))
        if forms and len(forms) == 1:
            return next(iter(forms))
        return term

    def stored_form(self, t: Triple, written: Quad | None = None) -> Triple:
        """The triple as this store holds it once added (Oxigraph canonicalises some literals,
        e.g. ``"7"^^xsd:long`` becomes ``"7"^^xsd:integer``); ``written``: a quad of ``t`` the caller has
        made already (a change's write), which the probe stores instead of making one."""
        o = t.object
        if not isinstance(o, Literal):
            return t
        stored = _STORED.get(o)
        if stored is None:
            probed = _probed(o, written)
            stored = probed.object
            if written is not None and stored != o:  # the probe's quad holds the caller's triple as stored,
                return probed.triple  # made by pyoxigraph (a literal argument costs it 1.7 µs)
        return t if stored == o else triple(t.subject, t.predicate, stored)

    def forget(self, graph: NamedNode) -> None:
        """Forget the forms of a graph being cleared (and their persisted copies)."""
        gone = [(k, v) for k, v in self._literal_forms.items() if k[0] == graph.value]
        if self._store.durable and gone:
            self._store._write([], [_form_quad(k[0], k[1], k[2], lit) for k, lit in gone])
        self._literal_forms = {k: v for k, v in self._literal_forms.items() if k[0] != graph.value}
        self._rebuild_value_forms()


#: literals the probe store canonicalised, as it stored them (a robot writes each clock value two or three
#: times: as the new ``now``, as a visit's time and as the old ``now`` of the next step)
_STORED: dict[Literal, Literal] = {}
_STORED_MAX = 4096


def stored_literal(lit: Literal, written: Quad | None = None) -> Literal:
    """``lit`` as Oxigraph stores it: asked of a scratch store (Oxigraph's own canonical form, never a
    copy of its rules), remembered for the next few thousand literals.  ``written``: a quad with ``lit``
    as its object that the caller made already (a change's write): the probe stores that one, since a quad
    with a literal object costs pyoxigraph ≈ 2.5 µs to make (it tries the other kinds of term first), half
    of a probe."""
    stored = _STORED.get(lit)
    return stored if stored is not None else _probed(lit, written).object


def _probed(lit: Literal, written: Quad | None) -> Quad:
    """The probe store's quad of ``lit`` (``written``, or one of the probe's graph, as it stores it), the
    literal's stored form remembered."""
    global _PROBE, _probes
    with _PROBE_LOCK:
        _probes += 1
        if _probes >= _PROBE_RENEW:
            _PROBE, _probes = ox.Store(), 0
        _PROBE.add(written if written is not None else Quad(_PROBE_GRAPH, _PROBE_GRAPH, lit, _PROBE_GRAPH))
        quad = next(iter(_PROBE))  # the probe holds this one quad (each one is removed once read)
        _PROBE.remove(quad)
        if len(_STORED) >= _STORED_MAX:
            _STORED.clear()
        stored = _STORED[lit] = _STORED[quad.object] = quad.object  # the stored form is its own (a reasoner's
        note_stored_value(stored, lit)  # discard asks it), and a number's value is the written one's
    return quad


def stored_seen(lit: Literal, stored: Literal) -> None:
    """``stored`` is how an Oxigraph store holds ``lit``, read back from it after a write of it: remembered
    as :func:`_probed` remembers a probe's answer (the same engine's term), so that no probe is paid for it."""
    with _PROBE_LOCK:
        if len(_STORED) >= _STORED_MAX:
            _STORED.clear()
        _STORED[lit] = _STORED[stored] = stored
        note_stored_value(stored, lit)


def _is_scratch(graph) -> bool:
    """Reasoner scratch graphs and the persisted state need no literal forms."""
    return not isinstance(graph, NamedNode) or graph == FORMS or graph == META


def _form_quad(graph: str, s: Term, p: NamedNode, lit: Literal) -> Quad:
    return Quad(s, p, Literal(f"{graph} {lit}"), FORMS)


def _parse_literal(text: str) -> Literal | None:
    term = parse_term(text)
    return term if isinstance(term, Literal) else None


__all__ = ["FORMS", "LiteralForms"]
