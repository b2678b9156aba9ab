"""Compiling an ontology leaves no cycle for the collector: the compiler and its parts are freed by their
reference counts as soon as the rules are made.

Why: a LOAD compiles with the cycle collector paused (:mod:`topostore.rdf.collector`), and a full
collection is rare once millions of long-lived objects exist, so a compiler kept alive by a cycle
(its parts pointing back at it) stayed in memory through the REASON after the LOAD: at 3,000 classes
of ``benchmarks.tbox``, 5.3 million objects, 450 MiB of the process.
"""

from __future__ import annotations

import gc
import warnings

from topostore import Ontology, OntologyWarning
from topostore.compile.pipeline import compile_ontology
from topostore.rdf.vocab import ASSERTED

#: complements, existentials, a universal, disjoint classes and a SWRL-free TBox: every part of the
#: compiler (restrictions, negation, subsumption) and the profile report's unnamed values are used
TBOX = """@prefix : <http://e.org/c#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
:p a owl:ObjectProperty . :A a owl:Class . :B a owl:Class ; owl:disjointWith :A .
:C owl:equivalentClass [ a owl:Class ; owl:complementOf :A ] .
:D rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :B ] .
:E owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :C ] .
:F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality 2 ; owl:onClass :B ] .
:x a :D , :F .
"""


def test_compiling_leaves_no_compiler_for_the_cycle_collector() -> None:
    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        onto.load_data(TBOX)
    gc.collect()
    enabled = gc.isenabled()
    gc.disable()
    try:
        rules = compile_ontology(onto.store, ASSERTED)
        gc.set_debug(gc.DEBUG_SAVEALL)
        gc.collect()
        left = sorted({type(o).__qualname__ for o in gc.garbage if type(o).__module__.startswith("topostore.compile")})
    finally:
        gc.set_debug(0)
        gc.garbage.clear()
        if enabled:
            gc.enable()
    assert rules.rules and left == [], left
