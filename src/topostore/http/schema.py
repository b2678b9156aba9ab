"""Classes and properties as the inspector shows them: hierarchy, axioms, rules, each inference with its why.

The axioms are read from the asserted graph with the compiler's own reader
(:class:`~topostore.compile.tbox_reader.TBoxReader`) and written as the rules'
origins are (``URGENT SubClassOf LOCATION``, ``ROOM EquivalentTo (LOCATION
and (hasDoor some DOOR))``), so a proof's rule and the class page agree.

An inferred subclass relation is proved the way classification finds it
(:mod:`topostore.reason.classify`): a prototype individual of the class is
given to the rules, and the derivation of its membership in the superclass is
the proof, with the prototype shown as ``(any ROOM)``.
"""

from __future__ import annotations

import re
from functools import lru_cache
from typing import TYPE_CHECKING, Any

from pyoxigraph import NamedNode, Triple

from ..compile.builtins import FUNCTIONS
from ..compile.class_expressions import ClassExpressionReader
from ..compile.model import Expr, Prop, TBox
from ..compile.rule import Rule, RuleSet
from ..compile.tbox_reader import TBoxReader
from ..errors import RuleCompileError
from ..ontology.explain import Explainer
from ..rdf.terms import sparql
from ..rdf.vocab import ASSERTED, PROTOTYPE_PREFIX, TYPE, rdfs
from ..reason.materialize import Materializer
from ..stores import memory_store
from ..stores.base import Store
from .entities import View, display_name

if TYPE_CHECKING:  # pragma: no cover
    from ..ontology.facade import Ontology

_CHARACTERISTIC_NAMES = {"FunctionalProperty": "Functional", "InverseFunctionalProperty": "InverseFunctional",
                         "TransitiveProperty": "Transitive", "SymmetricProperty": "Symmetric",
                         "AsymmetricProperty": "Asymmetric", "IrreflexiveProperty": "Irreflexive",
                         "ReflexiveProperty": "Reflexive"}


# --------------------------------------------------------------------------- axioms

def read_tbox(view: View) -> TBox | None:
    """The asserted axioms, or None (with a warning) when they cannot be read."""
    try:
        return TBoxReader(view.onto.store, ASSERTED).read()
    except RuleCompileError as exc:
        view.warnings.append(f"the axioms could not be read: {exc}")
        return None


def _mentions(e: Expr | Prop | NamedNode | None, target: NamedNode) -> bool:
    if e is None:
        return False
    if isinstance(e, NamedNode):
        return e == target
    if isinstance(e, Prop):
        return e.iri == target
    return (e.kind == "named" and e.node == target) or _mentions(e.prop, target) or _mentions(e.filler, target) \
        or e.datatype == target or target in e.individuals or e.value == target \
        or any(_mentions(m, target) for m in e.members)


def _named_in(*parts: Expr | Prop | NamedNode | None) -> set[NamedNode]:
    """The named classes, properties and individuals an axiom's parts name."""
    found: set[NamedNode] = set()

    def walk(e: Expr | Prop | NamedNode | None) -> None:
        if e is None:
            return
        if isinstance(e, NamedNode):
            found.add(e)
        elif isinstance(e, Prop):
            found.add(e.iri)
        else:
            if e.kind == "named":
                found.add(e.node)
            walk(e.prop)
            walk(e.filler)
            walk(e.datatype)
            found.update(i for i in e.individuals if isinstance(i, NamedNode))
            if isinstance(e.value, NamedNode):
                found.add(e.value)
            for m in e.members:
                walk(m)

    for p in parts:
        walk(p)
    return found


def _prop_text(p: Prop, prefix: str) -> str:
    return ("inverse " if p.inverse else "") + display_name(p.iri, prefix)


def axioms_of(view: View, tbox: TBox, e: NamedNode) -> list[dict[str, Any]]:
    """The asserted axioms naming ``e``, as text and with the entities they name (links on the page)."""
    prefix = view.onto.prefix
    found: list[tuple[str, set[NamedNode]]] = []
    for word, pairs in (("SubClassOf", tbox.subclass), ("EquivalentTo", tbox.equivalent),
                        ("DisjointWith", tbox.disjoint)):
        for a, b in pairs:
            if _mentions(a, e) or _mentions(b, e):
                found.append((f"{a} {word} {b}", _named_in(a, b)))
    for word, props in (("domain", tbox.domain), ("range", tbox.range)):
        for p, c in props:
            if _mentions(p, e) or _mentions(c, e):
                found.append((f"{_prop_text(p, prefix)} {word} {c}", _named_in(p, c)))
    for p, dt in tbox.data_range:
        if e in (p, dt):
            found.append((f"{display_name(p, prefix)} range {display_name(dt, prefix)}", {p}))
    for sub, sup in tbox.subproperty:
        if e in (sub.iri, sup.iri):
            found.append((f"{_prop_text(sub, prefix)} SubPropertyOf {_prop_text(sup, prefix)}", {sub.iri, sup.iri}))
    for a, b in tbox.inverse:
        if e in (a, b):
            found.append((f"{display_name(a, prefix)} InverseOf {display_name(b, prefix)}", {a, b}))
    for p, chain in tbox.chains:
        if e == p or any(c.iri == e for c in chain):
            text = " o ".join(_prop_text(c, prefix) for c in chain)
            found.append((f"{text} SubPropertyOf {display_name(p, prefix)}", {p, *(c.iri for c in chain)}))
    for a, b in tbox.disjoint_props:
        if e in (a, b):
            found.append((f"{display_name(a, prefix)} DisjointWith {display_name(b, prefix)}", {a, b}))
    unique = dict.fromkeys(found_text for found_text, _ in found)
    named = {text: names for text, names in found}
    return [{"text": text, "entities": [view.term(n) for n in sorted(named[text], key=lambda n: n.value)]}
            for text in unique]


def characteristics(tbox: TBox, p: NamedNode) -> list[str]:
    return [short for name, short in _CHARACTERISTIC_NAMES.items() if tbox.has(name, p)]


# --------------------------------------------------------------------------- rules

_IRI = re.compile(r"<([^<>\s]*)>")


def rules_naming(view: View, e: NamedNode) -> list[dict[str, str]]:
    """The SWRL rules whose atoms name ``e``, written ``body ⇒ head`` with short names."""
    needle = sparql(e)
    prefix = view.onto.prefix
    chosen: dict[str, Rule] = {}
    for rule in view.onto.rules.rules:
        if not rule.name.startswith("swrl:") or rule.head is None:
            continue
        atoms = (*rule.body, rule.head)
        if any(needle in (a.s, a.p, a.o) for a in atoms) and not any(a.aux for a in rule.body):
            if rule.name not in chosen or len(rule.origin) < len(chosen[rule.name].origin):
                chosen[rule.name] = rule

    def atom_text(a) -> str:
        text = f"{a.s} {'a' if a.p == sparql(TYPE) else a.p} {a.o}"
        return _IRI.sub(lambda m: display_name(NamedNode(m.group(1)), prefix), text)

    out = []
    for name, rule in sorted(chosen.items()):
        body = ", ".join(atom_text(a) for a in rule.body)
        conditions = " ".join(rule.filters.split())
        if conditions:
            body += ", " + _IRI.sub(lambda m: display_name(NamedNode(m.group(1)), prefix), conditions)
        out.append({"name": name, "origin": rule.origin, "text": f"{body} ⇒ {atom_text(rule.head)}"})
    return out


# --------------------------------------------------------------------------- class hierarchy

class _PrototypeExplainer(Explainer):
    """Proofs over the prototypes' scratch store, naming class expressions from the ontology's axioms
    (the scratch store holds the prototypes and their consequences, not the axioms)."""

    def __init__(self, store: Store, rules: list[Rule], short, axioms: ClassExpressionReader) -> None:
        super().__init__(store, rules, short)
        self.axioms = axioms

    def _render_node(self, node: NamedNode) -> str:
        try:
            return str(self.axioms.expr(node))
        except RuleCompileError:
            return super()._render_node(node)


class Prototypes:
    """A scratch store where each named class has one prototype individual, closed under the rules:
    the proof of ``prototype(C) a D`` is the proof of ``C SubClassOf D``.  One per rule set, kept
    while the rules do not change (they are recompiled, a new object, when the TBox changes)."""

    def __init__(self, rules: RuleSet) -> None:
        self.rules = rules
        self.store = memory_store()
        self.store.use_functions(FUNCTIONS)
        classes = sorted(rules.named_classes, key=lambda c: c.value)
        self.of = {c: NamedNode(f"{PROTOTYPE_PREFIX}inspector:{i}") for i, c in enumerate(classes)}
        self.store.add([Triple(p, TYPE, c) for c, p in self.of.items()], ASSERTED)
        Materializer(self.store, rules).run()
        self.names = {p: c for c, p in self.of.items()}

    def proof(self, onto: Ontology, sub: NamedNode, sup: NamedNode) -> dict[str, Any]:
        proto = self.of.get(sub)
        if proto is None:
            return {"triple": f"{onto.short(sub)} rdfs:subClassOf {onto.short(sup)}", "status": "not entailed"}

        def short(t) -> str:
            cls = self.names.get(t)
            return f"(any {onto.short(cls)})" if cls is not None else onto.short(t)

        explainer = _PrototypeExplainer(self.store, self.rules.all_rules, short, ClassExpressionReader(onto.store, ASSERTED))
        tree = _assumed(explainer.explain(Triple(proto, TYPE, sup)).to_dict())
        origin = f"every {onto.short(sub)} is a {onto.short(sup)}"
        if tree["status"] == "not entailed" and sub in onto.reasoning.unsatisfiable():
            tree, origin = None, f"{onto.short(sub)} is unsatisfiable (no individual can be a member): under every class"
        return {"triple": f"{onto.short(sub)} rdfs:subClassOf {onto.short(sup)}", "status": "inferred",
                "rule": "classification", "origin": origin, "bindings": {}, "premises": [tree] if tree else []}


def _assumed(node: dict[str, Any]) -> dict[str, Any]:
    """The prototype's own membership is where a subsumption proof starts: ``assumed``, not asserted."""
    if node["status"] == "asserted" and node["triple"].startswith("(any "):
        node["status"] = "assumed"
    for p in node.get("premises", []):
        _assumed(p)
    return node


class _Same:
    """A rule set as a cache key by identity: a RuleSet compares by value and has no hash, and a
    recompiled one (the TBox changed) is a new object, so "the same object" is "the same rules"."""

    __slots__ = ("rules",)

    def __init__(self, rules: RuleSet) -> None:
        self.rules = rules

    def __hash__(self) -> int:
        return id(self.rules)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _Same) and other.rules is self.rules


def prototypes(rules: RuleSet) -> Prototypes:
    """The prototypes of ``rules`` (a few rule sets are kept: one per loaded reference in use)."""
    return _prototypes(_Same(rules))


@lru_cache(maxsize=8)
def _prototypes(key: _Same) -> Prototypes:
    return Prototypes(key.rules)


def hierarchy(view: View, cls: NamedNode) -> dict[str, list[dict[str, Any]]]:
    """Named superclasses and subclasses, each told (asserted ``rdfs:subClassOf``) or inferred (with its proof)."""
    onto = view.onto
    store = onto.store
    told_sup = {o for o in store.objects(cls, rdfs("subClassOf"), ASSERTED) if isinstance(o, NamedNode)}
    told_sub = {s for s in store.subjects(rdfs("subClassOf"), cls, ASSERTED) if isinstance(s, NamedNode)}

    def entry(sub: NamedNode, sup: NamedNode, told: bool, shown: NamedNode) -> dict[str, Any]:
        out: dict[str, Any] = {"class": view.term(shown), "inferred": not told}
        if not told:
            out["why"] = prototypes(onto.rules).proof(onto, sub, sup)
        return out

    def key(c: NamedNode) -> str:
        return display_name(c, onto.prefix)

    sups = sorted(onto.superclasses(cls) | told_sup, key=key)
    subs = sorted(onto.subclasses(cls) | told_sub, key=key)
    return {"superclasses": [entry(cls, s, s in told_sup, s) for s in sups],
            "subclasses": [entry(s, cls, s in told_sub, s) for s in subs]}


def property_sections(view: View, tbox: TBox | None, p: NamedNode) -> dict[str, Any]:
    """Characteristics, domains and ranges (as axioms say them) and super-properties of a property."""
    if tbox is None:
        return {}
    prefix = view.onto.prefix
    domains = [str(c) for q, c in tbox.domain if q.iri == p and not q.inverse]
    ranges = [str(c) for q, c in tbox.range if q.iri == p and not q.inverse]
    ranges += [display_name(dt, prefix) for q, dt in tbox.data_range if q == p]
    supers = [view.term(sup.iri) for sub, sup in tbox.subproperty if sub.iri == p and not sub.inverse]
    inverses = [view.term(b if a == p else a) for a, b in tbox.inverse if p in (a, b)]
    return {"characteristics": characteristics(tbox, p), "domain": sorted(set(domains)),
            "range": sorted(set(ranges)), "superproperties": supers, "inverse_of": inverses}


__all__ = ["read_tbox", "axioms_of", "rules_naming", "hierarchy", "property_sections", "prototypes"]
