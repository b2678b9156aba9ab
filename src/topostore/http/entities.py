"""One entity as the inspector shows it: every fact marked asserted or inferred, each inference with its why.

:func:`describe_entity` answers ``GET /references/{name}/entities/{entity}``.
A fact is *inferred* when it holds in the graphs queries see (asserted ∪
inferred, :meth:`~topostore.ontology.facade.Ontology.visible_graphs`) but was not
asserted; its ``why`` is the derivation tree of :mod:`topostore.ontology.explain`, the
same one ``GET .../explain`` and ``topostore explain`` give, so the page never
has an explanation of its own.  Every other entity a fact names is given by
``name`` and ``iri``, which the page turns into a link.

Lists are cut at ``limit`` facts (a class of a large map can have thousands of
members); the answer says so in ``truncated`` and ``warnings``, never silently.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from pyoxigraph import Literal, NamedNode, Triple

from ..errors import InvalidNameError
from ..ontology.explain import Explainer
from ..ontology.files import SCHEMA_NAMESPACES
from ..rdf.terms import Term, iri, value_key
from ..rdf.vocab import (
    ASSERTED,
    DECLARATION_TYPES,
    DIFFERENT_FROM,
    FIRST,
    OWL,
    RDF,
    RDFS,
    REST,
    SAME_AS,
    THING,
    TYPE,
    XSD,
    is_internal,
    is_skolem,
    owl,
    rdfs,
)

if TYPE_CHECKING:  # pragma: no cover
    from ..ontology.facade import Ontology

#: Prefixed names the inspector accepts and shows for the standard vocabularies.
PREFIXES = {"rdf": RDF, "rdfs": RDFS, "owl": OWL, "xsd": XSD}
#: Prefixes of words in proofs that are never links (the vocabulary, not the reference's entities).
STANDARD = {*PREFIXES, "swrl", "swrlb"}
DEFAULT_LIMIT = 100
MAX_LIMIT = 5000
#: Individual-to-individual assertions of the OWL vocabulary that belong on an individual's page.
OWL_ASSERTIONS = (SAME_AS, DIFFERENT_FROM)
ANNOTATIONS = (rdfs("label"), rdfs("comment"))
_CLASS_DECLARATIONS = (owl("Class"), rdfs("Class"))
_PROPERTY_KINDS = {owl("ObjectProperty"): "object property", owl("DatatypeProperty"): "data property",
                   owl("AnnotationProperty"): "annotation property"}


def resolve_entity(onto: Ontology, text: str) -> NamedNode:
    """The IRI a user means: ``R1`` (a name in the ontology's namespace), ``<http://…#R1>``,
    ``http://…#R1`` or ``urn:…`` (full IRIs), ``owl:Thing`` (a standard prefix)."""
    name = text.strip()
    if len(name) > 2 and name.startswith("<") and name.endswith(">"):
        return iri(name[1:-1])
    head, sep, local = name.partition(":")
    if sep and head in PREFIXES:
        return iri(PREFIXES[head] + local)
    if sep and (local.startswith("//") or head.lower() == "urn"):
        return iri(name)
    if not name:
        raise InvalidNameError("the entity name is empty")
    return onto.iri(name)


def display_name(term: NamedNode, prefix: str) -> str:
    """How the inspector names an entity: its local name in the ontology's namespace, ``owl:Thing``
    for the standard vocabularies, the full IRI otherwise (each resolves back with :func:`resolve_entity`)."""
    v = term.value
    if v.startswith(prefix) and len(v) > len(prefix):
        return v[len(prefix):]
    for short, ns in PREFIXES.items():
        if v.startswith(ns) and len(v) > len(ns):
            return f"{short}:{v[len(ns):]}"
    return v


@dataclass
class View:
    """What one answer needs: the ontology, one explainer (its proofs are shared between the facts
    of the page), the list limit, and what was cut or could not be done."""

    onto: Ontology
    limit: int = DEFAULT_LIMIT
    warnings: list[str] = field(default_factory=list)
    truncated: dict[str, int] = field(default_factory=dict)
    _explainer: Explainer | None = None

    @property
    def explainer(self) -> Explainer:
        if self._explainer is None:
            self._explainer = Explainer(self.onto.store, self.onto.rules.all_rules, self.onto.short)
        return self._explainer

    def graphs(self) -> list[NamedNode]:
        return self.onto.visible_graphs()

    def term(self, t: Term) -> dict[str, Any]:
        """An RDF term as JSON: ``{"name", "iri"}`` for an entity (a link on the page),
        ``{"value", "datatype"}`` for a literal, ``{"expression"}`` for an anonymous class."""
        if isinstance(t, Literal):
            shown = self.onto.store.restore(t)
            out: dict[str, Any] = {"value": shown.value, "datatype": display_name(shown.datatype, self.onto.prefix)}
            if shown.language:
                out["language"] = shown.language
            return out
        if isinstance(t, NamedNode) and not is_internal(t):
            return {"name": display_name(t, self.onto.prefix), "iri": t.value}
        if isinstance(t, NamedNode) and is_skolem(t):
            return {"expression": self.explainer.render_term(t)}
        return {"expression": str(t)}

    def fact(self, t: Triple, inferred: bool, **fields: Any) -> dict[str, Any]:
        """One fact: its fields, ``inferred``, and for an inferred one the derivation tree (``why``)."""
        out = {**fields, "inferred": inferred}
        if inferred:
            out["why"] = self.explainer.explain(t).to_dict()
        return out

    def cut(self, section: str, items: list) -> list:
        """The first ``limit`` items; the full count goes to ``truncated`` and a warning."""
        if len(items) > self.limit:
            self.truncated[section] = len(items)
            self.warnings.append(f"{section}: {len(items)} facts, the first {self.limit} shown (ask with ?limit=N, "
                                 f"at most {MAX_LIMIT})")
            return items[:self.limit]
        return items


def visible(view: View, s: Term | None, p: NamedNode | None, o: Term | None) -> list[tuple[Triple, bool]]:
    """(triple, inferred) for the triples matching the pattern in the visible graphs, each once
    (a fact both asserted and inferred counts as asserted), in a stable order."""
    found: dict[tuple, tuple[Triple, bool]] = {}
    store = view.onto.store
    for g in view.graphs():
        for t in store.triples(s, p, o, g):
            key = (t.subject, t.predicate, value_key(t.object))
            if key not in found or g == ASSERTED:
                found[key] = (t, g != ASSERTED)
    return sorted(found.values(), key=lambda item: (str(item[0].predicate), str(item[0].subject), str(item[0].object)))


def _is_user_class(t: Term) -> bool:
    return isinstance(t, NamedNode) and t.value not in DECLARATION_TYPES and t != THING and not is_internal(t)


def _is_assertion(p: NamedNode) -> bool:
    """A property whose values are facts about individuals (not schema, not topostore's own)."""
    return p in OWL_ASSERTIONS or not (p.value.startswith(SCHEMA_NAMESPACES) or is_internal(p))


# --------------------------------------------------------------------------- kinds

def entity_kinds(onto: Ontology, e: NamedNode, graphs: Iterable[NamedNode]) -> list[str]:
    """What ``e`` is (a name can be punned): class, object/data/annotation property, individual."""
    store = onto.store
    declared = {t.object for g in graphs for t in store.triples(e, TYPE, None, g)}
    kinds = []
    rules = onto.rules
    if declared & set(_CLASS_DECLARATIONS) or e in rules.named_classes or e == THING:
        kinds.append("class")
    for decl, kind in _PROPERTY_KINDS.items():
        if decl in declared:
            kinds.append(kind)
    if "object property" not in kinds and e in rules.object_properties:
        kinds.append("object property")
    if "data property" not in kinds and e in rules.data_properties:
        kinds.append("data property")
    typed = any(_is_user_class(c) or c == owl("NamedIndividual") for c in declared)
    if typed or _has_assertions(store, e, graphs):
        kinds.append("individual")
    return kinds


def _has_assertions(store, e: NamedNode, graphs: Iterable[NamedNode]) -> bool:
    for g in graphs:
        if any(_is_assertion(t.predicate) for t in store.triples(e, None, None, g)):
            return True
        if any(_is_assertion(t.predicate) and t.predicate != TYPE for t in store.triples(None, None, e, g)):
            return True
    return False


def is_mentioned(onto: Ontology, e: NamedNode) -> bool:
    """Whether any stored triple names ``e`` (an unknown name is a 404, not an empty page)."""
    store = onto.store
    for g in [ASSERTED, *onto.visible_graphs()]:
        for pattern in ((e, None, None), (None, e, None), (None, None, e)):
            if next(iter(store.triples(*pattern, g)), None) is not None:
                return True
    return False


# --------------------------------------------------------------------------- individuals

def individual_sections(view: View, e: NamedNode) -> dict[str, Any]:
    """Types, property values and the facts naming ``e`` as a value (its incoming links);
    each list is cut before its proofs are built, so a hub individual costs ``limit`` proofs."""
    types = view.cut("types", [(t, inferred) for t, inferred in visible(view, e, TYPE, None)
                               if _is_user_class(t.object) or (is_skolem(t.object) and not inferred)])
    values = view.cut("values", [(t, inferred) for t, inferred in visible(view, e, None, None)
                                 if _is_assertion(t.predicate) and t.predicate != TYPE])
    incoming = view.cut("referenced_by", [(t, inferred) for t, inferred in visible(view, None, None, e)
                                          if _is_assertion(t.predicate) and t.predicate != TYPE
                                          and not is_internal(t.subject)])
    return {"types": [view.fact(t, inferred, **{"class": view.term(t.object)}) for t, inferred in types],
            "values": [view.fact(t, inferred, property=view.term(t.predicate), value=view.term(t.object))
                       for t, inferred in values],
            "referenced_by": [view.fact(t, inferred, subject=view.term(t.subject), property=view.term(t.predicate))
                              for t, inferred in incoming]}


def members(view: View, cls: NamedNode) -> list[dict[str, Any]]:
    """The individuals of a class, each membership asserted or inferred (with its why)."""
    rows = [(t, inferred) for t, inferred in visible(view, None, TYPE, cls) if not is_internal(t.subject)]
    rows = view.cut("members", rows)
    return [view.fact(t, inferred, individual=view.term(t.subject)) for t, inferred in rows]


def assertions(view: View, prop: NamedNode) -> list[dict[str, Any]]:
    """The facts using a property, each asserted or inferred (with its why)."""
    rows = [(t, inferred) for t, inferred in visible(view, None, prop, None) if not is_internal(t.subject)]
    rows = view.cut("assertions", rows)
    return [view.fact(t, inferred, subject=view.term(t.subject), value=view.term(t.object)) for t, inferred in rows]


def _all_different_groups(store, e: NamedNode) -> list[Term]:
    """The asserted ``owl:AllDifferent`` axioms listing ``e`` (found from its list cell backwards)."""
    groups: list[Term] = []
    for cell in store.subjects(FIRST, e, ASSERTED):
        head, seen = cell, {cell}
        while (before := store.subjects(REST, head, ASSERTED)) and before[0] not in seen:
            head = before[0]
            seen.add(head)
        for p in (owl("distinctMembers"), owl("members")):
            groups += [g for g in store.subjects(p, head, ASSERTED)
                       if store.contains(Triple(g, TYPE, owl("AllDifferent")), ASSERTED)]
    return groups


def different_from(view: View, e: NamedNode) -> list[dict[str, Any]]:
    """The individuals ``e`` is told to differ from by an ``owl:AllDifferent`` axiom (Protégé's
    "Different individuals"), each with the axiom; ``owl:differentFrom`` facts are among the values."""
    store = view.onto.store
    rows: list[tuple[Term, Term]] = []
    for group in _all_different_groups(store, e):
        for p in (owl("distinctMembers"), owl("members")):
            for head in store.objects(group, p, ASSERTED):
                rows += [(m, group) for m in store.list_items(head, ASSERTED) if m != e]
    rows = view.cut("different_from", rows)
    return [{"individual": view.term(m), "inferred": False, "axiom": view.explainer.render_term(g)} for m, g in rows]


def annotations(view: View, e: NamedNode) -> list[dict[str, Any]]:
    """Labels and comments of any entity (what Protégé shows in its annotations pane)."""
    return [{"property": view.term(t.predicate), "value": view.term(t.object)}
            for p in ANNOTATIONS for t, _ in visible(view, e, p, None)]


# --------------------------------------------------------------------------- search

def _kind_of_type(t: Triple) -> tuple[Term, str] | None:
    """What an ``rdf:type`` triple says about its subject's kind (None: nothing)."""
    c = t.object
    if c in _CLASS_DECLARATIONS:
        return t.subject, "class"
    if c in _PROPERTY_KINDS:
        return t.subject, _PROPERTY_KINDS[c]
    if _is_user_class(c) or c == owl("NamedIndividual"):
        return t.subject, "individual"
    return None


def search_entities(onto: Ontology, text: str, limit: int = 20) -> tuple[list[dict[str, str]], int]:
    """Entities whose name contains ``text`` (case-insensitive): exact matches first, then
    names starting with it, then the rest, alphabetically.  Candidates are what has an
    ``rdf:type`` (individuals, declared classes and properties) and the classes used.
    Returns the first ``limit`` and how many match in all."""
    needle = text.strip().lower()
    kinds: dict[NamedNode, str] = {}
    for g in [ASSERTED, *onto.visible_graphs()]:
        for t in onto.store.triples(None, TYPE, None, g):
            if _is_user_class(t.object):
                kinds.setdefault(t.object, "class")
            found = _kind_of_type(t)
            if found is not None and isinstance(found[0], NamedNode) and not is_internal(found[0]):
                if kinds.get(found[0], "individual") == "individual":
                    kinds[found[0]] = found[1]
    hits = [(display_name(e, onto.prefix), e, kind) for e, kind in kinds.items()]
    hits = [h for h in hits if needle in h[0].lower()]
    hits.sort(key=lambda h: (h[0].lower() != needle, not h[0].lower().startswith(needle), h[0].lower(), h[0]))
    return [{"name": n, "iri": e.value, "kind": kind} for n, e, kind in hits[:limit]], len(hits)


_TOKEN = re.compile(r"[^\s(),{}]+")


def link_names(view: View, texts: Iterable[str]) -> dict[str, str]:
    """Which words of proof and axiom texts are entities of the reference (word -> IRI), so the
    page links exactly those (a literal value or a rule name is never a link)."""
    out: dict[str, str] = {}
    seen: set[str] = set()
    for text in texts:
        for word in _TOKEN.findall(text):
            if word in seen or word[0] in "?\"'" or word[0].isdigit() or word.partition(":")[0] in STANDARD:
                continue
            seen.add(word)
            try:
                e = resolve_entity(view.onto, word)
            except InvalidNameError:
                continue
            if is_mentioned(view.onto, e):
                out[word] = e.value
    return out


__all__ = ["View", "resolve_entity", "display_name", "entity_kinds", "individual_sections", "members", "assertions",
           "search_entities", "link_names", "is_mentioned", "annotations", "different_from", "visible", "DEFAULT_LIMIT", "MAX_LIMIT"]
