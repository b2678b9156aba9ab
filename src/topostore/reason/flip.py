"""Value replacements seen only through built-in comparisons: evaluate the flip, not the closure.

Why this exists
---------------
A robot step *replaces* values: ``now(Robot1)`` goes from t to t+5,
``visitedAt(R1)`` from v to t+5.  In the rules these values are only compared
(the Urgency rule's ``now - visitedAt > threshold``), never joined.  Plain
delete-and-rederive treats the old ``now`` as a deleted premise of *every*
URGENT fact, over-deletes them all and proves them again: the cost of a clock
tick follows the number of URGENT locations instead of the number of
locations whose urgency actually changes.

For a rule whose changed atoms read a value that occurs nowhere else in the
rule but in its filters, the matches in the old and in the new state have the
same shape; only the filter outcome can differ.  One query per rule therefore
finds exactly the heads whose derivation by that rule *flips*: it binds each
changed atom to the old and the new value at once (the old one from a scratch
graph of replaced facts) and keeps the bindings where the rule's filters
answer differently.  Lost heads become over-deletion candidates (they may
still hold through another derivation, which the usual proof decides);
gained heads are re-checked once the deletions are done and then seed the
ordinary semi-naive rounds.  An atom whose value is not even compared (e.g.
``visitedAt`` under a domain axiom) cannot flip at all and costs nothing.

Conditions, checked per REASON (anything else takes the ordinary path):

* a *clean replacement*: the change of ``(s, p)`` is one removed and one added
  fact, and ``s`` has exactly that one value of ``p`` afterwards;
* every change of ``p`` in the batch is clean, no rule that can fire derives
  ``p``, and ``p`` is not ``rdf:type``;
* the rule is monotone, reads nothing changed in its filters' graph patterns,
  and every body atom that reads a changed predicate is such an atom.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Iterable
from typing import NamedTuple

from pyoxigraph import Literal, NamedNode, Triple

from ..compile.condition import BIND, TEST
from ..compile.rule import Atom, Rule, join_order
from ..rdf.terms import sparql
from ..rdf.vocab import INTERNAL, TYPE
from .plan import nested

#: Old values of cleanly replaced facts (scratch; never visible to queries).
CHANGE_OLD = NamedNode(INTERNAL + "graph:flip-old")

_STRING = re.compile(r'"(?:[^"\\]|\\.)*"' + r"|'(?:[^'\\]|\\.)*'")
_VARIABLE = re.compile(r"\?(\w+)")


def _rename(text: str, names: Collection[str], suffix: str) -> str:
    """``text`` with the variables in ``names`` renamed ``?x`` → ``?x__suffix`` (not inside strings)."""
    def swap(m: re.Match) -> str:
        return f"?{m.group(1)}__{suffix}" if m.group(1) in names else m.group(0)

    out, last = [], 0
    for s in _STRING.finditer(text):
        out.append(_VARIABLE.sub(swap, text[last:s.start()]))
        out.append(s.group(0))
        last = s.end()
    out.append(_VARIABLE.sub(swap, text[last:]))
    return "".join(out)


#: the filter variables of a rule without filters (most rules: every rule per pair of disjoint classes)
_NONE: frozenset[str] = frozenset()


def filter_variables(rule: Rule) -> frozenset[str]:
    """Names (without ``?``) of the variables the filters mention."""
    if not rule.conditions:
        return _NONE
    return frozenset(v[1:] for c in rule.conditions for v in c.variables)


def plain_filters(rule: Rule) -> bool:
    """Filters made only of BIND and FILTER lines without graph patterns (no EXISTS)."""
    return all(c.plain for c in rule.conditions)


def compared_only(rule: Rule, j: int) -> bool:
    """Whether atom ``j``'s object is a variable the rule uses only in its filters (or not at all).

    A value a BIND computes from it (``swrlb:add(?w, ?v, 1)``, transitively) counts as the value itself:
    written in the head or joined in another atom, a new value makes another head, not the same head
    flipped, so such an atom is read by the ordinary delta (a value bound only to be compared, as the
    Urgency rule's ``?d`` of ``subtract(?d, ?h, ?v)``, still flips)."""
    atom = rule.body[j]
    if not atom.o.startswith("?") or not atom.p.startswith("<") or atom.p == str(TYPE) or atom.aux:
        return False
    if atom.o in (atom.s, atom.p):
        return False
    reached = _computed_from(rule, atom.o)
    if rule.head is not None and not reached.isdisjoint(rule.head.variables()):
        return False
    return all(reached.isdisjoint(other.variables()) for k, other in enumerate(rule.body) if k != j)


def _computed_from(rule: Rule, variable: str) -> set[str]:
    """``variable`` and every variable a BIND of ``rule`` computes from it, directly or through another."""
    reached = {variable}
    binds = [c for c in rule.conditions if c.kind == BIND and c.binds]
    grown = True
    while grown:
        grown = False
        for c in binds:
            if c.binds not in reached and not reached.isdisjoint(c.variables - {c.binds}):
                reached.add(c.binds)
                grown = True
    return reached


class Replacement(NamedTuple):
    """One clean replacement of the single value of ``(s, p)`` (a tuple: made for every replaced value
    of every step, where a frozen dataclass sets each field through ``object.__setattr__``)."""

    old: Triple
    new: Triple


def clean_replacements(added: Iterable[Triple], removed: Iterable[Triple], values_now) -> dict[str, list[Replacement]]:
    """Predicates (IRI text) all of whose changes in the batch are clean replacements.

    ``values_now(s, p)`` gives the current values of ``(s, p)`` in the asserted graph.  The definition:
    a REASON finds them in one pass, with the pairs known to hold one value (:func:`.kinds.replaced_in`).
    """
    return _clean(_by_pair(added, removed), lambda pair: values_now(*pair))


def _by_pair(added: Iterable[Triple], removed: Iterable[Triple]) -> dict[tuple, tuple[list[Triple], list[Triple]]]:
    """The added and the removed triples of each (subject, predicate)."""
    by_pair: dict[tuple, tuple[list[Triple], list[Triple]]] = {}
    for t in added:
        by_pair.setdefault((t.subject, t.predicate), ([], []))[0].append(t)
    for t in removed:
        by_pair.setdefault((t.subject, t.predicate), ([], []))[1].append(t)
    return by_pair


def _clean(by_pair: dict, values_now) -> dict[str, list[Replacement]]:
    """:func:`clean_replacements` of the changes ``by_pair`` (:func:`_by_pair`); ``values_now(pair)`` is
    asked only of a pair with one triple added and one removed."""
    clean: dict[str, list[Replacement]] = {}
    dirty: set[str] = set()
    for pair, (adds, rems) in by_pair.items():
        p = pair[1]
        key = f"<{p.value}>"
        if p == TYPE or len(adds) != 1 or len(rems) != 1 or len(values_now(pair)) != 1:
            dirty.add(key)
            continue
        clean.setdefault(key, []).append(Replacement(rems[0], adds[0]))
    return {p: pairs for p, pairs in clean.items() if p not in dirty}


_KIND_TEST = re.compile(r"^\s*!?\s*is(?:Literal|IRI|URI|Blank)\(\?\w+\)\s*$")


def kind_tests_only(rule: Rule, atoms: Iterable[int]) -> bool:
    """Whether the conditions on the values of ``atoms`` only test their kind (``isLiteral``, ``isIRI``,
    ``isBlank``, negated or not), as the filter an implied range atom leaves behind."""
    names = {rule.body[j].o for j in atoms}
    return all(c.kind == TEST and _KIND_TEST.match(c.expression) for c in rule.conditions if c.variables & names)


def same_kind(r: Replacement) -> bool:
    """Whether a replacement keeps the value's kind (IRI, blank node or literal): a kind test cannot flip."""
    return type(r.old.object) is type(r.new.object)


def flip_atoms(rule: Rule, clean: Collection[str], changed) -> tuple[int, ...] | None:
    """The rule's atoms on cleanly replaced values (``clean``: predicates as IRI text), when every atom
    ``changed(key)`` says is changed is one of them and compared only, and the rule's filters are plain
    and read nothing changed (else None): the atoms a flip evaluates instead of the ordinary delta."""
    if not plain_filters(rule) or any(changed(k) for k in rule.filter_reads):
        return None
    handled = []
    for j, atom in enumerate(rule.body):
        if not changed(atom.read_key()):
            continue
        if atom.p not in clean or not compared_only(rule, j):
            return None
        handled.append(j)
    return tuple(handled) or None


def flip_query(branches: Iterable[str]) -> str:
    """One SELECT over the branches of several rules: head ``?h0 ?h1 ?h2``, ``?rule``, ``?ok__n`` (true: gained)."""
    return "SELECT DISTINCT ?rule ?h0 ?h1 ?h2 ?ok__n WHERE {\n" + "\nUNION\n".join(branches) + "\n}"


def flip_branches(rule: Rule, changed: tuple[int, ...], lateral: bool, tag: int,
                  windows: dict[int, dict[int, list[Triple]]] | None = None, compact: bool = False) -> list[str]:
    """UNION branches finding the heads whose derivation by ``rule`` flips (``?rule`` = ``tag``).

    ``changed`` are the body atoms reading a replaced value (all compared only).
    One branch per changed atom starts from that atom's replaced facts; the
    changed atoms before it in ``changed`` are read with their new value only.
    A match whose changed atoms are the set C is thus evaluated exactly (old
    and new values paired) by the branch of the first atom of C; the other
    branches may give it a wrong row, which costs a proof or a re-check and
    never a wrong fact (see :meth:`IncrementalReasoner._flips`).  Callers put
    the atoms of the most frequent predicates first: a branch that joins them
    unbound then scans them without a look-up of the old value per fact.
    With ``lateral``, the other atoms follow in join order, each evaluated per
    solution so far, and the filters stand right after the atom that binds
    their last variable: only the bindings that flip reach the atoms after it.
    ``windows`` (per seed atom, per other atom: the facts in its window, see
    :mod:`.window`) restricts those atoms to the facts given, as a VALUES table.
    ``compact`` binds only ``?ok__n`` (no ``?rule``, no ``?h0``..``?h2``, each test written once
    per state inside one FILTER): for an update whose template is the head itself, where every
    BIND costs planning time (see :func:`compact_possible`).
    """
    renamed = {rule.body[k].o[1:] for k in changed}
    targets = {c.binds[1:] for c in rule.conditions if c.binds}
    renamed |= targets
    needed = {f"?{v}" for v in filter_variables(rule) - targets}
    head = rule.head
    if compact:
        tests = "\n  ".join(_compact_instances(rule, renamed))
    else:
        project = " ".join(f"BIND({term} AS ?h{i})" for i, term in enumerate((head.s, head.p, head.o)))
        tests = "\n  ".join(_instances(rule, renamed) + [project, f"BIND({tag} AS ?rule)"])
    branches = []
    for position, k in enumerate(changed):
        seed = rule.body[k]
        settled = set(changed[:position])
        start = [f"GRAPH {CHANGE_OLD} {{ {seed.s} {seed.p} {_rename(seed.o, renamed, 'o')} }}",
                 f"{seed.s} {seed.p} {_rename(seed.o, renamed, 'n')} ."]
        windowed = (windows or {}).get(k, {})
        order = [m for m in join_order(rule.body, k) if m != k]
        if windowed:  # the windowed atoms first: a few facts, looked up by value
            order = sorted(order, key=lambda m: m not in windowed)
        rest = [_settled_atom(rule.body[m], renamed) if m in settled
                else _paired_atom(rule.body[m], renamed) if m in changed else rule.atom_text(m) for m in order]
        rest = [_values(rule.body[m], windowed[m], renamed if m in settled else set()) + " " + text
                if m in windowed else text for m, text in zip(order, rest)]
        if lateral:
            bound = set(seed.variables())
            at = 0
            while not needed <= bound and at < len(order):
                bound |= rule.body[order[at]].variables()
                at += 1
            body = "\n  ".join(start + rest[:at] + [tests]) if at == 0 else "\n  ".join(start)
            levels = rest[:at - 1] + [rest[at - 1] + "\n  " + tests] + rest[at:] if at else rest
            body += nested(levels, "")
        else:
            body = "\n  ".join(start + rest + [tests])
        branches.append("{\n  " + body + "\n}")
    return branches


def _values(atom: Atom, facts: list[Triple], renamed: set[str]) -> str:
    """A VALUES table binding the atom's variables to ``facts`` (its object renamed ``__n`` when settled)."""
    columns = [(term, i) for i, term in enumerate((atom.s, atom.o)) if term.startswith("?")]
    names = [_rename(term, renamed, "n") for term, _ in columns]
    rows = " ".join("(" + " ".join(sparql(t.subject if i == 0 else t.object) for _, i in columns) + ")"
                    for t in facts)
    return f"VALUES ({' '.join(names)}) {{ {rows} }}"


def _paired_atom(atom: Atom, renamed: set[str]) -> str:
    """Another changed atom: its new value from the store, its old one from CHANGE_OLD if replaced."""
    new, old, probe = (_rename(atom.o, renamed, x) for x in ("n", "o", "o0"))
    return (f"{atom.s} {atom.p} {new} . OPTIONAL {{ GRAPH {CHANGE_OLD} {{ {atom.s} {atom.p} {probe} }} }} "
            f"BIND(COALESCE({probe}, {new}) AS {old})")


def _settled_atom(atom: Atom, renamed: set[str]) -> str:
    """A changed atom that an earlier branch pairs: read with its new value as the old one too."""
    new, old = (_rename(atom.o, renamed, x) for x in ("n", "o"))
    return f"{atom.s} {atom.p} {new} . BIND({new} AS {old})"


def _instances(rule: Rule, renamed: set[str]) -> list[str]:
    """The filters evaluated for the old (``__o``) and new (``__n``) values, and their difference."""
    out = []
    for suffix in ("o", "n"):
        tests = []
        for i, condition in enumerate(rule.conditions):  # plain: tests and BINDs only
            if condition.kind == TEST:
                tests.append(f"?f{i}__{suffix}")
                expression = _rename(condition.expression, renamed, suffix)
                out.append(f"BIND(COALESCE(({expression}), false) AS ?f{i}__{suffix})")
            else:
                out.append(_rename(condition.text, renamed, suffix))
        out.append(f"BIND(({' && '.join(tests) or 'true'}) AS ?ok__{suffix})")
    out.append("FILTER(?ok__o != ?ok__n)")
    return out


def _compact_instances(rule: Rule, renamed: set[str]) -> list[str]:
    """The rule's BINDs for the old and new values, then its tests once per state: ``?ok__n`` and
    the FILTER keeping the bindings whose answer differs."""
    out = []
    tests: dict[str, list[str]] = {"o": [], "n": []}
    for suffix in ("o", "n"):
        for condition in rule.conditions:  # plain: tests and BINDs only
            if condition.kind == TEST:
                tests[suffix].append(f"COALESCE(({_rename(condition.expression, renamed, suffix)}), false)")
            else:
                out.append(_rename(condition.text, renamed, suffix))
    out.append(f"BIND(({' && '.join(tests['n']) or 'true'}) AS ?ok__n)")
    out.append(f"FILTER(({' && '.join(tests['o']) or 'true'}) != ?ok__n)")
    return out


def compact_possible(rule: Rule, changed: tuple[int, ...]) -> bool:
    """Whether the head names no value the flip renames (a compared value or a BIND's result), so an
    update can write the head as it stands."""
    renamed = {rule.body[k].o for k in changed} | {c.binds for c in rule.conditions if c.binds}
    return not (rule.head.variables() & renamed)


def head_triple(row) -> Triple:
    return Triple(row["h0"], row["h1"], row["h2"])


def gained(row) -> bool:
    """Whether the row's head became derivable (``?ok__n`` true; some servers answer booleans as 1/0)."""
    ok = row["ok__n"]
    return isinstance(ok, Literal) and ok.value in ("true", "1")


__all__ = ["CHANGE_OLD", "Replacement", "clean_replacements", "compact_possible", "compared_only", "filter_variables",
           "flip_atoms", "flip_branches", "flip_query", "gained", "head_triple", "kind_tests_only", "plain_filters",
           "same_kind"]
