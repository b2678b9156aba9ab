"""A manipulation's path through the ontology and the store: ``Ontology.change`` (one delta, one
transaction) and the terms made for it (``rdf.terms.triple`` / ``quad``), checked against what
the separate retraction and assertion did before."""

from __future__ import annotations

import pytest
from pyoxigraph import Quad, Triple
from support import names, typed

from topostore import Ontology
from topostore.errors import InvalidValueError
from topostore.ontology.changes import SpellingKeptWarning
from topostore.rdf import terms
from topostore.rdf.vocab import ASSERTED, TYPE

EX = "http://example.org/change#"
n = names(EX)
TBOX = f"""@prefix : <{EX}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
:Robot a owl:Class . :speed a owl:DatatypeProperty . :at a owl:ObjectProperty .
"""


@pytest.fixture
def onto() -> Ontology:
    o = Ontology(prefix=EX)
    o.load_data(TBOX)
    o.add(Triple(n("r1"), TYPE, n("Robot")), Triple(n("r1"), n("speed"), typed("7", "long")),
          Triple(n("r1"), n("at"), n("a")))
    o.reason()
    return o


def asserted(onto: Ontology, p: str) -> list:
    return sorted(str(t.object) for t in onto.store.triples(n("r1"), n(p), None, ASSERTED))


@pytest.fixture
def armor():
    """A call to an in-process aRMOR service (``armor(command, spec1, spec2, args)``), closed after the test."""
    from topostore.armor import ArmorService

    service = ArmorService()

    def call(command: str, spec1: str, spec2: str, args: list[str]):
        return service.call({"client_name": "c", "reference_name": "r", "command": command,
                             "primary_command_spec": spec1, "secondary_command_spec": spec2, "args": args})
    yield call
    service.close()


def loaded_by_armor(armor, tmp_path, data: str) -> None:
    """LOAD of the TBox and ``data`` through ``armor``."""
    path = tmp_path / "o.ttl"
    path.write_text(TBOX + data)
    assert armor("LOAD", "FILE", "", [str(path), EX.rstrip("#"), "false", "PELLET", "true"]).success


def test_terms_made_equal_the_constructors_and_literal_ones_are_kept() -> None:
    lit = typed("12", "long")
    made = terms.triple(n("s"), n("p"), lit)
    assert made == Triple(n("s"), n("p"), lit)
    assert terms.triple(n("s"), n("p"), typed("12", "long")) is made  # the same value made again: kept
    assert terms.triple(n("s"), n("p"), typed("012", "long")) != made  # another spelling is another term
    q = terms.quad(n("s"), n("p"), lit, n("g"))
    assert q == Quad(n("s"), n("p"), lit, n("g")) and terms.quad(n("s"), n("p"), lit, n("g")) is q
    assert terms.triple(n("s"), n("p"), n("o")) == Triple(n("s"), n("p"), n("o")) and \
        terms.quad(n("s"), n("p"), n("o"), n("g")) == Quad(n("s"), n("p"), n("o"), n("g"))


def test_change_removes_then_adds_and_the_ledger_nets_them(onto: Ontology) -> None:
    added, removed = onto.change([Triple(n("r1"), n("speed"), typed("8", "long"))],
                                 [Triple(n("r1"), n("speed"), typed("7", "long"))])
    assert [t.object.value for t in added] == ["8"] and [t.object.value for t in removed] == ["7"]
    assert asserted(onto, "speed") == [str(typed("8", "integer"))]
    assert onto.dirty
    net_added, net_removed = onto.ledger.net_changes()
    assert len(net_added) == 1 and len(net_removed) == 1
    # and back: the ledger's record cancels out, the literal keeps the form it was written in
    onto.change([Triple(n("r1"), n("speed"), typed("7", "long"))], [Triple(n("r1"), n("speed"), typed("8", "long"))])
    assert onto.ledger.net_changes() == ([], [])
    assert [str(v) for v in onto.data_values("speed", "r1")] == [str(typed("7", "long"))]


def test_change_of_a_value_to_itself_keeps_it(onto: Ontology) -> None:
    """Removed, then added again in the same transaction: present afterwards, nothing to reason, and
    reported as what it is, no change."""
    same = Triple(n("r1"), n("speed"), typed("7", "long"))
    added, removed = onto.change([same], [same])
    assert added == [] and removed == []
    assert asserted(onto, "speed") == [str(typed("7", "integer"))]
    assert onto.ledger.net_changes() == ([], [])


def test_change_deduplicates_and_reports_only_what_changed(onto: Ontology) -> None:
    new = Triple(n("r1"), n("at"), n("b"))
    added, removed = onto.change([new, new, Triple(n("r1"), n("at"), n("a"))], [Triple(n("r1"), n("at"), n("zz"))])
    assert added == [new] and removed == []
    assert asserted(onto, "at") == [f"<{EX}a>", f"<{EX}b>"]


def test_change_with_an_invalid_value_changes_nothing(onto: Ontology) -> None:
    bad = Triple(n("r1"), n("speed"), typed("fast", "long"))
    with pytest.raises(InvalidValueError):
        onto.change([bad], [Triple(n("r1"), n("at"), n("a"))])
    assert asserted(onto, "at") == [f"<{EX}a>"] and asserted(onto, "speed") == [str(typed("7", "integer"))]
    assert onto.ledger.net_changes() == ([], [])


def test_a_value_swapped_for_another_spelling_is_kept_and_said(onto: Ontology) -> None:
    """Removing ``7`` and adding ``"7.0"^^xsd:decimal`` in one change nets out in the store (literals are keyed
    by value): the asserted graph keeps ``7``, so the report and the ledger hold nothing, and a named warning
    says which spelling stayed."""
    with pytest.warns(SpellingKeptWarning, match="stays as written"):
        added, removed = onto.change([Triple(n("r1"), n("speed"), typed("7.0", "decimal"))],
                                     [Triple(n("r1"), n("speed"), typed("7", "long"))])
    assert (added, removed) == ([], [])
    assert asserted(onto, "speed") == [str(typed("7", "integer"))]
    assert onto.ledger.net_changes() == ([], [])


def test_a_spelling_of_one_stored_form_swapped_is_kept_and_said(onto: Ontology) -> None:
    """``"0100"`` and ``"100"`` as xsd:long are one stored form: replaced in one change they cancel in the
    ledger, so the spelling written first stays; the change reports nothing done and says so."""
    first = Triple(n("r1"), n("count"), typed("0100", "long"))
    onto.change([first], [])
    with pytest.warns(SpellingKeptWarning, match="stays as written"):
        added, removed = onto.change([Triple(n("r1"), n("count"), typed("100", "long"))], [first])
    assert (added, removed) == ([], [])
    assert [str(v) for v in onto.data_values("count", "r1")] == [str(typed("0100", "long"))]


def test_an_armor_replace_by_another_spelling_says_which_stays(armor, tmp_path) -> None:
    """REPLACE DATAPROP of ``3`` by ``"3.0"^^xsd:decimal``: the reply says the spelling ``3`` stayed."""
    loaded_by_armor(armor, tmp_path, ":r1 :speed 3 .")
    reply = armor("REPLACE", "DATAPROP", "IND", ["speed", "r1", "decimal", "3.0", "3"])
    assert reply.success and "stays as written" in reply.error_description
    assert armor("QUERY", "DATAPROP", "IND", ["speed", "r1"]).queried_objects == ['"3"^^xsd:integer']


def test_one_value_replaced_by_another_that_takes_back_an_earlier_removal_says_the_spelling_kept(
        onto: Ontology) -> None:
    """One value removed and one of another value added (a REPLACE's shape), where the added one, written as
    ``"7.0"^^xsd:decimal``, takes back the removal of ``"7"^^xsd:long`` earlier in the transaction: the store
    keeps ``7`` as it was, and the change says so (the shape alone does not say the added spelling was
    stored)."""
    nine = Triple(n("r1"), n("speed"), typed("9", "long"))
    onto.change([nine], [])
    with pytest.warns(SpellingKeptWarning, match="removed and added in one transaction"), onto.store.transaction():
        onto.remove(Triple(n("r1"), n("speed"), typed("7", "long")))
        added, removed = onto.change([Triple(n("r1"), n("speed"), typed("7.0", "decimal"))], [nine])
    assert removed == [nine] and len(added) == 1
    assert asserted(onto, "speed") == [str(typed("7", "integer"))]
    assert [str(v) for v in onto.data_values("speed", "r1")] == [str(typed("7", "long"))]


def test_an_armor_replace_finds_the_old_and_the_new_value_among_several(armor, tmp_path) -> None:
    """REPLACE reads every value of the pair once: the old one is removed whatever its place among them, a
    new one held already is not added again (no warning of an old value missing), and an individual's
    REPLACE compares individuals, a value's compares values (``"5"^^xsd:long`` is ``5``)."""
    loaded_by_armor(armor, tmp_path, ":r1 :speed 3 , 5 , 8 . :r1 :at :a , :b , :c .")
    reply = armor("REPLACE", "DATAPROP", "IND", ["speed", "r1", "long", "5", "8"])
    assert reply.success and reply.error_description == ""
    assert armor("REASON", "", "", []).success  # a buffered reasoner answers a removed value until REASON
    assert armor("QUERY", "DATAPROP", "IND", ["speed", "r1"]).queried_objects == \
        ['"3"^^xsd:integer', '"5"^^xsd:integer']
    reply = armor("REPLACE", "OBJECTPROP", "IND", ["at", "r1", "c", "a"])
    assert reply.success and reply.error_description == ""
    assert armor("REASON", "", "", []).success
    assert armor("QUERY", "OBJECTPROP", "IND", ["at", "r1"]).queried_objects == [f"<{EX}b>", f"<{EX}c>"]
    reply = armor("REPLACE", "OBJECTPROP", "IND", ["at", "r1", "d", "a"])  # a is gone: d added, b, c kept
    assert reply.success and "was not asserted" in reply.error_description
    assert armor("REASON", "", "", []).success
    assert armor("QUERY", "OBJECTPROP", "IND", ["at", "r1"]).queried_objects == \
        [f"<{EX}b>", f"<{EX}c>", f"<{EX}d>"]
