"""A deferred ask shown empty by a census of the AllDifferent keys instead of its join.

Why
---
A SWRL rule with ``x ≠ y`` has a candidate rule asking the value rules about each body pair whose
ordinary conclusion ``H(x, y)`` is not known (:mod:`.negation`); a full REASON evaluates it last, as
``body MINUS { H }``.  On a map it adds nothing (every pair sharing a door is declared different by the
AllDifferent keys, so ``connectedTo`` is already derived), yet at 100,000 locations the body's join of
the doors with themselves and the anti-join cost 0.67 s.  One census query of the keys and of the
individuals the body can bind to ``x`` and ``y`` answers it at less than half that.

Same answer
-----------
Let ``R`` be a deferred candidate rule (body ``B``, asked pair ``x``, ``y``, ``!sameTerm(x, y)`` among
its conditions, known conclusion ``H``), and ``J`` a rule of the set concluding ``H`` whose body is
``B`` with ``?k1 ts:differentKeyOf x`` and ``?k2 ts:differentKeyOf y`` (in the helper graph) and whose
conditions are ``R``'s with "two keys of one group" on ``?k1``, ``?k2``: the AllDifferent source joined
into the conclusion (:mod:`..compile.inline_difference`), positive and in the first stratum.  At the first
stratum's fixpoint, when ``R`` is asked, suppose

1. every rule writing keys is a generic key rule and the store holds one AllDifferent group
   (:func:`.one_group.keys_kept_by_group`, :func:`.one_group.one_group`): any two keys pass the group
   part of the test, which is then ``!sameTerm(?k1, ?k2)``;
2. the census (:func:`census_text`) counts as many key facts as distinct keys and as distinct holders:
   the key facts pair keys and holders one to one, so two different holders hold different keys;
3. and as many distinct holders as distinct terms among the holders and the values of ``x`` in one body
   atom holding it, and of ``y`` in one holding it: every term a match of ``B`` binds to ``x`` or ``y``
   holds a key (a match of ``B`` matches each of its atoms).

Then take a match of ``B`` with ``x ≠ y``: ``x`` holds a key ``k1``, ``y`` a key ``k2``, ``k1 ≠ k2`` by
(2) and in one group by (1), so ``J`` matches and, at the fixpoint, ``H(x, y)`` is known: ``body MINUS
{ H }`` is empty and the ask is left out.  When a condition fails the ask is evaluated as before.
Each count reads the default dataset (a superset of the graphs the ask reads its atoms in) and the
helper graph ``J`` reads its keys in.  An ask answered early (:mod:`.early_reads`) reads besides its
own keys the keys, the AllDifferent nodes and their member lists: a later write of one drops the early
answer.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass

from pyoxigraph import NamedNode

from ..compile import condition as cond
from ..compile.rule import Atom, ReadKey, Rule
from ..rdf.vocab import ASSERTED, AUX, DIFFERENT_KEY_OF, INFERRED, owl
from ..stores.base import Store
from .negation import deferred
from .one_group import group_test, keys_kept_by_group, one_group
from .triggers import may_write_any

_KEY = f"<{DIFFERENT_KEY_OF.value}>"
#: what one AllDifferent group and the keys' census read besides the ask's own keys
GROUP_READS: frozenset[ReadKey] = frozenset({
    ("p", _KEY), ("t", f"<{owl('AllDifferent').value}>"),
    *(("p", f"<{p.value}>") for p in (owl("distinctMembers"), owl("members")))})
_COUNTS = ("pairs", "keys", "held", "all")
#: the census's default dataset (:func:`census_text`)
_DEFAULT = frozenset({ASSERTED, INFERRED, AUX})


@dataclass(frozen=True)
class KeyCensus:
    """The census that may show a deferred ask empty (see the module docstring): the ask's rule."""

    rule: Rule

    def covers(self, store: Store, graphs: Mapping[ReadKey, NamedNode] | None = None) -> bool:
        """Whether the census shows every body pair's conclusion known (conditions 2 and 3); ``graphs``:
        the graph the ask reads a key of its body in, where it reads one alone."""
        rows = list(store.query(census_text(self.rule, graphs or {})))
        if len(rows) != 1:
            return False
        counts = {int(rows[0][name].value) for name in _COUNTS}
        return len(counts) == 1

    def reads(self) -> frozenset[ReadKey]:
        """The keys the census counts (:func:`census_text`): the keys, the AllDifferent group and the body
        atoms holding the asked pair; nothing written to them, its answer on more data is the same."""
        return GROUP_READS | {a.read_key() for a in _pair_atoms(self.rule)}

    def covers_as_read(self, graphs: Mapping[ReadKey, NamedNode]) -> bool:
        """Whether a census reading the pair's atoms in ``graphs`` counts what it counts when it covered
        reading them in the default dataset: each graph is one of the default dataset's, so the values
        it counts of the pair are a subset of those, all of them key holders, and its key counts the same."""
        return all(g in _DEFAULT for g in graphs.values())


def key_censuses(rules: Sequence[Rule]) -> dict[int, KeyCensus]:
    """By deferred rule, the census of its keys, for those with a key-joined conclusion in ``rules``
    (none when a rule other than the generic key rules may write keys)."""
    if not keys_kept_by_group(list(rules)):
        return {}
    out = {}
    for i in sorted(deferred(rules)):
        pair = (rules[i].head.s, rules[i].head.o)
        if not all(any(v in (a.s, a.p, a.o) for a in rules[i].body) for v in pair):
            continue  # a term of the pair is not the body's to count
        if any(keyed_conclusion(rules[i], other) for other in rules):
            out[i] = KeyCensus(rules[i])
    return out


def covered(store: Store, census: KeyCensus | None, queued: Collection[ReadKey | None],
            graphs: Mapping[ReadKey, NamedNode] | None = None, taken: bool = False) -> bool:
    """Whether the deferred ask with ``census`` is empty now (conditions 1 to 3); ``queued``: the keys the
    evaluations waiting in the queue may write (none of them may be one the census reads); ``graphs``:
    as :meth:`KeyCensus.covers`; ``taken``: the census is known to cover on the data now (taken before,
    nothing it counts written since), so it is not counted again."""
    if census is None or may_write_any(queued, census.rule.reads() | GROUP_READS):
        return False
    return one_group(store, queued) and (taken or census.covers(store, graphs))


def keyed_conclusion(rule: Rule, other: Rule) -> bool:
    """Whether ``other`` is ``rule``'s conclusion joined with the AllDifferent keys of its asked pair."""
    x, y = rule.head.s, rule.head.o
    if (rule.unless_known is None or other.head != rule.unless_known or other.stratum != 0 or other.negates
            or other.is_check or _form(cond.test(f"!sameTerm({x}, {y})")) not in {_form(c) for c in rule.conditions}):
        return False
    extra = list(other.body)
    for atom in rule.body:
        if atom not in extra:
            return False
        extra.remove(atom)
    keys = {a.o: a.s for a in extra if a.aux and a.p == _KEY and a.s.startswith("?")}
    if len(extra) != 2 or set(keys) != {x, y} or keys[x] == keys[y]:
        return False
    allowed = {_form(c) for c in (*rule.conditions, cond.test(group_test(keys[x], keys[y])),
                                  cond.test(f"!sameTerm({keys[x]}, {keys[y]})"))}
    return {_form(c) for c in other.conditions} <= allowed and not (_variables(rule) & set(keys.values()))


def census_text(rule: Rule, graphs: Mapping[ReadKey, NamedNode]) -> str:
    """The census query of ``rule``'s keys: key facts, distinct keys, distinct holders, and distinct terms
    among the holders and the values of the asked pair in one body atom each (read in its graph of
    ``graphs``, else in the default dataset, as the ask reads it)."""
    taken = _variables(rule)
    key, member, held = (_free(name, taken) for name in ("census_key", "census_member", "census_held"))
    branches = [f"GRAPH {AUX} {{ {key} {_KEY} {member} . }} BIND({member} AS {held})"]
    named = {str(AUX): AUX}
    for v, atom in zip((rule.head.s, rule.head.o), _pair_atoms(rule), strict=True):
        renamed = Atom(*(member if t == v else t for t in (atom.s, atom.p, atom.o)), atom.aux)
        graph = AUX if atom.aux else graphs.get(atom.read_key())
        branch = renamed.text() if graph is None else f"GRAPH {graph} {{ {renamed.text()} }}"
        if graph is not None:
            named[str(graph)] = graph
        if branch not in branches:
            branches.append(branch)
    union = " UNION ".join(f"{{ {b} }}" for b in branches)
    return (f"SELECT (COUNT({key}) AS ?pairs) (COUNT(DISTINCT {key}) AS ?keys) (COUNT(DISTINCT {held}) AS ?held) "
            f"(COUNT(DISTINCT {member}) AS ?all)\nFROM {ASSERTED} FROM {INFERRED} FROM {AUX} "
            f"{' '.join(f'FROM NAMED {g}' for g in named.values())}\nWHERE {{ {union} }}")


def _pair_atoms(rule: Rule) -> tuple[Atom, Atom]:
    """The body atom the census reads each term of the asked pair in: the first holding it."""
    x, y = (next(a for a in rule.body if v in (a.s, a.p, a.o)) for v in (rule.head.s, rule.head.o))
    return x, y


def _form(c: cond.Condition) -> tuple:
    """What a condition tests or binds, apart from how it was written."""
    return c.kind, c.expression, c.binds, c.negated


def _variables(rule: Rule) -> set[str]:
    """Every variable of ``rule``'s body and conditions."""
    return {v for a in rule.body for v in a.variables()} | {v for c in rule.conditions for v in c.variables}


def _free(name: str, taken: set[str]) -> str:
    """A variable named after ``name`` that ``taken`` does not hold."""
    k = 0
    while f"?{name}{k or ''}" in taken:
        k += 1
    return f"?{name}{k or ''}"


__all__ = ["GROUP_READS", "KeyCensus", "census_text", "covered", "key_censuses", "keyed_conclusion"]
