"""A SPARQL update keeps each literal it adds as written *for that triple*.

The update's delta is computed on a scratch Oxigraph store, which keeps numbers canonical (``"100"^^xsd:int`` as
``"100"^^xsd:integer``, ``1.50`` as ``1.5``); :mod:`topostore.sparql.written` gives each added literal back the
spelling the insert template wrote at its position.  A literal written elsewhere (another triple, a FILTER, a
DELETE) spells nothing added, and a value a WHERE binds from the store keeps the spelling the store holds.  A
value VALUES or BIND gives a variable keeps the spelling written there, and a blank node's values theirs.
"""

from __future__ import annotations

import time

import pytest
from fuzz_support import count_case, fuzz_settings
from hypothesis import given
from hypothesis import strategies as st
from pyoxigraph import Literal, NamedNode, RdfFormat, parse
from support import reasoned_turtle

from topostore import Ontology
from topostore.armor.reference import Reference
from topostore.rdf.vocab import XSD
from topostore.sparql.execute import Job, run_update
from topostore.sparql.written import may_respell

NS = "http://example.org/spelled#"
PROPS = ["battery", "level", "p0", "p1", "p2", "p3", "old"]
HEAD = (f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . "
        f"@prefix xsd: <{XSD}> .\n" + " ".join(f":{p} a owl:DatatypeProperty ." for p in PROPS) + "\n")
PROLOGUE = f"PREFIX xsd: <{XSD}> PREFIX k: <{NS}> "


def ontology(data: str = "") -> Ontology:
    return reasoned_turtle(HEAD + data)


def update(o: Ontology, text: str) -> None:
    run_update(Reference("ref", o, NS), text, Job(time.monotonic() + 60), 60.0)


def values(o: Ontology, prop: str, subject: str) -> list[Literal]:
    return o.data_values(NamedNode(NS + prop), NamedNode(NS + subject))


def written(spelling: str) -> Literal:
    """The literal ``spelling`` writes (as a Turtle load keeps it)."""
    triples = list(parse(f"@prefix xsd: <{XSD}> . <x:s> <x:p> {spelling} .", RdfFormat.TURTLE))
    assert isinstance(triples[0].object, Literal)
    return triples[0].object


def typed(lexical: str, datatype: str) -> Literal:
    return Literal(lexical, datatype=NamedNode(XSD + datatype))


#: name -> (update, r's battery, s's level)
CASES = {
    "a_bare_integer_beside_an_int_of_the_same_value": (
        'INSERT DATA { k:r k:battery 100 . k:s k:level "100"^^xsd:int }', [typed("100", "integer")], [typed("100", "int")]),
    "an_explicit_integer_beside_a_long": (
        'INSERT DATA { k:r k:battery "100"^^xsd:integer . k:s k:level "100"^^xsd:long }',
        [typed("100", "integer")], [typed("100", "long")]),
    "a_typed_literal_only_in_a_filter": (
        'INSERT { k:r k:battery 7 } WHERE { FILTER(7 = "7"^^xsd:short) }', [typed("7", "integer")], []),
    "a_typed_literal_only_in_a_delete": (
        'DELETE DATA { k:s k:level "3"^^xsd:byte } ; INSERT DATA { k:r k:battery 3 }', [typed("3", "integer")], []),
}


@pytest.mark.parametrize("name", list(CASES))
def test_each_added_literal_keeps_the_spelling_written_for_it(name: str) -> None:
    text, r_battery, s_level = CASES[name]
    o = ontology()
    update(o, PROLOGUE + text)
    assert values(o, "battery", "r") == r_battery
    assert values(o, "level", "s") == s_level


def test_a_saved_ontology_shows_each_updated_literal_as_written() -> None:
    o = ontology()
    update(o, PROLOGUE + 'INSERT DATA { k:r k:battery 100 . k:s k:level "100"^^xsd:int }')
    saved = o.serialize("ntriples").decode()
    assert f'<{NS}r> <{NS}battery> "100"^^<{XSD}integer> .' in saved
    assert f'<{NS}s> <{NS}level> "100"^^<{XSD}int> .' in saved


@pytest.mark.parametrize("spelling", ["1.50", "1e0", "007", "+5", "-0", ".5", '"007"^^xsd:integer',
                                      '"1.50"^^xsd:decimal'])
def test_an_update_keeps_a_bare_number_as_a_load_does(spelling: str) -> None:
    loaded = ontology(f"<{NS}r> <{NS}battery> {spelling} .")
    updated = ontology()
    update(updated, PROLOGUE + f"INSERT DATA {{ k:r k:battery {spelling} }}")
    assert values(updated, "battery", "r") == values(loaded, "battery", "r") == [written(spelling)]


def test_a_value_bound_from_the_store_keeps_its_held_spelling() -> None:
    o = ontology(f'<{NS}q> <{NS}level> "6"^^xsd:long, 1.50 .')
    update(o, PROLOGUE + 'INSERT { k:s k:level ?v } WHERE { k:q k:level ?v FILTER(?v != "7"^^xsd:short) }')
    assert sorted(values(o, "level", "s"), key=str) == sorted([typed("6", "long"), typed("1.50", "decimal")], key=str)
    update(o, PROLOGUE + 'INSERT { k:t k:level ?v } WHERE { k:q k:level ?v FILTER(?v = 6) }')
    assert values(o, "level", "t") == [typed("6", "long")]


@pytest.mark.parametrize("held", ["6.0", '"6"^^xsd:long', '"6"^^xsd:double', '"06"^^xsd:integer'])
@pytest.mark.parametrize("also", ["", " . k:r k:p0 1.50"])
def test_a_value_written_in_the_template_keeps_its_spelling_beside_a_held_one(held: str, also: str) -> None:
    """The store holding the value in another spelling (of another subject) does not respell what the
    template wrote, whether or not the text is read for spellings (a bare 6 stays xsd:integer)."""
    o = ontology(f"<{NS}q> <{NS}level> {held} .")
    update(o, PROLOGUE + f"INSERT DATA {{ k:r k:battery 6{also} }}")
    assert values(o, "battery", "r") == [typed("6", "integer")]


@pytest.mark.parametrize("where", ['VALUES ?v { "007"^^xsd:long }', 'VALUES (?s ?v) { (k:q "007"^^xsd:long) }',
                                   'BIND("007"^^xsd:long AS ?v)'])
def test_a_value_bound_by_values_or_bind_keeps_its_spelling(where: str) -> None:
    o = ontology()
    update(o, PROLOGUE + f"INSERT {{ k:r k:battery ?v }} WHERE {{ {where} }}")
    assert values(o, "battery", "r") == [typed("007", "long")]


@pytest.mark.parametrize("where", [
    'k:q k:battery ?v OPTIONAL { k:nothing k:p0 ?w BIND("007"^^xsd:long AS ?v) }',
    'k:q k:battery ?v { SELECT ?x WHERE { VALUES ?v { "007"^^xsd:long } BIND(1 AS ?x) } }',
    '{ k:q k:battery ?v } UNION { VALUES ?v { "007"^^xsd:long } FILTER(false) }',
    'k:q k:battery ?v FILTER NOT EXISTS { VALUES ?v { "007"^^xsd:long } k:nothing k:p0 ?v }'])
def test_a_value_bound_inside_a_nested_group_does_not_respell_one_from_the_store(where: str) -> None:
    """A VALUES or BIND inside an OPTIONAL, a subquery, a UNION branch or EXISTS may bind none of the rows
    inserted: the value the WHERE matched in the store keeps the store's spelling (xsd:int, not xsd:long)."""
    o = ontology(f'<{NS}q> <{NS}battery> "7"^^xsd:int .')
    update(o, PROLOGUE + f"INSERT {{ k:r k:level ?v }} WHERE {{ {where} }}")
    assert values(o, "level", "r") == [typed("7", "int")]


def test_a_value_bound_only_in_another_operation_spells_nothing() -> None:
    o = ontology()
    update(o, PROLOGUE + 'INSERT { k:q k:level ?v } WHERE { BIND("1.50"^^xsd:decimal AS ?v) } ; '
                         "INSERT { k:r k:battery ?v } WHERE { BIND(1.5 AS ?v) }")
    assert values(o, "level", "q") == [typed("1.50", "decimal")]
    assert values(o, "battery", "r") == [typed("1.5", "decimal")]


def test_a_value_computed_in_bind_has_no_spelling_in_the_text() -> None:
    o = ontology()
    update(o, PROLOGUE + 'INSERT { k:r k:battery ?v } WHERE { BIND("007"^^xsd:long + 0 AS ?v) }')
    assert values(o, "battery", "r") == [typed("7", "integer")]


def blank_values(o: Ontology) -> list[str]:
    saved = o.serialize("ntriples").decode().splitlines()
    return sorted(line.split(" ", 2)[2] for line in saved if line.startswith("_:") and f"<{NS}battery>" in line)


@pytest.mark.parametrize("nodes", ['k:s k:old [ k:battery "007"^^xsd:long ]', '_:b k:battery "007"^^xsd:long',
                                   '[ k:battery "007"^^xsd:long ] . k:s k:battery "7"^^xsd:int'])
def test_a_blank_nodes_value_keeps_its_spelling(nodes: str) -> None:
    o = ontology()
    update(o, PROLOGUE + f"INSERT DATA {{ {nodes} }}")
    assert blank_values(o) == [f'"007"^^<{XSD}long> .']


def test_two_blank_nodes_holding_one_value_keep_a_spelling_each() -> None:
    o = ontology()
    update(o, PROLOGUE + 'INSERT DATA { k:s k:old [ k:battery "007"^^xsd:long ], [ k:battery "7"^^xsd:int ] }')
    assert blank_values(o) == [f'"007"^^<{XSD}long> .', f'"7"^^<{XSD}int> .']


def test_a_template_at_the_triples_own_subject_spells_it_before_one_under_a_variable() -> None:
    o = ontology()
    update(o, PROLOGUE + 'INSERT { ?s k:battery "6"^^xsd:long . k:r k:battery "6"^^xsd:int } '
                         "WHERE { VALUES ?s { k:q } }")
    assert values(o, "battery", "r") == [typed("6", "int")]
    assert values(o, "battery", "q") == [typed("6", "long")]


def test_the_last_operation_that_wrote_a_triple_spells_it() -> None:
    o = ontology()
    update(o, PROLOGUE + 'INSERT DATA { k:r k:battery "6"^^xsd:long } ; DELETE DATA { k:r k:battery "6"^^xsd:long } ; '
                         'INSERT DATA { k:r k:battery "6"^^xsd:int }')
    assert values(o, "battery", "r") == [typed("6", "int")]


def test_a_plain_update_is_not_read_for_spellings() -> None:
    assert not may_respell(PROLOGUE + "INSERT DATA { k:r100 k:battery 100 ; k:level -2.5, 0 }")
    assert may_respell(PROLOGUE + "INSERT DATA { k:r k:battery 1.50 }")
    assert may_respell(PROLOGUE + 'INSERT DATA { k:r k:battery "5"^^xsd:long }')


def spellings(n: int) -> list[str]:
    """Spellings of the value ``n`` (some of one stored term, some of another datatype)."""
    return [str(n), f"0{n}", f"+{n}", f'"{n}"^^xsd:int', f'"{n}"^^xsd:long', f'"0{n}"^^xsd:integer',
            f'"{n}"^^<{XSD}short>', f"{n}.0", f"{n}.50", f"{n}e0", f'"{n}.0"^^xsd:decimal']


@st.composite
def spelled_updates(draw: st.DrawFn) -> tuple[str, dict[tuple[str, str], str]]:
    """An INSERT DATA or DELETE/INSERT/WHERE text writing one value in several spellings at several positions
    (distinct subjects and predicates), with other spellings of it in a DELETE and a FILTER; the spelling
    written at each position."""
    n = draw(st.integers(min_value=1, max_value=9))
    words = spellings(n)
    positions = draw(st.lists(st.tuples(st.sampled_from(["a", "b", "c"]), st.sampled_from(["p0", "p1", "p2", "p3"])),
                              min_size=1, max_size=5, unique=True))
    at = {pos: draw(st.sampled_from(words)) for pos in positions}
    other = draw(st.sampled_from(words))
    form = draw(st.sampled_from(["data", "subjects bound", "values bound"]))
    if form == "data":
        body = " ".join(f"k:{s} k:{p} {w} ." for (s, p), w in at.items())
        text = f"DELETE DATA {{ k:a k:old {other} }} ; INSERT DATA {{ {body} }}"
    elif form == "subjects bound":  # the subjects through variables bound by VALUES
        body = " ".join(f"?{s} k:{p} {w} ." for (s, p), w in at.items())
        text = (f"DELETE {{ k:a k:old {other} }} INSERT {{ {body} }} "
                f"WHERE {{ VALUES (?a ?b ?c) {{ (k:a k:b k:c) }} FILTER({other} = {other}) }}")
    else:  # the values through variables, each bound by VALUES (one variable or a row of several) or BIND
        body = " ".join(f"k:{s} k:{p} ?v{i} ." for i, (s, p) in enumerate(at))
        binds = [draw(st.sampled_from(["values", "row", "bind"])) for _ in at]
        row = [i for i, b in enumerate(binds) if b == "row"]
        where = [f"VALUES ?v{i} {{ {w} }}" if b == "values" else f"BIND({w} AS ?v{i})"
                 for i, (b, w) in enumerate(zip(binds, at.values(), strict=True)) if b != "row"]
        if row:
            words = list(at.values())
            where.append(f"VALUES ({' '.join(f'?v{i}' for i in row)}) {{ ({' '.join(words[i] for i in row)}) }}")
        text = (f"DELETE {{ k:a k:old {other} }} INSERT {{ {body} }} "
                f"WHERE {{ {' '.join(where)} FILTER({other} = {other}) }}")
    return PROLOGUE + text, at


@fuzz_settings(0.06)
@given(spelled_updates())
def test_every_added_literal_is_spelled_as_written_at_its_position(case: tuple[str, dict[tuple[str, str], str]]) -> None:
    count_case()
    text, at = case
    o = ontology()
    update(o, text)
    for (s, p), spelling in at.items():
        assert values(o, p, s) == [written(spelling)], (text, s, p)
