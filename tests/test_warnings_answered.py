"""A warning is no fault of a command: under a warnings filter that turns warnings into errors
(``warnings.simplefilter("error")``, ``python -W error``), a command whose REASON gives a
:class:`~topostore.PelletDifferenceWarning` (or whose load gives notices) is answered as done, the warning's
text in its reply and on the log, and no command is left half-done by it.
"""

from __future__ import annotations

import json
import logging
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest
from click.testing import CliRunner
from fidelity_cases import document, namespace
from http_support import InProcess, config, in_process
from pyoxigraph import Literal, NamedNode, Triple

from topostore import ArmorService, PelletDifferenceWarning
from topostore.armor.reference import Change, Delta
from topostore.armor.types import ArmorResponse
from topostore.cli.group import cli
from topostore.compile.notices import answered

IRI = namespace("answered")[:-1]
#: a functional data property holding 5 (consistent): a string value added to it is inconsistent in OWL 2
#: only (Pellet 2.3.1 does not tell 5 and "five" apart)
BODY = (f"<{IRI}> a owl:Ontology .\n:d a owl:DatatypeProperty, owl:FunctionalProperty .\n"
        ":q a owl:DatatypeProperty .\n:x a owl:NamedIndividual ; :d 5 .\n")
#: besides, an axiom not reasoned completely: its load gives a notice (an OntologyWarning)
UNION = ":A a owl:Class .\n:B a owl:Class .\n:C a owl:Class ; rdfs:subClassOf [ owl:unionOf ( :A :B ) ] .\n"
SAID = "Pellet 2.3.1 does not tell these two values apart"


@contextmanager
def as_errors() -> Iterator[None]:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        yield


def written(tmp_path: Path, body: str = BODY) -> Path:
    path = tmp_path / "answered.ttl"
    path.write_text(document("answered", body))
    return path


def call(service: ArmorService, command: str, spec1: str = "", spec2: str = "", *args: str) -> ArmorResponse:
    return service.call({"reference_name": "r", "command": command, "primary_command_spec": spec1,
                         "secondary_command_spec": spec2, "args": list(args)})


def loaded(tmp_path: Path, buffered_manipulation: bool = False, buffered_reasoner: bool = False,
           body: str = BODY) -> ArmorService:
    service = ArmorService()
    with as_errors():
        reply = call(service, "LOAD", "FILE", "", str(written(tmp_path, body)), IRI, str(buffered_manipulation).lower(),
                     "PELLET", str(buffered_reasoner).lower())
    assert reply.success and reply.exit_code == 0, reply
    return service


def d_values(service: ArmorService) -> list[Literal]:
    onto = service.reference("r").ontology
    return onto.data_values(NamedNode(namespace("answered") + "d"), NamedNode(namespace("answered") + "x"))


def test_a_manipulation_whose_reason_warns_is_done_and_says_it(tmp_path: Path,
                                                               caplog: pytest.LogCaptureFixture) -> None:
    service = loaded(tmp_path)
    with as_errors(), caplog.at_level(logging.WARNING, logger="topostore.armor"):
        reply = call(service, "ADD", "DATAPROP", "IND", "d", "x", "STRING", "five")
    assert reply.success and reply.exit_code == 0, reply
    assert SAID in reply.error_description and not reply.is_consistent
    assert Literal("five") in d_values(service)
    assert any(SAID in r.getMessage() for r in caplog.records if r.name.startswith("topostore.armor"))
    with as_errors():  # the next command finds the state the first left: nothing to undo, nothing pending
        reply = call(service, "REMOVE", "DATAPROP", "IND", "d", "x", "STRING", "five")
    assert reply.success and reply.is_consistent and reply.error_description == "", reply
    assert [v.value for v in d_values(service)] == ["5"]


def test_a_reason_command_that_warns_is_done(tmp_path: Path) -> None:
    """A buffered reasoner: the change waits for REASON, whose warning is in its reply."""
    service = loaded(tmp_path, buffered_reasoner=True)
    with as_errors():
        added = call(service, "ADD", "DATAPROP", "IND", "d", "x", "STRING", "five")
        reasoned = call(service, "REASON")
    assert added.success and added.error_description == "" and added.is_consistent
    assert reasoned.success and reasoned.exit_code == 0 and SAID in reasoned.error_description, reasoned
    assert not reasoned.is_consistent


def test_an_apply_of_buffered_changes_that_warns_leaves_no_change_queued(tmp_path: Path) -> None:
    service = loaded(tmp_path, buffered_manipulation=True)
    with as_errors():
        assert call(service, "ADD", "DATAPROP", "IND", "d", "x", "STRING", "five").success
        applied = call(service, "APPLY")
    assert applied.success and SAID in applied.error_description, applied
    ref = service.reference("r")
    assert ref.buffer == [] and Literal("five") in d_values(service)


def test_a_load_that_warns_is_done(tmp_path: Path) -> None:
    """A load's notices and its REASON's warning, both raised as errors by the filter, are in its reply."""
    service = ArmorService()
    body = BODY + UNION + ':x :d "five" .\n'
    with as_errors():
        reply = call(service, "LOAD", "FILE", "", str(written(tmp_path, body)), IRI, "false", "PELLET", "false")
    assert reply.success and reply.exit_code == 0, reply
    assert "not reasoned completely" in reply.error_description and SAID in reply.error_description
    assert not reply.is_consistent


@pytest.fixture
def server(tmp_path: Path) -> Iterator[InProcess]:
    with in_process(config(tmp_path / "data", allow_update=True)) as s:
        yield s


def test_the_http_service_answers_commands_that_warn(server: InProcess) -> None:
    """Over HTTP: an aRMOR command, a SPARQL Update and a Graph Store write whose REASON warns."""
    with as_errors():
        status, _, body = server.request("/references/r/data?default&iri=" + IRI,
                                         document("answered", BODY).encode(), {"Content-Type": "text/turtle"}, "PUT")
        assert status == 201, body
        reply = server.armor("ADD", "DATAPROP", "IND", ["d", "x", "STRING", "five"], ref="r")
        assert reply["success"] and reply["exit_code"] == 0 and SAID in reply["error_description"], reply
        server.armor("REMOVE", "DATAPROP", "IND", ["d", "x", "STRING", "five"], ref="r")
        update = f'PREFIX : <{namespace("answered")}> INSERT DATA {{ :x :d "five" }}'
        status, _, body = server.request("/references/r/sparql", update.encode(),
                                         {"Content-Type": "application/sparql-update"})
        assert status == 200, body
        outcome = json.loads(body)
        assert outcome["added"] == 1 and not outcome["is_consistent"]
        assert any(SAID in w for w in outcome["warnings"]), outcome
        status, _, body = server.request("/references/r/data?default", document("answered", ':x :q "kept" .').encode(),
                                         {"Content-Type": "text/turtle"}, "POST")
        assert status == 200, body
        assert any(SAID in w for w in json.loads(body)["warnings"]), body


def test_the_command_line_shows_the_warning_of_a_reason(tmp_path: Path) -> None:
    path = written(tmp_path, BODY + ':x :d "five" .\n')
    plain = CliRunner().invoke(cli, ["reason", str(path)])
    with as_errors():
        result = CliRunner().invoke(cli, ["reason", str(path)])
    assert result.exit_code == plain.exit_code and not isinstance(result.exception, Warning), result.output
    assert "warning: x has the different values" in result.output and SAID in result.output


def test_a_manipulation_inside_a_command_answers_its_warning_in_its_own_block(tmp_path: Path) -> None:
    """A reference's manipulation inside a block already answering the warnings (an aRMOR command's) answers
    its REASON's in a block of its own: the texts are its last change's warning, and the command's block
    keeps none of them, before and after; a wider block and none at all alike."""
    service = loaded(tmp_path)
    ref = service.reference("r")
    x, d = NamedNode(namespace("answered") + "x"), NamedNode(namespace("answered") + "d")

    def change(value: str) -> Change:
        return Change("ADD", lambda _onto: Delta(add=[Triple(x, d, Literal(value))]))

    with as_errors(), answered(PelletDifferenceWarning) as heard:
        heard.append("said before")
        (done,) = ref.applied([change("five")])
        assert heard == ["said before"]
    assert SAID in done.warning and done.warning.count(SAID) == 1, done.warning
    with as_errors(), answered(PelletDifferenceWarning, UserWarning) as wider:
        (again,) = ref.applied([change("six")])
    assert SAID in again.warning and wider == []
    with as_errors():
        (alone,) = ref.applied([change("seven")])
    assert SAID in alone.warning
