"""compile/: the rule value, the generic rule files, swrlb built-ins, shared SPARQL fragments, and what
compile_ontology makes of small TBoxes and SWRL rules — each checked by its structure or by running the SPARQL it
writes, without reasoning."""

from __future__ import annotations

from pathlib import Path

import pytest
from pyoxigraph import NamedNode, QuerySolutions
from pyoxigraph import Store as OxStore

from topostore import Ontology
from topostore.compile import Atom, Rule, RuleSet, compile_ontology
from topostore.compile.builtins import SUPPORTED, translate
from topostore.compile.generic import expand, generic_rules, parse_rule_file
from topostore.compile.key_form import one_list_rule
from topostore.compile.snippets import distinct_values, in_datatype
from topostore.compile.swrl_text import removal_triples, rule_labels, rule_triples, rules_among
from topostore.errors import RuleCompileError
from topostore.rdf.vocab import ASSERTED, SWRLB, XSD

NS = "http://e.org/t#"
TYPE = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>"
PREFIXES = f"""\
@prefix : <{NS}> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://e.org/t> a owl:Ontology .
"""


def n(local: str) -> str:
    return f"<{NS}{local}>"


def evaluate(expression: str, **values: str) -> list[str | None]:
    """Values of ``?r`` when ``expression`` is BIND to it, with the given variables bound (SPARQL text)."""
    names = " ".join(f"?{k}" for k in values)
    row = " ".join(values.values())
    query = f"PREFIX xsd: <{XSD}> SELECT ?r WHERE {{ VALUES ({names}) {{ ({row}) }} BIND({expression} AS ?r) }}"
    solutions = OxStore().query(query)
    assert isinstance(solutions, QuerySolutions)
    return [None if s["r"] is None else s["r"].value for s in solutions]


def holds(expression: str, **values: str) -> bool:
    """Whether ``FILTER(expression)`` keeps the row with the given bindings."""
    names = " ".join(f"?{k}" for k in values)
    row = " ".join(values.values())
    return bool(OxStore().query(f"PREFIX xsd: <{XSD}> ASK {{ VALUES ({names}) {{ ({row}) }} FILTER({expression}) }}"))


def compiled(turtle: str) -> tuple[Ontology, RuleSet]:
    onto = Ontology()
    onto.load_data(PREFIXES + turtle, "turtle")
    return onto, compile_ontology(onto.store, ASSERTED)


def own_rules(rules: RuleSet) -> dict[str, list[Rule]]:
    """The rules compiled from the ontology (not the generic ones), by name."""
    generic = {(r.name, r.origin) for r in (*generic_rules(), one_list_rule())}
    out: dict[str, list[Rule]] = {}
    for r in rules.all_rules:
        if (r.name, r.origin) not in generic:
            out.setdefault(r.name, []).append(r)
    return out


# ---------------------------------------------------------------- the Rule value

def test_atom_read_keys_and_variables() -> None:
    assert Atom("?x", TYPE, n("ROOM")).read_key() == ("t", n("ROOM"))
    assert Atom("?x", TYPE, "?c").read_key() == ("p", TYPE)
    assert Atom("?x", n("hasDoor"), "?d").read_key() == ("p", n("hasDoor"))
    assert Atom("?x", "?p", "?o").read_key() == ("*",)
    assert Atom("?x", n("hasDoor"), n("D1")).variables() == {"?x"}
    assert Atom("?x", n("hasDoor"), "?d").text() == f"?x {n('hasDoor')} ?d ."


def test_join_order_starts_from_the_given_atom_and_never_joins_unconnected_atoms() -> None:
    """Each atom after the first shares a variable with what is bound before it: no cross product of extensions."""
    from topostore.compile.rule import join_order

    atoms = (Atom("?l", TYPE, n("LOCATION")), Atom("?r", n("isIn"), "?l"), Atom("?r", TYPE, n("ROBOT")),
             Atom("?l", n("visitedAt"), "?t"))
    for first, bound in ((None, set()), (2, set()), (3, set()), (None, {"?l"})):
        order = join_order(atoms, first, bound)
        assert sorted(order) == [0, 1, 2, 3]
        if first is not None:
            assert order[0] == first
        seen = set(bound) | atoms[order[0]].variables()
        for k in order[1:]:
            assert atoms[k].variables() & seen, (first, bound, order)
            seen |= atoms[k].variables()
    assert join_order(atoms, bound={"?l"})[0] == 0  # with ?l bound, checking its class costs nothing


def test_rule_reads_writes_and_kind() -> None:
    body = (Atom("?x", n("hasDoor"), "?d"),)
    rule = Rule("prp-dom", "test", body, Atom("?x", TYPE, n("LOCATION")), filter_reads=frozenset({("p", n("now"))}))
    check = Rule("cax-dw", "test", (Atom("?x", TYPE, n("A")), Atom("?x", TYPE, n("B"))), violation=("?x",))
    assert (rule.is_check, check.is_check) == (False, True)
    assert rule.reads() == {("p", n("hasDoor")), ("p", n("now"))}
    assert rule.writes() == ("t", n("LOCATION")) and check.writes() is None
    assert rule.head_aux() is False
    assert Rule("x", "t", body, Atom("?x", "<urn:topostore:different>", "?d")).head_aux() is True
    rules = RuleSet()
    rules.add([rule, check, rule])
    assert rules.rules == [rule, check]  # a rule added twice is kept once
    assert (rules.inference_rules, rules.checks) == ([rule], [check])


# ---------------------------------------------------------------- generic rule files

def test_expand_prefixed_names() -> None:
    assert expand("owl:sameAs") == "<http://www.w3.org/2002/07/owl#sameAs>"
    assert expand("ts:graph:aux") == "<urn:topostore:graph:aux>"
    assert [expand(t) for t in ("?x", "<urn:a>", '"a:b"', "plain", "ex:unknown")] == [
        "?x", "<urn:a>", '"a:b"', "plain", "ex:unknown"]


def test_parse_rule_file(tmp_path: Path) -> None:
    path = tmp_path / "r.rq"
    path.write_text("# name: eq-test\n# origin: a test\n# reads: p owl:sameAs\n# head-graph: aux\n"
                    "CONSTRUCT { ?y owl:sameAs ?x . }\nWHERE {\n  ?x owl:sameAs ?y .\n"
                    "  GRAPH ts:graph:aux { ?x ts:different ?y . }\n  FILTER(!sameTerm(?x, ?y))\n}\n")
    rule = parse_rule_file(path)
    same = "<http://www.w3.org/2002/07/owl#sameAs>"
    assert (rule.name, rule.origin, rule.head) == ("eq-test", "a test", Atom("?y", same, "?x"))
    assert rule.body == (Atom("?x", same, "?y"), Atom("?x", "<urn:topostore:different>", "?y", aux=True))
    assert rule.head_aux() is True and rule.is_check is False
    assert rule.reads() == {("p", same), ("p", "<urn:topostore:different>")}
    check = tmp_path / "c.rq"
    check.write_text("# name: c\n# message: {x} is odd\nSELECT ?x WHERE {\n  ?x a ?y .\n}\n")
    assert (parse_rule_file(check).violation, parse_rule_file(check).message) == (("?x",), "{x} is odd")
    bad = tmp_path / "bad.rq"
    bad.write_text("CONSTRUCT { ?x ?p ?o } WHERE { ?x ?p ?o }")
    with pytest.raises(RuleCompileError, match="needs a '# name:' header"):
        parse_rule_file(bad)


def test_generic_rules_are_the_rule_files() -> None:
    names = sorted({r.name for r in generic_rules()})
    assert names == ["all-different", "different", "different-candidate", "different-self", "eq-diff-self", "eq-diff1",
                     "eq-rep-o",
                     "eq-rep-s", "eq-sym", "eq-trans", "prp-npa1", "prp-npa2"]
    assert len(generic_rules()) == len(list((Path(__file__).parents[1] / "rules").glob("*.rq")))


# ---------------------------------------------------------------- swrlb built-ins

@pytest.mark.parametrize("name,args,expected", [
    ("add", ["?a", "?b"], "10"), ("subtract", ["?a", "?b"], "4"), ("multiply", ["?a", "?b"], "21"),
    ("integerDivide", ["?n", "?b"], "-2"),  # truncated towards zero, as Java does
    ("mod", ["?n", "?b"], "-1"), ("pow", ["?b", "3"], "27"), ("pow", ["?b", "0"], "1"),
    ("abs", ["?n"], "7"), ("unaryMinus", ["?a"], "-7"), ("stringConcat", ["?a", "?b"], "73"),
    ("stringLength", ['"robot"'], "5"), ("upperCase", ['"r1"'], "R1"), ("substring", ['"corridor"', "1", "3"], "cor"),
])
def test_arithmetic_and_string_built_ins_bind_their_result(name: str, args: list[str], expected: str) -> None:
    bound = {"?a", "?b", "?n"}
    condition = translate(SWRLB + name, ["?r", *args], bound)
    assert (condition.kind, condition.binds) == ("bind", "?r")
    assert evaluate(condition.expression, a="7", b="3", n="-7") == [expected]


def test_a_bound_result_is_compared_and_comparisons_filter() -> None:
    condition = translate(SWRLB + "subtract", ["?r", "?a", "?b"], {"?r", "?a", "?b"})
    assert (condition.kind, condition.binds) == ("test", None)
    assert holds(condition.expression, r="4", a="7", b="3") is True
    assert holds(condition.expression, r="5", a="7", b="3") is False
    greater = translate(SWRLB + "greaterThan", ["?a", "?b"], {"?a", "?b"}).expression
    assert holds(greater, a="8", b="7") and not holds(greater, a="7", b="7")
    equal = translate(SWRLB + "equal", ["?x", "5"], set())
    assert (equal.kind, equal.expression, equal.binds) == ("bind", "5", "?x")
    assert holds(translate(SWRLB + "containsIgnoreCase", ['"Corridor"', '"DOR"'], set()).expression) is True


def test_built_ins_wait_for_their_inputs_and_refuse_bad_calls() -> None:
    assert translate(SWRLB + "add", ["?r", "?a", "?b"], {"?a"}) is None  # ?b not bound yet
    assert translate(SWRLB + "lessThan", ["?a", "?b"], {"?a"}) is None
    with pytest.raises(RuleCompileError, match="unsupported built-in .*#sqrt"):
        translate(SWRLB + "sqrt", ["?r", "?a"], {"?a"})
    with pytest.raises(RuleCompileError, match="swrlb:lessThan takes 2 arguments, got 3"):
        translate(SWRLB + "lessThan", ["?a", "?b", "?c"], {"?a", "?b", "?c"})
    with pytest.raises(RuleCompileError, match="swrlb:subtract takes a result and 2..2 arguments, got 2 in all"):
        translate(SWRLB + "subtract", ["?r", "?a"], {"?a"})
    assert SUPPORTED == [
        "abs", "add", "ceiling", "contains", "containsIgnoreCase", "date", "dateTime", "divide", "endsWith", "equal", "floor",
        "greaterThan", "greaterThanOrEqual", "integerDivide", "lessThan", "lessThanOrEqual", "lowerCase", "matches",
        "mod", "multiply", "notEqual", "pow", "round", "startsWith", "stringConcat", "stringLength", "substring",
        "subtract", "time", "unaryMinus", "unaryPlus", "upperCase"]


# ---------------------------------------------------------------- shared SPARQL fragments

@pytest.mark.parametrize("datatype,value,inside", [
    ("long", '"5"^^xsd:long', True), ("long", "5", True), ("long", '"5.0"^^xsd:decimal', True),
    ("long", '"5.5"^^xsd:decimal', False), ("long", '"9223372036854775808"^^xsd:integer', False),
    ("long", '"5"', False), ("long", "<urn:x>", False), ("byte", "-129", False), ("byte", "-128", True),
    ("nonNegativeInteger", "-1", False), ("decimal", "1.5", True), ("decimal", '"1.5"^^xsd:double', False),
    ("string", '"x"', True), ("string", '"x"@en', False), ("double", '"1.5"^^xsd:double', True),
    ("double", "1.5", False), ("boolean", "true", True),
])
def test_in_datatype(datatype: str, value: str, inside: bool) -> None:
    expression = in_datatype("?v", NamedNode(XSD + datatype))
    assert expression is not None
    query_value = value
    for local in ("long", "decimal", "integer", "double"):
        query_value = query_value.replace(f"^^xsd:{local}", f"^^<{XSD}{local}>")
    assert holds(expression, v=query_value) is inside


def test_in_datatype_is_none_for_unchecked_datatypes() -> None:
    assert in_datatype("?v", NamedNode("http://example.org/myType")) is None


@pytest.mark.parametrize("a,b,distinct", [("1", "1", False), ("1", "1.0", False), ("1", "2", True), ('"1"', "1", True),
                                          ("<urn:a>", "<urn:b>", True), ("<urn:a>", "<urn:a>", False)])
def test_distinct_values(a: str, b: str, distinct: bool) -> None:
    assert holds(distinct_values("?a", "?b"), a=a, b=b) is distinct


# ---------------------------------------------------------------- OWL axioms → rules

TBOX = """
:p a owl:ObjectProperty ; rdfs:domain :C ; rdfs:range :D .
:A rdfs:subClassOf :B .
:B owl:disjointWith :C .
:v a owl:DatatypeProperty , owl:FunctionalProperty .
"""


def test_compile_ontology_names_the_schema_and_compiles_each_axiom() -> None:
    _, rules = compiled(TBOX)
    assert sorted(c.value for c in rules.named_classes) == [NS + c for c in "ABCD"]
    assert (rules.object_properties, rules.data_properties) == ({NamedNode(NS + "p")}, {NamedNode(NS + "v")})
    own = own_rules(rules)
    assert sorted(own) == ["cax-dw", "cax-sco", "cls-nothing2", "different-disjoint", "different-values", "prp-dom",
                           "prp-fp", "prp-rng"]
    [sco] = own["cax-sco"]
    assert (sco.body, sco.head) == ((Atom("?x", TYPE, n("A")),), Atom("?x", TYPE, n("B")))
    [dom], [rng] = own["prp-dom"], own["prp-rng"]
    assert (dom.body, dom.head) == ((Atom("?x", n("p"), "?y"),), Atom("?x", TYPE, n("C")))
    assert (rng.body, rng.head) == ((Atom("?x", n("p"), "?y"),), Atom("?y", TYPE, n("D")))
    [dw] = own["cax-dw"]
    assert dw.is_check and set(dw.body) == {Atom("?x", TYPE, n("B")), Atom("?x", TYPE, n("C"))}
    [fp] = own["prp-fp"]
    assert fp.is_check and set(fp.body) == {Atom("?x", n("v"), "?y1"), Atom("?x", n("v"), "?y2")}
    assert len(own["different-disjoint"]) == 2  # B-then-C and C-then-B


def test_an_existential_restriction_becomes_an_anonymous_class() -> None:
    _, rules = compiled(":p a owl:ObjectProperty . :E owl:equivalentClass [ a owl:Restriction ; "
                        "owl:onProperty :p ; owl:someValuesFrom :D ] .")
    own = own_rules(rules)
    # E stands for its equivalent expression (compile/fold.py): the rule of the restriction concludes E;
    # the way back from the anonymous class stays for a membership of it told in the data
    assert sorted(own) == ["cax-eqc2", "cls-nothing2", "cls-svf1"]
    [svf], [eqc2] = own["cls-svf1"], own["cax-eqc2"]
    anonymous = eqc2.body[0].o  # the restriction's class, an IRI of the helper vocabulary
    assert anonymous.startswith("<urn:topostore:bnode:")
    assert svf.body == (Atom("?x", n("p"), "?y1"), Atom("?y1", TYPE, n("D")))
    assert svf.head == Atom("?x", TYPE, n("E"))
    assert eqc2.head == Atom("?x", TYPE, n("E"))
    assert svf.head_aux() is False and eqc2.head_aux() is False


# ---------------------------------------------------------------- SWRL rules (human syntax → RDF → rules)

SWRL_TBOX = """
:LOCATION a owl:Class . :URGENT a owl:Class .
:visitedAt a owl:DatatypeProperty . :now a owl:DatatypeProperty . :isIn a owl:ObjectProperty .
"""


def test_swrl_text_becomes_standard_rdf_and_one_rule() -> None:
    onto, _ = compiled(SWRL_TBOX)
    text = "LOCATION(?l) ^ visitedAt(?l, ?t) ^ isIn(?r, ?l) ^ now(?r, ?n) ^ swrlb:subtract(?d, ?n, ?t) " \
           "^ swrlb:greaterThan(?d, 7) -> URGENT(?l)"
    triples = rule_triples(text, "Late", onto.store, NS)
    kinds = sorted(t.object.value.rsplit("#", 1)[1] for t in triples if t.predicate.value.endswith("#type")
                   and t.object.value.startswith("http://www.w3.org/2003/11/swrl#"))
    # one list cell per atom (6 in the body, 1 in the head), one swrl:Variable per variable
    assert kinds == ["AtomList"] * 7 + ["BuiltinAtom"] * 2 + ["ClassAtom"] * 2 + ["DatavaluedPropertyAtom"] * 2 + [
        "Imp", "IndividualPropertyAtom"] + ["Variable"] * 5
    onto.store.add(triples, ASSERTED)
    assert rule_labels(onto.store) == ["Late"]
    [rule] = own_rules(compile_ontology(onto.store, ASSERTED))["swrl:Late"]
    assert rule.head == Atom("?l", TYPE, n("URGENT"))
    assert set(rule.body) == {Atom("?l", TYPE, n("LOCATION")), Atom("?l", n("visitedAt"), "?t"),
                              Atom("?r", n("isIn"), "?l"), Atom("?r", n("now"), "?n")}
    assert rule.reads() == {("t", n("LOCATION")), ("p", n("visitedAt")), ("p", n("isIn")), ("p", n("now"))}
    assert set(removal_triples(onto.store, "Late")) == set(triples)  # removing the rule takes exactly its triples


@pytest.mark.parametrize("text,message", [
    ("LOCATION(?l) -> ", "expected"),
    ("KITCHEN(?l) -> URGENT(?l)", "KITCHEN"),
    ("LOCATION(?l) -> URGENT(?x)", "?x"),
    ("LOCATION(?l) ^ swrlb:sqrt(?r, ?l) -> URGENT(?l)", "sqrt"),
    ("LOCATION(?l) -> ex:URGENT(?l)", "unknown prefix 'ex'"),
])
def test_rules_that_cannot_compile_are_refused_naming_the_problem(text: str, message: str) -> None:
    """A rule the caller adds (``refuse``) is refused, not set aside."""
    onto, _ = compiled(SWRL_TBOX)
    with pytest.raises(RuleCompileError, match=message.replace("?", r"\?").replace("(", r"\(")):
        triples = rule_triples(text, "Bad", onto.store, NS)
        onto.store.add(triples, ASSERTED)
        compile_ontology(onto.store, ASSERTED, refuse=rules_among(triples))


def test_a_rule_that_cannot_compile_is_set_aside_unless_refused() -> None:
    onto, _ = compiled(SWRL_TBOX)
    onto.store.add(rule_triples("LOCATION(?l) ^ swrlb:sqrt(?r, ?l) -> URGENT(?l)", "Bad", onto.store, NS), ASSERTED)
    (notice,) = [n for n in compile_ontology(onto.store, ASSERTED).notices if n.subject == "Bad"]
    assert notice.incomplete and "sqrt" in notice.reason and "SWRL rule set aside" in str(notice)


def test_rule_labels_must_be_given_and_unique() -> None:
    onto, _ = compiled(SWRL_TBOX)
    with pytest.raises(RuleCompileError, match="needs a non-empty label"):
        rule_triples("LOCATION(?l) -> URGENT(?l)", " ", onto.store, NS)
    onto.store.add(rule_triples("LOCATION(?l) -> URGENT(?l)", "All", onto.store, NS), ASSERTED)
    with pytest.raises(RuleCompileError, match="labelled 'All' already exists"):
        rule_triples("LOCATION(?l) -> URGENT(?l)", "All", onto.store, NS)
    with pytest.raises(RuleCompileError, match=r"no SWRL rule labelled 'None' \(rules: All\)"):
        removal_triples(onto.store, "None")
