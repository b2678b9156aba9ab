"""Consistency: every match of a check rule is an inconsistency, reported with
the axiom it violates and the individuals involved.

A check reads the default dataset (asserted, inferred, helper graphs), where each pattern is looked
up in every graph.  Before the checks run, one query finds which graphs hold facts of each key their
bodies read (:func:`.present.key_graphs`): a check with a key that has no fact cannot match and is not
run, and an atom whose key lies in one graph is read in that graph, as a full REASON's rules are
(:func:`.order.single_graphs`).  Filters still read the whole dataset.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from itertools import islice

from pyoxigraph import Literal, NamedNode

from ..compile.condition import TEST
from ..compile.disjointness import CHECK, Disjointness, ToldPair, check_query
from ..compile.generic import PREFIXES
from ..compile.owl_restrictions import term_before
from ..compile.rule import ReadKey, Rule, RuleSet
from ..compile.schema import Row, schema_rule
from ..rdf.terms import sparql
from ..rdf.vocab import ASSERTED, AUX, INFERRED, TYPE, XSD
from ..stores.base import Store, unskolem
from .present import KeyGraphs, key_graphs

_TYPE = str(TYPE)
#: How many matches of one check are reported (one is enough to be inconsistent).
MAX_REPORTED = 20


def short(term) -> str:
    """``term`` as a message names it: an IRI by its local name, a literal as :func:`spelled`."""
    term = unskolem(term)
    if isinstance(term, Literal):
        return spelled(term)
    if isinstance(term, NamedNode):
        v = term.value
        return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]
    return str(term)


def spelled(value: Literal) -> str:
    """``value`` as a reader writes it in Turtle: an XML Schema datatype by its ``xsd:`` name, ``xsd:string``
    left out: a message names values, not their datatypes' full IRIs."""
    lexical = str(Literal(value.value))
    if value.language:
        return f"{lexical}@{value.language}"
    datatype = value.datatype.value
    if datatype == XSD + "string":
        return lexical
    if datatype.startswith(XSD):
        return f"{lexical}^^xsd:{datatype[len(XSD):]}"
    return f"{lexical}^^<{datatype}>"


@dataclass(frozen=True)
class Violation:
    """One inconsistency: the rule, the axiom it was compiled from, the individuals."""

    rule: str
    axiom: str
    individuals: dict = field(default_factory=dict)
    message: str = ""

    def __str__(self) -> str:
        return f"{self.message} [{self.rule}: {self.axiom}]"


#: The graphs the checks read, as their default dataset
GRAPHS = [ASSERTED, INFERRED, AUX]


def check_text(rule: Rule, graphs: dict[ReadKey, NamedNode] | None = None) -> str:
    """The query of a check; ``graphs``: the one graph holding every fact of some read keys."""
    proj = " ".join(rule.violation)
    first = "".join(f"{line}\n  " for line in several_values(rule, graphs or {}))
    return f"SELECT DISTINCT {proj} WHERE {{\n  {first}{rule.where(graphs=graphs)}\n}} LIMIT {MAX_REPORTED}"


def several_values(rule: Rule, graphs: dict[ReadKey, NamedNode]) -> list[str]:
    """Subqueries keeping a check to the subjects with two values, where it pairs two values.

    A maximum-cardinality check pairs two values ``?x p ?y1``, ``?x p ?y2`` that it orders strictly
    (:func:`~topostore.compile.owl_restrictions.term_before`), so every match has two different
    terms as values: the subjects holding at least two, counted first in the same graphs the
    atoms read, are the only ones it can match, and the pair join then runs on those alone (at
    10,000 locations the max-1 check on visit times reads 10,000 subjects of one value each).
    """
    out = []
    for i, a in enumerate(rule.body):
        for b in rule.body[i + 1:]:
            if (a.s, a.p, a.aux) != (b.s, b.p, b.aux) or a.p.startswith("?") or a.p == _TYPE \
                    or not all(t.startswith("?") for t in (a.s, a.o, b.o)) or a.o == b.o:
                continue
            ordered = {term_before(a.o, b.o), term_before(b.o, a.o)}
            if not any(c.kind == TEST and c.expression in ordered for c in rule.conditions):
                continue
            pattern = f"{a.s} {a.p} ?several_value ."
            graph = AUX if a.aux else graphs.get(a.read_key())
            if graph is not None:
                pattern = f"GRAPH {graph} {{ {pattern} }}"
            out.append(f"{{ SELECT {a.s} WHERE {{ {pattern} }} GROUP BY {a.s} HAVING (COUNT(DISTINCT ?several_value) > 1) }}")
    return out


#: members counted per class when ordering a check's classes (a bound: only "small first" matters)
SMALL_CLASS = 1000


def small_first(store: Store, rule: Rule, graphs: dict[ReadKey, NamedNode]) -> Rule:
    """``rule`` with its class atoms on one subject (a disjointness check: ``?x a C1 . ?x a C2``) ordered
    by their members, fewest first.

    The store joins the atoms in the order written: 10,000 doors each looked up among the robots cost
    9.5 ms, the one robot looked up among the doors 0.06 ms (and 10,000 LOCATIONs among the doors 38 ms
    against 9 ms the other way).  The members are counted from the index up to :data:`SMALL_CLASS`, so
    only where a look-up costs no request (a store with round trips keeps the written order).
    """
    atoms = rule.body
    if store.round_trips or len(atoms) < 2 or len({a.s for a in atoms}) != 1 \
            or any(a.p != _TYPE or a.o.startswith("?") for a in atoms):
        return rule
    sizes = {a: _members(store, a, graphs) for a in atoms}
    ordered = tuple(sorted(atoms, key=sizes.__getitem__))
    return rule if ordered == atoms else replace(rule, body=ordered)


def _members(store: Store, atom, graphs: dict[ReadKey, NamedNode]) -> int:
    """The members of ``atom``'s class in the graphs it is read in, counted up to :data:`SMALL_CLASS`."""
    cls = NamedNode(atom.o[1:-1])
    one = AUX if atom.aux else graphs.get(atom.read_key())
    count = 0
    for graph in [one] if one is not None else GRAPHS:
        count += sum(1 for _ in islice(store.triples(None, TYPE, cls, graph), SMALL_CLASS - count))
        if count >= SMALL_CLASS:
            break
    return count


def check_keys(rules: RuleSet) -> set[ReadKey]:
    """The read keys of the checks' body atoms (the told pairs of disjoint classes read their classes)."""
    keys = {atom.read_key() for rule in rules.base_checks for atom in rule.body}
    table = rules.disjointness
    return keys | {("t", c) for c in table.classes()} if table is not None else keys


def one_graphs(rule: Rule, found: KeyGraphs) -> dict[ReadKey, NamedNode] | None:
    """The one graph of each key of ``rule`` whose facts lie in one graph; None when a key the rule
    needs has no fact (the check cannot match)."""
    out: dict[ReadKey, NamedNode] = {}
    for atom in rule.body:
        where = found.get(atom.read_key())
        if where is None:  # a variable predicate: the whole dataset
            continue
        if not where:
            return None
        if len(where) == 1:
            out[atom.read_key()] = next(iter(where))
    return out


def _message(rule: Rule, row: dict) -> str:
    text = rule.message or f"{rule.name} violated"
    for var, value in row.items():
        text = text.replace("{" + var + "}", short(value))
    return text


def check_consistency(store: Store, rules: RuleSet, keys: KeyGraphs | None = None,
                      known: Mapping[int, list[dict]] | None = None) -> list[Violation]:
    """All violations of the check rules over asserted ∪ inferred knowledge.

    ``keys``: the graphs of :data:`GRAPHS` holding facts of each key the checks read
    (:func:`.present.key_graphs`, asked here when not given).  ``known``: the matches of some checks
    (by their index in ``rules.checks``) found already, beside the rules' fixpoint (:mod:`.early_reads`).

    The told pairs of disjoint classes (after the other checks in ``rules.checks``) are checked in one
    query (:func:`disjoint_violations`) unless all were found already: their checks are then never
    made one per pair."""
    base = rules.base_checks
    table = rules.disjointness
    told = len(table.told) if table is not None else 0
    if not base and not told:
        return []
    if keys is None:
        keys = key_graphs(store, check_keys(rules), GRAPHS)
    known = known or {}
    if told and not all(j in known for j in range(len(base), len(base) + told)):
        matches = [known[j] if j in known else check_rows(store, rule, keys) for j, rule in enumerate(base)]
        return violations(base, matches) + disjoint_violations(store, table, keys)
    checks = rules.checks
    matches = [known[j] if j in known else check_rows(store, rule, keys) for j, rule in enumerate(checks)]
    return violations(checks, matches)


def disjoint_violations(store: Store, table: Disjointness, keys: KeyGraphs) -> list[Violation]:
    """The violations of the told pairs of disjoint classes: one query over the pairs whose classes
    both have facts, each violation named as the pair's own check (``cax-dw``) names it."""
    pairs = table.told_among(key for (kind, key), where in keys.items() if kind == "t" and where)
    if not pairs:
        return []
    by_row = {pair.row: pair for pair in pairs}
    found: dict[Row, list[dict]] = {}
    limit = MAX_REPORTED * len(pairs)
    if _collect(store, check_query(pairs, limit), by_row, found) >= limit:
        # the LIMIT counts rows, not pairs: a busy pair may have taken the rows of others, so each pair
        # not yet full is asked again on its own (an inconsistent ontology: rare, and each answer is small)
        for pair in pairs:
            if len(found.get(pair.row, ())) < MAX_REPORTED:
                found.pop(pair.row, None)
                _collect(store, check_query([pair], MAX_REPORTED), by_row, found)
    check = schema_rule(CHECK)
    rows = [pair.row for pair in pairs if pair.row in found]  # the told order, whichever query found them
    instantiated = [check.instantiate(row, by_row[row].origin, by_row[row].labels) for row in rows]
    return violations(instantiated, [found[row] for row in rows])


def _collect(store: Store, text: str, by_row: dict[Row, ToldPair], found: dict[Row, list[dict]]) -> int:
    """Add the individuals of each pair the check ``text`` matches to ``found`` (at most
    :data:`MAX_REPORTED` per pair); how many rows it answered."""
    answered = 0
    for solution in store.query(text, graphs=GRAPHS, prefixes=PREFIXES):
        answered += 1
        pair = by_row.get((sparql(solution["c"]), sparql(solution["d"])))
        if pair is not None and len(found.setdefault(pair.row, [])) < MAX_REPORTED:
            found[pair.row].append({"x": solution["x"]})
    return answered


def check_rows(store: Store, rule: Rule, keys: KeyGraphs) -> list[dict]:
    """The matches of one check (its violation variables), reading each key in the graphs ``keys`` gives."""
    graphs = one_graphs(rule, keys)
    if graphs is None:
        return []
    text = check_text(small_first(store, rule, graphs), graphs)
    return [{v[1:]: solution[v[1:]] for v in rule.violation if solution[v[1:]] is not None}
            for solution in store.query(text, graphs=GRAPHS, prefixes=PREFIXES)]


def violations(checks: list[Rule], matches: list[list[dict]]) -> list[Violation]:
    """The violations of ``checks`` from their matches, in check order, each reported once."""
    found: list[Violation] = []
    seen: set = set()
    for rule, rows in zip(checks, matches, strict=True):
        # sorted, so that the report does not depend on evaluation order
        for row in sorted(rows, key=lambda r: [str(v) for v in r.values()]):
            key = (rule.name, rule.origin, frozenset(row.values()))
            if key in seen:  # the same violation found with its variables swapped
                continue
            seen.add(key)
            found.append(Violation(rule.name, rule.origin, {k: unskolem(v) for k, v in row.items()}, _message(rule, row)))
    return found
