"""The keys with facts after a full REASON, and the consistency checks that read each key in its one
graph, answer what a scan of every quad and the checks on the whole dataset answer."""

from __future__ import annotations

import pytest
from pyoxigraph import NamedNode, Triple
from support import TBOX_OWL as TBOX

from topostore import Ontology
from topostore.compile.generic import PREFIXES
from topostore.demo.mapgen import generate
from topostore.rdf.vocab import ASSERTED, AUX, INFERRED, TYPE
from topostore.reason.consistency import GRAPHS, check_consistency, check_keys, check_text, one_graphs
from topostore.reason.present import key_graphs, with_facts
from topostore.stores import memory_store

EX = "http://example.org/present#"


def iri(name: str) -> NamedNode:
    return NamedNode(EX + name)


def test_key_graphs_names_each_graph_holding_a_key_and_none_for_a_key_without_facts() -> None:
    store = memory_store()
    store.add([Triple(iri("a"), iri("p"), iri("b")), Triple(iri("a"), TYPE, iri("C"))], ASSERTED)
    store.add([Triple(iri("a"), iri("p"), iri("c")), Triple(iri("b"), iri("q"), iri("c"))], INFERRED)
    keys = {("p", f"<{EX}p>"), ("p", f"<{EX}q>"), ("p", f"<{EX}absent>"), ("t", f"<{EX}C>"), ("t", f"<{EX}D>"),
            ("p", str(TYPE)), ("*",)}
    found = key_graphs(store, keys, [ASSERTED, INFERRED, AUX])
    assert found == {("p", f"<{EX}p>"): {ASSERTED, INFERRED}, ("p", f"<{EX}q>"): {INFERRED},
                     ("p", f"<{EX}absent>"): set(), ("t", f"<{EX}C>"): {ASSERTED}, ("t", f"<{EX}D>"): set(),
                     ("p", str(TYPE)): {ASSERTED}}
    assert with_facts(found) == ({f"<{EX}p>", f"<{EX}q>", str(TYPE)}, {f"<{EX}C>"})
    assert with_facts(found, INFERRED) == ({f"<{EX}p>", f"<{EX}q>"}, set())
    assert with_facts(key_graphs(store, keys, [ASSERTED])) == ({f"<{EX}p>", str(TYPE)}, {f"<{EX}C>"})


def test_a_key_that_is_no_iri_counts_as_held_by_every_graph() -> None:
    found = key_graphs(memory_store(), {("t", "ex:C"), ("p", "<a> <b>")}, [ASSERTED, INFERRED])
    assert found == {("t", "ex:C"): {ASSERTED, INFERRED}, ("p", "<a> <b>"): {ASSERTED, INFERRED}}


def scan(onto: Ontology, graphs: list[NamedNode]) -> tuple[set[str], set[str]]:
    """Every predicate and class with a fact in ``graphs`` (what the census was before)."""
    store = onto.store
    preds = {str(r["p"]) for r in store.query("SELECT DISTINCT ?p WHERE { ?s ?p ?o }", graphs=graphs)}
    classes = {str(r["c"]) for r in store.query(f"SELECT DISTINCT ?c WHERE {{ ?s {TYPE} ?c }}", graphs=graphs)}
    return preds, classes


def reasoned_map(n: int, seed: int) -> Ontology:
    onto = Ontology.from_file(TBOX)
    onto.add(*generate(n, seed=seed).triples(all_different=True))
    onto.reason(mode="full")
    return onto


@pytest.mark.parametrize("seed", [1, 2])
def test_the_census_after_a_full_reason_agrees_with_a_scan_on_every_key_the_rules_read(seed: int) -> None:
    onto = reasoned_map(12, seed)
    reasoner = onto._reasoner
    needed = reasoner.triggers.needed_keys() | reasoner.check_triggers.needed_keys()
    for got, graphs in ((reasoner.state.present, [ASSERTED, INFERRED, AUX]), (reasoner.state.asserted, [ASSERTED])):
        preds, classes = scan(onto, graphs)
        assert got == ({k for k in preds if ("p", k) in needed}, {k for k in classes if ("t", k) in needed})
        assert got[0] and got[1]


INCONSISTENT = f"""
@prefix : <{EX}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
:A a owl:Class . :B a owl:Class . :E a owl:Class . :F a owl:Class . :A owl:disjointWith :B . :E owl:disjointWith :F .
:Sub rdfs:subClassOf :B .
:v a owl:DatatypeProperty , owl:FunctionalProperty .
:x a :A , :Sub ; :v 1 , 2 .
:y a :A ; :v 3 .
"""


def test_checks_read_in_one_graph_find_what_checks_on_the_whole_dataset_find() -> None:
    onto = Ontology()
    onto.load_data(INCONSISTENT, "turtle")
    report = onto.reason(mode="full")
    assert not report.consistent
    store, rules = onto.store, onto.rules
    keys = key_graphs(store, check_keys(rules), GRAPHS)
    # B's members are inferred only (x via Sub), A's asserted only; E and F have none
    assert keys[("t", f"<{EX}B>")] == {INFERRED} and keys[("t", f"<{EX}A>")] == {ASSERTED}
    assert keys[("t", f"<{EX}E>")] == set()
    skipped = [c for c in rules.checks if one_graphs(c, keys) is None]
    assert skipped, "the check of E and F has no fact to read"
    whole = [sorted(str(v) for v in row) for c in rules.checks
             for row in store.query(check_text(c), graphs=GRAPHS, prefixes=PREFIXES)]
    split = [sorted(str(v) for v in row) for c in rules.checks if one_graphs(c, keys) is not None
             for row in store.query(check_text(c, one_graphs(c, keys)), graphs=GRAPHS, prefixes=PREFIXES)]
    assert sorted(whole) == sorted(split) and whole
    assert check_consistency(store, rules) == check_consistency(store, rules, keys) == report.violations


def test_a_remote_store_with_a_reference_name_answers_the_same_keys_and_graphs(oxigraph_url: str) -> None:
    """A named reference on a SPARQL server keeps its graphs under names of its own; the keys with facts,
    and what a full REASON records as asserted, are told in the engine's graph names all the same."""
    from topostore.stores import open_store

    triples = [Triple(iri("a"), iri("p"), iri("b")), Triple(iri("a"), TYPE, iri("C"))]
    keys = {("p", f"<{EX}p>"), ("t", f"<{EX}C>"), ("p", str(TYPE)), ("p", f"<{EX}absent>")}
    local, remote = memory_store(), open_store(oxigraph_url, reference="present-ref")
    for store in (local, remote):
        store.add(triples, ASSERTED)
    assert key_graphs(remote, keys, [ASSERTED, INFERRED, AUX]) == key_graphs(local, keys, [ASSERTED, INFERRED, AUX])
    assert key_graphs(remote, keys, [ASSERTED])[("p", f"<{EX}p>")] == {ASSERTED}

    states = []
    for store in (memory_store(), open_store(oxigraph_url, reference="present-map")):
        onto = Ontology(store=store)
        onto.load(TBOX)
        onto.reason(mode="full")
        states.append(onto._reasoner.state)
    assert states[1].asserted == states[0].asserted and states[0].asserted[0]
    assert states[1].present == states[0].present

