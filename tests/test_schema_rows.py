"""What is a row of a file of ``rules/owl/`` (topostore.compile.schema.SchemaRule.row_of) and what is not.

A rule carrying a setting no instantiation has (its body as written, a known conclusion that makes its
asks idle) is no row: the rule set keeps it as it is, and a full REASON runs it as it is instead of the
generic rule over the table, which would drop the setting.
"""

from __future__ import annotations

from dataclasses import replace

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from test_schema_rules import PREFIXES, _c, _declarations, _i, _materialize, _p, facts

from topostore.compile.condition import test as condition_test
from topostore.compile.rule import Atom, RuleSet
from topostore.compile.schema import schema_rule
from topostore.compile.schema_program import full_program
from topostore.compile.schema_tables import hold_tables

TYPE = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>"


def _subclass_rules(n: int) -> list:
    sco = schema_rule("cax-sco")
    return [sco.instantiate((f"<urn:c{i}>", f"<urn:c{i + 1}>"), f"c{i} SubClassOf c{i + 1}") for i in range(n)]


def test_a_rule_with_settings_of_its_own_is_no_row() -> None:
    sco = schema_rule("cax-sco")
    rule = _subclass_rules(1)[0]
    assert sco.row_of(rule) == ("<urn:c0>", "<urn:c1>")
    written = rule.body + (Atom("?x", TYPE, "<urn:implied>"),)
    own = [replace(rule, written=written), replace(rule, written_conditions=(condition_test("!isLiteral(?x)"),)),
           replace(rule, unless_known=rule.head), replace(rule, value_range=("<urn:p>", "<urn:d>"))]
    assert [sco.row_of(r) for r in own] == [None] * len(own)


def test_the_rule_set_and_a_full_reason_keep_such_a_rule_as_it_is() -> None:
    """Twenty subclass rows run generically in a full REASON; the one whose body as written differs and
    the one asking only where its conclusion is unknown stay rules of their own, settings included."""
    rules = _subclass_rules(20)
    premises = rules[3].body + (Atom("?x", TYPE, "<urn:implied>"),)
    rules[3] = replace(rules[3], written=premises)
    rules[7] = replace(rules[7], unless_known=rules[7].head)
    kept, tables = hold_tables(rules)
    assert kept == [rules[3], rules[7]] and tables is not None and len(tables) == 18
    program = full_program(RuleSet(rules=kept, tables=tables), threshold=0)
    assert "cax-sco" in program.rows and ("<urn:c3>", "<urn:c4>") not in program.rows["cax-sco"]
    run = program.rules.rules
    assert [r.written for r in run if r.written] == [premises]
    assert [r.unless_known for r in run if r.unless_known is not None] == [rules[7].head]


# ---------------------------------------------------------------------- the non-memberships and one-ofs as tables
NS = "http://example.org/rows#"
COMPLEMENTS = f"""\
@prefix : <{NS}> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
:Meat owl:disjointWith :Veg . :Salami rdfs:subClassOf :Meat . :VegTopping rdfs:subClassOf :Veg .
:Veggie owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :Pizza [ owl:onProperty :top ; owl:allValuesFrom :Veg ] ) ] .
:NonVeggie owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :Pizza [ owl:complementOf :Veggie ] ) ] .
:MeatPizza rdfs:subClassOf [ owl:onProperty :top ; owl:someValuesFrom :Meat ] .
:Back owl:equivalentClass [ a owl:Restriction ; owl:onProperty [ owl:inverseOf :top ] ; owl:allValuesFrom :Veg ] .
:Front owl:equivalentClass [ a owl:Class ; owl:complementOf :Back ] .
:Shade owl:equivalentClass [ a owl:Class ; owl:oneOf ( :red :green :blue ) ] .
:p1 a :Pizza ; :top :s1 . :s1 a :Salami .
:p2 a :Pizza , :MeatPizza .
:p3 a :Pizza ; :top :v1 . :v1 a :VegTopping .
"""
NEGATION = {"neg-dw", "neg-svf", "neg-sco", "neg-int", "neg-com", "neg-avf", "cls-oo"}


def _loaded(text: str):
    import warnings

    from topostore import Ontology

    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the complement's incompleteness is named: not what is tested here
        onto.load_data(text, "turtle")
    return onto


def test_the_non_memberships_and_one_ofs_are_rows_of_their_files() -> None:
    onto = _loaded(COMPLEMENTS)
    tables = onto.rules.tables
    assert tables is not None and NEGATION <= set(tables.held)
    assert not [r for r in onto.rules.rules if r.name in NEGATION and not r.is_check and r.name != "neg-avf"]
    [inverse] = [r for r in onto.rules.rules if r.name == "neg-avf"]  # on an inverse property: no row
    assert inverse.body[0].s == "?y"
    assert len(tables.rows("cls-oo")) == 3 and tables.rows("neg-dw")


def test_the_non_membership_tables_run_generically_to_the_same_closure() -> None:
    from pyoxigraph import NamedNode

    onto = _loaded(COMPLEMENTS)
    assert NEGATION <= set(full_program(onto.rules, 0).rows)
    generic, instantiated = _materialize(onto, 0), _materialize(onto, 1 << 30)
    assert generic == instantiated
    non_veggie, shade = NamedNode(NS + "NonVeggie"), NamedNode(NS + "Shade")
    inferred = generic[0]
    typed = {(s, o) for s, p, o in inferred if p.value.endswith("#type")}
    assert {(NamedNode(NS + "p1"), non_veggie), (NamedNode(NS + "p2"), non_veggie)} <= typed
    assert (NamedNode(NS + "p3"), non_veggie) not in typed and (NamedNode(NS + "red"), shade) in typed


def test_the_rules_of_a_growing_tbox_stay_as_many() -> None:
    """The tutorial-style TBox of 100 and of 400 classes: more axioms are more rows, not more rules."""
    from benchmarks import tbox

    counts = [len(_loaded(tbox.turtle(n)).rules.rules) for n in (100, 400)]
    assert counts[0] == counts[1]


complements = st.lists(st.one_of(
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :{} [ owl:complementOf :{} ] ) ] .".format, _c, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:onProperty :{} ; owl:allValuesFrom :{} ] ] ."
              .format, _c, _p, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:onProperty [ owl:inverseOf :{} ] ; "
              "owl:allValuesFrom :{} ] ] .".format, _c, _p, _c),
    st.builds(":{} rdfs:subClassOf [ owl:onProperty :{} ; owl:someValuesFrom :{} ] .".format, _c, _p, _c),
    st.builds(":{} rdfs:subClassOf :{} .".format, _c, _c),
    st.builds(":{} owl:disjointWith :{} .".format, _c, _c),
    st.builds("[ a owl:AllDisjointClasses ; owl:members ( :{} :{} :{} ) ] .".format, _c, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:oneOf ( :{} :{} ) ] .".format, _c, _i, _i),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :{} :{} ) ] ] .".format, _c, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :{} :{} :{} ) ] ] .".format,
              _c, _c, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :{} :{} :{} :{} :{} ) ] ] .".format,
              _c, _c, _c, _c, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :{} :{} :{} :{} :{} ) ] .".format,
              _c, _c, _c, _c, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :{} :{} :{} :{} :{} :{} :{} :{} ) ] ] ."
              .format, _c, _c, _c, _c, _c, _c, _c, _c, _c),
    st.builds(":{} owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :{} :{} :{} :{} :{} :{} :{} :{} ) ] .".format,
              _c, _c, _c, _c, _c, _c, _c, _c, _c),
), max_size=10)


@settings(max_examples=property_examples(40), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(complements, facts)
def test_generic_equals_instantiated_on_generated_complements(tbox, abox) -> None:
    """The files of the non-memberships and the one-ofs over their tables reach the closure their
    instantiations reach, on generated TBoxes with complements (both compared, never owlrl: a complement
    on the left is beyond OWL 2 RL)."""
    onto = _loaded(PREFIXES + _declarations() + "\n" + "\n".join(tbox + abox) + "\n")
    assert _materialize(onto, 0) == _materialize(onto, 1 << 30)


# ---------------------------------------------------------------------- intersections: a file per width
INTERSECTIONS = f"""\
@prefix : <{NS}> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
:Two owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A :B ) ] .
:Three owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A :B :C ) ] .
:Four owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A :B :C :D ) ] .
:Five owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A :B :C :D :E ) ] .
:TwoAndThing owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A owl:Thing :E ) ] .
:Eight owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A :B :C :D :E :F :G :H ) ] .
:Nine owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A :B :C :D :E :F :G :H :I ) ] .
:x a :A , :B , :C , :D . :y a :A , :B , :C , :D , :E . :z a :A , :B , :C , :D , :E , :F , :G , :H , :I .
"""


def test_an_intersection_is_a_row_of_the_file_of_its_width() -> None:
    """cls-int1 of 2 to 8 members (owl:Thing left out) are rows of cls-int1-2 … cls-int1-8, still named
    cls-int1 (what an explanation shows); nine members keep a rule of their own."""
    onto = _loaded(INTERSECTIONS)
    tables = onto.rules.tables
    assert tables is not None
    assert [len(tables.rows(f"cls-int1-{n}")) for n in range(2, 9)] == [2, 1, 1, 1, 0, 0, 1]
    assert all(r.name == "cls-int1" for n in (2, 3, 4, 5, 8) for r in tables.held[f"cls-int1-{n}"])
    [nine] = [r for r in onto.rules.rules if r.name == "cls-int1"]
    assert len(nine.body) == 9


def test_the_intersection_files_run_generically_to_the_same_closure() -> None:
    onto = _loaded(INTERSECTIONS)
    generic = _materialize(onto, 0)
    assert generic == _materialize(onto, 1 << 30)
    typed = {(s.value.rsplit("#", 1)[-1], o.value.rsplit("#", 1)[-1]) for s, p, o in generic[0]
             if p.value.endswith("#type")}
    assert {("x", "Two"), ("x", "Three"), ("x", "Four"), ("y", "Five"), ("y", "TwoAndThing")} <= typed
    assert {("z", "Eight"), ("z", "Nine")} <= typed
    assert ("x", "Five") not in typed and ("x", "TwoAndThing") not in typed and ("y", "Eight") not in typed


def test_a_file_of_a_width_is_named_by_its_rule_and_width(tmp_path, monkeypatch) -> None:
    import pytest

    from topostore import resources
    from topostore.compile import schema
    from topostore.errors import RuleCompileError

    (tmp_path / "owl").mkdir()
    text = (resources.rules_dir() / "owl" / "cls-int1-2.rq").read_text()
    (tmp_path / "owl" / "cls-int1-3.rq").write_text(text)  # two body atoms in a file named for three
    monkeypatch.setattr(resources, "rules_dir", lambda: tmp_path)
    schema.schema_rules.cache_clear()
    try:
        with pytest.raises(RuleCompileError, match="cls-int1-2.rq"):
            schema.schema_rules()
    finally:
        monkeypatch.undo()
        schema.schema_rules.cache_clear()
        schema._by_shape.cache_clear()


# ---------------------------------------------------------------------- unions' non-memberships: a file per width
UNIONS = f"""\
@prefix : <{NS}> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
:Out owl:disjointWith :A , :B , :C , :D . :Near owl:disjointWith :A , :B , :C , :D , :E .
:Far owl:disjointWith :A , :B , :C , :D , :E , :F , :G , :H . :Beyond owl:disjointWith :A , :B , :C , :D , :E , :F , :G , :H , :I .
:NotTwo owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :A :B ) ] ] .
:NotThree owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :A :B :C ) ] ] .
:NotFour owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :A :B :C :D ) ] ] .
:NotFive owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :A :B :C :D :E ) ] ] .
:NotEight owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :A :B :C :D :E :F :G :H ) ] ] .
:NotNine owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf ( :A :B :C :D :E :F :G :H :I ) ] ] .
:x a :Out . :y a :Near . :z a :Far . :w a :Beyond .
"""


def test_a_union_s_non_membership_is_a_row_of_the_file_of_its_width() -> None:
    """neg-uni of 2 to 8 members are rows of neg-uni-2 … neg-uni-8, still named neg-uni (what an explanation
    shows); nine members keep a rule of their own."""
    onto = _loaded(UNIONS)
    tables = onto.rules.tables
    assert tables is not None
    assert [len(tables.rows(f"neg-uni-{n}")) for n in range(2, 9)] == [1, 1, 1, 1, 0, 0, 1]
    assert all(r.name == "neg-uni" for n in (2, 3, 4, 5, 8) for r in tables.held[f"neg-uni-{n}"])
    assert [len(r.body) for r in onto.rules.rules if r.name == "neg-uni"] == [9]


def test_the_union_files_run_generically_to_the_same_closure() -> None:
    onto = _loaded(UNIONS)
    assert {"neg-uni-2", "neg-uni-3", "neg-uni-4", "neg-uni-5", "neg-uni-8"} <= set(full_program(onto.rules, 0).rows)
    generic = _materialize(onto, 0)
    assert generic == _materialize(onto, 1 << 30)
    typed = {(s.value.rsplit("#", 1)[-1], o.value.rsplit("#", 1)[-1]) for s, p, o in generic[0]
             if p.value.endswith("#type")}
    assert {("x", "NotTwo"), ("x", "NotThree"), ("x", "NotFour"), ("y", "NotFive")} <= typed
    assert {("z", "NotEight"), ("w", "NotNine")} <= typed
    assert ("x", "NotFive") not in typed and ("y", "NotEight") not in typed and ("z", "NotNine") not in typed
