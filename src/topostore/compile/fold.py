"""A named class equivalent to an anonymous class expression stands for it in every rule.

Why
---
``ROOM ≡ LOCATION ⊓ ∃hasDoor.DOOR`` compiles to rules that derive the intersection's membership
(a helper fact per location), copy it to ROOM (``cax-eqc2``) and back (``cax-eqc1``).  Every
member of the one class is a member of the other in the closure, so the helper membership says
nothing ROOM does not: on the tutorial map it is 40,000 helper facts at 10,000 locations (the
intersections of ROOM and CORRIDOR, LOCATION's ``visitedAt exactly 1``), each written, read and
maintained, and one more key (and one more step operation) per change.

Here, when a named class ``C`` and an anonymous expression ``E`` are equivalent, and each is
equivalent to no other class of that kind, every rule reads and writes ``C`` where it read or wrote
``E``; the rule copying ``C`` into ``E`` disappears.  The rule copying ``E`` into ``C`` stays as it
was, for a membership of ``E`` told in the data (a blank node the file also uses as a class).

Same closure
------------
In the closure ``E(x) ⟺ C(x)``: a rule matching ``E(x)`` matches ``C(x)`` for the same bindings,
and a rule concluding ``E(x)`` concludes what ``cax-eqc2`` turned into ``C(x)``.  What is no longer
derived is only ``E(x)`` itself, a helper fact no query shows (anonymous classes are not answered).

A restriction an intersection already implies its other part of
----------------------------------------------------------------
In ``ROOM ≡ LOCATION ⊓ ∃hasDoor.DOOR`` with ``hasDoor``'s domain LOCATION, every instance of the
restriction ``R = ∃hasDoor.DOOR`` has a ``hasDoor`` value, so is a LOCATION: ``R ⊑ LOCATION``, the
intersection is ``R`` itself, and ``ROOM ≡ R`` in every model.  Left as it is, the closure holds a helper
fact ``R(x)`` per room (100,000 at 100,000 locations) copied into ROOM by the intersection's rule.
:func:`restriction_names` finds such restrictions (``∃p.X``, ``≥n p.X`` or ``=n p.X`` with ``n ≥ 1``,
on a property whose subjects, or objects for an inverse, the single-atom rules put in the other part;
the intersection of two parts with one named equivalent; no fact or rule outside the axioms naming the
restriction), and :func:`fold_equivalents` then reads and writes the named class for the restriction
as well: its own rule (``cls-svf1``, a minimum's count) concludes ROOM, and the intersection's rules,
now concluding what they read, disappear.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import replace

from pyoxigraph import NamedNode

from ..rdf.terms import sparql
from ..rdf.vocab import TYPE, is_skolem
from .condition import Condition
from .model import Expr
from .rule import Atom, Rule

_TYPE = str(TYPE)


def fold_equivalents(rules: list[Rule], more: Mapping[str, str] | None = None) -> list[Rule]:
    """``rules`` with each anonymous class that has exactly one named equivalent replaced by it (and the
    restrictions of ``more``, :func:`restriction_names`, by theirs); a rule then concluding one of the
    atoms it reads is left out."""
    names = {**_equivalents(rules), **(more or {})}
    if not names:
        return rules
    out: list[Rule] = []
    seen: set[tuple] = set()
    for rule in rules:
        if _is_copy(rule, names):
            continue  # C(x) ⟹ E(x): now C(x) ⟹ C(x)
        if rule.name == "cax-eqc2" and _copies_back(rule, names):
            out.append(rule)  # E(x) ⟹ C(x) stays, for a membership of E told in the data
            continue
        folded = _folded(rule, names)
        if folded.head is not None and not folded.is_check and folded.head in folded.body:
            folded = _told(rule, folded, more or {})  # C(x) ∧ A(x) ⟹ C(x) concludes what it reads
            if folded is None:
                continue
        key = (folded.name, folded.body, folded.head, folded.conditions, folded.violation)
        if key not in seen:
            seen.add(key)
            out.append(folded)
    return out


def _told(rule: Rule, folded: Rule, more: Mapping[str, str]) -> Rule | None:
    """For an intersection's rule reading a restriction of ``more``, the copy ``R(x) ⟹ C(x)`` left in its
    place, for a membership of ``R`` told in the data (as ``cax-eqc2`` stays for an expression): every
    ``R`` is an ``A``, so ``C`` holds of it.  None for any other rule."""
    head = folded.head
    for atom in rule.body:
        if atom.p == _TYPE and atom.s == head.s and more.get(atom.o) == head.o:
            told = Atom(atom.s, atom.p, atom.o)  # read wherever it is told, not in the helper graph alone
            return replace(rule, name="cax-eqc2", body=(told,), conditions=(), filter_reads=frozenset(),
                           written=(told,), written_conditions=None, head=head)
    return None


def _pair(rule: Rule) -> tuple[str, str] | None:
    """(body class, head class) of a single-atom class copy ``?x a A ⟹ ?x a B``, or None."""
    if rule.is_check or len(rule.body) != 1 or rule.conditions:
        return None
    (atom,), head = rule.body, rule.head
    if atom.p != _TYPE or head.p != _TYPE or atom.s != head.s or atom.o.startswith("?") or head.o.startswith("?"):
        return None
    return atom.o, head.o


def _equivalents(rules: list[Rule]) -> dict[str, str]:
    """Anonymous class → its one named equivalent, for pairs copied both ways by cax-eqc1/cax-eqc2."""
    forward = {_pair(r) for r in rules if r.name == "cax-eqc1"} - {None}
    back = {_pair(r) for r in rules if r.name == "cax-eqc2"} - {None}
    both = {(a, b) for a, b in forward if (b, a) in back} | {(b, a) for a, b in back if (a, b) in forward}
    pairs = {(named, anon) for named, anon in both if _anonymous(anon) and not _anonymous(named)}
    named_count: dict[str, int] = {}
    anon_count: dict[str, int] = {}
    for named, anon in pairs:
        named_count[named] = named_count.get(named, 0) + 1
        anon_count[anon] = anon_count.get(anon, 0) + 1
    return {anon: named for named, anon in pairs if named_count[named] == 1 and anon_count[anon] == 1}


def _anonymous(term: str) -> bool:
    return term.startswith("<") and is_skolem(term[1:-1])


def _is_copy(rule: Rule, names: dict[str, str]) -> bool:
    pair = _pair(rule)
    return rule.name == "cax-eqc1" and pair is not None and names.get(pair[1]) == pair[0]


def _copies_back(rule: Rule, names: dict[str, str]) -> bool:
    pair = _pair(rule)
    return pair is not None and names.get(pair[0]) == pair[1]


def _folded(rule: Rule, names: dict[str, str]) -> Rule:
    """The rule with every anonymous class of ``names`` replaced by its named equivalent."""
    def term(t: str) -> str:
        return names.get(t, t)

    def atoms(body: tuple[Atom, ...]) -> tuple[Atom, ...]:
        return tuple(Atom(a.s, a.p, term(a.o), a.aux and not (a.p == _TYPE and a.o in names)) for a in body)

    def conditions(cs: tuple[Condition, ...]) -> tuple[Condition, ...]:
        return tuple(_condition(c, names) for c in cs)

    mentioned = any(a.o in names for a in (*rule.body, *rule.written, *((rule.head,) if rule.head else ())))
    if not mentioned and not any(anon in c.text for c in rule.conditions for anon in names):
        return rule
    head = rule.head and Atom(rule.head.s, rule.head.p, term(rule.head.o), rule.head.aux)
    reads = frozenset(("t", names[k[1]]) if k[0] == "t" and k[1] in names else k for k in rule.filter_reads)
    return replace(rule, body=atoms(rule.body), head=head, conditions=conditions(rule.conditions), filter_reads=reads,
                   written=atoms(rule.written),
                   written_conditions=None if rule.written_conditions is None else conditions(rule.written_conditions))


def _condition(c: Condition, names: dict[str, str]) -> Condition:
    expression, written = c.expression, c.written
    for anon, named in names.items():
        expression, written = expression.replace(anon, named), written.replace(anon, named)
    return c if (expression, written) == (c.expression, c.written) else replace(c, expression=expression,
                                                                                written=written)


def equivalent_names(rules: list[Rule]) -> dict[str, str]:
    """The anonymous classes :func:`fold_equivalents` replaces, with their named equivalents (what
    the rows of a schema table held apart from the rules are renamed by)."""
    return _equivalents(rules)


def restriction_names(expressions: Iterable[Expr], kept: Iterable[NamedNode], rules: list[Rule],
                      implied: Mapping[tuple[str, str], frozenset[str]]) -> dict[str, str]:
    """Restriction → the named class equivalent to the one intersection it makes with a class it already
    implies (see the module): ``implied`` gives the classes of a property's subjects or objects in the
    closure (:func:`.implied.position_classes`); ``kept``, the nodes named outside the axioms."""
    names = _equivalents(rules)
    held = {sparql(node) for node in kept}
    found: dict[str, set[str]] = {}
    for e in expressions:
        named = names.get(sparql(e.node)) if e.kind == "and" and len(e.members) == 2 else None
        if named is None:
            continue
        for r, other in (e.members, e.members[::-1]):
            node = sparql(r.node)
            if node not in held and node != named and _implies(r, sparql(other.node), implied):
                found.setdefault(node, set()).add(named)
    return {node: next(iter(named)) for node, named in found.items() if len(named) == 1 and node not in names}


def _implies(r: Expr, other: str, implied: Mapping[tuple[str, str], frozenset[str]]) -> bool:
    """Whether every instance of restriction ``r`` is an instance of class ``other``: ``r`` asks for at
    least one value of its property, whose subjects (objects, for an inverse) are ``other``'s."""
    if r.is_named or r.prop is None or r.kind not in ("some", "min", "exact") or (r.kind != "some" and r.n < 1):
        return False
    position = ("o" if r.prop.inverse else "s", sparql(r.prop.iri))
    return other in implied.get(position, frozenset())


__all__ = ["equivalent_names", "fold_equivalents", "restriction_names"]
