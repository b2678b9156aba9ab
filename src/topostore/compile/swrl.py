"""SWRL rules (standard RDF vocabulary, as Protégé writes them) → rules.

Every enabled ``swrl:Imp`` becomes one rule per head atom.  A rule that cannot
be translated (an unknown built-in, an atom of no known kind, an atom missing its
predicate or arguments, a variable the body does not bind) is set aside, as Pellet
ignores it, with a notice naming the rule (label or IRI), the atom and why; the
other rules are compiled.  A rule the caller adds itself (``refuse``) is refused
instead, naming the same.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

from pyoxigraph import Literal, NamedNode

from ..errors import RuleCompileError
from ..rdf.terms import Term, sparql
from ..rdf.vocab import DIFFERENT_FROM, ENTAILED_PREFIX, SAME_AS, SWRLA, TYPE, is_skolem, rdfs, swrl
from ..stores.base import Store
from . import builtins, data_ranges, sqwrl
from . import condition as cond
from .class_expressions import ClassExpressionReader
from .condition import Condition
from .inline_difference import DifferenceAsk
from .model import Expr, is_datatype
from .notices import INCOMPLETE, RULE_SET_ASIDE, SQWRL_QUERY, Notice
from .rule import Atom, Rule
from .snippets import candidate_atom, different_atom, in_datatype, surely_in_datatype
from .swrl_atoms import Names, SwrlAtom, read_atoms
from .swrl_same_as import rebinding, same_as_forms

T = str(TYPE)


@dataclass
class _Body:
    """What one rule body compiles to, built by :meth:`SwrlCompiler._body`."""

    patterns: list[Atom] = field(default_factory=list)
    conditions: list[Condition] = field(default_factory=list)
    #: read keys of graph patterns inside the conditions
    reads: set = field(default_factory=set)
    #: variables bound by the patterns and the BINDs placed so far
    bound: set[str] = field(default_factory=set)
    #: tests placed after the built-ins, when every variable is bound: (test, variables it needs, atom)
    deferred: list[tuple[Condition, list[str], SwrlAtom]] = field(default_factory=list)
    #: DifferentIndividualsAtoms: (x, y, atom)
    different: list[tuple[str, str, SwrlAtom]] = field(default_factory=list)


@contextmanager
def _about(name: str, a: SwrlAtom, what: str = "atom") -> Iterator[None]:
    """Name the rule and the atom in a compile error raised inside."""
    try:
        yield
    except RuleCompileError as exc:
        raise RuleCompileError(f"SWRL rule {name!r}, {what} {a.describe(name)}: {exc}") from None


def _why(name: str, exc: RuleCompileError) -> str:
    """A compile error's text without the rule's name it starts with (the notice names the rule)."""
    text = str(exc)
    for prefix in (f"SWRL rule {name!r}, ", f"SWRL rule {name!r} "):
        if text.startswith(prefix):
            return text[len(prefix):]
    return text


def _require_bound(name: str, a: SwrlAtom, needs: Iterable[str], bound: set[str], where: str) -> None:
    """Refuse an atom using a variable the body does not bind."""
    missing = [v for v in needs if v.startswith("?") and v not in bound]
    if missing:
        raise RuleCompileError(f"SWRL rule {name!r}, {where}atom {a.describe(name)}: variable {missing[0]} "
                               "is not bound by the body")


class SwrlCompiler:
    def __init__(self, store: Store, graph: NamedNode, reader: ClassExpressionReader, refuse: Collection[Term] = ()) -> None:
        """``refuse``: the rules (their ``swrl:Imp`` nodes) refused with a RuleCompileError when they cannot be
        compiled, rather than set aside (a rule a command adds, a rule a loader repaired)."""
        self.store, self.graph, self.reader = store, graph, reader
        self.refuse = refuse
        self.variables = {v for v in store.subjects(TYPE, swrl("Variable"), graph)}
        self.expressions: list[Expr] = []
        #: anonymous class expressions of rule atoms: (expression, in a head)
        self.used_as: list[tuple[Expr, bool]] = []
        #: whether a rule or query has a DifferentIndividuals atom in its body
        self.uses_difference = False
        #: predicates of conclusions drawn with entailed-only difference
        self.entailed_predicates: set[NamedNode] = set()
        #: SQWRL queries by name, and what was said about them
        self.queries: dict[str, sqwrl.SqwrlQuery] = {}
        self.notices: list[Notice] = []
        #: rules asking which pairs a SQWRL query's DifferentIndividuals atoms need checked
        self.query_rules: list[Rule] = []
        #: rules with one DifferentIndividuals atom, joined with the difference rules (.inline_difference)
        self.asks: list[DifferenceAsk] = []

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
            if self.is_query(node):
                self.compile_query(node)
                continue
            try:
                with self._undone_on_failure():
                    rules += self.compile_rule(node)
            except RuleCompileError as exc:
                if node in self.refuse:
                    exc.rule = node  # which rule, so that a loader may set a repaired one aside
                    raise
                name = self.rule_name(node)
                self.notices.append(Notice(INCOMPLETE, name, _why(name, exc), RULE_SET_ASIDE, node=node))
        return rules

    @contextmanager
    def _undone_on_failure(self) -> Iterator[None]:
        """What compiling one rule recorded (expressions it names, difference asks) taken back if it fails."""
        sizes = (len(self.expressions), len(self.used_as), len(self.asks))
        entailed, difference = set(self.entailed_predicates), self.uses_difference
        try:
            yield
        except RuleCompileError:
            del self.expressions[sizes[0]:], self.used_as[sizes[1]:], self.asks[sizes[2]:]
            self.entailed_predicates, self.uses_difference = entailed, difference
            raise

    # ------------------------------------------------------------------ SQWRL
    def is_query(self, node: Term) -> bool:
        """A rule using SQWRL built-ins (in its head or body) is a query, not a rule."""
        for part in ("head", "body"):
            head = self._one(node, swrl(part))
            atoms = self.store.list_items(head, self.graph) if head is not None else []
            if any(sqwrl.is_sqwrl(self._one(a, swrl("builtin"))) for a in atoms):
                return True
        return False

    def compile_query(self, node: Term) -> None:
        """A SQWRL query → a SPARQL SELECT (:mod:`.sqwrl`); one that cannot be translated is set aside
        with a notice, never refusing the file (a query concludes nothing)."""
        name = self.rule_name(node)
        try:
            query, candidates = self._query(name, node)
        except RuleCompileError as exc:
            self.notices.append(Notice(SQWRL_QUERY, name, f"set aside, not translated: {exc}", node=node))
            return
        if name in self.queries:
            self.notices.append(Notice(SQWRL_QUERY, name, "set aside: another SQWRL query has this name", node=node))
            return
        self.queries[name] = query
        self.query_rules += candidates
        self.notices.append(Notice(SQWRL_QUERY, name, f"a query, not a rule: run it by name ({', '.join(query.columns)})",
                                   node=node))

    def _query(self, name: str, node: Term) -> tuple[sqwrl.SqwrlQuery, list[Rule]]:
        body_atoms = read_atoms(self.store, self.graph, self._one(node, swrl("body")))
        head_atoms = read_atoms(self.store, self.graph, self._one(node, swrl("head")))
        for a in body_atoms:
            if a.kind == "BuiltinAtom" and sqwrl.is_sqwrl(a.predicate):
                raise RuleCompileError(f"sqwrl:{sqwrl.operator(a.predicate)} in a query body (collections) "
                                       "is not supported")
        arg = Names(self.variables)
        wheres, candidates, bound = [], [], set()
        for form, _ in same_as_forms(body_atoms, [], self.variables):  # a union of the forms, each variable kept
            body = self._body(name, form, arg)
            patterns = body.patterns + [different_atom(x, y) for x, y, _ in body.different]
            where = Rule(f"sqwrl:{name}", f"SQWRL query {name}", tuple(patterns), None, tuple(body.conditions),
                         frozenset(body.reads)).where()
            again = [(arg(y), arg(x)) for y, x in rebinding(body_atoms, form, self.variables)]
            wheres.append(where + "".join(f"\n  BIND({x} AS {y})" for y, x in again))
            bound = body.bound | {y for y, _ in again}
            candidates += self._difference_rules(name, body)
        parts = []
        for a in head_atoms:
            if a.kind != "BuiltinAtom" or not sqwrl.is_sqwrl(a.predicate):
                raise RuleCompileError(f"{a.describe(name)} beside SQWRL built-ins in a head")
            texts = [arg(x) for x in a.args]
            _require_bound(name, a, texts, bound, "head ")
            parts.append((sqwrl.operator(a.predicate), texts, list(a.args)))
        head = sqwrl.read_head(parts)
        where = wheres[0] if len(wheres) == 1 else "\n  UNION\n  ".join(f"{{ {w} }}" for w in wheres)
        text, columns = sqwrl.select_text(head, where)
        return sqwrl.SqwrlQuery(name, text, columns, f"SQWRL query {name}"), candidates

    # ------------------------------------------------------------------ translation
    def compile_rule(self, node: Term) -> list[Rule]:
        """The rules of one ``swrl:Imp``: one per head atom (two when difference is only entailed),
        plus a candidate rule per DifferentIndividualsAtom of the body."""
        name = self.rule_name(node)
        body_atoms = read_atoms(self.store, self.graph, self._one(node, swrl("body")))
        head_atoms = read_atoms(self.store, self.graph, self._one(node, swrl("head")))
        if not head_atoms:
            raise RuleCompileError(f"SWRL rule {name!r} has no head atom")
        out: list[Rule] = []
        for body_form, head_form in same_as_forms(body_atoms, head_atoms, self.variables):
            arg = Names(self.variables)
            body = self._body(name, body_form, arg)
            rules = self._difference_rules(name, body)
            heads: list[Rule] = []
            for a in head_form:
                heads += self._head_rules(name, a, arg, body)
            if len(body.different) == 1:  # tested where it is asked, once the difference rules are known
                x, y, _ = body.different[0]
                self.asks.append(DifferenceAsk(x, y, rules[0], heads))
            out += rules + heads
        return out

    def _body(self, name: str, atoms: list[SwrlAtom], arg: Names) -> _Body:
        """Patterns first, then the built-ins in an order where each one's inputs are bound,
        then the tests that need every variable bound."""
        body = _Body()
        pending: list[SwrlAtom] = []
        for a in atoms:
            with _about(name, a):
                self._body_atom(a, arg, body, pending)
        body.bound = set().union(*(p.variables() for p in body.patterns))
        self._builtins(name, pending, arg, body)
        for test, needs, a in body.deferred:
            _require_bound(name, a, needs, body.bound, "")
            body.conditions.append(test)
        return body

    @staticmethod
    def _builtins(name: str, pending: list[SwrlAtom], arg: Names, body: _Body) -> None:
        """Place each built-in as soon as its inputs are bound (a BIND binds its result)."""
        pending = list(pending)
        #: variables to test for a data value, and those a strict built-in's condition already proves one
        needs: dict[str, None] = {}
        proven: set[str] = set()
        #: variables a built-in bound to a number (an arithmetic result): compared as SPARQL compares numbers
        numbers: set[str] = set()
        while pending:
            placed = False
            for a in list(pending):
                texts = [arg(x) for x in a.args]
                iri = a.predicate.value if a.predicate else ""
                with _about(name, a):
                    placed_as = builtins.conditions(iri, texts, body.bound, numbers)
                if placed_as is not None:
                    body.conditions += placed_as
                    if any(t.startswith("<") for t in texts):  # an individual (an IRI) given as an argument
                        body.conditions.append(cond.test("false"))
                    # a built-in's arguments are data values: on an individual it is false, as in Pellet;
                    # and an error leaves a BIND's variable unbound but keeps the row, so the built-in
                    # holds only where its value is defined (isLiteral of an unbound variable is false)
                    inputs = [t for t in texts if t in body.bound]
                    if builtins.is_strict(iri):
                        proven.update(inputs)
                    else:
                        needs.update(dict.fromkeys(inputs))
                    for bound_var in (c.binds for c in placed_as if c.binds):
                        needs[bound_var] = None
                        body.bound.add(bound_var)
                        if builtins.gives_number(iri, texts, bound_var):
                            numbers.add(bound_var)
                    pending.remove(a)
                    placed = True
            if not placed:
                raise RuleCompileError(f"SWRL rule {name!r}, atom {pending[0].describe(name)}: its input variables "
                                       "are never bound (rule is not DL-safe)")
        body.conditions += [builtins.defined(v) for v in needs if v not in proven]

    @staticmethod
    def _difference_rules(name: str, body: _Body) -> list[Rule]:
        """Difference: ask about exactly the pairs the rest of the body produces."""
        rules = []
        for x, y, a in body.different:
            _require_bound(name, a, [x, y], body.bound, "")
            rules.append(Rule(f"swrl:{name}", f"SWRL rule {name}: which pairs to check for difference",
                              tuple(body.patterns), candidate_atom(x, y),
                              (*body.conditions, cond.test(f"!sameTerm({x}, {y})")), frozenset(body.reads)))
        return rules

    def _head_rules(self, name: str, a: SwrlAtom, arg: Names, body: _Body) -> list[Rule]:
        """The rule concluding head atom ``a``; with difference atoms in the body, a second rule for
        individuals different by entailment only (its conclusion holds but fires no other rule)."""
        with _about(name, a, "head atom"):
            h = self._head_atom(a, arg)
        _require_bound(name, a, sorted(h.variables(), key=[h.s, h.p, h.o].index), body.bound, "head ")
        declared = [different_atom(x, y, declared=True) for x, y, _ in body.different]
        entailed = [different_atom(x, y) for x, y, _ in body.different]
        conditions, reads = tuple(body.conditions), frozenset(body.reads)
        rules = [Rule(f"swrl:{name}", f"SWRL rule {name}", tuple(body.patterns + declared), h, conditions, reads)]
        if entailed:
            weak = Atom(h.s, str(NamedNode(ENTAILED_PREFIX + h.p[1:-1])), h.o)
            rules.append(Rule(f"swrl:{name}", f"SWRL rule {name} (individuals different by entailment only)",
                              tuple(body.patterns + entailed), weak, conditions, reads))
            self.entailed_predicates.add(NamedNode(h.p[1:-1]))
        return rules

    def _class(self, pred: Term | None, head: bool = False) -> str:
        if not isinstance(pred, NamedNode):
            raise RuleCompileError("missing class predicate")
        e = self.reader.expr(pred)
        if not e.is_named:
            self.expressions.append(e)
            self.used_as.append((e, head))
        return sparql(e.node)

    def _body_atom(self, a: SwrlAtom, arg: Names, body: _Body, pending: list[SwrlAtom]) -> None:
        k = a.kind
        if k == "ClassAtom":
            self._need(a, 1)
            body.patterns.append(Atom(arg(a.args[0]), T, self._class(a.predicate)))
        elif k in ("IndividualPropertyAtom", "DatavaluedPropertyAtom"):
            self._need(a, 2)
            if not isinstance(a.predicate, NamedNode):
                raise RuleCompileError("missing property predicate")
            body.patterns.append(Atom(arg(a.args[0]), sparql(a.predicate), arg(a.args[1])))
        elif k == "SameIndividualAtom":
            self._need(a, 2)
            x, y = arg(a.args[0]), arg(a.args[1])
            same = cond.test(f"sameTerm({x}, {y}) || EXISTS {{ {x} {SAME_AS} {y} }}", reads_graph=True)
            body.deferred.append((same, [x, y], a))
            body.reads.add(("p", str(SAME_AS)))
        elif k == "DifferentIndividualsAtom":
            self._need(a, 2)
            x, y = arg(a.args[0]), arg(a.args[1])
            body.different.append((x, y, a))
            self.uses_difference = True
        elif k == "DataRangeAtom":
            self._need(a, 1)
            test = surely_in_datatype(arg(a.args[0]), self._data_range(a.predicate))
            body.deferred.append((cond.test(test), [arg(a.args[0])], a))
        elif k == "BuiltinAtom":
            pending.append(a)
        else:
            raise RuleCompileError(f"unsupported atom type swrl:{k}")

    def _data_range(self, pred: Term | None) -> NamedNode:
        """The datatype a DataRangeAtom tests: a named one of the datatype map, a name defined by a data range
        (:mod:`.datatype_definitions`), or a data range written in the atom (numeric facets, a one-of, a complement,
        a union, an intersection), the last two as the IRI :mod:`.data_ranges` names them (the value test of a range or a restriction)."""
        if isinstance(pred, NamedNode) and is_skolem(pred):
            datatype = self.reader.data_range(pred, "a data range atom", typed=True)
        else:
            datatype = self.reader.datatype_defs.get(pred, pred) if isinstance(pred, NamedNode) else None
        if datatype is None or not (is_datatype(datatype) or data_ranges.parts(datatype) is not None
                                    or data_ranges.composition(datatype) is not None):
            raise RuleCompileError("its data range is neither a datatype of the OWL 2 datatype map nor one defined "
                                   "by a data range")
        if data_ranges.composition(datatype) is not None and in_datatype("?v", datatype) is None:
            # built of a datatype whose values are not tested (the ontology's own): the atom's truth is unknown
            raise RuleCompileError(f"its data range {data_ranges.readable(datatype)} is built of a datatype whose "
                                   "values topostore does not test")
        return datatype

    @staticmethod
    def _need(a: SwrlAtom, n: int) -> None:
        if len(a.args) < n:
            raise RuleCompileError(f"expects {n} argument(s), found {len(a.args)}")

    def _head_atom(self, a: SwrlAtom, arg: Names) -> Atom:
        k = a.kind
        if k == "ClassAtom":
            self._need(a, 1)
            return Atom(arg(a.args[0]), T, self._class(a.predicate, head=True))
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
