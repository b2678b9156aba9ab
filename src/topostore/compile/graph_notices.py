"""What the profile report reads off the asserted graph itself rather than off the TBox's expressions.

A datatype whose values are not tested, the RDF list vocabulary, imports not loaded, the universal and
the empty properties, and the reflexivity of ``owl:sameAs``: each is found by looking the graph up, not
by where a class expression is used (:mod:`.profile`, which runs these beside its own checks).  ``note``
is the report's: (axiom kind, axiom, reason) → one :data:`~.notices.INCOMPLETE` notice.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from itertools import islice

from pyoxigraph import NamedNode

from ..rdf.vocab import FIRST, NIL, OWL, RDFS, REST, SAME_AS, TYPE, is_skolem, owl
from ..stores.base import Store
from . import data_ranges
from .model import Expr, is_datatype, short_name
from .notices import NOT_STORED, UNCHECKED_DATATYPE, UNSUPPORTED, Notice
from .range_values import emptiness, included
from .snippets import in_datatype

#: the report's note: (axiom kind, axiom, reason)
Note = Callable[[str, str, str], None]

#: The universal and the empty properties, with what they mean.
_TOP_AND_BOTTOM = {
    "topObjectProperty": "the universal property (every two individuals are linked by it)",
    "topDataProperty": "the universal data property (every individual has every literal as its value)",
    "bottomObjectProperty": "the empty property (a link by it, or an existential on it, is inconsistent)",
    "bottomDataProperty": "the empty data property (a value of it, or an existential on it, is inconsistent)",
}

#: Why ``x owl:sameAs x`` is not stored, said whenever a file uses owl:sameAs.
REFLEXIVE_SAME_AS = ("owl:sameAs is reflexive: x sameAs x holds for every individual, but is not stored (it "
                     "would add a triple per term and list each individual as its own alias); every fact of an "
                     "individual is copied to each of its names, so only the triple x sameAs x itself is not "
                     "answered")


def unchecked_datatypes(note: Note, data_range: Iterable[tuple[NamedNode, NamedNode]],
                        uses: Iterable[tuple[Expr, bool, str, NamedNode | None]], store: Store,
                        graph: NamedNode) -> None:
    """A range or a universal restriction into a datatype whose values topostore does not test: a value
    outside it is not found.  For a datatype of the ontology's own (not in the OWL 2 datatype map, not
    defined) that is the OWL 2 Direct Semantics (its value space is any set of values, so no value is
    known to be outside it), but Pellet takes such a datatype as disjoint from the built-in ones and finds
    ``:d 3`` with ``:d rdfs:range :MyType`` inconsistent: the difference is said, never silent."""
    for p, dt in data_range:
        unchecked(note, dt, f"{short_name(p)} range {short_name(dt)}", store, graph)
    for e, positive, axiom, _ in uses:
        if e.datatype is None:
            continue
        if positive and e.kind == "all":
            unchecked(note, e.datatype, axiom, store, graph)
        elif e.kind in ("some", "min", "exact", "max") and data_ranges.composition(e.datatype) is not None:
            unchecked(note, e.datatype, axiom, store, graph)
            if positive and e.kind != "max" and emptiness(e.datatype) is None:
                note(UNCHECKED_DATATYPE, axiom, f"whether {data_ranges.readable(e.datatype)} has any value is not "
                     "decided: a value required in it is not found inconsistent where it has none")
    undecided_inclusions(note, [(e, positive, axiom) for e, positive, axiom, _ in uses])


def undecided_inclusions(note: Note, uses: list[tuple[Expr, bool, str]]) -> None:
    """Two data restrictions on one property, one of them into a range built of others, where whether every
    value of one range is in the other is not decided (:func:`.range_values.included`): a membership in the one
    (a restriction an individual is told to be in) is not carried to the other."""
    on: dict = {}  # property -> {datatype: [told of an individual, an axiom using it]}
    for e, positive, axiom in uses:
        if e.datatype is not None and e.kind in ("some", "min", "exact"):
            found = on.setdefault(e.prop, {}).setdefault(e.datatype, [False, axiom])
            found[0] = found[0] or positive
    for ranges in on.values():
        built = {dt for dt in ranges if data_ranges.composition(dt) is not None}
        if not built:
            continue
        for a, (told, _) in ranges.items():
            for b in ranges:
                # only a restriction told of an individual carries a membership
                if told and a != b and (a in built or b in built) and included(a, b) is None:
                    note(UNCHECKED_DATATYPE, ranges[a][1], f"whether every value of "
                         f"{_readable(a)} is one of {_readable(b)} is not decided: a restriction into the one is "
                         "not found to imply one into the other")


def _readable(dt: NamedNode) -> str:
    return data_ranges.readable(dt) or short_name(dt)


def unchecked(note: Note, dt: NamedNode, axiom: str, store: Store, graph: NamedNode) -> None:
    if in_datatype("?v", dt) is not None or is_skolem(dt) or data_ranges.parts(dt) is not None:
        return
    if data_ranges.composition(dt) is not None:
        note(UNCHECKED_DATATYPE, axiom, f"{data_ranges.readable(dt)} is built of a datatype whose values topostore "
             "does not test: a value is known in it only where a member it is surely in says so, never outside it")
        return
    if is_datatype(dt):
        note(UNCHECKED_DATATYPE, axiom, f"{short_name(dt)} is a datatype whose values topostore does not "
             "test: a value outside it is not found inconsistent")
        return
    if store.objects(dt, owl("equivalentClass"), graph):
        note(UNCHECKED_DATATYPE, axiom, f"{short_name(dt)} is defined by a data range topostore does not test "
             "(its definition is set aside, said on its own): no value is checked against it")
        return
    declared = NamedNode(RDFS + "Datatype") in store.objects(dt, TYPE, graph)
    note(UNCHECKED_DATATYPE, axiom, f"{short_name(dt)} is not a datatype of the OWL 2 datatype map"
         + ("" if declared else " and is not declared rdfs:Datatype (as OWL 2 DL requires)")
         + ", nor defined: its value space may be any set of values (OWL 2 Direct Semantics), so no "
         "value is checked against it; a reasoner that takes it as disjoint from the built-in datatypes "
         "(Pellet) finds a value of another datatype inconsistent")


def list_vocabulary(note: Note, store: Store, graph: NamedNode) -> None:
    """``rdf:nil`` is the empty list: a first element or a rest of it is a contradiction under the
    RDF-Based semantics, which topostore does not find (it reads lists, it does not reason about them)."""
    for p in (FIRST, REST):
        for t in islice(store.triples(NIL, p, None, graph), 1):
            note(UNSUPPORTED, f"nil {short_name(p)} {short_name(t.object)}", "rdf:nil is the empty list, which "
                 "has no first element and no rest: inconsistent under the RDF-Based semantics; the RDF "
                 "list vocabulary is not reasoned, the statement is kept as a plain triple")


#: the subjects of :func:`malformed_lists`' notices
TWO_FIRSTS = "an RDF list with a cell of two rdf:first"
OPEN_END = "an AllDifferent axiom whose member list does not end in rdf:nil"
MALFORMED = frozenset({TWO_FIRSTS, OPEN_END})


def malformed_now(store: Store, graph: NamedNode) -> frozenset[str]:
    """The subjects of the notices :func:`malformed_lists` gives ``graph`` as it is now: a list cell is a fact
    where the list is an AllDifferent's (editing it compiles no rules), so what was said at compile time is
    compared with this after such an edit."""
    found: set[str] = set()
    malformed_lists(lambda kind, axiom, reason: found.add(axiom), store, graph)
    return frozenset(found)


def malformed_lists(note: Note, store: Store, graph: NamedNode) -> None:
    """An ``owl:AllDifferent`` member list that does not end in ``rdf:nil`` (it loops back on itself, or is
    cut short), and any list cell with two ``rdf:first``: a group's keys hold every member reached, a reader
    one of the two (the TBox's own lists are named as the reader reads them)."""
    if store.writes_pending:  # a query would commit them: the quad reads see them and leave them undoable
        two_firsts, open_end = _malformed_by_quads(store, graph)
    else:  # two queries, 15 ms and 31 ms CPU on a map of 40,000 list cells (the quad reads: 170 ms)
        count = f"SELECT (COUNT(*) AS ?n) (COUNT(DISTINCT ?c) AS ?m) WHERE {{ ?c <{FIRST.value}> ?x }}"
        two_firsts = any(row["n"] != row["m"] for row in store.query(count, graphs=[graph]))
        ends = (f"SELECT ?list WHERE {{ ?group a <{OWL}AllDifferent> ; <{OWL}distinctMembers>|<{OWL}members> "
                f"?list . FILTER NOT EXISTS {{ ?list <{REST.value}>* <{NIL.value}> }} }} LIMIT 1")
        open_end = any(True for _ in store.query(ends, graphs=[graph]))
    if two_firsts:
        note(UNSUPPORTED, TWO_FIRSTS, "a malformed RDF list: an axiom "
             "reading it takes one of the two, an AllDifferent group both")
    if open_end:
        note(UNSUPPORTED, OPEN_END, "a malformed "
             "RDF list (it loops back on itself or is cut short): its group holds the members reached")


def _malformed_by_quads(store: Store, graph: NamedNode) -> tuple[bool, bool]:
    """:func:`malformed_lists`' two tests by the quad reads: (a cell with two rdf:first, an AllDifferent
    member list not ending in rdf:nil)."""
    cells: set = set()
    two_firsts = False
    for t in store.triples(None, FIRST, None, graph):
        two_firsts = two_firsts or t.subject in cells
        cells.add(t.subject)
    groups = store.subjects(TYPE, owl("AllDifferent"), graph)
    rest = {t.subject: t.object for t in store.triples(None, REST, None, graph)} if groups else {}
    for head in (h for g in groups for p in (owl("distinctMembers"), owl("members")) for h in store.objects(g, p, graph)):
        node, seen = head, set()
        while node != NIL and node not in seen and node in rest:
            seen.add(node)
            node = rest[node]
        if node != NIL:
            return two_firsts, True
    return two_firsts, False


def imports(note: Note, store: Store, graph: NamedNode) -> None:
    """An ``owl:imports`` of an ontology not loaded: its axioms are missing (topostore fetches no URL)."""
    imported = [t.object for t in store.triples(None, owl("imports"), None, graph)]
    if not imported:
        return
    loaded = {t.subject for t in store.triples(None, TYPE, owl("Ontology"), graph)}
    loaded |= {t.object for t in store.triples(None, owl("versionIRI"), None, graph)}
    for target in imported:
        if target not in loaded:
            note(UNSUPPORTED, f"imports {target.value}", "the imported ontology is not loaded and "
                 "not fetched (topostore reads no URL): its axioms are not reasoned; load its file too")


def top_and_bottom(note: Note, store: Store, graph: NamedNode) -> None:
    """The universal and the empty properties have no rules: named wherever a file uses them."""
    for name, meaning in _TOP_AND_BOTTOM.items():
        p = owl(name)
        if any(next(iter(store.triples(*pattern, graph)), None) is not None
               for pattern in ((p, None, None), (None, p, None), (None, None, p))):
            note(UNSUPPORTED, f"owl:{name}", f"{meaning}: not reasoned, used as any other property")


def reflexive_equality(store: Store, graph: NamedNode) -> Notice | None:
    """Said once when the file states an equality: see :data:`REFLEXIVE_SAME_AS` for why."""
    first = next(iter(store.triples(None, SAME_AS, None, graph)), None)
    if first is None:
        return None
    subject = f"owl:sameAs (as in {short_name(first.subject)} sameAs {short_name(first.object)})"
    return Notice(NOT_STORED, subject, REFLEXIVE_SAME_AS)


__all__ = ["REFLEXIVE_SAME_AS", "MALFORMED", "malformed_lists", "malformed_now",
           "imports", "list_vocabulary", "reflexive_equality", "top_and_bottom",
           "unchecked_datatypes"]
