"""What the AllDifferent keys cost a full REASON, form by form: ``python -m benchmarks.full_keys SIZE [--reps N]``.

Two evaluations of a full REASON on the chain maps are about the AllDifferent keys: ``all-different``
(``rules/all-different-key.rq``: a key per member, found through the list walk) and the connecting
SWRL rule joined with ``rules/different-by-group.rq`` (two key look-ups per pair of locations sharing a
door, then the test that both keys name one group).  Before the key's form is changed, each part and
each candidate form is timed here on the same reasoned store, in one process, the forms in turns
(``--reps`` rounds), as ``SELECT (COUNT(*))`` over the WHERE the reasoner sends (the census's graphs):

* the join: as compiled (each key found from its member as an object, ``?k ts:differentKeyOf ?x``);
  without the key atoms (its floor); the group as a term of its own (``?x inGroup ?g`` twice, no
  string test: the floor of a key whose group is compared by term equality); the keys looked up by
  their member as a subject (``?x key ?k``, the form before: a location holds far more quads as a
  subject than as an object, and the in-memory store walks a term's quads to look one up); the keys
  joined by hash (each key atom its own subquery);
* the key's making: the list walk alone, the walk with its ``rdf:first``, the key with two MD5s, with the
  group's MD5 only, with no MD5, the member its own key (the one-list form), and each written into a
  scratch graph.

The alternative forms' facts are written into scratch graphs made from the reasoned helper graph (not
timed) and dropped at the end; topostore's own graphs are only read.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
import warnings

from topostore.rdf.vocab import ASSERTED, AUX, DIFFERENT_KEY_OF, KEY_PREFIX

from . import maps
from .limits import lift_time_limit

_OWL = "http://www.w3.org/2002/07/owl#"
_RDF = "http://www.w3.org/1999/02/22-rdf-syntax-ns#"
_SCRATCH = "urn:topostore:bench:keys:"
_HAS_DOOR = f"<{maps.MAP_NS}hasDoor>"
_A, _X, _K = f"<{ASSERTED.value}>", f"<{AUX.value}>", f"<{DIFFERENT_KEY_OF.value}>"
_SUBJ, _GRP, _OUT = f"<{_SCRATCH}subject>", f"<{_SCRATCH}group>", f"<{_SCRATCH}out>"
_KEY, _IN_GROUP = f"<{_SCRATCH}key>", f"<{_SCRATCH}inGroup>"
_GROUP_TEST = (f'STRBEFORE(STRAFTER(STR(?k1), "{KEY_PREFIX}"), ":") = '
               f'STRBEFORE(STRAFTER(STR(?k2), "{KEY_PREFIX}"), ":")')
_DOORS = f"GRAPH {_A} {{ ?l2 {_HAS_DOOR} ?d }} GRAPH {_A} {{ ?l1 {_HAS_DOOR} ?d }} FILTER(!isLiteral(?d)) " \
         "FILTER(!sameTerm(?l1, ?l2))"
_WALK = (f"GRAPH {_A} {{ ?group <{_RDF}type> <{_OWL}AllDifferent> . "
         f"?group <{_OWL}distinctMembers>|<{_OWL}members> ?list . ?list <{_RDF}rest>* ?cell . }}")
_MEMBER = f"GRAPH {_A} {{ ?cell <{_RDF}first> ?x }}"


def _key(group: str, member: str) -> str:
    return f'BIND(IRI(CONCAT("{KEY_PREFIX}", {group}, ":", {member})) AS ?key)'


#: the connecting rule's join, form by form (WHERE groups counted as they are)
JOINS = {
    "as compiled": f"{_DOORS} GRAPH {_X} {{ ?k2 {_K} ?l2 }} GRAPH {_X} {{ ?k1 {_K} ?l1 }} "
                   f"FILTER(!sameTerm(?k1, ?k2) && {_GROUP_TEST})",
    "no key atoms": _DOORS,
    "group as a term": f"{_DOORS} GRAPH {_GRP} {{ ?l2 {_IN_GROUP} ?g }} GRAPH {_GRP} {{ ?l1 {_IN_GROUP} ?g }}",
    "keys by subject": f"{_DOORS} GRAPH {_SUBJ} {{ ?l2 {_KEY} ?k2 }} GRAPH {_SUBJ} {{ ?l1 {_KEY} ?k1 }} "
                       f"FILTER(!sameTerm(?k1, ?k2) && {_GROUP_TEST})",
    "keys by hash": f"{_DOORS} {{ SELECT ?l1 ?k1 WHERE {{ GRAPH {_X} {{ ?k1 {_K} ?l1 }} }} }} "
                    f"{{ SELECT ?l2 ?k2 WHERE {{ GRAPH {_X} {{ ?k2 {_K} ?l2 }} }} }} "
                    f"FILTER(!sameTerm(?k1, ?k2) && {_GROUP_TEST})",
}
#: the key's making, part by part (counted, and the keyed forms written into a scratch graph)
MAKING = {
    "list walk": _WALK,
    "walk + rdf:first": f"{_WALK} {_MEMBER}",
    "key, two MD5s": f"{_WALK} {_MEMBER} {_key('MD5(STR(?list))', 'MD5(STR(?x))')}",
    "key, group MD5": f"{_WALK} {_MEMBER} {_key('MD5(STR(?list))', 'STR(?x)')}",
    "key, no MD5": f"{_WALK} {_MEMBER} {_key('STR(?list)', 'STR(?x)')}",
    "key, the member itself": f"{_WALK} {_MEMBER} BIND(?x AS ?key)",
}


def _scratch(ox) -> None:
    """The alternative forms' facts, from the reasoned helper graph and the asserted lists (not timed)."""
    ox.update(f"INSERT {{ GRAPH {_SUBJ} {{ ?x {_KEY} ?k }} }} WHERE {{ GRAPH {_X} {{ ?k {_K} ?x }} }}")
    ox.update(f"INSERT {{ GRAPH {_GRP} {{ ?x {_IN_GROUP} ?group }} }} WHERE {{ {_WALK} {_MEMBER} }}")


def _cpu_count(ox, where: str) -> tuple[float, int]:
    start = time.process_time()
    rows = int(next(iter(ox.query(f"SELECT (COUNT(*) AS ?n) WHERE {{ {where} }}")))[0].value)
    return time.process_time() - start, rows


def _cpu_write(ox, where: str) -> float:
    ox.update(f"DROP SILENT GRAPH {_OUT}")
    start = time.process_time()
    ox.update(f"INSERT {{ GRAPH {_OUT} {{ ?key {_K} ?x }} }} WHERE {{ {where} }}")
    return time.process_time() - start


def measure(size: str, reps: int) -> dict[str, list[float]]:
    """CPU seconds per form over ``reps`` rounds (forms in turns) on the reasoned chain map of ``size``."""
    warnings.simplefilter("ignore")  # the map's notices are not what is measured
    lift_time_limit()
    onto, _ = maps.loaded(size)
    onto.reason()
    ox = onto.store._ox  # read only, besides the scratch graphs dropped below
    _scratch(ox)
    times: dict[str, list[float]] = {}
    rows: dict[str, int] = {}
    try:
        for _ in range(reps):
            for name, where in {**JOINS, **MAKING}.items():
                seconds, rows[name] = _cpu_count(ox, where)
                times.setdefault(name, []).append(seconds)
                if "key," in name:
                    times.setdefault(name + ", written", []).append(_cpu_write(ox, where))
    finally:
        ox.update(f"DROP SILENT GRAPH {_SUBJ} ; DROP SILENT GRAPH {_GRP} ; DROP SILENT GRAPH {_OUT}")
    for name, n in rows.items():
        print(f"{size} {name:<22} rows {n:>8}")
    return times


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("size", help="chain map size, e.g. 30000")
    parser.add_argument("--reps", type=int, default=5)
    args = parser.parse_args(argv)
    times = measure(args.size, args.reps)
    print(f"{'form':<32} {'median':>8} {'min':>8}  CPU s, {args.reps} rounds")
    for name, values in times.items():
        print(f"{name:<32} {statistics.median(values):8.3f} {min(values):8.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
