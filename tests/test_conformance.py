"""The W3C OWL 2 test cases of the RL profile: topostore passes every check owlrl (the OWL 2 RL
peer) passes, with no crash and no timeout (the whole collection: ``make conformance``)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the benchmarks package lives beside src/

from benchmarks import conformance  # noqa: E402
from benchmarks.conformance_case import entailment_tests, parse  # noqa: E402

pytestmark = pytest.mark.skipif(importlib.util.find_spec("owlrl") is None, reason="owlrl (the peer) is a test extra")


@pytest.mark.skipif(not conformance.CASES.is_file(), reason=f"no OWL 2 test cases at {conformance.CASES}")
def test_rl_cases_topostore_passes_what_owlrl_passes() -> None:
    cases, _ = conformance.read_cases()
    rl = [c for c in cases if c.category == "RL"]
    assert len(rl) > 50
    conformance.run_all(rl, timeout=60, jobs=2, progress=False)
    missing = [f"{c.id} {check}: {c.results['topostore'].get(check)}" for c in rl for check in c.checks
               if c.results["owlrl"].get(check) is True and c.results["topostore"].get(check) is not True]
    assert missing == []
    broken = [f"{c.id}: {v}" for c in rl for v in c.results["topostore"].values()
              if isinstance(v, str) and v.startswith(("timeout", "crash"))]
    assert broken == []
    for (category, check), cell in conformance.tally(rl).items():
        assert cell["topostore"] >= cell["owlrl"], (category, check, cell)


def test_a_case_that_hangs_or_kills_its_child_answers_alone(tmp_path: Path) -> None:
    """A batch child that times out or dies answers that for its case only; a new child takes the rest."""
    cases = [conformance.Case(f"c{k}", "RL", "Approved", ["consistency"], "<rdf:RDF/>") for k in range(3)]
    conformance.run_batch(cases, "no-such-engine", tmp_path, timeout=60)  # the child dies on each case
    assert all(c.results["no-such-engine"]["consistency"].startswith("crash (exit 1)") for c in cases)
    slow = [conformance.Case(f"s{k}", "RL", "Approved", ["consistency"], "<rdf:RDF/>") for k in range(2)]
    conformance.run_batch(slow, "topostore", tmp_path, timeout=0.001)  # no child answers that fast
    assert [c.results["topostore"]["consistency"] for c in slow] == ["timeout (0.001 s)"] * 2
    empty = '<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#"/>'
    fine = [conformance.Case(f"f{k}", "RL", "Approved", ["consistency"], empty) for k in range(2)]
    conformance.run_batch(fine, "topostore", tmp_path, timeout=60)
    assert [c.results["topostore"]["consistency"] for c in fine] == [True, True]


def test_entailment_reductions() -> None:
    """A conclusion's axioms become fresh individuals, ASKs and inconsistency tests."""
    tests = entailment_tests(parse("""<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#"
        xmlns:rdfs="http://www.w3.org/2000/01/rdf-schema#" xmlns:owl="http://www.w3.org/2002/07/owl#"
        xml:base="http://example.org/">
      <owl:Ontology/>
      <owl:Class rdf:about="A"><rdfs:subClassOf rdf:resource="B"/><owl:disjointWith rdf:resource="C"/></owl:Class>
      <rdf:Description rdf:about="a"><ex:p xmlns:ex="http://example.org/" rdf:resource="b"/></rdf:Description>
      <rdf:Description rdf:about="a"><rdf:type><owl:Restriction><owl:onProperty rdf:resource="p"/>
        <owl:someValuesFrom rdf:resource="B"/></owl:Restriction></rdf:type></rdf:Description>
    </rdf:RDF>"""))
    asks = {(str(s).rsplit("/", 1)[-1].rsplit("#", 1)[-1], str(o).rsplit("/", 1)[-1].rsplit("#", 1)[-1])
            for s, _, o in tests.asks}
    assert ("a", "b") in asks  # an assertion: asked as it is
    assert any(o == "B" and s.startswith("t") for s, o in asks)  # A ⊑ B: a fresh A asked to be a B
    assert any(s == "a" and o.startswith("Q") for s, o in asks)  # a : ∃p.B as a : Q, Q ≡ ∃p.B added
    assert len(tests.contradictions) == 1  # A disjoint C: a fresh A and C is inconsistent


def test_table_has_every_category_and_type() -> None:
    case = conformance.Case("x", "RL", "Approved", ["consistency"], "<rdf:RDF/>",
                            results={"topostore": {"consistency": True}, "owlrl": {"consistency": False}})
    text = conformance.table([case], 0, 60)
    assert "| RL | — | — | 1 / 0 of 1 | — | 1 / 0 of 1 |" in text
    assert all(f"| {c} |" in text for c in conformance.CATEGORIES)


def test_document_lists_every_full_and_dl_failure_with_what_the_profile_report_names() -> None:
    """Full and DL failures are listed whatever owlrl answers, each with the premise's notices, those the
    conclusion's expressions add, or "no profile notice"; the headings count them."""
    def case(cid: str, category: str, mine: object, theirs: bool, **said: list[str]) -> conformance.Case:
        return conformance.Case(cid, category, "Approved", ["positive"], "<rdf:RDF/>",
                                results={"topostore": {"positive": mine, **said}, "owlrl": {"positive": theirs}})

    cases = [case("f1", "Full", False, False, notices=["complement on the left"]),
             case("f2", "Full", False, True),
             case("f3", "Full", False, False, question_notices=["maximum cardinality on the left"]),
             case("f4", "Full", True, True),
             case("d1", "DL", "error: LoadError: bad", False),
             case("r1", "RL", False, False)]
    text = conformance.document(cases, "table")
    full = text[text.index("## Every check topostore fails in Full"):text.index("## Every check topostore fails in DL")]
    assert "(3; 1 without a profile notice)" in full
    assert "`f1` — owlrl fails; profile report: complement on the left" in full
    assert "`f2` — owlrl passes; no profile notice" in full
    assert "`f3` — owlrl fails; with the conclusion's expressions loaded: maximum cardinality on the left" in full
    assert "`f4`" not in full and "`r1`" not in full
    dl = text[text.index("## Every check topostore fails in DL"):]
    assert "(1; 1 without a profile notice)" in dl and "- positive entailment (1; 1 without a notice): `d1`" in dl
    assert "x owl:sameAs x" in full  # why the failures without a notice have none
    behind = text[text.index("## Checks topostore fails where owlrl passes"):text.index("## Every check")]
    assert "`f2`" in behind and "`d1`" in behind and "`f1`" not in behind


def test_a_case_records_what_the_conclusions_expressions_add_to_the_profile_report() -> None:
    """x : ≤1 p with p functional: the premise is Horn, the question needs a maximum on the left."""
    from benchmarks.conformance_case import run_case

    head = ('<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" '
            'xmlns:owl="http://www.w3.org/2002/07/owl#">')
    premise = head + ('<owl:FunctionalProperty rdf:about="http://e.org/p"/>'
                      '<owl:Thing rdf:about="http://e.org/x"/></rdf:RDF>')
    conclusion = head + ('<owl:Thing rdf:about="http://e.org/x"><rdf:type><owl:Restriction>'
                         '<owl:onProperty rdf:resource="http://e.org/p"/><owl:maxCardinality rdf:datatype='
                         '"http://www.w3.org/2001/XMLSchema#nonNegativeInteger">1</owl:maxCardinality>'
                         '</owl:Restriction></rdf:type></owl:Thing></rdf:RDF>')
    out = run_case("topostore", {"id": "t", "checks": ["positive", "consistency"], "premise": premise,
                                 "conclusion": conclusion, "nonconclusion": ""})
    assert out["consistency"] is True and out["notices"] == []
    assert "maximum cardinality on the left" in out["question_notices"]
