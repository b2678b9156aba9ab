"""What a full REASON does after its fixpoint, with its reads beside its one write.

After the rules reach their fixpoint a full REASON reads a lot and writes little: the census of which
graphs hold the keys rules and checks read (:func:`.present.key_graphs`), the consistency checks
(:func:`.consistency.check_consistency`), the size of the asserted graph; its one write is the entailed-only
graph (:func:`.entailed.publish_entailed`).  The reads look at the asserted, inferred and helper graphs
alone (so do the counts of the asserted and inferred graphs); the write changes the entailed graph alone.  So on a store that allows it
(:attr:`topostore.stores.base.Store.overlaps`: in memory, the engine releasing the GIL while it
evaluates) the census and the checks run in a worker thread (:class:`topostore.stores.overlap.Beside`)
while this thread publishes and counts; elsewhere (a durable or remote store) they run one after the
other, in the order a sequential REASON takes: census, checks, publication, counts.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..compile.rule import RuleSet
from ..rdf.vocab import ASSERTED, INFERRED
from ..stores.base import Store
from ..stores.overlap import Beside
from .consistency import Violation, check_consistency
from .entailed import publish_entailed
from .present import KeyGraphs


@dataclass(frozen=True)
class Closed:
    """What a full REASON found after its fixpoint."""

    #: the graphs holding facts of each key a rule or check reads
    keys: KeyGraphs
    violations: list[Violation]
    #: quads of the asserted graph
    asserted: int
    #: quads of the inferred graph (what the run derived)
    inferred: int


def close_full(store: Store, rules: RuleSet, census: Callable[[], KeyGraphs]) -> Closed:
    """The census (``census``), the consistency checks and the sizes of the asserted and inferred graphs,
    with the entailed-only graph published; where the store overlaps, the census and the checks in a worker
    thread while this one publishes and counts (two counts are about what the checks cost)."""
    def reads() -> tuple[KeyGraphs, list[Violation]]:
        keys = census()
        return keys, check_consistency(store, rules, keys)

    with Beside(reads, overlap=store.overlaps) as checked:
        publish_entailed(store, rules)
        asserted, inferred = store.count(ASSERTED), store.count(INFERRED)
    keys, violations = checked.result()
    return Closed(keys, violations, asserted, inferred)


__all__ = ["Closed", "close_full"]
