"""compile_ontology: asserted graph → RuleSet (generic + OWL + SWRL rules)."""

from __future__ import annotations

import logging

from pyoxigraph import NamedNode

from ..store import Store
from .generic import generic_rules
from .guard import guard_rules
from .implied import simplify
from .model import TBoxReader
from .owl import OwlCompiler
from .rule import RuleSet
from .swrl import SwrlCompiler

logger = logging.getLogger("topostore.compile")


def compile_ontology(store: Store, graph: NamedNode) -> RuleSet:
    """All rules for the ontology in ``graph``.

    Raises :class:`~topostore.errors.RuleCompileError` naming the rule and atom
    when a SWRL rule or an axiom cannot be translated, or when a rule would be
    too large for the store to evaluate safely (:mod:`.guard`).  What the rules
    do not reason completely is in ``warnings`` (also logged).
    """
    reader = TBoxReader(store, graph)
    tbox = reader.read()
    swrl = SwrlCompiler(store, graph, reader)
    swrl_rules = swrl.compile()
    tbox.typed_expressions.extend(swrl.expressions)
    owl = OwlCompiler(tbox)
    rules = RuleSet()
    rules.add(generic_rules())
    rules.add(owl.compile())
    rules.add(swrl_rules)
    simplified = RuleSet()
    simplified.add(simplify(rules.rules))  # rules that differed only in implied atoms become one
    rules.rules = simplified.rules
    rules.named_classes = set(tbox.named_classes)
    rules.data_properties = set(tbox.data_properties)
    rules.object_properties = set(tbox.object_properties)
    rules.entailed_predicates = set(swrl.entailed_predicates)
    rules.warnings = list(owl.warnings)
    for warning in rules.warnings:
        logger.warning("%s", warning)
    guard_rules(rules)
    return rules
