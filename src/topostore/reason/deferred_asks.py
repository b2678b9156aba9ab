"""The deferred asks of a full run: the candidate rules evaluated after the first stratum's fixpoint.

Rules with a negated premise ("not known to be different") ask only once every fact they could
ask about is derived (:mod:`.negation`), unless a census of the AllDifferent keys shows them empty
(:mod:`.keyed_asks`); they read the keys whose facts are all asserted in the
asserted graph alone, and what they derive then runs its own semi-naive rounds.
"""

from __future__ import annotations

from collections.abc import Collection
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode

from ..compile.rule import ReadKey, Rule, key_pattern
from ..rdf.vocab import ASSERTED
from .insert_text import insert_text
from .keyed_asks import covered
from .negation import unless_known_text
from .order import TYPE_KEY
from .stats import ReasonStats
from .triggers import Present, matches

if TYPE_CHECKING:
    from .materialize import Materializer


def ask_unknown(run: Materializer, stats: ReasonStats, active: list[int]) -> None:
    """After the first stratum's fixpoint: the deferred candidate rules without the pairs whose
    conclusion is known (:mod:`.negation`), then the rounds their facts trigger among ``active``."""
    rules, run._deferring = sorted(run._deferring), set()
    # written by the asks queued before a later one reads them
    asking = {w for i in rules if (w := run.rules[i].writes()) is not None}
    for i in rules:
        if not run.triggers.feasible(i, run.present):
            continue
        idle = run._idle.get(i)
        if idle is not None and any(run.triggers.feasible(w, run.present) for w in idle.others):
            idle = None  # a rule of a variable predicate may have written the key
        key = idle.key if idle is not None else None
        early = run._early.answer(i) if key is None and run._early is not None else None
        if early is False:
            continue  # asked early, beside the later components' writes: no match (:mod:`.early_reads`)
        graphs = only_asserted(run.rules[i], run._derived, run._asserted, asking) if key is None else {}
        census = run.censuses.get(i)
        taken = census is not None and run._early is not None and run._early.covered(census, graphs)
        if key is None and early is None and covered(run.store, census, run._queued, graphs, taken):
            continue  # every body pair's conclusion is known by the AllDifferent keys (:mod:`.keyed_asks`)
        if key is None:
            text = insert_text(run.rules[i], None, run.planned, run._lateral, run._direct, graphs, bare=run.bare(i))
            if run.rules[i].unless_known is not None:
                text = unless_known_text(text, run.rules[i])
        elif next(iter(run.store.triples(*key_pattern(key), ASSERTED)), None) is not None:
            # its asks on derived facts of the key are idle: the asserted ones alone
            text = insert_text(run.rules[i], None, run.planned, run._lateral, run._direct, {key: ASSERTED},
                               bare=run.bare(i))
        else:
            continue
        stats.evaluations += 1
        run._queued.add(run.rules[i].writes())
        if run._early is not None:
            run._early.wrote(run.rules[i].writes())
        run._timed(text, run.rules[i].name, stats)
    if rules:
        run._flush()
        stats.rounds += 1
        run.propagate(active, stats)


def only_asserted(rule: Rule, derived: Collection[ReadKey], asserted: Present,
                  asking: Collection[ReadKey] = ()) -> dict[ReadKey, NamedNode]:
    """The read keys of ``rule``'s body whose facts are all asserted so far in a full run: read
    there alone (one index look-up per pattern instead of one per graph of the default dataset).

    A key had asserted facts at the start (``asserted``) and no rule of this run wrote it
    (``derived`` holds every key written: the first passes add theirs, every round its delta's).
    A rule of a variable predicate may have written any key, one of a variable class any class:
    then the keys they may cover stay on the default dataset.  The deferred ask of Connectability's
    candidate reads its 20,000 door facts so: 65 → 54 ms at 10,000 locations.  ``asking``: the
    keys the deferred asks write, which a later one of them may read before they reach a delta.
    """
    written = set(derived) | set(asking)
    if any(k[0] == "*" for k in written):
        return {}
    any_class = ("p", TYPE_KEY) in written or any(k[0] == "t" for k in asking)
    out: dict[ReadKey, NamedNode] = {}
    for atom in rule.body:
        key = atom.read_key()
        if atom.aux or key[0] not in ("p", "t") or key == ("p", TYPE_KEY) or key in written:
            continue
        if (key[0] == "t" and any_class) or not matches(key, *asserted):
            continue
        out[key] = ASSERTED
    return out
