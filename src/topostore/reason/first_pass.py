"""The first pass of a full run's ordered stratum and its shortcuts.

Each component of the rule dependency graph is evaluated once, rule by rule, in one request, before
its semi-naive rounds.  Its shortcuts: a rule whose every read fact is asserted reads the asserted
graph alone (:func:`.implied_passes.implied_first_passes`), a rule leaves out the class atoms another atom
implies (:func:`.implied_passes.implied_atoms`, as the rule :func:`without` gives), rules concluding one
class run as one (:mod:`.class_unions`), and a key only claimed by an earlier rule of the pass is
looked up before its readers run (:func:`claims_hold`).
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from ..compile.rule import Rule, key_pattern
from ..rdf.vocab import ASSERTED, AUX, INFERRED
from .class_unions import lead_first
from .order import TYPE_KEY
from .stats import ReasonStats

if TYPE_CHECKING:
    from .materialize import Materializer


def first_pass(run: Materializer, component: list[int], back: set[int], stats: ReasonStats) -> None:
    """Evaluate a component's rules once each, in order, in one request.

    Operations of one request see what the earlier ones wrote, so a rule's facts are already
    read by every later rule of the pass: they go to the next delta only for a rule in
    ``back`` (a rule of the pass at or before it reads them) or with a head of any class or
    predicate.  The key a rule without delta writes joins ``run.present`` at once (a
    superset, as it must be), so later rules of the pass are not skipped for want of it.
    """
    read = run._direct
    for i in component:
        if i in run._joined:
            continue  # evaluated with the first rule of its class union
        members = [m for m in (i, *run._unions.get(i, ()))
                   if run.triggers.feasible(m, run.present) and claims_hold(run, m)]
        if not members:
            continue
        i, *union = lead_first(run.rules, members)
        union = tuple(union)
        asserted_only = i in run._implied
        if asserted_only and not run._has_asserted(run.rules[i].body[0].read_key()):
            continue  # every fact it reads is derived, and what it concludes of them holds already
        key = run.rules[i].writes()
        if i in back or key[0] == "*" or key == ("p", TYPE_KEY):
            run._run(i, None, stats, asserted_only, first=True)
            run._derived.add(key)
            continue
        run._direct = (read[0], None)
        try:
            run._run(i, None, stats, asserted_only, first=True, union=union)
        finally:
            run._direct = read
        run._derived.add(key)
        if key[1] not in run.present[1 if key[0] == "t" else 0]:
            run._claimed.add(key)
        run.present[1 if key[0] == "t" else 0].add(key[1])
        if key[0] == "t":
            run.present[0].add(TYPE_KEY)
    run._flush()
    stats.rounds += 1


def claims_hold(run: Materializer, i: int) -> bool:
    """Whether rule ``i`` can still match once the keys it reads that earlier rules of the pass only
    claimed (``run._claimed``: put in ``run.present`` before their evaluation ran) are looked up.

    A claim is a superset, as ``present`` must be; but a rule that wrote nothing leaves its
    readers to scan for nothing (the six disjoint-classes rules over 10,000 doors and locations,
    asking about pairs no rule asked about).  The queued evaluations are sent first, so that the
    look-up sees what they wrote: one request more per pass that needs it.
    """
    keys = {a.read_key() for a in run.rules[i].body} & run._claimed
    if not keys:
        return True
    run._flush()
    for key in keys:
        run._claimed.discard(key)
        pattern = key_pattern(key)
        if not any(next(iter(run.store.triples(*pattern, g)), None) is not None for g in (INFERRED, AUX, ASSERTED)):
            run.present[1 if key[0] == "t" else 0].discard(key[1])
    return run.triggers.feasible(i, run.present)


def without(rule: Rule, atoms: tuple[int, ...]) -> Rule:
    """``rule`` with the body atoms ``atoms`` left out (the body as written kept for explanations)."""
    return replace(rule, body=tuple(a for n, a in enumerate(rule.body) if n not in atoms), written=rule.premises)
