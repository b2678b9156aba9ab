"""Fuzzing ArmorService.call / call_many and the Ontology manipulation methods.

Invariants on every case: a reply (no exception escapes), a documented exit
code, the asserted, inferred and helper graphs unchanged after a failing
request, no file outside the data directory touched, and the service still
answers afterwards.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from fuzz_support import DOCUMENTED_CODES, count_case, fuzz_settings, graphs, request, text, tree
from hypothesis import given
from hypothesis import strategies as st
from support import IRI, SHARED

from topostore import Ontology
from topostore.armor import ArmorResponse, ArmorService
from topostore.errors import TopostoreError
from topostore.rdf.vocab import ASSERTED

# thousands of generated cases: run without line tracing (coverage comes from the exact tests)
pytestmark = pytest.mark.no_cover



class Harness:
    """One service on a data directory inside a sandbox whose other files must never change."""

    def __init__(self, sandbox: Path) -> None:
        self.sandbox = sandbox
        self.data = sandbox / "data"
        self.data.mkdir()
        (self.data / "map.owl").write_bytes((SHARED / "topological_map_abox.owl").read_bytes())
        (sandbox / "outside.owl").write_text("keep")
        (self.data / "escape").symlink_to(sandbox / "outside.owl")
        self.service = ArmorService(data_dir=self.data)
        self.service.max_query_seconds = 2.0
        self.ensure()
        self.outside = self.outside_tree()

    def outside_tree(self) -> dict:
        return {k: v for k, v in tree(self.sandbox).items() if not k.startswith(str(self.data))}

    def ensure(self) -> None:
        """Keep a loaded, unmounted, unbuffered reference "ref" to aim at."""
        if "ref" not in self.service.reference_names():
            r = self.service.call({"reference_name": "ref", "command": "LOAD", "primary_command_spec": "FILE",
                                   "args": ["map.owl", IRI, "false", "PELLET", "false"]})
            assert r.exit_code == 0, r
        for name in self.service.reference_names():
            ref = self.service.reference(name)
            ref.owner = None
            ref.buffered_manipulation = ref.buffered_reasoner = False
            ref.buffer.clear()

    def check(self, response: ArmorResponse, before: dict) -> None:
        assert isinstance(response, ArmorResponse)
        assert response.exit_code in DOCUMENTED_CODES, response
        assert "internal error" not in response.error_description, response
        if not response.success and response.exit_code != 0:
            assert graphs(self.service) == before, response
        assert self.outside_tree() == self.outside
        alive = self.service.call({"reference_name": "ref", "command": "GET", "primary_command_spec": "ALL",
                                   "secondary_command_spec": "REFS"})
        assert alive.exit_code == 0


@pytest.fixture(scope="module")
def harness(tmp_path_factory: pytest.TempPathFactory) -> Harness:
    return Harness(tmp_path_factory.mktemp("fuzz-armor"))


@fuzz_settings(3.0)
@given(req=request())
def test_fuzz_armor_call(harness: Harness, req: object) -> None:
    count_case()
    harness.ensure()
    before = graphs(harness.service)
    response = harness.service.call(req)  # type: ignore[arg-type]
    harness.check(response, before)


@fuzz_settings(0.5)
@given(reqs=st.lists(request(), max_size=5))
def test_fuzz_armor_call_many(harness: Harness, reqs: list) -> None:
    count_case()
    harness.ensure()
    result = harness.service.call_many(reqs)
    assert len(result.armor_responses) == len(reqs)
    for r in result.armor_responses:
        assert r.exit_code in DOCUMENTED_CODES and "internal error" not in r.error_description, r
    assert result.success == all(r.success for r in result.armor_responses)


@pytest.fixture(scope="module")
def onto() -> Ontology:
    o = Ontology.from_file(SHARED / "topological_map_abox.owl", prefix=IRI + "#")
    o.reason()
    return o


METHODS = ["add_fact", "remove_fact", "add_type", "remove_type", "add_data", "replace", "add_all_different",
           "remove_individual", "sparql", "select", "query", "types", "instances", "object_values", "data_values"]


@fuzz_settings(1.0)
@given(method=st.sampled_from(METHODS), args=st.lists(st.one_of(text(), st.integers(), st.floats(), st.none()),
                                                       min_size=0, max_size=4))
def test_fuzz_ontology_methods(onto: Ontology, method: str, args: list) -> None:
    """Wrong values raise a topostore error (or TypeError for a wrong call) and change nothing;
    a change that breaks reasoning (e.g. removing a property a SWRL rule uses) is rolled back by REASON."""
    count_case()
    asserted = lambda: frozenset(onto.store.triples(graph=ASSERTED))  # noqa: E731
    before = asserted()
    try:
        getattr(onto, method)(*args)
    except (TopostoreError, TypeError, ValueError):
        assert asserted() == before
        return
    try:
        onto.reason()
    except TopostoreError:
        assert asserted() == before
