"""OWL 2 datatype definitions: a named datatype equal to a data range (``:Small owl:equivalentClass
[ a rdfs:Datatype ; owl:onDatatype xsd:integer ; owl:withRestrictions ( [ xsd:maxInclusive 10 ] ) ]``).

OWL 2 maps ``DatatypeDefinition(:Small DR)`` to an ``owl:equivalentClass`` triple, so the class axioms
would read it as a class equivalence and set it aside as a malformed class expression.  Read here
first instead: the name stands for the range wherever the range itself may stand (a property's range,
a restriction's filler), as the IRI :mod:`.data_ranges` gives it, or as the built-in datatype it is
made equal to.  A definition by a range topostore does not read (a string facet) is set aside with its
reason, and the name stays undefined.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pyoxigraph import NamedNode, Triple

from ..errors import RuleCompileError
from ..rdf.vocab import OWL, RDFS, TYPE, is_skolem
from .model import is_datatype

if TYPE_CHECKING:  # pragma: no cover
    from .class_expressions import ClassExpressionReader

_DATATYPE = NamedNode(RDFS + "Datatype")
_EQUIVALENT = NamedNode(OWL + "equivalentClass")


def is_definition(t: Triple, reader: ClassExpressionReader) -> bool:
    """Whether an ``owl:equivalentClass`` triple defines a datatype: a named datatype made equal to a data
    range (a node restricting a datatype, one typed ``rdfs:Datatype``, or a named datatype: a built-in one, one
    declared ``rdfs:Datatype``)."""
    if not isinstance(t.subject, NamedNode) or is_skolem(t.subject):
        return False
    declared = _DATATYPE in reader.store.objects(t.subject, TYPE, reader.graph)
    if not isinstance(t.object, NamedNode):
        return False
    if is_skolem(t.object):
        return bool(reader.store.objects(t.object, NamedNode(OWL + "onDatatype"), reader.graph)) or \
            _DATATYPE in reader.store.objects(t.object, TYPE, reader.graph)
    return declared and (is_datatype(t.object) or _DATATYPE in reader.store.objects(t.object, TYPE, reader.graph))


def read_definitions(reader: ClassExpressionReader) -> tuple[dict[NamedNode, NamedNode], list[tuple[str, str]]]:
    """({named datatype: the range it stands for}, [(axiom, why set aside)]): every datatype definition
    of the graph, a chain of names (``:A`` defined as ``:B``, ``:B`` as a range) followed to its end."""
    told: dict[NamedNode, NamedNode] = {}
    aside: list[tuple[str, str]] = []
    definitions: dict[NamedNode, list] = {}
    for t in reader.store.triples(None, _EQUIVALENT, None, reader.graph):
        if is_definition(t, reader):
            definitions.setdefault(t.subject, []).append(t)
    for name, ts in definitions.items():
        if len(ts) > 1:  # both hold: their intersection, which no one range here stands for
            aside.append((f"{_short(name)} DatatypeDefinition", f"defined {len(ts)} times (the values of both "
                          f"definitions): {_short(name)} stays undefined"))
        elif not is_skolem(ts[0].object):
            told[name] = ts[0].object
    ranges = {name: ts[0] for name, ts in definitions.items() if len(ts) == 1 and is_skolem(ts[0].object)}
    # OWL 2 forbids a definition naming itself through others (:A as :B or integer, :B as :A or string): no
    # range stands for such names, which stay undefined
    cyclic = _cyclic({name: _named(reader, t.object, definitions) for name, t in ranges.items()} |
                     {name: {told[name]} for name in told})
    for name in sorted(cyclic, key=lambda n: n.value):
        aside.append((f"{_short(name)} DatatypeDefinition", f"the definition of {_short(name)} names "
                      f"{_short(name)} itself through other definitions (OWL 2 forbids cyclic datatype "
                      f"definitions): {_short(name)} stays undefined"))
        told.pop(name, None)
        ranges.pop(name, None)
    # a range may name another defined datatype (:NotSmall as the complement of :Small): read again, with the
    # names read so far standing for their ranges, until no range changes (at most once per definition)
    for _ in range(len(ranges) + 1):
        reader.datatype_defs = {name: _end(name, told) for name in told}
        failed, before = [], dict(told)
        for name, t in ranges.items():
            try:
                declared = _DATATYPE in reader.store.objects(name, TYPE, reader.graph)  # the OWL API types the range by it
                told[name] = reader.data_range(t.object, f"the definition of {_short(name)}", typed=declared)
            except RuleCompileError as exc:
                failed.append((f"{_short(name)} DatatypeDefinition", f"{exc}: {_short(name)} stays undefined"))
        if told == before:
            break
    return {name: _end(name, told) for name in told}, aside + failed


def _named(reader: ClassExpressionReader, node: NamedNode, definitions: dict) -> set[NamedNode]:
    """The defined datatypes a range written at ``node`` names, its nested ranges included."""
    found: set[NamedNode] = set()
    todo, seen = [node], {node}
    while todo:
        for t in reader.store.triples(todo.pop(), None, None, reader.graph):
            o = t.object
            if isinstance(o, NamedNode) and is_skolem(o):
                if o not in seen:
                    seen.add(o)
                    todo.append(o)
            elif isinstance(o, NamedNode) and o in definitions:
                found.add(o)
    return found


def _cyclic(edges: dict[NamedNode, set[NamedNode]]) -> set[NamedNode]:
    """The names that reach themselves along ``edges``."""
    cyclic = set()
    for start in edges:
        todo, seen = list(edges[start]), set()
        while todo:
            n = todo.pop()
            if n == start:
                cyclic.add(start)
                break
            if n not in seen:
                seen.add(n)
                todo.extend(edges.get(n, ()))
    return cyclic


def _end(name: NamedNode, told: dict[NamedNode, NamedNode]) -> NamedNode:
    """What a chain of defined names ends in (the last name of a cycle, which stays a name)."""
    seen = {name}
    while (nxt := told.get(name)) is not None and nxt not in seen:
        seen.add(nxt)
        name = nxt
    return name


def _short(t: NamedNode) -> str:
    v = t.value
    return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]


__all__ = ["is_definition", "read_definitions"]
