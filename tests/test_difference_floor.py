"""The hand-written floors of benchmarks.difference_floor write what the rules they stand for wrote."""

from __future__ import annotations

from pathlib import Path

import pytest
from pyoxigraph import NamedNode

from benchmarks import difference_floor as floor
from benchmarks import maps
from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, AUX, ENTAILED, ENTAILED_PREFIX, INFERRED, INTERNAL, OWL, RDF

CONNECTED = maps.MAP_NS + "connectedTo"


def _reasoned(size: str, tmp_path: Path, grouped: bool = True) -> Ontology:
    path, _ = maps.write(size, tmp_path)
    onto = Ontology()
    onto.load(path)
    if not grouped:  # every AllDifferent node with its list: no pair is declared different
        onto.store.update(f"DELETE {{ GRAPH <{ASSERTED.value}> {{ ?s ?p ?o }} }} WHERE {{ GRAPH <{ASSERTED.value}> {{ "
                          f"?g a <{OWL}AllDifferent> ; (<{OWL}distinctMembers>|<{RDF}rest>)* ?s . ?s ?p ?o }} }}")
        onto.reason(mode="full")  # the removal is a change of ordinary facts: reason it through
    assert onto.reason(mode="full").consistent
    return onto


def _pairs(onto: Ontology, predicate: str, graph: NamedNode) -> set[tuple[str, str]]:
    return {(t.subject.value, t.object.value) for t in onto.store.triples(None, NamedNode(predicate), None, graph)}


def _written_pairs(onto: Ontology, name: str) -> set[tuple[str, str]]:
    return {(s, o) for s, _, o in floor.written_by(onto, name)}


def test_each_form_of_the_conclusion_writes_the_inferred_links(tmp_path: Path) -> None:
    onto = _reasoned("200", tmp_path)
    links = _pairs(onto, CONNECTED, INFERRED)
    assert links
    for name in ("pairs", "pairs_keys", "pairs_keys_sameterm", "pairs_typed", "pairs_groups"):
        assert _written_pairs(onto, name) == links, name


def test_the_keys_are_the_rules_keys(tmp_path: Path) -> None:
    onto = _reasoned("200", tmp_path)
    keys = {(t.object.value, t.subject.value) for t in onto.store.triples(None, NamedNode(INTERNAL + "differentKeyOf"), None, AUX)}
    assert _written_pairs(onto, "keys") == keys
    assert {s for s, _ in _written_pairs(onto, "keys_typed")} == {s for s, _ in keys}


def test_the_twin_forms_write_the_twins_and_declared_pairs_ask_nothing(tmp_path: Path) -> None:
    onto = _reasoned("200", tmp_path)
    twins = _written_pairs(onto, "twin")
    assert twins and twins == _written_pairs(onto, "twin_joined") == _written_pairs(onto, "twin_values")
    assert twins <= _written_pairs(onto, "twin_candidates") == _pairs(onto, CONNECTED, INFERRED)
    # the full REASON wrote a twin only for pairs another rule asked about (Reachability's)
    assert _pairs(onto, ENTAILED_PREFIX + CONNECTED, AUX) < twins
    # every linked pair is declared different: nothing to ask of the value rules, nothing published
    assert _written_pairs(onto, "candidates_undeclared") == set() == _written_pairs(onto, "candidates_not_grouped")
    assert not _pairs(onto, CONNECTED, ENTAILED)


def test_without_a_group_every_pair_is_asked_and_published(tmp_path: Path) -> None:
    onto = _reasoned("40", tmp_path, grouped=False)
    asked = _written_pairs(onto, "twin_candidates")
    assert asked and not _pairs(onto, CONNECTED, INFERRED)
    assert _written_pairs(onto, "candidates_undeclared") == asked == _written_pairs(onto, "candidates_not_grouped")
    assert _written_pairs(onto, "twin") == _pairs(onto, CONNECTED, ENTAILED) != set()
    assert _pairs(onto, ENTAILED_PREFIX + CONNECTED, AUX) == _written_pairs(onto, "twin")
    assert asked <= _pairs(onto, INTERNAL + "valueCandidate", AUX)


@pytest.mark.parametrize("name", sorted(floor.VARIANTS))
def test_every_variant_runs_on_the_example_map(name: str, tmp_path: Path) -> None:
    onto = _reasoned("example", tmp_path)
    result = floor.measure(onto, [name], 1)[name]
    assert result["quads"] >= 0 and len(result["runs_s"]) == 1
