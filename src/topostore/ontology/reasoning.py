"""The reasoning part of an ontology: its compiled rules, its reasoner, the last REASON's report.

A named part of one :class:`~topostore.ontology.facade.Ontology` (``onto.reasoning``); the ontology's
``rules``, ``reason``, ``superclasses`` and ``subclasses`` are these.  The state it works on (the
compiled rules ``onto._rules``, the reasoner ``onto._reasoner``, the report ``onto._report``, the
classification ``onto._superclasses``, ``onto.dirty``) stays on the ontology, where the loading, the
manipulation path and the ledger's rollback read and reset it too.  The classification the last successful
REASON answered is kept here (``kept``): what a buffered reasoner answers until the next one.
"""

from __future__ import annotations

from contextlib import nullcontext
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode, Quad, Triple

from ..compile import RuleSet, compile_ontology
from ..compile.graph_notices import MALFORMED, malformed_now
from ..compile.key_form import form_changed
from ..compile.notices import Notice, OntologyWarning, warn
from ..rdf.vocab import ASSERTED, HAS_VALUE, INFERRED, NOTHING, TYPE
from ..reason import ReasonStats, Violation
from ..reason.classify import Classification, unsatisfiable, unsatisfiable_text
from ..reason.incremental import IncrementalReasoner
from ..stores import check_rules
from ..stores.literal_forms import FORMS
from ..stores.meta import META
from . import state as durable_state

if TYPE_CHECKING:
    from .facade import Ontology


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


class OntologyReasoning:
    """Compiles one ontology's rules, runs its reasoner and keeps what the last REASON found."""

    def __init__(self, onto: Ontology) -> None:
        self.onto = onto
        #: the classification of the last successful REASON (its rules and value types, made when first read)
        self.kept: Classification | None = None
        #: the named values of the hasValue restrictions of one compiled rule set (schema triples: the same
        #: while the rules are)
        self._values_of: tuple[RuleSet, frozenset[NamedNode]] | None = None

    def rules(self) -> RuleSet:
        """The compiled rules, compiled again when the TBox or the SWRL rules changed."""
        onto = self.onto
        if onto._rules is None:
            rules = compile_ontology(onto.store, ASSERTED)
            check_rules(onto.store, rules)
            onto._rules = rules
        return onto._rules

    def reason(self, profile: bool, mode: str) -> ReasonReport:
        """The body of :meth:`Ontology.reason` (its mode checked and its failure undone by the ledger)."""
        onto = self.onto
        if onto.groups_touched:
            onto.groups_touched = False
            if onto._rules is not None and (form_changed(onto.store, ASSERTED, onto._rules.one_list)
                                            or _lists_said_otherwise(onto.store, onto._rules)):
                onto._rules = None  # the AllDifferent keys change form, or a list's notice: new rules, a full REASON
        rules = self.rules()
        forced = ""
        if onto._reasoner is None or onto._reasoner.ruleset is not rules:
            onto._reasoner = IncrementalReasoner(onto.store, rules)
        elif onto.dirty and not onto.ledger.incremental:
            forced = "asserted changes were not tracked (too many since the last REASON)"
        onto._reasoner.max_change_share = onto.max_change_share
        before = onto.events.before_reason(onto.store, None if onto._report is None else onto._report.consistent)
        added, removed = onto.ledger.net_changes()
        durable_state.begin_reason(onto.store)
        # the reasoner writes its own graphs only (what a store with listings keeps of the asserted graph stays)
        with onto.store.keeping((ASSERTED,)) if onto.store.listings is not None else nullcontext():
            stats, violations = onto._reasoner.reason(added, removed, mode=mode, profile=profile,
                                                      forced_reason=forced)
        onto.store.maybe_compact()
        previous, onto._report = onto._report, ReasonReport(not violations, violations, stats,
                                                            [n for n in rules.notices if n.incomplete])
        self.keep(rules)
        self._advance_views(previous)
        onto.dirty = False
        onto.events.after_reason(onto.store, onto._report.consistent, before, stats.seconds)
        durable_state.end_reason(onto.store, onto._report.consistent)
        return onto._report

    def _advance_views(self, previous: ReasonReport | None) -> None:
        """Bring the class views to the new report (dropped when the visible graphs changed or the run was full).

        The touched types are the closure's changes: an asserted type fact removed or added while the closure
        infers it too touches none of them.  While inconsistent the asserted graph alone is answered, where
        such a change is one of membership, so the views are dropped then."""
        onto = self.onto
        same_graphs = previous is not None and previous.consistent and onto._report.consistent
        touched = onto._reasoner.touched_types if same_graphs else None
        onto.views.advance(previous, onto._report, touched, onto.reads._instance_flags)

    def forget(self) -> None:
        """Drop the compiled rules and the reasoner: the asserted graph was changed underneath them (rollback)."""
        onto = self.onto
        onto._rules = None
        onto._superclasses = None
        self.kept = None  # no REASON answers the graph as it is now
        onto._reasoner = None
        onto.ledger.stop_incremental()
        onto.dirty = True

    def restore_report(self, consistent: bool, dirty: bool) -> None:
        """State of a reopened durable ontology: its last REASON's outcome (no violations kept)."""
        self.onto._report = ReasonReport(consistent)
        self.onto.dirty = dirty

    def rolled_back(self, adds: list[Quad], removes: list[Quad]) -> None:
        """A store transaction failed with asserted changes pending: the ledger forgets them (they were
        recorded as made, set back as refused writes are); the reasoner's own graphs are its own business
        (a failed REASON restores them)."""
        onto = self.onto
        added, removed = _asserted(adds), _asserted(removes)
        if added or removed:
            onto.ledger.lost(onto.store, [(added, removed)])
            onto.changes.touch(added + removed)  # a schema triple among them: rules compiled meanwhile are stale

    def writes_lost(self, lost: list[tuple[list[Quad], list[Quad]]], certain: bool) -> None:
        """The store could not write changes it had accepted (a remote store defers them): undo them
        here too.  The ledger is set back exactly; a lost write of the reasoner's graphs, or a loss the
        store cannot state exactly (``certain`` false: a server that did not answer may hold the changes
        after all; a lost drop of scratch graphs), makes the next REASON a full one over what the server
        holds; class views wait for the next REASON."""
        onto = self.onto
        onto.ledger.lost(onto.store, [(_asserted(adds), _asserted(removes)) for adds, removes in lost])
        if not certain or any(q.graph_name not in (ASSERTED, FORMS, META) for adds, removes in lost
                              for q in adds + removes):
            onto._reasoner = None
            onto.ledger.stop_incremental()
        onto.dirty = True
        onto.views.clear()

    def classification(self, said: bool = True) -> dict[NamedNode, set[NamedNode]]:
        """Each named class's superclasses, classified once per compiled rule set and value types (``said``: an
        unsatisfiable class is warned of when the classification is made)."""
        onto = self.onto
        rules = self.rules()
        values = self.value_types(rules)
        current = onto._superclasses
        if current is None or not current.of(rules, values):
            kept = self.kept
            current = onto._superclasses = kept if kept is not None and kept.of(rules, values) \
                else Classification(rules, values)
        return _made(current, said)

    def keep(self, rules: RuleSet | None = None) -> None:
        """Keep the classification of the rules and value types now as the one the last REASON answered (by
        reference: it is made when first read); at a successful REASON, and for a durable store reopened as
        its last REASON left it."""
        rules = self.rules() if rules is None else rules
        values = self.value_types(rules)
        current = self.onto._superclasses
        if current is not None and current.of(rules, values):
            self.kept = current
        elif self.kept is None or not self.kept.of(rules, values):
            self.kept = Classification(rules, values)

    def kept_classification(self) -> dict[NamedNode, set[NamedNode]] | None:
        """The classification the last successful REASON answered, made now if it was not (None: none kept)."""
        return None if self.kept is None else _made(self.kept, said=False)

    def unsatisfiable(self, classes: dict | None = None) -> list[NamedNode]:
        """The named classes no individual can be a member of (each under every class, as Pellet has it) in
        ``classes`` (a classification; None: the current one)."""
        return unsatisfiable(self.classification() if classes is None else classes)

    def value_types(self, rules: RuleSet | None = None) -> frozenset[Triple]:
        """The classes (told and inferred) of the named individuals the hasValue restrictions of ``rules`` (None:
        the current ones) give as values: a class told ``∃p.{a}`` is under ``∃p.K`` where ``a`` is a ``K``,
        which classification's prototypes see only with ``a``'s classes beside them."""
        values = self._has_values(self.rules() if rules is None else rules)
        if not values:
            return frozenset()
        store = self.onto.store
        return frozenset(Triple(a, TYPE, t.object) for a in values for g in (ASSERTED, INFERRED)
                         for t in store.triples(a, TYPE, None, g) if isinstance(t.object, NamedNode))

    def _has_values(self, rules: RuleSet) -> frozenset[NamedNode]:
        """The named values of the hasValue restrictions ``rules`` were compiled from, read once per rule set."""
        if self._values_of is None or self._values_of[0] is not rules:
            store = self.onto.store
            self._values_of = (rules, frozenset(t.object for t in store.triples(None, HAS_VALUE, None, ASSERTED)
                                                if isinstance(t.object, NamedNode)))
        return self._values_of[1]

    def superclasses(self, cls: NamedNode, classes: dict | None = None) -> set[NamedNode]:
        """The superclasses of ``cls`` in ``classes`` (a classification; None: the current one)."""
        return set((self.classification() if classes is None else classes).get(cls, set()))

    def subclasses(self, target: NamedNode, classes: dict | None = None) -> set[NamedNode]:
        """Named classes subsumed by ``target`` (direct and indirect; never owl:Nothing) in ``classes`` (a
        classification; None: the current one).  A class the rules do not name but a fact types with (used as
        a type only) has only the unsatisfiable classes under it, which are under every class; owl:Nothing has
        none (the OWL API's answer), nor has a name that is no class."""
        if target == NOTHING:
            return set()
        classes = self.classification() if classes is None else classes
        found = {c for c, sups in classes.items() if target in sups and c != target}
        if target not in classes and self._typed_with(target):
            found.update(c for c in unsatisfiable(classes) if c != target)
        return found

    def _typed_with(self, cls: NamedNode) -> bool:
        """Whether a fact types some individual with ``cls`` (asserted or inferred)."""
        store = self.onto.store
        return any(True for g in (ASSERTED, INFERRED) for _ in store.triples(None, TYPE, cls, g))


def _made(classification: Classification, said: bool) -> dict[NamedNode, set[NamedNode]]:
    """The superclasses of ``classification``; where this read makes them and ``said``, its unsatisfiable classes
    are warned of."""
    if classification.made or not said:
        return classification.superclasses()
    supers = classification.superclasses()
    empty = unsatisfiable(supers)
    if empty:
        warn(unsatisfiable_text(empty), OntologyWarning)
    return supers


def _lists_said_otherwise(store, rules: RuleSet) -> bool:
    """Whether the malformed-list notices the rules were compiled with are no longer those of the asserted
    graph (an AllDifferent's list cell edited: a fact, no schema change): the REASON's report says them."""
    said = frozenset(n.subject for n in rules.notices if n.subject in MALFORMED)
    return malformed_now(store, ASSERTED) != said


def _asserted(quads: list[Quad]) -> list[Triple]:
    """The triples of the asserted graph among ``quads`` (what the change ledger records)."""
    return [q.triple for q in quads if q.graph_name == ASSERTED]


__all__ = ["OntologyReasoning", "ReasonReport"]
