"""A load says which spelling it did not take, through every loader (the Python API, an aRMOR LOAD, the
CLI), in the Graph Store's words; it counts the facts stored, one per value whatever its spellings."""

from __future__ import annotations

import subprocess
import sys
import warnings
from pathlib import Path

import pytest
from pyoxigraph import Literal, NamedNode, Triple
from support import armor_load

from topostore import Ontology, OntologyWarning, SpellingKeptWarning
from topostore.armor import ArmorService
from topostore.rdf.vocab import ASSERTED

NS = "http://e.org/spell#"
XSD = "http://www.w3.org/2001/XMLSchema#"
HEAD = f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . <http://e.org/spell> a owl:Ontology . "
#: two facts, each written in two spellings: an integer and a language tag
TWICE = HEAD + f':x :s "1"^^<{XSD}integer> , "01"^^<{XSD}integer> . :y :s "a"@EN , "a"@en .'
#: what the load says of each spelling not taken
SAID = (f'<{NS}x> <{NS}s> "1"^^<{XSD}integer> stays as written: <{NS}x> <{NS}s> "01"^^<{XSD}integer> is the same '
        "value, written again in the document",
        f'<{NS}y> <{NS}s> "a"@EN stays as written: <{NS}y> <{NS}s> "a"@en is the same value, its language tag '
        "spelled otherwise (a tag keeps the spelling it was first written with)")


def ontology(into: str) -> Ontology:
    """An empty ontology (a document is streamed into it), or one holding a fact already (the ordinary load)."""
    onto = Ontology(prefix=NS)
    if into == "non-empty":
        onto.load_data(HEAD + ':z :s "q" .')
    return onto


@pytest.mark.parametrize("into", ["empty", "non-empty"])
def test_load_data_warns_of_each_spelling_not_taken_and_counts_the_facts(into: str) -> None:
    onto = ontology(into)
    with pytest.warns(SpellingKeptWarning) as said:
        added = onto.load_data(TWICE)
    assert added == 2 + (into == "empty")  # :x :s 1, :y :s "a"@EN (and the owl:Ontology declaration)
    (warning,) = said
    assert str(warning.message) == "<data>: " + "; ".join(SAID)
    assert warning.filename == __file__  # it points at the caller of load_data
    assert onto.notice_lines()[-1] == "; ".join(SAID)
    assert isinstance(warning.message, OntologyWarning)  # a load notice, as the others are


@pytest.mark.parametrize("into", ["empty", "non-empty"])
def test_load_of_a_file_warns_alike(into: str, tmp_path: Path) -> None:
    path = tmp_path / "twice.ttl"
    path.write_text(TWICE)
    onto = ontology(into)
    with pytest.warns(SpellingKeptWarning, match="written again in the document"):
        assert onto.load(path) == 2 + (into == "empty")
    assert onto.store.count(ASSERTED) == 3 + (into == "non-empty")  # and :z :s "q"


def test_a_document_of_one_spelling_each_says_nothing() -> None:
    onto = Ontology(prefix=NS)
    with warnings.catch_warnings():
        warnings.simplefilter("error", SpellingKeptWarning)
        onto.load_data(HEAD + f':x :s "1"^^<{XSD}integer> , "1"^^<{XSD}integer> . :y :s "a"@EN .')
    assert onto.files.spelling_notes == [] and onto.notice_lines() == []


def test_two_spellings_added_in_one_change_count_once() -> None:
    """A change recorded in the ledger (after a REASON) adds one fact for a value written twice."""
    onto = Ontology(prefix=NS)
    onto.load_data(HEAD)
    onto.reason()
    x, s = NamedNode(NS + "x"), NamedNode(NS + "s")
    one, again = (Triple(x, s, Literal(v, datatype=NamedNode(XSD + "integer"))) for v in ("1", "01"))
    assert onto.add(one, again) == 1
    assert onto.remove(one, again) == 1 and onto.store.count(ASSERTED) == 1


def test_a_new_value_whose_tag_is_spelled_as_stored_is_not_called_the_same_value() -> None:
    """``"b"@fr`` where the document spelled the tag ``FR`` first is a new value, stored and shown as
    ``"b"@FR``: the note says so, and calls ``"a"@fr`` (a second spelling of ``"a"@FR``) the same value."""
    onto = Ontology(prefix=NS)
    with pytest.warns(SpellingKeptWarning) as said:
        onto.load_data(HEAD + ':x :s "a"@FR , "a"@fr . :y :s "b"@fr .')
    text = str(said[0].message)
    assert f'<{NS}x> <{NS}s> "a"@FR stays as written: <{NS}x> <{NS}s> "a"@fr is the same value' in text
    assert (f'<{NS}y> <{NS}s> "b"@fr is stored as <{NS}y> <{NS}s> "b"@FR: a new value, its language tag spelled as '
            "the store spells it") in text
    assert "b\"@FR stays" not in text


def test_armor_load_replies_with_the_spellings_not_taken(tmp_path: Path) -> None:
    path = tmp_path / "twice.ttl"
    path.write_text(TWICE)
    reply = armor_load(ArmorService(), path, "http://e.org/spell")
    assert reply.success, reply
    assert "; ".join(SAID) in reply.error_description


def test_the_cli_says_the_spellings_not_taken(tmp_path: Path) -> None:
    path = tmp_path / "twice.ttl"
    path.write_text(TWICE)
    done = subprocess.run([sys.executable, "-m", "topostore.cli", "reason", str(path)], capture_output=True, text=True,
                          timeout=120, check=False)
    assert done.returncode == 0, done.stderr
    assert f"warning: {path}: {'; '.join(SAID)}" in " ".join(done.stderr.split("\n")), done.stderr
    assert "SpellingKeptWarning" not in done.stderr  # a warning: line, not a Python warning


def test_a_held_value_whose_tag_a_later_document_spells_otherwise_is_the_same_value() -> None:
    """Over a graph holding ``"a"@FR``, a document's ``"a"@fr`` is that value (it stays as written), and its
    ``"b"@fr`` a new value stored as ``"b"@FR``."""
    onto = Ontology(prefix=NS)
    onto.load_data(HEAD + ':x :s "a"@FR .')
    with pytest.warns(SpellingKeptWarning) as said:
        assert onto.load_data(HEAD + ':x :s "a"@fr . :y :s "b"@fr .') == 1
    assert str(said[0].message) == (
        f'<data>: <{NS}x> <{NS}s> "a"@FR stays as written: <{NS}x> <{NS}s> "a"@fr is the same value, its language '
        f"tag spelled otherwise (a tag keeps the spelling it was first written with); <{NS}y> <{NS}s> \"b\"@fr is "
        f'stored as <{NS}y> <{NS}s> "b"@FR: a new value, its language tag spelled as the store spells it (a tag '
        "keeps the spelling it was first written with)")


@pytest.mark.parametrize(("held", "written"), [("1", "01"), ("1.0", "1")])
def test_a_value_held_in_another_spelling_is_said_by_a_later_load(held: str, written: str) -> None:
    """A document writing a value the graph holds in another spelling stores nothing and says which stays,
    in the Graph Store's words; a value it writes in the spelling held is not named."""
    onto = Ontology(prefix=NS)
    onto.load_data(HEAD + f':x :s "{held}"^^<{XSD}decimal> .')
    with pytest.warns(SpellingKeptWarning) as said:
        assert onto.load_data(HEAD + f':x :s "{written}"^^<{XSD}decimal> , "{held}"^^<{XSD}decimal> .') == 0
    assert str(said[0].message) == (
        f'<data>: <{NS}x> <{NS}s> "{held}"^^<{XSD}decimal> stays as written: <{NS}x> <{NS}s> '
        f'"{written}"^^<{XSD}decimal> is the same value, already in the graph (to change only its spelling, remove '
        "it first and add it then)")
