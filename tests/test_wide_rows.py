"""Wide unions under complements and wide intersections, many individuals: a generic rule of n body atoms
is planned from its schema rows first.

The rows of ``neg-uni-n`` bind a union's every member before its ``ts:notType`` atoms are read, so each
atom is a look-up; joined the other way, an individual's n-tuples of non-memberships come first (thirty
of them and a union of four members did not end in a minute).  The generated TBox runs in a child
process bounded in time (a hang is a failure, not a stuck test run), generic against instantiated.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

from topostore.compile.schema import schema_rules
from topostore.rdf.vocab import DELTA
from topostore.reason.plan import plan_where

TESTS = Path(__file__).parent
#: the child's bound: the planned evaluation takes a few seconds with the imports
SECONDS = 60


def wide_tbox(classes: int = 30, individuals: int = 20, per_width: int = 4, seed: int = 7) -> str:
    """Complements of unions of 2 to 9 members over ``classes`` classes that every individual ``x`` is
    told out of (thirty non-memberships each), and intersections of 2 to 9 members over classes that
    every individual ``y`` is in."""
    import random

    rnd = random.Random(seed)
    a = [f":A{i}" for i in range(classes)]
    b = [f":B{i}" for i in range(classes)]
    lines = ["@prefix : <http://example.org/wide#> .", "@prefix owl: <http://www.w3.org/2002/07/owl#> .",
             ":Out owl:disjointWith " + " , ".join(a) + " ."]
    for width in range(2, 10):
        for k in range(per_width):
            lines.append(f":Not{width}_{k} owl:equivalentClass [ a owl:Class ; owl:complementOf [ owl:unionOf "
                         f"( {' '.join(rnd.sample(a, width))} ) ] ] .")
            lines.append(f":All{width}_{k} owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( {' '.join(rnd.sample(b, width))} ) ] .")
    lines += [f":x{i} a :Out ." for i in range(individuals)]
    lines += [f":y{i} a " + " , ".join(rnd.sample(b, classes - 3)) + " ." for i in range(individuals)]
    return "\n".join(lines) + "\n"


CHILD = textwrap.dedent("""
    import json, sys, warnings
    sys.path[:0] = [{tests!r}]
    from test_schema_rules import _materialize
    from test_wide_rows import wide_tbox
    from topostore import Ontology
    from topostore.compile.schema_program import full_program
    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        onto.load_data(wide_tbox(), "turtle")
    generic_rows = sorted(full_program(onto.rules, 0).rows)
    generic, instantiated = _materialize(onto, 0), _materialize(onto, 1 << 30)
    typed = sorted({{(s.value.rsplit("#", 1)[1], o.value.rsplit("#", 1)[1]) for s, p, o in generic[0]
                    if p.value.endswith("#type")}})
    print(json.dumps({{"rows": generic_rows, "same": generic == instantiated, "typed": typed}}))
""")


def test_wide_rows_over_many_individuals_run_generically_in_bounded_time() -> None:
    try:
        done = subprocess.run([sys.executable, "-c", CHILD.format(tests=str(TESTS))], capture_output=True,
                              text=True, timeout=SECONDS)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"the generic evaluation of the wide rows did not end within {SECONDS} s") from None
    assert done.returncode == 0, done.stderr[-3000:]
    got = json.loads(done.stdout.strip().splitlines()[-1])
    assert {f"neg-uni-{n}" for n in range(2, 9)} | {f"cls-int1-{n}" for n in range(2, 9)} <= set(got["rows"])
    assert got["same"]
    typed = {tuple(pair) for pair in got["typed"]}
    # every x is out of every A: in every complement of a union; every intersection whose members a y has
    assert {("x0", f"Not{w}_{k}") for w in range(2, 10) for k in range(4)} <= typed
    assert any(c.startswith("All8_") for _, c in typed) and any(c.startswith("All2_") for _, c in typed)


def test_a_generic_rule_reads_its_rows_before_its_body() -> None:
    """The schema graph's pattern opens a generic rule's WHERE without delta and planned per delta fact
    (flat or LATERAL), the delta atom after it, and a full round's delta evaluation where its rows are of
    more than two terms; rows of two (``cax-sco``) follow the delta, which binds one of their terms."""
    for key in ("neg-uni-4", "neg-uni-8", "cls-int1-8", "cax-sco", "prp-spo2"):
        generic = schema_rules()[key]
        rule = generic.evaluable(False)
        schema = f"GRAPH {generic.graph} "
        texts = [rule.where(), plan_where(rule, 0, DELTA, lateral=False), plan_where(rule, 0, DELTA, lateral=True)]
        if key != "cax-sco":
            texts.append(rule.where(0, str(DELTA)))
        for text in texts:
            lines = text.split("\n")
            assert lines[0].strip().startswith(schema), (key, text)
            assert text.count(schema) == 1
        for text in texts[1:]:
            assert text.split("\n")[1].strip().startswith(f"GRAPH {DELTA} "), (key, text)
    rule = schema_rules()["cax-sco"].evaluable(False)
    lines = [line.strip() for line in rule.where(0, str(DELTA)).split("\n")]
    assert lines[0].startswith(f"GRAPH {DELTA} ") and lines[1].startswith(f"GRAPH {schema_rules()['cax-sco'].graph} ")


def test_a_delta_that_binds_no_row_term_reads_on_before_the_rows() -> None:
    """``different-disjoint``'s rows (every pair of disjoint classes: tens of thousands on a large TBox)
    are read once a class is bound: after a new candidate pair, its first member's classes; after a new
    class fact, the pairs of candidates it has (helper facts, few) before the classes disjoint with it."""
    generic = schema_rules()["different-disjoint"]
    rule = generic.evaluable(True)
    schema = f"GRAPH {generic.graph} "
    atoms = [a.text() for a in rule.body]
    candidate, typed = atoms.index("?a <urn:topostore:differenceCandidate> ?b ."), atoms.index(
        "?a <http://www.w3.org/1999/02/22-rdf-syntax-ns#type> ?c .")
    lines = [line.strip() for line in rule.where(candidate, str(DELTA)).split("\n")]
    assert lines[0].startswith(f"GRAPH {DELTA} ") and "rdf-syntax-ns#type" in lines[1], lines
    assert lines[2].startswith(schema), lines
    lines = [line.strip() for line in rule.where(typed, str(DELTA)).split("\n")]
    assert lines[0].startswith(f"GRAPH {DELTA} ") and "differenceCandidate" in lines[1], lines
    assert lines[2].startswith(schema), lines
