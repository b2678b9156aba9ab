"""Classification: the named superclasses of every named class.

Uses the rules themselves: one prototype individual per class is asserted in a
scratch store and the rules run to their fixpoint; the prototype's types are
the class's superclasses.  This finds what the rules know about restrictions
too (every ``≥2 hasDoor.DOOR`` is a ``∃hasDoor.DOOR``, so CORRIDOR ⊑ ROOM).  The ``known`` facts of named
individuals a class's restrictions link to (a hasValue's value and its classes) are asserted beside
them: ``E ⊑ ∃p.{a}`` with ``a`` a ``K`` is under ``∃p.K``.

SWRL rules are left out: they are DL-safe, binding named individuals only, so
``R(?x) -> K(?x)`` makes every named member of R a K but entails no ``R ⊑ K``
(Pellet's, and so aRMOR's, ``getSubClasses``), while a prototype is a named
individual the rule would bind.

A class whose prototype violates a check (a member of owl:Nothing, of two
disjoint classes, …) is unsatisfiable: it is under every class, as Pellet
classifies it, and its superclasses hold owl:Nothing so that a reader can name it
(:func:`unsatisfiable`).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import replace

from pyoxigraph import NamedNode, Triple

from ..compile.builtins import FUNCTIONS
from ..compile.rule import RuleSet
from ..rdf.vocab import ASSERTED, INFERRED, NOTHING, PROTOTYPE_PREFIX, THING, TYPE, is_internal
from ..stores import memory_store
from .consistency import check_consistency
from .materialize import Materializer


def classify(rules: RuleSet, known: Iterable[Triple] = ()) -> dict[NamedNode, set[NamedNode]]:
    """Each named class's named superclasses (itself and owl:Thing left out); ``known``: facts asserted
    beside the prototypes (see the module's docstring)."""
    scratch = memory_store()
    scratch.use_functions(FUNCTIONS)
    classes = sorted(rules.named_classes, key=lambda c: c.value)
    protos = {c: NamedNode(f"{PROTOTYPE_PREFIX}{i}") for i, c in enumerate(classes)}
    scratch.add([*(Triple(p, TYPE, c) for c, p in protos.items()), *known], ASSERTED)
    dl_rules = _without_swrl(rules)
    Materializer(scratch, dl_rules).run()
    supers: dict[NamedNode, set[NamedNode]] = {}
    for c, p in protos.items():
        types = {t.object for g in (ASSERTED, INFERRED) for t in scratch.triples(p, TYPE, None, g)}
        supers[c] = {t for t in types if isinstance(t, NamedNode) and t != c and t != THING and not is_internal(t)}
    empty = _violating(scratch, dl_rules, set(protos.values()))
    for c, p in protos.items():
        if p in empty or NOTHING in supers[c]:
            supers[c] = {d for d in classes if d != c} | {NOTHING}
    return supers


def unsatisfiable(supers: dict[NamedNode, set[NamedNode]]) -> list[NamedNode]:
    """The classes :func:`classify` found unsatisfiable, sorted."""
    return sorted((c for c, s in supers.items() if NOTHING in s), key=lambda c: c.value)


def unsatisfiable_text(classes: list[NamedNode]) -> str:
    """What a reader is told of unsatisfiable classes: each is listed under every class."""
    names = ", ".join(c.value.rsplit("#", 1)[-1].rsplit("/", 1)[-1] for c in classes)
    return (f"unsatisfiable class{'es' if len(classes) > 1 else ''} {names}: no individual can be a member, "
            "so each is a subclass of every class (as Pellet classifies it)")


def _without_swrl(rules: RuleSet) -> RuleSet:
    """``rules`` without the SWRL rules (the same set when it has none)."""
    if not any(r.name.startswith("swrl:") for r in rules.rules):
        return rules
    return replace(rules, rules=[r for r in rules.rules if not r.name.startswith("swrl:")])


def _violating(scratch, rules: RuleSet, protos: set[NamedNode]) -> set[NamedNode]:
    """The prototypes a check names: their classes have no member."""
    return {v for violation in check_consistency(scratch, rules) for v in violation.individuals.values()
            if v in protos}
