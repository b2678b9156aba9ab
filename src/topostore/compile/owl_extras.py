"""Keys, reflexive properties and restriction subsumption through properties → rules.

* Keys (``owl:hasKey``), OWL 2 RL's prp-key: ``C hasKey (p1 … pn)``, ``x`` and ``y`` in ``C``,
  ``x pi zi`` and ``y pi zi`` for every i ⇒ ``x owl:sameAs y``.  Keys apply to named individuals
  only (OWL 2 Direct Semantics), so neither side may be an unnamed node (a skolemised blank node).
* ``ReflexiveProperty`` p: ``x p x`` for every individual — every node typed with a class (not a
  declaration such as ``owl:Class``), or linked by a property of the ontology (not a schema one).
* ``owl:Thing ⊑ C``: every individual (as above) is in ``C``.
* An existential into owl:Nothing (``∃p.⊥``, ``≥n p.⊥`` with n ≥ 1) has no instance: a member of it
  is a member of owl:Nothing (then inconsistent, cls-nothing2).
* Restrictions subsumed through sub-properties and fillers: ``≥n p.C ⊑ ≥m q.D`` when ``p ⊑ q``,
  ``n ≥ m`` and ``C ⊑ D`` (the same property is :mod:`.owl`'s ext-card-sub), and ``∀q.C ⊑ ∀p.D``
  when ``p ⊑ q`` (or ``p = q``) and ``C ⊑ D`` — Horn, and what RDF-Based Semantics documents
  compare restrictions by.  The sub-properties are those of the whole hierarchy of property expressions
  (:mod:`.property_hierarchy`: through inverses and symmetry too).  What an existential's unnamed value
  is besides its filler (its property's ranges, a universal of its subject) is :mod:`.existential_values`'.
* The subject of an existential (``∃p.C``, ``≥n p.C`` with n ≥ 1) is in the domain of ``p`` and of each of its
  super-properties (the range for an inverse one), its value unnamed: ``x ∈ ∃p.C ⇒ x ∈ D``.
"""

from __future__ import annotations

from collections.abc import Iterable

from pyoxigraph import NamedNode

from ..rdf.terms import sparql
from ..rdf.vocab import (
    NOTHING,
    SAME_AS,
    SKOLEM_PREFIX,
    THING,
    TYPE,
)
from . import condition as cond
from .every_individual import for_every_individual
from .existential_values import existential_value_rules
from .fillers import FillerIndex
from .model import Expr, Prop, TBox, describe
from .owl import OwlCompiler
from .property_hierarchy import subject_classes, super_expressions
from .rule import Atom, Rule
from .schema import schema_rule
from .snippets import DERIVED_STRINGS, one_string


def _prop_atom(s: str, p: Prop, o: str) -> Atom:
    return Atom(o, sparql(p.iri), s) if p.inverse else Atom(s, sparql(p.iri), o)


def key_rule(cls: Expr, props: tuple[Prop, ...]) -> Rule:
    """The prp-key rule of one key (a key of owl:Thing asks no type: every individual is a Thing, typed or not)."""
    body = [] if cls.node == THING else [Atom("?x", str(TYPE), sparql(cls.node)),
                                         Atom("?y", str(TYPE), sparql(cls.node))]
    for k, p in enumerate(props):
        body += [_prop_atom("?x", p, f"?z{k}"), _prop_atom("?y", p, f"?z{k}")]
    named = (f'!sameTerm(?x, ?y) && isIRI(?x) && isIRI(?y) && !STRSTARTS(STR(?x), "{SKOLEM_PREFIX}") '
             f'&& !STRSTARTS(STR(?y), "{SKOLEM_PREFIX}")')
    keys = " ".join(p.iri.value.rsplit("#", 1)[-1] for p in props)
    return Rule("prp-key", f"{describe(cls)} HasKey ({keys})", tuple(body), Atom("?x", str(SAME_AS), "?y"),
                (cond.test(named),))


def key_string_rule(cls: Expr, props: tuple[Prop, ...], i: int) -> Rule:
    """The prp-key rule of one key matching the ``i``-th property's values as strings: ``x``'s value of a
    type derived from xsd:string (``"a"^^xsd:token``) is the string ``y`` holds as another literal (``"a"``,
    one value, two terms, which :func:`key_rule`'s join by term does not meet); the other properties' values
    by term or as one string.  Asking the derived type of ``x``'s value keeps the rule to the few such literals."""
    rule = key_rule(cls, props)
    body = [a for a in rule.body if a.p == str(TYPE)]
    tests = [rule.conditions[0]]
    for k, p in enumerate(props):
        z, w = f"?z{k}", f"?w{k}"
        body += [_prop_atom("?x", p, z), _prop_atom("?y", p, w)]
        if k == i:
            tests.append(cond.test(f"isLiteral({z}) && datatype({z}) IN ({DERIVED_STRINGS}) && {one_string(z, w)}"))
        else:
            tests.append(cond.test(f"sameTerm({z}, {w}) || COALESCE(({one_string(z, w)}), false)"))
    return Rule("prp-key", rule.origin, tuple(body), rule.head, tuple(tests))


def key_rules(tb: TBox) -> list[Rule]:
    """The prp-key rules of every key: by term, and by string for each property that may hold data values."""
    rules = []
    for cls, props in tb.keys:
        if props:
            rules.append(key_rule(cls, props))
            rules += [key_string_rule(cls, props, i) for i, p in enumerate(props)
                      if not p.inverse and p.iri not in tb.object_properties]
    return rules


def reflexive_rules(tb: TBox) -> list[Rule]:
    """``x p x`` for every individual, for each reflexive property ``p``."""
    rules = []
    for p in sorted(tb.characteristics.get("ReflexiveProperty", ()), key=lambda t: t.value):
        rules += for_every_individual("prp-refl", f"{p.value.rsplit('#', 1)[-1]} is reflexive",
                                      Atom("?x", sparql(p), "?x"))
    return rules


def thing_rules(tb: TBox, expressions: Iterable[Expr] = ()) -> list[Rule]:
    """``owl:Thing ⊑ C`` (or ``owl:Thing ≡ C``): every individual is a member of ``C`` — how a range or
    a property's universal restriction is often written (``owl:Thing ⊑ ∀p.A``); and of a union among
    ``expressions`` with owl:Thing as a member, or an intersection of owl:Thing alone (no rule types an
    individual with owl:Thing itself)."""
    supers = {b for a, b in tb.subclass if a.node == THING and b.node != THING}
    supers |= {e for e in expressions if (e.kind == "or" and any(m.node == THING for m in e.members))
               or (e.kind == "and" and all(m.node == THING for m in e.members))}
    supers |= {y for a, b in tb.equivalent for x, y in ((a, b), (b, a)) if x.node == THING and y.node != THING}
    rules = []
    for b in sorted(supers, key=lambda e: e.node.value):
        rules += for_every_individual("cax-sco-thing", f"Thing SubClassOf {describe(b)}",
                                      Atom("?x", str(TYPE), sparql(b.node)))
    return rules


def unsatisfiable_rules(owl: OwlCompiler) -> list[Rule]:
    """``x ∈ ∃p.⊥ ⇒ x ∈ ⊥`` (and for minimum and exact cardinalities of at least one into owl:Nothing)."""
    return [Rule("cls-svf-nothing", f"{describe(e)} has no instance", (Atom("?x", str(TYPE), sparql(e.node)),),
                 Atom("?x", str(TYPE), sparql(NOTHING)))
            for e in owl.all_expressions()
            if e.kind in ("some", "min", "exact") and (e.kind == "some" or e.n >= 1)
            and e.filler is not None and e.filler.node == NOTHING]


def restriction_rules(owl: OwlCompiler) -> list[Rule]:
    """``x ∈ a ⇒ x ∈ b`` for the restriction pairs subsumed through properties (see the module)."""
    supers = super_expressions(owl.tb)
    exprs = owl.all_expressions()
    rules = []

    def subsume(a: Expr, b: Expr) -> None:
        rules.append(schema_rule("ext-restriction-sub").instantiate((a.term, b.term),
                                                                    f"{describe(a)} is subsumed by {describe(b)}"))

    lower = [e for e in exprs if e.kind in ("some", "min", "exact")]
    wider = FillerIndex(owl.subsumption, [e for e in lower if e.kind != "exact"])
    for a in lower:
        above = supers.get(a.prop, ())
        if not above:
            continue  # no super-property: nothing to compare (the same property is ext-card-sub's)
        for b in wider.subsuming(a):
            if b.prop in above:
                na, nb = (1 if a.kind == "some" else a.n), (1 if b.kind == "some" else b.n)
                if na >= nb >= 1:
                    subsume(a, b)
    alls = [e for e in exprs if e.kind == "all" and not e.prop.inverse]
    index = FillerIndex(owl.subsumption, alls)
    for a in alls:
        if a.filler is None and a.datatype is None:
            continue
        for b in index.subsuming(a):
            if a.node != b.node and (a.prop == b.prop or a.prop in supers.get(b.prop, ())):
                subsume(a, b)
    rules += existential_value_rules(owl.tb, owl.subsumption, supers, exprs, lambda a, b, origin: rules.append(
        schema_rule("ext-restriction-sub").instantiate((a.term, b.term), origin)))
    return rules


def existential(e: Expr) -> bool:
    """``e`` is an existential: every member has a value of its property, perhaps unnamed."""
    return e.kind == "some" or (e.kind in ("min", "exact") and e.n >= 1)


def existential_domain_rules(owl: OwlCompiler, uses: Iterable[tuple[Expr, bool, str, NamedNode | None]]) -> list[Rule]:
    """``x ∈ ∃p.C ⇒ x ∈ D`` for each domain ``D`` of ``p`` or of a super-property expression of ``p`` (a range
    for an inverse one): prp-dom, for a value no one named, so that no told value is needed.

    ``uses``: where each expression occurs (:func:`.profile.all_uses`).  A member of the restriction is one
    by a told value of ``p`` (then in ``D`` by prp-dom already) or by an axiom that puts it there: a rule
    is made only where such an axiom's subject is not told to be in ``D`` (``ROOM ≡ LOCATION ⊓ ∃hasDoor.DOOR``
    needs none), so the rules that compare classes read no more than before where nothing is missed."""
    supers = super_expressions(owl.tb)
    subjects: dict[NamedNode, set[NamedNode | None]] = {}
    for e, positive, _, subject in uses:
        if positive and existential(e):
            subjects.setdefault(e.node, set()).add(subject)
    rules = []
    for e in owl.all_expressions():
        if not existential(e) or e.node not in subjects:
            continue
        for axiom, c in subject_classes(owl.tb, supers, e.prop):
            if all(s is not None and (s == c.node or c.node in owl.told.get(s, ())) for s in subjects[e.node]):
                continue
            rules.append(Rule("ext-domain", f"a member of {describe(e)} is in {describe(c)} ({axiom})",
                              (Atom("?x", str(TYPE), sparql(e.node)),), Atom("?x", str(TYPE), sparql(c.node))))
    return rules


__all__ = ["existential", "existential_domain_rules", "key_rule", "key_rules", "reflexive_rules",
           "restriction_rules"]
