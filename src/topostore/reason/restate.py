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
long as ``B`` has no asserted fact (an asserted ``B`` fact would support ``A``
without ``C``); a path that comes back to the question it started from adds
nothing (a derivation around a cycle is not well founded).  So rule ``i`` can be left out for derived ``A`` facts, and its
recheck (``KEEP``) only needs the *asserted* ``A`` facts, which the step did not
change.
"""

from __future__ import annotations

from collections.abc import Collection, Iterator, Mapping

from ..compile.condition import TEST
from ..compile.rule import Atom, ReadKey, Rule
from ..rdf import lexer
from .triggers import Present, matches

Triple = tuple[str, str, str]


def restates(rules: list[Rule], i: int, writers: Mapping[ReadKey, list[int]], changed: Collection[ReadKey],
             asserted: Present | None, through: set[ReadKey]) -> bool:
    """Whether rule ``i`` (one premise, no condition) concludes what every derivation of its
    premise's facts already required (see the module docstring).  ``writers``: the rules that can
    derive each key; ``changed``: the keys with asserted facts added or removed; ``asserted``: the keys
    with asserted facts (a superset; None: any).  The keys a derivation was followed through (they
    must have no asserted fact for the answer to hold) are added to ``through``."""
    rule = rules[i]
    if len(rule.body) != 1 or rule.conditions or rule.head is None:
        return False
    atom = rule.body[0]
    key = atom.read_key()
    if key in changed:
        return False

    def passable(inner: ReadKey) -> bool:
        """A premise's key the question may pass to: every fact of it is derived, and stays so."""
        if inner in changed or asserted is None:
            return False
        return not matches(inner, *asserted)

    passed: set[ReadKey] = set()
    found = _required(rules, _terms(atom), _terms(rule.head), key, writers, passable, {}, passed)
    if found:
        through |= passed
    return found


def _required(rules: list[Rule], pattern: Triple, concluded: Triple, key: ReadKey,
              writers: Mapping[ReadKey, list[int]], passable, trail: dict, passed: set) -> bool:
    """Whether every derivation of a ``key`` fact matching ``pattern`` required ``concluded``."""
    shape = _canonical(pattern, concluded)
    if key in trail:
        return trail[key] == shape  # around a cycle, back to the same question
    found = writers.get(key, [])
    if not found:
        return False
    trail = {**trail, key: shape}
    return all(_required_by(rules, rules[w], pattern, concluded, writers, passable, trail, passed) for w in found)


def _required_by(rules: list[Rule], writer: Rule, pattern: Triple, concluded: Triple,
                 writers: Mapping[ReadKey, list[int]], passable, trail: dict, passed: set) -> bool:
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
    if not passable(inner) or not all(t in premise.variables() for t in theirs if t.startswith("?")):
        return False
    passed.add(inner)
    return _required(rules, _terms(premise), theirs, inner, writers, passable, trail, passed)


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


def covering(rules: list[Rule], candidates: Collection[int]) -> dict[int, ReadKey]:
    """Rules among ``candidates`` that never conclude anything new while one of their premises only
    matches derived facts: by rule, that premise's key.

    Reachability asks whether ``l1`` and ``l2`` are different for every ``connectedTo(l1, l2)`` the
    robot's place has; but every rule deriving ``connectedTo(l1, l2)`` (Connectability) had two places
    sharing a door, and Connectability's own question already asked about that pair from those very
    premises.  While no ``connectedTo`` fact is asserted, Reachability's question adds no fact: a
    compiled step may leave that rule out, and with it the path from ``isIn`` to the difference keys.
    The premises another rule ``r`` reads must be evaluated premises of each deriving rule ``w``, and
    ``r``'s filters must be among ``w``'s or the rule's own (as text); ``r`` must not itself be left out.
    """
    found = Covering(rules, candidates)
    return {i: key for i in sorted(found.candidates) if (key := found.key(i)) is not None}


class Covering:
    """:func:`covering` rule by rule, when asked: a robot step asks about the rules its change reaches,
    a few of the tens of thousands a large TBox compiles to (trying them all took most of the first
    step's time)."""

    def __init__(self, rules: list[Rule], candidates: Collection[int]) -> None:
        self.rules = rules
        self.candidates = frozenset(candidates)
        self.writers: dict[ReadKey, list[int]] = {}
        writers = self.writers
        for n, rule in enumerate(rules):
            if rule.head is not None:
                writers.setdefault(rule.writes(), []).append(n)
        self.readers = _Readers(rules)
        self._first: dict[int, ReadKey | None] = {}
        self._key: dict[int, ReadKey | None] = {}

    def key(self, i: int) -> ReadKey | None:
        """The premise key rule ``i`` adds nothing from while it only matches derived facts, or None."""
        if i not in self._key:
            key = self._covered_at(i)
            # a rule that helps cover another must stay
            if key is not None and any(self._covered_at(n) is not None
                                       for n in _helpers(self.rules, i, key, self.writers, self.readers)):
                key = None
            self._key[i] = key
        return self._key[i]

    def _covered_at(self, i: int) -> ReadKey | None:
        if i not in self.candidates:
            return None
        if i not in self._first:
            self._first[i] = _covered_at(self.rules, i, self.writers, self.readers)
        return self._first[i]


class _Readers:
    """Rules with a head by the key they write and the least key they read: the rules writing a key
    and reading only keys among a writer's premises are found under those premises' keys, not by
    trying every rule that writes the key (a TBox of hundreds of classes has thousands of them)."""

    def __init__(self, rules: list[Rule]) -> None:
        self._by: dict[tuple[ReadKey | None, ReadKey | None], list[int]] = {}
        by = self._by
        for n, rule in enumerate(rules):
            if rule.head is not None:
                reads = rule.reads()
                by.setdefault((rule.writes(), min(reads) if reads else None), []).append(n)

    def within(self, written: ReadKey | None, premises: Collection[ReadKey]) -> list[int]:
        """The rules writing ``written`` whose every read key is among ``premises`` may be among these
        (in rule order); the caller tests the whole set."""
        found = set(self._by.get((written, None), ()))
        for key in premises:
            found.update(self._by.get((written, key), ()))
        return sorted(found)


def _covered_at(rules: list[Rule], i: int, writers: Mapping[ReadKey, list[int]], readers: _Readers) -> ReadKey | None:
    rule = rules[i]
    if rule.head is None or any(c.kind != TEST or c.reads_graph for c in rule.conditions):
        return None
    for atom in rule.body:
        key = atom.read_key()
        if not atom.p.startswith("<") or key == rule.writes() or not writers.get(key):
            continue
        if all(any(True for _ in _derivers(rules, i, atom, rules[w], readers)) for w in writers[key]):
            return key
    return None


def _helpers(rules: list[Rule], i: int, key: ReadKey, writers: Mapping[ReadKey, list[int]],
             readers: _Readers) -> set[int]:
    atom = next(a for a in rules[i].body if a.read_key() == key)
    return {n for w in writers[key] for n in _derivers(rules, i, atom, rules[w], readers)}


def _derivers(rules: list[Rule], i: int, atom: Atom, writer: Rule, readers: _Readers) -> Iterator[int]:
    """The rules other than ``i`` that derive rule ``i``'s conclusion from ``writer``'s evaluated premises,
    whenever ``writer`` derives a fact matching ``atom`` and rule ``i``'s filters hold."""
    rule = rules[i]
    if writer.head is None or any(c.kind != TEST or c.reads_graph for c in writer.conditions):
        return
    theta = _match(_terms(atom), _terms(writer.head))
    if theta is None or any(t.startswith("?") and t not in theta for t in _terms(rule.head)):
        return
    goal = tuple(theta.get(t, t) for t in _terms(rule.head))
    known = {_squash(c.text) for c in writer.conditions}
    known |= {_squash(_substitute(c.text, theta)) for c in rule.conditions if c.variables <= theta.keys()}
    premise_keys = {a.read_key() for a in writer.body}
    for n in readers.within(rule.writes(), premise_keys):
        other = rules[n]
        if n == i or not other.reads() <= premise_keys \
                or any(c.kind != TEST or c.reads_graph for c in other.conditions):
            continue  # (a rule reading a key the writer does not read cannot be embedded in it)
        for sigma in _embeddings(other.body, writer.body, {}):
            if tuple(sigma.get(t, t) for t in _terms(other.head)) == goal and all(
                    _squash(_substitute(c.text, sigma)) in known for c in other.conditions):
                yield n
                break


def _embeddings(body: tuple[Atom, ...], premises: tuple[Atom, ...], sigma: dict[str, str]) -> Iterator[dict[str, str]]:
    """Substitutions mapping every atom of ``body`` onto one of ``premises`` (backtracking)."""
    if not body:
        yield sigma
        return
    first, rest = body[0], body[1:]
    for premise in premises:
        if first.aux != premise.aux:
            continue
        extended = dict(sigma)
        if all(extended.setdefault(m, t) == t if m.startswith("?") else m == t
               for m, t in zip(_terms(first), _terms(premise))):
            yield from _embeddings(rest, premises, extended)


def _substitute(text: str, mapping: Mapping[str, str]) -> str:
    """``text`` with its variables replaced by ``mapping``'s terms."""
    out, last = [], 0
    for token in lexer.tokens(text):
        if token.kind == lexer.VARIABLE and token.text in mapping:
            out += [text[last:token.start], mapping[token.text]]
            last = token.start + len(token.text)
    return "".join(out) + text[last:]


def _squash(text: str) -> str:
    return " ".join(text.split())


__all__ = ["Covering", "covering", "restates"]
