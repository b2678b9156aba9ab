"""Publishing the conclusions drawn with entailed-only difference.

A SWRL rule whose DifferentIndividuals atom holds only by entailment (the two
individuals are not declared different, but equating them would be
inconsistent) still has an entailed conclusion, which Pellet reports; Pellet
finds it by refutation and never uses it to fire other rules.  The compiler
derives such conclusions in the helper graph under an internal predicate (so no
rule reads them); this step copies them, under their real predicate, into the
ENTAILED graph that queries see.  It runs after every REASON and costs one
index look-up per such conclusion.
"""

from __future__ import annotations

from pyoxigraph import NamedNode, Triple

from ..compile.rule import RuleSet
from ..store import Store
from ..vocab import ASSERTED, AUX, ENTAILED, ENTAILED_PREFIX, INFERRED


def publish_entailed(store: Store, rules: RuleSet) -> None:
    """Make ENTAILED hold exactly the entailed-only conclusions that are neither inferred nor asserted.

    Read from the indexes and changed by difference, so the cost follows the
    number of such conclusions (usually none), not the size of the map: a
    DROP and a re-INSERT with NOT EXISTS would join against every inferred
    fact of the predicate on every REASON.
    """
    wanted: set[Triple] = set()
    for p in rules.entailed_predicates:
        internal = NamedNode(ENTAILED_PREFIX + p.value)
        for t in store.triples(None, internal, None, AUX):
            conclusion = Triple(t.subject, p, t.object)
            if not store.contains(conclusion, INFERRED) and not store.contains(conclusion, ASSERTED):
                wanted.add(conclusion)
    present = set(store.triples(graph=ENTAILED))
    if present - wanted:
        store.discard(present - wanted, (ENTAILED,))
    if wanted - present:
        store.add_scratch(wanted - present, ENTAILED)
