"""The Graph Store's write replies count what the asserted graph gained and lost, not the triples a
document wrote, and say which spelling stays wherever a written spelling of a value is not taken."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from http_support import InProcess, config, in_process

NS = "http://e.org/counts#"
XSD = "http://www.w3.org/2001/XMLSchema#"
HEAD = (f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . "
        "<http://e.org/counts> a owl:Ontology . :s a owl:DatatypeProperty . ")
#: three facts written as seven triples: one value in two spellings of one datatype and repeated, one in two
#: datatypes the store keeps as one value, one plain string repeated
REPEATS = (f':x :s "1"^^<{XSD}int> , "01"^^<{XSD}int> . :x :s "1"^^<{XSD}int> . '
           f':y :s "2"^^<{XSD}integer> , "2"^^<{XSD}int> . :z :s "5" , "5" .')


@pytest.fixture
def server(tmp_path: Path):
    with in_process(config(tmp_path / "data", allow_update=True)) as s:
        yield s


def send(server: InProcess, method: str, body: str | None = None) -> tuple[int, dict]:
    headers = {"Content-Type": "text/turtle"} if body is not None else None
    status, _, reply = server.request("/references/counts/data?default",
                                      None if body is None else (HEAD + body).encode(), headers, method)
    assert status in (200, 201), reply
    return status, json.loads(reply)


def saved(server: InProcess) -> bytes:
    _, _, body = server.request("/references/counts/data?default", None, {"Accept": "application/n-triples"})
    return body


def test_a_created_reference_counts_the_triples_stored_and_says_which_spelling_stays(server: InProcess) -> None:
    """A PUT that creates the reference (201) counts the five triples the graph holds, not the nine parsed;
    each value written in a second spelling is named with the spelling that stays."""
    status, body = send(server, "PUT", REPEATS)
    assert status == 201 and body["added"] == 5 and body["removed"] == 0, body
    text = " ".join(body["warnings"])
    assert f'"1"^^<{XSD}int> stays as written: <{NS}x> <{NS}s> "01"^^<{XSD}int> is the same value' in text, body
    assert f'"2"^^<{XSD}integer> stays as written: <{NS}y> <{NS}s> "2"^^<{XSD}int> is the same value' in text, body
    assert "5" not in text  # a repeated triple is one fact: nothing to say
    _, deleted = send(server, "DELETE")
    assert deleted["removed"] == 5 and deleted["added"] == 0, deleted


def test_put_and_post_count_what_the_graph_gained(server: InProcess) -> None:
    """Over a graph that holds the three facts, a PUT or POST of the same document gains nothing; a POST
    that adds one fact, written twice, counts one; a PUT that keeps one fact counts the others removed."""
    send(server, "PUT", REPEATS)
    for method in ("PUT", "POST"):
        _, body = send(server, method, REPEATS)
        assert body["added"] == 0 and body["removed"] == 0, (method, body)
    _, body = send(server, "POST", ':w :s "9" . :w :s "9" .')
    assert body["added"] == 1 and body["removed"] == 0 and body["warnings"] == [], body
    _, body = send(server, "POST", f':v :s "3"^^<{XSD}long> , "03"^^<{XSD}long> , "3"^^<{XSD}long> .')
    assert body["added"] == 1 and len(body["warnings"]) == 1, body
    assert body["warnings"][0].startswith(f'<{NS}v> <{NS}s> "3"^^<{XSD}long> stays as written: <{NS}v> <{NS}s> '
                                          f'"03"^^<{XSD}long> is the same value, written again'), body
    _, body = send(server, "DELETE")
    assert body["removed"] == 7, body
    send(server, "PUT", REPEATS)
    _, body = send(server, "POST", ':w :s "9" .')
    assert body["added"] == 1, body
    _, body = send(server, "PUT", f':x :s "1"^^<{XSD}int> , "1"^^<{XSD}int> .')
    assert body["added"] == 0 and body["removed"] == 3, body  # :y, :z and :w go
    assert f'"1"^^<{XSD}int>'.encode() in saved(server)


@pytest.mark.parametrize("held, posted", [("int", "01\"^^<{xsd}int"), ("int", "1\"^^<{xsd}integer"),
                                          ("integer", "1\"^^<{xsd}int"), ("long", "+1\"^^<{xsd}integer")])
def test_a_post_of_a_value_held_in_another_spelling_says_which_stays(held: str, posted: str,
                                                                      server: InProcess) -> None:
    """A POST writing a stored value in another spelling adds nothing and says so, in the words a PUT uses."""
    send(server, "PUT", f':x :s "1"^^<{XSD}{held}> .')
    written = '"' + posted.format(xsd=XSD) + ">"
    _, body = send(server, "POST", f":x :s {written} .")
    assert body["added"] == 0 and body["removed"] == 0, body
    assert len(body["warnings"]) == 1, body
    assert body["warnings"][0].startswith(f'<{NS}x> <{NS}s> "1"^^<{XSD}{held}> stays as written: '
                                          f'<{NS}x> <{NS}s> {written} is the same value'), body
    assert f'"1"^^<{XSD}{held}>'.encode() in saved(server) and written.encode() not in saved(server)


#: one value of a blank node written in two spellings: the note names the node
BLANK = f':x :o [ :s "1"^^<{XSD}int> , "01"^^<{XSD}int> ] .'


@pytest.mark.parametrize("methods", [["PUT"], ["PUT", "PUT"], ["PUT", "POST"]], ids=["create", "put", "post"])
def test_a_note_names_a_blank_node_as_the_graph_holds_it(methods: list[str], server: InProcess) -> None:
    """The note of a spelling not taken names a blank node as GET writes the stored graph (``_:id``), on the
    PUT that creates the reference, a PUT and a POST: the node the graph holds, not the name of a parse."""
    if len(methods) > 1:
        send(server, "PUT", ':w :s "9" .')
    _, body = send(server, methods[-1], BLANK)
    stored = re.findall(r"_:\w+", saved(server).decode())
    assert len(set(stored)) == 1, saved(server)
    node = stored[0]
    assert body["warnings"] == [f'{node} <{NS}s> "1"^^<{XSD}int> stays as written: {node} <{NS}s> "01"^^<{XSD}int> '
                                "is the same value, written again in the document"], body


#: why a language tag's spelling is not taken, as the notes say it
TAG_KEPT = "is the same value, its language tag spelled otherwise (a tag keeps the spelling it was first written with)"


def tag_note(subject: str, kept: str, other: str, value: str = "a") -> str:
    return (f'<{NS}{subject}> <{NS}s> "{value}"@{kept} stays as written: '
            f'<{NS}{subject}> <{NS}s> "{value}"@{other} {TAG_KEPT}')


def test_a_post_of_a_held_value_with_its_tag_spelled_otherwise_says_which_stays(server: InProcess) -> None:
    """pyoxigraph lowers tags, so ``"chat"@EN-gb`` over a held ``"chat"@en-GB`` is the triple held: nothing
    is added, and the reply says the tag keeps its spelling (GET shows it)."""
    send(server, "PUT", ':x :s "chat"@en-GB .')
    _, body = send(server, "POST", ':x :s "chat"@EN-gb .')
    assert body["added"] == 0 and body["warnings"] == [tag_note("x", "en-GB", "EN-gb", "chat")], body
    assert b'"chat"@en-GB' in saved(server) and b"EN-gb" not in saved(server)
    _, body = send(server, "POST", ':x :s "chat"@en-GB .')
    assert body["added"] == 0 and body["warnings"] == [], body  # the spelling kept: nothing to say


@pytest.mark.parametrize("methods", [["PUT"], ["PUT", "PUT"], ["PUT", "POST"]], ids=["create", "put", "post"])
def test_one_value_written_with_two_tag_spellings_keeps_the_first(methods: list[str], server: InProcess) -> None:
    """``"a"@FR , "a"@fr`` is one triple: the first spelling stays, and the other is said, on each write."""
    if len(methods) > 1:
        send(server, "PUT", ':w :s "9" .')
    _, body = send(server, methods[-1], ':y :s "a"@FR , "a"@fr .')
    assert body["added"] == (3 if len(methods) == 1 else 1), body
    assert body["warnings"] == [tag_note("y", "FR", "fr")], body
    assert b'"a"@FR' in saved(server) and b'"a"@fr' not in saved(server)


RDF_XML_FR = (f'<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:c="{NS}">'
              f'<rdf:Description rdf:about="{NS}y"><c:s xml:lang="Fr">a</c:s></rdf:Description></rdf:RDF>')
JSON_LD_FR = json.dumps({"@id": f"{NS}y", f"{NS}s": {"@value": "a", "@language": "fR"}})


@pytest.mark.parametrize(("media", "doc", "spelled"), [
    ("application/rdf+xml", RDF_XML_FR, "Fr"), ("application/ld+json", JSON_LD_FR, "fR")], ids=["rdf-xml", "json-ld"])
def test_a_tag_spelling_not_taken_is_said_in_other_syntaxes(server: InProcess, media: str, doc: str,
                                                           spelled: str) -> None:
    """RDF/XML's ``xml:lang`` and JSON-LD's ``@language`` spellings are read too (the parsers lower them as
    Turtle's)."""
    send(server, "PUT", ':y :s "a"@FR .')
    status, _, reply = server.request("/references/counts/data?default", doc.encode(), {"Content-Type": media}, "POST")
    body = json.loads(reply)
    assert status == 200 and body["added"] == 0 and body["warnings"] == [tag_note("y", "FR", spelled)], body


def test_text_that_looks_like_a_tag_is_no_spelling(server: InProcess) -> None:
    """A string or a comment holding ``"a"@fr`` writes no tag: only real literals are said."""
    send(server, "PUT", ':y :s "a"@FR .')
    _, body = send(server, "POST", ':y :s "a\\"@fr" . # :y :s "a"@fr\n:y :s "b" .')
    assert body["added"] == 2 and body["warnings"] == [], body


def test_a_created_reference_names_a_blank_node_whose_tag_is_spelled_twice(server: InProcess) -> None:
    """A document whose blank node holds one tagged value in two spellings: the 201's note names the node
    the graph holds, with the spelling that stays."""
    _, body = send(server, "PUT", ':x :o [ :s "a"@FR , "a"@fr ] .')
    node = re.findall(r"_:\w+", saved(server).decode())[0]
    assert body["warnings"] == [f'{node} <{NS}s> "a"@FR stays as written: {node} <{NS}s> "a"@fr {TAG_KEPT}'], body


def test_a_new_value_whose_tag_is_spelled_otherwise_is_no_same_value(server: InProcess) -> None:
    """``"b"@fr`` over a graph that spells the tag ``FR`` adds a new value, shown as ``"b"@FR``: the note
    says it is stored so, not that ``"b"@FR`` stays as written (it never was)."""
    send(server, "PUT", ':y :s "a"@FR .')
    _, body = send(server, "POST", ':y :s "b"@fr .')
    assert body["added"] == 1, body
    assert body["warnings"] == [f'<{NS}y> <{NS}s> "b"@fr is stored as <{NS}y> <{NS}s> "b"@FR: a new value, its '
                                "language tag spelled as the store spells it (a tag keeps the spelling it was "
                                "first written with)"], body
    assert b'"b"@FR' in saved(server)


def test_a_sparql_update_counts_what_the_graph_took(server: InProcess) -> None:
    """An INSERT DATA of a value the graph holds in another spelling adds nothing: the answer counts 0, not
    the one triple the update planned, and says which spelling stays."""
    send(server, "PUT", f':x :s "1"^^<{XSD}int> .')
    update = f'INSERT DATA {{ <{NS}x> <{NS}s> "1.0"^^<{XSD}decimal> }}'
    status, _, reply = server.request("/references/counts/sparql", update.encode(),
                                      {"Content-Type": "application/sparql-update"}, "POST")
    body = json.loads(reply)
    assert status == 200 and body["added"] == 0 and body["removed"] == 0, body
    assert len(body["warnings"]) == 1 and "already in the graph" in body["warnings"][0], body
    assert f'"1"^^<{XSD}int>'.encode() in saved(server)


def test_one_instant_spelled_twice_is_one_triple_and_said(server: InProcess) -> None:
    """``…Z`` and ``…+00:00`` name one instant in one zone, which the store holds as one triple: counted once
    and the second spelling named; the same instant in another zone is another triple of the store."""
    instant = f'"2020-01-01T00:00:00Z"^^<{XSD}dateTime>'
    status, body = send(server, "PUT", f':w :s {instant} , "2020-01-01T00:00:00+00:00"^^<{XSD}dateTime> , '
                                       f'"2020-01-01T01:00:00+01:00"^^<{XSD}dateTime> .')
    assert status == 201 and body["added"] == 4, body  # the two instants and the head's two triples
    assert f'{instant} stays as written' in " ".join(body["warnings"]), body
    _, again = send(server, "POST", f':w :s "2020-01-01T00:00:00.000+00:00"^^<{XSD}dateTime> .')
    assert again["added"] == 0, again
