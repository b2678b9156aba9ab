"""QUERY CLASS RESTRICTIONS (spec §3.4): the restrictions of a class's axioms in aRMOR's grammar.

aRMOR classifies every class expression nested in an axiom of the class: the restrictions inside a union,
a complement or another restriction's filler are items too.  A filler that is itself an expression is
written as aRMOR writes it: the OWL API's text of the expression cut by aRMOR's short-name heuristic
(:func:`heuristic`), so ``∃p.(∃q.D)`` gives ``p(D)``, never a blank node's label, which changes on every LOAD.
Named fillers are not listed as class items (spec §7 item 12), and SubClassOf axioms are read as well.
"""

from __future__ import annotations

from pyoxigraph import Literal, NamedNode, Triple

from ..ontology.facade import Ontology
from ..rdf.vocab import ASSERTED, THING, TYPE, XSD, is_internal, owl, rdfs
from .context import Context, Reply, asserted
from .manipulation import EQUIVALENT_CLASS, SUBCLASS_OF
from .render import abbreviate, short_name

_CARDINALITIES = (
    ("MIN", ("minQualifiedCardinality", "minCardinality")),
    ("MAX", ("maxQualifiedCardinality", "maxCardinality")),
    ("EXACT", ("qualifiedCardinality", "cardinality")),
)
_VALUES = (("SOME", "someValuesFrom"), ("ALL", "allValuesFrom"))
#: the OWL API's names of the expressions, by the property a restriction node holds its filler with
_API_NAMES = {"someValuesFrom": "SomeValuesFrom", "allValuesFrom": "AllValuesFrom", "hasValue": "HasValue",
              "minQualifiedCardinality": "MinCardinality", "minCardinality": "MinCardinality",
              "maxQualifiedCardinality": "MaxCardinality", "maxCardinality": "MaxCardinality",
              "qualifiedCardinality": "ExactCardinality", "cardinality": "ExactCardinality"}
_LISTS = (("intersectionOf", "ObjectIntersectionOf"), ("unionOf", "ObjectUnionOf"), ("oneOf", "ObjectOneOf"))


def _named(term) -> bool:
    return isinstance(term, NamedNode) and not is_internal(term)


def _is_data_restriction(onto: Ontology, prop, filler) -> bool:
    if onto.store.contains(Triple(prop, TYPE, owl("DatatypeProperty")), ASSERTED):
        return True
    return isinstance(filler, NamedNode) and (
        filler.value.startswith(XSD)
        or filler == rdfs("Literal")
        or onto.store.contains(Triple(filler, TYPE, rdfs("Datatype")), ASSERTED)
    )


def _one(onto: Ontology, node, name: str):
    values = onto.store.objects(node, owl(name), ASSERTED)
    return values[0] if values else None


def heuristic(text: str) -> str:
    """aRMOR's short name of an object's text (spec §2.4): after the last ``#`` up to the last ``>``; else
    after the last ``/`` of a URL up to the last ``>``; else between the first two quotes; else the text."""
    for mark in ("#", "/"):
        if mark in text and (mark == "#" or ("http" in text and "://" in text)):
            after = text[text.rindex(mark) + 1:]
            return after[:after.rindex(">")] if ">" in after else after
    if text.count('"') >= 2:
        return text.split('"')[1]
    return text


def api_text(onto: Ontology, node, seen: frozenset = frozenset()) -> str:
    """``node`` as the OWL API's ``toString`` writes it (functional syntax, full IRIs in angle brackets,
    the well-known vocabularies abbreviated, the operands of a set sorted); ``seen``: the anonymous
    expressions it is nested in, so that one nested in itself (not OWL, but RDF can say it) is written
    ``(cyclic)`` once round."""
    if isinstance(node, Literal):
        return f'"{node.value}"^^{abbreviate(node.datatype.value) or f"<{node.datatype.value}>"}'
    if _named(node):
        return abbreviate(node.value) or f"<{node.value}>"
    if node in seen:
        return "(cyclic)"
    seen = seen | {node}
    inverse = _one(onto, node, "inverseOf")
    if inverse is not None:
        return f"ObjectInverseOf({api_text(onto, inverse, seen)})"
    for name, api in _LISTS:
        head = _one(onto, node, name)
        if head is not None:
            members = sorted(api_text(onto, m, seen) for m in onto.store.list_items(head, ASSERTED))
            return f"{api}({' '.join(members)})"
    operand = _one(onto, node, "complementOf")
    if operand is not None:
        return f"ObjectComplementOf({api_text(onto, operand, seen)})"
    return _restriction_text(onto, node, seen)


def _restriction_text(onto: Ontology, node, seen: frozenset) -> str:
    prop = _one(onto, node, "onProperty")
    for name, api in _API_NAMES.items():
        value = _one(onto, node, name)
        if prop is None or value is None:
            continue
        filler = _one(onto, node, "onClass") or _one(onto, node, "onDataRange")
        kind = "Data" if _is_data_restriction(onto, prop, filler if "Cardinality" in api else value) else "Object"
        if "Cardinality" in api:
            tail = f" {api_text(onto, filler, seen)}" if filler is not None else ""
            return f"{kind}{api}({value.value} {api_text(onto, prop, seen)}{tail})"
        return f"{kind}{api}({api_text(onto, prop, seen)} {api_text(onto, value, seen)})"
    return str(node)


def _shown(onto: Ontology, term) -> str:
    """A property or filler in an item: its short name, an expression by aRMOR's heuristic."""
    return short_name(term) if _named(term) else heuristic(api_text(onto, term))


def restriction_item(onto: Ontology, subject: str, node) -> str | None:
    """One restriction in aRMOR's grammar, e.g. ``C-DEFINITION_MIN_OBJECT : CORRIDOR -> hasDoor 2(DOOR)``."""
    prop = _one(onto, node, "onProperty")
    if prop is None:
        return None
    for kind, names in _CARDINALITIES:
        for name in names:
            count = _one(onto, node, name)
            if count is not None:
                filler = _one(onto, node, "onClass") or _one(onto, node, "onDataRange")
                data = _is_data_restriction(onto, prop, filler)
                filler = filler or (rdfs("Literal") if data else THING)
                return (
                    f"C-DEFINITION_{kind}_{'DATA' if data else 'OBJECT'} : {subject} -> "
                    f"{_shown(onto, prop)} {count.value}({_shown(onto, filler)})"
                )
    for kind, name in _VALUES:
        filler = _one(onto, node, name)
        if filler is not None:
            data = _is_data_restriction(onto, prop, filler)
            shape = f"{kind}_{'DATA' if data else 'OBJECT'}"
            return f"C-DEFINITION_{shape} : {subject} -> {_shown(onto, prop)}({_shown(onto, filler)})"
    return None


def _filler(onto: Ontology, node):
    """The class expression a restriction node restricts its values to, if any."""
    for name in ("someValuesFrom", "allValuesFrom", "onClass"):
        value = _one(onto, node, name)
        if value is not None:
            return value
    return None


def restriction_items(onto: Ontology, cls: NamedNode, expression, classes: bool = True,
                      seen: frozenset = frozenset()) -> list[str]:
    """Items of one class expression and of every expression nested in it: named classes (not inside a
    filler: ``classes`` false) and restrictions, intersections, unions and complements opened (``seen``: the
    anonymous expressions it is nested in: one nested in itself is opened once)."""
    subject = short_name(cls)
    if _named(expression):
        shown = classes and expression not in (cls, THING)
        return [f"C-DEFINITION_CLASS : {subject} -> ({short_name(expression)})"] if shown else []
    if expression in seen:
        return []
    seen = seen | {expression}
    for name in ("intersectionOf", "unionOf"):
        operands = onto.store.objects(expression, owl(name), ASSERTED)
        if operands:
            return [item for member in onto.store.list_items(operands[0], ASSERTED)
                    for item in restriction_items(onto, cls, member, classes, seen)]
    operand = _one(onto, expression, "complementOf")
    if operand is not None:
        return restriction_items(onto, cls, operand, classes, seen)
    item = restriction_item(onto, subject, expression)
    filler = _filler(onto, expression)
    nested = restriction_items(onto, cls, filler, False, seen) if filler is not None and not _named(filler) else []
    return ([item] if item else []) + nested


def query_class_restrictions(ctx: Context) -> Reply:
    """QUERY CLASS RESTRICTIONS: one element per SubClassOf/EquivalentClasses axiom with a restriction."""
    onto, cls = ctx.onto, ctx.iri(0, "class")
    expressions = (
        [t.object for t in asserted(onto, cls, SUBCLASS_OF)]
        + [t.object for t in asserted(onto, cls, EQUIVALENT_CLASS)]
        + [t.subject for t in asserted(onto, None, EQUIVALENT_CLASS, cls)]
    )
    answers = []
    for expression in dict.fromkeys(expressions):
        items = restriction_items(onto, cls, expression)
        if any(not i.startswith("C-DEFINITION_CLASS") for i in items):
            answers.append("[" + ", ".join(sorted(set(items))) + "]")  # sorted: reproducible answers
    return Reply(queried_objects=sorted(answers))


__all__ = ["api_text", "heuristic", "query_class_restrictions", "restriction_item", "restriction_items"]
