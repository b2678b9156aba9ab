"""The :class:`Rule` value: what a rule reads, what it writes, where it comes from.

A rule is kept structured (body atoms apart from filters) rather than as one
SPARQL string, because the reasoner needs to evaluate it in several ways: in
full, or with one body atom restricted to the facts derived in the previous
round (semi-naive evaluation), and it needs to know which predicates and
classes a rule reads to skip rules nothing new can trigger.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, TypeVar

from pyoxigraph import NamedNode

from ..rdf.vocab import AUX, TYPE, is_internal, is_skolem
from .condition import Condition, render
from .join_order import join_order

if TYPE_CHECKING:
    from .disjointness import Disjointness
    from .schema_tables import SchemaTables

#: A read key: ("p", predicate IRI), ("t", class IRI) for ``?x rdf:type <C>``,
#: or ("*",) for a pattern with a variable predicate (reads everything).
ReadKey = tuple


def key_pattern(key: ReadKey) -> tuple:
    """The (subject, predicate, object) pattern of a read key's facts (``("p", …)`` or ``("t", …)``),
    None where any term matches: what the reasoner looks a key up by in the store's indexes."""
    term = NamedNode(key[1][1:-1])
    return (None, TYPE, term) if key[0] == "t" else (None, term, None)

_TYPE_TEXT = str(TYPE)

T = TypeVar("T")


@dataclass(frozen=True)
class Atom:
    """One triple pattern; terms are SPARQL text (variables or rendered terms).

    ``aux`` marks a pattern over the reasoner's helper graph (anonymous class
    memberships, AllDifferent groups), which users never see.
    """

    s: str
    p: str
    o: str
    aux: bool = False
    # derived once: the reasoner asks for them thousands of times per REASON
    _key: ReadKey = field(init=False, repr=False, compare=False)
    _vars: frozenset = field(init=False, repr=False, compare=False)
    _hash: int = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.p.startswith("?"):
            key: ReadKey = ("*",)
        elif self.p == _TYPE_TEXT and not self.o.startswith("?"):
            key = ("t", self.o)
        else:
            key = ("p", self.p)
        object.__setattr__(self, "_key", key)
        object.__setattr__(self, "_vars", frozenset(t for t in (self.s, self.p, self.o) if t.startswith("?")))
        object.__setattr__(self, "_hash", hash((self.s, self.p, self.o, self.aux)))

    def __hash__(self) -> int:
        # kept: rule sets are merged and deduplicated by their atoms (tens of thousands on a large TBox)
        return self._hash

    def text(self) -> str:
        return f"{self.s} {self.p} {self.o} ."

    def read_key(self) -> ReadKey:
        return self._key

    def variables(self) -> set[str]:
        return set(self._vars)


def head_is_aux(p: str, o: str) -> bool:
    """Whether a derived triple belongs in the helper graph rather than the inferred one."""
    for term in (p, o):
        if term.startswith("<") and is_internal(NamedNode(term[1:-1])) and not is_skolem(term[1:-1]):
            return True
    # memberships of anonymous class expressions (skolemised blank nodes)
    return p == str(TYPE) and o.startswith("<") and is_skolem(o[1:-1])


@dataclass(frozen=True)
class Rule:
    """A Horn rule: if ``body`` (and ``conditions``) match, ``head`` holds.

    A rule with ``violation`` set is a consistency check instead: every match is
    an inconsistency, reported with the variables listed in ``violation``.
    """

    name: str
    origin: str
    body: tuple[Atom, ...]
    head: Atom | None = None
    #: the FILTERs and BINDs, in order, as the compiler built them
    conditions: tuple[Condition, ...] = ()
    filter_reads: frozenset = frozenset()
    violation: tuple[str, ...] = ()
    message: str = ""
    #: where the head goes: None decides from the head's terms, True = helper graph
    aux_head: bool | None = None
    #: evaluation stratum: rules with negated premises ("not known different")
    #: run only once everything they negate has reached its fixpoint
    stratum: int = 0
    #: the body as written, when atoms the TBox implies were dropped from ``body`` (see :mod:`.implied`)
    written: tuple[Atom, ...] = field(default=(), compare=False)
    #: the conditions as written, when dropping implied atoms added some (``FILTER(!isLiteral(?y))``)
    written_conditions: tuple[Condition, ...] | None = field(default=None, compare=False)
    #: a check that a data property's values lie in its range: (the property's IRI, the datatype's
    #: IRI), so that values already known can be decided without a query (see :func:`.datatypes.surely_in`)
    value_range: tuple[str, str] | None = field(default=None, compare=False)
    #: a candidate rule whose pairs need not be asked where this atom (the asking rule's ordinary
    #: conclusion) is known: a full REASON evaluates it last, without them (see :mod:`..reason.negation`)
    unless_known: Atom | None = field(default=None, compare=False)
    #: the conditions as SPARQL lines (rendered once: every evaluation text contains them)
    filters: str = field(init=False, repr=False, compare=False)
    _reads: frozenset = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "filters", render(self.conditions) if self.conditions else "")
        object.__setattr__(self, "_reads", frozenset([a._key for a in self.body]) | self.filter_reads)

    @property
    def premises(self) -> tuple[Atom, ...]:
        """The body as written: what an explanation shows (``body`` may leave implied atoms out)."""
        return self.written or self.body

    @property
    def written_filters(self) -> str:
        """The conditions as written, as SPARQL lines (what an explanation shows)."""
        return self.filters if self.written_conditions is None else render(self.written_conditions)

    @property
    def negates(self) -> bool:
        """A condition tests the absence of data: matches may disappear when facts are added."""
        return any(c.negated for c in self.conditions)

    @property
    def binds(self) -> frozenset[str]:
        """The variables the conditions bind (``?name``)."""
        return frozenset(c.binds for c in self.conditions if c.binds)

    @property
    def conditions_read_graph(self) -> bool:
        """A condition holds a graph pattern (an EXISTS), i.e. reads facts beyond the body's."""
        return any(c.reads_graph for c in self.conditions)

    @property
    def is_check(self) -> bool:
        return self.head is None

    def reads(self) -> frozenset:
        return self._reads

    def writes(self) -> ReadKey | None:
        return self.head.read_key() if self.head else None

    def head_aux(self) -> bool:
        return self._head_aux

    @cached_property
    def _head_aux(self) -> bool:
        """Whether the head goes to the helper graph (decided once: a full REASON asks per evaluation)."""
        if self.aux_head is not None:
            return self.aux_head
        return self.head is not None and head_is_aux(self.head.p, self.head.o)

    def where(self, delta_index: int | None = None, delta_graph: str = "",
              graphs: Mapping[ReadKey, NamedNode] | None = None) -> str:
        """The WHERE group; with ``delta_index``, that atom reads only the delta graph.

        Atoms are written in a join order chosen by :func:`join_order` (the delta
        atom first), because the store evaluates a basic graph pattern largely in
        the order it is written.  ``graphs`` names the one graph that holds every fact of
        some read keys (see :func:`.atom_text`).
        """
        if delta_index is None and not graphs:
            return self._plain_where
        return self._where(delta_index, delta_graph, graphs)

    @cached_property
    def bucket(self) -> tuple:
        """The name, head, body atoms (as a set, with their number) and filters: what :meth:`RuleSet.add`
        groups rules by before it compares their WHERE texts (kept: a compilation merges twice)."""
        return self.name, self.head, frozenset(self.body), len(self.body), self.filters

    @cached_property
    def _plain_where(self) -> str:
        """The WHERE group over the default graphs, built once: it is the rule's identity when rule sets
        are merged (:meth:`RuleSet.add`) and the text of most evaluations."""
        return self._where(None, "", None)

    @cached_property
    def placed(self) -> tuple[str, frozenset[str], str]:
        """The conditions as a WHERE places them: the leading ones' lines (a generic rule's schema rows,
        :func:`.condition.leading`), the variables those bind, and the other conditions' lines."""
        lead = tuple(c for c in self.conditions if c.leads)
        if not lead:
            return "", frozenset(), self.filters
        return render(lead), frozenset().union(*(c.variables for c in lead)), render(
            tuple(c for c in self.conditions if not c.leads))

    def _where(self, delta_index: int | None, delta_graph: str, graphs: Mapping[ReadKey, NamedNode] | None) -> str:
        lead, bound, filters = self.placed
        if lead and delta_index is not None and len(bound) <= 2:  # the delta first, then a pair's rows
            order = join_order(self.body, delta_index)
            atoms = [self.atom_text(i, delta_index, delta_graph, graphs) for i in order]
            lines = atoms[:1 + _binding(self.body, order, bound)]
            lines += [lead] + atoms[len(lines):]
        else:
            order = join_order(self.body, delta_index, bound)
            lines = ([lead] if lead else []) + [self.atom_text(i, delta_index, delta_graph, graphs) for i in order]
        if filters:
            lines.append(filters)
        return "\n  ".join(lines)

    def atom_text(self, i: int, delta_index: int | None = None, delta_graph: str = "",
                  graphs: Mapping[ReadKey, NamedNode] | None = None) -> str:
        """Body atom ``i`` as a pattern: on the delta graph, the helper graph, the one graph
        ``graphs`` names for its read key, or the default graph.

        A default-graph pattern is looked up in each graph of the default dataset (asserted,
        inferred, helper); where the caller knows that one graph holds all the key's facts, one
        look-up suffices (a quarter of a join's cost on the maps, docs/benchmarks-history.md).
        """
        atom = self.body[i]
        if i == delta_index:
            return f"GRAPH {delta_graph} {{ {atom.text()} }}"
        if atom.aux:
            return f"GRAPH {AUX} {{ {atom.text()} }}"
        graph = graphs.get(atom.read_key()) if graphs else None
        if graph is not None:
            return f"GRAPH {graph} {{ {atom.text()} }}"
        return atom.text()

    def sparql(self) -> str:
        """A readable rendering (CONSTRUCT or SELECT over the union graph), for `topostore rules`."""
        body = self.where()
        dropped = [a for a in self.written if a not in self.body]
        if dropped:
            body += "\n  # implied by the axioms, not evaluated: " + " ".join(a.text() for a in dropped)
        if self.head is not None:
            return f"# {self.name}: {self.origin}\nCONSTRUCT {{ {self.head.text()} }}\nWHERE {{\n  {body}\n}}"
        proj = " ".join(self.violation) or "*"
        return f"# {self.name}: {self.origin} (inconsistent when it matches)\nSELECT {proj}\nWHERE {{\n  {body}\n}}"


def _bucket(rule: Rule) -> tuple:
    """What two rules with the same WHERE text and head share (the text lists the body's atoms in join
    order, then the filters): a cheap key that only rules which may be one have in common."""
    return rule.bucket


@dataclass
class RuleSet:
    """All rules of one ontology, plus schema facts the query layer needs."""

    rules: list[Rule] = field(default_factory=list)
    #: named class -> its named superclasses (told and entailed), for class queries
    superclasses: dict[NamedNode, set[NamedNode]] = field(default_factory=dict)
    named_classes: set[NamedNode] = field(default_factory=set)
    data_properties: set[NamedNode] = field(default_factory=set)
    object_properties: set[NamedNode] = field(default_factory=set)
    #: predicates whose entailed-only conclusions are published (see vocab.ENTAILED)
    entailed_predicates: set[NamedNode] = field(default_factory=set)
    #: what the compilation set aside or reasons only in part (topostore.compile.notices.Notice)
    notices: list = field(default_factory=list)
    #: SQWRL queries of the ontology by name (compile.sqwrl.SqwrlQuery), run like named queries
    queries: dict = field(default_factory=dict)
    #: the pairs of disjoint classes as rows (:class:`.disjointness.Disjointness`), None when there are
    #: none: :attr:`rules` holds no rule per pair, :attr:`inference_rules` and :attr:`checks` do
    disjointness: Disjointness | None = None
    #: the instantiations of the rules of ``rules/owl/`` as tables (:class:`.schema_tables.SchemaTables`),
    #: None when there are none: :attr:`rules` holds none of them, :attr:`inference_rules` does
    tables: SchemaTables | None = None
    #: the AllDifferent keys' form: the one member list the asserted graph holds, whose members are their
    #: own keys (:mod:`.key_form`); None: a key names its list and member
    one_list: NamedNode | None = None
    #: (the list :meth:`add` last appended to, its length then, its rules by :func:`_bucket`)
    _seen: tuple | None = field(default=None, init=False, repr=False, compare=False)
    #: what :meth:`derived` made from :attr:`rules`: key -> (the rules list, its length, the value)
    _derived: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def derived(self, key: Hashable, make: Callable[[], T]) -> T:
        """``make()``, kept while :attr:`rules` is the same list of the same length: what every full
        REASON derives from the rules alone (which rules run generically, over which rows) is then
        derived once per compilation, not once per REASON."""
        held = self._derived.get(key)
        if held is not None and held[0] is self.rules and held[1] == len(self.rules):
            return held[2]
        value = make()
        self._derived[key] = (self.rules, len(self.rules), value)
        return value

    def add(self, rules: Iterable[Rule]) -> None:
        """Append the rules not already in the set: two rules are one when their name, WHERE text and
        head are the same (a body written in another order may give the same text).

        The WHERE text is compared only between rules of the same name, head, filters and body atoms
        (:func:`_bucket`): most rules of a large TBox share that with no other, and their texts are
        never built.  The buckets of the rules held are kept between calls (a compilation adds a dozen
        batches to tens of thousands of rules); they are read again only when :attr:`rules` was
        replaced or changed in between."""
        seen = self._seen_keys()
        for r in rules:
            bucket = seen.setdefault(_bucket(r), [])
            if bucket and any(other.where() == r.where() for other in bucket):
                continue
            bucket.append(r)
            self.rules.append(r)
        self._seen = (self.rules, len(self.rules), seen)

    def _seen_keys(self) -> dict[tuple, list[Rule]]:
        held = self._seen
        if held is not None and held[0] is self.rules and held[1] == len(self.rules):
            return held[2]
        seen: dict[tuple, list[Rule]] = {}
        for r in self.rules:
            seen.setdefault(_bucket(r), []).append(r)
        return seen

    @property
    def inference_rules(self) -> list[Rule]:
        """The inference rules, with the rows of the schema tables bound one by one and a rule per ordered
        pair of disjoint classes (what a robot step maintains rule by rule)."""
        return list(self.derived(("inference-rules", id(self.disjointness), id(self.tables)), lambda: [
            r for r in self.compiled_rules() if not r.is_check] + self._per_pair()[0]))

    def held_rules(self) -> list[Rule]:
        """The instantiations of the schema tables (none when the rule set holds no table)."""
        return [] if self.tables is None else self.tables.rules()

    def compiled_rules(self) -> list[Rule]:
        """:attr:`rules` with the schema tables' rows bound, each where the compiler emitted it."""
        return self.rules if self.tables is None else self.tables.merged(self.rules)

    @property
    def checks(self) -> list[Rule]:
        """The checks, with a ``cax-dw`` check per told pair of disjoint classes after the others."""
        return list(self.derived(("checks", id(self.disjointness), id(self.tables)), lambda: [
            r for r in self.compiled_rules() if r.is_check] + self._per_pair()[1]))

    @property
    def base_checks(self) -> list[Rule]:
        """The checks other than the disjointness of a told pair (:attr:`checks` begins with them)."""
        return list(self.derived(("base-checks", id(self.tables)), lambda: [
            r for r in self.compiled_rules() if r.is_check]))

    @property
    def all_rules(self) -> list[Rule]:
        """Every rule, the instantiations of the schema tables and of the disjointness rows included (what an explanation and
        ``topostore rules --all`` read)."""
        return list(self.derived(("all-rules", id(self.disjointness), id(self.tables)), lambda:
                                 self.compiled_rules() + self._per_pair()[0] + self._per_pair()[1]))

    def count_text(self) -> str:
        """How many rules, and the pairs of disjoint classes held as rows (what the CLI reports)."""
        text = f"{len(self.rules)} rules"
        if self.tables is not None:
            text += f" ({len(self.tables)} schema rows in {len(self.tables.held)} tables)"
        table = self.disjointness
        if table is not None:
            text += f" and {len(table.different)} ordered pairs of disjoint classes as rows"
        return text

    def _per_pair(self) -> tuple[list[Rule], list[Rule]]:
        if self.disjointness is None:
            return [], []
        return self.disjointness.rules()


def _binding(body: tuple[Atom, ...], order: list[int], lead_vars: frozenset[str]) -> int:
    """How many atoms of ``order`` after the first (the delta) a generic rule's schema rows follow
    (:meth:`Rule._where`): the first atoms until one of the rows' variables is bound, and a helper-graph
    atom of a bound term after it (its facts are few: ``different-disjoint``'s candidate pairs of a new
    class fact, not every class disjoint with it).

    Why not the rows first, as without delta: a table scanned whole per delta evaluation costs its size
    each round (``different-disjoint`` at 400 classes + 400 functional properties: 0.2 s of a full REASON's 0.6 s
    CPU, docs/benchmarks-history.md); read by a bound term it costs the delta's matches.  Rows of more
    than two terms (a union's or an intersection's members, a restriction's property and filler) still
    lead: ``neg-uni-8`` read after its delta did not end in a minute (the engine joined its other
    non-memberships before the rows bound their classes)."""
    known = set(body[order[0]]._vars)
    for n, i in enumerate(order[1:]):
        if known & lead_vars and not (body[i].aux and known & body[i]._vars):
            return n
        known |= body[i]._vars
    return len(order) - 1
