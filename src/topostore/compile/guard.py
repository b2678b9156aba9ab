"""Bound the compiled query, not the process: refuse a rule too large for the store to evaluate.

Oxigraph's parser and planner recurse on a query's structure, and past a size
the native stack overflows and the whole process dies (SIGSEGV) — no Python
``except`` catches that.  Measured with pyoxigraph 0.5 on an 8 MiB stack: a
basic graph pattern of about 850 chained triple patterns, or about 3,000
BINDs in one group, is enough.  An ontology decides how big its rules are (an
``intersectionOf`` of a thousand classes, a property chain of a thousand
links, a SWRL rule with a thousand atoms), so every compiled rule is measured
here before any store sees it, with limits far below those crash points, and
the whole ontology is refused with a :class:`~topostore.errors.RuleCompileError`
naming the rule and its axiom when one is past them.  Cardinalities, the one
construct whose rule used to grow with a number in the ontology, are compiled
by counting (:mod:`.counting`) and stay small for every n.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import RuleCompileError
from ..rdf.lexer import CLOSE, COMMENT, OPEN, PUNCT, tokens
from .rule import Rule, RuleSet


@dataclass(frozen=True)
class RuleLimits:
    """Bounds on one compiled rule (defaults well below the crash points measured above)."""

    #: triple patterns in the body
    max_atoms: int = 256
    #: FILTERs, BINDs and other group lines
    max_conditions: int = 512
    #: tokens of the rule's text (IRIs, names, punctuation)
    max_tokens: int = 20_000
    #: nesting of ( { [ in the rule's text
    max_depth: int = 64
    #: texts up to this many characters are not lexed: no compiled construct nests 64 deep
    #: that briefly, and they cannot hold more tokens than characters (keeps a TBox of
    #: thousands of rules from paying a lexer pass per rule)
    lex_above: int = 4_000


LIMITS = RuleLimits()


def measure(text: str, stop: int) -> tuple[int, int]:
    """(tokens, deepest nesting) of SPARQL ``text``; counting stops past ``stop`` tokens."""
    count = depth = deepest = 0
    for token in tokens(text):
        if token.kind == COMMENT:
            continue
        count += 1
        if count > stop:
            break
        if token.kind == PUNCT and token.text in OPEN:
            depth += 1
            deepest = max(deepest, depth)
        elif token.kind == PUNCT and token.text in CLOSE:
            depth -= 1
    return count, deepest


def check_rule(rule: Rule, limits: RuleLimits = LIMITS) -> None:
    """Raise :class:`RuleCompileError` when ``rule`` is past ``limits``; say which limit and why."""
    problem = ""
    if len(rule.body) > limits.max_atoms:
        problem = f"{len(rule.body)} body atoms (at most {limits.max_atoms})"
    elif len(rule.conditions) > limits.max_conditions:
        problem = f"{len(rule.conditions)} filters (at most {limits.max_conditions})"
    elif sum(len(a.s) + len(a.p) + len(a.o) for a in rule.body) + len(rule.filters) > limits.lex_above:
        count, depth = measure(rule.sparql(), limits.max_tokens)
        if count > limits.max_tokens:
            problem = f"more than {limits.max_tokens} tokens"
        elif depth > limits.max_depth:
            problem = f"nesting {depth} deep (at most {limits.max_depth})"
    if problem:
        origin = rule.origin if len(rule.origin) <= 200 else rule.origin[:200] + "…"
        raise RuleCompileError(f"rule {rule.name} for {origin} is too large to evaluate safely: {problem}; "
                               "the ontology was not reasoned (split the axiom into smaller ones)")


def guard_rules(rules: RuleSet, limits: RuleLimits = LIMITS) -> None:
    """Check every rule of ``rules`` (:func:`check_rule`) before a store evaluates any of them."""
    for rule in rules.rules:
        check_rule(rule, limits)


__all__ = ["LIMITS", "RuleLimits", "check_rule", "guard_rules", "measure"]
