"""What a repeated kind of change keeps between REASONs: the decisions its kind settles, and the
(subject, predicate) pairs known to hold one value.

A robot repeats a few kinds of change step after step (its place, its clock and the visit time of a
place replaced).  What maintenance decides from the *kind* of a change alone — its added and lost
read keys, its cleanly replaced predicates — and from the keys with facts is kept here by that kind,
so that a repeated step decides nothing again:

* :class:`Decisions` keeps each decision by its key.  It is sound because every input of a decision
  is in its key: the kind itself, and the keys with facts (:attr:`.maintenance.MaintenanceState.present`,
  ``asserted``) by their sizes, which tell the sets since those only grow between full runs.  It is
  cleared by a full run, which makes new sets (their sizes could then repeat with other keys).
* :attr:`KeptKinds.single` keeps the (subject, predicate text) pairs known to hold exactly one value
  in the asserted graph, so that a clean replacement (:func:`.flip.clean_replacements`) of such a
  pair needs no look-up.  It is
  sound because each change the reasoner is given is a net change: a pair with one triple added and
  one removed holds as many values after it as before, and every other pair of a change leaves the
  set.  It is cleared by a full run and by a failed REASON (the asserted graph may then have been set
  back without a change passing here), and kept for in-memory stores only: a remote store's graph
  may be written by others, and its look-ups are one batched request anyway.

One pass over a change (:func:`read_change`) reads what the kind's key and the clean replacements
need of each triple; :func:`replaced_of` finds the pairs with one triple added and one removed for
both kinds of store, which differ only in how the values now held are read.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable
from typing import TYPE_CHECKING, NamedTuple

from pyoxigraph import Triple

from ..rdf.vocab import TYPE
from .flip import Replacement
from .plan import KeyCounts
from .program import Signature, signature

if TYPE_CHECKING:
    from .compiled_step import CompiledStep
    from .maintenance import MaintenanceState
    from .negation import Completion

#: pairs :attr:`KeptKinds.single` holds at most (forgotten beyond: looked up again)
SINGLE_MAX = 100_000

#: no pair known to hold one value (where none is kept)
_NONE: frozenset = frozenset()

#: rdf:type as a read key's text
_TYPE_TEXT = str(TYPE)


class Decisions:
    """Decisions kept by their key (at most ``limit``: all are forgotten beyond, and decided again)."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self._decided: dict[tuple, object] = {}

    def get(self, key: tuple, decide: Callable[[], object]) -> object:
        """The decision kept for ``key``, or ``decide()`` kept from now on."""
        if key in self._decided:
            return self._decided[key]
        if len(self._decided) >= self.limit:
            self._decided.clear()
        value = self._decided[key] = decide()
        return value

    def clear(self) -> None:
        """A full run recounted the keys with facts: decide afresh."""
        self._decided.clear()


class KeptKinds:
    """The decisions kept by kind of change and the pairs known to hold one value, of one reasoner."""

    def __init__(self, limit: int) -> None:
        self.decided = Decisions(limit)
        #: (subject, predicate) pairs of the asserted graph known to hold one value since the last REASON
        self.single: set[tuple] = set()

    def replaced(self, store, change: Change, graph) -> dict[str, list[Replacement]]:
        """The change's clean replacements, the kept pairs brought to the state after it."""
        return replaced_of(store, change, graph, self.single)

    def maintained(self, census: tuple, lost: tuple, replaced: dict, state: MaintenanceState, step: CompiledStep,
                   completion: Completion | None) -> tuple[Signature, bool, bool]:
        """What maintenance decides from the kind of a change (:meth:`_decide`), kept by the kind and the
        sizes of ``state``'s keys with facts; ``completion``: None where no rule is deferred."""
        present, asserted = state.present, state.asserted
        return self.decided.get(("maintain", tuple(census[0]), tuple(census[1]), tuple(lost[0]), tuple(lost[1]),
                                 tuple(replaced), len(present[0]), len(present[1]), len(asserted[0]),
                                 len(asserted[1])),
                                lambda: self._decide(census, lost, replaced, state, step, completion))

    @staticmethod
    def _decide(census: tuple, lost: tuple, replaced: dict, state: MaintenanceState, step: CompiledStep,
                completion: Completion | None) -> tuple[Signature, bool, bool]:
        """What maintenance decides from the kind of a change alone (its added and lost read keys,
        ``census`` and ``lost``, and its cleanly replaced predicates), given the keys with facts: the
        compiled program's signature; whether an added fact may have been inferred (then it is discarded
        from the reasoner's graphs: a newly asserted fact that was inferred is asserted only, as from
        scratch; none can have been where no rule that can fire writes its key, a robot's clock); whether
        the loss may leave a pair of a deferred rule unasked (:mod:`.negation`).

        Each is a function of those keys and of the keys with facts, which :meth:`maintained` keeps it by."""
        discard = bool(census[0]) and step.compiler.state_graphs.derived(census, state.present)
        ask_again = completion is not None and bool(lost[0]) and completion.needed(state.present, lost,
                                                                                   asserted=True)
        return signature(census, lost, replaced), discard, ask_again

    def failed(self) -> None:
        """A REASON failed: the asserted graph may be set back behind the kept pairs."""
        self.single.clear()

    def clear(self) -> None:
        """A full run: new sets of keys with facts, and the asserted graph read afresh."""
        self.decided.clear()
        self.single.clear()


class Change(NamedTuple):
    """A net change read once (:func:`read_change`): the read keys it adds facts of and loses facts of
    (:func:`~..stores.reads.key_census` of each side), and each side's (subject, predicate text) pairs
    with their one triple (None where a pair has several)."""

    census: KeyCounts
    lost: KeyCounts
    news: dict[tuple, Triple | None]
    olds: dict[tuple, Triple | None]


def read_change(added: Iterable[Triple], removed: Iterable[Triple]) -> Change:
    """One pass over each side of a change: what the census, the kind's key and the clean replacements
    read of it (a term read from a triple is a new object each time, its text a call: each is read once)."""
    news, census = _one_pass(added)
    olds, lost = _one_pass(removed)
    return Change(census, lost, news, olds)


def _one_pass(triples: Iterable[Triple]) -> tuple[dict[tuple, Triple | None], KeyCounts]:
    found: dict[tuple, Triple | None] = {}
    preds: dict[str, int] = {}
    classes: dict[str, int] = {}
    for t in triples:
        key = str(t.predicate)
        preds[key] = preds.get(key, 0) + 1
        if key == _TYPE_TEXT:  # by its text: a pyoxigraph term's equality is a call
            c = str(t.object)
            classes[c] = classes.get(c, 0) + 1
        pair = (t.subject, key)
        if found.setdefault(pair, t) is not t:
            found[pair] = None
    return found, (preds, classes)


def replaced_in(store, added: Collection[Triple], removed: Collection[Triple], graph,
                single: set[tuple] | None = None) -> dict[str, list[Replacement]]:
    """:func:`.flip.clean_replacements` of a net change (:func:`replaced_of` of it read once)."""
    return replaced_of(store, read_change(added, removed), graph, single)


def replaced_of(store, change: Change, graph, single: set[tuple] | None = None) -> dict[str, list[Replacement]]:
    """:func:`.flip.clean_replacements` of a net change, the values now held read from ``graph`` of
    ``store`` for the pairs with one triple added and one removed only: one look-up each in memory (none
    for a pair in ``single``), one batch where reads are round trips.

    ``single`` (in memory): the pairs known to hold one value in ``graph`` before the change, brought to
    the state after it: a pair found or kept clean is in it, any other pair of the change is not."""
    olds = dict(change.olds)
    news = change.news
    if store.round_trips:
        ask = {pair: (pair[0], new.predicate) for pair, new in news.items()
               if new is not None and olds.get(pair) is not None and pair[1] != _TYPE_TEXT}
        now = store.objects_many(list(ask.values()), graph) if ask else {}
        known: Collection[tuple] = _NONE
        kept: set[tuple] = set()

        def holds_one(pair: tuple) -> bool:
            return len(now.get(ask[pair], ())) == 1
    else:
        known = kept = set() if single is None else single

        def holds_one(pair: tuple) -> bool:
            return len(store.objects(pair[0], news[pair].predicate, graph)) == 1
    clean: dict[str, list[Replacement]] = {}
    dirty: set[str] = set()
    for pair, new in news.items():
        key = pair[1]
        old = olds.pop(pair, None)
        if new is None or old is None or key == _TYPE_TEXT or (pair not in known and not holds_one(pair)):
            kept.discard(pair)
            dirty.add(key)
            continue
        kept.add(pair)
        clean.setdefault(key, []).append(Replacement(old, new))
    for pair in olds:  # removed, nothing added
        kept.discard(pair)
        dirty.add(pair[1])
    if len(kept) > SINGLE_MAX:
        kept.clear()
    return {p: pairs for p, pairs in clean.items() if p not in dirty} if dirty else clean


__all__ = ["Change", "Decisions", "KeptKinds", "SINGLE_MAX", "read_change", "replaced_in", "replaced_of"]
