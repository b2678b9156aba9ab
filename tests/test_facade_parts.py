"""The Ontology facade hands its API to named parts: a forwarded method has the part's signature, the
facade's docstring, and reaches the part (the public API is the same as when each was written out)."""

from __future__ import annotations

import inspect

from topostore import Ontology
from topostore.ontology.delegation import forward
from topostore.ontology.files import OntologyFiles
from topostore.ontology.reads import OntologyQueries


def forwarded() -> dict[str, object]:
    return {name: f for name, f in vars(Ontology).items() if callable(f) and getattr(f, "__qualname__", "")
            == f"Ontology.{name}" and hasattr(f, "__signature__")}


def test_forwarded_methods_have_the_parts_signatures_and_a_name_of_the_facade() -> None:
    found = forwarded()
    assert {"types", "instances", "load", "load_data", "iri", "replace", "save"} <= found.keys()
    for name, f in found.items():
        assert f.__name__ == name
        assert list(inspect.signature(f).parameters)[0] == "self", name
    assert inspect.signature(Ontology.types) == inspect.signature(OntologyQueries.types)
    assert inspect.signature(Ontology.load) == inspect.signature(OntologyFiles.load)
    assert inspect.getdoc(Ontology.types) == "Named classes of an individual (asserted ∪ inferred), without owl:Thing."


def test_a_forwarded_method_calls_the_part_with_its_arguments() -> None:
    class Part:
        def echo(self, a: int, b: int = 2) -> tuple[int, int]:
            return a, b

    class Facade:
        def __init__(self) -> None:
            self.part = Part()

        echo = forward("part", Part.echo, "Says back.")

    assert Facade().echo(1) == (1, 2) and Facade().echo(1, b=3) == (1, 3)
    assert Facade.echo.__doc__ == "Says back." and str(inspect.signature(Facade.echo)) == str(inspect.signature(Part.echo))


def test_the_facade_reads_and_changes_through_its_parts() -> None:
    o = Ontology(prefix="http://e.org/a#")
    assert o.iri("x").value == "http://e.org/a#x" and o.short(o.iri("x")) == "x"
    o.add_type("x", "A")
    o.add_data("d", "x", 7)
    assert o.replace("x", "d", 8) == 1
    o.reason()
    assert [c.value for c in o.types("x")] == ["http://e.org/a#A"] and [v.value for v in o.data_values("d", "x")] == ["8"]
