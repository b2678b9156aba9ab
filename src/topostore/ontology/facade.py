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
from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from pyoxigraph import Literal, NamedNode, Quad, RdfFormat, Triple

from ..compile import RuleSet, compile_ontology
from ..compile.builtins import FUNCTIONS as RULE_FUNCTIONS
from ..compile.notices import Notice
from ..compile.swrl_text import removal_triples, rule_labels, rule_triples
from ..rdf.skolem import named
from ..rdf.terms import Term, check_literal, entity, literal_of
from ..rdf.vocab import (
    ASSERTED,
    AUX,
    DEFAULT_PREFIX,
    ENTAILED,
    INFERRED,
    NOTHING,
    TYPE,
    XSD,
    owl,
)
from ..reason import ReasonStats, Violation, classify
from ..reason import limits as reason_limits
from ..reason.incremental import DEFAULT_MAX_CHANGE_SHARE, IncrementalReasoner
from ..reason.limits import ReasonLimits
from ..stores import StoreSpec, check_rules, open_store
from ..stores.base import Store
from ..stores.facts import Fact
from ..stores.literal_forms import FORMS
from ..stores.meta import META
from . import state as durable_state
from .changes import AssertedChanges
from .events import EventHub
from .files import OntologyFiles, is_schema_triple
from .ledger import ChangeLedger, all_or_nothing
from .named_queries import QueryItem
from .reads import OntologyQueries
from .views import ClassViews, Render


@dataclass
class ReasonReport:
    """The outcome of :meth:`Ontology.reason`."""

    consistent: bool
    violations: list[Violation] = field(default_factory=list)
    stats: ReasonStats = field(default_factory=ReasonStats)
    #: axioms not reasoned completely (non-Horn or unsupported), each with the reason
    #: (:class:`topostore.compile.notices.Notice`); empty when the answers are complete
    incomplete: list[Notice] = field(default_factory=list)

    def explain(self) -> str:
        return "consistent" if self.consistent else "; ".join(str(v) for v in self.violations)


class Ontology:
    """One ontology: asserted and inferred graphs in an Oxigraph store, plus its rules.

    This class holds the state and reasoning, and delegates to named parts:
    loading and saving to ``files`` (:class:`~topostore.ontology.files.OntologyFiles`), the read
    API to ``reads`` (:class:`~topostore.ontology.reads.OntologyQueries`), the manipulations to
    ``changes`` (:class:`~topostore.ontology.changes.AssertedChanges`), the record of asserted
    changes to ``ledger`` (:class:`~topostore.ontology.ledger.ChangeLedger`).
    """

    def __init__(self, prefix: str | None = None, store: Store | StoreSpec = None, strict: bool = False) -> None:
        """``store``: a Store, or a store setting (None: memory; a directory; an http(s) SPARQL server URL).

        ``strict``: refuse (IncompleteOntologyError, nothing changed) a document with axioms topostore
        does not reason completely or rules it had to skip, instead of loading it with warnings.

        A durable store whose inferred graphs were left unfinished (or inconsistent) is brought back by
        a full REASON here, in the constructor; :attr:`opened` then says "rebuilt" and the log says why
        (see :func:`topostore.ontology.state.reopen`)."""
        self.store = store if isinstance(store, Store) else open_store(store)
        self.store.use_functions(RULE_FUNCTIONS)  # the extension functions compiled rules call (swrlb:pow)
        #: loading and saving
        self.files = OntologyFiles(self)
        #: the read API (types, instances, values, SPARQL, named queries)
        self.reads = OntologyQueries(self)
        self._prefix = prefix
        self._found_prefix: str | None = None
        self._rules: RuleSet | None = None
        self._superclasses: dict | None = None
        self._report: ReasonReport | None = None
        self.load_notices = []  # what loading repaired or set aside (topostore.compile.notices)
        self.strict = strict
        self.dirty = True  # asserted graph changed since the last reasoning
        #: the asserted changes since the last successful REASON: what incremental REASON, rollback and
        #: a unit of work's undo read (see topostore.ontology.ledger)
        self.ledger = ChangeLedger()
        #: the manipulation path: every asserted change, recorded in the ledger
        self.changes = AssertedChanges(self)
        self._reasoner: IncrementalReasoner | None = None
        #: share of the asserted graph above which REASON recomputes from scratch instead of incrementally
        self.max_change_share = DEFAULT_MAX_CHANGE_SHARE
        #: rounds, inferred facts and seconds one REASON may use (see topostore.reason.limits)
        self.limits: ReasonLimits = reason_limits.DEFAULTS
        #: class answers kept up to date from each REASON's touched type facts (see topostore.ontology.views)
        self.views = ClassViews()
        #: change notifications: subscribe with ``onto.events.subscribe(callback, "rdf:type URGENT")``
        self.events = EventHub(lambda: self.prefix)
        self.store.on_lost.append(self._writes_lost)
        #: how a durable store was found: "new", "reopened" or "rebuilt" (see topostore.ontology.state)
        self.opened = durable_state.reopen(self)

    def restore_report(self, consistent: bool, dirty: bool) -> None:
        """State of a reopened durable ontology: its last REASON's outcome (no violations kept)."""
        self._report = ReasonReport(consistent)
        self.dirty = dirty

    @property
    def prefix(self) -> str:
        """Namespace for entity names: the ontology IRI + '#' unless given."""
        if self._prefix is None:
            if self._found_prefix is None:  # looked up once per schema change (a round trip on a server)
                found = DEFAULT_PREFIX
                # kept only once the read succeeded: a read that fails (a remote store's queued writes
                # refused on the way) must not leave the default namespace behind for good
                for t in self.store.triples(None, TYPE, owl("Ontology"), ASSERTED):
                    if isinstance(t.subject, NamedNode):
                        iri = t.subject.value
                        found = iri if iri.endswith(("#", "/")) else iri + "#"
                        break
                self._found_prefix = found
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

    # ------------------------------------------------------------------ manipulation (the ``changes`` part)
    def add(self, *triples: Triple) -> int:
        """Assert triples (a blank node named as a load names it); returns how many were new."""
        return self.changes.add(*named(triples))

    def remove(self, *triples: Triple) -> int:
        """Retract asserted triples (inferred ones cannot be removed, only their premises)."""
        return self.changes.remove(*named(triples))

    def add_new(self, *triples: Triple) -> list[Triple]:
        """Assert triples; returns those that were new (see :meth:`AssertedChanges.add_new`)."""
        return self.changes.add_new(*triples)

    def remove_present(self, *triples: Triple) -> list[Triple]:
        """Retract asserted triples; returns those that were asserted."""
        return self.changes.remove_present(*triples)

    def change(self, add: Sequence[Triple | Fact], remove: Sequence[Triple | Fact]) -> tuple[list[Triple], list[Triple]]:
        """Retract ``remove``, then assert ``add``, in one transaction (see :meth:`AssertedChanges.change`)."""
        return self.changes.change(add, remove)

    def schema_changed(self) -> None:
        """A schema triple was added or removed: the rules, the classification and the namespace are read again."""
        self._rules = None
        self._superclasses = None
        self._found_prefix = None
        self.ledger.stop_incremental()

    def incremental_ready(self) -> bool:
        """Whether the reasoner can maintain its closure from the ledger's net changes."""
        return self._reasoner is not None and self._reasoner.state.ready

    def forget_reasoning(self) -> None:
        """Drop the compiled rules and the reasoner: the asserted graph was changed underneath them (rollback)."""
        self._rules = None
        self._superclasses = None
        self._reasoner = None
        self.ledger.stop_incremental()
        self.dirty = True

    def _writes_lost(self, lost: list[tuple[list[Quad], list[Quad]]], certain: bool) -> None:
        """The store could not write changes it had accepted (a remote store defers them): undo them
        here too.  The ledger is set back exactly; a lost write of the reasoner's graphs, or a loss the
        store cannot state exactly (``certain`` false: a server that did not answer may hold the changes
        after all; a lost drop of scratch graphs), makes the next REASON a full one over what the server
        holds; class views wait for the next REASON."""
        def asserted(quads: list[Quad]) -> list[Triple]:
            return [q.triple for q in quads if q.graph_name == ASSERTED]

        self.ledger.lost(self.store, [(asserted(adds), asserted(removes)) for adds, removes in lost])
        if not certain or any(q.graph_name not in (ASSERTED, FORMS, META) for adds, removes in lost
                              for q in adds + removes):
            self._reasoner = None
            self.ledger.stop_incremental()
        self.dirty = True
        self.views.clear()

    def value(self, value: object, datatype: str | None = None) -> Literal:
        """A validated literal from a Python value (int → xsd:integer, ...) or text + datatype."""
        if isinstance(value, Literal):
            check_literal(value)
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
        return self.changes.add(self.fact(subject, prop, obj))

    def remove_fact(self, subject: str, prop: str, obj: object) -> int:
        return self.changes.remove(self.fact(subject, prop, obj))

    def add_type(self, individual: str, cls: str) -> int:
        return self.changes.add(Triple(self.iri(individual), TYPE, self.iri(cls)))

    def remove_type(self, individual: str, cls: str) -> int:
        return self.changes.remove(Triple(self.iri(individual), TYPE, self.iri(cls)))

    def add_data(self, prop: str, individual: str, value: object, datatype: str | None = None) -> int:
        return self.changes.add(Triple(self.iri(individual), self.iri(prop), self.value(value, datatype)))

    def replace(self, subject: str, prop: str, new: object, old: object | None = None) -> int:
        """Replace ``old`` by ``new`` (every current value when ``old`` is None); atomic.

        Values are matched by data value, so ``7`` replaces a stored ``"7"^^xsd:long``.
        Returns how many old facts were removed.
        """
        return self.changes.replace(subject, prop, new, old)

    def add_all_different(self, names: Sequence[str | NamedNode]) -> NamedNode:
        """One owl:AllDifferent over ``names`` (deduplicated): linear in size, never n² pairs."""
        return self.changes.add_all_different(names)

    def remove_individual(self, name: str | NamedNode) -> int:
        """Remove every asserted triple mentioning the individual, and whole AllDifferent axioms containing it."""
        return self.changes.remove_individual(name)

    def subscribe(self, callback, pattern: str | None = None, maxsize: int = 100):
        """Call ``callback(event)`` after each REASON that changed an inferred triple matching
        ``pattern`` (e.g. ``"rdf:type URGENT"``) or the consistency; see :mod:`topostore.ontology.events`."""
        return self.events.subscribe(callback, pattern, maxsize)

    # ------------------------------------------------------------------ explanations
    def explain(self, subject: str | Term, predicate: str | Term, obj: object):
        """Why ``subject predicate obj`` holds: a :class:`~topostore.ontology.explain.Explanation` tree
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
        return self.files._add_checked(rule_triples(text, label, self.store, self.prefix, comment))[0]

    def remove_rule(self, label: str) -> int:
        """Remove the SWRL rule(s) labelled ``label`` (loaded or added); RuleCompileError if none."""
        return self.changes.remove(*removal_triples(self.store, label))

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
        rules = self.rules  # the mode was checked by all_or_nothing
        forced = ""
        if self._reasoner is None or self._reasoner.ruleset is not rules:
            self._reasoner = IncrementalReasoner(self.store, rules)
        elif self.dirty and not self.ledger.incremental:
            forced = "asserted changes were not tracked (too many since the last REASON)"
        self._reasoner.max_change_share = self.max_change_share
        before = self.events.before_reason(self.store, None if self._report is None else self._report.consistent)
        added, removed = self.ledger.net_changes()
        durable_state.begin_reason(self.store)
        with self.store.keeping((ASSERTED,)):  # the reasoner writes its own graphs only
            stats, violations = self._reasoner.reason(added, removed, mode=mode, profile=profile,
                                                      forced_reason=forced)
        self.store.maybe_compact()
        previous, self._report = self._report, ReasonReport(not violations, violations, stats,
                                                            [n for n in rules.notices if n.incomplete])
        self._advance_views(previous)
        self.dirty = False
        self.events.after_reason(self.store, self._report.consistent, before, stats.seconds)
        durable_state.end_reason(self.store, self._report.consistent)
        return self._report

    def _advance_views(self, previous: ReasonReport | None) -> None:
        """Bring the class views to the new report (dropped when the visible graphs changed or the run was full)."""
        same_graphs = previous is not None and previous.consistent == self._report.consistent
        touched = self._reasoner.touched_types if same_graphs else None
        self.views.advance(previous, self._report, touched, self.reads._instance_flags)

    @property
    def report(self) -> ReasonReport | None:
        return self._report

    @property
    def is_consistent(self) -> bool:
        """Consistency as of the last reasoning.

        Reading it on an ontology never reasoned runs :meth:`reason` first (the aRMOR answer to
        "is it consistent?" needs a closure), so it may take as long as a REASON and raise what
        REASON raises; :attr:`report` is the side-effect-free read (None before any REASON)."""
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


    # ------------------------------------------------------------------ files (the ``files`` part)
    @classmethod
    def from_file(cls, *paths: str | os.PathLike[str], prefix: str | None = None, fmt: str | None = None,
                  base_iri: str | None = None, store: Store | StoreSpec = None, strict: bool = False) -> Ontology:
        """A new ontology with the documents at ``paths`` loaded in order."""
        onto = cls(prefix=prefix, store=store, strict=strict)
        for p in paths:
            onto.load(p, fmt=fmt, base_iri=base_iri)
        return onto

    def load(self, path: str | os.PathLike[str], fmt: str | None = None, base_iri: str | None = None,
             progress: Callable[[int], None] | None = None) -> int:
        """Add a document's triples to the asserted graph; all or nothing (see :meth:`OntologyFiles.load`)."""
        return self.files.load(path, fmt, base_iri, progress)

    def load_data(self, data: str | bytes, fmt: str = "turtle", base_iri: str | None = None) -> int:
        """Add a document given as text or bytes; all or nothing."""
        return self.files.load_data(data, fmt, base_iri)

    @property
    def notices(self) -> list[Notice]:
        """What loading repaired or set aside, then what the current rules set aside or reason only in part."""
        return self.files.notices

    def notice_lines(self) -> list[str]:
        """:attr:`notices` one line per kind (and axiom kind), naming each rule or axiom with its reason."""
        return self.files.notice_lines()

    def triples(self, inferred: bool = False) -> list[Triple]:
        """The asserted (or visible) triples, literals as the user wrote them."""
        return self.files.triples(inferred)

    def serialize(self, fmt: str | RdfFormat = "turtle", inferred: bool = False) -> bytes:
        return self.files.serialize(fmt, inferred)

    def save(self, path: str | os.PathLike[str], fmt: str | None = None, inferred: bool = False) -> Path:
        """Write asserted (or asserted + inferred) triples; the format follows the extension."""
        return self.files.save(path, fmt, inferred)

    # ------------------------------------------------------------------ reads (the ``reads`` part)
    def types(self, individual: str | NamedNode) -> list[NamedNode]:
        """Named classes of an individual (asserted ∪ inferred), without owl:Thing."""
        return self.reads.types(individual)

    def instances(self, cls: str | NamedNode) -> list[NamedNode]:
        """Individuals of a class (asserted ∪ inferred); a class asked again after REASON is read from its view."""
        return self.reads.instances(cls)

    def rendered_instances(self, cls: str | NamedNode, key: Hashable, render: Render) -> list[str]:
        """:meth:`instances` rendered by ``render`` (None leaves a member out), sorted, without duplicates."""
        return self.reads.rendered_instances(cls, key, render)

    def object_values(self, prop: str | NamedNode, individual: str | NamedNode, names: bool = True) -> list:
        return self.reads.object_values(prop, individual, names)

    def data_values(self, prop: str | NamedNode, individual: str | NamedNode) -> list[Literal]:
        return self.reads.data_values(prop, individual)

    def properties_of(self, individual: str | NamedNode, data: bool) -> list[NamedNode]:
        return self.reads.properties_of(individual, data)

    def sparql(self, text: str, bindings: dict[str, Term] | None = None, **kwargs):
        """Raw SPARQL over the visible graphs, through the one guard on user SPARQL."""
        return self.reads.sparql(text, bindings, **kwargs)

    def select(self, text: str, bindings: dict[str, Term] | None = None, timeout: float | None = None):
        """(variables, rows, timed_out) of a SELECT query over the visible graphs."""
        return self.reads.select(text, bindings, timeout)

    def query(self, name_or_text: str, params: dict[str, object] | None = None,
              timeout: float | None = None) -> list[QueryItem]:
        """Run a named query (or SELECT text) and return ``QueryItem`` results."""
        return self.reads.query(name_or_text, params, timeout)

    def query_names(self) -> dict[str, str]:
        """The named queries this ontology runs by name (name → description)."""
        return self.reads.query_names()


__all__ = ["Ontology", "ReasonReport", "is_schema_triple", "NOTHING", "AUX"]
