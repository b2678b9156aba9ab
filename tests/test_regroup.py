"""A rule's heads diffed where one atom's value is cleanly replaced (reason/regroup.py): equal to from scratch
and to the general DRed run over histories mixing replacements with other changes, and used where it applies."""

from __future__ import annotations

from unittest import mock

from hypothesis import given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import NamedNode, Triple
from swrl_support import NS, PREFIXES, obj, rule
from test_step_program import assert_as_from_scratch, toggle, turtle

from topostore.rdf.vocab import INFERRED, INTERNAL, SKOLEM_PREFIX
from topostore.reason import emit, look_join

#: ``Join`` (``p``'s subject in the head) is ``r``'s one prover, whose heads feed a class (``C``) and a
#: transitive property (``u``, a recursive component); ``Twice`` reads two single-valued atoms; ``v`` has two
#: provers (``Also`` from ``w``), so its part keeps DRed
TBOX = PREFIXES + f"""
:A a owl:Class . :C a owl:Class ; rdfs:subClassOf :A .
:p a owl:ObjectProperty . :q a owl:ObjectProperty . :k a owl:ObjectProperty . :w a owl:ObjectProperty .
:r a owl:ObjectProperty ; rdfs:range :C . :t a owl:ObjectProperty . :v a owl:ObjectProperty .
:u a owl:ObjectProperty , owl:TransitiveProperty .
{rule([obj(':p', '?x', '?y'), obj(':q', '?y', '?z')], [obj(':r', '?x', '?z')], 'Join')}
{rule([obj(':r', '?x', '?z')], [obj(':u', '?x', '?z')], 'Feed')}
{rule([obj(':p', '?x', '?y'), obj(':k', '?x', '?z'), obj(':q', '?y', '?z')], [obj(':t', '?x', '?y')], 'Twice')}
{rule([obj(':p', '?x', '?y'), obj(':q', '?y', '?z')], [obj(':v', '?x', '?z')], 'Two')}
{rule([obj(':w', '?x', '?z')], [obj(':v', '?x', '?z')], 'Also')}
"""

NAMES = [f"i{n}" for n in range(4)]


def N(name: str) -> NamedNode:
    return NamedNode(NS + name)


def _derived(onto) -> set:
    """The inferred facts without a skolemised term or a key made from one (two loads name those apart)."""
    return {t for t in onto.store.triples(graph=INFERRED)
            if not any(n in f"{t.subject} {t.object}" for n in (SKOLEM_PREFIX, INTERNAL + "key:"))}


def _apply(onto, op: tuple) -> None:
    """``replace``: a subject's one ``p`` or ``k`` value replaced (a clean replacement where it had one);
    else a fact toggled (``q``, ``w``, a second ``p`` value, an asserted head ``r``)."""
    kind, p, a, b = op
    if kind == "replace":
        onto.replace(N(a), N(p), N(b))
    else:
        toggle(onto, Triple(N(a), N(p), N(b)))


replaces = st.tuples(st.just("replace"), st.sampled_from(["p", "k"]), st.sampled_from(NAMES[:2]), st.sampled_from(NAMES))
toggles = st.tuples(st.just("toggle"), st.sampled_from(["q", "w", "p", "r"]), st.sampled_from(NAMES), st.sampled_from(NAMES))


@settings(max_examples=property_examples(20), deadline=None)
@given(batches=st.lists(st.lists(st.one_of(replaces, replaces, toggles), min_size=1, max_size=3), min_size=1,
                        max_size=5),
       whole=st.booleans())
def test_regrouped_heads_equal_from_scratch_and_the_general_run(batches: list, whole: bool) -> None:
    """Each REASON's graphs as from scratch, and as a reasoner without the diff (its DRed) has them; ``whole``:
    the program as one request (as on a remote store, where no look-up runs)."""
    onto, general = turtle(TBOX), turtle(TBOX)
    for o in (onto, general):
        for s in NAMES[:2]:
            o.replace(N(s), N("p"), N("i2"))
            o.replace(N(s), N("k"), N("i3"))
        o.add(Triple(N("i2"), N("q"), N("i3")))
        o.reason()
    onto._reasoner.store.round_trips = whole
    for batch in batches:
        for op in batch:
            _apply(onto, op)
            _apply(general, op)
        report = onto.reason(mode="incremental")
        assert_as_from_scratch(onto, report, consistency=False)
        with mock.patch.object(emit, "regroupable", lambda *a: False):
            general._reasoner.step.programs.clear()
            general.reason(mode="incremental")
        assert _derived(general) == _derived(onto)


def test_a_replaced_value_diffs_the_heads_of_its_keys_one_prover_and_keeps_dred_for_two() -> None:
    """Moving ``i0``'s ``p`` value: ``r`` (one prover) is diffed, no candidate of it rechecked; ``v`` (two
    provers, ``w`` having facts) has its candidates rechecked; every REASON as from scratch."""
    onto = turtle(TBOX)
    onto.replace(N("i0"), N("p"), N("i1"))
    for z in ("i2", "i3"):
        onto.add(Triple(N("i1"), N("q"), N(z)))
    onto.add(Triple(N("i2"), N("q"), N("i0")))
    onto.add(Triple(N("i3"), N("w"), N("i0")))
    onto.reason()
    rechecked: list = []
    originals = {name: getattr(look_join.Joined, name) for name in ("delete", "keep")}

    def spied(name):
        def run(self, store):
            rechecked.append(self.rule.head.read_key()[1])
            return originals[name](self, store)
        return run

    with mock.patch.multiple(look_join.Joined, delete=spied("delete"), keep=spied("keep")):
        for target in ("i2", "i1", "i2", "i0", "i1"):
            onto.replace(N("i0"), N("p"), N(target))
            report = onto.reason(mode="incremental")
            assert report.stats.program == "compiled"
            assert_as_from_scratch(onto, report)
    assert f"<{NS}r>" not in rechecked and f"<{NS}v>" in rechecked
