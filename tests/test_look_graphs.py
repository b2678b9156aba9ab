"""The graphs a look-up operation reads an atom from (reason/look_join.StateGraphs): every graph a rule may
have written the atom's key to, and no other."""

from __future__ import annotations

from topostore.compile.rule import Atom, Rule
from topostore.rdf.vocab import ASSERTED, AUX, INFERRED, TYPE
from topostore.reason.look_join import StateGraphs

T = str(TYPE)


def _rule(name: str, head: Atom, aux: bool | None = None) -> Rule:
    return Rule(name, "test", (Atom("?x", "<urn:x:p>", "?y"),), head, aux_head=aux)


def test_a_key_no_rule_writes_is_read_from_the_asserted_graph_alone() -> None:
    graphs = StateGraphs([_rule("q", Atom("?x", "<urn:x:q>", "?y")),
                          _rule("c", Atom("?x", T, "<urn:x:C>")),
                          _rule("h", Atom("?x", "<urn:x:h>", "?y"), aux=True)])
    assert graphs.of(Atom("?a", "<urn:x:clock>", "?t")) == (ASSERTED,)
    assert graphs.of(Atom("?a", "<urn:x:q>", "?t")) == (ASSERTED, INFERRED)
    assert graphs.of(Atom("?a", T, "<urn:x:C>")) == (ASSERTED, INFERRED)
    assert graphs.of(Atom("?a", T, "<urn:x:D>")) == (ASSERTED,)
    assert graphs.of(Atom("?a", "<urn:x:h>", "?t")) == (ASSERTED, AUX)
    assert graphs.of(Atom("?a", T, "?c")) == (ASSERTED, INFERRED)  # any class: C's rule writes some
    assert graphs.of(Atom("?a", "?p", "?o")) == (ASSERTED, INFERRED, AUX)
    assert graphs.of(Atom("?a", "<urn:x:clock>", "?t", aux=True)) == (AUX,)


def test_rules_writing_any_predicate_or_any_class_reach_every_key_they_may_match() -> None:
    graphs = StateGraphs([_rule("types", Atom("?x", T, "?c"))])
    assert graphs.of(Atom("?a", T, "<urn:x:C>")) == (ASSERTED, INFERRED)
    assert graphs.of(Atom("?a", "<urn:x:clock>", "?t")) == (ASSERTED,)
    graphs = StateGraphs([_rule("same-as", Atom("?x", "?p", "?y"))])
    assert graphs.of(Atom("?a", "<urn:x:clock>", "?t")) == (ASSERTED, INFERRED)
    assert graphs.of(Atom("?a", T, "<urn:x:C>")) == (ASSERTED, INFERRED)
