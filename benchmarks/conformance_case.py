"""One W3C OWL 2 test case on one engine, in a process of its own (see :mod:`benchmarks.conformance`).

``python -m benchmarks.conformance_case ENGINE CASE.json`` prints one JSON object (``--batch ENGINE
CASE.json...``: one per case, in order, each on a line starting ``RESULT``): for each check
of the case (``consistency``, ``inconsistency``, ``positive``, ``negative``) true when the engine
passes it, false when it does not, or ``"error: ..."`` when it refused the premise.

Entailment is decided the same way for both engines: the conclusion's type assertions with a class
expression become ``Q ≡ expression`` plus ``a rdf:type Q``, its subclass axioms a fresh individual of
the subclass asked to be in the superclass; every other triple is a SPARQL ASK (blank nodes as
variables) over the premise's closure.  An inconsistent premise entails everything.
"""

from __future__ import annotations

import json
import sys
import warnings
from dataclasses import dataclass, field
from itertools import count

import rdflib
from rdflib import BNode, Graph, URIRef
from rdflib.namespace import OWL, RDF, RDFS

_TRIVIAL_TYPES = {OWL.Class, OWL.ObjectProperty, OWL.DatatypeProperty, OWL.AnnotationProperty, OWL.NamedIndividual,
                  OWL.Thing, OWL.Ontology, RDFS.Datatype, RDFS.Class, RDF.Property}
_TEST = "http://topostore.invalid/conformance#"


#: Predicates that state an axiom about a class expression rather than describe it: naming an
#: expression must not copy them, or the conclusion under test would be added to the premise.
_AXIOMS = {RDFS.subClassOf, OWL.equivalentClass, OWL.disjointWith, OWL.disjointUnionOf}


def _subgraph(g: Graph, node: BNode, into: list, seen: set) -> None:
    """Triples describing a blank node (a class expression and its lists), depth first; never the
    axioms it takes part in (:data:`_AXIOMS`)."""
    if node in seen:
        return
    seen.add(node)
    for t in g.triples((node, None, None)):
        if t[1] in _AXIOMS:
            continue
        into.append(t)
        if isinstance(t[2], BNode):
            _subgraph(g, t[2], into, seen)


@dataclass
class Tests:
    """What a conclusion asks of the premise: ``extra`` triples added, then ``asks`` hold; and each
    triple set of ``contradictions``, added alone, makes the premise inconsistent."""

    extra: list = field(default_factory=list)
    asks: list = field(default_factory=list)
    contradictions: list = field(default_factory=list)


class _Reducer:
    """Turns a conclusion's axioms into :class:`Tests` (the reductions of entailment to what a
    reasoner answers: types of fresh individuals, ASKs, inconsistency)."""

    def __init__(self, conclusion: Graph) -> None:
        self.g, self.t, self.fresh, self.consumed = conclusion, Tests(), count(), set()

    def individual(self) -> URIRef:
        return URIRef(f"{_TEST}t{next(self.fresh)}")

    def name(self, expr) -> URIRef:
        """A named class for ``expr`` (itself when named; else Q ≡ expr added to the premise)."""
        if not isinstance(expr, BNode):
            return expr
        q = URIRef(f"{_TEST}Q{next(self.fresh)}")
        body: list = []
        _subgraph(self.g, expr, body, set())
        self.consumed.update(body)
        self.t.extra.extend(body)
        self.t.extra.append((q, OWL.equivalentClass, expr))
        return q

    def members(self, node) -> list:
        out: list = []
        while node != RDF.nil and node is not None:
            self.consumed.update(self.g.triples((node, None, None)))
            out.append(self.g.value(node, RDF.first))
            node = self.g.value(node, RDF.rest)
        return out

    def reduce(self, t: tuple) -> bool:
        """Add the tests of one triple; False when it is left to a plain ASK."""
        s, p, o = t
        g, tests = self.g, self.t
        x, y, z = self.individual(), self.individual(), self.individual()
        if p == RDF.type and o in _TRIVIAL_TYPES and not isinstance(s, BNode):
            return True
        if p == RDF.type and isinstance(o, BNode) and not isinstance(s, BNode) and _is_class_expression(g, o):
            tests.asks.append((s, RDF.type, self.name(o)))
        elif p in (RDFS.subClassOf, OWL.equivalentClass) and (not isinstance(s, BNode) or _is_class_expression(g, s)):
            for sub, sup in [(s, o)] if p == RDFS.subClassOf else [(s, o), (o, s)]:
                if sup != OWL.Thing:
                    i = self.individual()
                    tests.extra.append((i, RDF.type, self.name(sub)))
                    tests.asks.append((i, RDF.type, self.name(sup)))
        elif p == OWL.disjointWith:
            tests.contradictions.append([(x, RDF.type, self.name(s)), (x, RDF.type, self.name(o))])
        elif p == OWL.differentFrom:
            tests.contradictions.append([(s, OWL.sameAs, o)])
        elif p in (RDFS.subPropertyOf, OWL.equivalentProperty, OWL.inverseOf) and not isinstance(s, BNode):
            pairs = [(s, o)] if p == RDFS.subPropertyOf else [(s, o), (o, s)]
            for a, b in pairs:
                i, j = self.individual(), self.individual()
                tests.extra.append((i, a, j))
                tests.asks.append((j, b, i) if p == OWL.inverseOf else (i, b, j))
        elif p in (RDFS.domain, RDFS.range) and not isinstance(s, BNode) and not _is_data_range(g, o):
            tests.extra.append((x, s, y))
            tests.asks.append((x if p == RDFS.domain else y, RDF.type, self.name(o)))
        elif p == OWL.propertyDisjointWith:
            tests.contradictions.append([(x, s, y), (x, o, y)])
        elif p == RDF.type and o == OWL.TransitiveProperty:
            tests.extra += [(x, s, y), (y, s, z)]
            tests.asks.append((x, s, z))
        elif p == RDF.type and o == OWL.SymmetricProperty:
            tests.extra.append((x, s, y))
            tests.asks.append((y, s, x))
        elif p == RDF.type and o in (OWL.FunctionalProperty, OWL.InverseFunctionalProperty):
            tests.extra += [(x, s, y), (x, s, z)] if o == OWL.FunctionalProperty else [(y, s, x), (z, s, x)]
            tests.asks.append((y, OWL.sameAs, z))
        elif p == RDF.type and o == OWL.IrreflexiveProperty:
            tests.contradictions.append([(x, s, x)])
        elif p == RDF.type and o == OWL.AsymmetricProperty:
            tests.contradictions.append([(x, s, y), (y, s, x)])
        elif p == RDF.type and o in (OWL.AllDifferent, OWL.AllDisjointClasses) and isinstance(s, BNode):
            self.consumed.update(g.triples((s, None, None)))
            head = g.value(s, OWL.distinctMembers) or g.value(s, OWL.members)
            items = self.members(head)
            for k, a in enumerate(items):
                for b in items[k + 1:]:
                    if o == OWL.AllDifferent:
                        tests.contradictions.append([(a, OWL.sameAs, b)])
                    else:
                        i = self.individual()
                        tests.contradictions.append([(i, RDF.type, self.name(a)), (i, RDF.type, self.name(b))])
        elif p == RDF.type and o == OWL.NegativePropertyAssertion and isinstance(s, BNode):
            self.consumed.update(g.triples((s, None, None)))
            source, prop = g.value(s, OWL.sourceIndividual), g.value(s, OWL.assertionProperty)
            target = g.value(s, OWL.targetIndividual) or g.value(s, OWL.targetValue)
            tests.contradictions.append([(source, prop, target)])
        else:
            return False
        return True


def entailment_tests(conclusion: Graph) -> Tests:
    """The tests of a conclusion ontology (see :class:`Tests`)."""
    r = _Reducer(conclusion)
    for o in conclusion.subjects(RDF.type, OWL.Ontology):
        r.consumed.update(conclusion.triples((o, None, None)))
    for t in list(conclusion):
        if t not in r.consumed and r.reduce(t):
            r.consumed.add(t)
    r.t.asks += [t for t in conclusion if t not in r.consumed]
    return r.t


def _is_data_range(g: Graph, node) -> bool:
    """A datatype or data range (its values are literals: no fresh individual can be one)."""
    if str(node).startswith(("http://www.w3.org/2001/XMLSchema#", str(RDFS.Literal), str(RDF.PlainLiteral))):
        return True
    return (node, RDF.type, RDFS.Datatype) in g or any(g.triples((node, OWL.onDatatype, None)))


def _is_class_expression(g: Graph, node) -> bool:
    return any(g.triples((node, p, None)) for p in (OWL.onProperty, OWL.intersectionOf, OWL.unionOf,
                                                    OWL.complementOf, OWL.oneOf))


def ask_text(triples: list[tuple]) -> str:
    def term(t) -> str:
        return f"?b{t}" if isinstance(t, BNode) else t.n3()
    return "ASK { " + " ".join(f"{term(s)} {term(p)} {term(o)} ." for s, p, o in triples) + " }"


BASE = "http://example.org/"


def parse(text: str) -> Graph:
    return Graph().parse(data=text, format="xml", publicID=BASE)


# ------------------------------------------------------------------------------------- engines

def topostore_run(premise_text: str, extra: list[tuple], asks: list[tuple] | None) -> tuple[bool, bool, list[str]]:
    """(consistent, the ASK holds, the profile report's axiom kinds) with topostore, reading the
    premise's RDF/XML itself (then the extra triples)."""
    from topostore import Ontology, OntologyWarning

    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        onto.load_data(premise_text, "rdfxml", base_iri=BASE)
        if extra:
            g = Graph()
            for t in extra:
                g.add(t)
            onto.load_data(g.serialize(format="nt"), "ntriples")
    report = onto.reason()
    consistent, kinds = report.consistent, sorted({n.axiom_kind or n.kind for n in onto.notices})
    if not asks or not consistent:
        return consistent, not consistent, kinds
    return consistent, bool(onto.sparql(ask_text(asks))), kinds


def owlrl_run(premise_text: str, extra: list[tuple], asks: list[tuple] | None) -> tuple[bool, bool, list[str]]:
    """(consistent, the ASK holds, []) with owlrl (OWL 2 RL closure; inconsistency = its error messages)."""
    import owlrl

    premise = parse(premise_text)
    for t in extra:
        premise.add(t)
    owlrl.DeductiveClosure(owlrl.OWLRL_Semantics).expand(premise)
    errors = URIRef("http://www.daml.org/2002/03/agents/agent-ont#ErrorMessage")
    consistent = (None, RDF.type, errors) not in premise and (None, RDF.type, OWL.Nothing) not in premise
    if not asks or not consistent:
        return consistent, not consistent, []
    return consistent, bool(premise.query(ask_text(asks)).askAnswer), []


ENGINES = {"topostore": topostore_run, "owlrl": owlrl_run}


def entails(run, premise_text: str, tests: Tests) -> tuple[bool, set[str]]:
    """Whether the premise entails the conclusion the tests were made from, and the profile report's
    axiom kinds with the conclusion's expressions loaded (what the engine says of the question asked)."""
    consistent, holds, kinds = run(premise_text, tests.extra, tests.asks or None)
    said = set(kinds)
    if not consistent:
        return True, said
    if tests.asks and not holds:
        return False, said
    for triples in tests.contradictions:
        consistent, _, kinds = run(premise_text, triples, None)
        said |= set(kinds)
        if consistent:
            return False, said
    return True, said


def run_case(engine: str, case: dict) -> dict[str, object]:
    """The checks of ``case`` on ``engine``; ``notices``: the axiom kinds the profile report names for the
    premise; ``question_notices``: those it adds once the conclusion's expressions are loaded."""
    run = ENGINES[engine]
    out: dict[str, object] = {}
    try:
        checks = case["checks"]
        consistent, _, kinds = run(case["premise"], [], None)
        out["notices"] = kinds
        if "consistency" in checks:
            out["consistency"] = consistent
        if "inconsistency" in checks:
            out["inconsistency"] = not consistent
        asked: set[str] = set()
        for check, key in (("positive", "conclusion"), ("negative", "nonconclusion")):
            if check in checks and case.get(key):
                entailed, said = entails(run, case["premise"], entailment_tests(parse(case[key])))
                asked |= said
                out[check] = entailed if check == "positive" else not entailed
        out["question_notices"] = sorted(asked - set(kinds))
    except Exception as exc:  # a refusal or a failure of the engine is this case's answer, not the run's end
        message = f"error: {type(exc).__name__}: {' '.join(str(exc).split())[:300]}"
        for check in case["checks"]:
            out.setdefault(check, message)
    return out


def main(argv: list[str]) -> int:
    """``ENGINE FILE`` or ``--batch ENGINE FILE...``: each case's answers, one line each, as they are found."""
    if argv and argv[0] == "--batch":
        engine, paths = argv[1], argv[2:]
    else:
        engine, paths = argv[0], argv[1:]
    for path in paths:
        with open(path, encoding="utf-8") as f:
            case = json.load(f)
        print("RESULT " + json.dumps(run_case(engine, case)), flush=True)
    return 0


if __name__ == "__main__":  # pragma: no cover
    rdflib.logger.setLevel("ERROR")
    sys.exit(main(sys.argv[1:]))
