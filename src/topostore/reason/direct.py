"""Compiled-step operations answered by index look-ups instead of a SPARQL update, where few facts are in play.

Why this exists
---------------
On the in-memory store a SPARQL update costs 20–40 µs to parse and plan even when it moves one fact,
while an index look-up costs about a microsecond.  Several operations of the compiled step
(:mod:`.program`) need no join at all: moving a key's flipped facts to its candidates or into its
graph (``lost``, ``gained``), and the candidates, rechecks and additions of a rule with one body
atom and no filter (a domain, range or subclass axiom: the commonest OWL rules).  Each such
operation has an equivalent here that reads its few facts through the store's quad API; when there
are more than :data:`FEW` of them, or a fact it would write holds a literal (whose stored spelling
the SPARQL text leaves to the store), it answers False and the SPARQL text runs instead.  Only
stores where a look-up is not a round trip use them (see :class:`.staged.StagedRun`); the whole
program as one request (:meth:`.program.StepProgram.text`) is unchanged.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

from pyoxigraph import BlankNode, Literal, NamedNode, Triple

from ..compile.rule import Atom, ReadKey, Rule, key_pattern
from ..rdf.terms import parse_term
from ..rdf.vocab import AUX
from .atom_shape import Shape
from .delta_texts import FLIP_LOST, KEEP, NEW_STATE
from .scratch import CANDIDATES, FLIP_GAINED, NEW_FACTS, OVERDELETED

#: at most this many facts are moved through look-ups; more go through the SPARQL text
FEW = 16

#: the look-ups of a key's lost (``minus``) or gained (``plus``) facts that may be given them instead of
#: reading them back from OVERDELETED or NEW_FACTS, by name: where no rule of the program writes the key,
#: those graphs hold exactly the change's facts of it all run long (:attr:`.staged_plan.BoundOp.given`)
GIVEN = frozenset(("candidates", "additions", "run"))

#: :func:`~..compile.rule.key_pattern` kept per key: a step looks its keys up a dozen times, and each
#: pattern made anew parses its IRI into a term
pattern_of = functools.lru_cache(maxsize=4096)(key_pattern)

_STATE_SET = frozenset(NEW_STATE)


class _AllKept:
    """A recheck's answer (truthy, as True is) where every candidate of its key is now kept: it read them
    all (its head's pattern is its key's, no variable repeated) and proved each, so a staged run need not
    read the key's candidates and kept facts back to find that out (:mod:`.staged_code`)."""

    __slots__ = ()

    def __repr__(self) -> str:
        return "ALL_KEPT"


ALL_KEPT = _AllKept()


def whole_key(head: Shape, key: ReadKey) -> bool:
    """Whether a head's candidates, read by its free pattern, are every candidate of ``key`` each bound
    (:data:`ALL_KEPT` may be answered): the pattern is the key's and no variable is repeated."""
    names = [x for x in head.terms if isinstance(x, str)]
    return head.free == pattern_of(key) and len(set(names)) == len(names)


def _facts(store, pattern: tuple, graph: NamedNode) -> list[Triple] | None:
    """The facts of ``pattern`` in ``graph``, None when there are more than :data:`FEW`."""
    return store.few_facts(*pattern, (graph,), FEW)


def _known(store, facts: list[Triple], graphs: tuple[NamedNode, ...]) -> list[bool]:
    """Whether each fact is in one of ``graphs`` (:meth:`.Store.known_in`: one read per fact over every
    graph where the store offers it, else one look-up batch)."""
    return store.known_in(facts, _STATE_SET if graphs is NEW_STATE else frozenset(graphs))


def _in_state(store, pattern: tuple) -> list[Triple] | None:
    """Every fact of ``pattern`` in the state graphs by one index read over all graphs (``match_in``: a
    bound subject or object), instead of a read per graph, most of which find nothing (a class kept by
    an asserted or an inferred fact); None where that read does not apply or finds more than :data:`FEW`
    (a list cut at its limit could miss the fact that proves)."""
    match_in = getattr(store, "match_in", None)
    found = match_in(*pattern, _STATE_SET, FEW) if match_in is not None else None
    return found if found is not None and len(found) <= FEW else None


def _movable(facts: list[Triple]) -> list[Triple] | None:
    """``facts`` where look-ups may move them: at most :data:`FEW`, none holding a literal (the SPARQL text
    moves those: a literal may be stored in another spelling); else None."""
    if len(facts) > FEW or any(isinstance(t.object, Literal) for t in facts):
        return None
    return facts


@dataclass(frozen=True)
class Lost:
    """:func:`.delta_texts.lost`: flipped-false facts of ``key`` present in ``graph`` become candidates."""

    key: ReadKey
    graph: NamedNode

    @property
    def reads(self) -> frozenset:
        """The keys whose facts it reads (its own)."""
        return frozenset((self.key,))

    def run(self, store) -> bool:
        facts = _facts(store, pattern_of(self.key), FLIP_LOST)
        return facts is not None and self.handed(store, facts)

    def handed(self, store, facts: list[Triple]) -> bool:
        """:meth:`run` with the flipped-false facts of ``key`` given (a staged run's flips found them
        and wrote them nowhere); False where the text must run (which reads them from FLIP_LOST)."""
        facts = _movable(facts)
        if facts is None:
            return False
        _add_candidates(store, facts, self.graph)
        return True


@dataclass(frozen=True)
class Gained:
    """:func:`.delta_texts.gained`: flipped-true facts of ``key`` not known yet, into ``graph`` and NEW_FACTS."""

    key: ReadKey
    graph: NamedNode

    @property
    def reads(self) -> frozenset:
        """The keys whose facts it reads (its own)."""
        return frozenset((self.key,))

    def run(self, store) -> bool:
        facts = _facts(store, pattern_of(self.key), FLIP_GAINED)
        return facts is not None and self.handed(store, facts)

    def handed(self, store, facts: list[Triple]) -> bool:
        """:meth:`run` with the flipped-true facts of ``key`` given (see :meth:`Lost.handed`)."""
        facts = _movable(facts)
        if facts is None:
            return False
        _write_new(store, facts, self.graph)
        return True


def _add_candidates(store, facts: list[Triple], graph: NamedNode) -> None:
    """The facts present in ``graph`` become candidates (of a recheck)."""
    store.add_scratch([t for t, here in zip(facts, store.contains_each(facts, graph)) if here], CANDIDATES)


def _write_new(store, heads: list[Triple], graph: NamedNode) -> None:
    """The heads not known in the new state, into ``graph`` and NEW_FACTS."""
    if not heads:
        return  # a join that derived nothing: nothing to look up
    heads = list(dict.fromkeys(heads))
    new = [t for t, known in zip(heads, _known(store, heads, NEW_STATE)) if not known]
    if new:
        store.add_scratch(new, graph)
        store.add_scratch(new, NEW_FACTS)


class OneAtom:
    """A rule with one body atom and no filter, on named terms (see :func:`one_atom`): its
    candidates from removed facts, its recheck of candidates and its additions from added facts."""

    def __init__(self, rule: Rule, graph: NamedNode) -> None:
        self.atom = rule.body[0]
        self.head = rule.head
        self.graph = graph
        self._body, self._head = Shape(_terms(self.atom)), Shape(_terms(self.head))
        #: the keys whose facts it reads: the atom's and the head's
        self.reads = frozenset((self.atom.read_key(), self.head.read_key()))
        #: whether its recheck reads every candidate of its key (:func:`whole_key`)
        self._whole = whole_key(self._head, self.head.read_key())

    def _heads(self, facts: list[Triple]) -> list[Triple] | None:
        """The heads the facts derive (None when one would hold a literal)."""
        out = []
        bind = self._body.bind
        for t in facts:
            bound = bind(t)
            if bound is None:
                continue
            head = _instance(self._head.terms, bound)
            if head is False:
                return None
            if head is not None:
                out.append(head)
        return out

    def candidates(self, store, facts: list[Triple] | None = None) -> bool:
        """:func:`.delta_texts.candidates`: heads present in the graph that a removed fact derived;
        ``facts``: the removed facts of the atom's key where the run has them (:data:`GIVEN`), else read."""
        if facts is None:
            facts = _facts(store, self._body.free, OVERDELETED)
        heads = None if facts is None else self._heads(facts)
        if heads is None:
            return False
        _add_candidates(store, heads, self.graph)
        return True

    def additions(self, store, facts: list[Triple] | None = None) -> bool:
        """:func:`.delta_texts.additions`: heads an added fact derives, not known yet; ``facts``: as
        :meth:`candidates`' (the added ones)."""
        if facts is None:
            facts = _facts(store, self._body.free, NEW_FACTS)
        heads = None if facts is None else self._heads(facts)
        if heads is None:
            return False
        _write_new(store, heads, self.graph)
        return True

    def keep(self, store) -> bool:
        """:func:`.delta_texts.keep`: the candidates the rule derives from the new state go to KEEP."""
        candidates = _facts(store, self._head.free, CANDIDATES)
        if candidates is None:
            return False
        graphs = (AUX,) if self.atom.aux else NEW_STATE
        kept = []
        for c in candidates:
            bound = self._head.bind(c)
            if bound is None:
                continue
            pattern = self._body.read(bound)
            found = _in_state(store, pattern) if graphs is NEW_STATE else None
            if self._proves(found, bound) if found is not None \
                    else any(self._proves(store.triples(*pattern, g), bound) for g in graphs):
                kept.append(c)
        store.add_scratch(kept, KEEP)
        return ALL_KEPT if self._whole and len(kept) == len(candidates) else True

    def _proves(self, facts, bound: dict[str, object]) -> bool:
        """Whether one of ``facts`` matches the atom with the head's values ``bound`` (a variable
        the head leaves free but the atom repeats must take one value)."""
        for t in facts:
            found = self._body.bind(t)
            if found is not None and all(found[x] == value for x, value in bound.items() if x in found):
                return True
        return False


class Relaxed:
    """:func:`.delta_texts.candidates` widened: every present head that agrees with a removed fact of
    atom ``j`` on the head's variables that atom binds, whatever the rest of the body.

    A candidate is only rechecked, and the recheck of a key whose inputs are final is exact whatever
    the candidates (a present fact no longer derivable is deleted, any other kept), so a superset
    of the exact candidates changes nothing but the work: this one costs look-ups instead of a join,
    and is used only while it stays as small as :data:`FEW` (else the exact SPARQL text runs)."""

    def __init__(self, rule: Rule, j: int, graph: NamedNode) -> None:
        self._body, self._head = Shape(_terms(rule.body[j])), Shape(_terms(rule.head))
        self.graph = graph
        #: the keys whose facts it reads: atom ``j``'s and the head's
        self.reads = frozenset((rule.body[j].read_key(), rule.head.read_key()))
        #: keys without whose facts before the change the rule derived nothing through a lost fact of atom
        #: ``j`` (its other atoms): no candidate is needed then, however wide this one's would be
        self.needs = {"run": frozenset(a.read_key() for m, a in enumerate(rule.body) if m != j)}

    def run(self, store, facts: list[Triple] | None = None) -> bool:
        """The candidates into CANDIDATES; ``facts``: as :meth:`OneAtom.candidates`'."""
        heads = self.candidates(store, facts)
        if heads is None:
            return False
        store.add_scratch(heads, CANDIDATES)
        return True

    def candidates(self, store, facts: list[Triple] | None = None) -> list[Triple] | None:
        """The candidates (None: more than :data:`FEW`, the text finds them); ``facts``: as :meth:`run`'s."""
        if facts is None:
            facts = _facts(store, self._body.free, OVERDELETED)
        if facts is None:
            return None
        heads: dict[Triple, None] = {}
        for t in facts:
            bound = self._body.bind(t)
            if bound is None:
                continue
            found = _facts(store, self._head.read(bound), self.graph)
            if found is None:
                return None
            heads.update(dict.fromkeys(found))
            if len(heads) > FEW:
                return None
        return list(heads)


def relaxable(rule: Rule, j: int) -> bool:
    """Whether :class:`Relaxed` applies to atom ``j``: every term of the atom and the head a variable
    or an IRI, and a head variable bound by the atom (else every fact of the key would be a candidate)."""
    atom, head = rule.body[j], rule.head
    if head is None or not (head.variables() & atom.variables()):
        return False
    return _named_only(atom, head)


def one_atom(rule: Rule) -> bool:
    """Whether :class:`OneAtom` can evaluate ``rule``: one body atom, no filter, every term a
    variable or an IRI, the head's variables bound by the atom."""
    if len(rule.body) != 1 or rule.conditions or rule.head is None:
        return False
    atom, head = rule.body[0], rule.head
    return _named_only(atom, head) and head.variables() <= atom.variables()


def _named_only(*atoms: Atom) -> bool:
    """Every term of ``atoms`` a variable or an IRI: what the quad API can match without the store's
    literal spellings."""
    return all(t.startswith("?") or (t.startswith("<") and t.endswith(">")) for a in atoms for t in (a.s, a.p, a.o))


def _term(text: str):
    """A variable's name (str) or the named term."""
    return text if text.startswith("?") else parse_term(text)


def _terms(atom: Atom) -> tuple:
    """The atom's subject, predicate and object as :func:`_term` gives them."""
    return tuple(_term(t) for t in (atom.s, atom.p, atom.o))


def _instance(terms: tuple, bound: dict[str, object]) -> Triple | None | bool:
    """The head for ``bound``: None where SPARQL would not write it (a literal subject, a predicate
    that is not an IRI), False where a literal object would leave its spelling to this code."""
    s, p, o = terms  # each a variable's name or a term (no generator: a step makes a few heads per part)
    s = bound[s] if isinstance(s, str) else s
    p = bound[p] if isinstance(p, str) else p
    o = bound[o] if isinstance(o, str) else o
    return triple_of(s, p, o)


def triple_of(s, p, o) -> Triple | None | bool:
    """A head of terms ``s``, ``p``, ``o`` as :func:`_instance` gives it (a generated flip branch's heads)."""
    if not isinstance(s, (NamedNode, BlankNode)) or not isinstance(p, NamedNode):
        return None
    if isinstance(o, Literal):
        return False
    return Triple(s, p, o)


__all__ = ["ALL_KEPT", "FEW", "Gained", "Lost", "OneAtom", "Relaxed", "one_atom", "relaxable", "whole_key"]
