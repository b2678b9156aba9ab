"""The floor of each way to tell a pair apart, by hand: ``python -m benchmarks.difference_floor N [--reps R]``.

A full REASON of the chain maps (:mod:`benchmarks.maps`) spends most of its difference work on two
things: the AllDifferent test of Connectability's conclusion (two key look-ups per door pair) and
the entailed-only twin of that conclusion (the pairs asked of the value rules, ``ts:valueCandidate``;
their difference by visit times, ``ts:different``; the twin itself), which publishes nothing on these
maps because every pair is declared different.  Before a rule form is changed, the same work is
written by hand and timed on the reasoned store: each variant is one ``INSERT`` into a scratch graph
(dropped before each run), the variants alternated ``R`` times, the CPU median printed as JSON with
the number of quads each wrote, so a cheaper form that writes a different set shows it.

Variants (``NAME``: what it does):

* ``keys``: the AllDifferent keys as the rules write them on these maps, whose asserted graph holds one
  member list (``rules/one-list/all-different-key.rq``: the member its own key); ``keys_by_list``: as
  ``rules/all-different-key.rq`` writes them where there are more lists (two MD5s, a new IRI per
  member); ``keys_typed``: a literal key ``STR(member)^^group`` (no hash, no new string: the
  member's string and the group's IRI are in the store already); ``groups``: the group node alone per
  member (what the hand-written floor reads; it cannot tell a member's ``owl:sameAs`` alias from
  another member);
* ``pairs``: the door pairs alone (the body without any difference); ``pairs_keys``: with the key
  test as the rule runs it (look-ups and the group's string test); ``pairs_keys_sameterm``: the
  look-ups with only ``!sameTerm`` of the keys (the string test's share); ``pairs_typed``: the typed
  keys' test (``sameTerm(DATATYPE(..))``); ``pairs_groups``: the group-node join;
* ``twin_candidates``, ``twin_values``, ``twin``: the three evaluations of the entailed-only twin as
  the rules ran them for every door pair (each reading the one before in the scratch graph; since
  :mod:`topostore.reason.negation` a full REASON asks only pairs whose conclusion is not known);
  ``twin_joined``: the twin with the visit-time test in its body (one rule);
* ``candidates_undeclared``: the asked pairs less the pairs whose ordinary conclusion is known (a
  ``MINUS`` of the inferred head): what the value rules would need to be asked if the candidates
  left out declared pairs; ``candidates_not_grouped``: the same by ``FILTER NOT EXISTS`` over the keys.

The last two are not monotone (a withdrawn declaration must add a candidate): docs/benchmarks-history.md
says what keeping them would need of the robot step.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
import warnings

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, AUX, INFERRED, INTERNAL, OWL, RDF

from . import maps
from .limits import lift_time_limit

SCRATCH = f"<{INTERNAL}graph:floor-scratch>"
A, I, X = f"<{ASSERTED.value}>", f"<{INFERRED.value}>", f"<{AUX.value}>"
#: the dataset every rule of a full REASON is evaluated over, plus the scratch graph by name
USING = f"USING {A} USING {I} USING {X} USING NAMED {X} USING NAMED {A} USING NAMED {I} USING NAMED {SCRATCH}"
KEY, VALUE_CANDIDATE, DIFFERENT = f"<{INTERNAL}differentKey>", f"<{INTERNAL}valueCandidate>", f"<{INTERNAL}different>"
#: the helper graph's keys, key first (the scratch forms above keep the member first)
KEY_OF = f"<{INTERNAL}differentKeyOf>"
M = maps.MAP_NS
MEMBERS = f"<{OWL}distinctMembers>|<{OWL}members>"
LIST = f"<{RDF}rest>*/<{RDF}first>"
GROUP_OF = 'STRBEFORE(STRAFTER(STR({k}), "urn:topostore:key:"), ":")'
DOOR_PAIRS = (f"GRAPH {A} {{ ?l2 <{M}hasDoor> ?d . }} GRAPH {A} {{ ?l1 <{M}hasDoor> ?d . }} "
              "FILTER(!isLiteral(?d)) FILTER(!sameTerm(?l1, ?l2))")
VALUES_DIFFER = (f"GRAPH {A} {{ ?l1 <{M}visitedAt> ?v1 . }} GRAPH {A} {{ ?l2 <{M}visitedAt> ?v2 . }} "
                 "FILTER((!sameTerm(?v1, ?v2) && COALESCE(?v1 != ?v2, true)))")


def _insert(head: str, where: str) -> str:
    return f"INSERT {{ GRAPH {SCRATCH} {{ {head} }} }} {USING} WHERE {{ {where} }}"


def _keyed(where_keys: str, test: str) -> str:
    """The door pairs with ``where_keys`` (``?l1``/``?l2`` to ``?k1``/``?k2``) and ``test``."""
    return _insert(f"?l1 <{M}connectedTo> ?l2", f"{DOOR_PAIRS} {where_keys} FILTER({test})")


def _member_key(bind: str) -> str:
    """The keys of the members of each AllDifferent's member list ``?group`` (the group is the list)."""
    return _insert(f"?x {KEY} ?key", f"GRAPH {A} {{ ?node a <{OWL}AllDifferent> }} ?node {MEMBERS} ?group . "
                   f"?group {LIST} ?x . BIND({bind} AS ?key)")


#: the twin's evaluations as the rules ran them before :mod:`topostore.reason.negation`, each reading
#: the one before it in the scratch graph (the helper graph now holds none of these facts for door pairs)
_CANDIDATES = _insert(f"?l1 {VALUE_CANDIDATE} ?l2", DOOR_PAIRS)
_VALUES = _insert(f"?l1 {DIFFERENT} ?l2", f"GRAPH {SCRATCH} {{ ?l1 {VALUE_CANDIDATE} ?l2 . }} {VALUES_DIFFER}")
#: variant name → (setup updates into the scratch graph, the timed update)
VARIANTS: dict[str, tuple[tuple[str, ...], str]] = {
    "keys": ((), _member_key("?x")),
    "keys_by_list": ((), _member_key('IRI(CONCAT("urn:topostore:key:", MD5(STR(?group)), ":", MD5(STR(?x))))')),
    "keys_typed": ((), _member_key("STRDT(STR(?x), ?group)")),
    "groups": ((), _member_key("?group")),
    "pairs": ((), _insert(f"?l1 <{M}connectedTo> ?l2", DOOR_PAIRS)),
    "pairs_keys": ((), _keyed(f"GRAPH {X} {{ ?k1 {KEY_OF} ?l1 . ?k2 {KEY_OF} ?l2 . }}",
                              f"!sameTerm(?k1, ?k2) && {GROUP_OF.format(k='?k1')} = {GROUP_OF.format(k='?k2')}")),
    "pairs_keys_sameterm": ((), _keyed(f"GRAPH {X} {{ ?k1 {KEY_OF} ?l1 . ?k2 {KEY_OF} ?l2 . }}", "!sameTerm(?k1, ?k2)")),
    "pairs_typed": ((_member_key("STRDT(STR(?x), ?group)"),),
                    _keyed(f"GRAPH {SCRATCH} {{ ?l1 {KEY} ?k1 . ?l2 {KEY} ?k2 . }}",
                           "!sameTerm(?k1, ?k2) && sameTerm(DATATYPE(?k1), DATATYPE(?k2))")),
    "pairs_groups": ((_member_key("?group"),),
                     _keyed(f"GRAPH {SCRATCH} {{ ?l1 {KEY} ?g . ?l2 {KEY} ?g . }}", "true")),
    "twin_candidates": ((), _CANDIDATES),
    "twin_values": ((_CANDIDATES,), _VALUES),
    "twin": ((_CANDIDATES, _VALUES), _insert(f"?l1 <{M}connectedTo> ?l2",
                                             f"{DOOR_PAIRS} GRAPH {SCRATCH} {{ ?l1 {DIFFERENT} ?l2 . }}")),
    "twin_joined": ((), _insert(f"?l1 <{M}connectedTo> ?l2", f"{DOOR_PAIRS} {VALUES_DIFFER}")),
    "candidates_undeclared": ((), _insert(f"?l1 {VALUE_CANDIDATE} ?l2",
                                          f"{DOOR_PAIRS} MINUS {{ GRAPH {I} {{ ?l1 <{M}connectedTo> ?l2 }} }}")),
    "candidates_not_grouped": ((), _insert(
        f"?l1 {VALUE_CANDIDATE} ?l2",
        f"{DOOR_PAIRS} FILTER NOT EXISTS {{ GRAPH {X} {{ ?k1 {KEY_OF} ?l1 . ?k2 {KEY_OF} ?l2 . }} "
        f"FILTER(!sameTerm(?k1, ?k2) && {GROUP_OF.format(k='?k1')} = {GROUP_OF.format(k='?k2')}) }}")),
}


def measure(onto: Ontology, names: list[str], reps: int) -> dict[str, dict[str, object]]:
    """CPU seconds (median, all runs) and quads written of each variant, alternated ``reps`` times."""
    store = onto.store
    runs: dict[str, list[float]] = {n: [] for n in names}
    written: dict[str, int] = {}
    for _ in range(reps):
        for name in names:
            setup, timed = VARIANTS[name]
            store.update(f"DROP SILENT GRAPH {SCRATCH}")
            for text in setup:
                store.update(text)
            before = _count(onto)
            start = time.process_time()
            store.update(timed)
            runs[name].append(time.process_time() - start)
            written[name] = _count(onto) - before
    store.update(f"DROP SILENT GRAPH {SCRATCH}")
    return {n: {"cpu_s": round(statistics.median(runs[n]), 4), "runs_s": [round(t, 4) for t in runs[n]],
                "quads": written[n]} for n in names}


def written_by(onto: Ontology, name: str) -> set[tuple[str, str, str]]:
    """The (subject, predicate, object) values variant ``name`` writes (for the tests: each variant
    said to run as a rule runs writes what the rule wrote)."""
    store = onto.store
    store.update(f"DROP SILENT GRAPH {SCRATCH}")
    setup, timed = VARIANTS[name]
    for text in setup:
        store.update(text)
    before = _scratch(onto)  # the setup's own facts are not the variant's
    store.update(timed)
    out = _scratch(onto) - before
    store.update(f"DROP SILENT GRAPH {SCRATCH}")
    return out


def _scratch(onto: Ontology) -> set[tuple[str, str, str]]:
    rows = onto.store.query(f"SELECT ?s ?p ?o WHERE {{ GRAPH {SCRATCH} {{ ?s ?p ?o }} }}")
    return {(r["s"].value, r["p"].value, r["o"].value) for r in rows}


def _count(onto: Ontology) -> int:
    rows = onto.store.query(f"SELECT (COUNT(*) AS ?n) WHERE {{ GRAPH {SCRATCH} {{ ?s ?p ?o }} }}")
    return int(next(iter(rows))["n"].value)


def run(size: str, names: list[str], reps: int) -> dict[str, object]:
    """Load map ``size``, reason in full, and measure ``names``."""
    onto, _ = maps.loaded(size)
    start = time.process_time()
    report = onto.reason(mode="full")
    reasoned = time.process_time() - start
    entailed = onto.store.query(f"SELECT (COUNT(*) AS ?n) WHERE {{ GRAPH <{INTERNAL}graph:entailed> {{ ?s ?p ?o }} }}")
    return {"size": size, "reason_cpu_s": round(reasoned, 3), "consistent": report.consistent,
            "entailed_published": int(next(iter(entailed))["n"].value), "load_average": os.getloadavg(),
            "variants": measure(onto, names, reps)}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.difference_floor", description=__doc__.split("\n")[0])
    parser.add_argument("size", help="a map of benchmarks.maps: example or a number of locations")
    parser.add_argument("--reps", type=int, default=3, help="runs of each variant, alternated")
    parser.add_argument("--only", nargs="*", choices=sorted(VARIANTS), help="the variants to run (default: all)")
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore")
    lift_time_limit()
    json.dump(run(args.size, args.only or list(VARIANTS), args.reps), sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
