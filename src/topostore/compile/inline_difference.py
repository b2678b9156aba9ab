"""A rule's difference tested where it is asked, not materialised pair by pair.

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

Here each declared-difference rule (a *declared source*: a rule reading ``?a
ts:differenceCandidate ?b`` and writing ``?a ts:declaredDifferent ?b``: AllDifferent keys,
owl:differentFrom either way, disjoint classes) is joined into the SWRL rule's conclusion instead:
the body with the source's other atoms and conditions, ``?a``/``?b`` bound to ``x``/``y``.  No
candidate, no declared or copied difference fact is written for the rule's pairs; every new rule is
positive, so semi-naive and incremental evaluation treat them as any other.

The entailed-only conclusion (difference by values only) keeps reading ``ts:different``, but its
pairs are asked as ``ts:valueCandidate`` (:data:`~.snippets.VALUE_CANDIDATE`): no declared difference
is derived for them.  The value sources (two values of a property allowing one) then read
``ts:valueCandidate`` alone, and every other rule asking about a pair asks both kinds (its candidate
rule writes both), so one set of value rules serves every asker.  Why not join the value sources into
the SWRL rules too: a robot step replaces visit times, and a value test joined into each rule is then
maintained rule by rule (the connecting rule's flip, the reaching rule's deltas on both visit times
besides its location), where the value rules over the asked pairs serve every rule once; measured,
the joined form cost the example step 0.5 ms more, two sets of value rules 0.2 ms
(docs/benchmarks-history.md).

The entailed-only twin of a pair is published only where the rule's ordinary head is not known, so
its value candidate rule carries that head as ``unless_known`` when the head names the asked pair
(``connectedTo(l1, l2)`` asking ``l1 ≠ l2``): a full REASON then asks only the pairs whose head is not
known, and maintenance keeps the asks exact enough for what is published (:mod:`..reason.negation`).

An OWL rule that needs one pair of fillers different (a minimum cardinality of two, :func:`owl_asks`)
reads ``ts:different`` as a plain conclusion: it is joined with every source, declared and by values.

Same closure
------------
The conclusion fired on ``declaredDifferent(x, y)``; that fact held exactly when some declared
source matched the candidate ``(x, y)``, and the candidate held exactly when the rest of the body
matched with ``x ≠ y``: the joined rules have the same matches.  The entailed-only head was
concluded on ``different(x, y)``, i.e. a declared source or a value source: for a declared one the
rule's own head holds for the same body, so that entailed-only head was never published (ENTAILED
keeps only those neither asserted nor inferred); the value sources over the same pairs give the rest.
Without value sources the entailed-only head is never published, and its rules are left out.

A source is left out of a join when its ``?a`` (``?b``) must be in a class disjoint with one that
``x`` (``y``) is in, as the bodies write them or as the axioms imply from the positions the variables
hold (a domain, a range, a superclass; :func:`.implied.classes_of`): ``C1(a), C2(b)`` of a
disjoint-classes source, or the domain of a value source's property (two doors have no visit time
when doors and locations are disjoint).  Such a join matches only an individual of two disjoint
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
from .implied import classes_of, position_classes
from .rule import Atom, Rule
from .snippets import VALUE_CANDIDATE

#: joined rules per SWRL rule beyond which its candidates stay materialised
MAX_JOINED = 16
#: ordered pairs of disjoint classes beyond which no ask is joined (each is a declared source: with
#: more, every join would pass :data:`MAX_JOINED` but where the disjointness itself prunes nearly all)
MAX_DISJOINT_SOURCES = 8 * MAX_JOINED

_CANDIDATE, _DECLARED, _DIFFERENT, _TYPE = str(DIFFERENCE_CANDIDATE), str(DECLARED_DIFFERENT), str(DIFFERENT), str(TYPE)
_VALUE_CANDIDATE = str(VALUE_CANDIDATE)
_VARIABLE = re.compile(r"\?([A-Za-z_][A-Za-z0-9_]*)")


@dataclass
class DifferenceAsk:
    """The rules asking whether ``x ≠ y``: the candidate rule and the rules reading the answer."""

    x: str
    y: str
    candidate: Rule
    #: the head rules: a SWRL rule's conclusion on declared difference and its entailed-only one on
    #: difference; an OWL rule's conclusions on difference (``twins`` False)
    heads: list[Rule]
    #: whether heads reading ``ts:different`` are entailed-only twins of heads on declared difference
    twins: bool = True


def owl_asks(rules: list[Rule]) -> list[DifferenceAsk]:
    """The OWL rules that need one pair of fillers different (a minimum cardinality of two): per
    axiom (origin), one ``different-candidate`` rule and rules reading its pair as one body atom.
    An axiom whose rules read the difference any other way (negated, in a filter, in a check)
    keeps its candidates."""
    groups: dict[str, list[Rule]] = {}
    for r in rules:
        if not r.name.startswith("swrl:"):
            groups.setdefault(r.origin, []).append(r)
    orphans = _orphan_readers(groups)
    asks = []
    for group in groups.values():
        candidates = [r for r in group if r.name == "different-candidate" and r.head.p == _CANDIDATE]
        if len(candidates) != 1:
            continue
        candidate = candidates[0]
        if any(set(candidate.body) <= set(o.body) for o in orphans):
            continue  # it also asks for another axiom, whose own copy of it was merged into it
        others = [r for r in group if r is not candidate]
        if any(r.is_check or ("p", _DIFFERENT) in r.filter_reads or r.negates for r in others):
            continue
        readers = [r for r in others if any(a.p in (_DIFFERENT, _DECLARED) for a in r.body)]
        ask = DifferenceAsk(candidate.head.s, candidate.head.o, candidate, readers, twins=False)
        if readers and all(_difference_atom(r, ask) is not None and r.stratum == 0 for r in readers):
            asks.append(ask)
    return asks


def _orphan_readers(groups: dict[str, list[Rule]]) -> list[Rule]:
    """The rules reading ``ts:different`` (in the body or a filter) of an axiom without a candidate rule.

    Why: a rule set keeps one of two rules alike but for their origin (:meth:`.rule.RuleSet.add`), so two
    axioms whose fillers are written alike (``p min 2 F`` and ``p min 3 F``) share one candidate rule,
    filed under the origin of whichever came first.  Joining that origin's readers and dropping the
    candidate would leave the other axiom's readers with no pair ever asked: its candidate stays."""
    orphans = []
    for group in groups.values():
        if any(r.name == "different-candidate" and r.head is not None and r.head.p == _CANDIDATE for r in group):
            continue
        orphans += [r for r in group if any(a.p in (_DIFFERENT, _DECLARED) for a in r.body)
                    or ("p", _DIFFERENT) in r.filter_reads]
    return orphans


def inline_difference(rules: list[Rule], asks: list[DifferenceAsk], disjoint: list[Rule] | None = None,
                      disjoint_rows: int = 0) -> list[Rule]:
    """``rules`` with each ask's conclusions joined with the sources, a SWRL rule's entailed-only
    conclusion reading the value sources' answers for its pairs (see the module docstring).

    ``disjoint``: the ``different-disjoint`` sources, which the rule set holds as rows
    (:mod:`.disjointness`), instantiated by the caller; ``disjoint_rows``: how many there are, to
    be given instead of them past :data:`MAX_DISJOINT_SOURCES` (no ask is joined then, and nothing
    is instantiated)."""
    if disjoint_rows > MAX_DISJOINT_SOURCES:
        return rules
    sources = _sources(rules)
    if sources is None or not asks:
        return rules
    sources += disjoint or []
    declared = [s for s in sources if s.head.p == _DECLARED]
    values = [s for s in sources if s.head.p == _DIFFERENT]
    apart = _Apart(rules, declared)
    dropped: set[int] = set()
    added: list[Rule] = []
    asked = False
    for ask in asks:
        if not ask.twins:  # an OWL conclusion on difference: every source answers it
            joined = _joined(ask, ask.heads, declared + values, apart)
            if joined is not None:
                dropped |= {id(ask.candidate), *(id(r) for r in ask.heads)}
                added += joined
            continue
        conclusions = [r for r in ask.heads if _difference_atom(r, ask) is not None
                       and _difference_atom(r, ask).p == _DECLARED]
        entailed = [r for r in ask.heads if r not in conclusions]
        joined = _joined(ask, conclusions, declared, apart)
        if joined is None or any(_difference_atom(r, ask) is None for r in entailed):
            continue
        dropped |= {id(ask.candidate), *(id(r) for r in conclusions)}
        added += joined
        if values and entailed:
            added.append(_asks_values(ask.candidate, _known_conclusion(ask, conclusions)))
            asked = True
        else:  # nothing but a declared difference could fire it: never published
            dropped |= {id(r) for r in entailed}
    if asked:  # the value sources answer ts:valueCandidate alone; the other askers ask both kinds
        asking = [r for r in rules if id(r) not in dropped and r.head is not None and r.head.p == _CANDIDATE]
        dropped |= {id(s) for s in values}
        added += [_asks_values(r) for r in asking] + [_reading_value_candidates(s) for s in values]
    return [r for r in rules if id(r) not in dropped] + added


def _difference_atom(head: Rule, ask: DifferenceAsk) -> Atom | None:
    """The head rule's one difference atom on the ask's pair, or None."""
    found = [a for a in head.body if a.p in (_DECLARED, _DIFFERENT)]
    if len(found) != 1 or (found[0].s, found[0].o) != (ask.x, ask.y):
        return None
    return found[0]


def _asks_values(candidate: Rule, unless_known: Atom | None = None) -> Rule:
    """The candidate rule asking the value sources only (``ts:valueCandidate``); ``unless_known``:
    the ordinary conclusion whose known facts make the ask idle (:func:`_known_conclusion`)."""
    head = candidate.head
    return replace(candidate, head=Atom(head.s, _VALUE_CANDIDATE, head.o, aux=True),
                   origin=candidate.origin.replace("for difference", "for difference by values"),
                   unless_known=unless_known)


def _known_conclusion(ask: DifferenceAsk, conclusions: list[Rule]) -> Atom | None:
    """The one head of a SWRL rule's conclusions when it names the asked pair itself (``x``/``y`` as
    its subject and object), else None.

    Why: the entailed-only twin of a pair is published only where that head is neither asserted nor
    inferred, so its pair need not be asked of the value rules where the head is known.  The head must
    name the pair: a head on other variables (``canReach(r, l2)`` asking ``l1 ≠ l2``) is known through
    one match of the body while another match's pair may still need asking."""
    heads = {r.head for r in conclusions}
    if len(heads) != 1:
        return None
    head = heads.pop()
    if head is None or head.p.startswith("?") or {head.s, head.o} != {ask.x, ask.y}:
        return None
    return head


def _reading_value_candidates(source: Rule) -> Rule:
    """A value source answering the pairs asked as ``ts:valueCandidate``."""
    def swap(body: tuple[Atom, ...]) -> tuple[Atom, ...]:
        return tuple(Atom(a.s, _VALUE_CANDIDATE, a.o, a.aux) if a.p == _CANDIDATE else a for a in body)

    return replace(source, body=swap(source.body), written=swap(source.written))


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


def _joined(ask: DifferenceAsk, heads: list[Rule], sources: list[Rule], apart: _Apart) -> list[Rule] | None:
    """The rules replacing the ask's ``heads``, or None when they stay as they are."""
    x, y = ask.x, ask.y
    if not (x.startswith("?") and y.startswith("?")) or x == y or not heads:
        return None
    out = [_join(head, _difference_atom(head, ask), source) for head in heads for source in sources
           if not apart.contradictory(head, x, y, source)]
    return out if len(out) <= MAX_JOINED else None


class _Apart:
    """Which joins could only match an individual of two disjoint classes."""

    def __init__(self, rules: list[Rule], declared: list[Rule]) -> None:
        #: (class, class) of every disjoint-classes source, both orders
        self.disjoint = {_disjoint_classes(s) for s in declared if s.name == "different-disjoint"} - {None}
        self.implied = position_classes(rules) if self.disjoint else {}

    def contradictory(self, head: Rule, x: str, y: str, source: Rule) -> bool:
        """Whether ``source``'s ``?a`` (``?b``) must be in a class disjoint with one ``head`` puts ``x``
        (``y``) in, as written or implied by the axioms (a domain, a range, a superclass): such a join
        matches only where the disjointness check reports an inconsistency."""
        return any((c, d) in self.disjoint
                   for mine, theirs in ((x, "?a"), (y, "?b"))
                   for c in classes_of(theirs, source.premises, self.implied)
                   for d in classes_of(mine, head.premises, self.implied))


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
