"""An ontology reference: store + compiled rules + reasoner.  The Python API.

>>> from topostore import Ontology
>>> onto = Ontology.from_file("ontology/topological_map.ttl", "ontology/topological_map_abox.ttl")
>>> onto.reason().consistent
True
>>> sorted(onto.object_values("canReach", "Robot1"))
['R1', 'R2']

Manipulations change the asserted graph only; :meth:`Ontology.reason`
brings the inferred graph to the closure of the asserted graph as it is *now*
(incrementally from the net changes since the last reasoning when that is
sound, see :mod:`topostore.reason.incremental`), so conclusions whose premises
were removed disappear.  Queries answer over
asserted ∪ inferred knowledge as of the last reasoning (only asserted knowledge
while the ontology is inconsistent, as aRMOR does).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from pyoxigraph import Literal, NamedNode, RdfFormat, Triple

from .compile import RuleSet, compile_ontology
from .compile.builtins import FUNCTIONS as RULE_FUNCTIONS
from .compile.swrl_text import removal_triples, rule_labels, rule_triples
from .errors import QueryError, UnknownTypeError
from .events import EventHub
from .queries import QueryItem, collect, get_named_query, render_jena, substitutions, to_items
from .reason import ReasonStats, Violation, classify
from .reason.incremental import DEFAULT_MAX_CHANGE_SHARE, IncrementalReasoner
from .journal import Journal, all_or_nothing
from .reason import limits as reason_limits
from .reason.limits import ReasonLimits
from .safeio import atomic_write
from .store import Store, fresh_skolem, guess_format, serialize
from .stores import StoreSpec, check_rules, open_store
from .stores import state as durable_state
from .terms import Term, entity, literal_of, value_key
from .reason.entailed import publish_entailed
from .vocab import (
    ASSERTED, AUX, ENTAILED, DECLARATION_TYPES, DIFFERENT_FROM, INFERRED, NIL, NOTHING, OWL, RDF, RDFS, SWRL, THING, TYPE,
    DEFAULT_PREFIX, FIRST, REST, STANFORD_SWRL, SWRLB, XSD, is_internal, is_skolem, owl,
)

_SCHEMA_NS = (RDF, RDFS, OWL, SWRL, STANFORD_SWRL)
_ABOX_PREDICATES = {TYPE, owl("sameAs"), DIFFERENT_FROM, FIRST, REST, owl("distinctMembers"), owl("members")}


def is_schema_triple(t: Triple) -> bool:
    """True for triples that change the rules (TBox axioms, SWRL rules), not just facts."""
    p = t.predicate
    if p == TYPE:
        return isinstance(t.object, NamedNode) and t.object.value.startswith(_SCHEMA_NS) and t.object not in (
            owl("NamedIndividual"), owl("Thing"), owl("AllDifferent"))
    if p in _ABOX_PREDICATES:
        return False
    return p.value.startswith(_SCHEMA_NS)


@dataclass
class ReasonReport:
    """The outcome of :meth:`Ontology.reason`."""

    consistent: bool
    violations: list[Violation] = field(default_factory=list)
    stats: ReasonStats = field(default_factory=ReasonStats)

    def explain(self) -> str:
        return "consistent" if self.consistent else "; ".join(str(v) for v in self.violations)


class Ontology:
    """One ontology: asserted and inferred graphs in an Oxigraph store, plus its rules."""

    def __init__(self, prefix: str | None = None, store: Store | StoreSpec = None) -> None:
        """``store``: a Store, or a store setting (None: memory; a directory; an http(s) SPARQL server URL)."""
        self.store = store if isinstance(store, Store) else open_store(store)
        self.store.use_functions(RULE_FUNCTIONS)  # the extension functions compiled rules call (swrlb:pow)
        self._prefix = prefix
        self._found_prefix: str | None = None
        self._rules: RuleSet | None = None
        self._superclasses: dict | None = None
        self._report: ReasonReport | None = None
        self.dirty = True  # asserted graph changed since the last reasoning
        # net asserted changes since the last reasoning (add then remove cancels),
        # tracked only while an incremental REASON can use them
        self._added: dict[Triple, None] = {}
        self._removed: dict[Triple, None] = {}
        self._tracking = False
        self._reasoner: IncrementalReasoner | None = None
        #: share of the asserted graph above which REASON recomputes from scratch instead of incrementally
        self.max_change_share = DEFAULT_MAX_CHANGE_SHARE
        #: rounds, inferred facts and seconds one REASON may use (see topostore.reason.limits)
        self.limits: ReasonLimits = reason_limits.DEFAULTS
        self._journal = Journal()  # asserted changes since the last successful REASON, to roll back
        #: change notifications: subscribe with ``onto.events.subscribe(callback, "rdf:type URGENT")``
        self.events = EventHub(lambda: self.prefix)
        #: how a durable store was found: "new", "reopened" or "rebuilt" (see stores/state.py)
        self.opened = durable_state.reopen(self)

    def restore_report(self, consistent: bool, dirty: bool) -> None:
        """State of a reopened durable ontology: its last REASON's outcome (no violations kept)."""
        self._report = ReasonReport(consistent)
        self.dirty = dirty

    # ------------------------------------------------------------------ loading
    @classmethod
    def from_file(cls, *paths: str | os.PathLike[str], prefix: str | None = None, fmt: str | None = None,
                  base_iri: str | None = None, store: Store | StoreSpec = None) -> "Ontology":
        onto = cls(prefix=prefix, store=store)
        for p in paths:
            onto.load(p, fmt=fmt, base_iri=base_iri)
        return onto

    def load(self, path: str | os.PathLike[str], fmt: str | None = None, base_iri: str | None = None,
             progress: Callable[[int], None] | None = None) -> int:
        """Add a document's triples to the asserted graph; all or nothing.

        Rules are compiled before anything is added, so a file with a rule that
        cannot be translated is refused and leaves the ontology as it was.
        ``progress(n)`` is told how many triples have been parsed so far.
        """
        triples = self.store.parse_file(path, fmt, base_iri, progress)
        return self._add_checked(triples)

    def load_data(self, data: str | bytes, fmt: str = "turtle", base_iri: str | None = None) -> int:
        triples = self.store.parse_bytes(data, guess_format("x", fmt), base_iri)
        return self._add_checked(triples)

    def _add_checked(self, triples: list[Triple]) -> int:
        """Add loaded triples; when they change the rules, compile first on a copy,
        so that an untranslatable rule leaves the ontology untouched, and keep
        that compilation (it is the one the new asserted graph gives)."""
        if not any(is_schema_triple(t) for t in triples):
            return self.add(*triples)
        scratch = Store()
        scratch.add(self.store.triples(graph=ASSERTED), ASSERTED)
        scratch.add(triples, ASSERTED)
        rules = compile_ontology(scratch, ASSERTED)  # raises RuleCompileError, nothing added
        check_rules(self.store, rules)
        added = self.add(*triples)
        self._rules = rules
        return added

    @property
    def prefix(self) -> str:
        """Namespace for entity names: the ontology IRI + '#' unless given."""
        if self._prefix is None:
            if self._found_prefix is None:  # looked up once per schema change (a round trip on a server)
                self._found_prefix = DEFAULT_PREFIX
                for t in self.store.triples(None, TYPE, owl("Ontology"), ASSERTED):
                    if isinstance(t.subject, NamedNode):
                        iri = t.subject.value
                        self._found_prefix = iri if iri.endswith(("#", "/")) else iri + "#"
                        break
            return self._found_prefix
        return self._prefix

    @prefix.setter
    def prefix(self, value: str) -> None:
        self._prefix = value

    def iri(self, name: str | NamedNode) -> NamedNode:
        """IRI of a named entity (``<full IRI>`` or a name in :attr:`prefix`)."""
        if not isinstance(name, (str, NamedNode)):
            raise TypeError(f"an entity name must be a string or a NamedNode, not {type(name).__name__}")
        return name if isinstance(name, NamedNode) else entity(name, self.prefix)

    def short(self, term: Term) -> str:
        """Name of a term relative to :attr:`prefix` (full IRI otherwise); literals as text."""
        if isinstance(term, NamedNode):
            v = term.value
            return v[len(self.prefix):] if v.startswith(self.prefix) else v
        if isinstance(term, Literal):
            return term.value
        return str(term)

    # ------------------------------------------------------------------ manipulation
    def add(self, *triples: Triple) -> int:
        """Assert triples; returns how many were new."""
        triples = tuple(dict.fromkeys(triples))
        for t in triples:
            _validate(t)
        self._touch(triples)
        self._track(triples, added=True)
        self._journal.record(self.store, triples, added=True)
        return self.store.add(triples, ASSERTED)

    def remove(self, *triples: Triple) -> int:
        """Retract asserted triples (inferred ones cannot be removed, only their premises)."""
        triples = tuple(dict.fromkeys(triples))
        self._touch(triples)
        self._track(triples, added=False)
        self._journal.record(self.store, triples, added=False)
        return self.store.remove(triples, ASSERTED)

    def _touch(self, triples: Iterable[Triple]) -> None:
        self.dirty = True
        durable_state.note_changed(self.store)
        if any(is_schema_triple(t) for t in triples):
            self._rules = None
            self._superclasses = None
            self._found_prefix = None
            self._stop_tracking()

    def _track(self, triples: Iterable[Triple], added: bool) -> None:
        """Record net asserted changes (call before the store changes; ``triples`` deduplicated).

        Tracking stops (and the next REASON is a full one) once the change
        exceeds the share of the asserted graph where incremental reasoning
        pays off, so loading a large file keeps no copy of it.
        """
        if not self._tracking:
            return
        mine, other = (self._added, self._removed) if added else (self._removed, self._added)
        for t in triples:
            t = self.store.stored_form(t)  # both sets hold triples as the store does, so they cancel
            if self.store.contains(t, ASSERTED) == added:
                continue  # adding a present triple or removing an absent one changes nothing
            if t in other:
                del other[t]
            else:
                mine[t] = None
        reasoner = self._reasoner
        limit = self.max_change_share * (reasoner.state.asserted_size if reasoner else 0)
        if len(self._added) + len(self._removed) > max(limit, 1000):
            self._stop_tracking()

    def _stop_tracking(self) -> None:
        self._tracking = False
        self._added.clear()
        self._removed.clear()

    def value(self, value: object, datatype: str | None = None) -> Literal:
        """A validated literal from a Python value (int → xsd:integer, ...) or text + datatype."""
        if isinstance(value, Literal):
            _validate_literal(value)
            return value
        if datatype is not None:
            if not isinstance(datatype, str):
                raise TypeError(f"a datatype must be a string, not {type(datatype).__name__}")
            local = datatype[len(XSD):] if datatype.startswith(XSD) else datatype
            return literal_of(str(value), local)
        if isinstance(value, bool):
            return literal_of(str(value).lower(), "boolean")
        if isinstance(value, int):
            return literal_of(str(value), "integer")
        if isinstance(value, float):
            return literal_of(repr(value), "double")
        return Literal(str(value))

    def fact(self, subject: str, prop: str, obj: object) -> Triple:
        """A triple from names: ``obj`` is an individual name, a Literal or a Python value."""
        o = self.iri(obj) if isinstance(obj, (str, NamedNode)) and not isinstance(obj, Literal) else self.value(obj)
        return Triple(self.iri(subject), self.iri(prop), o)

    def add_fact(self, subject: str, prop: str, obj: object) -> int:
        return self.add(self.fact(subject, prop, obj))

    def remove_fact(self, subject: str, prop: str, obj: object) -> int:
        return self.remove(self.fact(subject, prop, obj))

    def add_type(self, individual: str, cls: str) -> int:
        return self.add(Triple(self.iri(individual), TYPE, self.iri(cls)))

    def remove_type(self, individual: str, cls: str) -> int:
        return self.remove(Triple(self.iri(individual), TYPE, self.iri(cls)))

    def add_data(self, prop: str, individual: str, value: object, datatype: str | None = None) -> int:
        return self.add(Triple(self.iri(individual), self.iri(prop), self.value(value, datatype)))

    def replace(self, subject: str, prop: str, new: object, old: object | None = None) -> int:
        """Replace ``old`` by ``new`` (every current value when ``old`` is None); atomic.

        Values are matched by data value, so ``7`` replaces a stored ``"7"^^xsd:long``.
        Returns how many old facts were removed.
        """
        new_t = self.fact(subject, prop, new)
        s, p = new_t.subject, new_t.predicate
        with self.store.transaction():  # one commit: a durable store never holds half a REPLACE
            if old is None:
                olds = list(self.store.triples(s, p, None, ASSERTED))
            else:
                old_t = self.fact(subject, prop, old)
                key = value_key(old_t.object)
                olds = [t for t in self.store.triples(s, p, None, ASSERTED) if value_key(t.object) == key]
            self.remove(*olds)
            self.add(new_t)
        return len(olds)

    def add_all_different(self, names: Sequence[str | NamedNode]) -> NamedNode:
        """One owl:AllDifferent over ``names`` (deduplicated): linear in size, never n² pairs."""
        members = list(dict.fromkeys(self.iri(n) for n in names))
        group = fresh_skolem()
        triples = [Triple(group, TYPE, owl("AllDifferent"))]
        nodes = [fresh_skolem() for _ in members]
        triples.append(Triple(group, owl("distinctMembers"), nodes[0] if nodes else NIL))
        for i, (node, m) in enumerate(zip(nodes, members)):
            triples.append(Triple(node, FIRST, m))
            triples.append(Triple(node, REST, nodes[i + 1] if i + 1 < len(nodes) else NIL))
        self.add(*triples)
        return group

    def remove_individual(self, name: str | NamedNode) -> int:
        """Remove every asserted triple mentioning the individual, and whole AllDifferent axioms containing it."""
        ind = self.iri(name)
        doomed = list(self.store.triples(ind, None, None, ASSERTED)) + list(self.store.triples(None, None, ind, ASSERTED))
        for t in list(doomed):
            if t.predicate == FIRST:
                doomed += self._axiom_of_list_node(t.subject)
        return self.remove(*dict.fromkeys(doomed))

    def _axiom_of_list_node(self, node: Term) -> list[Triple]:
        head = node
        while True:
            prev = self.store.subjects(REST, head, ASSERTED)
            if not prev:
                break
            head = prev[0]
        out: list[Triple] = []
        for owner in self.store.subjects(owl("distinctMembers"), head, ASSERTED) + self.store.subjects(owl("members"), head, ASSERTED):
            out += list(self.store.triples(owner, None, None, ASSERTED))
            cur = head
            while cur != NIL:
                out += list(self.store.triples(cur, None, None, ASSERTED))
                rest = self.store.objects(cur, REST, ASSERTED)
                cur = rest[0] if rest else NIL
        return out

    def subscribe(self, callback, pattern: str | None = None, maxsize: int = 100):
        """Call ``callback(event)`` after each REASON that changed an inferred triple matching
        ``pattern`` (e.g. ``"rdf:type URGENT"``) or the consistency; see :mod:`topostore.events`."""
        return self.events.subscribe(callback, pattern, maxsize)

    # ------------------------------------------------------------------ explanations
    def explain(self, subject: str | Term, predicate: str | Term, obj: object):
        """Why ``subject predicate obj`` holds: a :class:`~topostore.explain.Explanation` tree
        (rule and premises down to asserted facts), "asserted", or "not entailed"."""
        from .explain import explain

        return explain(self, subject, predicate, obj)

    # ------------------------------------------------------------------ SWRL rules at run time
    def add_rule(self, text: str, label: str, comment: str | None = None) -> int:
        """Add a SWRL rule written as Protégé shows it (``A(?x) ^ p(?x, ?y) -> B(?y)``).

        Stored in the standard SWRL RDF vocabulary and compiled like a loaded
        rule; a rule that cannot be parsed or compiled is refused naming the
        atom (RuleCompileError) and nothing changes.  Takes effect at the next REASON.
        """
        return self._add_checked(rule_triples(text, label, self.store, self.prefix, comment))

    def remove_rule(self, label: str) -> int:
        """Remove the SWRL rule(s) labelled ``label`` (loaded or added); RuleCompileError if none."""
        return self.remove(*removal_triples(self.store, label))

    def rule_labels(self) -> list[str]:
        return rule_labels(self.store)

    # ------------------------------------------------------------------ reasoning
    @property
    def rules(self) -> RuleSet:
        """The compiled rules (recompiled when the TBox or the SWRL rules change)."""
        if self._rules is None:
            rules = compile_ontology(self.store, ASSERTED)
            check_rules(self.store, rules)
            self._rules = rules
        return self._rules

    @all_or_nothing  # under self.limits; a failure restores the state of the last successful REASON
    def reason(self, profile: bool = False, mode: str = "auto") -> ReasonReport:
        """Bring the inferred graph to the closure of the asserted graph as it is now.

        ``mode`` "auto" maintains the inferred graph incrementally from the net
        changes since the last reasoning when that is sound and the change is
        small, "incremental" whenever sound, "full" always recomputes.  The
        result is the same in every mode; ``report.stats.mode`` and
        ``.reason`` say which was used and why.
        """
        if mode not in ("auto", "incremental", "full"):
            raise ValueError(f"unknown reasoning mode {mode!r}; use auto, incremental or full")
        rules = self.rules
        forced = ""
        if self._reasoner is None or self._reasoner.ruleset is not rules:
            self._reasoner = IncrementalReasoner(self.store, rules)
        elif self.dirty and not self._tracking:
            forced = "asserted changes were not tracked (too many since the last REASON)"
        self._reasoner.max_change_share = self.max_change_share
        before = self.events.before_reason(self.store, None if self._report is None else self._report.consistent)
        added, removed = list(self._added), list(self._removed)
        self._stop_tracking()
        durable_state.begin_reason(self.store)
        try:
            stats, violations = self._reasoner.reason(added, removed, mode=mode, profile=profile,
                                                      forced_reason=forced)
        finally:
            self._tracking = self._reasoner.state.ready
        publish_entailed(self.store, rules)
        self.store.maybe_compact()
        self._report = ReasonReport(not violations, violations, stats)
        self.dirty = False
        self.events.after_reason(self.store, self._report.consistent, before, stats.seconds)
        durable_state.end_reason(self.store, self._report.consistent)
        return self._report

    @property
    def report(self) -> ReasonReport | None:
        return self._report

    @property
    def is_consistent(self) -> bool:
        """Consistency as of the last reasoning (reasons first if never reasoned)."""
        if self._report is None:
            self.reason()
        return self._report.consistent

    @property
    def violations(self) -> list[Violation]:
        return [] if self._report is None else self._report.violations

    def visible_graphs(self) -> list[NamedNode]:
        """Graphs queries see: asserted ∪ inferred (with the entailed-only SWRL
        conclusions), or asserted only while inconsistent."""
        if self._report is not None and not self._report.consistent:
            return [ASSERTED]
        return [ASSERTED, INFERRED, ENTAILED]

    def superclasses(self, cls: str | NamedNode) -> set[NamedNode]:
        if self._superclasses is None:
            self._superclasses = classify(self.rules)
        return set(self._superclasses.get(self.iri(cls), set()))

    def subclasses(self, cls: str | NamedNode) -> set[NamedNode]:
        """Named classes subsumed by ``cls`` (direct and indirect; never owl:Nothing)."""
        target = self.iri(cls)
        if self._superclasses is None:
            self._superclasses = classify(self.rules)
        return {c for c, sups in self._superclasses.items() if target in sups and c != target}

    # ------------------------------------------------------------------ queries
    def _objects(self, s: Term, p: NamedNode) -> list[Term]:
        seen: dict = {}
        for g in self.visible_graphs():
            for o in self.store.objects(s, p, g):
                seen.setdefault(value_key(o), self.store.original_literal(ASSERTED, s, p, o) if isinstance(o, Literal) else o)
        return list(seen.values())

    def types(self, individual: str | NamedNode) -> list[NamedNode]:
        """Named classes of an individual (asserted ∪ inferred), without owl:Thing."""
        return [t for t in self._objects(self.iri(individual), TYPE) if _is_user_class(t)]

    def instances(self, cls: str | NamedNode) -> list[NamedNode]:
        c = self.iri(cls)
        found: dict = {}
        for g in self.visible_graphs():
            for s in self.store.subjects(TYPE, c, g):
                if not is_internal(s) or is_skolem(s):
                    found[s] = None
        return list(found)

    def object_values(self, prop: str | NamedNode, individual: str | NamedNode, names: bool = True) -> list:
        vals = [o for o in self._objects(self.iri(individual), self.iri(prop)) if isinstance(o, NamedNode)]
        return [self.short(v) for v in vals] if names else vals

    def data_values(self, prop: str | NamedNode, individual: str | NamedNode) -> list[Literal]:
        return [o for o in self._objects(self.iri(individual), self.iri(prop)) if isinstance(o, Literal)]

    def properties_of(self, individual: str | NamedNode, data: bool) -> list[NamedNode]:
        s = self.iri(individual)
        props: dict = {}
        for g in self.visible_graphs():
            for t in self.store.triples(s, None, None, g):
                if isinstance(t.object, Literal) == data and not t.predicate.value.startswith(_SCHEMA_NS) and not is_internal(t.predicate):
                    props[t.predicate] = None
        return list(props)

    def sparql(self, text: str, bindings: dict[str, Term] | None = None, **kwargs):
        """Raw SPARQL over the visible graphs (asserted ∪ inferred).

        User text passes the one SPARQL guard (size, nesting, SERVICE, internal
        functions) before Oxigraph parses it, and runs without the reasoner's
        extension functions.
        ``bindings`` fix variables to terms with pyoxigraph's ``substitutions=``;
        in a SELECT query a bound variable must be projected.
        """
        from .sparql.guard import check_user_sparql  # here: the sparql package imports this module

        check_user_sparql(text)
        if bindings is not None and not isinstance(bindings, dict):
            raise TypeError(f"bindings must be a dict of variable name -> term, not {type(bindings).__name__}")
        kwargs.setdefault("custom_functions", {})
        if not bindings:
            return self.store.query(text, graphs=self.visible_graphs(), **kwargs)
        try:
            return self.store.query(text, graphs=self.visible_graphs(), substitutions=substitutions(bindings), **kwargs)
        except QueryError as exc:
            if "SELECT projection" not in str(exc):
                raise
            names = " ".join(f"?{b}" for b in bindings)
            raise QueryError(f"a query parameter must be in the SELECT list (add {names} to it): parameters are "
                             "bound with pyoxigraph's substitutions, which fix projected variables only") from None

    def select(self, text: str, bindings: dict[str, Term] | None = None, timeout: float | None = None):
        """(variables, rows, timed_out) of a SELECT query over the visible graphs."""
        result = self.sparql(text, bindings)
        if not hasattr(result, "variables"):
            raise QueryError("only SELECT queries return rows")
        return collect(result, timeout)

    def query(self, name_or_text: str, params: dict[str, object] | None = None, timeout: float | None = None) -> list[QueryItem]:
        """Run a named query (or SELECT text) and return ``QueryItem`` results.

        ``params`` values are entity names / NamedNodes for ``iri`` parameters
        and Python values or Literals for ``literal`` parameters.
        """
        params = params or {}
        if not isinstance(name_or_text, str):
            raise TypeError(f"a query name or text must be a string, not {type(name_or_text).__name__}")
        if name_or_text.lstrip().upper().startswith(("SELECT", "PREFIX", "BASE")):
            text, kinds = name_or_text, {k: "iri" for k in params}
        else:
            q = get_named_query(name_or_text)
            text, kinds = q.text, q.params
            missing = set(q.params) - set(params)
            if missing:
                raise QueryError(f"query {q.name!r} needs the parameter(s) {', '.join(sorted(missing))}")
            unknown = set(params) - set(q.params)
            if unknown:
                raise QueryError(f"query {q.name!r} has no parameter(s) {', '.join(sorted(unknown))}")
        bindings = {k: (self.iri(v) if kinds.get(k) == "iri" else self.value(v)) for k, v in params.items()}
        variables, rows, _ = self.select(text, bindings, timeout)
        # parameters are projected so that pyoxigraph can substitute them; their fixed values are not answers
        keep = [i for i, v in enumerate(variables) if v not in bindings]
        rows = [[row[i] for i in keep] for row in rows]
        return to_items([variables[i] for i in keep], rows, lambda t: render_jena(t, self.store.restore))

    # ------------------------------------------------------------------ persistence
    def triples(self, inferred: bool = False) -> list[Triple]:
        graphs = self.visible_graphs() if inferred else [ASSERTED]
        return self.store.dump(graphs, restore_literals_from=ASSERTED)

    def serialize(self, fmt: str | RdfFormat = "turtle", inferred: bool = False) -> bytes:
        rdf_format = guess_format("x", fmt) if isinstance(fmt, str) else fmt
        prefixes = {"owl": OWL, "rdf": RDF, "rdfs": RDFS, "xsd": XSD, "swrl": SWRL,
                    "swrlb": SWRLB, "": self.prefix}
        return serialize(self.triples(inferred), rdf_format, prefixes)

    def save(self, path: str | os.PathLike[str], fmt: str | None = None, inferred: bool = False) -> Path:
        """Write asserted (or asserted + inferred) triples; the format follows the extension."""
        path = Path(path)
        data = self.serialize(guess_format(path, fmt), inferred)
        return atomic_write(path, data)  # temporary file beside it, never through a symlink, removed on failure


def _is_user_class(t: Term) -> bool:
    return isinstance(t, NamedNode) and t.value not in DECLARATION_TYPES and t != THING and not is_internal(t)


def _validate_literal(lit: Literal) -> None:
    dt = lit.datatype.value
    if lit.language or not dt.startswith(XSD):
        return
    local = dt[len(XSD):]
    try:
        literal_of(lit.value, local)  # an invalid value of a type topostore knows raises InvalidValueError
    except UnknownTypeError:  # a datatype topostore does not validate (xsd:anyURI, xsd:gYear, ...): kept as written
        return


def _validate(t: Triple) -> None:
    if isinstance(t.object, Literal):
        _validate_literal(t.object)


__all__ = ["Ontology", "ReasonReport", "is_schema_triple", "NOTHING", "AUX"]
