"""A buffered reasoner's class hierarchy is that of its last REASON until the next one (spec §2.5): QUERY CLASS
CLASS and DISJOINT CLASS CLASS answer the subclasses told now ∪ the classification Pellet made when it was last
flushed, whatever changed since (a schema triple, or a fact a hasValue restriction classifies by), across a
durable restart too; a live reasoner and the Python API answer the current one."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest
from pyoxigraph import NamedNode, Triple

from topostore import Ontology, OntologyWarning
from topostore.armor import ArmorResponse, ArmorService
from topostore.rdf.vocab import owl, rdfs

NS = "http://example.org/k#"
PREFIXES = (f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . "
            "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n")
#: ``C ≡ ∃p.{a}``, ``D ≡ ∃p.K``: C ⊑ D exactly while a is a K (Pellet classifies with the ABox's nominals)
HAS_VALUE = """:p a owl:ObjectProperty . :K a owl:Class . :a a owl:NamedIndividual .
:C a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :a ] .
:D a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :K ] ."""
#: a small hierarchy: S ⊑ A ⊑ T, B ⊑ T, X and Y to make disjoint
HIERARCHY = """:T a owl:Class . :A a owl:Class ; rdfs:subClassOf :T . :B a owl:Class ; rdfs:subClassOf :T .
:S a owl:Class ; rdfs:subClassOf :A . :X a owl:Class . :Y a owl:Class . :W a owl:Class ; rdfs:subClassOf :X , :Y .
:i a owl:NamedIndividual , :S ."""


def iri(name: str) -> NamedNode:
    return NamedNode(NS + name)


class Reference:
    """One reference loaded from a Turtle body (a buffered reasoner or a live one), asked by command."""

    def __init__(self, tmp_path: Path, body: str, buffered: bool, store: str | None = None) -> None:
        self.path = tmp_path / "o.ttl"
        self.path.write_text(PREFIXES + f"<{NS[:-1]}> a owl:Ontology .\n" + body)
        self.store = store
        self.service = ArmorService(store=store)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OntologyWarning)
            assert self("LOAD", "FILE", "", str(self.path), NS[:-1], "false", "PELLET", str(buffered).lower()).success

    def __call__(self, command: str, spec1: str = "", spec2: str = "", *args: str) -> ArmorResponse:
        reply = self.service.call({"client_name": "c", "reference_name": "ref", "command": command,
                                   "primary_command_spec": spec1, "secondary_command_spec": spec2,
                                   "args": list(args)})
        assert reply.success and reply.exit_code == 0, reply
        return reply

    def under(self, cls: str) -> list[str]:
        """QUERY CLASS CLASS ``cls`` as local names."""
        return [x[len(NS) + 1:-1] for x in self("QUERY", "CLASS", "CLASS", cls).queried_objects]

    def restart(self) -> None:
        """Close the service and open another on the same durable store."""
        self.service.close()
        self.service = ArmorService(store=self.store)


@pytest.mark.parametrize("buffered", [True, False])
def test_a_fact_a_has_value_classifies_by_waits_for_reason(tmp_path: Path, buffered: bool) -> None:
    """``a ∈ K`` puts C ≡ ∃p.{a} under D ≡ ∃p.K: a buffered reasoner sees it at the next REASON, both ways, a
    schema change made after the fact's included (Z ⊑ C: under C at once, told)."""
    ref = Reference(tmp_path, HAS_VALUE, buffered)
    assert ref.under("D") == []
    ref("ADD", "IND", "CLASS", "a", "K")
    assert ref.under("D") == ([] if buffered else ["C"])
    ref("ADD", "CLASS", "CLASS", "Z", "C")
    assert ref.under("D") == ([] if buffered else ["C", "Z"]) and ref.under("C") == ["Z"]
    ref("REASON")
    assert ref.under("D") == ["C", "Z"]
    ref("REMOVE", "IND", "CLASS", "a", "K")
    assert ref.under("D") == (["C", "Z"] if buffered else [])
    ref("REASON")
    assert ref.under("D") == []


@pytest.mark.parametrize("buffered", [True, False])
def test_disjoint_class_class_reads_the_kept_hierarchy(tmp_path: Path, buffered: bool) -> None:
    """DISJOINT CLASS CLASS makes the subclasses QUERY CLASS CLASS answers disjoint: a buffered reasoner's of its
    last REASON (C is no subclass of D until the REASON after ``a ∈ K``)."""
    ref = Reference(tmp_path, HAS_VALUE + " :E a owl:Class ; rdfs:subClassOf :D .", buffered)
    ref("ADD", "IND", "CLASS", "a", "K")
    reply = ref("DISJOINT", "CLASS", "CLASS", "D")
    assert ("1 subclass(es); no axiom added" in reply.error_description) is buffered


@pytest.mark.parametrize("buffered", [True, False])
def test_query_class_ind_bottom_reads_the_hierarchy_query_class_class_answers(tmp_path: Path, buffered: bool) -> None:
    """QUERY CLASS IND with bottom=true keeps the classes of an individual with no subclass among them as QUERY
    CLASS CLASS answers the subclasses: a buffered reasoner's of its last REASON until the next one."""
    ref = Reference(tmp_path, HAS_VALUE + " :b a owl:NamedIndividual , :K . :x a owl:NamedIndividual ; :p :a , :b .",
                    buffered)
    assert ref("QUERY", "CLASS", "IND", "x", "true").queried_objects == ["C", "D"]
    ref("ADD", "IND", "CLASS", "a", "K")
    assert ref.under("D") == ([] if buffered else ["C"])
    assert ref("QUERY", "CLASS", "IND", "x", "true").queried_objects == (["C", "D"] if buffered else ["C"])
    ref("REASON")
    assert ref.under("D") == ["C"]
    assert ref("QUERY", "CLASS", "IND", "x", "true").queried_objects == ["C"]


@pytest.mark.parametrize("buffered", [True, False])
def test_subclass_equivalent_and_disjoint_changes_wait_for_reason(tmp_path: Path, buffered: bool) -> None:
    """MAKE EQUIVALENT CLASS (A ≡ T: A leaves T's subclasses, T's others come under A), a retracted and a told
    SubClassOf, and DISJOINT CLASS (W ⊑ X ⊓ Y made unsatisfiable) change a buffered reasoner's answer at REASON."""
    ref = Reference(tmp_path, HIERARCHY, buffered)
    ref("MAKE", "EQUIVALENT", "CLASS", "A")
    ref("REMOVE", "CLASS", "CLASS", "B", "T")
    ref("ADD", "CLASS", "CLASS", "B", "S")
    ref("DISJOINT", "CLASS", "", "X", "Y")
    before = {"T": ["A", "B", "S"], "A": ["S"], "S": [], "X": ["W"]}
    after = {"T": ["B", "S", "W"], "A": ["B", "S", "W"], "S": ["B", "W"], "X": ["W"]}  # W under every class
    if buffered:
        before["S"] = ["B"]  # told now
        assert {c: ref.under(c) for c in before} == before
        assert ref("QUERY", "CLASS", "CLASS", "T").error_description == ""
    ref("REASON")
    assert {c: ref.under(c) for c in after} == after
    assert "unsatisfiable class W" in ref("QUERY", "CLASS", "CLASS", "T").error_description


@pytest.mark.parametrize("buffered", [True, False])
def test_an_unsatisfiable_class_stays_so_until_reason(tmp_path: Path, buffered: bool) -> None:
    """W ⊑ X ⊓ Y with X, Y disjoint is under every class and named; the disjointness retracted, a buffered
    reasoner still says so until the next REASON."""
    ref = Reference(tmp_path, HIERARCHY + " :X owl:disjointWith :Y .", buffered)
    assert "W" in ref.under("T") and "unsatisfiable class W" in ref("QUERY", "CLASS", "CLASS", "T").error_description
    ref.service.reference("ref").manipulate("retract", [], [Triple(iri("X"), owl("disjointWith"), iri("Y"))])
    assert ("W" in ref.under("T")) is buffered
    assert ("unsatisfiable class W" in ref("QUERY", "CLASS", "CLASS", "T").error_description) is buffered
    ref("REASON")
    assert "W" not in ref.under("T")


def test_an_inconsistent_reason_answers_told_subclasses_only(tmp_path: Path) -> None:
    """Pellet answers nothing of an inconsistent ontology: after an inconsistent REASON the told subclasses alone,
    whatever changed since, until a REASON finds it consistent again."""
    ref = Reference(tmp_path, HIERARCHY + " :X owl:disjointWith :Y . :j a :X , :Y .", True)
    assert not ref("REASON").is_consistent
    assert ref.under("T") == ["A", "B"]
    ref("REMOVE", "IND", "CLASS", "j", "Y")
    ref("ADD", "CLASS", "CLASS", "Z", "S")
    assert ref.under("T") == ["A", "B"] and ref.under("S") == ["Z"]
    assert ref("REASON").is_consistent
    assert ref.under("T") == ["A", "B", "S", "W", "Z"]


def test_a_failed_reason_keeps_the_hierarchy_of_the_last_good_one(tmp_path: Path) -> None:
    """A REASON that fails undoes every change since the last good one: its hierarchy is answered (the ontology is
    that one again), and the next change waits for a REASON as before."""
    from swrl_support import PREFIXES as RULE_PREFIXES
    from swrl_support import builtin, data, rule

    from topostore.reason.limits import ReasonLimits

    ref = Reference(tmp_path, HAS_VALUE, True)
    ref("ADD", "IND", "CLASS", "a", "K")
    ref("ADD", "CLASS", "CLASS", "Z", "C")
    onto = ref.service.reference("ref").ontology
    onto.limits = ReasonLimits(max_rounds=50, max_inferred=10_000, max_seconds=20)
    runaway = rule([data(":counter", "?x", "?v"), builtin("add", "?w", "?v", 1)], [data(":counter", "?x", "?w")])
    onto.load_data(RULE_PREFIXES + runaway + ':c1 :counter "0"^^xsd:integer .\n', "turtle")
    failed = ref.service.call({"client_name": "c", "reference_name": "ref", "command": "REASON",
                               "primary_command_spec": "", "secondary_command_spec": "", "args": []})
    assert not failed.success and "were undone" in failed.error_description
    assert ref.under("D") == [] and ref.under("C") == []
    ref("ADD", "IND", "CLASS", "a", "K")
    assert ref.under("D") == []
    ref("REASON")
    assert ref.under("D") == ["C"]


@pytest.mark.parametrize("buffered", [True, False])
def test_a_durable_reference_answers_the_same_hierarchy_after_a_restart(tmp_path: Path, buffered: bool) -> None:
    """The hierarchy of the last REASON survives a restart of a durable reference changed since (a schema change
    and a fact a hasValue classifies by), and a second one; the next REASON answers the current one."""
    ref = Reference(tmp_path, HAS_VALUE + " :E a owl:Class ; rdfs:subClassOf :D .", buffered,
                    store=str(tmp_path / "refs"))
    ref("ADD", "IND", "CLASS", "a", "K")
    ref("REMOVE", "CLASS", "CLASS", "E", "D")
    ref("ADD", "CLASS", "CLASS", "F", "E")
    expected = {"D": ["E"] if buffered else ["C"], "E": ["F"], "K": []}  # buffered: E ⊑ D kept, F ⊑ E told
    assert {c: ref.under(c) for c in expected} == expected
    ref.restart()
    assert {c: ref.under(c) for c in expected} == expected
    ref.restart()
    assert {c: ref.under(c) for c in expected} == expected
    ref("REASON")
    assert {c: ref.under(c) for c in expected} == {"D": ["C"], "E": ["F"], "K": []}


def test_a_durable_reference_reopened_reasoned_keeps_what_it_answers_then(tmp_path: Path) -> None:
    """Reopened with nothing changed since its REASON, the hierarchy it answers is the one to keep: a change made
    after the restart waits for the next REASON, across another restart too."""
    ref = Reference(tmp_path, HAS_VALUE, True, store=str(tmp_path / "refs"))
    ref.restart()
    ref("ADD", "IND", "CLASS", "a", "K")
    ref("ADD", "CLASS", "CLASS", "Z", "C")
    assert ref.under("D") == []
    ref.restart()
    assert ref.under("D") == [] and ref.under("C") == ["Z"]
    ref("REASON")
    assert ref.under("D") == ["C", "Z"]


def test_a_failed_commit_does_not_leave_an_older_hierarchy_kept(tmp_path: Path, monkeypatch) -> None:
    """The first change after a REASON writes its hierarchy; a commit of that change that fails (an I/O error)
    wrote nothing, so the next change writes it, and a restart answers that REASON's hierarchy, not an older one."""
    from topostore.stores.base import META
    from topostore.stores.oxigraph import OxigraphStore

    ref = Reference(tmp_path, HAS_VALUE + " :b a owl:NamedIndividual .", True, store=str(tmp_path / "refs"))
    ref("ADD", "IND", "CLASS", "b", "K")  # the first change after LOAD's REASON keeps LOAD's hierarchy
    ref("ADD", "IND", "CLASS", "a", "K")
    ref("REASON")
    assert ref.under("D") == ["C"]
    commit, failed = OxigraphStore._commit, []

    def failing(store, adds, removes):
        if not failed and any(q.graph_name == META for q in adds):
            failed.append(True)
            raise OSError("injected I/O error")
        return commit(store, adds, removes)

    monkeypatch.setattr(OxigraphStore, "_commit", failing)
    reply = ref.service.call({"client_name": "c", "reference_name": "ref", "command": "ADD",
                              "primary_command_spec": "IND", "secondary_command_spec": "CLASS", "args": ["b", "T"]})
    assert failed and not reply.success
    ref("REMOVE", "IND", "CLASS", "b", "K")
    assert ref.under("D") == ["C"]
    ref.restart()
    reply = ref("QUERY", "CLASS", "CLASS", "D")
    assert reply.queried_objects == [f"<{NS}C>"] and reply.error_description == ""


def test_a_store_without_the_kept_hierarchy_says_the_current_one_is_answered(tmp_path: Path) -> None:
    """A durable store that holds no hierarchy of its last REASON (written before it was kept) and was changed
    since answers the current one, and says so by name until the next REASON."""
    from topostore.armor.context import NOT_KEPT
    from topostore.armor.durable import KEPT

    ref = Reference(tmp_path, HAS_VALUE, True, store=str(tmp_path / "refs"))
    ref("ADD", "IND", "CLASS", "a", "K")
    store = ref.service.reference("ref").ontology.store
    with store.transaction():
        store.meta_set(KEPT, None)
    ref.restart()
    reply = ref("QUERY", "CLASS", "CLASS", "D")
    assert reply.queried_objects == [f"<{NS}C>"] and NOT_KEPT in reply.error_description
    ref("REASON")
    assert ref("QUERY", "CLASS", "CLASS", "D").error_description == ""


def test_the_python_api_answers_the_current_hierarchy() -> None:
    """The Python API has no buffered reasoner: a change shows at once, before any REASON."""
    o = Ontology(prefix=NS)
    o.load_data(PREFIXES + HAS_VALUE, "turtle")
    o.reason()
    assert o.subclasses("D") == set()
    o.add_type("a", "K")
    assert o.subclasses("D") == {o.iri("C")}
    o.add(Triple(iri("Z"), rdfs("subClassOf"), iri("C")))
    assert o.subclasses("D") == {o.iri("C"), o.iri("Z")}
