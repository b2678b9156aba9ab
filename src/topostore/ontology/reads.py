"""Questions to an ontology: its answers over asserted ∪ inferred knowledge.

A named part of :class:`topostore.ontology.facade.Ontology` (``onto.reads``): the typed questions
(types, instances, property values), raw SPARQL through the one guard on user
SPARQL, and named queries with safely bound parameters.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Quad, Triple

from ..compile.annotation_properties import annotation_properties
from ..errors import QueryError
from ..rdf.terms import Term, value_key
from ..rdf.vocab import ASSERTED, AUX, DECLARATION_TYPES, INFERRED, THING, TYPE, is_internal, is_skolem
from ..sparql.guard import check_user_sparql
from .files import SCHEMA_NAMESPACES
from .named_queries import QueryItem, collect, get_named_query, named_queries, render_jena, substitutions, to_items
from .views import Render

if TYPE_CHECKING:  # pragma: no cover
    from .facade import Ontology


class OntologyQueries:
    """The read API: a named part of one :class:`~topostore.ontology.facade.Ontology` (``onto.reads``).

    It reads the ontology's ``store``, ``iri``, ``short``, ``value``, ``rules``, class ``views`` and
    ``visible_graphs`` (asserted ∪ inferred, or asserted only while inconsistent).
    """

    def __init__(self, onto: Ontology) -> None:
        self.onto = onto
        #: whether an asserted fact removed since the last REASON is answered until the next one, as the
        #: last REASON's answer held it: what aRMOR's buffered reasoner answers (its half of a query is the
        #: state it was last flushed with, told facts included; spec §2.5).  Off for the Python API, where
        #: a removed fact is gone at once; an aRMOR reference with a buffered reasoner turns it on.
        self.answers_removed = False

    def _removed(self) -> Iterable[Triple]:
        """The asserted facts (as written) removed since the last successful REASON, while they are answered
        (:attr:`answers_removed`, the ontology changed since, and consistent at that REASON: an inconsistent
        one answers asserted facts only)."""
        onto = self.onto
        if not (self.answers_removed and onto.dirty and onto.ledger.removed) or len(onto.visible_graphs()) == 1:
            return ()
        return onto.ledger.removed.values()

    def _objects(self, s: Term, p: NamedNode) -> list[Term]:
        seen: dict = {}
        for objects in self._objects_in_graphs(s, p).values():
            for o in objects:
                if isinstance(o, Literal):  # one answer per data value, as the user wrote it
                    seen.setdefault(value_key(o), self.onto.store.original_literal(ASSERTED, s, p, o))
                else:  # an individual is its own key
                    seen.setdefault(o, o)
        for t in self._removed():
            if t.subject == s and t.predicate == p:
                o = t.object
                seen.setdefault(value_key(o) if isinstance(o, Literal) else o, o)
        return list(seen.values())

    def _objects_in_graphs(self, s: Term, p: NamedNode) -> dict[NamedNode, list[Term]]:
        """The values of (s, p) in each visible graph; a read that goes to the store carries the class
        views' pending decisions with it (one request for both, see :mod:`.views`)."""
        graphs, store = self.onto.visible_graphs(), self.onto.store
        if not store.round_trips:  # a read costs no request: the views decide their own pairs
            return store.batched.objects_in(s, p, graphs)
        owner = self._view_owner()
        pairs = self.onto.views.pending(owner) if owner is not None else []
        if not pairs:
            return store.batched.objects_in(s, p, graphs)
        values, found = store.batched.objects_and_presence(s, p, graphs, self._type_quads(pairs, graphs))
        self.onto.views.settle(pairs, self._members(pairs, found, len(graphs)))
        return values

    @staticmethod
    def _type_quads(pairs: list[tuple[Term, NamedNode]], graphs: list[NamedNode]) -> list[Quad]:
        return [Quad(s, TYPE, c, g) for s, c in pairs for g in graphs]

    @staticmethod
    def _members(pairs: list[tuple[Term, NamedNode]], found: list[bool], n: int) -> list[bool]:
        """Membership of each pair from the presence of its type fact in each of ``n`` graphs."""
        return [any(found[i * n:(i + 1) * n]) and _shown(s) for i, (s, _) in enumerate(pairs)]

    def types(self, individual: str | NamedNode) -> list[NamedNode]:
        """Named classes of an individual (asserted ∪ inferred), without owl:Thing."""
        return [t for t in self._objects(self.onto.iri(individual), TYPE) if _is_user_class(t)]

    def instances(self, cls: str | NamedNode) -> list[NamedNode]:
        """Individuals of a class (asserted ∪ inferred); a class asked again after REASON is read from its view."""
        c = self.onto.iri(cls)
        owner = self._view_owner()
        return self._instances(c) if owner is None else self.onto.views.get(c, owner, lambda: self._instances(c))

    def rendered_instances(self, cls: str | NamedNode, key: Hashable, render: Render) -> list[str]:
        """:meth:`instances` rendered by ``render`` (None leaves a member out), sorted, without duplicates.

        After a REASON the answer is kept as a view (see :mod:`topostore.ontology.views`), so asking for a
        big class every step costs the change, not the class.
        """
        c = cls if type(cls) is NamedNode else self.onto.iri(cls)  # an aRMOR QUERY's class is an IRI already
        owner = self._view_owner()
        if owner is None:
            return sorted({text for m in self._instances(c) if (text := render(m)) is not None})
        return self.onto.views.rendered(c, owner, lambda: self._instances(c), key, render)

    def _view_owner(self) -> object | None:
        """The REASON outcome class views belong to; None while asserted changes wait for a REASON."""
        return None if self.onto.dirty else self.onto.report

    def _instances(self, c: NamedNode) -> list[NamedNode]:
        members = [s for s in self.onto.store.batched.subjects_in(TYPE, c, self.onto.visible_graphs()) if _shown(s)]
        removed = [t.subject for t in self._removed() if t.predicate == TYPE and t.object == c and _shown(t.subject)]
        return list(dict.fromkeys(members + removed)) if removed else members

    def _instance_flags(self, pairs: list[tuple[Term, NamedNode]]) -> list[bool]:
        """Whether each (individual, class) pair is one of :meth:`instances` (what a class view re-decides):
        one index read per pair over every graph where the store offers it, else one batch of look-ups of a
        quad per pair and visible graph (:meth:`.Store.known_in`)."""
        found = self.onto.store.known_in([Triple(s, TYPE, c) for s, c in pairs], frozenset(self.onto.visible_graphs()))
        return [known and _shown(s) for known, (s, _) in zip(found, pairs, strict=True)]

    def object_values(self, prop: str | NamedNode, individual: str | NamedNode, names: bool = True) -> list:
        vals = self._individuals(*self._pair(individual, prop))
        return [self.onto.short(v) for v in vals] if names else vals

    def individual_values(self, prop: NamedNode, individual: NamedNode) -> list[NamedNode]:
        """:meth:`object_values` of an individual and a property given as IRIs, as terms (an aRMOR QUERY's)."""
        return self._individuals(individual, prop)

    def _individuals(self, s: Term, p: NamedNode) -> list[NamedNode]:
        """The individuals of :meth:`_objects`: where a read costs no request, the store's one read of every
        visible graph taken as it is (no literal among them to key by value: a data value is no answer)."""
        onto = self.onto
        store = onto.store
        if store.round_trips or self._removed():  # removed facts still answered: :meth:`_objects` adds them
            return [o for o in self._objects(s, p) if isinstance(o, NamedNode)]
        found = store.objects_by_graph(s, p, onto.visible_graphs())
        return list(dict.fromkeys(o for objects in found.values() for o in objects if isinstance(o, NamedNode)))

    def data_values(self, prop: str | NamedNode, individual: str | NamedNode) -> list[Literal]:
        return [o for o in self._objects(*self._pair(individual, prop)) if isinstance(o, Literal)]

    def _pair(self, individual: str | NamedNode, prop: str | NamedNode) -> tuple[NamedNode, NamedNode]:
        """The IRIs of an individual and a property; those given as IRIs (an aRMOR QUERY's, every robot
        step) are taken as they are, without the facade's two forwarded calls each."""
        if type(individual) is NamedNode and type(prop) is NamedNode:
            return individual, prop
        return self.onto.iri(individual), self.onto.iri(prop)

    def properties_of(self, individual: str | NamedNode, data: bool) -> list[NamedNode]:
        """The object (``data`` false) or data properties ``individual`` has values of, as aRMOR lists them:
        an annotation property's assertions are no property values (the OWL API keeps them apart)."""
        s = self.onto.iri(individual)
        props: dict = {}
        for g in self.onto.visible_graphs():
            for t in self.onto.store.triples(s, None, None, g):
                p = t.predicate
                if isinstance(t.object, Literal) == data and not _is_schema_or_internal(p):
                    props[p] = None
        for t in self._removed():
            if t.subject == s and isinstance(t.object, Literal) == data and not _is_schema_or_internal(t.predicate):
                props[t.predicate] = None
        if not props:
            return []
        annotations = annotation_properties(self.onto.store, ASSERTED)  # as the reasoner reads them
        return [p for p in props if p not in annotations]

    def sparql(self, text: str, bindings: dict[str, Term] | None = None, **kwargs):
        """Raw SPARQL over the visible graphs (asserted ∪ inferred).

        User text passes the one SPARQL guard (size, nesting, SERVICE, internal
        functions) before Oxigraph parses it, and runs without the reasoner's
        extension functions.
        ``bindings`` fix variables to terms with pyoxigraph's ``substitutions=``;
        in a SELECT query a bound variable must be projected.
        """
        check_user_sparql(text)
        if bindings is not None and not isinstance(bindings, dict):
            raise TypeError(f"bindings must be a dict of variable name -> term, not {type(bindings).__name__}")
        kwargs.setdefault("custom_functions", {})
        if not bindings:
            return self.onto.store.query(text, graphs=self.onto.visible_graphs(), **kwargs)
        try:
            return self.onto.store.query(text, graphs=self.onto.visible_graphs(), substitutions=substitutions(bindings), **kwargs)
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

    def query(self, name_or_text: str, params: dict[str, object] | None = None,
              timeout: float | None = None) -> list[QueryItem]:
        """Run a named query (or SELECT text) and return ``QueryItem`` results.

        ``params`` values are entity names / NamedNodes for ``iri`` parameters
        and Python values or Literals for ``literal`` parameters.
        """
        params = params or {}
        if not isinstance(name_or_text, str):
            raise TypeError(f"a query name or text must be a string, not {type(name_or_text).__name__}")
        if name_or_text.lstrip().upper().startswith(("SELECT", "PREFIX", "BASE")):
            text, kinds = name_or_text, {k: "iri" for k in params}
        elif name_or_text in self.onto.rules.queries:
            if params:
                raise QueryError(f"SQWRL query {name_or_text!r} takes no parameters")
            return self._run_sqwrl(self.onto.rules.queries[name_or_text], timeout)
        else:
            q = get_named_query(name_or_text)
            text, kinds = q.text, q.params
            missing = set(q.params) - set(params)
            if missing:
                raise QueryError(f"query {q.name!r} needs the parameter(s) {', '.join(sorted(missing))}")
            unknown = set(params) - set(q.params)
            if unknown:
                raise QueryError(f"query {q.name!r} has no parameter(s) {', '.join(sorted(unknown))}")
        bindings = {k: (self.onto.iri(v) if kinds.get(k) == "iri" else self.onto.value(v)) for k, v in params.items()}
        variables, rows, _ = self.select(text, bindings, timeout)
        # parameters are projected so that pyoxigraph can substitute them; their fixed values are not answers
        keep = [i for i, v in enumerate(variables) if v not in bindings]
        rows = [[row[i] for i in keep] for row in rows]
        return to_items([variables[i] for i in keep], rows, lambda t: render_jena(t, self.onto.store.restore))


    def _run_sqwrl(self, query, timeout: float | None) -> list[QueryItem]:
        """A SQWRL query of the ontology (compiled text, not user text: it may read the helper graph
        for anonymous classes and difference, which holds only while the ontology is consistent)."""
        graphs = self.onto.visible_graphs()
        if INFERRED in graphs:
            graphs = [*graphs, AUX]
        variables, rows, _ = collect(self.onto.store.query(query.text, graphs=graphs), timeout)
        return to_items(variables, rows, lambda t: render_jena(t, self.onto.store.restore))

    def query_names(self) -> dict[str, str]:
        """The named queries this ontology runs by name: those of ``queries/`` and its SQWRL queries
        (name → description)."""
        names = {q.name: q.description for q in named_queries().values()}
        names.update({q.name: q.description for q in self.onto.rules.queries.values()})
        return names


def _shown(individual: Term) -> bool:
    """Whether :meth:`OntologyQueries.instances` shows an individual: not the reasoner's own nodes
    (skolemised blank nodes of the data are shown)."""
    return not is_internal(individual) or is_skolem(individual)


def _is_schema_or_internal(p: NamedNode) -> bool:
    return p.value.startswith(SCHEMA_NAMESPACES) or is_internal(p)


def _is_user_class(t: Term) -> bool:
    return isinstance(t, NamedNode) and t.value not in DECLARATION_TYPES and t != THING and not is_internal(t)


__all__ = ["OntologyQueries"]
