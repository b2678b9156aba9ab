"""SWRL rules in the human syntax Protégé shows → the standard SWRL RDF vocabulary.

``LOCATION(?l) ^ visitedAt(?l, ?v) ^ swrlb:greaterThan(?v, 5) -> URGENT(?l)``
becomes a ``swrl:Imp`` with ``swrl:body``/``swrl:head`` lists of atoms
(``swrl:ClassAtom``, ``swrl:IndividualPropertyAtom``,
``swrl:DatavaluedPropertyAtom``, ``swrl:SameIndividualAtom``,
``swrl:DifferentIndividualsAtom``, ``swrl:DataRangeAtom``,
``swrl:BuiltinAtom``), every cell typed ``swrl:AtomList`` and every variable a
``swrl:Variable`` — exactly what a file saved by Protégé holds.  So a rule added
at run time is compiled by :mod:`.swrl` like a loaded one, and SAVE writes it
in the standard vocabulary.

The text is read into atoms by :mod:`.swrl_syntax` (its grammar is there);
here an atom's kind follows from its predicate: ``swrlb:``
built-ins, ``sameAs``/``differentFrom``, XSD datatypes (data ranges), declared
classes, declared object and data properties.  Anything else is refused with
the atom named, before the ontology is touched.
"""

from __future__ import annotations

from collections.abc import Callable

from pyoxigraph import Literal, NamedNode, Triple

from ..errors import InvalidNameError, RuleCompileError
from ..rdf.terms import Term
from ..rdf.vocab import (
    ASSERTED,
    FIRST,
    NIL,
    REST,
    SWRL_VARIABLE_NS,
    SWRLA,
    SWRLB,
    TYPE,
    XSD,
    owl,
    rdfs,
    swrl,
    xsd,
)
from ..stores.base import Store, fresh_skolem
from .swrl_syntax import Parser, TextAtom, name_resolver

#: Namespace of the variables of rules added as text, as the OWL API writes them.
VARIABLE_NS = SWRL_VARIABLE_NS
_SAME = {"sameAs", "SameAs", "sameIndividual", "SameIndividual", "owl:sameAs"}
_DIFFERENT = {"differentFrom", "DifferentFrom", "differentIndividuals", "DifferentIndividuals", "owl:differentFrom"}

class RuleWriter:
    """Turns parsed atoms into SWRL RDF triples, classifying each atom against the asserted TBox."""

    def __init__(self, store: Store, resolve: Callable[[str], NamedNode], graph: NamedNode = ASSERTED) -> None:
        self.store, self.resolve, self.graph = store, resolve, graph
        self.triples: list[Triple] = []

    def _declared(self, iri: NamedNode, *types: NamedNode) -> bool:
        return any(self.store.contains(Triple(iri, TYPE, t), self.graph) for t in types)

    def _is_class(self, iri: NamedNode) -> bool:
        if self._declared(iri, owl("Class"), rdfs("Class")) or iri == owl("Thing"):
            return True
        return any(True for _ in self.store.triples(iri, rdfs("subClassOf"), None, self.graph)) or \
            any(True for _ in self.store.triples(iri, owl("equivalentClass"), None, self.graph))

    def var(self, name: str) -> NamedNode:
        v = NamedNode(VARIABLE_NS + name[1:])
        self.triples.append(Triple(v, TYPE, swrl("Variable")))
        return v

    def term(self, a: object) -> Term:
        return self.var(a) if isinstance(a, str) else a  # type: ignore[return-value]

    def atom(self, a: TextAtom) -> NamedNode:
        """The atom's node and triples; raises RuleCompileError naming the atom."""
        try:
            return self._atom(a)
        except (RuleCompileError, InvalidNameError) as exc:
            raise RuleCompileError(f"atom {a.text}: {exc}") from None

    def _atom(self, a: TextAtom) -> NamedNode:
        node = fresh_skolem()
        add = self.triples.append
        n = len(a.args)
        if a.name in _SAME or a.name in _DIFFERENT:
            if n != 2:
                raise RuleCompileError(f"{a.name} takes 2 arguments, got {n}")
            kind = "SameIndividualAtom" if a.name in _SAME else "DifferentIndividualsAtom"
            add(Triple(node, TYPE, swrl(kind)))
            add(Triple(node, swrl("argument1"), self.term(a.args[0])))
            add(Triple(node, swrl("argument2"), self.term(a.args[1])))
            return node
        pred = self.resolve(a.name)
        if pred.value.startswith(SWRLB):
            add(Triple(node, TYPE, swrl("BuiltinAtom")))
            add(Triple(node, swrl("builtin"), pred))
            add(Triple(node, swrl("arguments"), self.rdf_list([self.term(x) for x in a.args], typed=False)))
            return node
        if pred.value.startswith(XSD) or self._declared(pred, rdfs("Datatype")):
            self._arity(a, 1)
            add(Triple(node, TYPE, swrl("DataRangeAtom")))
            add(Triple(node, swrl("dataRange"), pred))
            add(Triple(node, swrl("argument1"), self.term(a.args[0])))
            return node
        if n == 1:
            if not self._is_class(pred):
                if self._declared(pred, owl("ObjectProperty"), owl("DatatypeProperty")):
                    self._arity(a, 2)
                raise RuleCompileError(f"{a.name} is not a declared class of the ontology")
            add(Triple(node, TYPE, swrl("ClassAtom")))
            add(Triple(node, swrl("classPredicate"), pred))
            add(Triple(node, swrl("argument1"), self.term(a.args[0])))
            return node
        self._arity(a, 2)
        if self._declared(pred, owl("ObjectProperty")):
            if isinstance(a.args[1], Literal):
                raise RuleCompileError(f"{a.name} is an object property; its second argument cannot be a value")
            kind = "IndividualPropertyAtom"
        elif self._declared(pred, owl("DatatypeProperty")):
            kind = "DatavaluedPropertyAtom"
        else:
            raise RuleCompileError(f"{a.name} is not a declared object or data property of the ontology")
        add(Triple(node, TYPE, swrl(kind)))
        add(Triple(node, swrl("propertyPredicate"), pred))
        add(Triple(node, swrl("argument1"), self.term(a.args[0])))
        add(Triple(node, swrl("argument2"), self.term(a.args[1])))
        return node

    @staticmethod
    def _arity(a: TextAtom, n: int) -> None:
        if len(a.args) != n:
            raise RuleCompileError(f"{a.name} takes {n} argument(s), got {len(a.args)}")

    def rdf_list(self, items: list[Term], typed: bool = True) -> Term:
        """An RDF collection; atom lists have every cell typed swrl:AtomList (as Protégé writes them)."""
        if not items:
            return NIL
        cells = [fresh_skolem() for _ in items]
        for k, (cell, item) in enumerate(zip(cells, items)):
            if typed:
                self.triples.append(Triple(cell, TYPE, swrl("AtomList")))
            self.triples.append(Triple(cell, FIRST, item))
            self.triples.append(Triple(cell, REST, cells[k + 1] if k + 1 < len(cells) else NIL))
        return cells[0]


def rule_triples(text: str, label: str, store: Store, prefix: str, comment: str | None = None) -> list[Triple]:
    """The SWRL RDF triples of rule ``text`` labelled ``label``; RuleCompileError naming the atom when refused."""
    if not label or not label.strip():
        raise RuleCompileError("a rule needs a non-empty label (it is how the rule is named and removed)")
    if imp_nodes(store, label):
        raise RuleCompileError(f"a SWRL rule labelled {label!r} already exists; remove it first")
    resolve = name_resolver(prefix)
    body, head = Parser(text, resolve).rule()
    writer = RuleWriter(store, resolve)
    body_nodes = [writer.atom(a) for a in body]
    head_nodes = [writer.atom(a) for a in head]
    imp = fresh_skolem()
    writer.triples += [
        Triple(imp, TYPE, swrl("Imp")),
        Triple(imp, rdfs("label"), Literal(label.strip())),
        Triple(imp, NamedNode(SWRLA + "isRuleEnabled"), Literal("true", datatype=xsd("boolean"))),
        Triple(imp, swrl("body"), writer.rdf_list(list(body_nodes))),
        Triple(imp, swrl("head"), writer.rdf_list(list(head_nodes))),
    ]
    if comment:
        writer.triples.append(Triple(imp, rdfs("comment"), Literal(comment)))
    return list(dict.fromkeys(writer.triples))


def rules_among(triples: list[Triple]) -> set[Term]:
    """The rules (``swrl:Imp`` nodes) ``triples`` type: those a command adds, refused rather than set aside
    when they cannot be compiled (:func:`topostore.compile.compile_ontology`'s ``refuse``)."""
    imp = swrl("Imp")
    return {t.subject for t in triples if t.predicate == TYPE and t.object == imp}


def imp_nodes(store: Store, label: str, graph: NamedNode = ASSERTED) -> list[Term]:
    """The swrl:Imp nodes labelled ``label``."""
    return [s for s in store.subjects(TYPE, swrl("Imp"), graph)
            if any(isinstance(o, Literal) and o.value == label for o in store.objects(s, rdfs("label"), graph))]


def rule_labels(store: Store, graph: NamedNode = ASSERTED) -> list[str]:
    """Labels of the SWRL rules in ``graph``, sorted."""
    out = []
    for s in store.subjects(TYPE, swrl("Imp"), graph):
        out += [o.value for o in store.objects(s, rdfs("label"), graph) if isinstance(o, Literal)]
    return sorted(out)


def removal_triples(store: Store, label: str, graph: NamedNode = ASSERTED) -> list[Triple]:
    """Every triple of the rule(s) labelled ``label``: the swrl:Imp, its atom lists, atoms and
    built-in argument lists, and the declarations of variables no other rule uses."""
    nodes = imp_nodes(store, label, graph)
    if not nodes:
        raise RuleCompileError(f"no SWRL rule labelled {label!r} (rules: {', '.join(rule_labels(store, graph)) or 'none'})")
    doomed: dict[Triple, None] = {}
    used: set[Term] = set()

    def take(node: Term) -> list[Triple]:
        ts = list(store.triples(node, None, None, graph))
        doomed.update(dict.fromkeys(ts))
        return ts

    def walk_list(head: Term, atoms: bool) -> None:
        seen: set[Term] = set()
        while head != NIL and head not in seen:
            seen.add(head)
            cell = take(head)
            for t in cell:
                if t.predicate == FIRST:
                    if atoms:
                        for at in take(t.object):
                            if at.predicate in (swrl("argument1"), swrl("argument2")):
                                used.add(at.object)
                            if at.predicate == swrl("arguments"):
                                walk_list(at.object, atoms=False)
                    else:
                        used.add(t.object)
            rest = [t.object for t in cell if t.predicate == REST]
            head = rest[0] if rest else NIL

    for imp in nodes:
        for t in take(imp):
            if t.predicate in (swrl("body"), swrl("head")):
                walk_list(t.object, atoms=True)
    for v in used:
        if not isinstance(v, NamedNode) or not store.contains(Triple(v, TYPE, swrl("Variable")), graph):
            continue
        others = [t for p in (swrl("argument1"), swrl("argument2"), FIRST)
                  for t in store.triples(None, p, v, graph) if t not in doomed]
        if not others:
            doomed[Triple(v, TYPE, swrl("Variable"))] = None
    return list(doomed)


__all__ = ["rule_triples", "removal_triples", "rule_labels", "imp_nodes", "VARIABLE_NS"]
