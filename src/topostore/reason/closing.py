"""What a full REASON does after its fixpoint, with its reads beside its one write.

After the rules reach their fixpoint a full REASON reads a lot and writes little: the census of which
graphs hold the keys rules and checks read (:func:`.present.key_graphs`), the consistency checks
(:func:`.consistency.check_consistency`), the size of the inferred graph; its one write is the entailed-only
graph (:func:`.entailed.publish_entailed`).  The reads look at the asserted, inferred and helper graphs
alone; the write changes the entailed graph alone.  The asserted graph's size, which no REASON changes, is
counted beside the rules themselves (:func:`counting_asserted`).  So on a store that allows it
(:attr:`topostore.stores.base.Store.overlaps`: in memory, the engine releasing the GIL while it
evaluates) the census and the checks run in a worker thread (:class:`topostore.stores.overlap.Beside`)
while this thread publishes and counts; elsewhere (a durable or remote store) they run one after the
other, in the order a sequential REASON takes: census, checks, publication, counts.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
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


def counting_asserted(store: Store) -> Beside[int]:
    """The asserted graph's size, counted in a worker thread while the block runs a full REASON's rules
    (which write the reasoner's graphs, never the asserted one: 0.45 s of SPARQL count at 100,000
    locations taken off the run's wall time); counted on entering the block where the store does not
    overlap."""
    return Beside(lambda: store.count(ASSERTED), overlap=store.overlaps)


def close_full(store: Store, rules: RuleSet, census: Callable[[], KeyGraphs], asserted: int,
               checked: Mapping[int, list[dict]] | None = None) -> Closed:
    """The census (``census``), the consistency checks and the inferred graph's size, with the entailed-only
    graph published; where the store overlaps, the census and the checks in a worker thread while this one
    publishes and counts.  ``asserted``: the asserted graph's size (:func:`counting_asserted`); ``checked``:
    the matches of the checks run beside the fixpoint already (:mod:`.early_reads`), by index."""
    def reads() -> tuple[KeyGraphs, list[Violation]]:
        keys = census()
        return keys, check_consistency(store, rules, keys, checked)

    with Beside(reads, overlap=store.overlaps) as reading:
        publish_entailed(store, rules)
        inferred = store.count(INFERRED)
    keys, violations = reading.result()
    return Closed(keys, violations, asserted, inferred)


__all__ = ["Closed", "close_full", "counting_asserted"]
