"""The W3C OWL 2 conformance test cases against topostore and owlrl (the OWL 2 RL peer).

``python -m benchmarks.conformance [--profile RL] [--timeout 60] [--jobs 2] [--write docs/conformance.md]``

Reads the test cases from ``../shared/conformance/owl2-wg/all.rdf`` (``--cases``; never copied into
the repository): every case with an RDF/XML premise, whatever its status (Approved, Proposed,
Extracredit, none).  Each case runs on each engine in a child process (:mod:`benchmarks.conformance_case`;
a child takes case after case) under a time limit per case, so a crash or a hang costs that case only.
Prints (and with ``--write`` writes) a table by category — RL (the OWL 2 RL profile), DL (OWL 2 DL
outside RL), Full (RDF-Based semantics only) — and test type, with the cases each engine fails.
"""

from __future__ import annotations

import argparse
import json
import queue
import subprocess
import sys
import tempfile
import threading
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT.parent / "shared" / "conformance" / "owl2-wg" / "all.rdf"
TEST = "http://www.w3.org/2007/OWL/testOntology#"
CATEGORIES = ("RL", "DL", "Full")
CHECKS = {"PositiveEntailmentTest": "positive", "InconsistencyTest": "inconsistency",
          "ConsistencyTest": "consistency", "NegativeEntailmentTest": "negative"}
HEADINGS = {"positive": "positive entailment", "inconsistency": "inconsistency", "consistency": "consistency",
            "negative": "negative entailment"}
ENGINES = ("topostore", "owlrl")


@dataclass
class Case:
    """One test case: its id, category, checks and documents (RDF/XML text)."""

    id: str
    category: str
    status: str
    checks: list[str]
    premise: str
    conclusion: str = ""
    nonconclusion: str = ""
    results: dict[str, dict[str, object]] = field(default_factory=dict)
    seconds: dict[str, float] = field(default_factory=dict)

    def payload(self) -> dict:
        return {"id": self.id, "checks": self.checks, "premise": self.premise, "conclusion": self.conclusion,
                "nonconclusion": self.nonconclusion}


def read_cases(path: Path = CASES) -> tuple[list[Case], int]:
    """(the cases with an RDF/XML premise, how many have none)."""
    import rdflib

    g = rdflib.Graph().parse(path, format="xml")
    t = rdflib.Namespace(TEST)

    def one(s, p) -> str:
        v = next(iter(g.objects(s, p)), None)
        return str(v) if v is not None else ""

    cases, without = [], 0
    for s in sorted(g.subjects(rdflib.RDF.type, t.TestCase)):
        premise = one(s, t.rdfXmlPremiseOntology)
        if not premise:
            without += 1
            continue
        types = {str(o)[len(TEST):] for o in g.objects(s, rdflib.RDF.type) if str(o).startswith(TEST)}
        checks = [CHECKS[k] for k in CHECKS if k in types]
        profiles = {str(o)[len(TEST):] for o in g.objects(s, t.profile)}
        species = {str(o)[len(TEST):] for o in g.objects(s, t.species)}
        category = "RL" if "RL" in profiles else "DL" if "DL" in species else "Full"
        status = one(s, t.status)[len(TEST):] or "none"
        cases.append(Case(one(s, t.identifier) or str(s), category, status, checks, premise,
                          one(s, t.rdfXmlConclusionOntology), one(s, t.rdfXmlNonConclusionOntology)))
    return cases, without


#: a child's answer line for one case (other output of the engines is ignored)
RESULT = "RESULT "


def run_batch(batch: list[Case], engine: str, folder: Path, timeout: float) -> None:
    """Run ``batch`` on ``engine`` in one child process, case after case, each within ``timeout``.

    Starting a Python with the engines loaded costs more than most cases, so a child runs many; a case
    that times out or crashes its child gets that as the answer of every check, and a new child takes
    the cases after it, so no case decides another's answer.
    """
    pending = list(batch)
    while pending:
        files = []
        for case in pending:
            path = folder / f"{abs(hash(case.id))}-{engine}.json"
            path.write_text(json.dumps(case.payload()), encoding="utf-8")
            files.append(str(path))
        with tempfile.TemporaryFile("w+", encoding="utf-8") as errors:
            child = subprocess.Popen([sys.executable, "-m", "benchmarks.conformance_case", "--batch", engine, *files],
                                     cwd=ROOT, stdout=subprocess.PIPE, stderr=errors, text=True)
            answers: queue.Queue[str | None] = queue.Queue()
            threading.Thread(target=_read_answers, args=(child, answers), daemon=True).start()
            while pending:
                case, start = pending.pop(0), time.perf_counter()
                try:
                    line = answers.get(timeout=timeout)
                except queue.Empty:
                    child.kill()
                    child.wait()
                    case.results[engine] = dict.fromkeys(case.checks, f"timeout ({timeout:g} s)")
                    case.seconds[engine] = timeout
                    break
                if line is None:  # the child died on this case
                    code = child.wait()
                    errors.seek(0)
                    tail = " ".join(errors.read().strip().splitlines()[-1:])[:200]
                    case.results[engine] = dict.fromkeys(case.checks, f"crash (exit {code}): {tail}")
                    case.seconds[engine] = time.perf_counter() - start
                    break
                case.results[engine] = json.loads(line)
                case.seconds[engine] = time.perf_counter() - start
            else:
                child.wait()


def _read_answers(child: subprocess.Popen, answers: queue.Queue) -> None:
    """Hand the child's answer lines to the parent as they come; None when its output ends."""
    for line in child.stdout:
        if line.startswith(RESULT):
            answers.put(line[len(RESULT):])
    answers.put(None)


def run_all(cases: list[Case], timeout: float, jobs: int, progress: bool = True) -> None:
    """Every case on every engine: per engine, the cases dealt into ``jobs`` batches run side by side."""
    batches = [(cases[k::jobs], engine) for engine in ENGINES for k in range(jobs) if cases[k::jobs]]
    with tempfile.TemporaryDirectory(prefix="conformance-") as tmp, ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = [pool.submit(run_batch, batch, engine, Path(tmp), timeout) for batch, engine in batches]
        for k, f in enumerate(futures, 1):
            f.result()
            if progress:
                print(f"  {k}/{len(futures)} batches", file=sys.stderr, flush=True)


def tally(cases: list[Case]) -> dict[tuple[str, str], Counter]:
    """(category, check) → Counter of cases and passes per engine."""
    out: dict[tuple[str, str], Counter] = {}
    for c in cases:
        for check in c.checks:
            cell = out.setdefault((c.category, check), Counter())
            cell["cases"] += 1
            for e in ENGINES:
                cell[e] += c.results.get(e, {}).get(check) is True
    return out


def table(cases: list[Case], without: int, timeout: float) -> str:
    cells = tally(cases)
    checks = list(HEADINGS)
    lines = ["| category | " + " | ".join(HEADINGS[c] for c in checks) + " | all |",
             "|---|" + "---|" * (len(checks) + 1)]
    totals = Counter()
    for cat in CATEGORIES:
        row, sub = [], Counter()
        for check in checks:
            cell = cells.get((cat, check), Counter())
            sub.update(cell)
            row.append(f"{cell['topostore']} / {cell['owlrl']} of {cell['cases']}" if cell["cases"] else "—")
        totals.update(sub)
        lines.append(f"| {cat} | " + " | ".join(row) + f" | {sub['topostore']} / {sub['owlrl']} of {sub['cases']} |")
    lines.append(f"| all | {'| ' * len(checks)}{totals['topostore']} / {totals['owlrl']} of {totals['cases']} |")
    problems = {e: sum(1 for c in cases for k, v in c.results.get(e, {}).items() if k in HEADINGS
                       and isinstance(v, str) and v.startswith(("timeout", "crash"))) for e in ENGINES}
    slowest = max((c.seconds.get("topostore", 0.0), c.id) for c in cases) if cases else (0.0, "")
    return "\n".join([
        "Cells: checks passed by topostore / by owlrl of the checks there.",
        "",
        *lines,
        "",
        f"{len(cases)} cases with an RDF/XML premise ({without} without one are not run); in child processes "
        f"(one case at a time, {timeout:g} s each; a case that hangs or crashes its child answers that alone). "
        f"Timeouts or crashes: topostore {problems['topostore']}, "
        f"owlrl {problems['owlrl']}; slowest topostore case {slowest[1]} ({slowest[0]:.1f} s).",
    ])


def _said(c: Case, engine: str) -> str:
    """What ``engine``'s profile report names for the premise of ``c`` (the axiom kinds its notices carry), and
    what it adds once the conclusion's class expressions are loaded (a question can need what is not
    reasoned completely even when the premise does not: ``x : C ⊔ ¬C`` asks for a complement)."""
    result = c.results.get(engine, {})
    named, asked = result.get("notices") or [], result.get("question_notices") or []
    said = [f"profile report: {', '.join(named)}"] if named else []
    said += [f"with the conclusion's expressions loaded: {', '.join(asked)}"] if asked else []
    return "; ".join(said) or NO_NOTICE


NO_NOTICE = "no profile notice"


def _ordered(cases: list[Case]) -> list[Case]:
    return sorted(cases, key=lambda c: (CATEGORIES.index(c.category), c.id))


def failures(cases: list[Case], engine: str = "topostore") -> list[str]:
    """Lines naming each check ``engine`` fails that the other engine passes, and every error of it."""
    other = next(e for e in ENGINES if e != engine)
    out = []
    for c in _ordered(cases):
        for check in c.checks:
            mine, theirs = c.results.get(engine, {}).get(check), c.results.get(other, {}).get(check)
            if mine is not True and (theirs is True or isinstance(mine, str)):
                why = mine if isinstance(mine, str) else f"{other} passes"
                out.append(f"- {c.category} {HEADINGS[check]}: `{c.id}` — {why}; {_said(c, engine)}")
    return out


def failed_in(cases: list[Case], category: str, engine: str = "topostore") -> list[str]:
    """Lines naming every check ``engine`` fails in ``category``, whatever the other engine does, each with
    what the other engine answers and what ``engine``'s profile report names for the premise: the target
    is that no failure there goes unnamed."""
    other = next(e for e in ENGINES if e != engine)
    out = []
    for c in _ordered(cases):
        if c.category != category:
            continue
        for check in c.checks:
            mine, theirs = c.results.get(engine, {}).get(check), c.results.get(other, {}).get(check)
            if mine is True:
                continue
            peer = f"{other} passes" if theirs is True else f"{other} fails"
            why = f"{mine}; {peer}" if isinstance(mine, str) else peer
            out.append(f"- {HEADINGS[check]}: `{c.id}` — {why}; {_said(c, engine)}")
    return out


def failed_in_brief(cases: list[Case], category: str, engine: str = "topostore") -> list[str]:
    """:func:`failed_in` made short: one line per test type, each failed case with its notices in brackets."""
    groups: dict[str, list[str]] = {}
    for c in _ordered(cases):
        if c.category != category:
            continue
        for check in c.checks:
            if c.results.get(engine, {}).get(check) is not True:
                said = _said(c, engine)
                groups.setdefault(check, []).append(f"`{c.id}`" + ("" if said == NO_NOTICE else f" ({said})"))
    out = []
    for check in HEADINGS:
        if check in groups:
            unnamed = sum(1 for item in groups[check] if not item.endswith(")"))
            out.append(f"- {HEADINGS[check]} ({len(groups[check])}; {unnamed} without a notice): "
                       + "; ".join(groups[check]))
    return out


UNNAMED = """A failure without a notice has a premise that states nothing topostore sets aside: the conclusion
asks for what the RDF-Based semantics entails from its own vocabulary (`rdfs:Class` ≡ `owl:Class`,
`rdf:first` and `rdf:rest` functional, an ontology header, `x owl:sameAs x` for every term) or for an
unnamed individual (a blank node standing for the value of an existential). topostore answers for
named individuals, as Pellet does, and does not store reflexive equality: `x owl:sameAs x` would add a
triple per term and list each individual as its own alias, while every fact of an individual is
already copied to each of its names; a file that states `owl:sameAs` is told so at LOAD (an
informative notice, *entailed, not stored*, which a strict load accepts)."""


def _section(title: str, lines: list[str], what: str) -> list[str]:
    """A heading counting ``lines`` and those without a profile notice, then the lines."""
    unnamed = sum(1 for line in lines if line.endswith(NO_NOTICE))
    return [f"## {title} ({len(lines)}; {unnamed} without a profile notice)", "", what, "", *(lines or ["- none"]),
            "", *([UNNAMED, ""] if unnamed and title.endswith("Full") else [])]


INTRODUCTION = """# W3C OWL 2 conformance

`make conformance` (`python -m benchmarks.conformance --write docs/conformance.md`) runs the OWL
Working Group's test cases (`../shared/conformance/owl2-wg/all.rdf`, read where they are) on topostore
and on owlrl, the OWL 2 RL reasoner for rdflib, each case and engine in a child process with a time
limit (a child takes case after case; one that hangs or crashes costs that case only). A case is one
or more checks: *consistency* and *inconsistency* of the premise,
*positive entailment* (the conclusion follows) and *negative entailment* (the non-conclusion does
not). Entailment is decided the same way for both engines (`benchmarks/conformance_case.py`): a
type with a class expression becomes `Q ≡ expression` and a type `Q`; a subclass, domain, range or
property axiom a fresh individual asked for its consequence; a disjointness or difference an
inconsistency test; every other triple a SPARQL ASK over the closure. Categories: **RL** the cases
of the OWL 2 RL profile, **DL** other OWL 2 DL cases, **Full** the RDF-Based-only ones.
The RL rows also run in `make test` (`tests/test_conformance.py`: topostore passes every check owlrl
passes there, with no crash and no timeout).
"""


def document(cases: list[Case], text: str) -> str:
    """docs/conformance.md: what is run, the table, every check topostore misses that owlrl passes, and
    every check topostore fails in the Full and DL categories with what its profile report names."""
    return "\n".join([
        INTRODUCTION, "## Results", "", text, "",
        *_section("Checks topostore fails where owlrl passes, and its errors", failures(cases),
                  "With the axiom kinds topostore's profile report names for the premise."),
        *_section("Every check topostore fails in Full", failed_in(cases, "Full"),
                  "The RDF-Based-only cases: each failed check, what owlrl answers, and the axiom kinds "
                  "topostore's profile report names for the premise (what it says it does not reason "
                  "completely)."),
        *_dl_section(cases),
    ])


def _dl_section(cases: list[Case]) -> list[str]:
    """The DL failures, short: by test type, each case with its notices in brackets."""
    lines = failed_in(cases, "DL")
    unnamed = sum(1 for line in lines if line.endswith(NO_NOTICE))
    return [f"## Every check topostore fails in DL ({len(lines)}; {unnamed} without a profile notice)", "",
            "The OWL 2 DL cases outside RL by test type, with the profile report's axiom kinds in brackets.", "",
            *(failed_in_brief(cases, "DL") or ["- none"]), ""]


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="python -m benchmarks.conformance", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cases", type=Path, default=CASES, help="all.rdf of the OWL 2 test cases")
    p.add_argument("--profile", choices=CATEGORIES, help="run one category only")
    p.add_argument("--only", nargs="*", metavar="ID", help="run these test case identifiers only")
    p.add_argument("--timeout", type=float, default=60.0, help="seconds per case and engine (default 60)")
    p.add_argument("--jobs", type=int, default=2, help="child processes at once (default 2)")
    p.add_argument("--write", type=Path, help="also write the table and the failures (markdown) here")
    p.add_argument("--json", type=Path, help="also write every result (JSON) here")
    return p.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    if not args.cases.is_file():
        print(f"no test cases at {args.cases}", file=sys.stderr)
        return 2
    cases, without = read_cases(args.cases)
    if args.profile:
        cases = [c for c in cases if c.category == args.profile]
    if args.only:
        cases = [c for c in cases if c.id in set(args.only)]
    start = time.perf_counter()
    run_all(cases, args.timeout, args.jobs)
    text = table(cases, without, args.timeout)
    print(text)
    print(f"\n({time.perf_counter() - start:.0f} s)")
    if args.write:
        args.write.write_text(document(cases, text), encoding="utf-8")
    if args.json:
        args.json.write_text(json.dumps({c.id: {"category": c.category, "status": c.status, **c.results}
                                         for c in cases}, indent=1), encoding="utf-8")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
