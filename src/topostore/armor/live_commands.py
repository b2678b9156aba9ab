"""aRMOR-style commands beyond aRMOR: explanations and SWRL rules at run time.

======================  ==============================  =========================================
key                     args                            reply
======================  ==============================  =========================================
``QUERY EXPLAIN –``     ``[subject, predicate, object]``  the derivation tree, one line per node
                                                         (two spaces of indent per level)
``QUERY EXPLAIN JSON``  ``[subject, predicate, object]``  one string: the tree as JSON
``ADD SWRL –``          ``[label, rule]`` or             adds the rule (Protégé syntax, e.g.
                        ``[label, rule, comment]``       ``LOCATION(?l) ^ … -> URGENT(?l)``)
``REMOVE SWRL –``       ``[label]``                      removes the rule(s) with that label
``QUERY SWRL –``        ``[]``                           labels of the SWRL rules, sorted
======================  ==============================  =========================================

``ADD SWRL`` checks the rule at once (parse and compile against the current
ontology): a rule that cannot compile is refused with 208 and a message naming
the atom, and nothing changes.  Both SWRL manipulations follow the
reference's buffering like every other manipulation.  (aRMOR's own ``SWRL``
key is undefined and still answers 205.)
"""

from __future__ import annotations

import json

from ..compile.pipeline import compile_ontology
from ..compile.swrl_text import removal_triples, rule_labels, rule_triples, rules_among
from ..errors import InvalidNameError, RuleCompileError, TopostoreError
from ..ontology.explain import resolve_triple
from ..rdf.vocab import ASSERTED
from ..stores import memory_store
from . import codes
from .codes import CommandError
from .context import Command, Context, Reply, fixed
from .reference import Change, Delta


def _explanation(ctx: Context):
    try:
        s, p, o = resolve_triple(ctx.onto, *ctx.args[:3])
    except (InvalidNameError, ValueError) as exc:
        raise CommandError(codes.INVALID_ARGUMENT, f"cannot read the triple: {exc}") from None
    try:
        return ctx.onto.explain(s, p, o)
    except TopostoreError as exc:  # a rule query failed or ran out of time
        raise CommandError(codes.REASONER_OR_QUERY_FAILURE, f"explanation failed: {exc}") from exc


def query_explain(ctx: Context) -> Reply:
    """QUERY EXPLAIN: why the triple holds, as indented lines (first line: the triple and its rule)."""
    return Reply(queried_objects=_explanation(ctx).lines())


def query_explain_json(ctx: Context) -> Reply:
    return Reply(queried_objects=[json.dumps(_explanation(ctx).to_dict(), ensure_ascii=False)])


def add_swrl(ctx: Context) -> Reply:
    """ADD SWRL: parse and compile the rule now (refused with 208 naming the atom), add it as a manipulation."""
    label, text = ctx.args[0], ctx.args[1]
    comment = ctx.args[2] if len(ctx.args) > 2 and ctx.args[2] else None
    onto = ctx.onto
    try:
        triples = rule_triples(text, label, onto.store, onto.prefix, comment)
        scratch = memory_store()
        scratch.add(onto.store.triples(graph=ASSERTED), ASSERTED)
        scratch.add(triples, ASSERTED)
        compile_ontology(scratch, ASSERTED, refuse=rules_among(triples))
    except (RuleCompileError, InvalidNameError) as exc:
        raise CommandError(codes.INVALID_ARGUMENT, f"SWRL rule {label!r} refused: {exc}") from None
    return ctx.submit(fixed("ADD SWRL", add=triples))


def remove_swrl(ctx: Context) -> Reply:
    """REMOVE SWRL: the rule's triples are found when the change is applied (buffering)."""
    label = ctx.args[0]
    if label not in rule_labels(ctx.onto.store):
        raise CommandError(codes.INVALID_ARGUMENT, f"no SWRL rule labelled {label!r} "
                           f"(rules: {', '.join(rule_labels(ctx.onto.store)) or 'none'})")

    def plan(onto) -> Delta:
        try:
            return Delta(remove=removal_triples(onto.store, label))
        except RuleCompileError as exc:  # removed meanwhile (buffered twice)
            return Delta(warning=str(exc))

    return ctx.submit(Change("REMOVE SWRL", plan))


def query_swrl(ctx: Context) -> Reply:
    return Reply(queried_objects=rule_labels(ctx.onto.store))


def live_commands() -> dict[tuple[str, str, str], Command]:
    m = dict(needs_ref=True, manipulation=True)
    q = dict(needs_ref=True, manipulation=False)
    triple = ("subject", "predicate", "object")
    return {
        ("QUERY", "EXPLAIN", ""): Command(query_explain, triple, 3, 3, **q),
        ("QUERY", "EXPLAIN", "JSON"): Command(query_explain_json, triple, 3, 3, **q),
        ("ADD", "SWRL", ""): Command(add_swrl, ("label", "rule", "comment"), 2, 3, **m),
        ("REMOVE", "SWRL", ""): Command(remove_swrl, ("label",), 1, 1, **m),
        ("QUERY", "SWRL", ""): Command(query_swrl, (), 0, 0, **q),
    }


__all__ = ["live_commands"]
