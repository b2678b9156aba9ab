"""SWRL rules written as Turtle for the tests: atoms, built-ins and one ``swrl:Imp``, in the standard SWRL RDF
vocabulary, under the prefixes of :data:`PREFIXES` (``:`` is ``http://example.org/swrltest#``)."""

from __future__ import annotations

import re
from decimal import Decimal

NS = "http://example.org/swrltest#"
PREFIXES = """\
@prefix : <http://example.org/swrltest#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
@prefix swrl: <http://www.w3.org/2003/11/swrl#> .
@prefix swrlb: <http://www.w3.org/2003/11/swrlb#> .
@prefix swrla: <http://swrl.stanford.edu/ontologies/3.3/swrla.owl#> .
@prefix var: <http://example.org/swrltest/var#> .
<http://example.org/swrltest> a owl:Ontology .
"""


def arg(a: object) -> str:
    """?x -> a SWRL variable, :x -> an individual, anything else -> a Turtle literal."""
    if isinstance(a, str) and a.startswith("?"):
        return "var:" + a[1:]
    if isinstance(a, str) and a.startswith(":"):
        return a
    if isinstance(a, bool):
        return "true" if a else "false"
    if isinstance(a, (int, Decimal)):
        return f'"{a}"^^xsd:{"integer" if isinstance(a, int) else "decimal"}'
    if isinstance(a, float):
        return f'"{a!r}"^^xsd:double'
    return str(a)  # already Turtle (e.g. '"abc"')


def cls(c: str, x: object) -> str:
    return f"[ a swrl:ClassAtom ; swrl:classPredicate {c} ; swrl:argument1 {arg(x)} ]"


def obj(p: str, x: object, y: object) -> str:
    return f"[ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate {p} ; swrl:argument1 {arg(x)} ; swrl:argument2 {arg(y)} ]"


def data(p: str, x: object, y: object) -> str:
    return f"[ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate {p} ; swrl:argument1 {arg(x)} ; swrl:argument2 {arg(y)} ]"


def same(x: object, y: object) -> str:
    return f"[ a swrl:SameIndividualAtom ; swrl:argument1 {arg(x)} ; swrl:argument2 {arg(y)} ]"


def diff(x: object, y: object) -> str:
    return f"[ a swrl:DifferentIndividualsAtom ; swrl:argument1 {arg(x)} ; swrl:argument2 {arg(y)} ]"


def data_range(dt: str, x: object) -> str:
    return f"[ a swrl:DataRangeAtom ; swrl:dataRange {dt} ; swrl:argument1 {arg(x)} ]"


def builtin(name: str, *args: object) -> str:
    return f"[ a swrl:BuiltinAtom ; swrl:builtin swrlb:{name} ; swrl:arguments ( {' '.join(arg(a) for a in args)} ) ]"


def rule(body: list[str], head: list[str], label: str = "TestRule", enabled: bool | None = True) -> str:
    text = " ".join(body + head)
    variables = sorted(set(re.findall(r"var:(\w+)", text)))
    out = "".join(f"var:{v} a swrl:Variable .\n" for v in variables)
    out += f'[] a swrl:Imp ;\n  rdfs:label "{label}"^^xsd:string ;\n'
    if enabled is not None:
        out += f"  swrla:isRuleEnabled {'true' if enabled else 'false'} ;\n"
    out += f"  swrl:body ( {' '.join(body)} ) ;\n  swrl:head ( {' '.join(head)} ) .\n"
    return out
