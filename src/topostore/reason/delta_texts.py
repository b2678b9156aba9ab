"""The SPARQL operations of the compiled step (:mod:`.program`, :mod:`.component`), one function each.

Every text reads one small graph first (a change, the candidates, a round's new facts) and the
rest of the rule per solution (:func:`.plan.plan_where`), so that its cost follows the change.
"""

from __future__ import annotations

from collections.abc import Iterable

from pyoxigraph import NamedNode

from ..compile.rule import ReadKey, Rule
from ..rdf.vocab import ASSERTED, AUX, INFERRED, INTERNAL, TYPE
from . import flip
from .plan import plan_where
from .scratch import ADDED, CANDIDATES, FLIP_GAINED, OVERDELETED, REMOVED, dataset, target

#: heads a rule still derives from the new state (the recheck's answer)
KEEP = NamedNode(INTERNAL + "graph:inc-keep")
#: heads whose derivation by a flipped comparison turned false
FLIP_LOST = NamedNode(INTERNAL + "graph:inc-flip-lost")

#: the graphs rules read, after the change / before it (its removed facts included)
NEW_STATE = (ASSERTED, INFERRED, AUX)
OLD_STATE = (ASSERTED, INFERRED, AUX, OVERDELETED)

_TYPE = str(TYPE)


def pattern(key: ReadKey) -> str:
    """The triple pattern of a key's facts (``?s ?o`` for the terms)."""
    return f"?s {_TYPE} {key[1]} ." if key[0] == "t" else f"?s {key[1]} ?o ."


def _into(head: str, graphs: Iterable[NamedNode]) -> str:
    return " ".join(f"GRAPH {g} {{ {head} }}" for g in graphs)


def candidates(flat: Rule, j: int, delta: NamedNode, lateral: bool, exclude: Iterable[NamedNode] = (),
               not_added: Iterable[int] = ()) -> str:
    """Heads present now that ``flat`` derived in the old state with atom ``j`` on ``delta`` (removed
    facts) go to CANDIDATES; not those in the ``exclude`` graphs.  ``flat`` reads its helper atoms from
    the default graph, whose old state includes OVERDELETED.  The atoms ``not_added`` (on predicates
    only asserted, never derived) leave out the facts just added: for them the old state is exact, so
    that a replaced value is not paired with its successor (a self-join over a replaced value)."""
    head = flat.head.text()
    where = plan_where(flat, j, delta, lateral=lateral)
    graph = target(flat)
    skip = "".join(f"\n  FILTER NOT EXISTS {{ GRAPH {g} {{ {head} }} }}" for g in exclude)
    skip += "".join(f"\n  FILTER NOT EXISTS {{ GRAPH {ADDED} {{ {flat.body[k].text()} }} }}" for k in not_added)
    named = (delta, graph, *exclude, *((ADDED,) if not_added else ()))
    return (f"INSERT {{ GRAPH {CANDIDATES} {{ {head} }} }}\n{dataset(OLD_STATE, named)}\n"
            f"WHERE {{\n  {where}\n  FILTER EXISTS {{ GRAPH {graph} {{ {head} }} }}{skip}\n}}")


def keep(rule: Rule, lateral: bool) -> str:
    """Mark the candidates that ``rule`` derives from the new state."""
    where = plan_where(rule, head_graph=CANDIDATES, lateral=lateral)
    return (f"INSERT {{ GRAPH {KEEP} {{ {rule.head.text()} }} }}\n{dataset(NEW_STATE, (AUX, CANDIDATES))}\n"
            f"WHERE {{\n  {where}\n}}")


def _asserted_premise(rule: Rule) -> str:
    """The one premise of ``rule`` read from the asserted graph (a rule restating it, see :mod:`.restate`)."""
    return f"GRAPH {ASSERTED} {{ {rule.body[0].text()} }}"


def keep_asserted(rule: Rule) -> str:
    """Mark the candidates that ``rule`` (one premise) derives from asserted facts (see :mod:`.restate`)."""
    head = rule.head.text()
    return (f"INSERT {{ GRAPH {KEEP} {{ {head} }} }} WHERE {{ GRAPH {CANDIDATES} {{ {head} }} "
            f"{_asserted_premise(rule)} }}")


def rederive_asserted(rule: Rule, delta: NamedNode, into: Iterable[NamedNode]) -> str:
    """Heads in ``delta`` that ``rule`` (one premise) derives from asserted facts, not known yet, into
    the graphs ``into`` (see :mod:`.restate`)."""
    head = rule.head.text()
    return (f"INSERT {{ {_into(head, into)} }}\n{dataset(NEW_STATE, (delta, ASSERTED))}\n"
            f"WHERE {{ GRAPH {delta} {{ {head} }} {_asserted_premise(rule)} "
            f"FILTER NOT EXISTS {{ {head} }} }}")


def additions(rule: Rule, j: int | None, delta: NamedNode, into: Iterable[NamedNode], lateral: bool) -> str:
    """Heads ``rule`` derives now with atom ``j`` on ``delta`` (or, with ``j`` None, the heads in
    ``delta`` it derives now), not known yet, into the graphs ``into``."""
    head = rule.head.text()
    if j is None:
        where = plan_where(rule, head_graph=delta, lateral=lateral)
    else:
        where = plan_where(rule, j, delta, lateral=lateral)
    return (f"INSERT {{ {_into(head, into)} }}\n{dataset(NEW_STATE, (AUX, delta))}\nWHERE {{\n  {where}\n"
            f"  FILTER NOT EXISTS {{ {head} }}\n}}")


def flips(rule: Rule, order: tuple[int, ...], lateral: bool, tag: int, windows: dict | None = None,
          seeded: bool = False) -> str:
    """The heads whose derivation by ``rule`` flips with the replaced values (see :mod:`.flip`) go to
    FLIP_GAINED or FLIP_LOST; ``windows`` narrows compared atoms to the facts in a value window.
    ``seeded``: only the branch of the first atom of ``order``, the others paired (exact where every
    fact of that atom's predicate was replaced: every match starts from a replaced fact)."""
    compact = flip.compact_possible(rule, order)
    branches = flip.flip_branches(rule, order, lateral, tag, windows, compact=compact)
    if seeded:
        branches = branches[:1]
    template = rule.head.text() if compact else "?h0 ?h1 ?h2"
    return (f"INSERT {{ GRAPH ?flip {{ {template} }} }}\n{dataset(NEW_STATE, (AUX, flip.CHANGE_OLD))}\n"
            "WHERE {\n  {\n" + "\nUNION\n".join(branches)
            + f"\n  }}\n  BIND(IF(?ok__n, {FLIP_GAINED}, {FLIP_LOST}) AS ?flip)\n}}")


def lost(key: ReadKey, graph: NamedNode) -> str:
    """Flipped-false heads of ``key`` that are present become candidates."""
    p = pattern(key)
    return f"INSERT {{ GRAPH {CANDIDATES} {{ {p} }} }} WHERE {{ GRAPH {FLIP_LOST} {{ {p} }} GRAPH {graph} {{ {p} }} }}"


def gained(key: ReadKey, into: Iterable[NamedNode]) -> str:
    """Flipped-true heads of ``key`` not known yet, into the graphs ``into``."""
    p = pattern(key)
    return (f"INSERT {{ {_into(p, into)} }} {dataset(NEW_STATE, (FLIP_GAINED,))} "
            f"WHERE {{ GRAPH {FLIP_GAINED} {{ {p} }} FILTER NOT EXISTS {{ {p} }} }}")


def _unconfirmed(p: str) -> str:
    """The candidates of pattern ``p`` no rule confirmed and not asserted."""
    return (f"GRAPH {CANDIDATES} {{ {p} }} FILTER NOT EXISTS {{ GRAPH {KEEP} {{ {p} }} }} "
            f"FILTER NOT EXISTS {{ GRAPH {ASSERTED} {{ {p} }} }}")


def recheck(key: ReadKey, graph: NamedNode) -> str:
    """The candidates of ``key`` no rule confirmed leave ``graph`` and join OVERDELETED (the key's
    removed facts for the keys downstream)."""
    p = pattern(key)
    return (f"DELETE {{ GRAPH {graph} {{ {p} }} }} INSERT {{ GRAPH {OVERDELETED} {{ {p} }} }} "
            f"WHERE {{ {_unconfirmed(p)} }}")


def recheck_one(rule: Rule, graph: NamedNode, asserted_premise: bool) -> str:
    """:func:`recheck` for a key with one prover: the candidates ``rule`` does not derive from the new
    state (``asserted_premise``: from its premise's asserted facts, see :mod:`.restate`) and that are
    not asserted leave ``graph`` and join OVERDELETED (one operation instead of a KEEP and a deletion)."""
    head = rule.head.text()
    proof = _asserted_premise(rule) if asserted_premise else rule.where()
    return (f"DELETE {{ GRAPH {graph} {{ {head} }} }} INSERT {{ GRAPH {OVERDELETED} {{ {head} }} }}\n"
            f"{dataset(NEW_STATE, (AUX, CANDIDATES, ASSERTED))}\n"
            f"WHERE {{ GRAPH {CANDIDATES} {{ {head} }} FILTER NOT EXISTS {{ {proof} }} "
            f"FILTER NOT EXISTS {{ GRAPH {ASSERTED} {{ {head} }} }} }}")


def restore(key: ReadKey, graph: NamedNode) -> str:
    """A removed asserted fact of ``key`` that a rule still derives stays, as inferred in ``graph``."""
    p = pattern(key)
    return (f"DELETE {{ GRAPH {OVERDELETED} {{ {p} }} }} INSERT {{ GRAPH {graph} {{ {p} }} }} "
            f"WHERE {{ GRAPH {REMOVED} {{ {p} }} GRAPH {KEEP} {{ {p} }} }}")


def over_delete(key: ReadKey, over: NamedNode, over_next: NamedNode) -> str:
    """The candidates of ``key`` no rule confirmed, not over-deleted yet, join ``over`` and ``over_next``
    (DRed inside a recursive component)."""
    p = pattern(key)
    return (f"INSERT {{ GRAPH {over} {{ {p} }} GRAPH {over_next} {{ {p} }} }} "
            f"WHERE {{ {_unconfirmed(p)} FILTER NOT EXISTS {{ GRAPH {over} {{ {p} }} }} }}")


def delete(key: ReadKey, over: NamedNode, graph: NamedNode) -> str:
    """The over-deleted facts of ``key`` leave ``graph`` and join OVERDELETED."""
    p = pattern(key)
    return (f"DELETE {{ GRAPH {graph} {{ {p} }} }} INSERT {{ GRAPH {OVERDELETED} {{ {p} }} }} "
            f"WHERE {{ GRAPH {over} {{ {p} }} }}")


def copy(key: ReadKey, source: NamedNode, into: Iterable[NamedNode]) -> str:
    """The facts of ``key`` in ``source`` into the graphs ``into``."""
    p = pattern(key)
    return f"INSERT {{ {_into(p, into)} }} WHERE {{ GRAPH {source} {{ {p} }} }}"


__all__ = ["FLIP_LOST", "KEEP", "NEW_STATE", "OLD_STATE", "additions", "candidates", "copy", "delete", "flips",
           "gained", "keep", "lost", "over_delete", "pattern", "recheck", "recheck_one", "restore"]
