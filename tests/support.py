"""Helpers shared by the tests: where the test data and the tutorial's files are (the one place that says so),
and short views of answers."""

from __future__ import annotations

import os
import shutil
import warnings
from collections.abc import Callable
from importlib.util import find_spec
from pathlib import Path

import pytest
from pyoxigraph import Literal, NamedNode, RdfFormat, Triple, parse

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, AUX, ENTAILED, INFERRED, XSD


def too_large_axiom(ns: str) -> list[Triple]:
    """The triples of an axiom (in namespace ``ns``) whose rule is too large for the store to evaluate safely
    (``compile/guard.py``): a REASON after they are added fails (RuleCompileError) and reverts every change since
    the last successful one."""
    members = " ".join(f"<{ns}A{i}>" for i in range(300))
    text = f"<{ns}C> <http://www.w3.org/2002/07/owl#equivalentClass> " \
           f"[ a <http://www.w3.org/2002/07/owl#Class> ; <http://www.w3.org/2002/07/owl#intersectionOf> ({members}) ] ."
    return list(parse(text, RdfFormat.TURTLE))


#: the marks of a test that runs Pellet (through Owlready2, on a Java runtime): skipped without either
NEEDS_PELLET = [
    pytest.mark.skipif(shutil.which("java") is None, reason="Pellet needs a Java runtime"),
    pytest.mark.skipif(find_spec("owlready2") is None, reason="Owlready2 (which bundles Pellet) is not installed"),
]


def needs_pellet(test: Callable) -> Callable:
    """``test`` with the marks of :data:`NEEDS_PELLET`."""
    for mark in NEEDS_PELLET:
        test = mark(test)
    return test


#: JVM options of the tests' Pellet runs: each run is one short JVM (a second or two) that the optimising JIT
#: compiler only slows down, so the quick one alone (C1) does it in about half the CPU; answers are the same
PELLET_JAVA_OPTIONS = "-XX:TieredStopAtLevel=1"


def pellet_env() -> dict[str, str]:
    """The environment of a process that runs Pellet through Owlready2: ours, with :data:`PELLET_JAVA_OPTIONS`
    added to the options the ``java`` launcher reads (``JDK_JAVA_OPTIONS``, kept if already set)."""
    env = dict(os.environ)
    env["JDK_JAVA_OPTIONS"] = " ".join(filter(None, [env.get("JDK_JAVA_OPTIONS"), PELLET_JAVA_OPTIONS]))
    return env

ROOT = Path(__file__).resolve().parents[1]
#: small project-owned files the tests read (saved maps, SQWRL queries)
DATA = ROOT / "tests" / "data"
#: ../shared/ontology beside the checkout (CI clones the repository with it there): the tutorial's files,
#: read where they are, never copied
SHARED = ROOT.parent / "shared" / "ontology"
TBOX_OWL = SHARED / "topological_map.owl"
ABOX_OWL = SHARED / "topological_map_abox.owl"
#: the tutorial ontology's IRI, and its namespace
IRI = "http://bnc/exp-rob-lab/2022-23"
NS = IRI + "#"
#: the example environment's clock (Robot1 now)
NOW = 1665579740


def closure(onto: Ontology) -> dict[str, set]:
    """The inferred, helper and entailed-only quads of an in-memory ontology, by graph: what a shortcut of
    the full REASON must leave as it was."""
    ox = onto.store._ox
    return {g.value: set(ox.quads_for_pattern(None, None, None, g)) for g in (INFERRED, AUX, ENTAILED)}


def same_closure_without(onto: Ontology, monkeypatch: pytest.MonkeyPatch, target: object, name: str,
                         replacement: object) -> None:
    """A full REASON of ``onto`` reaches the same closure and consistency with a shortcut switched off
    (``target.name`` replaced): a shortcut may only save work."""
    first = onto.reason(mode="full")
    kept = closure(onto)
    monkeypatch.setattr(target, name, replacement)
    again = onto.reason(mode="full")
    assert closure(onto) == kept
    assert first.consistent == again.consistent


def same_as_fresh_load(onto: Ontology, report: object) -> tuple[Ontology, object]:
    """Assert that ``onto``'s last REASON (its ``report``) concluded what a fresh ontology of its asserted
    triples concludes (consistency, inferred and entailed graphs); the fresh ontology and its report, for
    further comparisons."""
    fresh = Ontology()
    fresh.add(*onto.store.triples(graph=ASSERTED))
    fresh_report = fresh.reason()
    assert report.consistent == fresh_report.consistent
    for graph in (INFERRED, ENTAILED):
        assert set(onto.store.triples(graph=graph)) == set(fresh.store.triples(graph=graph))
    return fresh, fresh_report


def quiet_turtle(text: str) -> Ontology:
    """An ontology of Turtle ``text`` (its prefixes included), not reasoned; what it does not reason
    completely is named in warnings the caller does not look at."""
    from topostore import OntologyWarning

    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(text)
    return o


def reasoned_turtle(text: str) -> Ontology:
    """:func:`quiet_turtle`, reasoned and consistent."""
    o = quiet_turtle(text)
    assert o.reason().consistent
    return o


def names(ns: str) -> Callable[[str], NamedNode]:
    """The IRI maker of a test's namespace: ``names(EX)("r1")`` is ``<EX r1>``."""
    return lambda name: NamedNode(ns + name)


def typed(value: str, datatype: str) -> Literal:
    """A literal of XSD ``datatype`` (its local name), spelled ``value``."""
    return Literal(value, datatype=NamedNode(XSD + datatype))


def long(v: int) -> Literal:
    return Literal(str(v), datatype=NamedNode(XSD + "long"))


def types_of(o: Ontology, name: str) -> set[str]:
    return {o.short(t) for t in o.types(name)}


def instances(o: Ontology, cls: str) -> set[str]:
    return {o.short(i) for i in o.instances(cls)}


def connected(o: Ontology) -> set[tuple[str, str]]:
    """All connectedTo pairs the ontology answers (asserted ∪ inferred)."""
    rows = o.sparql(f"SELECT ?a ?b WHERE {{ ?a <{NS}connectedTo> ?b }}")
    return {(o.short(r["a"]), o.short(r["b"])) for r in rows}


def armor_load(service, path: Path | str, iri: str):
    """An aRMOR LOAD FILE of ``path`` as ``iri`` into reference "ref", the load's OntologyWarnings silenced
    (the reply's ``error_description`` carries them, which the callers check)."""
    from topostore import OntologyWarning

    request = {"client_name": "c", "reference_name": "ref", "command": "LOAD", "primary_command_spec": "FILE",
               "secondary_command_spec": "", "args": [str(path), iri, "false", "PELLET", "false"]}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        return service.call(request)


def map_or_text(text: str | None = None) -> Ontology:
    """An ontology of Turtle ``text``, or with None of the 200-location benchmark map, loaded with LOAD's
    notices silenced (the full-run tests read what a full REASON sends on either)."""
    from topostore import OntologyWarning

    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        if text is None:
            import sys
            import tempfile

            sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/ beside src/
            from benchmarks import maps

            with tempfile.TemporaryDirectory() as tmp:
                path, _ = maps.write("200", Path(tmp))
                onto.load(path)
        else:
            onto.load_data(text, "turtle")
    return onto


def full_run_updates(onto: Ontology, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The update texts a full REASON of ``onto`` sends, in order: every evaluation as an update (none of
    them found beside the run in the worker thread, :mod:`topostore.reason.early_rules`)."""
    from topostore.reason import early_reads

    texts: list[str] = []
    update = onto.store.update
    monkeypatch.setattr(early_reads, "ENABLED", False)

    def recording(text: str, *args, **kwargs):
        texts.append(text)
        return update(text, *args, **kwargs)

    monkeypatch.setattr(onto.store, "update", recording)
    onto.reason(mode="full")
    monkeypatch.undo()
    return texts
