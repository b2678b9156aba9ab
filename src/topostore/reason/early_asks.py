"""The deferred asks of a full run, asked early in a worker thread while the run goes on writing.

A deferred ask (:mod:`.deferred_asks`) waits for the first stratum's fixpoint, then evaluates its body
less the pairs whose conclusion is known; on a map whose links are all declared it adds nothing, and
costs 0.64 s at 100,000 locations.  What it reads is often final long before the fixpoint: the asserted
doors, and the conclusion (Connectability's ``connectedTo``) once the component writing it is done.  So,
where the store overlaps (:attr:`topostore.stores.base.Store.overlaps`), the ask is started as an ``ASK``
query in a worker thread (:class:`topostore.stores.overlap.Beside`) right after the last ordered
component writing a key it reads, while this thread evaluates the later components.  When the ask's
turn comes, its early answer is used only if

* no evaluation since the start may have written a key it reads (every evaluation of the run is
  noted, :meth:`EarlyAsks.wrote`; a rule of a variable predicate or class counts as writing them all),
* it reads each key in the same graphs it would read them in now (:func:`.deferred_asks.only_asserted`).

Then "no match" skips the insert (nothing to write); a match, or an early answer that does not hold,
sends the insert as before.  Every worker is joined before the run returns (:meth:`EarlyAsks.close`).
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from contextlib import ExitStack
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode

from ..compile.generic import PREFIXES
from ..compile.rule import ReadKey, Rule
from ..stores.overlap import ENABLED, Beside
from .insert_text import insert_text
from .negation import unless_known_text
from .order import TYPE_KEY

if TYPE_CHECKING:
    from .materialize import Materializer

#: a key standing for every key (a rule of a variable predicate reads or writes any)
_ANY = ("*",)


def ask_form(text: str) -> str:
    """The ``ASK`` query of an evaluation text (``INSERT { … }`` / dataset line / ``WHERE { … }``, as
    :func:`.insert_text.insert_text` writes it): true when the evaluation has a match."""
    head, dataset, where = text.split("\n", 2)
    if not head.startswith("INSERT") or not where.startswith("WHERE"):
        raise ValueError(f"not an evaluation text: {head[:40]!r}")
    words = dataset.replace("USING NAMED ", "FROM NAMED ").replace("USING ", "FROM ")
    return f"ASK {words}\n{where}"


def _reads(rule: Rule) -> frozenset[ReadKey]:
    """Every key the ask of ``rule`` reads: its body, its filters, its known conclusion."""
    keys = set(rule.reads())
    if rule.conditions_read_graph and not rule.filter_reads:
        keys.add(_ANY)
    if rule.unless_known is not None:
        keys.add(rule.unless_known.read_key())
    return frozenset(keys)


def _touches(written: ReadKey | None, reads: Collection[ReadKey]) -> bool:
    """Whether a rule writing ``written`` may have written a key among ``reads``."""
    if written is None:
        return False
    if written[0] == "*" or _ANY in reads or written in reads:
        return True
    return written == ("p", TYPE_KEY) and any(k[0] == "t" for k in reads)


class EarlyAsks:
    """The deferred asks of one full run started early; see the module docstring."""

    def __init__(self, run: Materializer, ordered: list[list[int]], rest: Collection[int]) -> None:
        self.run = run
        self._workers = ExitStack()
        #: rule -> the keys its ask reads
        self._reads: dict[int, frozenset[ReadKey]] = {}
        #: component index -> the asks to start after it (-1: before the first)
        self._start_after: dict[int, list[int]] = {}
        #: rule -> (the graphs its keys are read in, its answer) once started; dropped when it no longer holds
        self._started: dict[int, tuple[Mapping[ReadKey, NamedNode], Beside[bool]]] = {}
        #: the keys the deferred asks write (read by :func:`.deferred_asks.only_asserted`), fixed for the run
        self._asking = {w for j in run._deferring if (w := run.rules[j].writes()) is not None}
        if not (ENABLED and run.store.overlaps):
            return
        asks = [i for i in sorted(run._deferring) if i not in run._idle and run.rules[i].unless_known is not None]
        later = [run.rules[j].writes() for j in rest] + [run.rules[j].writes() for j in asks]
        for i in asks:
            reads = self._reads[i] = _reads(run.rules[i])
            if any(_touches(w, reads) for w in later):
                continue  # a rule run after the ordered components (or another ask) may write what it reads
            last = max((c for c, component in enumerate(ordered)
                        if any(_touches(run.rules[j].writes(), reads) for j in component)), default=-1)
            self._start_after.setdefault(last, []).append(i)

    def after(self, component: int) -> None:
        """The ordered component ``component`` is done (-1: none yet): start the asks that waited for it."""
        for i in self._start_after.pop(component, ()):
            run = self.run
            if not run.triggers.feasible(i, run.present):
                continue
            graphs = self._graphs(i)
            text = ask_form(self._text(i, graphs))
            side = self._workers.enter_context(Beside(lambda t=text, s=run.store: bool(s.query(t, prefixes=PREFIXES))))
            self._started[i] = (graphs, side)

    def wrote(self, key: ReadKey | None) -> None:
        """An evaluation writing ``key`` was sent or queued: the early asks reading it no longer hold."""
        for i in [i for i in self._started if _touches(key, self._reads[i])]:
            del self._started[i]

    def answer(self, i: int) -> bool | None:
        """Whether the ask of rule ``i`` has a match, from its early answer (None: ask it now)."""
        started = self._started.pop(i, None)
        if started is None or started[0] != self._graphs(i):
            return None
        graphs, side = started
        side.__exit__(None, None, None)  # joined here: its answer is needed now
        return side.result()

    def text(self, i: int) -> str:
        """The insert of rule ``i``'s ask, as the run sends it now."""
        return self._text(i, self._graphs(i))

    def close(self) -> None:
        """Join every worker still running (the run is over or failed)."""
        self._started.clear()
        self._workers.close()

    def _graphs(self, i: int) -> Mapping[ReadKey, NamedNode]:
        from .deferred_asks import only_asserted

        run = self.run
        return only_asserted(run.rules[i], run._derived, run._asserted, self._asking)

    def _text(self, i: int, graphs: Mapping[ReadKey, NamedNode]) -> str:
        run = self.run
        text = insert_text(run.rules[i], None, run.planned, run._lateral, run._direct, graphs)
        return unless_known_text(text, run.rules[i])


__all__ = ["EarlyAsks", "ask_form"]
