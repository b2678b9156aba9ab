"""Classification: the named superclasses of every named class.

Uses the rules themselves: one prototype individual per class is asserted in a
scratch store and the rules run to their fixpoint; the prototype's types are
the class's superclasses.  This finds what the rules know about restrictions
too (every ``≥2 hasDoor.DOOR`` is a ``∃hasDoor.DOOR``, so CORRIDOR ⊑ ROOM).  The ``known`` facts of named
individuals a class's restrictions link to (a hasValue's value and its classes) are asserted beside
them: ``E ⊑ ∃p.{a}`` with ``a`` a ``K`` is under ``∃p.K``.
"""

from __future__ import annotations

from collections.abc import Iterable

from pyoxigraph import NamedNode, Triple

from ..compile.builtins import FUNCTIONS
from ..compile.rule import RuleSet
from ..rdf.vocab import ASSERTED, INFERRED, PROTOTYPE_PREFIX, THING, TYPE, is_internal
from ..stores import memory_store
from .materialize import Materializer


def classify(rules: RuleSet, known: Iterable[Triple] = ()) -> dict[NamedNode, set[NamedNode]]:
    scratch = memory_store()
    scratch.use_functions(FUNCTIONS)
    classes = sorted(rules.named_classes, key=lambda c: c.value)
    protos = {c: NamedNode(f"{PROTOTYPE_PREFIX}{i}") for i, c in enumerate(classes)}
    scratch.add([*(Triple(p, TYPE, c) for c, p in protos.items()), *known], ASSERTED)
    Materializer(scratch, rules).run()
    supers: dict[NamedNode, set[NamedNode]] = {}
    for c, p in protos.items():
        types = {t.object for g in (ASSERTED, INFERRED) for t in scratch.triples(p, TYPE, None, g)}
        supers[c] = {t for t in types if isinstance(t, NamedNode) and t != c and t != THING and not is_internal(t)}
    return supers
