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
from collections.abc import Sequence

from pyoxigraph import Literal, NamedNode, Triple

from ..compile import RuleSet
from ..compile.builtins import FUNCTIONS as RULE_FUNCTIONS
from ..compile.notices import Notice
from ..compile.swrl_text import removal_triples, rule_labels, rule_triples
from ..rdf.skolem import named
from ..rdf.terms import Term
from ..rdf.vocab import ASSERTED, AUX, ENTAILED, INFERRED, NOTHING
from ..reason import Violation
from ..reason import limits as reason_limits
from ..reason.classify import Classification
from ..reason.incremental import DEFAULT_MAX_CHANGE_SHARE, IncrementalReasoner
from ..reason.limits import ReasonLimits
from ..stores import StoreSpec, open_store
from ..stores.base import Store
from ..stores.facts import Fact
from . import state as durable_state
from .changes import AssertedChanges
from .delegation import forward
from .events import EventHub
from .files import OntologyFiles, is_schema_triple
from .ledger import ChangeLedger, all_or_nothing
from .namespace import Namespace
from .reads import OntologyQueries
from .reasoning import OntologyReasoning, ReasonReport
from .values import OntologyValues
from .views import ClassViews


class Ontology:
    """One ontology: asserted and inferred graphs in an Oxigraph store, plus its rules.

    This class holds the state and reasoning, and delegates to named parts:
    loading and saving to ``files`` (:class:`~topostore.ontology.files.OntologyFiles`), the read
    API to ``reads`` (:class:`~topostore.ontology.reads.OntologyQueries`), the manipulations to
    ``changes`` (:class:`~topostore.ontology.changes.AssertedChanges`), the record of asserted
    changes to ``ledger`` (:class:`~topostore.ontology.ledger.ChangeLedger`), the rules, the reasoner
    and the report to ``reasoning`` (:class:`~topostore.ontology.reasoning.OntologyReasoning`), the
    values made from Python ones to ``values`` (:class:`~topostore.ontology.values.OntologyValues`).
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
        #: the compiled rules, the reasoner and the last REASON's report
        self.reasoning = OntologyReasoning(self)
        #: literals and facts made from Python values (with the language tags' spellings given)
        self.values = OntologyValues(self)
        #: the namespace entity names are read in
        self.names = Namespace(self.store, prefix)
        self._rules: RuleSet | None = None
        #: the current classification (``reason.classify.Classification``, made when first read); the one the last
        #: successful REASON answered is ``reasoning.kept``
        self._superclasses: Classification | None = None
        self._report: ReasonReport | None = None
        self.load_notices = []  # what loading repaired or set aside (topostore.compile.notices)
        self.strict = strict
        self.dirty = True  # asserted graph changed since the last reasoning
        #: a member link (owl:members, owl:distinctMembers) changed since the rules were compiled: the next
        #: REASON checks whether the AllDifferent keys' form still holds (topostore.compile.key_form)
        self.groups_touched = False
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
        self.store.on_lost.append(self.reasoning.writes_lost)
        self.store.on_rolled_back.append(self.reasoning.rolled_back)
        #: how a durable store was found: "new", "reopened", "rebuilt" or "asserted only" (see
        #: topostore.ontology.state)
        self.opened = durable_state.reopen(self)

    restore_report = forward("reasoning", OntologyReasoning.restore_report, "State of a reopened durable ontology: "
                             "its last REASON's outcome (no violations kept).")

    @property
    def prefix(self) -> str:
        """Namespace for entity names: the ontology IRI + '#' unless given."""
        return self.names.known or self.names.prefix  # read for every name of every command: known, no call

    @prefix.setter
    def prefix(self, value: str) -> None:
        self.names.given = value

    iri = forward("names", Namespace.iri, "IRI of a named entity (``<full IRI>`` or a name in :attr:`prefix`).")
    short = forward("names", Namespace.short, "Name of a term relative to :attr:`prefix` (full IRI otherwise); "
                    "literals as text.")

    # ------------------------------------------------------------------ manipulation (the ``changes`` part)
    def add(self, *triples: Triple) -> int:
        """Assert triples (a blank node named as a load names it); returns how many were new."""
        added = self.changes.add(*named(triples), said=True)
        self.values.asserted(triples)
        return added

    def remove(self, *triples: Triple) -> int:
        """Retract asserted triples (inferred ones cannot be removed, only their premises)."""
        return self.changes.remove(*named(triples))

    def add_new(self, *triples: Triple) -> list[Triple]:
        """Assert triples; returns those that were new (see :meth:`AssertedChanges.add_new`)."""
        new = self.changes.add_new(*triples)
        self.values.asserted(new)
        return new

    remove_present = forward("changes", AssertedChanges.remove_present, "Retract asserted triples; returns those "
                             "that were asserted.")

    def change(self, add: Sequence[Triple | Fact], remove: Sequence[Triple | Fact]) -> tuple[list[Triple], list[Triple]]:
        """Retract ``remove``, then assert ``add``, in one transaction (see :meth:`AssertedChanges.change`)."""
        added, removed = self.changes.change(add, remove)
        self.values.asserted(added)
        return added, removed

    def schema_changed(self) -> None:
        """A schema triple was added or removed: the rules, the classification and the namespace are read again."""
        self._rules = None
        self._superclasses = None
        self.names.forget()
        self.ledger.stop_incremental()

    def incremental_ready(self) -> bool:
        """Whether the reasoner can maintain its closure from the ledger's net changes."""
        return self._reasoner is not None and self._reasoner.state.ready

    def forget_reasoning(self) -> None:
        """Drop the compiled rules and the reasoner: the asserted graph was changed underneath them (rollback)."""
        self.reasoning.forget()

    def value(self, value: object, datatype: str | None = None, language: str | None = None) -> Literal:
        """A validated literal from a Python value (int → xsd:integer, ...) or text + datatype.

        ``language``: text tagged so (``value("colour", language="en-GB")``); the tag is kept as spelled
        once a change asserts the literal (pyoxigraph lowers tags: see :mod:`topostore.ontology.values`)."""
        return self.values.value(value, datatype, language)

    fact = forward("values", OntologyValues.fact, "A triple from names: ``obj`` is an individual name, a Literal or "
                   "a Python value.")
    add_fact = forward("values", OntologyValues.add_fact)
    remove_fact = forward("values", OntologyValues.remove_fact)
    add_type = forward("values", OntologyValues.add_type)
    remove_type = forward("values", OntologyValues.remove_type)
    add_data = forward("values", OntologyValues.add_data)
    replace = forward("values", OntologyValues.replace, """Replace ``old`` by ``new`` (every current value when \
``old`` is None); atomic.

Values are matched by data value, so ``7`` replaces a stored ``"7"^^xsd:long``.
Returns how many old facts were removed.""")

    add_all_different = forward("changes", AssertedChanges.add_all_different, "One owl:AllDifferent over ``names`` "
                                "(deduplicated): linear in size, never n² pairs.")
    remove_individual = forward("changes", AssertedChanges.remove_individual, "Remove every asserted triple "
                                "mentioning the individual, and whole AllDifferent axioms containing it.")

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
        return self.files._add_checked(rule_triples(text, label, self.store, self.prefix, comment), added_rules=True)[0]

    def remove_rule(self, label: str) -> int:
        """Remove the SWRL rule(s) labelled ``label`` (loaded or added); RuleCompileError if none."""
        return self.changes.remove(*removal_triples(self.store, label))

    def rule_labels(self) -> list[str]:
        return rule_labels(self.store)

    # ------------------------------------------------------------------ reasoning
    @property
    def rules(self) -> RuleSet:
        """The compiled rules (recompiled when the TBox or the SWRL rules change)."""
        return self._rules if self._rules is not None else self.reasoning.rules()

    @all_or_nothing  # under self.limits; a failure restores the state of the last successful REASON
    def reason(self, profile: bool = False, mode: str = "auto") -> ReasonReport:
        """Bring the inferred graph to the closure of the asserted graph as it is now.

        ``mode`` "auto" maintains the inferred graph incrementally from the net
        changes since the last reasoning when that is sound and the change is
        small, "incremental" whenever sound, "full" always recomputes.  The
        result is the same in every mode; ``report.stats.mode`` and
        ``.reason`` say which was used and why.
        """
        return self.reasoning.reason(profile, mode)  # the mode was checked by all_or_nothing

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
        return self.reasoning.superclasses(self.iri(cls))

    def subclasses(self, cls: str | NamedNode) -> set[NamedNode]:
        """Named classes subsumed by ``cls`` (direct and indirect, its equivalents included; never owl:Nothing;
        an unsatisfiable class is under every class, see :meth:`OntologyReasoning.unsatisfiable`)."""
        return self.reasoning.subclasses(self.iri(cls))

    # ------------------------------------------------------------------ files (the ``files`` part)
    @classmethod
    def from_file(cls, *paths: str | os.PathLike[str], prefix: str | None = None, fmt: str | None = None,
                  base_iri: str | None = None, store: Store | StoreSpec = None, strict: bool = False) -> Ontology:
        """A new ontology with the documents at ``paths`` loaded in order."""
        onto = cls(prefix=prefix, store=store, strict=strict)
        for p in paths:
            onto.load(p, fmt=fmt, base_iri=base_iri)
        return onto

    load = forward("files", OntologyFiles.load, "Add a document's triples to the asserted graph; all or nothing (see "
                   ":meth:`OntologyFiles.load`).")
    load_data = forward("files", OntologyFiles.load_data, "Add a document given as text or bytes; all or nothing.")

    @property
    def notices(self) -> list[Notice]:
        """What loading repaired or set aside, then what the current rules set aside or reason only in part."""
        return self.files.notices

    notice_lines = forward("files", OntologyFiles.notice_lines, """:attr:`notices` one line per kind (and axiom \
kind), naming each rule or axiom with its reason.""")
    triples = forward("files", OntologyFiles.triples, "The asserted (or visible) triples, literals as the user wrote them.")
    serialize = forward("files", OntologyFiles.serialize)
    save = forward("files", OntologyFiles.save, "Write asserted (or asserted + inferred) triples; the format follows "
                   "the extension.")

    # ------------------------------------------------------------------ reads (the ``reads`` part)
    types = forward("reads", OntologyQueries.types, "Named classes of an individual (asserted ∪ inferred), without "
                    "owl:Thing.")
    instances = forward("reads", OntologyQueries.instances, "Individuals of a class (asserted ∪ inferred); a class "
                        "asked again after REASON is read from its view.")
    rendered_instances = forward("reads", OntologyQueries.rendered_instances, ":meth:`instances` rendered by "
                                 "``render`` (None leaves a member out), sorted, without duplicates.")
    object_values = forward("reads", OntologyQueries.object_values)
    data_values = forward("reads", OntologyQueries.data_values)
    properties_of = forward("reads", OntologyQueries.properties_of)
    sparql = forward("reads", OntologyQueries.sparql, "Raw SPARQL over the visible graphs, through the one guard on "
                     "user SPARQL.")
    select = forward("reads", OntologyQueries.select, "(variables, rows, timed_out) of a SELECT query over the "
                     "visible graphs.")
    query = forward("reads", OntologyQueries.query, "Run a named query (or SELECT text) and return ``QueryItem`` "
                    "results.")
    query_names = forward("reads", OntologyQueries.query_names, "The named queries this ontology runs by name "
                          "(name → description).")


__all__ = ["Ontology", "ReasonReport", "is_schema_triple", "NOTHING", "AUX"]
