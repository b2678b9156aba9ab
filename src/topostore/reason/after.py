"""What follows a compiled step on a store where every request is a round trip: one query for all.

After maintenance the reasoner asks five things: did a recursive component need more rounds than
the one request had, does a rule with a negated premise match now, may a consistency check match a
new fact, which entailed-only conclusions changed their standing, and which class memberships did
the step touch.  Each is a query of its own on the in-memory store (where a query costs
microseconds); on a remote store they are the branches of one SELECT, each tagged with ``?part``,
and what they lead to (the ENTAILED graph's changes, the scratch graphs dropped) waits in the
request queue for the next request.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from pyoxigraph import NamedNode, Triple

from ..rdf.terms import Term
from ..rdf.vocab import ASSERTED, AUX, ENTAILED, INFERRED, TYPE
from .component import UNSETTLED
from .entailed import ENTAILED_TYPE, internal, standing
from .scratch import NEW_FACTS, OVERDELETED


@dataclass
class After:
    """The answers of the after-step query."""

    unsettled: bool = False
    negated: bool = False
    violation_possible: bool = False
    #: triples to add to / drop from the ENTAILED graph
    entailed_add: list[Triple] = field(default_factory=list)
    entailed_drop: list[Triple] = field(default_factory=list)
    touched_types: list[tuple[Term, NamedNode]] = field(default_factory=list)


def _flag(part: str, where: str) -> str:
    """A branch giving one row tagged ``part`` when ``where`` has a solution."""
    return f'{{ SELECT ("{part}" AS ?part) WHERE {{\n{where}\n}} LIMIT 1 }}'


def touched_types(s: str, c: str) -> str:
    """The group binding ``s`` and ``c`` to every (individual, class) whose type fact, real or
    entailed-only, the last maintenance may have changed (its new-facts and over-deleted graphs)."""
    return (f"VALUES ?g {{ {NEW_FACTS} {OVERDELETED} }} VALUES ?q {{ {TYPE} {ENTAILED_TYPE} }} "
            f"GRAPH ?g {{ {s} ?q {c} }} FILTER(isIRI({c}))")


def query(negated: Sequence[str], checks: Sequence[str], entailed: Iterable[NamedNode], settle: bool) -> str:
    """The after-step SELECT: ``negated`` and ``checks`` are the groups of the negated-premise rules and
    of the semi-naive consistency checks (their UNIONs flag a match), ``entailed`` the predicates with
    entailed-only conclusions, ``settle`` whether to ask about unrolled rounds."""
    branches = []
    if settle:
        branches.append(_flag("u", f"GRAPH {UNSETTLED} {{ ?u1 ?u2 ?u3 }}"))
    if negated:
        branches.append(_flag("n", "\nUNION\n".join(negated)))
    if checks:
        branches.append(_flag("v", "\nUNION\n".join(checks)))
    for p in entailed:  # touched triples of p, real or internal form, and where each stands now
        q = internal(p)
        branches.append(
            f'{{ SELECT DISTINCT ("e" AS ?part) ?s ?o ("{p.value}" AS ?p) ?i ?n ?a ?e WHERE {{ '
            f"VALUES ?g {{ {NEW_FACTS} {OVERDELETED} }} VALUES ?q {{ {p} {q} }} GRAPH ?g {{ ?s ?q ?o }} "
            f"BIND(EXISTS {{ GRAPH {AUX} {{ ?s {q} ?o }} }} AS ?i) BIND(EXISTS {{ GRAPH {INFERRED} {{ ?s {p} ?o }} }} AS ?n) "
            f"BIND(EXISTS {{ GRAPH {ASSERTED} {{ ?s {p} ?o }} }} AS ?a) "
            f"BIND(EXISTS {{ GRAPH {ENTAILED} {{ ?s {p} ?o }} }} AS ?e) }} }}")
    branches.append(f'{{ SELECT DISTINCT ("t" AS ?part) ?s ?o WHERE {{ {touched_types("?s", "?o")} }} }}')
    graphs = f"FROM {ASSERTED} FROM {INFERRED} FROM {AUX} " + " ".join(
        f"FROM NAMED {g}" for g in (ASSERTED, INFERRED, AUX, ENTAILED, NEW_FACTS, OVERDELETED, UNSETTLED))
    return f"SELECT ?part ?s ?p ?o ?i ?n ?a ?e {graphs} WHERE {{\n" + "\nUNION\n".join(branches) + "\n}"


def _true(term) -> bool:
    return term is not None and term.value in ("true", "1")


def read(rows) -> After:
    """The answers from the query's rows."""
    out = After()
    for row in rows:
        part = row["part"].value
        if part == "u":
            out.unsettled = True
        elif part == "n":
            out.negated = True
        elif part == "v":
            out.violation_possible = True
        elif part == "t":
            out.touched_types.append((row["s"], row["o"]))
        else:
            t = Triple(row["s"], NamedNode(row["p"].value), row["o"])
            change = standing(*(_true(row[v]) for v in ("i", "n", "a", "e")))
            if change is not None:
                (out.entailed_add if change else out.entailed_drop).append(t)
    out.touched_types = list(dict.fromkeys(out.touched_types))
    return out


__all__ = ["After", "query", "read", "touched_types"]
