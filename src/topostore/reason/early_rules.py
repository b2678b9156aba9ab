"""Rule evaluations of a full run's first pass found and written early, in the worker thread.

At 100,000 locations the AllDifferent keys (``rules/all-different-key.rq``: the member list walked by
``rdf:rest*/rdf:first``, two MD5s per member) cost 1.7 s of a full REASON's 8.4, evaluated in the main
thread, and the minimum of two doors (``ext-min-card``, counted per group by :mod:`.key_pairs`) 0.8 s for
50,000 memberships: both read far more than they write.  What the keys read (the asserted AllDifferent
list) is final before the run starts, and what the count reads (the doors and the keys) once the keys are
written.  So, where the store overlaps (:attr:`topostore.stores.base.Store.overlaps`), such an
evaluation's WHERE is evaluated as a ``CONSTRUCT`` in the worker thread (:class:`topostore.stores.overlap.Reader`,
the one :mod:`.early_reads` uses) from the component after which its reads are final, serialised there as
N-Triples and loaded there into its graph (:meth:`.Store.add_ntriples_beside`; the engine takes one writer
at a time, so the main thread's next update waits for the load, but neither the read nor the parse is the
main thread's).  An early evaluation whose facts a later one reads counts as written where it started: the
worker runs its reads in the order they were started, so the reader (the count after the keys) is
started at the same point, after it.  When the pass reaches the rule, it has nothing to write.

The early facts are kept as the rule's evaluation only if the evaluation at the rule's turn would be the
same one:

* **the same text**: the text the pass would send now (:meth:`.materialize.Materializer.first_pass_text`:
  its shortcuts, the heads it keeps out, its one-group form) equals the text evaluated early, but for the
  name of the delta graph, which an evaluation without delta does not read;
* **the same data**: no evaluation since the start may have written a key it reads, its head's key
  included (the heads it keeps out); every evaluation of the run is noted (:meth:`EarlyRules.wrote`, as
  :meth:`.early_reads.EarlyReads.wrote` does); a rule of a variable predicate or class counts as writing
  every key.

Otherwise the rule is evaluated at its turn as before.  The facts loaded early stay: only evaluations
without negation are started early (:func:`positive`: no ``MINUS``, ``NOT EXISTS`` or ``OPTIONAL``; a
count's ``HAVING (COUNT(…) > 1)`` only grows with the data), so what one found on the data of its start
holds on the final data too, and the evaluation at the turn adds the rest.  Only evaluations that write
to one graph qualify (a first pass's rule whose facts are not read again as a delta: not in ``back``, a
head of one predicate or class), only those that hash, walk a list or count (:func:`costly`), and only
those with first-pass work of the main thread between their start and their turn: for a plain join or an arithmetic
``BIND``, writing the solutions costs about as much as evaluating them (1.46 against 1.00 s per 300,000
quads written, docs/benchmarks-history.md), and with nothing to do meanwhile the pass would only wait for
the worker.  Without the second thread (``TOPOSTORE_OVERLAP=0``, a durable or remote store) nothing
starts early and the run is the sequential one, in the same order.

The worker also takes the census of a keyed conclusion (:mod:`.keyed_first_pass`), started where its reads
are final and awaited at the conclusion's turn, which then leaves its key atoms out where it covers.  Of the
reads started at one point, a census goes right after the last early evaluation writing a key it reads (the
keys), ahead of the others (the minimum's count): the conclusion's turn comes before the count's, and queued
behind the count the census kept the main thread waiting for both (1.2 s at 100,000 locations).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Collection, Mapping
from concurrent.futures import Future
from dataclasses import dataclass
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode, RdfFormat

from ..compile.generic import PREFIXES
from ..compile.rule import ReadKey, Rule
from ..stores.base import Store
from ..stores.overlap import Reader, early_result
from .key_pairs import grouped_form
from .keyed_asks import KeyCensus
from .one_group import one_group
from .order import TYPE_KEY
from .read_keys import Writes, evaluation_reads, touches
from .triggers import Present, may_write_any

if TYPE_CHECKING:
    from .materialize import Materializer

#: a SPARQL hash function
_HASH = re.compile(r"\b(MD5|SHA1|SHA256|SHA384|SHA512)\(", re.IGNORECASE)

#: an evaluation text's head writing into one graph: ``INSERT { GRAPH <g> { … } }``
_ONE_GRAPH = re.compile(r"INSERT \{ GRAPH (<[^>]+>) \{ ([^{}]*) \} \}")

#: what makes a WHERE able to lose a match when the data grows
_NEGATION = re.compile(r"\b(MINUS|NOT\s+EXISTS|OPTIONAL)\b", re.IGNORECASE)


@dataclass(frozen=True)
class Found:
    """An evaluation found and written early: the graph its facts went to, and their N-Triples' size."""

    graph: NamedNode
    size: int


def construct_form(text: str, delta: NamedNode) -> tuple[str, NamedNode] | None:
    """The ``CONSTRUCT`` query of an evaluation text writing its head into one graph (and that graph), its
    dataset without the delta graph ``delta``; None for a text of another shape, one whose WHERE reads
    the delta graph, or one whose WHERE is not :func:`positive`."""
    head, dataset, where = text.split("\n", 2)
    found = _ONE_GRAPH.fullmatch(head)
    if found is None or not where.startswith("WHERE") or str(delta) in where or not positive(where):
        return None
    words = _without_delta(dataset, delta).replace("USING NAMED ", "FROM NAMED ").replace("USING ", "FROM ")
    return f"CONSTRUCT {{ {found.group(2)} }}\n{words}\n{where}", NamedNode(found.group(1)[1:-1])


def positive(where: str) -> bool:
    """Whether a WHERE has no negation (``MINUS``, ``NOT EXISTS``, ``OPTIONAL``): its matches on some data
    stay matches on more, so its facts found on the data of its start hold at the fixpoint."""
    return _NEGATION.search(where) is None


def _without_delta(text: str, delta: NamedNode) -> str:
    """``text`` without its dataset's clause naming the delta graph (read by no evaluation without delta)."""
    return text.replace(f" USING NAMED {delta}", "")


def _evaluate(store: Store, query: str, graph: NamedNode) -> Found:
    """The worker's part: the ``CONSTRUCT`` evaluated and serialised by the engine (no GIL held), then
    loaded into ``graph`` by the engine, after the main thread's update under way."""
    triples = store.query(query, prefixes=PREFIXES).serialize(format=RdfFormat.N_TRIPLES) or b""
    if triples:
        store.add_ntriples_beside(triples, graph)
    return Found(graph, len(triples))


def _delay(ordered: list[list[int]], rules: list[Rule], eligible: Callable[[int, Present], bool],
           start: Present) -> None:
    """Move each component holding an evaluation the worker may take (``eligible`` with the keys that may
    hold facts by its turn), with the later components reading what it writes or what they write in turn,
    after the later components reading none of it, in place: the main thread evaluates those while the
    worker evaluates it (a minimum's count concluding CORRIDOR, read by CORRIDOR's copies into ROOM and
    LOCATION, goes after Connectability with them).  The order stays one where every reader follows its
    writers (a component moves only past components that read nothing it, or what moves with it, writes;
    those moving keep their order)."""
    present = (set(start[0]), set(start[1]))
    taken = []
    for component in ordered:
        if any(eligible(i, present) for i in component):
            taken.append(component)
        for i in component:
            _claim(present, rules[i].writes())
    if not taken:
        return
    reads = {id(c): frozenset().union(*(evaluation_reads(rules[j]) for j in c)) for c in ordered}
    for component in reversed(taken):
        at = next(n for n, c in enumerate(ordered) if c is component)
        written = [rules[i].writes() for i in component]
        moved, passed = [component], []
        for later in ordered[at + 1:]:
            if any(touches(w, reads[id(later)]) for w in written):
                moved.append(later)
                written += [rules[i].writes() for i in later]
            else:
                passed.append(later)
        ordered[at:] = passed + moved


def _claim(present: Present, key: ReadKey | None) -> None:
    """Add the key a rule of the ordered pass writes to ``present``, as the first pass does once it evaluated
    the rule (a rule of a variable predicate is never in that pass)."""
    if key is None or key[0] == "*":
        return
    present[1 if key[0] == "t" else 0].add(key[1])
    if key[0] == "t":
        present[0].add(TYPE_KEY)


def hashes(rule: Rule) -> bool:
    """Whether ``rule`` binds a term made with a hash function (the AllDifferent keys' two MD5s per member).
    Not a BIND of arithmetic: Urgency's subtraction at 100,000 locations cost the worker 0.32 s and the
    main thread 0.39 s to write its 100,000 memberships, against 0.36 s evaluating it there."""
    return any(c.binds and _HASH.search(c.expression) for c in rule.conditions)


def walks(rule: Rule) -> bool:
    """Whether ``rule`` reads an atom through a path of any length (the AllDifferent keys' walk of their
    member list, ``(rdf:rest*)/rdf:first``): where a member is its own key no term is made, but the walk
    still reads two list quads for each fact it writes, and beside the main thread's rules it is off
    their path."""
    return any("*" in a.p for a in rule.body)


def costly(rule: Rule) -> bool:
    """Whether an evaluation of ``rule`` reads far more than it writes, so that the worker takes it: it
    hashes (:func:`hashes`) or walks a list (:func:`walks`), or a full run counts it per group
    (:func:`.key_pairs.grouped_form`: every pair of a subject's values and their keys read for one
    membership; a plain join such as Connectability writes about one fact per match, and stays in the
    pass)."""
    return hashes(rule) or walks(rule) or grouped_form(rule) is not None


class EarlyRules:
    """The first-pass evaluations of one full run started early; see the module docstring."""

    def __init__(self, run: Materializer, ordered: list[list[int]], back: Collection[int], reader: Reader) -> None:
        self.run = run
        self._reader = reader
        #: component -> the rules whose evaluation starts after it (-1: before the first)
        self._after: dict[int, list[int]] = {}
        #: rule -> the keys its evaluation reads (its head's key included)
        self._reads: dict[int, frozenset[ReadKey]] = {}
        #: started and still holding: rule -> (its text without the delta graph, its facts written)
        self._started: dict[int, tuple[str, Future]] = {}
        #: the keyed conclusions' censuses (:mod:`.keyed_first_pass`): component -> those started after it;
        #: started and still holding: rule -> whether its census covers
        self._census_after: dict[int, list[int]] = {}
        self._censused: dict[int, Future] = {}
        #: the censuses that covered at their conclusion's turn and whose reads nothing written since
        #: touches (by ``id``): the deferred ask of the same census is answered by it (:meth:`covered`)
        self._covering: dict[int, KeyCensus] = {}
        _delay(ordered, run.rules, lambda i, present: self._eligible(i, back, present), run.present)
        #: the writers of the components before the one looked at, an early one where it starts (the worker
        #: writes its facts before it runs the reads started after it)
        before = Writes()
        #: how many rules the first pass evaluates in the components before each (the main thread's work
        #: while the worker evaluates: none, and the pass would only wait for it)
        evaluated = [0]
        #: the keys that may hold facts at each component's turn: the start's, and what the pass before wrote
        present = (set(run.present[0]), set(run.present[1]))
        for c, component in enumerate(ordered):
            for i in component:
                if i in run.keyed:
                    self._census_point(i, c, component, before)
                if not self._eligible(i, back, present):
                    before.add(c, run.rules[i].writes())
                    continue
                keys = evaluation_reads(run.rules[i]) | {run.rules[i].writes()}
                beside = Writes([(0, run.rules[j].writes()) for j in component if j != i])
                start = before.last(keys)
                if beside.last(keys) < 0 and evaluated[c] > evaluated[start + 1]:
                    self._reads[i] = keys
                    self._after.setdefault(start, []).append(i)
                before.add(start if i in self._reads else c, run.rules[i].writes())
            evaluated.append(evaluated[c] + sum(1 for i in component if run.first_pass_evaluates(i, present)))
            for i in component:
                _claim(present, run.rules[i].writes())

    def _census_point(self, i: int, c: int, component: list[int], before: Writes) -> None:
        """Note where the census of keyed conclusion ``i`` (of component ``c``) starts: after the last
        component writing a key it reads (an early writer where it starts), none where a rule of its own
        component may write one (the census would not see the data of its turn)."""
        reads = self.run.keyed[i].reads
        if Writes([(0, self.run.rules[j].writes()) for j in component if j != i]).last(reads) >= 0:
            return
        start = before.last(reads)
        if start < c:
            self._census_after.setdefault(start, []).append(i)

    def _eligible(self, i: int, back: Collection[int], present: Present) -> bool:
        """Whether rule ``i``'s first-pass evaluation reads far more than it writes (:func:`costly`) and
        writes into one graph alone (see the module), its keys able to hold facts by its turn (``present``)."""
        key = self.run.rules[i].writes()
        return (costly(self.run.rules[i]) and i not in back and key is not None and key[0] != "*"
                and key != ("p", TYPE_KEY) and self.run.first_pass_alone(i, present))

    def after(self, component: int) -> None:
        """The ordered component ``component`` is done (-1: none yet): start the evaluations that waited."""
        run = self.run
        store = run.store
        delta = run.delta_read
        early = self._after.pop(component, [])
        censuses = self._census_after.pop(component, [])
        for n, i in enumerate(early):
            censuses = self._census(censuses, early[n:])
            text = run.first_pass_text(i)
            form = construct_form(text, delta)
            if form is None:
                continue
            query, graph = form
            self._started[i] = (_without_delta(text, delta),
                                self._reader.submit(lambda q=query, g=graph: _evaluate(store, q, g)))
            self.wrote(run.rules[i].writes(), censuses_only=True)  # loaded after the censuses started before
        self._census(censuses, [])

    def _census(self, waiting: list[int], later: list[int]) -> list[int]:
        """Start the censuses of ``waiting`` that no early evaluation of ``later`` (started after them at the
        same point) writes a key of, and return the others.  A census is awaited at its conclusion's turn,
        the count of a minimum (queued beside it) only at a later component's: queued first, the census is
        ready when the conclusion's turn comes instead of waiting for the count in the worker."""
        store = self.run.store
        rest = []
        for i in waiting:
            if any(touches(self.run.rules[j].writes(), self.run.keyed[i].reads) for j in later):
                rest.append(i)
                continue
            census = self.run.keyed[i].census
            # the group read in the worker too: after the early writes started before it
            self._censused[i] = self._reader.submit(lambda c=census: one_group(store, ()) and c.covers(store))
        return rest

    def wrote(self, key: ReadKey | None, censuses_only: bool = False) -> None:
        """An evaluation writing ``key`` was sent, queued or started early: the early evaluations and the
        censuses reading it no longer hold (``censuses_only``: the censuses alone)."""
        for i in [i for i in self._censused if touches(key, self.run.keyed[i].reads)]:
            self._censused.pop(i).cancel()
        for c in [c for c, census in self._covering.items() if touches(key, census.reads())]:
            del self._covering[c]
        if censuses_only:
            return
        for i in [i for i in self._started if touches(key, self._reads[i])]:
            self._started.pop(i)[1].cancel()

    def keyless(self, i: int) -> bool:
        """Whether keyed conclusion ``i``'s first pass leaves its keys out: its census, started in the worker
        on the data of its turn (:meth:`wrote` drops it otherwise), covers, and nothing queued may write
        what it read (:mod:`.keyed_first_pass`)."""
        started = self._censused.pop(i, None)
        if started is None:
            return False
        if may_write_any(self.run._queued, self.run.keyed[i].reads):
            started.cancel()
            return False
        if not started.done():
            self._reader.help()
        try:
            covers = started.result() is True
        except Exception:  # noqa: BLE001 - the keys are kept: the pass evaluates the rule as written
            return False
        if covers:
            census = self.run.keyed[i].census
            self._covering[id(census)] = census
        return covers

    def covered(self, census: KeyCensus, graphs: Mapping[ReadKey, NamedNode]) -> bool:
        """Whether ``census``, read with the pair's atoms in ``graphs``, covers now without being taken
        again: it covered at its conclusion's turn (:meth:`keyless`), nothing written, queued or loaded
        since touches what it counts (:meth:`wrote`; the data only grows in a full run, so its counts are
        the same), and ``graphs`` reads a part of what it read (:meth:`.KeyCensus.covers_as_read`).  At
        100,000 locations the deferred ask's census is the same count of 400,000 rows, 0.3 s of the
        worker's, at the end of its queue."""
        return id(census) in self._covering and census.covers_as_read(graphs)

    def evaluated(self, i: int, text: str) -> Found | None:
        """Rule ``i``'s evaluation ``text`` found and written early (None: evaluate it now; an early reader
        of what it writes no longer holds once the pass notes that evaluation, :meth:`wrote`)."""
        started = self._started.pop(i, None)
        if started is None:
            return None
        if not started[1].done():
            self._reader.help()
        return early_result(started, _without_delta(text, self.run.delta_read))

    def loading(self, reads: frozenset[ReadKey]) -> bool:
        """Whether an evaluation started early writes a key of ``reads`` (its facts loaded by the worker,
        before the reads queued after it)."""
        return any(touches(self.run.rules[i].writes(), reads) for i in self._started)

    def close(self) -> None:
        """Drop what was not used (the reader is joined by its owner)."""
        for _, solutions in self._started.values():
            solutions.cancel()
        self._started.clear()
        for census in self._censused.values():
            census.cancel()
        self._censused.clear()
        self._covering.clear()


__all__ = ["EarlyRules", "Found", "construct_form", "costly", "positive"]
