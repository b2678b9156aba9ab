"""Asks left out where their answer cannot be published: candidates "unless known".

Why
---
A SWRL rule with a DifferentIndividuals atom ``x ≠ y`` has an entailed-only twin, concluded where
the pair is different by values alone (:mod:`..compile.inline_difference`).  Its pairs are asked of
the value rules as ``ts:valueCandidate``; but the twin of a pair is published only where the rule's
ordinary head ``H(x, y)`` is neither asserted nor inferred (:mod:`.entailed`).  On a map where every
pair is declared different the ask, the value difference and the twin are written for every pair and
never published: most of a full REASON's difference work.

A monotone rule cannot leave those pairs out.  Let ``f`` be the pairs asked, from the facts, and
``f`` monotone (as every positive rule set is); it must ask every body pair not declared different.
Take the facts without any declaration: every body pair must be asked.  Add the declarations (the
body does not read them): by monotonicity every body pair is still asked.  So any form that asks
nothing for declared pairs reads something negatively, and the robot step must keep it.

What is done instead: a candidate rule may carry ``unless_known = H`` (set by the compiler only when
``H``'s subject and object are the asked pair).  Its facts are then kept as a *superset* of the body
pairs whose ``H`` is not known:

* a full REASON evaluates such a rule last, once the fixpoint is reached, as ``body MINUS { H }``
  (:func:`unless_known_text`), and propagates what it adds (the value rules, the twins); where a census
  of the AllDifferent keys shows every body pair's ``H`` known, it is left out (:mod:`.keyed_asks`);
* incremental maintenance evaluates the rule as written (a superset: a twin whose head is known is
  never published), so the robot step's compiled program is the same as before;
* only a lost ``H(x, y)`` whose body still holds needs a pair asked that was left out.  ``H`` is
  lost with its body kept only when a fact the body does not read is lost: a declaration the
  conclusion joins (an AllDifferent key, ``owl:differentFrom``, a type of a disjoint class), a
  premise of another rule concluding ``H``, or an asserted ``H``.  Those are the completion
  keys (:class:`Completion`); a maintenance that lost one asks the pairs again (:func:`completion_text`: the body less the
  known heads and the pairs already asked), and propagates them as new facts.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from typing import NamedTuple

from pyoxigraph import NamedNode

from ..compile.rule import ReadKey, Rule
from ..rdf.vocab import ASSERTED, AUX, INFERRED, INTERNAL
from .restate import covering
from .triggers import matches, may_write

#: the pairs a maintenance asks again, the first delta of the propagation that follows
ASKED = NamedNode(INTERNAL + "graph:inc-asked")


def deferred(rules: Sequence[Rule]) -> set[int]:
    """The indices of the candidate rules a full REASON evaluates last, without known conclusions."""
    return {i for i, r in enumerate(rules) if r.unless_known is not None and r.head is not None}


class Idle(NamedTuple):
    """A candidate rule's idle asks (:func:`idle_asks`): the key it is covered at, whose asserted facts
    alone it reads, and the rules of a variable predicate that may write that key too (while one of
    them can fire, the asks are not idle)."""

    key: ReadKey
    others: tuple[int, ...]


def idle_asks(rules: Sequence[Rule], covered: Mapping[int, ReadKey]) -> dict[int, Idle]:
    """Candidate rules that ask nothing a twin could be published for, while the key they are covered at
    (:func:`.restate.covering`, by rule) has no asserted fact: by rule, that key.

    Reachability asks about ``l1 ≠ l2`` for every ``connectedTo(l1, l2)`` of the robot's place; the
    covering argument says Connectability's candidate asked the same pair.  A deferred candidate no
    longer does where ``connectedTo(l1, l2)`` is known; but when every rule deriving that key is a
    conclusion of the deferred rule's own SWRL rule (its head, joined with a declaration of the pair),
    each derived ``connectedTo(l1, l2)`` is a declared pair, so Reachability's own conclusion holds for
    every match and its twin is never published: its asks may be left out as the step leaves them out.
    A rule of a variable predicate (owl:sameAs replacement, a generic subproperty rule) may write the key
    too: it is named in the result, and the asks are idle only while it cannot fire."""
    owners = [rules[i] for i in deferred(rules)]
    out: dict[int, Idle] = {}
    for i, key in covered.items():
        rule = rules[i]
        atom = next((a for a in rule.body if a.read_key() == key), None)
        if atom is None or rule.head is None or (rule.head.s, rule.head.o) != (atom.s, atom.o):
            continue
        owner = next((d for d in owners if d.unless_known.read_key() == key), None)
        writers = [n for n, w in enumerate(rules) if w.head is not None and may_write(w.writes(), key)]
        exact = [rules[n] for n in writers if rules[n].writes() == key]
        if owner is not None and exact and all(
                w.name == owner.name and w.head == owner.unless_known and w.reads() > owner.reads()
                for w in exact):
            out[i] = Idle(key, tuple(n for n in writers if rules[n].writes() != key))
    return out


def evaluated_last(rules: Sequence[Rule]) -> tuple[set[int], dict[int, Idle]]:
    """The candidate rules a full REASON leaves out of its first stratum's fixpoint and runs after it:
    those asking unless a conclusion is known (:func:`deferred`), and those asking nothing a twin could
    be published for on derived facts of the key they are covered at, by rule, that key
    (:func:`idle_asks`: run on its asserted facts alone)."""
    later = deferred(rules)
    if not later:
        return later, {}
    asking = [i for i, r in enumerate(rules) if r.head is not None and r.head_aux() and i not in later]
    return later, idle_asks(rules, covering(list(rules), asking))


def unless_known_text(text: str, rule: Rule) -> str:
    """An evaluation text of ``rule`` (an ``INSERT … WHERE { … }`` over the default dataset: asserted,
    inferred and helper facts) that leaves out the matches whose ordinary conclusion
    ``rule.unless_known`` is known."""
    where_end = text.rstrip().rfind("}")
    return f"{text[:where_end]}  MINUS {{ {rule.unless_known.text()} }}\n}}"


class Completion:
    """When a maintenance must ask again the pairs a full REASON left out (see the module docstring).

    For each deferred rule with body keys ``B`` and known head key ``h``, the rules concluding ``h``:
    a conclusion of the same body (one reading all of ``B``) may lose ``h`` with its body kept when a
    fact it reads besides ``B`` is lost (a declaration); any other writer of ``h`` when any fact it
    reads is lost; and a removed asserted ``h``.  A writer counts only while every key it reads has
    facts (:attr:`..incremental.MaintenanceState.present`, a superset): one that cannot have matched
    cannot have concluded anything (``eq-rep-s`` without any ``owl:sameAs``)."""

    def __init__(self, rules: Sequence[Rule]) -> None:
        #: (keys that must have facts, keys whose loss matters) per writer of a deferred rule's head
        self.writers: list[tuple[frozenset[ReadKey], frozenset[ReadKey]]] = []
        #: the known heads' keys (their asserted facts' removal matters)
        self.heads: set[ReadKey] = set()
        #: what :meth:`_watched` decided, for the keys with facts it was asked with (and their sizes)
        self._present: tuple | None = None
        self._mark: tuple[int, int] = (0, 0)
        self._keys: tuple[bool, frozenset, frozenset] = (False, frozenset(), frozenset())
        for i in deferred(rules):
            rule = rules[i]
            head_key = rule.unless_known.read_key()
            self.heads.add(head_key)
            body = frozenset(a.read_key() for a in rule.body)
            for other in rules:
                if other is rule or other.head is None or not may_write(other.writes(), head_key):
                    continue
                needs = frozenset(k for k in other.reads() if k[0] != "*")
                self.writers.append((needs, other.reads() - body if body <= other.reads() else other.reads()))

    def needed(self, present: tuple[Collection[str], Collection[str]], lost: tuple[Collection[str], Collection[str]],
               asserted: bool = False) -> bool:
        """Whether losing facts of ``lost`` (predicates, classes) may leave a pair unasked; ``asserted``:
        the loss is of asserted facts (a removed asserted head counts too)."""
        if asserted and lost_any(self.heads, *lost):
            return True
        any_key, preds, classes = self._watched(present)
        lost_preds, lost_classes = lost
        return (any_key and bool(lost_preds)) or not preds.isdisjoint(lost_preds) \
            or not classes.isdisjoint(lost_classes)

    def _watched(self, present: tuple[Collection[str], Collection[str]]) -> tuple[bool, frozenset, frozenset]:
        """The keys whose loss matters while ``present`` holds the keys with facts (the writers whose
        every needed key has facts): whether any key does, the predicates, the classes.  ``present``
        only grows between a reasoner's full runs and general phases (which call :meth:`forget`), so
        its sizes tell it: a robot step asks twice per REASON and the answer is made once."""
        mark = (len(present[0]), len(present[1]))
        if present is self._present and mark == self._mark:
            return self._keys
        keys = {k for needs, watched in self.writers if all(matches(n, *present) for n in needs) for k in watched}
        self._keys = (any(k[0] == "*" for k in keys), frozenset(k[1] for k in keys if k[0] == "p"),
                      frozenset(k[1] for k in keys if k[0] == "t"))
        self._present, self._mark = present, mark
        return self._keys

    def forget(self) -> None:
        """The keys with facts may have shrunk (a full run, or the general phases): decide afresh."""
        self._present = None


def lost_any(keys: Collection[ReadKey], preds: Collection[str], classes: Collection[str]) -> bool:
    """Whether a loss of facts of ``preds``/``classes`` touches one of ``keys``."""
    return any(matches(k, preds, classes) for k in keys)


def completion_text(rule: Rule, seed: NamedNode) -> str:
    """The update asking again the pairs of deferred ``rule`` whose conclusion is not known and that
    are not asked yet, into the helper graph and ``seed`` (the next propagation's first delta)."""
    head = rule.head.text()
    return (f"INSERT {{ GRAPH {AUX} {{ {head} }} GRAPH {seed} {{ {head} }} }}\n"
            f"USING {ASSERTED} USING {INFERRED} USING {AUX} USING NAMED {AUX}\n"
            f"WHERE {{\n  {rule.where()}\n  MINUS {{ GRAPH {AUX} {{ {head} }} }}\n"
            f"  MINUS {{ {rule.unless_known.text()} }}\n}}")


__all__ = ["ASKED", "Completion", "Idle", "evaluated_last", "idle_asks", "completion_text", "deferred", "lost_any", "unless_known_text"]
