"""SQWRL queries (Protégé SWRLTab's sqwrl: built-ins in a rule head) load as queries, not rules:
listed, run by name through the named-query path, answered as QueryItems over what reasoning knows."""

from __future__ import annotations

import json
import warnings

import pytest
from click.testing import CliRunner
from support import DATA, armor_load

from topostore import Ontology, OntologyWarning, QueryError, QueryItem
from topostore.armor import ArmorService
from topostore.cli.group import cli
from topostore.compile.notices import SQWRL_QUERY

QUERIES = DATA / "sqwrl_queries.ttl"
NS = "http://example.org/people#"
INT = "^^http://www.w3.org/2001/XMLSchema#integer"

PREFIXES = """
@prefix : <http://example.org/people#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix swrl: <http://www.w3.org/2003/11/swrl#> .
@prefix q: <http://sqwrl.stanford.edu/ontologies/built-ins/3.4/sqwrl.owl#> .
"""


@pytest.fixture
def onto() -> Ontology:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o = Ontology.from_file(QUERIES)
    assert o.reason().consistent
    return o


def rows(items: list[QueryItem], width: int) -> list[tuple[str, ...]]:
    values = [i.value.replace(NS, "").replace(INT, "") for i in items]
    return [tuple(values[k:k + width]) for k in range(0, len(values), width)]


def test_queries_load_with_a_notice_and_are_not_rules() -> None:
    with pytest.warns(OntologyWarning, match="SQWRL query") as caught:
        o = Ontology.from_file(QUERIES)
    text = " ".join(str(w.message) for w in caught)
    assert all(name in text for name in ("ages", "people", "residents", "adult list", "age set"))
    assert sorted(o.rules.queries) == ["adult list", "ages", "people", "residents"]
    assert not any(r.name.startswith("swrl:ages") for r in o.rules.rules)  # a query concludes nothing
    assert o.reason().consistent
    aside = next(n for n in o.notices if n.subject == "age set")
    assert aside.kind == SQWRL_QUERY and "makeSet" in aside.reason


def test_select_with_order_and_column_names(onto: Ontology) -> None:
    items = onto.query("ages")
    assert [i.key for i in items[:2]] == ["person", "age"]
    assert rows(items, 2) == [("ann", "34"), ("bob", "19"), ("cid", "16")]


def test_count_over_inferred_types(onto: Ontology) -> None:
    assert rows(onto.query("people"), 1) == [("3",)]  # two of them Persons only as Students


def test_count_grouped_by_the_selected_column_ordered_by_the_count(onto: Ontology) -> None:
    assert rows(onto.query("residents"), 2) == [("genoa", "2"), ("turin", "1")]


def test_a_query_reads_what_rules_conclude(onto: Ontology) -> None:
    assert rows(onto.query("adult list"), 1) == [("ann",), ("bob",)]


def test_query_names_lists_them_beside_the_named_queries(onto: Ontology) -> None:
    names = onto.query_names()
    assert {"ages", "people", "residents", "adult list"} <= set(names)
    assert "individuals-of-class" in names  # the queries/*.rq ones stay


def test_a_query_takes_no_parameters(onto: Ontology) -> None:
    with pytest.raises(QueryError, match="takes no parameters"):
        onto.query("ages", {"x": "ann"})


def test_limit_distinct_and_difference() -> None:
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + """
        <http://example.org/people> a owl:Ontology .
        :Person a owl:Class . :livesIn a owl:ObjectProperty . :x a swrl:Variable . :y a swrl:Variable .
        :c a swrl:Variable .
        :ann a :Person ; :livesIn :genoa . :bob a :Person ; :livesIn :genoa . :cid a :Person ; :livesIn :genoa .
        [] a owl:AllDifferent ; owl:distinctMembers ( :ann :bob ) .
        [] a swrl:Imp ; rdfs:label "neighbours" ;
           swrl:body ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :livesIn ; swrl:argument1 :x ;
                         swrl:argument2 :c ]
                       [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :livesIn ; swrl:argument1 :y ;
                         swrl:argument2 :c ]
                       [ a swrl:DifferentIndividualsAtom ; swrl:argument1 :x ; swrl:argument2 :y ] ) ;
           swrl:head ( [ a swrl:BuiltinAtom ; swrl:builtin q:select ; swrl:arguments ( :x :y ) ]
                       [ a swrl:BuiltinAtom ; swrl:builtin q:orderBy ; swrl:arguments ( :x :y ) ] ) .
        [] a swrl:Imp ; rdfs:label "cities" ;
           swrl:body ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :livesIn ; swrl:argument1 :x ;
                         swrl:argument2 :c ] ) ;
           swrl:head ( [ a swrl:BuiltinAtom ; swrl:builtin q:selectDistinct ; swrl:arguments ( :c ) ]
                       [ a swrl:BuiltinAtom ; swrl:builtin q:countDistinct ; swrl:arguments ( :c ) ] ) .
        [] a swrl:Imp ; rdfs:label "first" ;
           swrl:body ( [ a swrl:ClassAtom ; swrl:classPredicate :Person ; swrl:argument1 :x ] ) ;
           swrl:head ( [ a swrl:BuiltinAtom ; swrl:builtin q:select ; swrl:arguments ( :x ) ]
                       [ a swrl:BuiltinAtom ; swrl:builtin q:orderBy ; swrl:arguments ( :x ) ]
                       [ a swrl:BuiltinAtom ; swrl:builtin q:limit ; swrl:arguments ( 2 ) ] ) .
        [] a swrl:Imp ; rdfs:label "mixed" ;
           swrl:body ( [ a swrl:ClassAtom ; swrl:classPredicate :Person ; swrl:argument1 :x ] ) ;
           swrl:head ( [ a swrl:BuiltinAtom ; swrl:builtin q:select ; swrl:arguments ( :x ) ]
                       [ a swrl:ClassAtom ; swrl:classPredicate :Person ; swrl:argument1 :x ] ) .
        """)
    assert o.reason().consistent
    # only ann and bob are known to be different (no unique name assumption)
    assert rows(o.query("neighbours"), 2) == [("ann", "bob"), ("bob", "ann")]
    assert rows(o.query("cities"), 2) == [("genoa", "1")]
    assert rows(o.query("first"), 1) == [("ann",), ("bob",)]
    mixed = next(n for n in o.notices if n.subject == "mixed")
    assert "set aside" in mixed.reason and "mixed" not in o.rules.queries


def test_cli_runs_and_lists_them() -> None:
    result = CliRunner().invoke(cli, ["query", str(QUERIES), "residents", "--format", "json"])
    assert result.exit_code == 0, result.output
    answer = json.loads(result.output[result.output.index("["):])
    assert [(r["c"].rsplit("#", 1)[-1], r["count_p"].split("^^")[0]) for r in answer] == [("genoa", "2"), ("turin", "1")]
    listed = CliRunner().invoke(cli, ["query", "--list", str(QUERIES)])
    assert "residents" in listed.output and "columns c, count_p" in listed.output


def test_armor_load_reply_names_the_queries() -> None:
    res = armor_load(ArmorService(), QUERIES, "http://example.org/people")
    assert res.success and "SQWRL query" in res.error_description and "residents" in res.error_description


def test_a_variable_bound_only_by_a_same_as_atom_ranges_over_the_aliases() -> None:
    """``D(?x) ^ sameAs(?x, ?y) -> sqwrl:select(?x, ?y)``: ?y is ?x itself and each alias (sameAs is reflexive),
    as in a rule (it was set aside with a notice, the variable "not bound by the body")."""
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + """
        <http://example.org/people> a owl:Ontology . :D a owl:Class . :x a swrl:Variable . :y a swrl:Variable .
        :a a owl:NamedIndividual , :D . :b a owl:NamedIndividual ; owl:sameAs :c . :c a owl:NamedIndividual , :D .
        :e a owl:NamedIndividual .
        [] a swrl:Imp ; rdfs:label "aliases" ;
           swrl:body ( [ a swrl:ClassAtom ; swrl:classPredicate :D ; swrl:argument1 :x ]
                       [ a swrl:SameIndividualAtom ; swrl:argument1 :x ; swrl:argument2 :y ] ) ;
           swrl:head ( [ a swrl:BuiltinAtom ; swrl:builtin q:select ; swrl:arguments ( :x :y ) ]
                       [ a swrl:BuiltinAtom ; swrl:builtin q:orderBy ; swrl:arguments ( :x :y ) ] ) .
        """)
    assert o.reason().consistent
    assert "aliases" in o.rules.queries
    assert rows(o.query("aliases"), 2) == [("a", "a"), ("b", "b"), ("b", "c"), ("c", "b"), ("c", "c")]


def test_a_chain_of_same_as_atoms_binds_each_variable_to_the_aliases() -> None:
    """``sameAs(?x, ?y) ^ sameAs(?y, ?z)``: every (x, y, z) of one individual's names, once each."""
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + """
        <http://example.org/people> a owl:Ontology . :D a owl:Class .
        :x a swrl:Variable . :y a swrl:Variable . :z a swrl:Variable .
        :a a owl:NamedIndividual , :D . :b a owl:NamedIndividual ; owl:sameAs :c . :c a owl:NamedIndividual , :D .
        [] a swrl:Imp ; rdfs:label "chain" ;
           swrl:body ( [ a swrl:ClassAtom ; swrl:classPredicate :D ; swrl:argument1 :x ]
                       [ a swrl:SameIndividualAtom ; swrl:argument1 :x ; swrl:argument2 :y ]
                       [ a swrl:SameIndividualAtom ; swrl:argument1 :y ; swrl:argument2 :z ] ) ;
           swrl:head ( [ a swrl:BuiltinAtom ; swrl:builtin q:select ; swrl:arguments ( :x :y :z ) ] ) .
        """)
    o.reason()
    names = [("a", "a", "a")] + [(x, y, z) for x in "bc" for y in "bc" for z in "bc"]
    assert sorted(rows(o.query("chain"), 3)) == names
