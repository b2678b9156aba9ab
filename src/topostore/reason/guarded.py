"""Classes a writer's body implies through a one-atom rule whose only condition is a non-literal guard.

:func:`.implied_passes.implied_first_passes` lets a rule ``A ⟹ C(v)`` read the asserted facts of ``A`` alone
when every rule writing ``A`` implies ``C`` of the term it writes; "implies" is read off the writer's
body through the one-atom rules :func:`..compile.implied.position_classes` follows, which take no rule
with a condition.  A restriction's rule often has one: ``hasDoor(x, y1) ⟹ ∃hasDoor.DOOR(x)`` left the
guard ``FILTER(!isLiteral(?y1))`` behind when its DOOR atom, implied by hasDoor's range, was dropped
(:mod:`..compile.implied`).  So ``≥2 hasDoor.DOOR ⊑ ∃hasDoor.DOOR`` (ext-card-sub) read every member
of the minimum (50,000 at 100,000 locations, 0.31 s) to conclude what the existential's own rule had
concluded of each from the very hasDoor links the minimum counted.

A writer implies the guarded rule's head of a term when its body holds an atom the guarded rule's
atom maps onto, the term at the head's place, and every guarded variable lands on a term that is no
literal wherever the writer matches: an IRI, the subject of one of the writer's atoms (a subject is
never a literal), or a variable the writer guards the same way.  The guarded rules must read a key
no ordered rule writes (the *base* of :func:`.implied_passes.implied_first_passes`): their own evaluation
reads every fact of it, so the argument never rests on a restricted rule.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from ..compile.condition import TEST, Condition
from ..compile.rule import Atom, Rule
from ..rdf.vocab import TYPE

_TYPE = str(TYPE)
#: the one condition a guarded rule may hold, on a variable of its atom
_GUARD = re.compile(r"\s*!\s*isLiteral\(\s*(\?\w+)\s*\)\s*")


@dataclass(frozen=True)
class Guarded:
    """``atom ∧ ⋀ !isLiteral(v) for v in guarded ⟹ head`` (a class head on a variable of ``atom``)."""

    atom: Atom
    head: Atom
    guarded: frozenset[str]


def guarded_rules(base: Iterable[Rule]) -> list[Guarded]:
    """The rules of ``base`` of one atom of a named predicate, concluding a named class of one of its
    variables, whose conditions are all ``!isLiteral`` guards of the atom's variables."""
    out: list[Guarded] = []
    for rule in base:
        if (rule.is_check or len(rule.body) != 1 or not rule.conditions or rule.stratum
                or rule.unless_known is not None):
            continue
        (atom,), head = rule.body, rule.head
        if (head.p != _TYPE or head.o.startswith("?") or not head.s.startswith("?")
                or atom.p.startswith("?") or head.s not in (atom.s, atom.o)):
            continue
        guarded = [_guarded_variable(c) for c in rule.conditions]
        if all(v is not None and v in atom.variables() for v in guarded):
            out.append(Guarded(atom, head, frozenset(guarded)))
    return out


def guarded_classes(term: str, writer: Rule, rules: list[Guarded], implied: Mapping) -> set[str]:
    """The classes ``term`` belongs to in the closure wherever ``writer``'s body and conditions match,
    through the guarded ``rules`` (and what ``implied``, :func:`..compile.implied.position_classes`,
    says of their classes)."""
    out: set[str] = set()
    if not rules:
        return out
    safe = {a.s for a in writer.body} | {v for v in map(_guarded_variable, writer.conditions) if v is not None}
    for rule in rules:
        for atom in writer.body:
            found = _mapping(rule.atom, atom)
            if found is None or found.get(rule.head.s) != term:
                continue
            if all(found[v] in safe or found[v].startswith("<") for v in rule.guarded):
                out.add(rule.head.o)
                out |= implied.get(("t", rule.head.o), frozenset())
    return out


def _guarded_variable(condition: Condition) -> str | None:
    """The variable a plain ``FILTER(!isLiteral(?v))`` guards, None for any other condition."""
    if condition.kind != TEST or condition.negated or condition.reads_graph:
        return None
    match = _GUARD.fullmatch(condition.expression)
    return match.group(1) if match else None


def _mapping(pattern: Atom, atom: Atom) -> dict[str, str] | None:
    """The terms of ``atom`` at the variables of ``pattern`` where ``pattern`` maps onto it (same
    predicate and graph, constants equal, a variable twice on one term), else None."""
    if pattern.p != atom.p or pattern.aux != atom.aux:
        return None
    found: dict[str, str] = {}
    for mine, theirs in ((pattern.s, atom.s), (pattern.o, atom.o)):
        if not mine.startswith("?"):
            if mine != theirs:
                return None
        elif found.setdefault(mine, theirs) != theirs:
            return None
    return found


__all__ = ["Guarded", "guarded_classes", "guarded_rules"]
