"""First-pass evaluations found early in the worker thread (topostore.reason.early_rules): the same closure and
violations as evaluating them at their turn, their solutions used only while what they read holds."""

from __future__ import annotations

import threading
from collections import Counter

import pytest
from pyoxigraph import NamedNode, RdfFormat, Store
from test_incremental import new_map

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, AUX, DIFFERENT_KEY_OF, ENTAILED, INFERRED
from topostore.reason import early_reads
from topostore.reason.early_rules import EarlyRules, construct_form
from topostore.stores.oxigraph import OxigraphStore

_DELTA = NamedNode("urn:g:delta")


def _graphs(onto) -> Counter:
    """The asserted, inferred, helper and entailed-only graphs."""
    return Counter((g, t) for g in (ASSERTED, INFERRED, AUX, ENTAILED) for t in onto.store.triples(graph=g))


def _used(monkeypatch) -> list[tuple[str, bool]]:
    """(rule name, whether its early solutions were written) of every evaluation of the runs that follow."""
    log: list[tuple[str, bool]] = []
    evaluated = EarlyRules.evaluated

    def logged(self, i, text):
        found = evaluated(self, i, text)
        log.append((self.run.rules[i].name, found is not None))
        return found

    monkeypatch.setattr(EarlyRules, "evaluated", logged)
    return log


def test_construct_form_of_an_evaluation_text():
    text = ("INSERT { GRAPH <g:aux> { ?k <p:key> ?x } }\nUSING <g:a> USING NAMED <g:aux> USING NAMED <urn:g:delta>\n"
            "WHERE {\n  ?x <p:p> ?y BIND(IRI(STR(?y)) AS ?k)\n}")
    query, graph = construct_form(text, _DELTA)
    assert graph == NamedNode("g:aux")
    assert query == ("CONSTRUCT { ?k <p:key> ?x }\nFROM <g:a> FROM NAMED <g:aux>\n"
                     "WHERE {\n  ?x <p:p> ?y BIND(IRI(STR(?y)) AS ?k)\n}")
    two = text.replace("{ GRAPH <g:aux> { ?k <p:key> ?x } }", "{ GRAPH <g:aux> { ?k <p:key> ?x } GRAPH <g:n> { ?k <p:key> ?x } }")
    assert construct_form(two, _DELTA) is None
    assert construct_form(text.replace("?x <p:p> ?y", "GRAPH <urn:g:delta> { ?x <p:p> ?y }"), _DELTA) is None


@pytest.mark.parametrize("method", ["add_ntriples", "add_ntriples_beside"])
@pytest.mark.parametrize("durable", [False, True])
def test_a_store_adds_a_query_serialisation(tmp_path, durable, method):
    source = Store()
    source.update('INSERT DATA { <s:a> <p:p> "1"^^<http://www.w3.org/2001/XMLSchema#integer> , <s:b> , "x"@en }')
    text = source.query("CONSTRUCT { ?s ?p ?o } WHERE { ?s ?p ?o }").serialize(format=RdfFormat.N_TRIPLES)
    store = OxigraphStore(tmp_path / "db" if durable else None)
    graph = NamedNode("urn:g:target")
    getattr(store, method)(text, graph)
    assert {(str(t.subject), str(t.object)) for t in store.triples(graph=graph)} == {
        (str(q.subject), str(q.object)) for q in source}
    store.close()


def test_the_keys_and_the_count_found_early_give_the_closure_of_a_sequential_run(monkeypatch):
    log = _used(monkeypatch)
    early = new_map(12, 3, True)
    found = early.reason(mode="full")
    # the keys hash, the minimum of two doors counts per group; Urgency's arithmetic and the joins stay in the pass
    assert {n for n, used in log if used} == {"all-different", "ext-min-card"}
    monkeypatch.setattr(early_reads, "ENABLED", False)
    log.clear()
    late = new_map(12, 3, True)
    sequential = late.reason(mode="full")
    assert not log
    assert _graphs(early) == _graphs(late)
    assert sorted(map(str, found.violations)) == sorted(map(str, sequential.violations))
    assert found.stats.derived == sequential.stats.derived


def test_an_early_evaluation_is_dropped_once_a_key_it_reads_is_written(monkeypatch):
    after = EarlyRules.after
    dropped = []

    def after_then_write(self, c):
        after(self, c)
        for i in list(self._started):
            self.wrote(("p", "<http://www.w3.org/1999/02/22-rdf-syntax-ns#first>"))  # as if a rule wrote list cells
            dropped.append(self.run.rules[i].name)

    monkeypatch.setattr(EarlyRules, "after", after_then_write)
    log = _used(monkeypatch)
    onto = new_map(12, 3, True)
    before = set(threading.enumerate())
    onto.reason(mode="full")
    assert "all-different" in dropped and ("all-different", False) in log and ("all-different", True) not in log
    assert set(threading.enumerate()) == before
    monkeypatch.setattr(early_reads, "ENABLED", False)
    late = new_map(12, 3, True)
    late.reason(mode="full")
    assert _graphs(onto) == _graphs(late)


_LIST = """@prefix : <http://example.org/o#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
@prefix swrl: <http://www.w3.org/2003/11/swrl#> .
@prefix var: <http://example.org/o/var#> .
:tail a owl:ObjectProperty .
:g a owl:AllDifferent ; owl:distinctMembers :l1 .
:l1 rdf:first :a ; :tail :l2 .
:l2 rdf:first :b ; rdf:rest rdf:nil .
var:x a swrl:Variable . var:y a swrl:Variable .
[ a swrl:Imp ;
  swrl:body ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :tail ; swrl:argument1 var:x ; swrl:argument2 var:y ] ) ;
  swrl:head ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate rdf:rest ; swrl:argument1 var:x ; swrl:argument2 var:y ] ) ] .
"""


def _keys_of_list(tmp_path, name: str) -> tuple[Ontology, set[str]]:
    path = tmp_path / name
    path.write_text(_LIST)
    onto = Ontology()
    onto.load(path)
    onto.reason(mode="full")
    return onto, {str(t.object) for t in onto.store.triples(p=DIFFERENT_KEY_OF, graph=AUX)}


def test_a_rule_writing_the_list_is_waited_for(tmp_path, monkeypatch):
    """A user rule writes ``rdf:rest``: the keys are evaluated (early or not) only once it is done."""
    started: list[tuple[int, str]] = []
    after = EarlyRules.after

    def logged_after(self, c):
        names = [self.run.rules[i].name for i in self._after.get(c, ())]
        after(self, c)
        started.extend((c, n) for n in names)

    monkeypatch.setattr(EarlyRules, "after", logged_after)
    early, keys = _keys_of_list(tmp_path, "early.ttl")
    assert keys == {"<http://example.org/o#a>", "<http://example.org/o#b>"}  # :b only through the derived rdf:rest
    assert all(c >= 0 for c, n in started if n == "all-different")
    monkeypatch.setattr(early_reads, "ENABLED", False)
    late, late_keys = _keys_of_list(tmp_path, "late.ttl")
    assert late_keys == keys and _named(early) == _named(late)


def _named(onto) -> Counter:
    """The graphs of :func:`_graphs` less the facts of a blank node (named anew by each load)."""
    return Counter((g, t) for g, t in _graphs(onto) if "bnode" not in str(t))


def test_an_evaluation_with_negation_is_not_started_early():
    """Facts found early stay in the store: only a WHERE whose matches survive more data is started early."""
    text = ("INSERT { GRAPH <g:aux> { ?k <p:key> ?x } }\nUSING <g:a> USING NAMED <g:aux>\n"
            "WHERE {\n  ?x <p:p> ?y BIND(IRI(STR(?y)) AS ?k) %s\n}")
    assert construct_form(text % "", _DELTA) is not None
    for negation in ("MINUS { ?x <p:q> ?y }", "FILTER NOT EXISTS { ?x <p:q> ?y }", "OPTIONAL { ?x <p:q> ?z }"):
        assert construct_form(text % negation, _DELTA) is None


def test_the_worker_writes_what_it_found(monkeypatch):
    """The keys and the count are loaded by the worker thread: the main thread neither evaluates nor parses them."""
    writers: list[tuple[str, NamedNode]] = []
    beside = OxigraphStore.add_ntriples_beside

    def logged(self, text, graph):
        writers.append((threading.current_thread().name, graph))
        beside(self, text, graph)

    monkeypatch.setattr(OxigraphStore, "add_ntriples_beside", logged)
    log = _used(monkeypatch)
    onto = new_map(12, 3, True)
    onto.reason(mode="full")
    assert len(writers) == len([n for n, used in log if used]) == 2
    assert all(name != threading.main_thread().name for name, _ in writers)
    # the keys go to the helper graph; the minimum's count concludes CORRIDOR itself (compile/fold.py)
    assert sorted(str(graph) for _, graph in writers) == sorted([str(AUX), str(INFERRED)])


def test_a_component_the_worker_takes_moves_after_those_not_reading_it(monkeypatch):
    """The count (ext-min-card, concluding CORRIDOR) is evaluated after Connectability, which does not read
    it: the main thread has the join to do while the worker counts; its readers (CORRIDOR's copies into
    ROOM and LOCATION) move with it and still follow it."""
    orders: list[list[str]] = []
    init = EarlyRules.__init__

    def logged(self, run, ordered, back, reader):
        init(self, run, ordered, back, reader)
        orders.append([f"{run.rules[i].name} {run.rules[i].writes()[1]}" for component in ordered for i in component])

    monkeypatch.setattr(EarlyRules, "__init__", logged)
    new_map(12, 3, True).reason(mode="full")
    names = orders[-1]

    def at(name: str, writes: str) -> int:
        return next(n for n, text in enumerate(names) if text.startswith(name + " ") and writes in text)

    assert at("all-different", "") < at("swrl:Connectability", "connectedTo") < at("ext-min-card", "")
    assert at("ext-min-card", "") < at("ext-card-sub", "ROOM")


def test_an_early_write_that_no_longer_holds_keeps_the_closure(monkeypatch):
    """An early evaluation already written by the worker, then dropped (a key it reads written since): the
    pass evaluates it at its turn, and the closure is the sequential one (the early facts held anyway)."""
    after = EarlyRules.after
    dropped = []

    def after_then_write(self, c):
        after(self, c)
        for i in list(self._started):
            if self.run.rules[i].name == "ext-min-card":
                self._started[i][1].result()  # written by the worker
                self.wrote(("p", "<http://bnc/exp-rob-lab/2022-23#hasDoor>"))  # as if a rule wrote doors
                dropped.append(i)

    monkeypatch.setattr(EarlyRules, "after", after_then_write)
    log = _used(monkeypatch)
    onto = new_map(12, 3, True)
    found = onto.reason(mode="full")
    assert dropped and ("ext-min-card", False) in log and ("all-different", True) in log
    monkeypatch.setattr(early_reads, "ENABLED", False)
    late = new_map(12, 3, True)
    sequential = late.reason(mode="full")
    assert _graphs(onto) == _graphs(late)
    assert sorted(map(str, found.violations)) == sorted(map(str, sequential.violations))
