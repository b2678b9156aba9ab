"""SWRL rules (standard RDF vocabulary, as Protégé writes them) → rules.

Every enabled ``swrl:Imp`` becomes one rule per head atom.  A rule that cannot
be translated is refused with a message naming the rule (label or IRI) and the
atom, never dropped silently.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from pyoxigraph import Literal, NamedNode

from ..errors import RuleCompileError
from ..store import Store
from ..terms import Term, sparql
from ..vocab import DIFFERENT_FROM, ENTAILED_PREFIX, SAME_AS, SWRL, SWRLA, TYPE, is_skolem, rdfs, swrl
from . import builtins
from .model import Expr, TBoxReader, is_datatype
from .rule import Atom, Rule
from .snippets import candidate_atom, different_atom, in_datatype

T = str(TYPE)


@dataclass(frozen=True)
class SwrlAtom:
    kind: str  # ClassAtom, IndividualPropertyAtom, ...
    predicate: Term | None
    args: tuple[Term, ...]
    node: Term

    def describe(self, rule_name: str) -> str:
        def short(t: Term | None) -> str:
            if t is None:
                return ""
            v = getattr(t, "value", str(t))
            return v.rsplit("#", 1)[-1].rsplit("/", 1)[-1]

        return f"{self.kind}({short(self.predicate)}{', ' if self.predicate else ''}{', '.join(short(a) for a in self.args)})"


class SwrlCompiler:
    def __init__(self, store: Store, graph: NamedNode, reader: TBoxReader) -> None:
        self.store, self.graph, self.reader = store, graph, reader
        self.variables = {v for v in store.subjects(TYPE, swrl("Variable"), graph)}
        self.expressions: list[Expr] = []
        #: predicates of conclusions drawn with entailed-only difference
        self.entailed_predicates: set[NamedNode] = set()

    def _one(self, s: Term, p: NamedNode) -> Term | None:
        v = self.store.objects(s, p, self.graph)
        return v[0] if v else None

    def rule_name(self, node: Term) -> str:
        label = self._one(node, rdfs("label"))
        if isinstance(label, Literal):
            return label.value
        return node.value if not is_skolem(node) else "an unnamed SWRL rule"

    def compile(self) -> list[Rule]:
        rules: list[Rule] = []
        for node in self.store.subjects(TYPE, swrl("Imp"), self.graph):
            enabled = self._one(node, NamedNode(SWRLA + "isRuleEnabled"))
            if isinstance(enabled, Literal) and enabled.value.strip().lower() in ("false", "0"):
                continue
            rules += self.compile_rule(node)
        return rules

    # ------------------------------------------------------------------ reading
    def atoms(self, head: Term | None, name: str) -> list[SwrlAtom]:
        if head is None:
            return []
        out = []
        for node in self.store.list_items(head, self.graph):
            kinds = [t.value[len(SWRL):] for t in self.store.objects(node, TYPE, self.graph) if t.value.startswith(SWRL)]
            kind = kinds[0] if kinds else "?"
            pred = (self._one(node, swrl("classPredicate")) or self._one(node, swrl("propertyPredicate"))
                    or self._one(node, swrl("dataRange")) or self._one(node, swrl("builtin")))
            if kind == "BuiltinAtom":
                lst = self._one(node, swrl("arguments"))
                args = tuple(self.store.list_items(lst, self.graph)) if lst is not None else ()
            else:
                args = tuple(a for a in (self._one(node, swrl("argument1")), self._one(node, swrl("argument2"))) if a is not None)
            out.append(SwrlAtom(kind, pred, args, node))
        return out

    # ------------------------------------------------------------------ translation
    def compile_rule(self, node: Term) -> list[Rule]:
        name = self.rule_name(node)
        body = self.atoms(self._one(node, swrl("body")), name)
        head = self.atoms(self._one(node, swrl("head")), name)
        if not head:
            raise RuleCompileError(f"SWRL rule {name!r} has no head atom")
        names: dict[Term, str] = {}
        self._deferred: list[tuple[str, list[str], SwrlAtom]] = []
        self._different: list[tuple[str, str, SwrlAtom]] = []

        def arg(t: Term) -> str:
            if t in self.variables:
                if t not in names:
                    local = re.sub(r"[^A-Za-z0-9_]", "_", t.value.rsplit("#", 1)[-1].rsplit("/", 1)[-1]) or "v"
                    candidate = f"?{local}"
                    while candidate in names.values():
                        candidate += "_"
                    names[t] = candidate
                return names[t]
            return sparql(t)

        patterns: list[Atom] = []
        filters: list[str] = []
        reads: set = set()
        pending: list[SwrlAtom] = []
        for a in body:
            try:
                self._body_atom(a, arg, patterns, filters, reads, pending)
            except RuleCompileError as exc:
                raise RuleCompileError(f"SWRL rule {name!r}, atom {a.describe(name)}: {exc}") from None
        bound = set().union(*(p.variables() for p in patterns)) if patterns else set()
        # built-ins: run each as soon as its inputs are bound
        while pending:
            progressed = False
            for a in list(pending):
                try:
                    out = builtins.translate(a.predicate.value if a.predicate else "", [arg(x) for x in a.args], bound)
                except RuleCompileError as exc:
                    raise RuleCompileError(f"SWRL rule {name!r}, atom {a.describe(name)}: {exc}") from None
                if out is not None:
                    text, newly = out
                    filters.append(text)
                    if newly:
                        bound.add(newly)
                    pending.remove(a)
                    progressed = True
            if not progressed:
                a = pending[0]
                raise RuleCompileError(
                    f"SWRL rule {name!r}, atom {a.describe(name)}: its input variables are never bound (rule is not DL-safe)"
                )
        # deferred tests that needed every variable bound
        for text, needs, a in self._deferred:
            missing = [v for v in needs if v.startswith("?") and v not in bound]
            if missing:
                raise RuleCompileError(f"SWRL rule {name!r}, atom {a.describe(name)}: variable {missing[0]} is not bound by the body")
            filters.append(text)
        rules = []
        # difference: ask about exactly the pairs the rest of the body produces
        declared: list[Atom] = []
        entailed: list[Atom] = []
        for x, y, a in self._different:
            for v in (x, y):
                if v.startswith("?") and v not in bound:
                    raise RuleCompileError(f"SWRL rule {name!r}, atom {a.describe(name)}: variable {v} is not bound by the body")
            rules.append(Rule(f"swrl:{name}", f"SWRL rule {name}: which pairs to check for difference", tuple(patterns),
                              candidate_atom(x, y), "\n  ".join(filters + [f"FILTER(!sameTerm({x}, {y}))"]), frozenset(reads)))
            declared.append(different_atom(x, y, declared=True))
            entailed.append(different_atom(x, y))
        for a in head:
            try:
                h = self._head_atom(a, arg)
            except RuleCompileError as exc:
                raise RuleCompileError(f"SWRL rule {name!r}, head atom {a.describe(name)}: {exc}") from None
            for v in h.variables():
                if v not in bound:
                    raise RuleCompileError(f"SWRL rule {name!r}, head atom {a.describe(name)}: variable {v} is not bound by the body")
            rules.append(Rule(f"swrl:{name}", f"SWRL rule {name}", tuple(patterns + declared), h, "\n  ".join(filters), frozenset(reads)))
            if entailed:
                # difference only entailed: the conclusion holds but fires no other rule
                weak = Atom(h.s, str(NamedNode(ENTAILED_PREFIX + h.p[1:-1])), h.o)
                rules.append(Rule(f"swrl:{name}", f"SWRL rule {name} (individuals different by entailment only)",
                                  tuple(patterns + entailed), weak, "\n  ".join(filters), frozenset(reads)))
                self.entailed_predicates.add(NamedNode(h.p[1:-1]))
        return rules

    def _class(self, pred: Term | None) -> str:
        if not isinstance(pred, NamedNode):
            raise RuleCompileError("missing class predicate")
        e = self.reader.expr(pred)
        if not e.is_named:
            self.expressions.append(e)
        return sparql(e.node)

    def _body_atom(self, a: SwrlAtom, arg, patterns, filters, reads, pending) -> None:
        k = a.kind
        if k == "ClassAtom":
            self._need(a, 1)
            patterns.append(Atom(arg(a.args[0]), T, self._class(a.predicate)))
        elif k in ("IndividualPropertyAtom", "DatavaluedPropertyAtom"):
            self._need(a, 2)
            if not isinstance(a.predicate, NamedNode):
                raise RuleCompileError("missing property predicate")
            patterns.append(Atom(arg(a.args[0]), sparql(a.predicate), arg(a.args[1])))
        elif k == "SameIndividualAtom":
            self._need(a, 2)
            x, y = arg(a.args[0]), arg(a.args[1])
            self._deferred.append((f"FILTER(sameTerm({x}, {y}) || EXISTS {{ {x} {SAME_AS} {y} }})", [x, y], a))
            reads.add(("p", str(SAME_AS)))
        elif k == "DifferentIndividualsAtom":
            self._need(a, 2)
            x, y = arg(a.args[0]), arg(a.args[1])
            self._different.append((x, y, a))
        elif k == "DataRangeAtom":
            self._need(a, 1)
            if not is_datatype(a.predicate):
                raise RuleCompileError("only named datatypes are supported as data ranges")
            test = in_datatype(arg(a.args[0]), a.predicate) or f"isLiteral({arg(a.args[0])})"
            self._deferred.append((f"FILTER({test})", [arg(a.args[0])], a))
        elif k == "BuiltinAtom":
            pending.append(a)
        else:
            raise RuleCompileError(f"unsupported atom type swrl:{k}")

    @staticmethod
    def _need(a: SwrlAtom, n: int) -> None:
        if len(a.args) < n:
            raise RuleCompileError(f"expects {n} argument(s), found {len(a.args)}")

    def _head_atom(self, a: SwrlAtom, arg) -> Atom:
        k = a.kind
        if k == "ClassAtom":
            self._need(a, 1)
            return Atom(arg(a.args[0]), T, self._class(a.predicate))
        if k in ("IndividualPropertyAtom", "DatavaluedPropertyAtom"):
            self._need(a, 2)
            if not isinstance(a.predicate, NamedNode):
                raise RuleCompileError("missing property predicate")
            return Atom(arg(a.args[0]), sparql(a.predicate), arg(a.args[1]))
        if k == "SameIndividualAtom":
            self._need(a, 2)
            return Atom(arg(a.args[0]), str(SAME_AS), arg(a.args[1]))
        if k == "DifferentIndividualsAtom":
            self._need(a, 2)
            return Atom(arg(a.args[0]), str(DIFFERENT_FROM), arg(a.args[1]))
        raise RuleCompileError(f"swrl:{k} is not supported in a rule head")
