"""Keys (``owl:hasKey``) → rules: two named instances of the class with the same key values are the same.

OWL 2 RL's prp-key: ``C hasKey (p1 … pn)``, ``x`` and ``y`` in ``C``, ``x pi zi`` and ``y pi zi`` for
every i ⇒ ``x owl:sameAs y``.  Keys apply to named individuals only (OWL 2 Direct Semantics), so
neither side may be an unnamed node (a skolemised blank node).
"""

from __future__ import annotations

from ..terms import sparql
from ..vocab import SAME_AS, SKOLEM_PREFIX, TYPE
from . import condition as cond
from .model import Expr, Prop, TBox, describe
from .rule import Atom, Rule


def _prop_atom(s: str, p: Prop, o: str) -> Atom:
    return Atom(o, sparql(p.iri), s) if p.inverse else Atom(s, sparql(p.iri), o)


def key_rule(cls: Expr, props: tuple[Prop, ...]) -> Rule:
    """The prp-key rule of one key."""
    body = [Atom("?x", str(TYPE), sparql(cls.node)), Atom("?y", str(TYPE), sparql(cls.node))]
    for k, p in enumerate(props):
        body += [_prop_atom("?x", p, f"?z{k}"), _prop_atom("?y", p, f"?z{k}")]
    named = (f'!sameTerm(?x, ?y) && isIRI(?x) && isIRI(?y) && !STRSTARTS(STR(?x), "{SKOLEM_PREFIX}") '
             f'&& !STRSTARTS(STR(?y), "{SKOLEM_PREFIX}")')
    keys = " ".join(p.iri.value.rsplit("#", 1)[-1] for p in props)
    return Rule("prp-key", f"{describe(cls)} HasKey ({keys})", tuple(body), Atom("?x", str(SAME_AS), "?y"),
                (cond.test(named),))


def key_rules(tb: TBox) -> list[Rule]:
    return [key_rule(cls, props) for cls, props in tb.keys if props]


__all__ = ["key_rule", "key_rules"]
