"""A language tag keeps the spelling its document gave it (``"colour"@en-GB``) through LOAD, SAVE in each
format, a durable store reopened, and the aRMOR query replies, although pyoxigraph lowers every tag."""

from __future__ import annotations

import json
import time
import warnings
from pathlib import Path

import pytest
from http_support import config, in_process
from pyoxigraph import Literal, NamedNode, RdfFormat, parse
from support import armor_load, too_large_axiom

from topostore import LoadError, Ontology, OntologyWarning
from topostore.armor import ArmorService
from topostore.armor.reference import Reference
from topostore.errors import InvalidValueError, RuleCompileError
from topostore.rdf.vocab import ASSERTED
from topostore.sparql.execute import Job, run_update

NS = "http://e.org/lang#"
TURTLE = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
<http://e.org/lang> a owl:Ontology . :s a owl:DatatypeProperty . :x a owl:NamedIndividual .
:x :s "colour"@en-GB , "hello"@EN-us , "plain"@fr , "says \\"@en-GB\\" inside"@de-CH .
"""
RDF_XML = f"""<?xml version="1.0"?>
<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:owl="http://www.w3.org/2002/07/owl#">
  <owl:DatatypeProperty rdf:about="{NS}s"/>
  <owl:NamedIndividual rdf:about="{NS}x"><s xmlns="{NS}" xml:lang="en-GB">colour</s></owl:NamedIndividual>
</rdf:RDF>
"""


def quiet(o: Ontology, text: str, fmt: str = "turtle") -> Ontology:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(text, fmt)
    return o


@pytest.mark.parametrize("suffix", ["ttl", "nt", "owl"])
def test_save_spells_tags_as_loaded_and_a_reload_keeps_them(suffix: str, tmp_path: Path) -> None:
    path = quiet(Ontology(), TURTLE).save(tmp_path / f"saved.{suffix}")
    spelled(path.read_text(), suffix)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        again = Ontology.from_file(path)
    spelled(again.save(tmp_path / f"again.{suffix}").read_text(), suffix)


def spelled(text: str, suffix: str) -> None:
    if suffix == "owl":
        assert 'xml:lang="en-GB"' in text and 'xml:lang="EN-us"' in text and 'xml:lang="fr"' in text
        assert 'xml:lang="de-CH"' in text
    else:
        assert '"colour"@en-GB' in text and '"hello"@EN-us' in text and '"plain"@fr' in text
        assert r'"says \"@en-GB\" inside"@de-CH' in text  # a quote inside a string is no tag


def test_rdf_xml_spellings_are_kept() -> None:
    assert b'"colour"@en-GB' in quiet(Ontology(), RDF_XML, "xml").serialize("ntriples")


def test_lowered_stored_values_are_unchanged() -> None:
    """The tag is one value whatever its case: the store's answers are pyoxigraph's literals, lowered."""
    o = quiet(Ontology(), TURTLE)
    assert {v.language for v in o.data_values(NamedNode(f"{NS}s"), NamedNode(f"{NS}x"))} == {"en-gb", "en-us", "fr", "de-ch"}


def test_a_refused_load_learns_no_spelling() -> None:
    o = Ontology()
    with pytest.raises(LoadError):
        o.load_data(TURTLE + ' :y :s "z"@pt-BR . this is not turtle', "turtle")
    assert not o.store.forms.tags
    quiet(o, f'@prefix : <{NS}> . :y :s "z"@pt-br .')
    assert b'"z"@pt-br' in o.serialize("ntriples")


def test_a_durable_store_keeps_the_spellings(tmp_path: Path) -> None:
    o = quiet(Ontology(store=tmp_path / "db"), TURTLE)
    o.store.close()
    again = Ontology(store=tmp_path / "db")
    assert b'"colour"@en-GB' in again.serialize("ntriples")


def test_armor_replies_spell_tags_as_loaded(tmp_path: Path) -> None:
    path = tmp_path / "lang.ttl"
    path.write_text(TURTLE)
    service = ArmorService()
    assert armor_load(service, path, "http://e.org/lang").success
    reply = service.call({"client_name": "c", "reference_name": "ref", "command": "QUERY",
                          "primary_command_spec": "DATAPROP", "secondary_command_spec": "IND", "args": ["s", "x"]})
    assert reply.success, reply
    assert '"colour"@en-GB' in reply.queried_objects and '"hello"@EN-us' in reply.queried_objects
    assert '"plain"@fr' in reply.queried_objects


def test_an_escaped_quote_before_an_at_sign_is_no_tag() -> None:
    """``\\"@EN\\"`` inside a string is text: the document's real ``@en`` stays as written."""
    text = (f'@prefix : <{NS}> . :s a <http://www.w3.org/2002/07/owl#DatatypeProperty> .\n'
            ':x :s "the mail said \\"@EN\\" twice"@fr , "hello"@en .\n')
    saved = quiet(Ontology(), text).serialize("ntriples")
    assert b'"hello"@en .' in saved and b"@EN ." not in saved


def test_the_first_spelling_wins_even_when_lowered() -> None:
    """Two documents spelling one tag ``en-gb`` then ``EN-GB``: the first (lower-case) spelling stays."""
    o = quiet(Ontology(), f'@prefix : <{NS}> . :x :s "a"@en-gb .\n')
    quiet(o, f'@prefix : <{NS}> . :x :s "b"@EN-GB .\n')
    saved = o.serialize("ntriples")
    assert b'"a"@en-gb' in saved and b'"b"@en-gb' in saved


def test_short_name_replies_show_values_unchanged(tmp_path: Path) -> None:
    """In the short-names mode a literal is its bare value: a value ending in ``"@en-gb`` is not respelled."""
    path = tmp_path / "lang.ttl"
    path.write_text(f'@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n'
                    '<http://e.org/lang> a owl:Ontology . :s a owl:DatatypeProperty . :x a owl:NamedIndividual .\n'
                    ':x :s "colour"@en-GB , "quote \\"@en-gb" .\n')
    service = ArmorService(short_names=True)
    assert armor_load(service, path, "http://e.org/lang").success
    reply = service.call({"client_name": "c", "reference_name": "ref", "command": "QUERY",
                          "primary_command_spec": "DATAPROP", "secondary_command_spec": "IND", "args": ["s", "x"]})
    assert reply.success, reply
    assert sorted(reply.queried_objects) == ["colour", 'quote "@en-gb']


@pytest.mark.parametrize("decoy", [
    ":a :s 'the spec writes \"colour\"@EN-gb here' .",  # inside a single-quoted string
    ':a :s """a long string "colour"@EN-gb inside""" .',  # inside a long string
    '# a comment writes "colour"@EN-gb once',  # a comment
])
def test_text_that_only_looks_like_a_tag_is_no_spelling(decoy: str) -> None:
    text = f"@prefix : <{NS}> .\n{decoy}\n:b :s \"colour\"@en-GB .\n"
    saved = quiet(Ontology(), text).serialize("ntriples")
    assert b'"colour"@en-GB' in saved and b"@EN-gb ." not in saved


def test_xml_text_and_comments_that_look_like_xml_lang_are_no_spelling() -> None:
    text = f"""<?xml version="1.0"?>
<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:m="{NS}">
  <!-- an old version had xml:lang="EN-gb" here -->
  <rdf:Description rdf:about="{NS}a"><m:note>write xml:lang="EN-gb" on it</m:note></rdf:Description>
  <rdf:Description rdf:about="{NS}b"><m:s xml:lang="en-GB">colour</m:s></rdf:Description>
</rdf:RDF>
"""
    assert b'"colour"@en-GB' in quiet(Ontology(), text, "xml").serialize("ntriples")


# ---------------------------------------------------------------- the other ways in than a document
def mapped() -> Ontology:
    """The TBox of :data:`TURTLE` without its literals (no spelling learned from a document)."""
    return quiet(Ontology(), f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
                 "<http://e.org/lang> a owl:Ontology . :s a owl:DatatypeProperty . :x a owl:NamedIndividual .\n")


@pytest.mark.parametrize("way", ["add", "add_new", "change", "add_data", "add_fact", "replace"])
def test_the_python_api_keeps_the_spelling_given_with_a_value(way: str) -> None:
    o = mapped()
    colour = o.value("colour", language="en-GB")
    assert colour.language == "en-gb"  # pyoxigraph's literal, lowered: the store's value is unchanged
    fact = o.fact("x", "s", colour)
    {"add": lambda: o.add(fact), "add_new": lambda: o.add_new(fact), "change": lambda: o.change([fact], []),
     "add_data": lambda: o.add_data("s", "x", colour), "add_fact": lambda: o.add_fact("x", "s", colour),
     "replace": lambda: o.replace("x", "s", colour)}[way]()
    assert b'"colour"@en-GB' in o.serialize("ntriples")
    assert [v.language for v in o.data_values("s", "x")] == ["en-gb"]


def test_a_value_made_but_never_asserted_spells_nothing() -> None:
    """A spelling given to ``value`` waits for a literal of its tag to be asserted: a document loaded first spells it."""
    o = mapped()
    o.value("colour", language="EN-gb")
    quiet(o, f'@prefix : <{NS}> . :x :s "grey"@en-GB .')
    o.add_data("s", "x", o.value("colour", language="EN-gb"))
    saved = o.serialize("ntriples")
    assert b'"colour"@en-GB' in saved and b'"grey"@en-GB' in saved and b"EN-gb" not in saved


def test_the_first_spelling_wins_over_a_value_given_later() -> None:
    o = quiet(mapped(), f'@prefix : <{NS}> . :x :s "a"@en-gb .')
    o.add_data("s", "x", o.value("b", language="EN-GB"))
    assert b'"b"@en-gb' in o.serialize("ntriples")


def test_a_bad_tag_is_refused_and_changes_nothing() -> None:
    o = mapped()
    with pytest.raises(InvalidValueError, match="language tag"):
        o.value("colour", language="en GB")
    with pytest.raises(InvalidValueError, match="not both"):
        o.value("colour", datatype="string", language="en-GB")
    assert not o.store.forms.tags


def test_a_durable_store_keeps_a_spelling_given_through_the_api(tmp_path: Path) -> None:
    o = Ontology(store=tmp_path / "db")
    o.add_data("s", "x", o.value("colour", language="en-GB"))
    o.store.close()
    assert b'"colour"@en-GB' in Ontology(store=tmp_path / "db").serialize("ntriples")


def sparql_update(o: Ontology, text: str) -> None:
    """A SPARQL update run as the HTTP service runs one (sparql.execute.run_update)."""
    run_update(Reference("ref", o, "http://e.org/lang"), text, Job(time.monotonic() + 60), 60.0)


@pytest.mark.parametrize("update", [
    f'INSERT DATA {{ <{NS}x> <{NS}s> "colour"@en-GB }}',
    f'PREFIX : <{NS}> INSERT {{ ?x :s "colour"@en-GB }} WHERE {{ ?x a <http://www.w3.org/2002/07/owl#NamedIndividual> }}',
])
def test_a_sparql_update_keeps_the_spelling_of_what_it_inserts(update: str, tmp_path: Path) -> None:
    o = Ontology(store=tmp_path / "db")
    quiet(o, f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
          "<http://e.org/lang> a owl:Ontology . :s a owl:DatatypeProperty . :x a owl:NamedIndividual .\n")
    sparql_update(o, update)
    assert b'"colour"@en-GB' in o.serialize("ntriples")
    o.store.close()
    assert b'"colour"@en-GB' in Ontology(store=tmp_path / "db").serialize("ntriples")


def test_a_tag_an_update_only_deletes_or_matches_is_no_spelling() -> None:
    o = quiet(mapped(), f'@prefix : <{NS}> . :x :s "old"@fr .')
    sparql_update(o, f'PREFIX : <{NS}> DELETE DATA {{ :x :s "old"@FR }} ; '
                  f'INSERT {{ :x :s "new"@fr-CA }} WHERE {{ FILTER(LANG("a"@EN-US) != "") }}')
    saved = o.serialize("ntriples")
    assert b'"new"@fr-CA' in saved and b"@FR" not in saved


def test_armor_replies_spell_a_tag_a_sparql_update_wrote(tmp_path: Path) -> None:
    path = tmp_path / "lang.ttl"
    path.write_text(f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
                    "<http://e.org/lang> a owl:Ontology . :s a owl:DatatypeProperty . :x a owl:NamedIndividual .\n")
    service = ArmorService()
    assert armor_load(service, path, "http://e.org/lang").success
    run_update(service.reference("ref"), f'INSERT DATA {{ <{NS}x> <{NS}s> "colour"@en-GB }}',
               Job(time.monotonic() + 60), 60.0)
    reply = service.call({"client_name": "c", "reference_name": "ref", "command": "QUERY",
                          "primary_command_spec": "DATAPROP", "secondary_command_spec": "IND", "args": ["s", "x"]})
    assert reply.queried_objects == ['"colour"@en-GB']


def test_the_graph_store_keeps_the_spelling_of_an_upload(tmp_path: Path) -> None:
    with in_process(config(tmp_path / "data", allow_update=True)) as server:
        status, _, reply = server.request("/references/lang/data?default", TURTLE.encode(),
                                          {"Content-Type": "text/turtle"}, "PUT")
        assert status == 201, reply
        added = f'<{NS}y> <{NS}s> "grey"@en-AU .\n'.encode()
        status, _, reply = server.request("/references/lang/data?default", added,
                                          {"Content-Type": "application/n-triples"}, "POST")
        assert status == 200, reply
        assert server.ok("QUERY", "DATAPROP", "IND", ["s", "y"], ref="lang")["queried_objects"] == ['"grey"@en-AU']


def test_a_refused_sparql_update_learns_no_spelling() -> None:
    o = mapped()
    with pytest.raises(Exception, match="integer"):
        sparql_update(o, f'INSERT DATA {{ <{NS}x> <{NS}s> "colour"@en-GB . <{NS}x> <{NS}n> '
                      '"many"^^<http://www.w3.org/2001/XMLSchema#integer> }')
    assert not o.store.forms.tags
    o.add_data("s", "x", "colour")
    assert o.store.count(ASSERTED) == 4


# ---------------------------------------------------------------- a spelling only from what a change added
@pytest.mark.parametrize(("update", "kept"), [
    # a DELETE template spells the tag before the INSERT template that adds the literal
    (f'PREFIX : <{NS}> DELETE {{ ?x :s "gone"@EN-gb }} INSERT {{ ?x :s "new"@en-GB }} WHERE {{ ?x :s "old" }}',
     b'"new"@en-GB'),
    # an earlier operation writes a literal of that tag which a later one deletes: not what is stored
    (f'PREFIX : <{NS}> INSERT DATA {{ :x :s "a"@EN-GB . :y :s "b"@en-gb }} ; DELETE DATA {{ :x :s "a"@en-gb }}',
     b'"b"@en-gb'),
    # a pattern of an earlier operation
    (f'PREFIX : <{NS}> DELETE WHERE {{ ?x :s "zz"@EN-GB }} ; INSERT DATA {{ :x :s "c"@en-gb }}', b'"c"@en-gb'),
    # the literal written in the WHERE's VALUES and inserted through a variable
    (f'PREFIX : <{NS}> INSERT {{ :x :s ?l }} WHERE {{ VALUES ?l {{ "colour"@en-GB }} }}', b'"colour"@en-GB'),
    # the same literal in a WHERE first and in the INSERT template: the INSERT's spelling
    (f'PREFIX : <{NS}> INSERT {{ ?x :s "new"@en-GB }} WHERE {{ ?x :s "old" OPTIONAL {{ ?x :s "new"@EN-gb }} }}',
     b'"new"@en-GB'),
    # STRLANG's tag argument, its literal's form being nowhere written
    (f'PREFIX : <{NS}> INSERT {{ :x :s ?l }} WHERE {{ BIND(STRLANG("colour", "en-GB") AS ?l) }}', b'"colour"@en-GB'),
    # a STRLANG call whose first argument nests calls, or holds a comma or a parenthesis in a string
    (f'PREFIX : <{NS}> INSERT {{ :x :s ?l }} WHERE {{ BIND(STRLANG(CONCAT(STR("a"), "b"), "en-GB") AS ?l) }}',
     b'"ab"@en-GB'),
    (f'PREFIX : <{NS}> INSERT {{ :x :s ?l }} WHERE {{ BIND(STRLANG("a,b)", \'en-GB\') AS ?l) }}', b'"a,b)"@en-GB'),
    # an escaped lexical form is compared as read
    (f'PREFIX : <{NS}> INSERT DATA {{ :x :s "tab\\there"@EN-gb . :y :s "tab\\u0009here"@en-GB }}',
     b'"tab\\there"@EN-gb'),
])
def test_an_update_spells_a_tag_only_from_a_literal_it_added(update: str, kept: bytes, tmp_path: Path) -> None:
    o = quiet(Ontology(store=tmp_path / "db"), f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
              "<http://e.org/lang> a owl:Ontology . :s a owl:DatatypeProperty . :x a owl:NamedIndividual .\n"
              ':y a owl:NamedIndividual . :x :s "old" .\n')
    sparql_update(o, update)
    assert kept in o.serialize("ntriples")
    o.store.close()
    assert kept in Ontology(store=tmp_path / "db").serialize("ntriples")  # the spelling persisted is that one


@pytest.mark.parametrize("how", ["upload", "load"])
def test_a_json_ld_document_keeps_its_spellings(how: str, tmp_path: Path) -> None:
    doc = json.dumps([{"@id": NS + "y", NS + "s": {"@value": "grey", "@language": "en-AU"}},
                      {"@context": {"@language": "fr-CA"}, "@id": NS + "z", NS + "s": "gris"}]).encode()
    if how == "load":
        path = tmp_path / "doc.jsonld"
        path.write_bytes(doc)
        o = mapped()
        o.load(path)
        saved = o.serialize("ntriples")
        assert b'"grey"@en-AU' in saved and b'"gris"@fr-CA' in saved
        return
    with in_process(config(tmp_path / "data", allow_update=True)) as server:
        status, _, reply = server.request("/references/lang/data?default", TURTLE.encode(),
                                          {"Content-Type": "text/turtle"}, "PUT")
        assert status == 201, reply
        status, _, reply = server.request("/references/lang/data?default", doc,
                                          {"Content-Type": "application/ld+json"}, "POST")
        assert status == 200, reply
        assert server.ok("QUERY", "DATAPROP", "IND", ["s", "y"], ref="lang")["queried_objects"] == ['"grey"@en-AU']
        assert server.ok("QUERY", "DATAPROP", "IND", ["s", "z"], ref="lang")["queried_objects"] == ['"gris"@fr-CA']


def test_a_spelling_given_to_a_value_never_asserted_is_not_the_stores() -> None:
    o = mapped()
    o.remove_fact("x", "s", o.value("a", language="EN-gb"))  # nothing asserted
    o.add_data("s", "x", o.value("b", language="en-GB"))
    saved = o.serialize("ntriples")
    assert b'"b"@en-GB' in saved and b"EN-gb" not in saved


def test_a_spelling_given_to_one_value_is_not_taken_by_another_literal() -> None:
    o = mapped()
    o.value("a", language="EN-GB")
    o.add_data("s", "x", Literal("c", language="en-gb"))
    assert b'"c"@en-gb' in o.serialize("ntriples")
    o.add_data("s", "x", o.value("a", language="EN-GB"))  # that value asserted: its spelling now
    assert b'"a"@EN-GB' in o.serialize("ntriples")


def test_an_assertion_a_unit_of_work_undoes_spells_nothing() -> None:
    o = mapped()
    o.reason()
    with pytest.raises(RuntimeError), o.ledger.undoable(o):
        o.add_data("s", "x", o.value("d", language="EN-gb"))
        raise RuntimeError("a later step failed")
    assert not o.store.forms.tags
    o.add_data("s", "x", o.value("e", language="en-GB"))
    assert b'"e"@en-GB' in o.serialize("ntriples")


def test_a_unit_of_work_that_succeeds_keeps_the_spelling_and_an_inner_undo_only_its_own() -> None:
    o = mapped()
    with o.ledger.undoable(o):
        o.add_data("s", "x", o.value("kept", language="en-GB"))
        with pytest.raises(RuntimeError), o.ledger.undoable(o):
            o.add_data("s", "x", o.value("undone", language="fr-CA"))
            raise RuntimeError("an inner step failed")
        assert not o.store.forms.tags  # held until the outermost unit ends
    saved = o.serialize("ntriples")
    assert b'"kept"@en-GB' in saved and b"undone" not in saved and not o.store.forms.tags.known("fr-ca")


@pytest.mark.parametrize(("accept", "written"), [
    ("application/n-triples", b'"colour"@en-GB'), ("text/turtle", b'"colour"@en-GB'),
    ("application/rdf+xml", b'xml:lang="en-GB"'), ("application/ld+json", b'"@language": "en-GB"'),
])
def test_a_graph_store_read_spells_tags_as_loaded(accept: str, written: bytes, tmp_path: Path) -> None:
    with in_process(config(tmp_path / "data", allow_update=True)) as server:
        status, _, reply = server.request("/references/lang/data?default", TURTLE.encode(),
                                          {"Content-Type": "text/turtle"}, "PUT")
        assert status == 201, reply
        status, _, body = server.request("/references/lang/data?default", None, {"Accept": accept}, "GET")
        assert status == 200 and written in body and b"en-gb" not in body, body[:400]


# ---------------------------------------------------------------- respelling never touches a string's text
TRICKY = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
<http://e.org/lang> a owl:Ontology . :s a owl:DatatypeProperty . :x a owl:NamedIndividual .
:x :s "colour"@en-GB , "q" , "@en-gb is a tag" , "b\\"@en-gb" , "\\\\" , "@en-gb next" , "@fr-ca"@fr-CA .
:x :s \"\"\"a long
string "@en-gb" with "quotes\\" @en-gb\"\"\" , "q2" , "@en-gb" , "x"@en-gb , "<@en-gb>" .
"""


FORMATS = {"turtle": RdfFormat.TURTLE, "ntriples": RdfFormat.N_TRIPLES, "xml": RdfFormat.RDF_XML,
           "json-ld": RdfFormat.JSON_LD, "nquads": RdfFormat.N_QUADS, "trig": RdfFormat.TRIG}


def literals_of(data: bytes, fmt: RdfFormat) -> set[tuple[str, str | None]]:
    """Each literal a document holds (its text and its lowered tag), the tags checked spelled as first written."""
    if fmt == RdfFormat.RDF_XML:
        assert b'xml:lang="en-GB"' in data and b'xml:lang="fr-CA"' in data and b'xml:lang="en-gb"' not in data
    elif fmt == RdfFormat.JSON_LD:
        assert b'"@language": "en-GB"' in data and b'"@language": "fr-CA"' in data and b'"en-gb"' not in data
    else:
        assert b'"colour"@en-GB' in data and b'"x"@en-GB' in data and b'"@fr-ca"@fr-CA' in data
    return {(q.object.value, q.object.language) for q in parse(data, fmt) if isinstance(q.object, Literal)}


WRITTEN = {(q.object.value, q.object.language) for q in parse(TRICKY.encode(), RdfFormat.TURTLE)
           if isinstance(q.object, Literal)}


@pytest.mark.parametrize("fmt", list(FORMATS))
def test_respelling_changes_no_strings_text(fmt: str) -> None:
    assert ("@en-gb is a tag", None) in WRITTEN and ('b"@en-gb', None) in WRITTEN
    o = quiet(Ontology(), TRICKY)
    assert literals_of(o.serialize(FORMATS[fmt]), FORMATS[fmt]) == WRITTEN


@pytest.mark.parametrize("accept", ["text/turtle", "application/n-triples", "application/rdf+xml",
                                    "application/ld+json"])
def test_a_graph_store_read_changes_no_strings_text(accept: str, tmp_path: Path) -> None:
    fmt = {"text/turtle": RdfFormat.TURTLE, "application/n-triples": RdfFormat.N_TRIPLES,
           "application/rdf+xml": RdfFormat.RDF_XML, "application/ld+json": RdfFormat.JSON_LD}[accept]
    with in_process(config(tmp_path / "data", allow_update=True)) as server:
        status, _, reply = server.request("/references/lang/data?default", TRICKY.encode(),
                                          {"Content-Type": "text/turtle"}, "PUT")
        assert status == 201, reply
        status, _, body = server.request("/references/lang/data?default", None, {"Accept": accept}, "GET")
        assert status == 200, body[:400]
    assert WRITTEN <= literals_of(body, fmt)


# ---------------------------------------------------------------- a failed REASON reverts a spelling with its literal
TOO_LARGE = too_large_axiom(NS)


def failed_reason(o: Ontology) -> None:
    """A REASON that fails (an axiom too large to evaluate): every asserted change since the last good one reverted."""
    o.add(*TOO_LARGE)
    with pytest.raises(RuleCompileError, match="too large"):
        o.reason()


@pytest.mark.parametrize("durable", [False, True])
def test_a_failed_reason_drops_the_spelling_of_a_literal_it_reverts(durable: bool, tmp_path: Path) -> None:
    o = mapped() if not durable else quiet(Ontology(store=tmp_path / "db"), mapped().serialize("turtle").decode())
    o.reason()
    o.add_data("s", "x", o.value("colour", language="en-GB"))
    assert o.store.forms.tags.known("en-gb")
    failed_reason(o)
    assert not o.store.forms.tags.known("en-gb") and b"colour" not in o.serialize("ntriples")
    o.add_data("s", "x", Literal("grey", language="en-gb"))  # written lowered: no reverted spelling for it
    assert b'"grey"@en-gb' in o.serialize("ntriples")
    if durable:
        o.store.close()
        assert b'"grey"@en-gb' in Ontology(store=tmp_path / "db").serialize("ntriples")
    else:  # the value given again, asserted by a change that stays: its spelling now
        o.add_data("s", "x", o.value("colour", language="en-GB"))
        assert b'"colour"@en-GB' in o.serialize("ntriples")


def test_a_failed_reason_inside_a_unit_drops_the_spellings_it_held() -> None:
    o = mapped()
    o.reason()
    with o.ledger.undoable(o):
        o.add_data("s", "x", o.value("before", language="en-GB"))  # a step before the inner unit's start
        with pytest.raises(RuleCompileError), o.ledger.undoable(o):
            o.add_data("s", "x", o.value("inner", language="fr-CA"))
            o.add(*TOO_LARGE)
            o.reason()
    assert not o.store.forms.tags and b"before" not in o.serialize("ntriples")


def test_a_failed_reason_keeps_the_spelling_of_a_literal_asserted_before_the_last_good_one() -> None:
    o = mapped()
    o.reason()
    with o.ledger.undoable(o):
        o.add_data("s", "x", o.value("kept", language="en-GB"))
        o.reason()
        o.add_data("s", "x", o.value("gone", language="fr-CA"))
        failed_reason(o)
    saved = o.serialize("ntriples")
    assert b'"kept"@en-GB' in saved and b"gone" not in saved and not o.store.forms.tags.known("fr-ca")


# ---------------------------------------------------------------- a document's spelling only from a literal it added
ADDED_ONLY = {
    RdfFormat.TURTLE: f'<{NS}x> <{NS}s> "old"@EN-gb , "new"@en-GB .',
    RdfFormat.RDF_XML: f"""<?xml version="1.0"?><rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#"
 xmlns:l="{NS}"><rdf:Description rdf:about="{NS}x" xml:lang="EN-gb"><l:s>old</l:s>
 <l:s rdf:resource="{NS}y"/><l:s xml:lang="en-GB">new</l:s></rdf:Description></rdf:RDF>""",
    RdfFormat.JSON_LD: json.dumps([{"@context": {"@language": "EN-gb"}, "@id": NS + "x", NS + "s": "old"},
                                   {"@id": NS + "x", NS + "s": [{"@value": "new", "@language": "en-GB"}]}]),
}


@pytest.mark.parametrize("fmt", list(ADDED_ONLY), ids=lambda f: f.name)
def test_a_document_spells_a_tag_only_from_a_literal_the_change_added(fmt: RdfFormat) -> None:
    from topostore.stores.language_tags import LanguageTags
    tags = LanguageTags()
    assert tags.learn(ADDED_ONLY[fmt].encode(), fmt, only={("new", "en-gb")}) == ["en-GB"]
    assert LanguageTags().learn(ADDED_ONLY[fmt].encode(), fmt, only={("old", "en-gb")}) == ["EN-gb"]


def test_the_spellings_waiting_for_their_literal_are_bounded() -> None:
    from topostore.ontology.values import PENDING
    o = mapped()
    first = o.value("first", language="EN-gb")
    for i in range(PENDING + 50):
        o.value(f"reading {i}", language="en-GB")  # made to query or remove, never asserted
    assert len(o.values._pending) == PENDING
    o.add_data("s", "x", first)  # the oldest was dropped: its spelling no longer waits
    o.add_data("s", "x", o.value(f"reading {PENDING + 49}", language="en-GB"))  # a recent one still does
    saved = o.serialize("ntriples")
    assert b'"first"@en-GB' in saved and b"EN-gb" not in saved


def test_json_ld_literals_are_read_in_the_order_written() -> None:
    """Nested value objects and properties come out in document order (the first spelling wins)."""
    import json

    from topostore.stores.written_tags import json_ld_literals

    doc = {"@id": "http://ex.org/x#r1",
           "http://ex.org/x#a": [{"@value": "colour", "@language": "en-GB"},
                                 {"@value": "colour", "@language": "en-gb"}],
           "http://ex.org/x#b": {"@value": "y", "@language": "fr-CA"}}
    assert json_ld_literals(json.dumps(doc).encode()) == [("colour", "en-GB"), ("colour", "en-gb"), ("y", "fr-CA")]


def test_a_literal_made_again_counts_as_made_now_among_the_waiting_spellings() -> None:
    from topostore import Ontology
    from topostore.ontology.values import PENDING

    onto = Ontology(prefix="http://ex.org/x#")
    onto.value("colour", language="en-GB")
    for i in range(PENDING - 1):
        onto.value(f"v{i}", language="fr-CA")
    made = onto.value("colour", language="en-GB")  # made again: among the last PENDING made
    onto.value("one more", language="fr-CA")
    onto.add_fact("r1", "label", made)
    assert onto.store.forms.tags.spelled("en-gb") == "en-GB"


@pytest.mark.parametrize("way", ["document", "sparql update", "buffered sparql update"])
def test_a_failed_reason_drops_a_spelling_a_document_or_an_update_brought(way: str) -> None:
    """A spelling read from a document or an update's text goes with the literals a failed REASON reverts,
    also where a literal asserted before carries its tag: that one is shown as it was before."""
    o = mapped()
    o.add_data("s", "x", Literal("kept", language="fr-ca"))
    o.reason()
    if way == "document":
        quiet(o, f'<{NS}x> <{NS}s> "colour"@en-GB , "bonjour"@FR-ca .')
    else:
        ref = Reference("ref", o, "http://e.org/lang", buffered_reasoner=way.startswith("buffered"))
        run_update(ref, f'INSERT DATA {{ <{NS}x> <{NS}s> "colour"@en-GB , "bonjour"@FR-ca }}',
                   Job(time.monotonic() + 60), 60.0)
        if not ref.buffered_reasoner:  # reasoned with the update: its spellings stay with its literals
            failed_reason(o)
            assert b'"colour"@en-GB' in o.serialize("ntriples")
            return
    assert o.store.forms.tags.known("en-gb") and o.store.forms.tags.spelled("fr-ca") == "FR-ca"
    failed_reason(o)
    saved = o.serialize("ntriples")
    assert b"colour" not in saved and not o.store.forms.tags.known("en-gb")
    assert b'"kept"@fr-ca' in saved and b"FR-ca" not in saved
    o.add_data("s", "x", Literal("grey", language="en-gb"))
    assert b'"grey"@en-gb' in o.serialize("ntriples")


@pytest.mark.parametrize("accept", ["application/sparql-results+json", "application/sparql-results+xml",
                                    "text/tab-separated-values", "text/turtle", "application/n-triples"])
def test_sparql_query_answers_spell_tags_as_written(accept: str, tmp_path: Path) -> None:
    """SELECT and CONSTRUCT answers over HTTP spell a tag as its literal was written (pyoxigraph lowers it)."""
    query = (f"CONSTRUCT {{ ?x <{NS}s> ?v }} WHERE {{ ?x <{NS}s> ?v }}" if "results" not in accept and
             "tab" not in accept else f"SELECT ?v WHERE {{ ?x <{NS}s> ?v }}")
    with in_process(config(tmp_path / "data", allow_update=True)) as server:
        status, _, reply = server.request("/references/lang/data?default", TURTLE.encode(),
                                          {"Content-Type": "text/turtle"}, "PUT")
        assert status == 201, reply
        status, _, body = server.sparql_get(query, accept, ref="lang")
        assert status == 200, body[:400]
    assert b"en-GB" in body and b"EN-us" in body and b"de-CH" in body, body[:600]
    assert b"en-gb" not in body.replace(b'\\"@en-GB\\"', b"") and b"en-us" not in body


@pytest.mark.parametrize("first, second", [("long", "integer"), ("integer", "long")])
def test_a_graph_store_upload_respelling_a_stored_value_says_so_and_counts_nothing(first: str, second: str,
                                                                                    tmp_path: Path) -> None:
    """A PUT that spells a stored value otherwise (``"7"^^xsd:integer`` where ``"7"^^xsd:long`` was written)
    changes nothing: the reply counts nothing added or removed and says which spelling stays, whichever of
    the two the store keeps as its canonical form; a POST of it adds nothing either, and says so too."""
    head = f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . <http://e.org/lang> a owl:Ontology . "
    xsd = "http://www.w3.org/2001/XMLSchema#"
    with in_process(config(tmp_path / "data", allow_update=True)) as server:
        def upload(kind: str, method: str) -> dict:
            doc = head + f':x :s "7"^^<{xsd}{kind}> .'
            status, _, reply = server.request("/references/lang/data?default", doc.encode(),
                                              {"Content-Type": "text/turtle"}, method)
            assert status in (200, 201), reply
            return json.loads(reply)

        upload(first, "PUT")
        for method in ("PUT", "POST"):
            body = upload(second, method)
            assert body["added"] == 0 and body["removed"] == 0, body
            assert any("stays as written" in w for w in body["warnings"]), body
            _, _, saved = server.request("/references/lang/data?default", None, {"Accept": "application/n-triples"})
            assert f'"7"^^<{xsd}{first}>'.encode() in saved


def test_a_graph_store_upload_writing_one_value_twice_counts_and_says_it_once(tmp_path: Path) -> None:
    """``"07"^^xsd:long`` and ``"7"^^xsd:integer`` in one document are one value: the upload is read with the
    first spelling of each value, so over a stored ``"7"^^xsd:long`` the reply counts nothing and the
    spelling it says stays is the one that does."""
    head = f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . <http://e.org/lang> a owl:Ontology . "
    xsd = "http://www.w3.org/2001/XMLSchema#"
    with in_process(config(tmp_path / "data", allow_update=True)) as server:
        def put(values: str) -> dict:
            status, _, reply = server.request("/references/lang/data?default", (head + f":x :s {values} .").encode(),
                                              {"Content-Type": "text/turtle"}, "PUT")
            assert status in (200, 201), reply
            return json.loads(reply)

        put(f'"7"^^<{xsd}long>')
        body = put(f'"07"^^<{xsd}long> , "7"^^<{xsd}integer>')
        assert body["added"] == 0 and body["removed"] == 0, body
        assert len(body["warnings"]) == 1 and f'"7"^^<{xsd}long> stays as written' in body["warnings"][0], body
        _, _, saved = server.request("/references/lang/data?default", None, {"Accept": "application/n-triples"})
    assert f'"7"^^<{xsd}long>'.encode() in saved and b'"07"' not in saved
