"""The passes of a full run (:meth:`.materialize.Materializer.run`): what is set up before them and their order.

A full run first looks up which needed keys have asserted facts, then prepares what its ordered
first stratum reads (the rules that cannot fire left out, the components in dependency order, the
implied and lean first passes, the one graph of a key, the class unions, the asserted paths), and
runs the components one by one (:func:`.first_pass.first_pass` and their semi-naive rounds), then
the rest and the upper strata.  The rounds themselves, the queue of one request and the promotion
of a delta stay in :mod:`.materialize`: this module is the order, that one the core loop.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..compile.rule import key_pattern
from ..rdf.vocab import ASSERTED, AUX, INFERRED
from .class_unions import class_unions
from .deferred_asks import ask_unknown
from .early_reads import EarlyReads
from .first_pass import first_pass, without
from .implied_passes import implied_atoms, implied_first_passes
from .insert_text import distinct_pays
from .order import asserted_paths, evaluation_order, reachable, single_graphs
from .stats import ReasonStats
from .triggers import Present

if TYPE_CHECKING:
    from .materialize import Materializer


def asserted_keys(run: Materializer) -> Present:
    """The predicates and classes rule bodies need that have an asserted fact (one look-up each)."""
    preds: set[str] = set()
    classes: set[str] = set()
    for kind, key in run.triggers.needed_keys():
        if next(iter(run.store.triples(*key_pattern((kind, key)), ASSERTED)), None) is not None:
            (classes if kind == "t" else preds).add(key)
    return preds, classes


def full_passes(run: Materializer, stats: ReasonStats) -> None:
    """The passes of a full run: components in order, then the rest and the upper strata."""
    # keys with facts so far; each round's delta adds its keys (_delta_round), so a rule
    # skipped here for an empty key runs as soon as that key gets a fact, with it as the delta
    run.present = asserted_keys(run)
    run._asserted_heads = {}
    rules = run.rules
    strata = sorted({r.stratum for r in rules}) or [0]
    first = [i for i, r in enumerate(rules) if r.stratum == strata[0]]
    # rules that cannot fire in the first stratum stay out of its order: left in, one such rule
    # (eq-rep-s without any owl:sameAs) ties every class reader and writer into one component
    # whose rules are then evaluated round after round; a key they need that an upper stratum
    # derives triggers them on its delta, which finds all they derive
    possible = reachable(run.triggers, first, run.present)
    first = [i for i in first if run.triggers.feasible(i, possible)]
    ordered, rest, back = evaluation_order(rules, first)
    flat = [i for c in ordered for i in c]
    # until the rules of a variable predicate and the upper strata run, only the ordered rules
    # write, so a key's facts lie where its asserted facts and its writers put them
    asserted = run._asserted = (set(run.present[0]), set(run.present[1]))
    run._claimed = set()
    run._implied = implied_first_passes(rules, flat, asserted)
    run._lean = {i: without(rules[i], atoms) for i, atoms in implied_atoms(rules, flat, asserted).items()}
    run._graphs = single_graphs(rules, flat, run.triggers.needed_keys(), asserted,
                                lambda r: AUX if r.head_aux() else INFERRED, ASSERTED)
    run._unions = class_unions(rules, ordered, back, run._graphs, ASSERTED, distinct_pays,
                               run._implied | set(run._lean) | run._deferring)
    run._joined = {j for others in run._unions.values() for j in others}
    run._paths = asserted_paths(rules, flat)
    # a text reading a key in one graph holds only for this run's asserted keys: none is kept from before
    run._texts = {k: t for k, t in run._texts.items() if not k[4]}
    run._early = early = EarlyReads(run, ordered, rest, run.checks, back)
    completed = False
    try:
        _fixpoint(run, stats, strata, ordered, rest, back)
        completed = True
    finally:
        run._early = None
        early.close(completed)
    run.checked = early.checked


def _fixpoint(run: Materializer, stats: ReasonStats, strata: list[int], ordered: list[list[int]], rest: list[int],
              back: set[int]) -> None:
    """The ordered components, then the rest and the upper strata (see :meth:`.Materializer.run`); each
    deferred ask and check started in the reader thread once the components writing what it reads are
    done (:mod:`.early_reads`)."""
    run._early.after(-1)
    try:
        for c, component in enumerate(ordered):
            first_pass(run, component, back, stats)
            run.propagate(component, stats)
            run._early.after(c)
    finally:
        run._graphs = None
        run._unions, run._joined, run._paths = {}, set(), set()
    for level in strata:
        active = [i for i, r in enumerate(run.rules) if r.stratum <= level]
        fresh = rest if level == strata[0] else [i for i in active if run.rules[i].stratum == level]
        for i in fresh:
            if run.triggers.feasible(i, run.present):
                run._run(i, None, stats)
        run._flush()
        stats.rounds += 1
        if level > strata[0] and not run.store.is_empty(run._direct[1]):
            run.upper_derived = True
        run.propagate(active, stats)
        if level == strata[0]:  # before the upper strata, which may read what the asks derive
            ask_unknown(run, stats, active)
