"""compile_ontology: asserted graph → RuleSet (generic + OWL + SWRL rules)."""

from __future__ import annotations

from collections.abc import Collection

from pyoxigraph import NamedNode

from ..rdf.terms import Term
from ..stores.base import Store
from .alike import kept_nodes, merge_alike
from .datatypes import range_rules
from .disjointness import Disjointness
from .fold import equivalent_names, fold_equivalents, restriction_names
from .generic import generic_rules
from .guard import guard_rules
from .implied import position_classes, simplify
from .inline_difference import MAX_DISJOINT_SOURCES, inline_difference, owl_asks
from .key_form import key_rule_form, one_member_list
from .owl import OwlCompiler
from .owl_extras import (
    existential_domain_rules,
    key_rules,
    reflexive_rules,
    restriction_rules,
    thing_rules,
    unsatisfiable_rules,
)
from .profile import all_uses, profile
from .range_values import empty_range_rules
from .rule import Rule, RuleSet
from .schema_tables import hold_tables
from .simple_properties import ignore_non_simple
from .swrl import SwrlCompiler
from .tbox_reader import TBoxReader
from .unsatisfiable import unsatisfiable


def compile_ontology(store: Store, graph: NamedNode, refuse: Collection[Term] = ()) -> RuleSet:
    """All rules for the ontology in ``graph``.

    A SWRL rule that cannot be translated is set aside with a notice naming it and why, unless it is one of
    ``refuse`` (its ``swrl:Imp`` node): then, as when a rule would be too large for the store to evaluate
    safely (:mod:`.guard`), :class:`~topostore.errors.RuleCompileError` is raised naming the rule and atom.
    What the rules do not reason completely is in ``notices`` (published at LOAD, see
    :mod:`topostore.compile.notices`).
    """
    reader = TBoxReader(store, graph)
    tbox = reader.read()
    swrl = SwrlCompiler(store, graph, reader.classes, refuse)
    swrl_rules = swrl.compile()
    tbox.typed_expressions.extend(swrl.expressions)
    merge_alike(tbox)  # after the SWRL rules: the expressions they name are kept
    owl = OwlCompiler(tbox)
    ignore_non_simple(tbox, owl.all_expressions())  # before any rule is made: as Pellet, not as written
    rules = RuleSet(one_list=one_member_list(store, graph))
    rules.add(key_rule_form(generic_rules(), rules.one_list))
    rules.add(owl.compile())
    rules.add(key_rules(tbox))
    rules.add(reflexive_rules(tbox))
    rules.add(thing_rules(tbox, owl.all_expressions()))
    rules.add(range_rules(tbox))
    rules.add(empty_range_rules(owl.all_expressions()))
    rules.add(restriction_rules(owl))
    rules.add(existential_domain_rules(owl, all_uses(tbox, swrl.used_as)))
    rules.add(unsatisfiable_rules(owl))
    empty_classes, undecided = unsatisfiable(owl)
    rules.add(empty_classes)
    rules.notices += profile(store, graph, tbox, owl, swrl.used_as, swrl.uses_difference)
    rules.notices += undecided
    rules.add(swrl_rules)
    rules.add(swrl.query_rules)
    rules.queries = dict(swrl.queries)
    rules.notices += swrl.notices
    # what the axioms imply of a property's terms: a DL-safe SWRL rule says nothing of a value only known to exist
    axioms = position_classes([r for r in rules.rules if not r.name.startswith("swrl:")])
    more = restriction_names(owl.all_expressions(), kept_nodes(tbox), rules.rules, axioms)
    disjointness = owl.disjointness.renamed({**equivalent_names(rules.rules), **more})
    rules.disjointness = disjointness if len(disjointness) else None
    rules.rules = fold_equivalents(rules.rules, more)  # before the joins: they then see the named classes
    rules.rules = inline_difference(rules.rules, swrl.asks + owl_asks(rules.rules), *_disjoint_sources(disjointness))
    simplified = RuleSet()
    simplified.add(simplify(rules.rules))  # rules that differed only in implied atoms become one
    rules.rules = simplified.rules
    rules.named_classes = set(tbox.named_classes)
    rules.data_properties = set(tbox.data_properties)
    rules.object_properties = set(tbox.object_properties)
    rules.entailed_predicates = set(swrl.entailed_predicates)
    rules.notices += owl.notices
    guard_rules(rules)
    rules.rules, rules.tables = hold_tables(rules.rules)  # one generic rule per file of rules/owl/
    return rules


def _disjoint_sources(disjointness: Disjointness) -> tuple[list[Rule] | None, int]:
    """The ``different-disjoint`` rules :func:`.inline_difference.inline_difference` may join, and how
    many rows there are (past :data:`.inline_difference.MAX_DISJOINT_SOURCES` none is made)."""
    count = len(disjointness.different)
    return (disjointness.rules()[0] if count <= MAX_DISJOINT_SOURCES else None), count
