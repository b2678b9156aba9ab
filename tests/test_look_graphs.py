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


def test_a_change_is_derivable_only_where_a_rule_that_can_fire_writes_one_of_its_keys() -> None:
    """The keys of asserted facts (:func:`key_census`) a rule may have inferred: only those facts are
    discarded from the inferred and helper graphs when they are asserted.  A rule one of whose premises
    never had a fact (``present``) never fired."""
    graphs = StateGraphs([_rule("q", Atom("?x", "<urn:x:q>", "?y")),
                          _rule("c", Atom("?x", T, "<urn:x:C>")),
                          _rule("h", Atom("?x", "<urn:x:h>", "?y"), aux=True)])
    present = ({"<urn:x:p>"}, set())
    assert not graphs.derived(({"<urn:x:clock>": 1, "<urn:x:p>": 2}, {}), present)
    assert graphs.derived(({"<urn:x:clock>": 1, "<urn:x:q>": 1}, {}), present)
    grows: tuple[set, set] = (set(), set())
    assert not graphs.derived(({"<urn:x:clock>": 1, "<urn:x:q>": 1}, {}), grows)  # :p never had facts
    grows[0].add("<urn:x:p>")  # asked again once the keys with facts grew
    assert graphs.derived(({"<urn:x:clock>": 1, "<urn:x:q>": 1}, {}), grows)
    assert graphs.derived(({"<urn:x:h>": 1}, {}), present)
    assert graphs.derived(({T: 1}, {"<urn:x:C>": 1}), present)
    assert not graphs.derived(({T: 1}, {"<urn:x:D>": 1}), present)  # rdf:type alone is no key: its classes are
    assert StateGraphs([_rule("types", Atom("?x", T, "?c"))]).derived(({T: 1}, {"<urn:x:D>": 1}), present)
    same_as = StateGraphs([Rule("eq-rep", "test", (Atom("?x", "<urn:x:same>", "?z"), Atom("?x", "?p", "?y")),
                                Atom("?z", "?p", "?y"))])
    assert not same_as.derived(({"<urn:x:clock>": 1}, {}), present)
    assert same_as.derived(({"<urn:x:clock>": 1}, {}), ({"<urn:x:same>"}, set()))


def test_a_look_up_reads_the_graphs_of_the_rules_that_can_have_fired_and_notes_what_left_one_out() -> None:
    """:meth:`StateGraphs.firing`: owl:sameAs replacement writes any predicate, but a rule whose premise had
    no fact since the last full run (nor gets one from the change) never wrote it: the clock is read from the
    asserted graph alone, and the premise joins ``absent`` (the program is compiled again once it has
    facts).  A premise with facts, or one the change gives some, keeps the graph."""
    same_as = Rule("eq-rep", "test", (Atom("?x", "<urn:x:same>", "?z"), Atom("?x", "?p", "?y")), Atom("?z", "?p", "?y"))
    graphs = StateGraphs([same_as, _rule("h", Atom("?x", "<urn:x:h>", "?y"), aux=True)])
    clock, helper = Atom("?a", "<urn:x:clock>", "?t"), Atom("?a", "<urn:x:h>", "?t")
    absent: set = set()
    assert graphs.firing(clock, ({"<urn:x:p>"}, set()), set(), absent) == (ASSERTED,)
    assert absent == {("p", "<urn:x:same>")}
    assert graphs.firing(helper, ({"<urn:x:p>"}, set()), set(), set()) == (ASSERTED, AUX)
    assert graphs.firing(clock, ({"<urn:x:same>"}, set()), set(), set()) == (ASSERTED, INFERRED)
    assert graphs.firing(clock, (set(), set()), {("p", "<urn:x:same>")}, set()) == (ASSERTED, INFERRED)
    assert graphs.firing(Atom("?a", "?p", "?o"), (set(), set()), set(), set()) == graphs.of(Atom("?a", "?p", "?o"))
