"""Read-only evaluations of a full run started early, in a worker thread, while the run goes on writing.

Two kinds: the deferred asks, whose answer the run needs at its first stratum's fixpoint, and the
consistency checks, whose matches the REASON needs after the run (:mod:`.closing`); a third, the
first pass's evaluations that read far more than they write (the AllDifferent keys, a minimum's count),
found and written by the worker, lives in :mod:`.early_rules` and shares the worker, its evaluations
queued first (the pass waits for them soonest).

**Deferred asks.**
A deferred ask (:mod:`.deferred_asks`) waits for the first stratum's fixpoint, then evaluates its body
less the pairs whose conclusion is known; on a map whose links are all declared it adds nothing, and
costs 0.64 s at 100,000 locations.  What it reads is often final long before the fixpoint: the asserted
doors, and the conclusion (Connectability's ``connectedTo``) once the component writing it is done.  So,
where the store overlaps (:attr:`topostore.stores.base.Store.overlaps`), the ask is started as an ``ASK``
query in a worker thread (:class:`topostore.stores.overlap.Reader`) right after the last ordered
component writing a key it reads, while this thread evaluates the later components.  When the ask's
turn comes, its early answer is used only if

* no evaluation since the start may have written a key it reads (every evaluation of the run is
  noted, :meth:`EarlyReads.wrote`; a rule of a variable predicate or class counts as writing them all),
* it reads each key in the same graphs it would read them in now (:func:`.deferred_asks.only_asserted`).

Then "no match" skips the insert (nothing to write); a match, or an early answer that does not hold,
sends the insert as before.  Where a census of the AllDifferent keys may show the ask empty
(:mod:`.keyed_asks`), the census is asked first, and the ``ASK`` only when it does not; a census that
covered at its keyed conclusion's turn (:mod:`.keyed_first_pass`), nothing it counts written since, is not
counted again (:meth:`.early_rules.EarlyRules.covered`).

**Checks.**  A check (:func:`.consistency.check_rows`) reads keys that are final once every rule that
may write them is done, the upper strata's and the deferred asks' included: it is started (with the
census of its own keys, :func:`.present.key_graphs`) right after the last ordered component writing one,
when no later rule may.  Its matches are kept when the run ends (:meth:`EarlyReads.close`) unless an
evaluation since its start may have written a key it reads; the REASON runs the others after the run.
Past :data:`EARLY_CHECKS` checks none is started early: they all run after the run, sharing one census.
A check reading no key that an evaluation started early writes (:mod:`.early_rules`: the worker loads its
facts before the reads queued after it) is queued as shared: when this thread would wait for the worker
(an early evaluation's turn, a census, an ask, the close), it runs such checks not started yet itself
(:meth:`.Reader.help`) rather than leaving them behind the keys and the count.

The reads run one after the other in one worker thread, in the order they were started; a read no longer
holding is dropped if it has not started.  The worker is joined before the run returns
(:meth:`EarlyReads.close`), also when it fails.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from concurrent.futures import CancelledError, Future
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode

from ..compile.generic import PREFIXES
from ..compile.rule import ReadKey, Rule
from ..stores.base import Store
from ..stores.overlap import ENABLED, Reader, early_result
from .consistency import GRAPHS, check_rows
from .early_rules import EarlyRules, Found
from .insert_text import insert_text
from .keyed_asks import GROUP_READS, KeyCensus
from .negation import unless_known_text
from .one_group import one_group
from .present import key_graphs
from .read_keys import Writes, evaluation_reads, touches

if TYPE_CHECKING:
    from .materialize import Materializer

#: at most this many checks are started early; with more (a TBox of 400 classes has 11,000 disjointness
#: checks) each early check would be a census and a query of its own in the worker, where the REASON's
#: checks after the run share one census and skip the checks whose keys hold no fact (measured on the
#: 400-class TBox: a full REASON 0.35 s sequential, 1.7-2.0 s with every check started early)
EARLY_CHECKS = 64


def ask_form(text: str) -> str:
    """The ``ASK`` query of an evaluation text (``INSERT { … }`` / dataset line / ``WHERE { … }``, as
    :func:`.insert_text.insert_text` writes it): true when the evaluation has a match."""
    head, dataset, where = text.split("\n", 2)
    if not head.startswith("INSERT") or not where.startswith("WHERE"):
        raise ValueError(f"not an evaluation text: {head[:40]!r}")
    words = dataset.replace("USING NAMED ", "FROM NAMED ").replace("USING ", "FROM ")
    return f"ASK {words}\n{where}"


def _start_points(run: Materializer, ordered: list[list[int]], reads: Mapping[int, frozenset[ReadKey]],
                  later: list[ReadKey | None]) -> dict[int, list[int]]:
    """For each read (by its key in ``reads``): the ordered component after which it may start, the last
    one writing a key it reads (-1: none), unless a key of ``later`` (written after the components) may be
    one of them (then it is left out)."""
    after = Writes([(0, key) for key in later])
    components = Writes([(c, run.rules[i].writes()) for c, component in enumerate(ordered) for i in component])
    points: dict[int, list[int]] = {}
    for n, keys in reads.items():
        if after.last(keys) >= 0:
            continue
        points.setdefault(components.last(keys), []).append(n)
    return points


def _has_match(store: Store, text: str, census: KeyCensus | None, graphs: Mapping[ReadKey, NamedNode]) -> bool:
    """Whether the ask ``text`` (reading its keys in ``graphs``) has a match: none when ``census`` shows it
    empty (:mod:`.keyed_asks`; the store held one AllDifferent group when it was started), else by asking it."""
    if census is not None and census.covers(store, graphs):
        return False
    return bool(store.query(text, prefixes=PREFIXES))


def _answered(value: bool) -> Future:
    """A read answered without the worker, as a done Future."""
    done: Future = Future()
    done.set_result(value)
    return done


class EarlyReads:
    """The deferred asks and checks of one full run started early; see the module docstring."""

    def __init__(self, run: Materializer, ordered: list[list[int]], rest: Collection[int],
                 checks: Sequence[Rule] = (), back: Collection[int] = ()) -> None:
        self.run = run
        self._reader = Reader()
        #: the first pass's evaluations found in the worker (:mod:`.early_rules`): none without it
        self.rules: EarlyRules | None = None
        #: the keys the deferred asks write (read by :func:`.deferred_asks.only_asserted`), fixed for the run
        self._asking = {w for j in run._deferring if (w := run.rules[j].writes()) is not None}
        self._checks = list(checks)
        #: the keys each ask (by rule) and each check (by index) reads
        self._ask_reads: dict[int, frozenset[ReadKey]] = {}
        self._check_reads: dict[int, frozenset[ReadKey]] = {}
        #: component index -> the asks and the checks to start after it (-1: before the first)
        self._asks_after: dict[int, list[int]] = {}
        self._checks_after: dict[int, list[int]] = {}
        #: started and still holding: ask -> (the graphs it reads its keys in, its answer); check -> matches
        self._asked: dict[int, tuple[Mapping[ReadKey, NamedNode], Future]] = {}
        self._checking: dict[int, Future] = {}
        #: check index -> its matches, once the run is over (:meth:`close`)
        self.checked: dict[int, list[dict]] = {}
        if not (ENABLED and run.store.overlaps):
            return
        self.rules = EarlyRules(run, ordered, back, self._reader)
        ranked = {i for component in ordered for i in component}
        feasible = [i for i in range(len(run.rules)) if run.triggers.feasible(i, run.present)]
        asks = [i for i in sorted(run._deferring) if i not in run._idle and run.rules[i].unless_known is not None]
        self._ask_reads = {i: evaluation_reads(run.rules[i]) | (GROUP_READS if i in run.censuses else frozenset())
                           for i in asks}
        # an ask is answered before the upper strata run: only the rest and the asks write after the components
        later = [run.rules[j].writes() for j in feasible if j in rest or j in run._deferring]
        self._asks_after = _start_points(run, ordered, self._ask_reads, later)
        # a check reads the run's end: the upper strata too (a rule that cannot match now and matches
        # later drops the reads of what it writes, :meth:`wrote`)
        if len(self._checks) > EARLY_CHECKS:
            return
        self._check_reads = {j: evaluation_reads(rule) for j, rule in enumerate(self._checks)}
        later = [run.rules[j].writes() for j in feasible if j not in ranked or j in rest or j in run._deferring]
        self._checks_after = _start_points(run, ordered, self._check_reads, later)

    def after(self, component: int) -> None:
        """The ordered component ``component`` is done (-1: none yet): start the reads that waited for it."""
        run = self.run
        store = run.store
        if self.rules is not None:  # first: the pass waits for them, the asks and checks come later
            self.rules.after(component)
        for i in self._asks_after.pop(component, ()):
            if not run.triggers.feasible(i, run.present):
                continue
            graphs = self._graphs(i)
            text = ask_form(self._text(i, graphs))
            census = run.censuses.get(i) if one_group(store, run._queued) else None
            if census is not None and self.covered(census, graphs):
                self._asked[i] = (graphs, _answered(False))  # no match: the census covers as it did
                continue
            self._asked[i] = (graphs, self._reader.submit(lambda t=text, c=census, g=graphs: _has_match(store, t, c, g)))
        for j in self._checks_after.pop(component, ()):
            rule, keys = self._checks[j], self._check_reads[j]
            self._checking[j] = self._reader.submit(lambda r=rule, k=keys: check_rows(store, r, key_graphs(store, k, GRAPHS)),
                                                    shared=self._shared(keys))

    def wrote(self, key: ReadKey | None) -> None:
        """An evaluation writing ``key`` was sent or queued: the early reads of it no longer hold."""
        if self.rules is not None:
            self.rules.wrote(key)
        for i in [i for i in self._asked if touches(key, self._ask_reads[i])]:
            self._asked.pop(i)[1].cancel()
        for j in [j for j in self._checking if touches(key, self._check_reads[j])]:
            self._checking.pop(j).cancel()

    def keyless(self, i: int) -> bool:
        """Whether rule ``i``'s first pass leaves its keys out (:mod:`.keyed_first_pass`), by the census the
        worker took for it: False without one."""
        return self.rules is not None and self.rules.keyless(i)

    def evaluated(self, i: int, text: str) -> Found | None:
        """The solutions of rule ``i``'s first-pass evaluation ``text`` found in the worker (None: evaluate
        it now), see :mod:`.early_rules`."""
        return self.rules.evaluated(i, text) if self.rules is not None else None

    def covered(self, census: KeyCensus, graphs: Mapping[ReadKey, NamedNode]) -> bool:
        """Whether ``census`` covers without being taken again (:meth:`.early_rules.EarlyRules.covered`);
        the caller knows the store holds one AllDifferent group."""
        return self.rules is not None and self.rules.covered(census, graphs)

    def _shared(self, reads: frozenset[ReadKey]) -> bool:
        """Whether a read of ``reads`` may be run by this thread instead of the worker (:meth:`.Reader.help`):
        no evaluation started early writes a key it reads, so it does not need the worker to have loaded
        one first."""
        return self.rules is not None and not self.rules.loading(reads)

    def answer(self, i: int) -> bool | None:
        """Whether the ask of rule ``i`` has a match, from its early answer (None: ask it now)."""
        started = self._asked.pop(i, None)
        if started is None:
            return None
        if not started[1].done():
            self._reader.help()
        return early_result(started, self._graphs(i))

    def close(self, completed: bool) -> None:
        """Join the worker; ``completed`` (the run reached its fixpoint): keep the matches of the checks
        that still hold in :attr:`checked` (a check that failed is left to the REASON, which runs it again
        and reports its error)."""
        if completed:
            self._reader.help()
            for j, matches in self._checking.items():
                try:
                    self.checked[j] = matches.result()
                except (Exception, CancelledError):  # noqa: BLE001 - run again after the run, where it raises
                    continue
        self._asked.clear()
        self._checking.clear()
        if self.rules is not None:
            self.rules.close()
        self._reader.__exit__(None, None, None)

    def _graphs(self, i: int) -> Mapping[ReadKey, NamedNode]:
        from .deferred_asks import only_asserted

        run = self.run
        return only_asserted(run.rules[i], run._derived, run._asserted, self._asking)

    def _text(self, i: int, graphs: Mapping[ReadKey, NamedNode]) -> str:
        run = self.run
        # bare: an ask matching more than the deferred insert only sends that insert (see the module)
        text = insert_text(run.rules[i], None, run.planned, run._lateral, run._direct, graphs, bare=run.bare(i))
        return unless_known_text(text, run.rules[i])


__all__ = ["EarlyReads", "ask_form"]
