"""Changes of the tutorial map that several suites run: the scenarios the Pellet differential compares with
Pellet and the store-equivalence tests run on every store, generated maps on the tutorial's TBox, the answers
compared, and the tutorial map damaged as aRMOR SAVE leaves it (nested SWRL atom lists)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from pyoxigraph import BlankNode, NamedNode, RdfFormat, Triple, serialize
from support import NS
from support import TBOX_OWL as TBOX

from topostore import Ontology
from topostore.demo import mapgen
from topostore.ontology.nary import axiom_of_list_node
from topostore.rdf.skolem import unskolemize
from topostore.rdf.vocab import DIFFERENT_FROM, FIRST, NIL, REST, TYPE, swrl
from topostore.stores import memory_store

#: the individuals whose answers are compared (those a scenario does not mention are left out)
NAMES = ["C1", "C2", "R1", "R2", "R3", "D1", "D2", "D3", "D4", "Robot1", "Robot2", "X"]
#: the object properties whose values are compared
PROPS = ["canReach", "connectedTo"]


def topostore(onto: Ontology, names: list[str], ns: str = NS, props: list[str] = PROPS) -> dict:
    if not onto.reason().consistent:
        return {"consistent": False}
    out = {}
    for name in names:
        types = sorted(onto.short(t) for t in onto.types(name) if t.value.startswith(ns))
        facts: dict = {"types": types}
        for p in props:
            values = sorted(onto.object_values(p, name))
            if values:
                facts[p] = values
        if mentioned(onto, name):
            out[name] = facts
    return {"consistent": True, "individuals": out}


def mentioned(onto: Ontology, name: str) -> bool:
    """Whether the file names this individual at all (Owlready2 then knows the entity)."""
    iri = onto.iri(name)
    return any(True for _ in onto.store.triples(iri, None, None)) or any(True for _ in onto.store.triples(None, None, iri))


def drop_all_different(onto: Ontology, member: str) -> None:
    """Remove the owl:AllDifferent axiom listing ``member`` (its other facts stay)."""
    for t in list(onto.store.triples(None, FIRST, onto.iri(member))):
        onto.remove(*axiom_of_list_node(onto.store, t.subject))


def long(onto: Ontology, n: int):
    return onto.value(n, "long")


SCENARIOS: dict[str, Callable[[Ontology], None]] = {
    "example": lambda o: None,
    "doors not declared different": lambda o: drop_all_different(o, "D1"),
    "locations not declared different, distinct visits": lambda o: drop_all_different(o, "C1"),
    "robot moved to R1": lambda o: o.replace("Robot1", "isIn", "R1"),
    "robot in an undeclared place: sameAs merge": lambda o: o.add_fact("Robot1", "isIn", "X"),
    "robot in two places declared different": lambda o: o.add_fact("Robot1", "isIn", "R1"),
    "a door that is a location": lambda o: o.add_fact("R1", "hasDoor", "R2"),
    "a room with a second, different door": lambda o: (o.add_fact("R1", "hasDoor", "D3"),
                                                       o.add_all_different(["D1", "D3"])),
    "a door link removed": lambda o: o.remove_fact("C1", "hasDoor", "D2"),
    "visited in the future": lambda o: o.replace("R2", "visitedAt", long(o, 1665579999)),
    "time advances": lambda o: o.replace("Robot1", "now", long(o, 1665579760)),
    "a new room not declared different": lambda o: (o.add_fact("R3", "hasDoor", "D1"),
                                                    o.add_fact("R3", "visitedAt", long(o, 1665579000))),
    "a new room declared different from C1 only": lambda o: (
        o.add_fact("R3", "hasDoor", "D1"), o.add_fact("R3", "visitedAt", long(o, 1665579000)),
        o.add(Triple(o.iri("R3"), DIFFERENT_FROM, o.iri("C1")))),
    "a location without doors": lambda o: o.add_fact("R3", "visitedAt", long(o, 1665579700)),
    "two visit times of one location": lambda o: o.add_fact("R1", "visitedAt", long(o, 1665579720)),
    "a literal outside its range": lambda o: o.add_data("visitedAt", "R1", "1.5", "decimal"),
    "second robot on the map": lambda o: (o.add_fact("Robot2", "isIn", "R2"), o.add_fact("Robot2", "now", long(o, 1665579800)),
                                          o.add_fact("Robot2", "urgencyThreshold", long(o, 50))),
}


def generated(size: int, seed: int, declared: bool) -> tuple[Ontology, list[str]]:
    """A generated map (corridors and rooms) on the reference TBox, and its individuals."""
    m = mapgen.generate(size, seed=seed)
    onto = Ontology.from_file(TBOX)
    onto.add(*m.triples(all_different=declared))
    return onto, m.locations + m.doors + list(m.robots)


def _list_items(index: dict, head) -> list:
    items = []
    while head != NIL:
        items.append(index[(head, FIRST)])
        head = index[(head, REST)]
    return items


def damage(source: Path, target: Path) -> None:
    """Write ``source`` with every rule body's tail nested in an atom list, and the first rule's
    body appended (nested) to the second's: the structures aRMOR SAVE leaves."""
    triples = memory_store().parse_file(source)
    index = {(t.subject, t.predicate): t.object for t in triples if t.predicate in (FIRST, REST, swrl("body"))}
    imps = [t.subject for t in triples if t.predicate == TYPE and t.object == swrl("Imp")]
    out = [t for t in triples if t.predicate != swrl("body")]
    fresh = iter(NamedNode(f"urn:topostore:bnode:damaged{k}") for k in range(10_000))

    def atom_list(items: list) -> NamedNode:
        head = NIL
        for item in reversed(items):
            cell = next(fresh)
            out.extend([Triple(cell, TYPE, swrl("AtomList")), Triple(cell, FIRST, item), Triple(cell, REST, head)])
            head = cell
        return head

    bodies = {imp: _list_items(index, index[(imp, swrl("body"))]) for imp in imps}
    for k, imp in enumerate(imps):
        atoms = bodies[imp]
        items = [atoms[0], atom_list(atoms[1:])]
        if k == 1:
            items.append(atom_list(bodies[imps[0]]))
        out.append(Triple(imp, swrl("body"), atom_list(items)))
    target.write_bytes(serialize([unskolemize(t) for t in out], format=RdfFormat.RDF_XML))
    assert not any(isinstance(t.subject, BlankNode) for t in out)
