"""Classification: the named superclasses of every named class.

Uses the rules themselves: one prototype individual per class is asserted in a
scratch store and the rules run to their fixpoint; the prototype's types are
the class's superclasses.  This finds what the rules know about restrictions
too (every ``≥2 hasDoor.DOOR`` is a ``∃hasDoor.DOOR``, so CORRIDOR ⊑ ROOM).  The ``known`` facts of named
individuals a class's restrictions link to (a hasValue's value and its classes) are asserted beside
them: ``E ⊑ ∃p.{a}`` with ``a`` a ``K`` is under ``∃p.K``.

SWRL rules and keys are left out: they are DL-safe, binding named individuals only, so
``R(?x) -> K(?x)`` makes every named member of R a K but entails no ``R ⊑ K``
(Pellet's, and so aRMOR's, ``getSubClasses``), while a prototype is a named
individual the rule would bind (a key would merge it with a named individual).

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
from ..rdf.vocab import ASSERTED, INFERRED, NOTHING, PROTOTYPE_PREFIX, SAME_AS, THING, TYPE, is_internal
from ..stores import memory_store
from .consistency import check_consistency
from .materialize import Materializer


def classify(rules: RuleSet, known: Iterable[Triple] = ()) -> dict[NamedNode, set[NamedNode]]:
    """Each named class's named superclasses (itself and owl:Thing left out); ``known``: facts asserted
    beside the prototypes (see the module's docstring).

    The prototypes share one run, so the rules may make two of them the same individual (an inverse
    functional property with a hasValue, a key, a oneOf): each would then take the other's classes and
    violations, where its class has members without the other's; or a check may name two of them together
    (two prototypes that must be one individual but are different).  A class whose prototype was merged with
    another, or named by a check with another, is classified again alone."""
    known = list(known)
    classes = sorted(rules.named_classes, key=lambda c: c.value)
    protos = {c: NamedNode(f"{PROTOTYPE_PREFIX}{i}") for i, c in enumerate(classes)}
    dl_rules = _without_swrl(rules)
    scratch = _run(dl_rules, protos, known)
    named = _violations(scratch, dl_rules, set(protos.values()))
    empty = {p for group in named for p in group}
    tangled = _merged(scratch, set(protos.values())) | {p for group in named if len(group) > 1 for p in group}
    supers: dict[NamedNode, set[NamedNode]] = {}
    for c, p in protos.items():
        if p in tangled:
            alone = _run(dl_rules, {c: p}, known)
            supers[c] = _named_types(alone, p, c)
            unsatisfiable = any(_violations(alone, dl_rules, {p}))
        else:
            supers[c] = _named_types(scratch, p, c)
            unsatisfiable = p in empty
        if unsatisfiable or NOTHING in supers[c]:
            supers[c] = {d for d in classes if d != c} | {NOTHING}
    return supers


class Classification:
    """One classification, made the first time it is read: from compiled rules and the types of the values of
    hasValue restrictions (see :func:`classify`), both held by reference, never a copy of the store; or as it was
    made before, given back whole (a durable store's, ``rules`` None).

    A buffered reasoner answers the classification of its last REASON until the next one: keeping its inputs
    costs a REASON nothing, and a change since (a schema triple, a value's type) makes a new one without touching
    this one."""

    __slots__ = ("rules", "values", "_supers")

    def __init__(self, rules: RuleSet | None, values: frozenset[Triple] = frozenset(),
                 supers: dict[NamedNode, set[NamedNode]] | None = None) -> None:
        if rules is None and supers is None:
            raise ValueError("a classification needs its rules or its superclasses")
        self.rules = rules
        self.values = values
        self._supers = supers

    def of(self, rules: RuleSet, values: frozenset[Triple]) -> bool:
        """Whether it is (or will be) made from these rules and value types."""
        return self.rules is rules and self.values == values

    @property
    def made(self) -> bool:
        """Whether the superclasses were made (reading them costs no classification)."""
        return self._supers is not None

    def superclasses(self) -> dict[NamedNode, set[NamedNode]]:
        """Each named class's named superclasses (:func:`classify`), made on the first read."""
        if self._supers is None:
            assert self.rules is not None
            self._supers = classify(self.rules, self.values)
        return self._supers


def _run(rules: RuleSet, protos: dict[NamedNode, NamedNode], known: list[Triple]):
    """A scratch store holding each prototype as a member of its class, ``known`` beside them, closed under
    ``rules``."""
    scratch = memory_store()
    scratch.use_functions(FUNCTIONS)
    scratch.add([*(Triple(p, TYPE, c) for c, p in protos.items()), *known], ASSERTED)
    Materializer(scratch, rules).run()
    return scratch


def _named_types(scratch, p: NamedNode, c: NamedNode) -> set[NamedNode]:
    """The named classes of prototype ``p`` of ``c`` (``c``, owl:Thing and internal classes left out)."""
    types = {t.object for g in (ASSERTED, INFERRED) for t in scratch.triples(p, TYPE, None, g)}
    return {t for t in types if isinstance(t, NamedNode) and t != c and t != THING and not is_internal(t)}


def _merged(scratch, protos: set[NamedNode]) -> set[NamedNode]:
    """The prototypes the run made the same individual as another prototype."""
    found: set[NamedNode] = set()
    for g in (ASSERTED, INFERRED):
        for t in scratch.triples(None, SAME_AS, None, g):
            if t.subject != t.object and t.subject in protos and t.object in protos:
                found.update((t.subject, t.object))
    return found


def unsatisfiable(supers: dict[NamedNode, set[NamedNode]]) -> list[NamedNode]:
    """The classes :func:`classify` found unsatisfiable, sorted."""
    return sorted((c for c, s in supers.items() if NOTHING in s), key=lambda c: c.value)


def unsatisfiable_text(classes: list[NamedNode]) -> str:
    """What a reader is told of unsatisfiable classes: each is listed under every class."""
    names = ", ".join(c.value.rsplit("#", 1)[-1].rsplit("/", 1)[-1] for c in classes)
    return (f"unsatisfiable class{'es' if len(classes) > 1 else ''} {names}: no individual can be a member, "
            "so each is a subclass of every class (as Pellet classifies it)")


def _without_swrl(rules: RuleSet) -> RuleSet:
    """``rules`` without those that bind named individuals only: the SWRL rules and the keys' (``prp-key``),
    which bind a prototype where Pellet's classification has none (the same set when it has neither)."""
    if not any(_named_only(r.name) for r in rules.rules):
        return rules
    return replace(rules, rules=[r for r in rules.rules if not _named_only(r.name)])


def _named_only(name: str) -> bool:
    """Whether a rule binds named individuals only (DL-safe): a SWRL rule or a key's."""
    return name.startswith("swrl:") or name == "prp-key"


def _violations(scratch, rules: RuleSet, protos: set[NamedNode]) -> list[set[NamedNode]]:
    """The prototypes each check names (checks naming none left out): their classes have no member, where a
    check names one alone."""
    named = ({v for v in violation.individuals.values() if v in protos} for violation in check_consistency(scratch, rules))
    return [group for group in named if group]
