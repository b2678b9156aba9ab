"""Body atoms the TBox already implies: dropped from evaluation, kept for explanations.

Why
---
A SWRL rule as users write it repeats what the axioms say: the tutorial's
Reachability rule reads ``isIn(?r, ?l1) ∧ LOCATION(?l1) ∧ ROBOT(?r) ∧
connectedTo(?l1, ?l2) ∧ LOCATION(?l2)`` although ``isIn`` has the domain ROBOT
and the range LOCATION, and ``connectedTo`` the range LOCATION.  Every such
atom is one more join per evaluation, and one more predicate the rule is said
to read: a change of LOCATION facts then triggers the rule, and the type atoms
tie rules into cycles (canReach ⟹ ROBOT by its domain, ROBOT ⟹ canReach by the
rule) that incremental maintenance has to treat as recursion.

When is dropping sound
----------------------
An atom ``?x rdf:type C`` is *implied* by another atom of the same body when
the rule set itself holds single-atom, condition-free rules that derive
``C(x)`` from that atom: a domain or range rule (``p(x, y) ⟹ C(x)``), a
subclass rule (``D(x) ⟹ C(x)``), and chains of them through sub-, inverse
and symmetric property rules.  Over any state closed under those rules (the
closure, or the facts proven to hold in it), the body with and without the
atom has the same matches; over a partial state during a fixpoint it matches
at least as often, and only facts the fixpoint derives anyway.  So the rule
set with the atoms dropped has the same closure, for every asserted graph.

An atom implied only through an *object* position (a range) also says that
the value is not a literal (a literal has no types: the range rule cannot
derive one), so the dropped atom leaves ``FILTER(!isLiteral(?y))`` behind
unless the variable is a subject elsewhere in the body.

The implications are read off the compiled rules, not the axioms, so they
hold for whatever the compilers emit; :attr:`Rule.written` keeps the body as
written, which explanations show as the premises.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import replace

from ..rdf.vocab import TYPE
from .condition import test
from .reach import Reach
from .rule import Atom, Rule

_TYPE = str(TYPE)

#: A position a term is known from: ("s", p) subject of p, ("o", p) object of p, ("t", C) instance of C.
Position = tuple[str, str]


def _is_var(term: str) -> bool:
    return term.startswith("?")


def _position_edges(rules: Iterable[Rule]) -> dict[Position, set[Position]]:
    """Edges ``a -> b``: a term at position ``a`` is, in the closure, also at position ``b``."""
    edges: dict[Position, set[Position]] = {}
    for rule in rules:
        if rule.is_check or len(rule.body) != 1 or rule.conditions or rule.stratum != 0:
            continue
        (atom,), head = rule.body, rule.head
        if not (_is_var(atom.s) and _is_var(head.s)) or _is_var(atom.p) or _is_var(head.p):
            continue
        if atom.p != _TYPE and not _is_var(atom.o):
            continue  # p(x, v) ⟹ A(x) (a hasValue) says nothing of p(x, y) in general
        sources = _positions(atom)
        if head.p == _TYPE:
            if _is_var(head.o):
                continue
            target = ("t", head.o)
            for var, pos in sources:
                if var == head.s:
                    edges.setdefault(pos, set()).add(target)
            continue
        if not _is_var(head.o) or head.s == head.o:
            continue
        for var, pos in sources:
            if var == head.s:
                edges.setdefault(pos, set()).add(("s", head.p))
            if var == head.o:
                edges.setdefault(pos, set()).add(("o", head.p))
    return edges


def _positions(atom: Atom) -> list[tuple[str, Position]]:
    """(variable, position) pairs an atom gives its variables."""
    if atom.p == _TYPE:
        return [(atom.s, ("t", atom.o))] if _is_var(atom.s) and not _is_var(atom.o) else []
    if atom.s == atom.o:
        return []  # p(x, x): a reflexive pattern says more than either position
    out = []
    if _is_var(atom.s):
        out.append((atom.s, ("s", atom.p)))
    if _is_var(atom.o):
        out.append((atom.o, ("o", atom.p)))
    return out


class ImpliedClasses(Mapping[Position, frozenset[str]]):
    """Per position, the classes its terms belong to in the closure: walked when a position is first
    asked for (a compilation asks of the few positions its multi-atom bodies hold, not of the tens of
    thousands of classes a large TBox's single-atom rules link)."""

    def __init__(self, edges: dict[Position, set[Position]]) -> None:
        self._edges = edges
        self._reach: Reach[Position] = Reach(lambda position: edges.get(position, ()))
        self._classes: dict[Position, frozenset[str]] = {}

    def __getitem__(self, start: Position) -> frozenset[str]:
        if start not in self._edges:
            raise KeyError(start)
        found = self._classes.get(start)
        if found is None:
            found = self._classes[start] = frozenset(
                c for kind, c in self._reach(start) if kind == "t" and (kind, c) != start)
        return found

    def __iter__(self) -> Iterator[Position]:
        return iter(self._edges)

    def __len__(self) -> int:
        return len(self._edges)


def _closure(edges: dict[Position, set[Position]]) -> ImpliedClasses:
    """Per position, the classes its terms belong to in the closure."""
    return ImpliedClasses(edges)


def position_classes(rules: Iterable[Rule]) -> Mapping[Position, frozenset[str]]:
    """Per position (subject or object of a property, instance of a class), the classes a term there
    belongs to in the closure, read off the single-atom rules as :func:`simplify` reads them."""
    return _closure(_position_edges(rules))


def classes_of(var: str, atoms: Iterable[Atom], implied: Mapping[Position, frozenset[str]]) -> set[str]:
    """The classes ``var`` belongs to in the closure wherever ``atoms`` match: those they type it with
    and those the positions it holds imply (``implied``: :func:`position_classes`)."""
    out: set[str] = set()
    for atom in atoms:
        for v, pos in _positions(atom):
            if v == var:
                out |= implied.get(pos, frozenset())
                if pos[0] == "t":
                    out.add(pos[1])
    return out


def simplify(rules: list[Rule]) -> list[Rule]:
    """The rules with every implied type atom dropped from their bodies (see the module docstring)."""
    edges = _position_edges(rules)
    implied = _closure(edges)
    # a class no single-atom rule concludes is implied by nothing: its atoms need no search for a witness
    targets = {c for found in edges.values() for kind, c in found if kind == "t"}
    return [_simplified(rule, implied, targets) for rule in rules]


def _simplified(rule: Rule, implied: Mapping[Position, frozenset[str]], targets: set[str]) -> Rule:
    if len(rule.body) < 2:
        return rule  # a single atom has no other atom to be implied by
    kept = list(rule.body)
    dropped: list[Atom] = []
    for atom in rule.body:
        if atom.p != _TYPE or atom.o not in targets or not _is_var(atom.s) or _is_var(atom.o):
            continue
        others = [a for a in kept if a is not atom]
        witness = _witness(atom, others, implied)
        if witness is not None:
            kept.remove(atom)
            dropped.append(atom)
    if not dropped:
        return rule
    conditions = list(rule.conditions)
    for atom in dropped:
        if not any(a.s == atom.s for a in kept):  # a subject is never a literal
            conditions.insert(0, test(f"!isLiteral({atom.s})"))
    return replace(rule, body=tuple(kept), conditions=tuple(conditions), written=rule.body,
                   written_conditions=rule.conditions)


def _witness(atom: Atom, others: list[Atom], implied: Mapping[Position, frozenset[str]]) -> Atom | None:
    """An atom among ``others`` that implies ``atom`` (``?x rdf:type C``), or None."""
    for other in others:
        for var, pos in _positions(other):
            if var == atom.s and atom.o in implied.get(pos, ()):
                return other
    return None


__all__ = ["classes_of", "position_classes", "simplify"]
