"""The text of one rule evaluation: the SPARQL INSERT a round or a pass sends, and its forms.

A rule is evaluated on the whole data or with one atom on the delta, planned per delta fact or not,
into the NEW_* graphs or straight into its final graph and the next delta (a full run), with its
known heads kept out by a look-up per solution or by one anti-join, projected on its head first
where that pays, or as one with the other rules concluding the same class.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from pyoxigraph import NamedNode

from ..compile.rule import ReadKey, Rule
from ..compile.schema import schema_dataset
from ..rdf.vocab import ASSERTED, AUX, DELTA, INFERRED, NEW_AUX, NEW_INFERRED
from .class_unions import union_where
from .key_pairs import grouped_form
from .one_group import without_group_tests
from .order import TYPE_KEY
from .plan import plan_where

DATASET = f"USING {ASSERTED} USING {INFERRED} USING {AUX} USING NAMED {AUX} USING NAMED {DELTA}"


def insert_text(rule: Rule, delta_index: int | None = None, planned: bool = False, lateral: bool = True,
                direct: tuple[NamedNode, NamedNode | None] | None = None,
                graphs: Mapping[ReadKey, NamedNode] | None = None, derived: bool = False,
                union: Sequence[Rule] = (), few: bool = False, one_group: bool = False, bare: bool = False) -> str:
    """The INSERT evaluating ``rule`` (atom ``delta_index`` on the delta) into NEW_*.

    ``planned`` uses :func:`.plan.plan_where` for delta evaluations (delta atom
    first, rest per delta fact), whose cost follows the delta rather than the data.
    ``direct`` = (delta read, next delta) writes the head into its final graph and into the
    next delta (None: no delta) instead of NEW_* (the full run's rounds, see :meth:`.materialize.Materializer.run`).
    ``graphs``: the one graph holding each of some read keys (:func:`.order.single_graphs`), read
    there instead of in the whole default dataset (unplanned evaluations only).  ``derived``: the
    head's key already has derived facts, which a rule without delta keeps out too.  ``union``: rules
    concluding the same class, evaluated with ``rule`` as one (:mod:`.class_unions`; no delta).
    ``few``: the evaluation has few solutions against a large head extent (:func:`.few_solutions.few_solutions`),
    so the heads known are kept out by a look-up per solution instead of reading the extent.
    ``one_group``: every AllDifferent key is of one group (:func:`.one_group.one_group`; no delta), so the
    "two keys of one group" tests are left out.  ``bare``: a full run's evaluation without delta whose
    head's key has no fact in any graph, neither derived nor queued nor asserted (checked by the caller,
    :meth:`.materialize.Materializer.bare`; the asserted graph does not change during the run), so no
    known head is kept out: the anti-join would remove nothing and still costs a hash look-up per match
    (the 200,000 AllDifferent keys at 100,000 locations: 8 %).
    """
    final = AUX if rule.head_aux() else INFERRED
    target = NEW_AUX if rule.head_aux() else NEW_INFERRED
    head = rule.head.text()
    delta = DELTA if direct is None else direct[0]
    small = planned and delta_index is not None and lateral
    pair = grouped_form(rule) if direct is not None and delta_index is None else None
    if one_group and pair is None and not union and delta_index is None:
        rule = without_group_tests(rule) or rule
    if planned and delta_index is not None:
        where = plan_where(rule, delta_index, delta, lateral=lateral)
    else:
        where = rule.where(delta_index, str(delta), graphs)
    if union:
        where = union_where((rule, *union), graphs)
    elif pair is not None:
        where = pair.where(graphs, one_group)
    elif direct is not None and delta_index is None and distinct_pays(rule):
        where = f"{{ SELECT DISTINCT {' '.join(sorted(rule.head.variables()))} WHERE {{\n  {where}\n  }} }}"
    into = f"GRAPH {target} {{ {head} }}" if direct is None else f"GRAPH {final} {{ {head} }}"
    if direct is not None and direct[1] is not None:
        into += f" GRAPH {direct[1]} {{ {head} }}"
    dataset = (DATASET if direct is None else DATASET.replace(str(DELTA), str(delta))) + schema_dataset(rule)
    named = {graphs[a.read_key()] for r in (rule, *union) for a in r.body
             if not a.aux and a.read_key() in graphs} if graphs else set()
    named -= {AUX, delta}
    known = new_only(rule, small or few)
    if direct is not None and direct[1] is None and not derived:
        # no delta and no derived fact of the head's key yet: only the asserted facts are kept out
        # (an inferred fact is never an asserted one); once another rule derived facts of the key,
        # writing them again costs more than the anti-join (a write looks up six indexes)
        known = new_only(rule, small or few, ASSERTED)
        named.add(ASSERTED)
    if bare and delta_index is None:
        known = ""
    dataset += "".join(f" USING NAMED {g}" for g in sorted(named, key=str))
    return f"INSERT {{ {into} }}\n{dataset}\nWHERE {{\n  {where}\n  {known}\n}}"


def distinct_pays(rule: Rule) -> bool:
    """Whether a full run's evaluation of ``rule`` without delta projects its matches on the head first.

    A class head on one variable from a body with more (a domain ``p(x, y) ⟹ C(x)``, a restriction
    ``p(x, y1) ∧ p(x, y2) ∧ … ⟹ R(x)``) matches once per value: writing a membership again looks
    up six indexes, hashing it away costs less (10,000 locations: ≥2 hasDoor 205 → 185 ms, ∃hasDoor
    65 → 47 ms).  Where each match is a new head (two-variable heads such as a difference by
    values) the hashing only costs (158 → 183 ms), so they keep the plain form.
    """
    head = rule.head
    return (head is not None and head.p == TYPE_KEY and not head.o.startswith("?")
            and len(head.variables()) == 1 and len({v for a in rule.body for v in a.variables()} | set(rule.binds)) > 1)


def new_only(rule: Rule, small: bool, graph: NamedNode | None = None) -> str:
    """The line that keeps the heads already known out of an evaluation.

    ``FILTER NOT EXISTS`` is a look-up per solution (≈ 9 µs each in Oxigraph), right for a small
    delta; ``MINUS`` reads the head's facts once and anti-joins them (a rule over 10,000 facts:
    9 ms instead of 92 ms).  Both mean the same when the head has a variable, which every solution
    binds (a rule's head variables come from its body); a ground head keeps ``NOT EXISTS``, as
    ``MINUS`` with no shared variable removes nothing.  ``graph`` looks in that graph only.
    """
    head = rule.head.text() if graph is None else f"GRAPH {graph} {{ {rule.head.text()} }}"
    if small or not rule.head.variables():
        return f"FILTER NOT EXISTS {{ {head} }}"
    return f"MINUS {{ {head} }}"
