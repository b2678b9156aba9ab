"""Which rules only restate a premise: the edges a compiled step may leave out.

Why this exists
---------------
canReach's range says its object is a LOCATION; but every rule deriving
canReach already required the place to be a LOCATION.  So a *derived* canReach
fact never gives a LOCATION fact a support it did not have before: the range
rule only matters for *asserted* canReach facts.  On the tutorial map such
rules (domains, ranges, an intersection's members, an equivalence's way back)
close the cycles that tie canReach, connectedTo, the difference keys and the
location classes into one recursive component; left out, the keys are plain
and each is rechecked once, in order, instead of running DRed over them all.

The argument is one of well-founded derivations.  Rule ``i`` has one premise
``A`` and no condition, and concludes ``C``.  If every rule that can derive an
``A`` fact has ``C`` (with the same terms) among its premises, then every
derived ``A`` fact was derived after ``C`` held, without ``A``'s help: ``C``
holds without rule ``i``.  A rule with one premise ``B`` deriving ``A`` (an
equivalence's way back, say) passes the question on to ``B``'s writers, as
long as no asserted ``B`` fact changed in the step; a path that comes back to
the question it started from adds nothing (a derivation around a cycle is not
well founded).  So rule ``i`` can be left out for derived ``A`` facts, and its
recheck (``KEEP``) only needs the *asserted* ``A`` facts, which the step did not
change.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping

from ..compile.rule import Atom, ReadKey, Rule

Triple = tuple[str, str, str]


def restates(rules: list[Rule], i: int, writers: Mapping[ReadKey, list[int]], changed: Collection[ReadKey]) -> bool:
    """Whether rule ``i`` (one premise, no condition) concludes what every derivation of its
    premise's facts already required (see the module docstring).  ``writers``: the rules that can
    derive each key; ``changed``: the keys with asserted facts added or removed."""
    rule = rules[i]
    if len(rule.body) != 1 or rule.conditions or rule.head is None:
        return False
    atom = rule.body[0]
    key = atom.read_key()
    if key in changed:
        return False
    return _required(rules, _terms(atom), _terms(rule.head), key, writers, changed, {})


def _required(rules: list[Rule], pattern: Triple, concluded: Triple, key: ReadKey,
              writers: Mapping[ReadKey, list[int]], changed: Collection[ReadKey], trail: dict) -> bool:
    """Whether every derivation of a ``key`` fact matching ``pattern`` required ``concluded``."""
    shape = _canonical(pattern, concluded)
    if key in trail:
        return trail[key] == shape  # around a cycle, back to the same question
    found = writers.get(key, [])
    if not found:
        return False
    trail = {**trail, key: shape}
    return all(_required_by(rules, rules[w], pattern, concluded, writers, changed, trail) for w in found)


def _required_by(rules: list[Rule], writer: Rule, pattern: Triple, concluded: Triple,
                 writers: Mapping[ReadKey, list[int]], changed: Collection[ReadKey], trail: dict) -> bool:
    if writer.head is None:
        return False
    mapping = _match(pattern, _terms(writer.head))
    if mapping is None:
        return False
    if any(t.startswith("?") and t not in mapping for t in concluded):
        return False  # a variable of the conclusion the premise does not bind
    theirs = tuple(mapping.get(t, t) for t in concluded)
    if any(_terms(a) == theirs for a in writer.premises):
        return True
    if len(writer.body) != 1 or writer.conditions:
        return False
    premise = writer.body[0]
    inner = premise.read_key()
    if inner in changed or not all(t in premise.variables() for t in theirs if t.startswith("?")):
        return False
    return _required(rules, _terms(premise), theirs, inner, writers, changed, trail)


def _match(pattern: Triple, head: Triple) -> dict[str, str] | None:
    """The substitution of ``pattern``'s variables by ``head``'s terms, or None when they differ."""
    mapping: dict[str, str] = {}
    for mine, theirs in zip(pattern, head):
        if mine.startswith("?"):
            if mapping.setdefault(mine, theirs) != theirs:
                return None
        elif mine != theirs:
            return None
    return mapping


def _canonical(pattern: Triple, concluded: Triple) -> tuple:
    """The two patterns with variables numbered in order of appearance (a question up to renaming)."""
    names: dict[str, str] = {}
    return tuple(names.setdefault(t, f"?{len(names)}") if t.startswith("?") else t for t in (*pattern, *concluded))


def _terms(atom: Atom) -> Triple:
    return (atom.s, atom.p, atom.o)


__all__ = ["restates"]
