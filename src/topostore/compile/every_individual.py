"""Rules whose conclusion holds of every individual, typed or not (``x p x`` for a reflexive ``p``,
``x ∈ C`` for ``owl:Thing ⊑ C``, ``x ∉ C`` for an expression with no instance).

Why a module of its own: OWL has no fact saying "x is an individual", so each such rule is one rule per
way a node shows up as one, and both the positive rules (:mod:`.owl_extras`) and the negative ones
(:mod:`.negation`) need the same set."""

from __future__ import annotations

from ..rdf.vocab import (
    DECLARATION_TYPES,
    DIFFERENT_FROM,
    DIFFERENT_KEY_OF,
    INTERNAL,
    NAMED_INDIVIDUAL,
    OWL,
    RDF,
    RDFS,
    SAME_AS,
    SWRL,
    TYPE,
)
from . import condition as cond
from .rule import Atom, Rule


def _not_schema(var: str) -> str:
    """SPARQL test: ``var`` is no RDF, RDFS, OWL, SWRL or internal IRI."""
    return " && ".join(f'!STRSTARTS(STR({var}), "{ns}")' for ns in (RDF, RDFS, OWL, SWRL, INTERNAL))


def for_every_individual(name: str, origin: str, head: Atom) -> list[Rule]:
    """``head`` (about ``?x``) for every individual ``?x``: every node typed with a class (not a
    declaration such as ``owl:Class``), or linked by a property of the ontology (not a schema one)."""
    declarations = ", ".join(f"<{t}>" for t in sorted(DECLARATION_TYPES) if t != NAMED_INDIVIDUAL.value)
    rules = [Rule(name, origin, (Atom("?x", str(TYPE), "?c"),), head,
                  (cond.test(f"isIRI(?x) && ?c NOT IN ({declarations}) && !isBlank(?c)"),))]
    for body in (Atom("?x", "?q", "?o"), Atom("?o", "?q", "?x")):
        rules.append(Rule(name, origin, (body,), head, (cond.test(f"isIRI(?x) && {_not_schema('?q')}"),)))
    # named only in an equality or a difference (how aRMOR's DISJOINT IND introduces names): still individuals
    for p in (SAME_AS, DIFFERENT_FROM):
        for body in (Atom("?x", str(p), "?o"), Atom("?o", str(p), "?x")):
            rules.append(Rule(name, origin, (body,), head, (cond.test("isIRI(?x)"),)))
    rules.append(Rule(name, origin, (Atom("?k", str(DIFFERENT_KEY_OF), "?x", aux=True),), head,
                      (cond.test("isIRI(?x)"),)))
    return rules


__all__ = ["for_every_individual"]
