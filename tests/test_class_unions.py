"""One class concluded by several rules of asserted-only keys, evaluated as one union in a full
REASON's first pass (reason/class_unions.py), and the deferred asks reading asserted-only keys in the
asserted graph (reason/deferred_asks.py ``only_asserted``): the same closure as the rules one by one."""

from __future__ import annotations

import sys
import tempfile
import warnings
from pathlib import Path

import pytest
from pyoxigraph import NamedNode
from support import closure

from topostore import Ontology, OntologyWarning
from topostore.rdf.vocab import ASSERTED, AUX, INTERNAL
from topostore.reason import deferred_asks, full_passes, insert_text
from topostore.reason.class_unions import class_unions, lead_first, union_where
from topostore.reason.order import asserted_paths, evaluation_order

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the benchmarks package lives beside src/
from benchmarks import maps, tbox  # noqa: E402
from benchmarks.cardinality import PREFIXES  # noqa: E402

NS = "http://example.org/card#"
DIFFERENT_KEY_OF = NamedNode(INTERNAL + "differentKeyOf")
DOMAIN_AND_RANGE = PREFIXES + """
:p a owl:ObjectProperty ; rdfs:domain :C . :q a owl:ObjectProperty ; rdfs:range :C .
:v a owl:DatatypeProperty ; rdfs:domain :C . :C rdfs:subClassOf :D .
:a :p :b . :c :q :d . :e :v 3 .
"""


def loaded(text: str | None = None, source: str = "") -> Ontology:
    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        if source == "tbox":
            onto.load_data(tbox.turtle(60), "turtle")
        elif source == "map":
            with tempfile.TemporaryDirectory() as tmp:
                path, _ = maps.write("200", Path(tmp))
                onto.load(path)
        elif source == "example":
            from topostore.resources import default_ontology_files
            for path in default_ontology_files():
                onto.load(path)
        else:
            onto.load_data(text, "turtle")
    return onto


def names(onto: Ontology, cls: str) -> set[str]:
    return {onto.short(i) for i in onto.instances(cls)}


def test_a_domain_and_a_range_of_one_class_conclude_their_own_members() -> None:
    """The range's body holds the domain's variable (``?x``) with another meaning: renamed apart,
    the subject ``:c`` of the range is no member."""
    onto = loaded(DOMAIN_AND_RANGE)
    assert onto.reason(mode="full").consistent
    assert names(onto, "C") == {"a", "d", "e"}
    assert names(onto, "D") == {"a", "d", "e"}


def test_the_union_groups_the_rules_of_one_class_with_asserted_keys_only() -> None:
    onto = loaded(DOMAIN_AND_RANGE)
    rules = onto.rules.inference_rules
    seen: list[dict] = []
    real = full_passes.class_unions

    def spy(*args, **kwargs):
        seen.append(real(*args, **kwargs))
        return seen[-1]

    full_passes.class_unions = spy
    try:
        onto.reason(mode="full")
    finally:
        full_passes.class_unions = real
    groups = [(lead, others) for found in seen for lead, others in found.items()]
    assert len(groups) == 1
    lead, others = groups[0]
    members = [rules[i] for i in (lead, *others)]
    assert {r.writes() for r in members} == {("t", f"<{NS}C>")}
    assert len(members) == 3
    ordered_members = lead_first(rules, [lead, *others])
    assert rules[ordered_members[0]].head.s == "?x"  # the two domains lead, the range is renamed
    text = union_where([rules[i] for i in ordered_members], {})
    assert text.count(" UNION ") == 2 and "AS ?x" in text


def test_a_key_written_in_the_pass_keeps_its_rule_apart() -> None:
    """A range over a derived property (``:t``, written by its subproperty's rule) reads a key the
    pass writes: its rule is not moved to the union's place, and its member still comes."""
    text = DOMAIN_AND_RANGE + ":s rdfs:subPropertyOf :t . :t rdfs:range :C . :f :s :g ."
    onto = loaded(text)
    rules = onto.rules.inference_rules
    order = [[i] for i in range(len(rules))]
    graphs = {key: ASSERTED for r in rules for key in r.reads() if key != ("p", f"<{NS}t>")}
    unions = class_unions(rules, order, set(), graphs, ASSERTED, insert_text.distinct_pays, set())
    joined = {i for lead, others in unions.items() for i in (lead, *others)}
    assert all(("p", f"<{NS}t>") not in rules[i].reads() for i in joined)
    assert onto.reason(mode="full").consistent
    assert names(onto, "C") == {"a", "d", "e", "g"}


@pytest.mark.parametrize("source", ["example", "tbox", "map", "text"])
@pytest.mark.parametrize("shortcut", ["unions", "asserted asks"])
def test_a_full_reason_reaches_the_same_closure_with_and_without(source: str, shortcut: str,
                                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    onto = loaded(DOMAIN_AND_RANGE, "" if source == "text" else source)
    onto.reason(mode="full")
    joined = closure(onto)
    if shortcut == "unions":
        monkeypatch.setattr(full_passes, "class_unions", lambda *args, **kwargs: {})
    else:
        monkeypatch.setattr(deferred_asks, "only_asserted", lambda rule, derived, asserted, asking=(): {})
    onto.reason(mode="full")
    assert closure(onto) == joined


GROUP = (DOMAIN_AND_RANGE + "@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .\n"
         "[] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) .\n")


def _path_rules(onto: Ontology) -> set[str]:
    rules = onto.rules.inference_rules
    ordered, _, _ = evaluation_order(rules, list(range(len(rules))))  # the variable predicates' rules apart
    return {rules[i].name for i in asserted_paths(rules, [i for c in ordered for i in c])}


def test_the_list_walk_reads_the_asserted_graph_only_while_no_rule_writes_a_list_key() -> None:
    assert _path_rules(loaded(GROUP)) == {"all-different"}
    # a rule writing rdf:rest (a subproperty's) may add list cells: the walk keeps the whole dataset
    written = loaded(GROUP + ":next rdfs:subPropertyOf rdf:rest . :n1 :next :n2 .")
    assert "all-different" not in _path_rules(written)
    for onto in (loaded(GROUP), written):
        assert onto.reason(mode="full").consistent
        keys = {onto.short(t.object) for t in onto.store.triples(None, DIFFERENT_KEY_OF, None, AUX)}
        assert keys == {"a", "b", "c"}


@pytest.mark.parametrize("source", ["map", "group"])
def test_the_keys_are_the_same_with_the_walk_on_every_graph(source: str, monkeypatch: pytest.MonkeyPatch) -> None:
    onto = loaded(GROUP, "" if source == "group" else source)
    onto.reason(mode="full")
    walked = closure(onto)
    monkeypatch.setattr(full_passes, "asserted_paths", lambda rules, ordered: set())
    onto.reason(mode="full")
    assert closure(onto) == walked
