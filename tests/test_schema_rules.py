"""The generic OWL rules of ``rules/owl/`` and their two uses (topostore.compile.schema, schema_program).

1. Each file parses into a rule with a schema atom; instantiating it with a row and reading the row
   back from the instantiation are inverse.
2. The compiler's rules of those kinds are instantiations, with the texts the compiler always wrote.
3. A full REASON running them generically over the schema graphs reaches the same closure as the
   instantiated rules; on generated TBoxes and ABoxes (hypothesis) both equal owlrl's OWL 2 RL
   closure on the named individuals.
"""

from __future__ import annotations

import sys

import owlrl
import pytest
import rdflib
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import NamedNode, Triple

from topostore import Ontology
from topostore.compile.notices import NON_SIMPLE
from topostore.compile.rule import Atom
from topostore.compile.schema import schema_rule, schema_rules, template_of
from topostore.compile.schema_program import GENERIC_ROWS, closed, full_program
from topostore.errors import RuleCompileError
from topostore.rdf.vocab import AUX, INFERRED, SCHEMA_PREFIX
from topostore.reason.consistency import check_consistency
from topostore.reason.materialize import Materializer
from topostore.resources import default_ontology

NS = "http://example.org/schema#"
TYPE = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>"
KINDS = {"cax-sco", "cax-eqc1", "cax-eqc2", "prp-dom", "prp-rng", "prp-spo1", "prp-inv1", "prp-inv2", "prp-symp",
         "prp-trp", "cax-dw", "different-disjoint", "ext-card-sub", "cls-svf1", "cls-avf", "cls-hv1", "cls-hv2",
         "cls-int2", "cls-uni", "prp-spo2", "ext-restriction-sub", "cls-oo", "neg-dw", "neg-svf", "neg-sco",
         "neg-int", "neg-com", "neg-avf", *(f"cls-int1-{n}" for n in range(2, 9)),
         *(f"neg-uni-{n}" for n in range(2, 9)), "prp-fp", "prp-ifp",
         "different-candidate-2-fp", "different-candidate-2-ifp", "different-values-3", "different-values-4-a",
         "different-values-4-b", "prp-fp-3", "prp-ifp-3", "prp-fp-2-data", "ext-some-value", "ext-all-value"}
#: the kinds the ontology EVERY_KIND has no axiom of (a restriction on a sub-property: see
#: test_restrictions_subsumed_through_properties_are_a_table; a one-of and the non-memberships a
#: complement needs: tests/test_schema_rows.py; the sameAs rules of functional properties:
#: tests/test_functional_rows.py, with their difference rules)
ELSEWHERE = {"ext-restriction-sub", "cls-oo", "prp-fp", "prp-ifp", "different-candidate-2-fp", "different-candidate-2-ifp",
             "different-values-3", "different-values-4-a", "different-values-4-b", "neg-dw", "neg-svf", "neg-sco",
             "neg-int", "neg-com", "neg-avf", "ext-some-value", "ext-all-value",
             *(f"cls-int1-{n}" for n in range(3, 9)), *(f"neg-uni-{n}" for n in range(2, 9))}
#: the generic checks (by file): the compiler emits their instantiations; a full REASON keeps them instantiated
CHECKS = {"cax-dw", "prp-fp-3", "prp-ifp-3", "prp-fp-2-data"}
PREFIXES = f"""\
@prefix : <{NS}> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
"""


def _closure(onto: Ontology) -> tuple[set, set]:
    return tuple({(t.subject, t.predicate, t.object) for t in onto.store.triples(None, None, None, g)}
                 for g in (INFERRED, AUX))


def _materialize(onto: Ontology, threshold: int) -> tuple[set, set]:
    """The closure a full materialisation reaches with the rules generic above ``threshold`` rows."""
    program = full_program(onto.rules, threshold)
    program.write(onto.store)
    try:
        Materializer(onto.store, program.rules).run()
    finally:
        program.drop(onto.store)
    assert _no_schema_graph(onto), "schema graphs left behind"
    return _closure(onto)


def _no_schema_graph(onto: Ontology) -> bool:
    return all(onto.store.is_empty(NamedNode(SCHEMA_PREFIX + name)) for name in schema_rules())


# ---------------------------------------------------------------- 1. the files
def test_every_kind_has_its_file_with_a_schema_atom() -> None:
    assert set(schema_rules()) == KINDS
    for rule in schema_rules().values():
        assert rule.schema and rule.variables and (rule.rule.head is None) == (rule.key in CHECKS)


def test_instantiation_and_row_of_are_inverse() -> None:
    sco = schema_rule("cax-sco")
    rule = sco.instantiate(("<urn:a>", "<urn:b>"), "a SubClassOf b")
    assert rule.body == (Atom("?x", TYPE, "<urn:a>"),) and rule.head == Atom("?x", TYPE, "<urn:b>")
    assert sco.row_of(rule) == ("<urn:a>", "<urn:b>")
    trp = schema_rule("prp-trp")
    rule = trp.instantiate(("<urn:p>",), "p is transitive")
    assert [a.text() for a in rule.body] == ["?x <urn:p> ?y .", "?y <urn:p> ?z ."]
    assert trp.row_of(rule) == ("<urn:p>",)
    assert sco.row_of(trp.instantiate(("<urn:p>",), "")) is None  # another rule's instantiation
    with pytest.raises(RuleCompileError):
        sco.instantiate(("<urn:a>",), "one term short")


def test_a_checks_instantiation_reports_the_individuals_and_names_the_rows_terms() -> None:
    dw = schema_rule("cax-dw")
    rule = dw.instantiate(("<urn:x#A>", "<urn:x#B>"), "A DisjointWith B")
    assert rule.violation == ("?x",) and rule.message == "{x} is in the disjoint classes A and B"
    assert dw.instantiate(("<urn:x#A>", "<urn:b>"), "", ("(p some A)", "B")).message == \
        "{x} is in the disjoint classes (p some A) and B"
    assert dw.row_of(rule) == ("<urn:x#A>", "<urn:x#B>")
    assert dw.evaluable(False).violation == ("?x", "?c", "?d")  # the generic check names what it read
    with pytest.raises(RuleCompileError):
        dw.instantiate(("<urn:a>", "<urn:b>"), "", ("one label",))


def test_a_helper_head_of_a_rule_file_is_a_helper_atom() -> None:
    head = schema_rule("different-disjoint").instantiate(("<urn:a>", "<urn:b>"), "").head
    assert head is not None and head.aux and schema_rule("cax-sco").rule.head.aux is False


def test_only_copying_rules_chain_and_their_rows_close() -> None:
    assert {n for n, r in schema_rules().items() if r.chains} == {"cax-sco", "cax-eqc1", "prp-spo1", "ext-card-sub",
                                                                     "ext-restriction-sub",
                                                                     "cls-int2"}
    assert sorted(closed([("a", "b"), ("b", "c"), ("c", "a")])) == [
        ("a", "b"), ("a", "c"), ("b", "a"), ("b", "c"), ("c", "a"), ("c", "b")]


@settings(max_examples=property_examples(200), deadline=None)
@given(st.lists(st.tuples(st.sampled_from("abcdefg"), st.sampled_from("abcdefg")), max_size=20))
def test_closed_rows_are_what_each_start_reaches(rows) -> None:
    """The closure's shortcut (a start takes whole the set an earlier start found) changes nothing."""
    from topostore.compile.reach import reachable

    succ: dict[str, list[str]] = {}
    for a, b in rows:
        succ.setdefault(a, []).append(b)
    assert closed(rows) == [(s, n) for s in succ for n in sorted(reachable(s, lambda x: succ.get(x, ())) - {s})]


def test_the_schema_atom_is_refused_in_the_rules_every_ontology_gets(tmp_path) -> None:
    from topostore.compile.generic import parse_rule_file

    path = tmp_path / "x.rq"
    path.write_text("# name: x\nCONSTRUCT { ?x ?p ?y }\nWHERE {\n  ?x ?p ?y .\n"
                    "  GRAPH ts:graph:schema { ?p a ?c . }\n}\n")
    with pytest.raises(RuleCompileError, match="schema atom"):
        parse_rule_file(path)


# ---------------------------------------------------------------- 2. what the compiler emits
EVERY_KIND = PREFIXES + """\
:A rdfs:subClassOf :B . :B owl:equivalentClass :C .
:D rdfs:subClassOf [ owl:intersectionOf ( :A :E ) ] .
:p rdfs:domain :A ; rdfs:range :B ; rdfs:subPropertyOf :q .
:q owl:inverseOf :r . :s a owl:SymmetricProperty . :t a owl:TransitiveProperty .
[ owl:inverseOf :p ] rdfs:domain :E .
:i :p :j . :k a :D . :j :s :k . :i :t :j . :j :t :k .
:G owl:disjointWith :H . [ owl:onProperty :p ; owl:minCardinality 2 ] rdfs:subClassOf :F .
:D rdfs:subClassOf [ owl:onProperty :p ; owl:someValuesFrom owl:Thing ] .
:m :p :g, :h . :g a :G . :h a :H .
:J owl:equivalentClass [ a owl:Class ; owl:unionOf ( :G :H ) ] . :K rdfs:subClassOf [ owl:onProperty :q ; owl:allValuesFrom :G ] .
:L owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :g ] .
[ owl:onProperty :s ; owl:someValuesFrom :G ] rdfs:subClassOf :M .
:n a :K ; :q :o . :u :s :g .
:v owl:propertyChainAxiom ( :p :s ) . :w owl:propertyChainAxiom ( :p :s :s ) . :g :s :h .
"""


def test_the_compiled_rules_of_those_kinds_are_instantiations_with_their_axioms() -> None:
    onto = Ontology()
    onto.load_data(EVERY_KIND, "turtle")
    rules = [r for r in onto.rules.all_rules if r.name in KINDS]
    texts = {(r.name, r.origin, " ".join(a.text() for a in r.body), r.head and r.head.text()) for r in rules}
    p, q, r_, a, b = (f"<{NS}{n}>" for n in ("p", "q", "r", "A", "B"))
    assert ("cax-sco", "A SubClassOf B", f"?x {TYPE} {a} .", f"?x {TYPE} {b} .") in texts
    assert ("prp-dom", "p domain A", f"?x {p} ?y .", f"?x {TYPE} {a} .") in texts
    assert ("prp-rng", "p range B", f"?x {p} ?y .", f"?y {TYPE} {b} .") in texts
    assert ("prp-spo1", "p SubPropertyOf q", f"?x {p} ?y .", f"?x {q} ?y .") in texts
    assert ("prp-inv2", "q InverseOf r", f"?x {r_} ?y .", f"?y {q} ?x .") in texts
    g, h = (f"<{NS}{n}>" for n in ("G", "H"))
    assert ("different-disjoint", "H and G are disjoint",
            f"?a <urn:topostore:differenceCandidate> ?b . ?a {TYPE} {h} . ?b {TYPE} {g} .",
            "?a <urn:topostore:declaredDifferent> ?b .") in texts
    assert any(n == "ext-card-sub" and o == "(p min 2 Thing) is subsumed by (p some Thing)" for n, o, _, _ in texts)
    dw = [r for r in rules if r.name == "cax-dw"]
    assert [(r.origin, " ".join(a.text() for a in r.body), r.violation, r.message) for r in dw] == [
        ("G DisjointWith H", f"?x {TYPE} {g} . ?x {TYPE} {h} .", ("?x",), "{x} is in the disjoint classes G and H")]
    # the domain of an inverse property expression has no row: its rule is written directly
    assert ("prp-dom", "p domain E", f"?y {p} ?x .", f"?x {TYPE} <{NS}E> .") in texts
    # so is an existential of owl:Thing (no filler atom: another shape than the table's)
    generic = schema_rules()
    assert all(generic[r.name].row_aux(generic[r.name].row_of(r)) == r.head_aux() for r in rules
               if generic[r.name].row_of(r) is not None)
    # and a chain of three properties (a row has a fixed number of terms)
    assert sorted(r.origin for r in rules if generic[r.name].row_of(r) is None) == [
        "class expression (p some Thing)", "p domain E", "w chain of p o s o s"]
    assert ("prp-spo2", "v chain of p o s", f"?u0 {p} ?u1 . ?u1 <{NS}s> ?u2 .", f"?u0 <{NS}v> ?u2 .") in texts


TUTORIAL_RULES = {  # as the compiler wrote them before the rules moved to rules/owl/ (same texts, origins, order)
    ("cax-sco", "URGENT SubClassOf LOCATION", "?x a URGENT", "?x a LOCATION"),
    ("prp-fp", "isIn is functional", "?x isIn ?y1 ?x isIn ?y2", "?y1 sameAs ?y2"),
    ("prp-fp", "isIn is functional", "?x isIn ?y1 ?x isIn ?y2 ?y1 _ ?y2",
     "{x} has the different values {y1} and {y2} of the functional property isIn"),
    ("cax-eqc2", "ROBOT EquivalentTo (isIn exact 1 LOCATION)", "?x a _", "?x a ROBOT"),
    ("cax-eqc2", "CORRIDOR EquivalentTo (LOCATION and (hasDoor min 2 DOOR))", "?x a _", "?x a CORRIDOR"),
    ("cax-eqc2", "ROOM EquivalentTo (LOCATION and (hasDoor some DOOR))", "?x a _", "?x a ROOM"),
    ("cax-eqc2", "LOCATION EquivalentTo (visitedAt exact 1 long)", "?x a _", "?x a LOCATION"),
    *(("prp-dom", f"{p} domain {c}", f"?x {p} ?y", f"?x a {c}") for p, c in (
        ("visitedAt", "LOCATION"), ("urgencyThreshold", "ROBOT"), ("now", "ROBOT"), ("canReach", "ROBOT"),
        ("connectedTo", "LOCATION"), ("isIn", "ROBOT"), ("hasDoor", "LOCATION"))),
    *(("prp-rng", f"{p} range {c}", f"?x {p} ?y", f"?y a {c}") for p, c in (
        ("canReach", "LOCATION"), ("connectedTo", "LOCATION"), ("isIn", "LOCATION"), ("hasDoor", "DOOR"))),
    # the class is folded into its intersection, and the restriction too (hasDoor's domain is LOCATION, the
    # intersection's other part): the rules read and write CORRIDOR and ROOM; the filler's atom is implied by
    # the range of hasDoor and dropped: both left as the passes after compilation made them
    ("ext-card-sub", "(hasDoor min 2 DOOR) is subsumed by (hasDoor some DOOR)", "?x a CORRIDOR", "?x a ROOM"),
    *(("cls-int2", f"class expression (LOCATION and {r})", f"?x a {c}", "?x a LOCATION")
      for c, r in (("CORRIDOR", "(hasDoor min 2 DOOR)"), ("ROOM", "(hasDoor some DOOR)"))),
    # what the intersection's rule left: a membership of the restriction told in the data is one of the class
    *(("cax-eqc2", f"class expression (LOCATION and {r})", "?x a _", f"?x a {c}")
      for c, r in (("CORRIDOR", "(hasDoor min 2 DOOR)"), ("ROOM", "(hasDoor some DOOR)"))),
    ("cls-svf1", "class expression (hasDoor some DOOR)", "?x hasDoor ?y1", "?x a ROOM"),
    *(("cax-dw", f"{a} DisjointWith {b}", f"?x a {a} ?x a {b}", f"{{x}} is in the disjoint classes {a} and {b}")
      for a, b in (("DOOR", "LOCATION"), ("DOOR", "ROBOT"), ("LOCATION", "ROBOT"))),
    *(("different-disjoint", f"{a} and {b} are disjoint", f"?a _ ?b ?a a {a} ?b a {b}", "?a _ ?b")
      for pair in (("DOOR", "LOCATION"), ("DOOR", "ROBOT"), ("LOCATION", "ROBOT")) for a, b in (pair, pair[::-1])),
}


def _short(atom: Atom) -> str:
    def term(t: str) -> str:
        if t == TYPE:
            return "a"
        if t.startswith("<urn:topostore:"):
            return "_"
        return t.rsplit("#", 1)[-1].rstrip(">") if t.startswith("<") else t
    return " ".join(term(t) for t in (atom.s, atom.p, atom.o))


def test_the_rule_set_holds_one_rule_per_file_and_its_table() -> None:
    """No instantiation of rules/owl/ is a rule of the rule set: each is a row of its table, bound one
    by one for maintenance (``inference_rules``) and read back by the full REASON's program."""
    onto = Ontology()
    onto.load_data(EVERY_KIND, "turtle")
    ruleset = onto.rules
    held = ruleset.held_rules()
    assert not [r for r in ruleset.rules if template_of(r) is not None and template_of(r).key in KINDS - CHECKS
                and template_of(r).row_of(r) is not None]
    assert ruleset.tables is not None and {template_of(r).key for r in held} == set(ruleset.tables.held)
    assert set(ruleset.tables.held) == KINDS - CHECKS - ELSEWHERE - {"different-disjoint"}  # the pairs: apart
    maintained = ruleset.inference_rules
    assert all(r in maintained for r in held) and all(r in ruleset.all_rules for r in held)
    assert ruleset.tables.rows("cax-sco") == [schema_rule("cax-sco").row_of(r) for r in ruleset.tables.held["cax-sco"]]
    assert "schema rows in" in ruleset.count_text()


def test_the_tutorial_maps_rules_of_those_kinds_are_the_ones_it_always_had() -> None:
    onto = Ontology()
    onto.load(default_ontology())
    got = [(r.name, r.origin, " ".join(_short(a) for a in r.body), _short(r.head) if r.head else r.message)
           for r in onto.rules.all_rules if r.name in KINDS]
    assert len(got) == len(TUTORIAL_RULES) and set(got) == TUTORIAL_RULES


# ---------------------------------------------------------------- 3. generic = instantiated
def test_generic_equals_instantiated_on_every_kind_with_a_class_expression() -> None:
    onto = Ontology()
    onto.load_data(EVERY_KIND, "turtle")
    program = full_program(onto.rules, 0)
    assert set(program.rows) == KINDS - CHECKS - ELSEWHERE
    assert any(r.head_aux() for r in program.rules.rules if r.name == "cax-sco")  # D into (A and E)
    instantiated = _materialize(onto, sys.maxsize)
    assert (NamedNode(NS + "k"), NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#type"),
            NamedNode(NS + "A")) in instantiated[0]
    # :g and :h are different as members of disjoint classes (different-disjoint), so :m has two values
    rdf_type = NamedNode(TYPE[1:-1])
    for s, c in (("m", "F"), ("o", "J"), ("u", "M"), ("m", "L"), ("o", "G")):
        assert (NamedNode(NS + s), rdf_type, NamedNode(NS + c)) in instantiated[0], (s, c)
    assert (NamedNode(NS + "m"), NamedNode(NS + "v"), NamedNode(NS + "h")) in instantiated[0]  # p o s
    assert _materialize(onto, 0) == instantiated


def test_the_rows_bound_keep_the_order_the_compiler_gave_them(monkeypatch) -> None:
    """What a REASON evaluates (the rows bound, among the other rules) is in the compiler's order, as
    when every axiom was a rule of its own."""
    import topostore.compile.pipeline as pipeline
    from topostore.rdf.vocab import ASSERTED

    onto = Ontology()
    onto.load_data(EVERY_KIND, "turtle")
    held = onto.rules
    monkeypatch.setattr(pipeline, "hold_tables", lambda rules: (rules, None))
    unheld = pipeline.compile_ontology(onto.store, ASSERTED)
    assert held.tables is not None and unheld.tables is None and len(held.rules) < len(unheld.rules)
    assert [(r.name, r.origin, r.where(), r.head) for r in held.compiled_rules()] == \
        [(r.name, r.origin, r.where(), r.head) for r in unheld.rules]


def test_restrictions_subsumed_through_properties_are_a_table() -> None:
    """∃p.C ⊑ ∃q.C for p ⊑ q is a row of ext-restriction-sub: no rule of its own in the rule set, the same
    closure generic or row by row, and maintained as a step adds a member."""
    onto = Ontology()
    onto.load_data(PREFIXES + ":p a owl:ObjectProperty ; rdfs:subPropertyOf :q . :q a owl:ObjectProperty .\n"
                   ":C a owl:Class . :A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :C ] .\n"
                   ":B owl:equivalentClass [ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom :C ] .\n"
                   ":x a :A .\n", "turtle")
    assert not any(r.name == "ext-restriction-sub" for r in onto.rules.rules)
    assert onto.rules.tables is not None and len(onto.rules.tables.held["ext-restriction-sub"]) == 1
    assert _materialize(onto, 0) == _materialize(onto, sys.maxsize)
    onto.reason()
    assert NamedNode(NS + "B") in onto.types(NamedNode(NS + "x"))
    onto.add(Triple(NamedNode(NS + "y"), NamedNode(TYPE[1:-1]), NamedNode(NS + "A")))  # maintained, row by row
    onto.reason()
    assert NamedNode(NS + "B") in onto.types(NamedNode(NS + "y"))


def test_a_universal_meeting_an_existentials_value_is_two_tables() -> None:
    """``x ∈ ∃p.D`` (a value of ``p`` and of its super-property ``q``, ext-some-value) and ``x ∈ ∀q.G`` put ``x`` in
    ``∃q.G`` (ext-all-value): rows of two tables, the same closure generic or row by row, maintained as a step
    adds a member."""
    onto = Ontology()
    onto.load_data(PREFIXES + ":p a owl:ObjectProperty ; rdfs:subPropertyOf :q . :q a owl:ObjectProperty .\n"
                   ":D a owl:Class . :G a owl:Class .\n"
                   ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :D ] .\n"
                   ":U rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :q ; owl:allValuesFrom :G ] .\n"
                   ":B owl:equivalentClass [ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom :G ] .\n"
                   ":x a :A , :U .\n", "turtle")
    assert not any(r.name in ("ext-some-value", "ext-all-value") for r in onto.rules.rules)
    assert onto.rules.tables is not None and len(onto.rules.tables.held["ext-all-value"]) == 1
    assert _materialize(onto, 0) == _materialize(onto, sys.maxsize)
    onto.reason()
    assert NamedNode(NS + "B") in onto.types(NamedNode(NS + "x"))
    y = NamedNode(NS + "y")
    onto.add(Triple(y, NamedNode(TYPE[1:-1]), NamedNode(NS + "A")))  # maintained, row by row
    onto.reason()
    assert NamedNode(NS + "B") not in onto.types(y)
    onto.add(Triple(y, NamedNode(TYPE[1:-1]), NamedNode(NS + "U")))
    onto.reason()
    assert NamedNode(NS + "B") in onto.types(y)


def test_generic_equals_instantiated_on_the_tutorial_map() -> None:
    onto = Ontology()
    onto.load(default_ontology())
    onto.load(default_ontology().with_name("topological_map_abox.ttl"))
    assert _materialize(onto, 0) == _materialize(onto, sys.maxsize)


def test_a_full_reason_runs_a_large_table_generically() -> None:
    chain = "\n".join(f":C{i} rdfs:subClassOf :C{i + 1} ." for i in range(GENERIC_ROWS + 4))
    onto = Ontology()
    onto.load_data(PREFIXES + chain + "\n:x a :C0 .\n", "turtle")
    default = set(full_program(onto.rules).rows)  # and ext-card-sub: each existential is below the next ones
    assert "cax-sco" in default and "cls-svf1" not in default
    onto.reason(mode="full")
    assert NamedNode(f"{NS}C{GENERIC_ROWS + 4}") in onto.types(NamedNode(NS + "x"))
    assert _no_schema_graph(onto)


def test_a_rule_file_may_raise_its_own_threshold() -> None:
    """cls-svf1 reads a variable predicate: a full REASON keeps 20 of its instantiations (its file's
    ``# generic-rows:``), and runs cax-sco generically over as many rows."""
    from topostore.compile.schema_program import rows_threshold

    assert rows_threshold(schema_rule("cls-svf1")) > 20 >= GENERIC_ROWS == rows_threshold(schema_rule("cax-sco"))
    axioms = "\n".join(f":C{i} rdfs:subClassOf :C{i + 1} . [ owl:onProperty :p ; owl:someValuesFrom :C{i} ] "
                       f"rdfs:subClassOf :D{i} ." for i in range(20))
    onto = Ontology()
    onto.load_data(PREFIXES + axioms + "\n:x :p :y . :y a :C0 .\n", "turtle")
    default = set(full_program(onto.rules).rows)  # and ext-card-sub: each existential is below the next ones
    assert "cax-sco" in default and "cls-svf1" not in default
    assert set(full_program(onto.rules, 0).rows) >= {"cax-sco", "cls-svf1"}
    onto.reason(mode="full")
    assert {NamedNode(f"{NS}D{i}") for i in range(20)} <= set(onto.types(NamedNode(NS + "x")))


def test_a_failed_full_reason_reports_its_own_error_when_dropping_the_schema_graphs_fails_too(monkeypatch) -> None:
    """The run's error is the one raised; a failure to drop the schema graphs after it does not hide it."""
    from topostore.compile.schema_program import GenericProgram

    chain = "\n".join(f":C{i} rdfs:subClassOf :C{i + 1} ." for i in range(GENERIC_ROWS + 4))
    onto = Ontology()
    onto.load_data(PREFIXES + chain + "\n:x a :C0 .\n", "turtle")

    def run_fails(self, *args, **kwargs):
        raise RuntimeError("the run itself")

    real_drop, calls = GenericProgram.drop, []

    def drop_fails(self, store):  # the drop inside write() (what a failed run left) still works
        calls.append(1)
        if len(calls) % 2 == 1:
            return real_drop(self, store)
        raise OSError("the drop")

    monkeypatch.setattr(Materializer, "run", run_fails)
    monkeypatch.setattr(GenericProgram, "drop", drop_fails)
    with pytest.raises(RuntimeError, match="the run itself"):
        onto.reason(mode="full")
    monkeypatch.undo()
    monkeypatch.setattr(GenericProgram, "drop", drop_fails)
    with pytest.raises(OSError, match="the drop"):
        onto.reason(mode="full")


# ---------------------------------------------------------------- generated TBoxes
CLASSES = [f"C{i}" for i in range(5)]
PROPS = [f"p{i}" for i in range(4)]
INDIVIDUALS = [f"i{i}" for i in range(4)]
_c, _p, _i = st.sampled_from(CLASSES), st.sampled_from(PROPS), st.sampled_from(INDIVIDUALS)
axioms = st.lists(st.one_of(
    st.builds(":{} rdfs:subClassOf :{} .".format, _c, _c),
    st.builds(":{} owl:equivalentClass :{} .".format, _c, _c),
    st.builds(":{} rdfs:subClassOf [ owl:intersectionOf ( :{} :{} ) ] .".format, _c, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :{} :{} ) ] .".format, _c, _c, _c),
    st.builds(":{} rdfs:domain :{} .".format, _p, _c),
    st.builds(":{} rdfs:range :{} .".format, _p, _c),
    st.builds(":{} rdfs:subPropertyOf :{} .".format, _p, _p),
    st.builds(":{} owl:equivalentProperty :{} .".format, _p, _p),
    st.builds(":{} owl:inverseOf :{} .".format, _p, _p),
    st.builds(":{} a owl:SymmetricProperty .".format, _p),
    st.builds(":{} a owl:TransitiveProperty .".format, _p),
    st.builds("[ owl:onProperty :{} ; owl:someValuesFrom :{} ] rdfs:subClassOf :{} .".format, _p, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Restriction ; owl:onProperty :{} ; owl:hasValue :{} ] .".format, _c, _p, _i),
    st.builds("[ owl:inverseOf :{} ] rdfs:domain :{} .".format, _p, _c),
    st.builds(":{} rdfs:subClassOf [ owl:onProperty :{} ; owl:allValuesFrom :{} ] .".format, _c, _p, _c),
    st.builds(":{} owl:disjointWith :{} .".format, _c, _c),
    st.builds("[ a owl:AllDisjointClasses ; owl:members ( :{} :{} :{} ) ] .".format, _c, _c, _c),
    st.builds("[ owl:unionOf ( :{} :{} ) ] rdfs:subClassOf :{} .".format, _c, _c, _c),
    st.builds(":{} owl:propertyChainAxiom ( :{} :{} ) .".format, _p, _p, _p),
    st.builds(":{} a owl:FunctionalProperty .".format, _p),
    st.builds(":{} a owl:InverseFunctionalProperty .".format, _p),
), max_size=10)
#: axioms beyond OWL 2 RL (what a tableau reasoner concludes from cardinalities, restriction subsumption
#: and the difference of members of disjoint classes): generic = instantiated, no owlrl to compare with
beyond_rl = st.lists(st.one_of(
    st.builds(":{} rdfs:subClassOf [ owl:onProperty :{} ; owl:minQualifiedCardinality 2 ; owl:onClass :{} ] ."
              .format, _c, _p, _c),
    st.builds("[ owl:onProperty :{} ; owl:minCardinality 2 ] rdfs:subClassOf :{} .".format, _p, _c),
    st.builds("[ owl:onProperty :{} ; owl:someValuesFrom :{} ] rdfs:subClassOf :{} .".format, _p, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Restriction ; owl:onProperty :{} ; owl:maxCardinality 1 ] .".format, _c, _p),
    st.builds(":{} a owl:FunctionalProperty .".format, _p),
    st.builds(":{} a owl:InverseFunctionalProperty .".format, _p),
    st.builds(":{} rdfs:subClassOf :{} .".format, _c, _c),
    st.builds(":{} owl:disjointWith :{} .".format, _c, _c),
    st.builds("[ a owl:AllDisjointClasses ; owl:members ( :{} :{} :{} ) ] .".format, _c, _c, _c),
    st.builds(":{} owl:disjointUnionOf ( :{} :{} ) .".format, _c, _c, _c),
), max_size=10)
facts = st.lists(st.one_of(st.builds(":{} a :{} .".format, _i, _c), st.builds(":{} :{} :{} .".format, _i, _p, _i)),
                 max_size=8)


def _declarations() -> str:
    return "\n".join([f":{c} a owl:Class ." for c in CLASSES] + [f":{p} a owl:ObjectProperty ." for p in PROPS]
                     + [f":{i} a owl:NamedIndividual ." for i in INDIVIDUALS])


def _named(triples) -> set[tuple[str, str, str]]:
    """Memberships of the named classes and links by the named properties, between named individuals."""
    inds, classes, props = ({NS + n for n in names} for names in (INDIVIDUALS, CLASSES, PROPS))
    rdf_type = TYPE[1:-1]
    return {(s, p, o) for s, p, o in triples
            if s in inds and ((p == rdf_type and o in classes) or (p in props and o in inds))}


def _value(term) -> str:
    return getattr(term, "value", str(term))


@settings(max_examples=property_examples(40), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(axioms, facts)
@example(tbox=[":p0 a owl:TransitiveProperty .", ":p0 a owl:FunctionalProperty ."], abox=[":i0 :p0 :i1 ."])
def test_generic_equals_instantiated_equals_owlrl_on_generated_tboxes(tbox, abox) -> None:
    text = PREFIXES + _declarations() + "\n" + "\n".join(tbox + abox) + "\n"
    onto = Ontology()
    onto.load_data(text, "turtle")
    instantiated = _materialize(onto, sys.maxsize)
    assert _materialize(onto, 0) == instantiated
    if check_consistency(onto.store, onto.rules):
        return  # an inconsistent ontology entails everything: owlrl's closure and ours say nothing alike
    if any(n.axiom_kind == NON_SIMPLE for n in onto.notices):
        return  # outside OWL 2 DL (a transitive property also functional, …): read as Pellet reads it, not as owlrl
    g = rdflib.Graph()
    g.parse(data=text, format="turtle")
    owlrl.DeductiveClosure(owlrl.OWLRL_Semantics).expand(g)
    expected = _named((str(s), str(p), str(o)) for s, p, o in g)
    asserted = {(t.subject, t.predicate, t.object) for t in onto.triples(inferred=False)}
    ours = _named((_value(s), _value(p), _value(o)) for s, p, o in instantiated[0] | asserted)
    assert ours == expected


@settings(max_examples=property_examples(40), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(beyond_rl, facts)
def test_generic_equals_instantiated_beyond_owl_rl(tbox, abox) -> None:
    onto = Ontology()
    onto.load_data(PREFIXES + _declarations() + "\n" + "\n".join(tbox + abox) + "\n", "turtle")
    assert _materialize(onto, 0) == _materialize(onto, sys.maxsize)


def test_the_rows_as_terms_are_the_rows_as_text() -> None:
    """What a full REASON writes in process (terms) is what a store with round trips is sent (text)."""
    from pyoxigraph import RdfFormat, parse

    rows = {"cax-sco": [(f"<{NS}A>", f"<{NS}B>")], "cls-hv1": [(f"<{NS}R>", f"<{NS}p>", '"3.0"^^<http://www.w3.org/2001/XMLSchema#decimal>')],
            "prp-spo2": [(f"<{NS}p>", f"<{NS}q>", f"<{NS}r>")]}
    for name, table in rows.items():
        generic = schema_rules()[name]
        text = "\n".join(t for row in table for t in generic.triples(row))
        assert list(generic.triple_terms(table)) == [q.triple for q in parse(text.encode(), format=RdfFormat.N_TRIPLES)]
