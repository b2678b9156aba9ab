"""The schema tables of a TBox and the generic OWL rules that join them (``rules/owl/*.rq``).

The OWL rules whose axioms fit a row of fixed width — class hierarchy (cax-sco), equivalent classes
(cax-eqc1/2), property hierarchy (prp-spo1, which also serves prp-eqp1/2: the reader reads an
EquivalentProperties axiom as two sub-property rows), domain (prp-dom), range (prp-rng), inverse
(prp-inv1/2), symmetric (prp-symp), transitive (prp-trp), chains of two properties (prp-spo2),
disjointness (the check cax-dw, and different-disjoint), restrictions by kind (cls-svf1, cls-avf,
cls-hv1/2, one row per member for cls-int2 and cls-uni, one per individual for cls-oo, a file per
number of members for cls-int1), restriction
subsumption (ext-card-sub, and ext-restriction-sub through the property hierarchy) and the
non-memberships a complement needs (neg-dw, neg-svf, neg-sco, neg-int, neg-com, neg-avf, neg-uni: a
``ts:notType`` head, a helper atom)
— are written once, as SPARQL files in
``rules/owl/``, each with *schema atoms* ``GRAPH ts:graph:schema { ... }`` that read a row of the
TBox's tables.  Those files are the single source of these rules, used two ways:

* **instantiated** (partial evaluation): a row's constants are substituted into the rule and the
  schema atom is dropped, giving one rule per axiom (:meth:`SchemaRule.instantiate`).  This is what
  the compiler emits (:mod:`.owl`), and what the rule set holds as rows of a table once the passes
  after compilation are done (:mod:`.schema_tables`): the robot step, whose delta rules need
  constants, reads them row by row;
* **generic**: the rule runs once against the rows written into a schema graph, whatever the number
  of axioms (:mod:`.schema_program`, chosen by a full REASON when a table is large), its rows read
  before its body (:func:`.condition.leading`): a body of n atoms over one individual's facts is then n
  look-ups per row, not every n-tuple of the individual's facts.

The rows of a table are what an axiom contributes (:mod:`.schema_rows`), as SPARQL terms in the order
the schema atom's variables first appear (``(C, D)`` for ``C SubClassOf D``).  Axioms on an inverse property
expression have no row (no generic rule reads property expressions), nor have shapes of another width
(a chain of three, an intersection of nine members): the compiler keeps emitting their rules directly.
A rule of n body atoms may be a file per n (``cls-int1-2.rq`` … ``cls-int1-8.rq``, each rule named
``cls-int1``; ``neg-uni-2.rq`` … ``neg-uni-8.rq``), and rules of one name and width a file each, labelled
(``different-candidate-2-fp.rq`` and ``-2-ifp.rq``, ``prp-fp.rq`` and the data property's check
``prp-fp-2-data.rq``): a file is keyed by its name (:attr:`SchemaRule.key`), and :func:`template_of` finds a
rule's file by its name and width, and among several by the row the rule is of.  A check's instantiation
reports the individuals only (:attr:`SchemaRule.reported`); its message names the row's terms.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from functools import cache, cached_property, lru_cache

from pyoxigraph import NamedNode, Triple

from ..errors import RuleCompileError
from ..rdf.terms import parse_term
from ..rdf.vocab import INTERNAL, SCHEMA_PREFIX, SKOLEM_PREFIX, TYPE
from . import condition as cond
from .generic import parse_rule_text
from .rule import Atom, Rule, head_is_aux

#: A row of a schema table: the SPARQL terms bound to the schema atom's variables, in order.
Row = tuple[str, ...]

_INTERNAL_TEXT, _SKOLEM_TEXT, _TYPE_TEXT = f"<{INTERNAL}", f"<{SKOLEM_PREFIX}", str(TYPE)

#: How the rule files write the schema graph (replaced by the real graph when a rule is evaluated).
_SCHEMA_GRAPH_TEXT = "ts:graph:schema"


@dataclass(frozen=True)
class SchemaRule:
    """A generic OWL rule: ``rule`` with the schema variables free, and the schema atoms it joins."""

    rule: Rule
    schema: tuple[Atom, ...]
    #: the table the schema atoms read (the file's ``# schema:`` header, its first word)
    table: str
    #: above how many instantiations a full REASON runs the rule generically (the file's
    #: ``# generic-rows:`` header; None: :data:`.schema_program.GENERIC_ROWS`)
    generic_rows: int | None = None
    #: the file's name without ``.rq``: the rule's name, or the name and the body's width where one
    #: rule of n atoms is a file per n (``cls-int1-2``: an intersection of two members)
    key: str = ""
    #: the schema atoms' variables, in order of first appearance: a row binds them in this order
    variables: tuple[str, ...] = field(init=False)

    def __post_init__(self) -> None:
        seen: list[str] = []
        for atom in self.schema:
            seen += [t for t in (atom.s, atom.p, atom.o) if t.startswith("?") and t not in seen]
        object.__setattr__(self, "variables", tuple(seen))
        mentioned = set().union(*(c.variables for c in self.rule.conditions)) if self.rule.conditions else set()
        if mentioned & set(seen):
            raise RuleCompileError(f"{self.name}: a filter reads a schema variable, which instantiation cannot drop")
        body_vars = set().union(*(a.variables() for a in self.rule.body)) if self.rule.body else set()
        if not set(seen) <= body_vars | (self.rule.head.variables() if self.rule.head else set()):
            raise RuleCompileError(f"{self.name}: a schema variable is used by no body atom nor the head")

    @property
    def name(self) -> str:
        return self.rule.name

    def _substitute(self, atom: Atom, row: Row) -> Atom:
        bound = dict(zip(self.variables, row))
        return _atom(bound.get(atom.s, atom.s), bound.get(atom.p, atom.p), bound.get(atom.o, atom.o), atom.aux)

    @cached_property
    def reported(self) -> tuple[str, ...]:
        """A check's reported variables once instantiated: the schema variables are constants there
        (the generic check reports them, so that its message can name the row's terms)."""
        return tuple(v for v in self.rule.violation if v not in self.variables)

    def instantiate(self, row: Row, origin: str, labels: Sequence[str] | None = None) -> Rule:
        """The rule of one row: its constants substituted, the schema atoms dropped (they hold).

        A check's message names the row's terms by ``labels`` (default: their short names), as the
        generic check's report names the terms it read."""
        if len(row) != len(self.variables) or (labels is not None and len(labels) != len(row)):
            raise RuleCompileError(f"{self.name}: a row of {len(row)} terms for {len(self.variables)} variables")
        r = self.rule
        body_plan, head_plan, head_aux = self._instance_plan
        message = r.message
        if message:
            for var, label in zip(self.variables, labels if labels is not None else [_short(t) for t in row]):
                message = message.replace("{" + var[1:] + "}", label)
        body = tuple([plan if plan.__class__ is Atom else _put(plan, row) for plan in body_plan])
        # built from the template's prototype instead of through the dataclass's __init__: a robot's
        # first step on a large TBox instantiates a rule per pair of disjoint classes (tens of
        # thousands); the fields :meth:`Rule.__post_init__` derives are the prototype's but the reads
        rule = object.__new__(Rule)
        fields = rule.__dict__
        fields.update(self._prototype)
        fields["origin"], fields["body"], fields["message"] = origin, body, message
        fields["head"] = _put(head_plan, row) if head_plan is not None else None
        fields["_reads"] = frozenset([a._key for a in body]) | r.filter_reads
        if head_aux is not None:
            # the head names no schema variable: where it goes is the template's answer, decided once
            # (a robot step's first indexes ask it of every instantiation)
            fields["_head_aux"] = head_aux
        return rule

    @cached_property
    def _prototype(self) -> dict:
        """The fields every instantiation shares (:meth:`instantiate` replaces the row's)."""
        r = self.rule
        made = Rule(r.name, r.origin, r.body, r.head, r.conditions, r.filter_reads, self.reported, r.message,
                    r.aux_head, r.stratum)
        return {k: v for k, v in vars(made).items() if k != "_head_aux"}

    @cached_property
    def _instance_plan(self) -> tuple[tuple[_Plan, ...], _Plan | None, bool | None]:
        """How an instantiation is built, worked out once per template rather than per row: per body
        atom (and the head) the atom itself when it names no schema variable, else its terms with each
        schema variable replaced by its position in the row; and the head's graph when the head names
        no schema variable (None: decided per instantiation)."""
        position = {v: i for i, v in enumerate(self.variables)}

        def plan(a: Atom) -> _Plan:
            terms = tuple(position.get(t, t) for t in (a.s, a.p, a.o))
            return a if all(isinstance(t, str) for t in terms) else (terms, a.aux)

        r = self.rule
        head = plan(r.head) if r.head is not None else None
        head_aux = r.head_aux() if isinstance(head, Atom) else None
        return tuple(plan(a) for a in r.body), head, head_aux

    def row_of(self, rule: Rule) -> Row | None:
        """The row ``rule`` is the instantiation of, or None when it is not one (another name or shape).

        What the passes after compilation made of a rule (a folded class, atoms dropped as implied)
        is kept: a rule matches only when its evaluated body, head and filters are the template's, and
        so are the settings an instantiation never has (:func:`_own_settings`)."""
        t = self.rule
        if (rule.name != t.name or len(rule.body) != len(t.body) or rule.conditions != t.conditions
                or rule.violation != self.reported or rule.stratum != t.stratum or rule.aux_head != t.aux_head
                or (rule.head is None) != (t.head is None) or _own_settings(rule)):
            return None
        atoms = rule.body + (rule.head,) if t.head is not None else rule.body
        bound: list[str | None] = [None] * len(self.variables)
        for got, (aux, terms) in zip(atoms, self._plan):
            if got.aux != aux:
                return None
            for g, w in zip((got.s, got.p, got.o), terms):
                if type(w) is int:  # a schema variable: the row's term, the same wherever it occurs
                    if g.startswith("?") or (bound[w] is not None and bound[w] != g):
                        return None
                    bound[w] = g
                elif w != g:
                    return None
        return tuple(bound)  # type: ignore[arg-type]  # every schema variable occurs (checked at load)

    @cached_property
    def _plan(self) -> tuple[tuple[bool, tuple[str | int, ...]], ...]:
        """Per atom of the template's body and head, what :meth:`row_of` compares: its helper flag, and
        per term the schema variable's index in a row or the term itself."""
        index = {v: i for i, v in enumerate(self.variables)}
        atoms = self.rule.body + ((self.rule.head,) if self.rule.head is not None else ())
        return tuple((a.aux, tuple(index.get(term, term) for term in (a.s, a.p, a.o))) for a in atoms)

    def triples(self, row: Row) -> list[str]:
        """The schema atoms of a row, as triples of SPARQL text (what the schema graph holds)."""
        bound = dict(zip(self.variables, row))
        return [f"{bound.get(a.s, a.s)} {bound.get(a.p, a.p)} {bound.get(a.o, a.o)} ." for a in self.schema]

    def triple_terms(self, rows: Iterable[Row]) -> Iterator[Triple]:
        """The schema atoms of ``rows`` as RDF triples (what :meth:`triples` writes as text), for a bulk
        write: a TBox of thousands of disjoint siblings has millions of rows, and text to parse per row
        cost most of a full REASON's write."""
        plan = [tuple((term, None) if term.startswith("?") else (None, _term(term)) for term in (a.s, a.p, a.o))
                for a in self.schema]
        index = {v: i for i, v in enumerate(self.variables)}
        for row in rows:
            for atom in plan:
                s, p, o = (_term(row[index[var]]) if var is not None else fixed for var, fixed in atom)
                yield Triple(s, p, o)

    @property
    def graph(self) -> NamedNode:
        """The graph a full REASON writes this rule's rows into (one per rule: rules sharing a table,
        such as cax-eqc1 and cax-eqc2, may be left different rows by the passes after compilation)."""
        return NamedNode(SCHEMA_PREFIX + (self.key or self.name))

    @property
    def chains(self) -> bool:
        """The rule copies one atom with one schema term replaced by another (cax-sco, prp-spo1): two
        rows ``(a, b)`` and ``(b, c)`` then conclude what ``(a, c)`` does, so its rows may be closed."""
        r = self.rule
        if len(r.body) != 1 or len(self.variables) != 2 or r.head is None or r.conditions:
            return False
        first, second = self.variables
        return self._substitute(r.body[0], (second, second)) == r.head and first in r.body[0].variables()

    def aux_test(self) -> str | None:
        """SPARQL that holds when a row's conclusion goes to the helper graph, as :func:`.rule.head_is_aux`
        decides it for the row's instantiation; None when no row's does (no schema term in the head)."""
        h = self.rule.head
        if h is None or h.aux:  # no row's (None) or every row's: a constant helper term (ts:notType)
            return None
        parts = []
        for term in (h.p, h.o):
            if term not in self.variables:
                continue
            if term == h.o and h.p == str(TYPE):
                parts.append(f'STRSTARTS(STR({term}), "{INTERNAL}")')  # a class expression or a helper class
            else:
                parts.append(f'(isIRI({term}) && STRSTARTS(STR({term}), "{INTERNAL}") '
                             f'&& !STRSTARTS(STR({term}), "{SKOLEM_PREFIX}"))')
        return " || ".join(parts) or None

    def row_aux(self, row: Row) -> bool:
        """Whether the conclusion of ``row`` goes to the helper graph: what :func:`.rule.head_is_aux`
        decides for the row's instantiation, on the SPARQL text (a full REASON asks it of every row:
        no IRI is built)."""
        r = self.rule
        if r.aux_head is not None or r.head is None:
            return bool(r.aux_head)
        bound = dict(zip(self.variables, row))
        p, o = bound.get(r.head.p, r.head.p), bound.get(r.head.o, r.head.o)
        if any(t.startswith(_INTERNAL_TEXT) and not t.startswith(_SKOLEM_TEXT) for t in (p, o)):
            return True
        return p == _TYPE_TEXT and o.startswith(_SKOLEM_TEXT)

    def evaluable(self, aux: bool) -> Rule:
        """The generic rule: one rule joining the rows of :attr:`graph`, whatever their number, for the
        rows whose conclusions go to the helper graph (``aux``) or to the inferred graph."""
        pattern = " ".join(a.text() for a in self.schema)
        # the rows first: every body atom is then a look-up of bound classes (:func:`.condition.leading`)
        conditions = self.rule.conditions + (cond.leading(f"GRAPH {self.graph} {{ {pattern} }}"),)
        test = self.aux_test()
        if test is not None:
            conditions += (cond.test(test if aux else f"!({test})"),)
        r = self.rule
        where = "helper" if aux else "inferred"
        return Rule(r.name, f"{r.origin} (generic: the rows of {self.table}, conclusions in the {where} graph)",
                    r.body, r.head, conditions, r.filter_reads, r.violation, r.message, aux, r.stratum)


def _own_settings(rule: Rule) -> bool:
    """Whether ``rule`` carries what no instantiation of a file has: a body or filters as written (an
    explanation's premises), a known conclusion that makes its asks idle (``unless_known``, which a
    full REASON's ask reads), a range to decide values by.  Such a rule is no row of the file: read as
    one, the generic rule over the table would stand for it and those settings would be lost."""
    return (bool(rule.written) or rule.written_conditions is not None or rule.unless_known is not None
            or rule.value_range is not None)


def _term(text: str):
    """The RDF term a row's SPARQL text names (:func:`..rdf.terms.parse_term`, kept per text)."""
    term = parse_term(text)
    if term is None:
        raise RuleCompileError(f"a schema row term is not an RDF term: {text!r}")
    return term


#: an atom of a template as an instantiation builds it: the atom itself (no schema variable), or its
#: (subject, predicate, object) with a schema variable as its position in the row, and its ``aux``
_Plan = Atom | tuple[tuple[str | int, str | int, str | int], bool]


def _put(plan: _Plan, row: Row) -> Atom:
    """The atom of ``plan`` for ``row`` (:meth:`SchemaRule._instance_plan`)."""
    if plan.__class__ is Atom:
        return plan  # type: ignore[return-value]
    (s, p, o), aux = plan  # type: ignore[misc]
    if s.__class__ is int:
        s = row[s]
    if p.__class__ is int:
        p = row[p]
    if o.__class__ is int:
        o = row[o]
    return _atom(s, p, o, aux)


@lru_cache(maxsize=1 << 16)
def _atom(s: str, p: str, o: str, aux: bool) -> Atom:
    """One :class:`Atom` per pattern: the rows of a table repeat their terms (a class in every row of
    its disjoint siblings), and an instantiation then reuses the atom instead of deriving it again."""
    return Atom(s, p, o, aux)


@cache
def schema_rules() -> dict[str, SchemaRule]:
    """The generic OWL rules of ``rules/owl/``, by name."""
    from ..resources import rules_dir

    found: dict[str, SchemaRule] = {}
    for path in sorted((rules_dir() / "owl").glob("*.rq")):
        rule, schema, headers = parse_rule_text(path)
        if not schema or not headers.get("schema"):
            raise RuleCompileError(f"{path}: a rule of rules/owl/ needs a '# schema:' header and a schema atom "
                                   f"(GRAPH {_SCHEMA_GRAPH_TEXT} {{ ... }})")
        width = f"{rule.name}-{len(rule.body)}"
        if path.stem not in (rule.name, width) and not path.stem.startswith(width + "-"):
            raise RuleCompileError(f"{path}: the file is named as its rule ({rule.name}.rq), or as its rule and "
                                   f"the number of its body atoms ({width}.rq, {width}-LABEL.rq for several "
                                   f"files of one width)")
        found[path.stem] = SchemaRule(_marked_head(rule), schema, headers["schema"].split()[0],
                                      _rows_header(path, headers.get("generic-rows")), path.stem)
    return found


@cache
def _by_shape() -> dict[tuple[str, int], tuple[SchemaRule, ...]]:
    """The generic rules by (name, number of body atoms): a rule written as a file per width has several,
    and a width may have several files (``different-candidate-2-fp``, ``-2-ifp``: two atoms each)."""
    found: dict[tuple[str, int], list[SchemaRule]] = {}
    for t in schema_rules().values():
        found.setdefault((t.name, len(t.rule.body)), []).append(t)
    return {shape: tuple(files) for shape, files in found.items()}


def template_of(rule: Rule) -> SchemaRule | None:
    """The file of ``rules/owl/`` ``rule`` may be an instantiation of (by its name and width), or None.

    Where several files have that shape, the one ``rule`` is a row of, or whose graph its conditions
    read (a generic rule), else the first."""
    files = _by_shape().get((rule.name, len(rule.body)))
    if files is None or len(files) == 1:
        return files[0] if files else None
    for t in files:
        if t.row_of(rule) is not None:
            return t
    for t in files:
        if any(str(t.graph) in c.text for c in rule.conditions):
            return t
    return files[0]


def _rows_header(path, text: str | None) -> int | None:
    """The ``# generic-rows:`` header, a count of rows (its first word)."""
    if text is None:
        return None
    word = text.split()[0] if text.split() else ""
    if not word.isdigit():
        raise RuleCompileError(f"{path}: '# generic-rows:' needs a number of rows, not {text!r}")
    return int(word)


def _marked_head(rule: Rule) -> Rule:
    """``rule`` with a head of constant helper terms marked as a helper atom (``ts:declaredDifferent``),
    as the compiler's atoms of the helper graph are: a SPARQL CONSTRUCT cannot write the graph."""
    h = rule.head
    if h is None or h.aux or not head_is_aux(h.p, h.o):
        return rule
    return replace(rule, head=Atom(h.s, h.p, h.o, aux=True))


def schema_dataset(rule: Rule) -> str:
    """The ``USING NAMED`` clause of the schema graph a generic rule joins ("" for any other rule):
    an update's GRAPH pattern sees only the graphs its dataset names."""
    generic = template_of(rule)
    if generic is None or not any(str(generic.graph) in c.text for c in rule.conditions):
        return ""
    return f" USING NAMED {generic.graph}"


def schema_rule(name: str) -> SchemaRule:
    try:
        return schema_rules()[name]
    except KeyError:
        raise RuleCompileError(f"no generic OWL rule {name!r} in rules/owl/") from None


def _short(term: str) -> str:
    """A row term's short name in a message (``<http://x#A>`` → ``A``), as a check's report shows it."""
    value = term[1:-1] if term.startswith("<") else term
    return value.rsplit("#", 1)[-1] if "#" in value else value.rsplit("/", 1)[-1]


__all__ = ["Row", "SchemaRule", "schema_dataset", "schema_rule", "schema_rules", "template_of"]
