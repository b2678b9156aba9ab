"""A SWRL rule's difference tested where it is asked, not materialised pair by pair.

Why
---
A SWRL rule with one DifferentIndividuals atom ``x ≠ y`` used to go through three layers of
helper facts: a candidate rule wrote ``x ts:differenceCandidate y`` for every match of the
rest of the body, the difference rules (AllDifferent keys, owl:differentFrom, disjoint classes;
two values of a property allowing one) turned candidates into ``ts:declaredDifferent`` or
``ts:different``, every declared difference was copied into ``ts:different``, and the rule read
``ts:declaredDifferent`` (its conclusion) or ``ts:different`` (its entailed-only conclusion).  On
a map where every connected pair is declared different that is four helper facts and four joins
per pair, most of a full REASON.

Here each difference rule (a *source*: a rule reading ``?a ts:differenceCandidate ?b`` and writing
``?a ts:declaredDifferent ?b`` or ``?a ts:different ?b``) is joined into the SWRL rule instead:
the body with the source's other atoms and conditions, ``?a``/``?b`` bound to ``x``/``y``.  A
declared-difference source concludes the rule's head; a value source (difference by entailment
only) concludes its entailed-only head.  No candidate, no difference fact is written for the
rule's pairs; every new rule is positive, so semi-naive and incremental evaluation treat them as
any other.

Same closure
------------
The rule fired on ``declaredDifferent(x, y)``; that fact held exactly when some declared source
matched the candidate ``(x, y)``, and the candidate held exactly when the rest of the body matched
with ``x ≠ y``: the joined rules have the same matches.  The entailed-only head was concluded on
``different(x, y)``, i.e. a declared source or a value source: for a declared one the rule's own
head holds for the same body, so that entailed-only head was never published (ENTAILED keeps only
those neither asserted nor inferred); value sources give the rest.

A disjoint-classes source ``C1(x), C2(y)`` is left out when the body as written types ``x`` (or
``y``) with a class disjoint with ``C1`` (``C2``): it could only match an individual of two disjoint
classes, an inconsistency the disjointness check reports.  A rule with more than one difference
atom, a source that does not fit the pattern, or more than :data:`MAX_JOINED` joined rules keep
the materialised candidates (correct, only slower).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

from ..rdf.vocab import DECLARED_DIFFERENT, DIFFERENCE_CANDIDATE, DIFFERENT, TYPE
from . import condition as cond
from .condition import Condition
from .rule import Atom, Rule

#: joined rules per SWRL rule beyond which its candidates stay materialised
MAX_JOINED = 16

_CANDIDATE, _DECLARED, _DIFFERENT, _TYPE = str(DIFFERENCE_CANDIDATE), str(DECLARED_DIFFERENT), str(DIFFERENT), str(TYPE)
_VARIABLE = re.compile(r"\?([A-Za-z_][A-Za-z0-9_]*)")


@dataclass
class DifferenceAsk:
    """The rules a SWRL rule with one DifferentIndividuals atom ``x ≠ y`` compiled to."""

    x: str
    y: str
    candidate: Rule
    #: the head rules: the conclusion on declared difference, the entailed-only one on difference
    heads: list[Rule]


def inline_difference(rules: list[Rule], asks: list[DifferenceAsk]) -> list[Rule]:
    """``rules`` with each ask's candidate and head rules replaced by the rules joining the sources."""
    sources = _sources(rules)
    if sources is None or not asks:
        return rules
    disjoint = {_disjoint_classes(s) for s in sources if s.name == "different-disjoint"}
    disjoint.discard(None)
    dropped: set[int] = set()
    added: list[Rule] = []
    for ask in asks:
        joined = _joined(ask, sources, disjoint)
        if joined is None:
            continue
        dropped |= {id(ask.candidate), *(id(r) for r in ask.heads)}
        added += joined
    return [r for r in rules if id(r) not in dropped] + added


def _sources(rules: list[Rule]) -> list[Rule] | None:
    """The difference sources, or None when one does not fit ``?a candidate ?b ⟹ ?a (declared)different ?b``."""
    sources = []
    for r in rules:
        if r.is_check or not any(a.p == _CANDIDATE for a in r.body):
            continue
        if r.head.p not in (_DECLARED, _DIFFERENT):
            continue  # another reader of candidates: leave everything as it is
        candidates = [a for a in r.body if a.p == _CANDIDATE]
        if (len(candidates) != 1 or (candidates[0].s, candidates[0].o) != ("?a", "?b")
                or (r.head.s, r.head.o) != ("?a", "?b") or r.stratum != 0 or r.negates):
            return None
        sources.append(r)
    return sources


def _disjoint_classes(source: Rule) -> tuple[str, str] | None:
    """(class of ?a, class of ?b) of a disjoint-classes source."""
    types = {a.s: a.o for a in source.body if a.p == _TYPE and not a.o.startswith("?")}
    return (types["?a"], types["?b"]) if "?a" in types and "?b" in types else None


def _joined(ask: DifferenceAsk, sources: list[Rule], disjoint: set) -> list[Rule] | None:
    """The rules replacing the ask's head rules, or None when they stay as they are."""
    x, y = ask.x, ask.y
    if not (x.startswith("?") and y.startswith("?")) or x == y:
        return None
    out = []
    for head in ask.heads:
        atom = next((a for a in head.body if a.p in (_DECLARED, _DIFFERENT) and (a.s, a.o) == (x, y)), None)
        if atom is None or sum(a.p in (_DECLARED, _DIFFERENT) for a in head.body) != 1:
            return None
        wanted = _DECLARED if atom.p == _DECLARED else _DIFFERENT
        known = {v: {a.o for a in head.premises if a.s == v and a.p == _TYPE and not a.o.startswith("?")}
                 for v in (x, y)}
        for source in sources:
            if source.head.p != wanted or _contradictory(source, known[x], known[y], disjoint):
                continue
            out.append(_join(head, atom, source))
    return out if len(out) <= MAX_JOINED else None


def _contradictory(source: Rule, x_classes: set[str], y_classes: set[str], disjoint: set) -> bool:
    """A disjoint-classes source that needs ``x`` or ``y`` in a class disjoint with one it is typed with."""
    pair = _disjoint_classes(source) if source.name == "different-disjoint" else None
    if pair is None:
        return False
    return any((pair[0], c) in disjoint for c in x_classes) or any((pair[1], c) in disjoint for c in y_classes)


def _join(head: Rule, atom: Atom, source: Rule) -> Rule:
    """``head`` with its difference ``atom`` replaced by ``source``'s body (its candidate dropped)."""
    taken = {v for a in head.premises for v in a.variables()} | {
        v for c in (*head.conditions, *(head.written_conditions or ())) for v in c.variables}
    names = {"a": atom.s[1:], "b": atom.o[1:]}
    for a in source.premises:
        for v in a.variables():
            _fresh(v[1:], names, taken)
    for c in (*source.conditions, *(source.written_conditions or ())):
        for v in c.variables:
            _fresh(v[1:], names, taken)

    def rename(text: str) -> str:
        return _VARIABLE.sub(lambda m: "?" + names.get(m.group(1), m.group(1)), text)

    def atoms(body: tuple[Atom, ...]) -> tuple[Atom, ...]:
        return tuple(Atom(rename(a.s), rename(a.p), rename(a.o), a.aux) for a in body if a.p != _CANDIDATE)

    def conditions(cs: tuple[Condition, ...]) -> tuple[Condition, ...]:
        return tuple(replace(c, expression=rename(c.expression), binds=c.binds and rename(c.binds),
                             written=rename(c.written)) for c in cs)

    apart = cond.test(f"!sameTerm({atom.s}, {atom.o})")
    rest = tuple(a for a in head.body if a is not atom)
    written = ()
    if head.written or source.written:
        written = tuple(a for a in head.premises if a != atom) + atoms(source.premises)
    written_conditions = None
    if head.written_conditions is not None or source.written_conditions is not None:
        written_conditions = ((head.written_conditions or head.conditions)
                              + conditions(source.written_conditions or source.conditions) + (apart,))
    return replace(head, body=rest + atoms(source.body),
                   conditions=head.conditions + conditions(source.conditions) + (apart,),
                   filter_reads=head.filter_reads | source.filter_reads, written=written,
                   written_conditions=written_conditions)


def _fresh(name: str, names: dict[str, str], taken: set[str]) -> None:
    """Give the source variable ``name`` a name no variable of the SWRL rule has."""
    if name in names:
        return
    fresh, k = f"{name}_d", 0
    while f"?{fresh}" in taken:
        k += 1
        fresh = f"{name}_d{k}"
    names[name] = fresh
    taken.add(f"?{fresh}")


__all__ = ["MAX_JOINED", "DifferenceAsk", "inline_difference"]
