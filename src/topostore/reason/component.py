"""A recursive component of the compiled step: delete and rederive inside it, confirming from outside first.

Why this exists
---------------
On the tutorial map most keys a step reaches form one recursive component: a
place's class decides which places are different (disjoint classes), what is
different decides what is connected (Connectability), and what is connected
decides the class (domain and range).  A recheck key by key (:mod:`.program`)
could let a fact confirm itself around that cycle, so inside a component the
compiled step runs DRed (Gupta, Mumick & Subrahmanian, SIGMOD 1993), with one
refinement that keeps it small: a candidate that a rule with every premise
*outside* the component still derives is confirmed on the spot (those premises
are final, so the fact really holds) and is not propagated.  Only the others
join the over-deleted set, whose consequences inside the component become the
next round's candidates; then the over-deleted facts go, those still derived
come back, and additions run semi-naively inside the component.

Sound: a confirmed fact holds in the new closure, so what depends on it keeps
its support; everything else that may have lost support is over-deleted and
rederived as in DRed.  The rounds are data-dependent, so a component runs only
key by key (:class:`~.program.StagedRun`); stores where each request is a round
trip use the general phases for such changes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pyoxigraph import NamedNode

from ..compile.rule import ReadKey
from ..rdf.vocab import INTERNAL
from . import delta_texts as texts
from . import limits
from .scratch import ADDED, CANDIDATES, FLIP_GAINED, NEW_FACTS, REMOVED

#: every fact of the component over-deleted so far, those of the last round, those of the next
OVER = NamedNode(INTERNAL + "graph:inc-comp-over")
OVER_DELTA = NamedNode(INTERNAL + "graph:inc-comp-over-delta")
OVER_NEXT = NamedNode(INTERNAL + "graph:inc-comp-over-next")
#: facts the component gained in the last round and in the next
ADD_DELTA = NamedNode(INTERNAL + "graph:inc-comp-add-delta")
ADD_NEXT = NamedNode(INTERNAL + "graph:inc-comp-add-next")
COMPONENT_SCRATCH = (OVER, OVER_DELTA, OVER_NEXT, ADD_DELTA, ADD_NEXT)
#: marked when a component run as one request needed more rounds than it had (see :func:`whole_ops`)
UNSETTLED = NamedNode(INTERNAL + "graph:inc-comp-unsettled")

ALWAYS, SEEDS = ("always",), ("seeds",)


@dataclass
class Component:
    """The operations of one recursive component, by phase and by the key they start from."""

    keys: tuple
    #: first candidates: (tag, text) with tags as in :class:`~.program.StagedRun`
    seeds: list = field(default_factory=list)
    #: per key: confirm its candidates from outside the component, then over-delete the others
    confirm: dict = field(default_factory=dict)
    #: per key: candidates from its facts over-deleted in the last round
    inner_candidates: dict = field(default_factory=dict)
    #: per key: delete its over-deleted facts; put back those still derived
    delete: dict = field(default_factory=dict)
    rederive: dict = field(default_factory=dict)
    #: heads a flipped comparison made true, added when their rule derives them after the deletions
    gained: list = field(default_factory=list)
    #: additions from changes outside the component: (tag, text)
    additions: list = field(default_factory=list)
    #: per key: additions from its facts gained in the last round
    inner_additions: dict = field(default_factory=dict)


def compile_component(e, keys: list[ReadKey]) -> Component:
    """The component's operations; ``e`` is the program's emitter (rules, changed keys, provers)."""
    inside = set(keys)
    comp = Component(tuple(keys))
    graphs = {key: e.target(key, [i for i in e.active if e.rules[i].writes() == key]) for key in keys}
    e.graphs.update(graphs)
    writers = [i for i in e.active if e.rules[i].writes() in inside]
    flipped = e.flip_ops(writers, comp.seeds, SEEDS)
    for i in flipped:
        rule = e.rules[i]
        comp.gained.append(texts.additions(rule, None, FLIP_GAINED, (graphs[rule.writes()], NEW_FACTS, ADD_NEXT),
                                           e.c.lateral))
    for i in writers:
        handled = set(e.handled(i) or ())
        rule = e.rules[i]
        into = (graphs[rule.writes()], NEW_FACTS, ADD_NEXT)
        for j, atom in enumerate(rule.body):
            key = atom.read_key()
            if key in inside:
                if not e.idle(i, j):
                    comp.inner_candidates.setdefault(key, []).append(
                        texts.candidates(e.c.flat(i), j, OVER_DELTA, e.c.lateral, (OVER, texts.KEEP)))
                    comp.inner_additions.setdefault(key, []).append(
                        texts.additions(rule, j, ADD_DELTA, into, e.c.lateral))
            elif j not in handled and key in e.minus and not e.idle(i, j):
                comp.seeds.append((("minus", key), e.candidates(i, j)))
            if key not in inside and j not in handled and key in e.plus and not e.idle(i, j):
                comp.additions.append((("plus", key), texts.additions(rule, j, NEW_FACTS, into, e.c.lateral)))
    for key in keys:
        if key in e.sig.removed:
            comp.seeds.append((ALWAYS, texts.copy(key, REMOVED, (OVER, OVER_NEXT))))
        if key in e.sig.added:
            comp.additions.append((ALWAYS, texts.copy(key, ADDED, (ADD_NEXT,))))
        provers = e.writers.get(key, [])
        # a rule only restating a premise reads its premise's asserted facts alone (see :mod:`.restate`)
        comp.confirm[key] = [text for text in (e.recheck(i) for i in provers
                                               if e.restated(i) or not (e.rules[i].reads() & inside)) if text]
        comp.confirm[key].append(texts.over_delete(key, OVER, OVER_NEXT))
        comp.delete[key] = texts.delete(key, OVER, graphs[key])
        into = (graphs[key], NEW_FACTS, ADD_NEXT)
        comp.rederive[key] = [texts.rederive_asserted(e.rules[i], OVER, into) if e.restated(i)
                              else texts.additions(e.rules[i], None, OVER, into, e.c.lateral)
                              for i in provers if not (e.restated(i) and e.rules[i].body[0].aux)]
    e.minus.update(keys)
    e.plus.update(keys)
    return comp


def run_component(run, comp: Component) -> None:
    """Run a component's phases on ``run`` (a :class:`~.program.StagedRun`), reading between rounds."""
    if run.components:  # the first component of a run finds them empty (dropped after every REASON)
        run.queue.append(" ; ".join(f"DROP SILENT GRAPH {g}" for g in COMPONENT_SCRATCH))
    run.components += 1
    for tag, text in comp.seeds:
        if tag[0] == "flip":
            tag, text = tag[1], run.flip_text(tag[2], tag[3], text)
        if text and (tag[0] != "minus" or tag[1] in run.minus):
            run.queue.append(text)
    run.flush()
    with limits.doing("the compiled step's over-deletion in a recursive component"):
        _overdelete(run, comp)
    over = [key for key in comp.keys if run.has(key, OVER)]
    run.queue += [comp.delete[key] for key in over]  # every deletion before any rederivation
    for key in over:
        run.queue += comp.rederive[key]
    run.queue += comp.gained
    for tag, text in comp.additions:
        if tag[0] != "plus" or tag[1] in run.plus:
            run.queue.append(text)
    run.flush()
    while _more(run, comp, ADD_NEXT, comp.inner_additions):  # additions inside the component, semi-naive
        limits.check()
        _next_round(run, comp, ADD_NEXT, ADD_DELTA, comp.inner_additions)
    for key in comp.keys:
        run.note(key)


def _overdelete(run, comp: Component) -> None:
    """Over-delete inside the component, round by round, confirming candidates from outside first."""
    while True:
        limits.check()
        for key in comp.keys:
            if run.has(key, CANDIDATES):
                run.queue += comp.confirm[key]
        run.queue.append(f"DROP SILENT GRAPH {CANDIDATES}")  # decided: the next round's are new ones
        run.flush()
        if not _more(run, comp, OVER_NEXT, comp.inner_candidates):
            break
        _next_round(run, comp, OVER_NEXT, OVER_DELTA, comp.inner_candidates)


def _more(run, comp: Component, found: NamedNode, by_key: dict) -> bool:
    """Whether the last round ``found`` facts of a key some operation of the next round starts from."""
    return run.has_any(found) and any(by_key.get(key) and run.has(key, found) for key in comp.keys)


def _next_round(run, comp: Component, found: NamedNode, delta: NamedNode, by_key: dict) -> None:
    """What the last round ``found`` becomes the ``delta``; the operations of the keys it holds run."""
    run.queue.append(f"DROP SILENT GRAPH {delta} ; MOVE SILENT {found} TO {delta}")
    run.flush()
    for key in comp.keys:
        if run.has(key, delta):
            run.queue += by_key.get(key, [])
    run.flush()


#: rounds of over-deletion and of additions a component gets when the program goes as one request
WHOLE_ROUNDS = 2


def whole_ops(comp: Component, flip_text, rounds: int = WHOLE_ROUNDS) -> list[str]:
    """The component as operations of one request, its rounds unrolled (``rounds`` of each phase).

    Where every request is a round trip, reading between rounds costs more than running a round
    that finds nothing.  Whether the rounds were enough is read afterwards: OVER_NEXT and ADD_NEXT
    are empty then (:data:`UNSETTLED_QUERY`); otherwise the reasoner recomputes in full, once: that
    kind of change takes the general phases from then on.  Two rounds are what a robot step of the
    tutorial map needs (its moves' canReach facts over-deleted, then their classes confirmed).
    """
    ops = [" ; ".join(f"DROP SILENT GRAPH {g}" for g in COMPONENT_SCRATCH)]
    for tag, text in comp.seeds:
        ops.append(flip_text(tag[2], tag[3], text) if tag[0] == "flip" else text)
    ops = [op for op in ops if op]
    for n in range(rounds):
        ops += [op for key in comp.keys for op in comp.confirm[key]]
        ops.append(f"DROP SILENT GRAPH {CANDIDATES}")
        if n < rounds - 1:
            ops.append(f"DROP SILENT GRAPH {OVER_DELTA} ; MOVE SILENT {OVER_NEXT} TO {OVER_DELTA}")
            ops += [op for key in comp.keys for op in comp.inner_candidates.get(key, [])]
    ops += [comp.delete[key] for key in comp.keys]
    ops += [op for key in comp.keys for op in comp.rederive[key]]
    ops += comp.gained + [text for _, text in comp.additions]
    for _ in range(rounds):
        ops.append(f"DROP SILENT GRAPH {ADD_DELTA} ; MOVE SILENT {ADD_NEXT} TO {ADD_DELTA}")
        ops += [op for key in comp.keys for op in comp.inner_additions.get(key, [])]
    # the next component starts by clearing these graphs: say now whether this one had rounds left
    ops.append(f"INSERT {{ GRAPH {UNSETTLED} {{ {UNSETTLED} {UNSETTLED} {UNSETTLED} }} }} WHERE {{ "
               f"{{ GRAPH {OVER_NEXT} {{ ?s ?p ?o }} }} UNION {{ GRAPH {ADD_NEXT} {{ ?s ?p ?o }} }} }}")
    return ops


UNSETTLED_QUERY = f"ASK {{ GRAPH {UNSETTLED} {{ ?s ?p ?o }} }}"

__all__ = ["COMPONENT_SCRATCH", "Component", "UNSETTLED_QUERY", "WHOLE_ROUNDS", "compile_component", "run_component",
           "whole_ops"]
