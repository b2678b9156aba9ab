"""Running a compiled step key by key (:mod:`.program`), where a request costs microseconds.

In memory, parsing and planning the operations is what a step costs, and most of them start from a
key the step did not change after all (a candidate confirmed, a derivation already known).  After
each key's operations, two index look-ups tell whether it lost or gained facts; later operations
starting from it run only if it did.  The result is the same as the whole program's, since a
left-out operation reads an empty change.  Recursive components run their rounds here too
(:func:`.component.run_component`).
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from itertools import islice

from pyoxigraph import Literal, NamedNode, Triple

from ..compile.generic import PREFIXES
from ..compile.rule import ReadKey
from ..rdf.vocab import ASSERTED, TYPE
from . import direct as direct_look_ups
from .component import run_component
from .delta_texts import FLIP_LOST, KEEP, NEW_STATE
from .direct import pattern_of
from .program import Signature, StepProgram
from .regroup import REGROUPED
from .scratch import CANDIDATES, FLIP_GAINED, NEW_FACTS, OVERDELETED
from .staged_plan import AFTER, BOTH, HANDED, SEEDING, SENT, BoundOp, Segment, segments
from .triggers import Present

#: up to how many candidates a key's rechecks go one by one, stopping once every candidate is kept
FEW = 32


#: the read key of an rdf:type atom whose class is a variable: every class's facts (never given by key)
_ANY_CLASS = ("p", f"<{TYPE.value}>")


def _by_key(facts: Collection[Triple]) -> tuple[dict, set]:
    """``facts`` by their read key (a class's membership under its class), in one pass, and the keys with a
    literal among them (read back in the store's spelling instead: :meth:`StagedRun.change_facts`)."""
    out: dict[tuple, list[Triple]] = {}
    literal: set[tuple] = set()
    for t in facts:
        p, o = t.predicate, t.object
        key = ("t", f"<{o.value}>") if p == TYPE and isinstance(o, NamedNode) else ("p", f"<{p.value}>")
        out.setdefault(key, []).append(t)
        if isinstance(o, Literal):
            literal.add(key)
    return out, literal


class StagedRun:
    """One key-by-key run of a :class:`~.program.StepProgram` on a store."""

    def __init__(self, store, program: StepProgram, sig: Signature,
                 flip_text: Callable[..., str],
                 changes: tuple[Collection[Triple], Collection[Triple]] | None = None,
                 before_text: Callable[[], None] | None = None, present: Present | None = None) -> None:
        """``flip_text(rule, order, text[, look_up_first])``: a flip's text for this run
        (:meth:`.compiled_step.CompiledStep._flip_text`); ``changes``: the added and removed asserted
        triples, written to the step's first lost and gained facts directly instead of by the program's
        first operation; ``before_text``: called once before the first text is sent (the copies of the
        changes its operations read); ``present``: the keys with facts before the run (a superset; None:
        any), whose absence leaves out an operation that would find nothing (:attr:`.staged_plan.BoundOp.needs`)."""
        self.store = store
        self.changes = changes
        self.before_text = before_text
        self.program = program
        #: a flip operation's text for this run (narrowed by a value window where one applies)
        self.flip_text = flip_text
        #: keys that lost / gained facts so far
        self.minus = set(sig.removed)
        self.plus = set(sig.added)
        self.queue: list[str] = []
        #: operations sent (the reasoner's evaluation count)
        self.sent = 0
        #: recursive components run so far (their scratch graphs start empty)
        self.components = 0
        #: operations with an equivalent through index look-ups use it (not where a look-up is a round trip)
        self.direct = {} if store.round_trips else program.direct
        #: keys whose facts the queued operations may write (a look-up of another key needs no flush);
        #: None: any key
        self.dirty: set = set()
        #: keys whose part ran, not yet looked up for lost or gained facts (done when a later part asks)
        self.unnoted: set = set()
        self.present = present
        #: SPARQL text was sent (it may write facts of any key its part writes, without a note)
        self.texts = False
        #: :meth:`change_facts` by (key, side), and each side's facts by key (:func:`_by_key`)
        self._change_facts: dict = {}

    def run(self) -> None:
        """Run the program part by part (:func:`segments`): a part none of whose operations can run (no
        operation sent whatever changed, and no key it starts from changed or may have) is passed by
        one set test; the others run operation by operation (:meth:`_part`)."""
        program = self.program
        plan = program.segments
        if plan is None:
            plan = program.segments = segments(program, self.direct)
        minus, plus, unnoted = self.minus, self.plus, self.unnoted
        for segment in plan:
            if segment.component is not None:
                self.flush()  # a component reads between its rounds whatever it likes
                for key in list(unnoted):
                    self._changed(key, minus)
                run_component(self, segment.component)
            elif segment.always or not (segment.minus.isdisjoint(minus) and segment.plus.isdisjoint(plus)
                                        and segment.keys.isdisjoint(unnoted)):
                self._part(segment.ops)
        self.flush()

    def _part(self, ops: list[BoundOp]) -> None:
        """Run one part's operations: each is sent when the key it starts from changed, and a key's
        recheck and flip results only when there is something to recheck or add (index look-ups,
        after sending what is queued).  A part's flipped facts come only from its own flips, so its
        flip results are not looked up when none of its flips ran.

        While every flip of the part that ran did by look-ups, their heads are kept here (``handed``)
        and given to the part's lost and gained operations, not written to FLIP_LOST and FLIP_GAINED
        and read back: those graphs' only readers are these operations.  What one of them cannot take
        (its SPARQL text runs), and everything once a flip runs otherwise, is written there first."""
        seeded = queued = flipped = False
        found: dict[tuple, bool] = {}
        mark = self.sent
        #: the flips' heads by the graph they would be written to; None: none yet, False: written there
        handed: dict | bool | None = None
        taken: set = set()  # the graphs whose heads an operation took
        regrouped: set[int] = set()  # regrouped candidates operations that diffed (their covered ones are done)
        for index, kind, key, text, flip, part, direct, reads, has_seeded, part_reads, hand, needs, given, \
                covered_by in ops:
            if covered_by is not None and covered_by in regrouped:
                continue
            look_up = True
            if given is not None and direct is not None:
                direct = self._given(direct, key, given, index, regrouped)
            fallback = None
            if flip is not None:
                if needs and self._without_facts(needs):
                    continue  # an atom it joins has no facts: nothing can flip
                compiled = text
                # a flip with a look-up form tries it first: a value window (its query, or only finding
                # that none applies) is made for the text alone, where the look-up gives up
                lazy = direct is not None
                text = self._flip(part_reads, flip, text, lazy)
                if not text:
                    continue  # nothing can flip this time
                flipped = True
                # a text narrowed by a value window: many facts, whose window query ran already
                look_up = text is compiled
                if lazy:  # where the look-up gives up, the text narrowed by a window query runs
                    fallback = (flip, compiled, part_reads)
                if hand is not None and look_up and handed is not False:
                    heads = self._heads(hand, reads)
                    if heads is not None:
                        if handed is None:
                            handed = {FLIP_GAINED: {}, FLIP_LOST: {}}
                        handed[FLIP_GAINED].update(dict.fromkeys(heads[0]))
                        handed[FLIP_LOST].update(dict.fromkeys(heads[1]))
                        continue
                if handed:
                    self._spill(handed)
                handed = False
            elif handed and kind in HANDED:
                graph = HANDED[kind]
                facts = list(handed[graph])
                taken.add(graph)  # kept for another such operation, and for a flip's text after it
                if facts:
                    if self.dirty:
                        self._reading(reads)
                    if hand is not None and hand(self.store, facts):
                        self.sent += 1
                    else:  # its text reads them from the graph
                        self.store.add_scratch(facts, HANDED[kind])
                        queued |= self._send(text, part, None, reads, False)
                    seeded |= kind in SEEDING
                continue
            if kind == "changes" and self.changes is not None:
                self.store.add_scratch(self.changes[0], NEW_FACTS)
                self.store.add_scratch(self.changes[1], OVERDELETED)
            elif kind == "keep":
                queued |= self._keep(found, key, text, seeded, direct, reads, has_seeded and index)
            elif kind == "delete":
                if not found.get(("kept", key)) and self._holds(found, CANDIDATES, key, seeded):
                    queued |= self._send(text, part, direct, reads, has_seeded and index)
            elif kind in SENT or (kind == "minus" and self._changed(key, self.minus)) \
                    or (kind == "plus" and self._changed(key, self.plus)) \
                    or (kind in AFTER and (flipped or kind == "recheck")
                        and self._holds(found, AFTER[kind], key, seeded)):
                if needs is not None and self._without_facts(needs):
                    continue  # it joins a key without facts: it finds nothing
                queued |= self._send(text, part, direct if look_up else None, reads, has_seeded and index,
                                     look_up, fallback, needs if flip is not None else None)
                seeded |= kind in SEEDING
            elif kind == "end":
                if handed and len(taken) < len(handed):  # heads no operation took: where the graphs would have them
                    self._spill(handed, taken)
                    handed = False
                if queued or self.sent != mark:  # something ran for this key (a look-up may have sent it)
                    self.unnoted.add(key)  # looked up when a later part asks (after a flush if needed)
        if handed and len(taken) < len(handed):
            self._spill(handed, taken)

    def _without_facts(self, keys: tuple) -> bool:
        """Whether one of ``keys`` (:attr:`.staged_plan.BoundOp.needs`) surely has no facts now: none before
        the run (:attr:`present`), and none gained since (looked up where its part ran unnoted; nothing
        queued that may write it)."""
        present, dirty = self.present, self.dirty
        if present is None or None in dirty:
            return False
        for key, which, name in keys:
            if name in present[which] or key in dirty:
                continue
            if key in self.unnoted:
                self._changed(key, self.plus)
            if key not in self.plus:
                return True
        return False

    def _finds_nothing(self, keys: tuple) -> bool:
        """Whether a flip whose text is about to be queued surely finds nothing: one of the keys it joins in
        the new state (:attr:`.staged_plan.BoundOp.needs`) has no fact in the state graphs now (index
        look-ups, after sending what is queued and may write it).  :meth:`_without_facts` answers from the
        keys with facts before the run, a superset that keeps a key once it had any (a helper key
        present once, empty on every step since, let a difference flip's text run at every step of a
        large map); asked only where a text would run, which costs far more than these reads."""
        for key, _, _ in keys:
            if self.dirty:
                self._reading((key,))
            pattern = pattern_of(key)
            if not any(self.store.has_match(*pattern, g) for g in NEW_STATE):
                return True
        return False

    def gained(self) -> set | None:
        """The keys that may have gained facts in this run (those noted as gaining, and those whose part
        ran unnoted); None where text ran or a component did (any key its operations write may have)."""
        if self.texts or self.components:
            return None
        return self.plus | self.unnoted

    def lost(self) -> set | None:
        """The keys that may have lost facts in this run, as :meth:`gained` says of those that may have gained."""
        if self.texts or self.components:
            return None
        return self.minus | self.unnoted

    def _heads(self, hand: Callable, reads: Collection | None) -> tuple | None:
        """A flip's heads by look-ups (:meth:`.look_flip.Flipped.heads`), after sending what is queued
        and may write what it ``reads``; counted as sent where found."""
        if self.dirty:
            self._reading(reads)
        heads = hand(self.store)
        if heads is not None:
            self.sent += 1
        return heads

    def _spill(self, handed: dict, taken: Collection = ()) -> None:
        """Write the heads kept for a part's lost and gained operations where their texts read them
        (but those of ``taken`` graphs, once no operation can read them any more)."""
        for graph, facts in handed.items():
            if facts and graph not in taken:
                self.store.add_scratch(list(facts), graph)

    def _changed(self, key: ReadKey, changes: set) -> bool:
        """Whether ``key`` is in ``changes`` (:attr:`minus` or :attr:`plus`), looking up first whether
        it lost or gained facts where its part ran and nothing asked yet."""
        if key in self.unnoted:
            self.unnoted.discard(key)
            self.note(key)
        return key in changes

    def _reading(self, keys: Collection) -> None:
        """Send what is queued when it may write facts of ``keys``, which Python is about to read (callers
        test ``dirty`` first: most reads find nothing queued)."""
        if self.dirty and (None in self.dirty or not self.dirty.isdisjoint(keys)):
            self.flush()

    def _flip(self, part_reads: Collection, tag: tuple, text: str, look_up_first: bool = False) -> str:
        """The flip's text for this run (:attr:`flip_text`): "" when nothing can flip, the compiled text,
        or one narrowed by a value window (not while its look-up runs first: ``look_up_first``);
        ``part_reads``: the keys its part may read (its rules' premises and its own key)."""
        if self.dirty:  # a value window's query reads the rule's premises
            self._reading(part_reads)
        return self.flip_text(tag[2], tag[3], text, True) if look_up_first else self.flip_text(tag[2], tag[3], text)

    def _seeded(self, index: int, text: str) -> str:
        """The text to queue for flip ``index`` whose compiled ``text`` runs: where every fact of a
        compared predicate was replaced, the one branch seeded by it instead of the UNION.  Asked only
        when the text is queued (an operation's look-ups do not read it)."""
        seeded = self.program.seeded.get(index)
        if not seeded or self.changes is None or self.store.round_trips:
            return text
        for p, single in seeded.items():
            if self._all_replaced(p):
                return single
        return text

    def _all_replaced(self, p: str) -> bool:
        """Whether every fact of predicate ``p`` (IRI text; asserted only, no rule derives it) was
        replaced by this change: as many facts as replaced subjects (one index read, stopped early)."""
        subjects = {t.subject for t in self.changes[0] if t.predicate.value == p[1:-1]}
        if not subjects:
            return False
        facts = islice(self.store.triples(None, NamedNode(p[1:-1]), None, ASSERTED), len(subjects) + 1)
        return sum(1 for _ in facts) == len(subjects)

    def change_facts(self, key: ReadKey, side: int) -> list[Triple] | None:
        """The change's added (``side`` 0) or removed (1) facts of ``key``: what NEW_FACTS or OVERDELETED hold
        of a key no rule of the program writes (:attr:`.staged_plan.BoundOp.given`), without reading them
        back; None where the look-up reads them itself: no change given (its text copies it), more than
        :data:`.direct.FEW`, or a literal among them (read back in the form the store keeps)."""
        found = self._change_facts.get((key, side), False)
        if found is not False:
            return found
        found = None
        if self.changes is not None:
            by_key = self._change_facts.get(side)
            if by_key is None:
                by_key = self._change_facts[side] = _by_key(self.changes[side])
            found = None if key == _ANY_CLASS or key in by_key[1] else by_key[0].get(key, [])
            if found is not None and len(found) > direct_look_ups.FEW:
                found = None
        self._change_facts[(key, side)] = found
        return found

    def _given(self, look_up: Callable, key: ReadKey, side: int, index: int, regrouped: set[int]) -> Callable:
        """``look_up`` given ``key``'s facts of the change (:meth:`change_facts`; both sides for a regrouped
        candidates operation, whose position joins ``regrouped`` where it diffed) as the interpreted run calls it."""
        if side != BOTH:
            return lambda store: look_up(store, self.change_facts(key, side))

        def diffed(store) -> object:
            answer = look_up(store, self.change_facts(key, 1), self.change_facts(key, 0))
            if answer is REGROUPED:
                regrouped.add(index)
            return answer

        return diffed

    def _send(self, text: str, key: ReadKey | None, direct: Callable | None, reads: Collection | None,
              seeded: int | bool, look_up: bool = True, fallback: tuple | None = None,
              joins: tuple | None = None) -> bool:
        """Run an operation (of ``key``'s part, None: of no key's) through its look-up equivalent
        ``direct`` (None: none, or not this time) where its facts are few (after sending what is queued
        and may write ``reads``, what it reads), else queue its text.  Whether it was queued.
        ``seeded``: the operation's position where it has a seeded text (:meth:`_seeded`), else False;
        ``fallback``: a flip's tag, compiled text and its part's reads, whose text for this run is made
        where the look-up gives up (a window query may narrow it); ``joins``: a flip's keys of the new state
        (:attr:`.staged_plan.BoundOp.needs`), looked up before its text is queued (:meth:`_finds_nothing`)."""
        if direct is not None:
            if self.dirty:  # nothing queued: nothing to send first (no call)
                self._reading(reads)
            if direct(self.store):
                self.sent += 1
                return False
            return self._queue(text, key, seeded, look_up, fallback, joins)
        return self._queue(text, key, seeded, look_up, None, joins)

    def _queue(self, text: str, key: ReadKey | None, seeded: int | bool, look_up: bool = True,
               fallback: tuple | None = None, joins: tuple | None = None) -> bool:
        """Queue an operation's text (:meth:`_send`'s second half, once no look-up answered); ``fallback``:
        a flip's tag, compiled text and part's reads where its look-up gave up (its text for this run is
        made now: "" queues nothing); ``joins``: a flip's keys of the new state, none of whose facts
        left means the text finds nothing (:meth:`_finds_nothing`).  Whether it was queued."""
        if fallback is not None:
            tag, compiled, part_reads = fallback
            text = self._flip(part_reads, tag, compiled)
            if not text:
                return False
            look_up = text is compiled
        if joins is not None and not self.store.round_trips and self._finds_nothing(joins):
            return False  # (where a look-up is a round trip, the text finds out)
        if look_up and seeded is not False:  # a flip's compiled text
            text = self._seeded(seeded, text)
        self.queue.append(text)
        self.dirty.add(key)
        return True

    def _keep(self, found: dict, key: ReadKey, text: str, seeded: bool, direct: Callable | None,
              reads: Collection | None, has_seeded: int | bool) -> bool:
        """Queue one of a key's rechecks, unless every candidate is kept already: while the key has
        few candidates, each recheck is sent alone and the candidates and kept ones counted after it.
        Kept ones are compared term by term, not through the store's value-keyed look-up: two spellings
        of one value (``"8"^^xsd:integer``, ``"8"^^xsd:decimal``) are two facts here, and one kept does
        not keep the other (the recheck deletes it unless a rule derives that very term)."""
        if found.get(("kept", key)) or not self._holds(found, CANDIDATES, key, seeded):
            return False
        queued = self._send(text, key, direct, reads, has_seeded)
        if found.get(("many", key)):
            return queued
        if self.dirty:
            self._reading((key,))
        candidates = self.facts(key, CANDIDATES, FEW)
        if len(candidates) >= FEW:
            found[("many", key)] = True
        elif set(candidates) <= set(self.facts(key, KEEP, FEW)):
            found[("kept", key)] = True
        return False

    def _holds(self, found: dict, graph: NamedNode, key: ReadKey, seeded: bool) -> bool:
        """Whether ``graph`` holds facts of ``key`` once what is queued has run (looked up once per key)."""
        if graph == CANDIDATES and not seeded:
            return False  # nothing could have made candidates
        answer = found.get((graph, key))
        if answer is None:
            if self.dirty:
                self._reading((key,))
            answer = found[(graph, key)] = self.has(key, graph)
        return answer

    def flush(self) -> None:
        """Send what is queued as one update request."""
        if self.queue:
            if self.before_text is not None:
                self.before_text()
                self.before_text = None
            self.sent += len(self.queue)
            self.texts = True
            self.store.update(" ;\n".join(self.queue), prefixes=PREFIXES)
            self.queue.clear()
        self.dirty.clear()

    def has(self, key: ReadKey, graph: NamedNode) -> bool:
        """Whether ``graph`` holds a fact of ``key`` (an index look-up)."""
        return self.store.has_match(*pattern_of(key), graph)

    def facts(self, key: ReadKey, graph: NamedNode, limit: int) -> list[Triple]:
        """The facts of ``key`` in ``graph``, at most ``limit`` of them."""
        return list(islice(self.store.triples(*pattern_of(key), graph), limit))

    def has_any(self, graph: NamedNode) -> bool:
        return self.store.has_match(None, None, None, graph)

    def note(self, key: ReadKey) -> None:
        """Record whether ``key`` lost or gained facts."""
        if self.dirty:
            self._reading((key,))
        if self.has(key, OVERDELETED):
            self.minus.add(key)
        if self.has(key, NEW_FACTS):
            self.plus.add(key)


__all__ = ["BoundOp", "Segment", "StagedRun", "segments"]
