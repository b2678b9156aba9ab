"""Rule evaluations of a full run's first pass found early, in the worker thread, and written at their turn.

At 100,000 locations the AllDifferent keys (``rules/all-different-key.rq``: the member list walked by
``rdf:rest*/rdf:first``, two MD5s per member) cost 1.7 s of a full REASON's 8.4, evaluated in the main
thread.  What that evaluation reads (the asserted AllDifferent list) is final before the run starts,
and the first rule reading the keys comes after a dozen components that never touch the list.  So,
where the store overlaps (:attr:`topostore.stores.base.Store.overlaps`), such an evaluation's WHERE is
evaluated as a ``CONSTRUCT`` in the worker thread (:class:`topostore.stores.overlap.Reader`, the one
:mod:`.early_reads` uses) from the component after which its reads are final, and serialised there as
N-Triples (neither holds the GIL); when the pass reaches the rule, the main thread sends what it queued,
then writes the triples (:func:`write_found`: the engine parses and inserts them, 0.5 s for 100,000 keys)
instead of evaluating the rule.

The early triples are used only if the evaluation at the rule's turn would be the same one:

* **the same text**: the text the pass would send now (:meth:`.materialize.Materializer.first_pass_text`:
  its shortcuts, the heads it keeps out, its one-group form) equals the text evaluated early, but for the
  name of the delta graph, which an evaluation without delta does not read;
* **the same data**: no evaluation since the start may have written a key it reads, its head's key
  included (the heads it keeps out); every evaluation of the run is noted (:meth:`EarlyRules.wrote`, as
  :meth:`.early_reads.EarlyReads.wrote` does); a rule of a variable predicate or class counts as writing
  every key.

Otherwise the early triples are dropped and the rule is evaluated as before.  Only evaluations that write
to one graph qualify (a first pass's rule whose facts are not read again as a delta: not in ``back``, a
head of one predicate or class), only those that hash (:func:`hashes`: the keys' MD5s), and only those
with first-pass work of the main thread between their start and their turn: for a plain join or an
arithmetic ``BIND``, writing the solutions costs the main thread about as much as evaluating them there
(1.46 against 1.00 s per 300,000 quads written, docs/benchmarks-history.md), and with nothing to do
meanwhile the pass would only wait for the worker.
Without the second thread (``TOPOSTORE_OVERLAP=0``, a durable or remote store) nothing starts early and
the run is the sequential one, in the same order.
"""

from __future__ import annotations

import re
from collections.abc import Collection
from concurrent.futures import Future
from dataclasses import dataclass
from time import perf_counter
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode, RdfFormat

from ..compile.generic import PREFIXES
from ..compile.rule import ReadKey, Rule
from ..stores.base import Store
from ..stores.overlap import Reader, early_result
from .order import TYPE_KEY
from .read_keys import Writes, evaluation_reads, touches
from .stats import ReasonStats

if TYPE_CHECKING:
    from .materialize import Materializer

#: a SPARQL hash function
_HASH = re.compile(r"\b(MD5|SHA1|SHA256|SHA384|SHA512)\(", re.IGNORECASE)

#: an evaluation text's head writing into one graph: ``INSERT { GRAPH <g> { … } }``
_ONE_GRAPH = re.compile(r"INSERT \{ GRAPH (<[^>]+>) \{ ([^{}]*) \} \}")


@dataclass(frozen=True)
class Found:
    """The solutions of an evaluation found early: its head's triples as N-Triples, and their graph."""

    triples: bytes
    graph: NamedNode


def construct_form(text: str, delta: NamedNode) -> tuple[str, NamedNode] | None:
    """The ``CONSTRUCT`` query of an evaluation text writing its head into one graph (and that graph), its
    dataset without the delta graph ``delta``; None for a text of another shape, or one whose WHERE reads
    the delta graph."""
    head, dataset, where = text.split("\n", 2)
    found = _ONE_GRAPH.fullmatch(head)
    if found is None or not where.startswith("WHERE") or str(delta) in where:
        return None
    words = _without_delta(dataset, delta).replace("USING NAMED ", "FROM NAMED ").replace("USING ", "FROM ")
    return f"CONSTRUCT {{ {found.group(2)} }}\n{words}\n{where}", NamedNode(found.group(1)[1:-1])


def _without_delta(text: str, delta: NamedNode) -> str:
    """``text`` without its dataset's clause naming the delta graph (read by no evaluation without delta)."""
    return text.replace(f" USING NAMED {delta}", "")


def _evaluate(store: Store, query: str, graph: NamedNode) -> Found:
    """The worker's part: the ``CONSTRUCT`` evaluated and serialised by the engine (no GIL held)."""
    triples = store.query(query, prefixes=PREFIXES).serialize(format=RdfFormat.N_TRIPLES)
    return Found(triples or b"", graph)


def write_found(store: Store, found: Found, name: str, stats: ReasonStats, profile: bool) -> None:
    """Write an evaluation's early solutions into their graph (timed under ``name`` when profiling)."""
    if not found.triples:
        return
    start = perf_counter()
    store.add_ntriples(found.triples, found.graph)
    if profile:
        stats.per_rule[name] = stats.per_rule.get(name, 0.0) + perf_counter() - start


def hashes(rule: Rule) -> bool:
    """Whether ``rule`` binds a term made with a hash function (the AllDifferent keys' two MD5s per member):
    such an evaluation costs far more than writing its solutions, so the worker takes it.  Not a BIND of
    arithmetic: Urgency's subtraction at 100,000 locations cost the worker 0.32 s and the main thread 0.39 s
    to write its 100,000 memberships, against 0.36 s evaluating it there."""
    return any(c.binds and _HASH.search(c.expression) for c in rule.conditions)


class EarlyRules:
    """The first-pass evaluations of one full run started early; see the module docstring."""

    def __init__(self, run: Materializer, ordered: list[list[int]], back: Collection[int], reader: Reader) -> None:
        self.run = run
        self._reader = reader
        #: component -> the rules whose evaluation starts after it (-1: before the first)
        self._after: dict[int, list[int]] = {}
        #: rule -> the keys its evaluation reads (its head's key included)
        self._reads: dict[int, frozenset[ReadKey]] = {}
        #: started and still holding: rule -> (its text without the delta graph, its solutions)
        self._started: dict[int, tuple[str, Future]] = {}
        before = Writes()  # the writers of the components before the one looked at
        #: how many rules the first pass evaluates in the components before each (the main thread's work
        #: while the worker evaluates: none, and the pass would only wait for it)
        evaluated = [0]
        for c, component in enumerate(ordered):
            for i in component:
                if not self._eligible(i, back):
                    continue
                keys = evaluation_reads(run.rules[i]) | {run.rules[i].writes()}
                beside = Writes([(0, run.rules[j].writes()) for j in component if j != i])
                start = before.last(keys)
                if beside.last(keys) < 0 and evaluated[c] > evaluated[start + 1]:
                    self._reads[i] = keys
                    self._after.setdefault(start, []).append(i)
            for i in component:
                before.add(c, run.rules[i].writes())
            evaluated.append(evaluated[c] + sum(1 for i in component if run.first_pass_evaluates(i)))

    def _eligible(self, i: int, back: Collection[int]) -> bool:
        """Whether rule ``i``'s first-pass evaluation hashes (:func:`hashes`) and writes into one graph alone
        (see the module)."""
        key = self.run.rules[i].writes()
        return (hashes(self.run.rules[i]) and i not in back and key is not None and key[0] != "*"
                and key != ("p", TYPE_KEY) and self.run.first_pass_alone(i))

    def after(self, component: int) -> None:
        """The ordered component ``component`` is done (-1: none yet): start the evaluations that waited."""
        run = self.run
        store = run.store
        delta = run.delta_read
        for i in self._after.pop(component, ()):
            text = run.first_pass_text(i)
            form = construct_form(text, delta)
            if form is None:
                continue
            query, graph = form
            self._started[i] = (_without_delta(text, delta),
                                self._reader.submit(lambda q=query, g=graph: _evaluate(store, q, g)))

    def wrote(self, key: ReadKey | None) -> None:
        """An evaluation writing ``key`` was sent or queued: the early evaluations reading it no longer hold."""
        for i in [i for i in self._started if touches(key, self._reads[i])]:
            self._started.pop(i)[1].cancel()

    def evaluated(self, i: int, text: str) -> Found | None:
        """The solutions of rule ``i``'s evaluation ``text``, found early (None: evaluate it now)."""
        started = self._started.pop(i, None)
        if started is None:
            return None
        return early_result(started, _without_delta(text, self.run.delta_read))

    def close(self) -> None:
        """Drop what was not used (the reader is joined by its owner)."""
        for _, solutions in self._started.values():
            solutions.cancel()
        self._started.clear()


__all__ = ["EarlyRules", "Found", "construct_form", "write_found"]
