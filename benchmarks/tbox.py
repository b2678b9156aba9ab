"""A Protégé-tutorial-style TBox of a given size (pizzas and toppings), the TBox-heavy benchmark input.

What the tutorial teaches, scaled by one number (the named classes, about 100 by default):
topping categories with leaf toppings made pairwise disjoint (Protégé's "make siblings disjoint"
writes one ``owl:disjointWith`` per pair, hence the many disjointness axioms), a spiciness value
partition (a covering union of disjoint classes), named pizzas with existential restrictions on
their base and toppings and a universal closure axiom over the union of their toppings, defined
classes (an intersection with a restriction; a complement; ``owl:hasValue``; a country class that
is an ``owl:oneOf``), functional, inverse and transitive properties, and about ten individuals
whose types follow from those definitions.  Written as N-Triples: topostore, owlrl (rdflib),
reasonable and Owlready2 (for Pellet) all read that one file.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from pyoxigraph import RdfFormat, parse, serialize

NS = "http://topostore.invalid/tbox#"
CATEGORIES = ["Cheese", "Meat", "Vegetable", "Fish", "Sauce", "Herb", "Nut", "Fruit"]
SPICINESS = ["Hot", "Medium", "Mild"]
COUNTRIES = ["Italy", "France", "America", "England", "Germany"]
#: topping categories that a vegetarian pizza may have
VEGETARIAN = ["Cheese", "Vegetable", "Sauce", "Herb", "Nut", "Fruit"]
#: the fixed classes besides the toppings and named pizzas (Food, Pizza, the bases, the categories,
#: the spiciness partition, Country and the defined classes)
FIXED = 9 + len(CATEGORIES) + len(SPICINESS) + 10


@dataclass(frozen=True)
class Shape:
    """How many of each kind a TBox of ``classes`` named classes gets."""

    toppings: int
    pizzas: int

    @classmethod
    def of(cls, classes: int) -> Shape:
        if classes < FIXED + 2 * len(CATEGORIES) + 4:
            raise ValueError(f"a tutorial-style TBox needs at least {FIXED + 2 * len(CATEGORIES) + 4} classes, "
                             f"not {classes}")
        rest = classes - FIXED
        pizzas = max(4, rest // 3)
        return cls(toppings=rest - pizzas, pizzas=pizzas)


def turtle(classes: int = 100, functional: int = 0) -> str:
    """The TBox and its individuals as Turtle text (``functional``: that many more functional properties,
    :func:`_functional`)."""
    shape = Shape.of(classes)
    lines = [f"@prefix : <{NS}> .", "@prefix owl: <http://www.w3.org/2002/07/owl#> .",
             "@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .",
             "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .", f"<{NS.rstrip('#')}> a owl:Ontology ."]
    lines += _properties() + _bases_and_partition()
    toppings = _toppings(shape.toppings)
    lines += _topping_axioms(toppings)
    lines += _pizzas(shape.pizzas, toppings)
    lines += _defined_classes() + _individuals(toppings) + _functional(functional)
    return "\n".join(lines) + "\n"


def write(classes: int, folder: Path, functional: int = 0) -> Path:
    """The TBox as one N-Triples file in ``folder``."""
    path = folder / (f"tbox-{classes}-f{functional}.nt" if functional else f"tbox-{classes}.nt")
    quads = parse(turtle(classes, functional).encode(), RdfFormat.TURTLE)
    path.write_bytes(serialize(quads, format=RdfFormat.N_TRIPLES) or b"")
    return path


def _properties() -> list[str]:
    return [":hasIngredient a owl:ObjectProperty, owl:TransitiveProperty ; rdfs:domain :Food ; rdfs:range :Food .",
            ":isIngredientOf a owl:ObjectProperty ; owl:inverseOf :hasIngredient .",
            ":hasTopping a owl:ObjectProperty ; rdfs:subPropertyOf :hasIngredient ; rdfs:domain :Pizza ; "
            "rdfs:range :Topping .",
            ":isToppingOf a owl:ObjectProperty ; owl:inverseOf :hasTopping .",
            ":hasBase a owl:ObjectProperty, owl:FunctionalProperty ; rdfs:subPropertyOf :hasIngredient ; "
            "rdfs:domain :Pizza ; rdfs:range :PizzaBase .",
            ":hasSpiciness a owl:ObjectProperty, owl:FunctionalProperty ; rdfs:range :Spiciness .",
            ":hasCountryOfOrigin a owl:ObjectProperty ."]


def _bases_and_partition() -> list[str]:
    out = [":Food a owl:Class .", ":Pizza a owl:Class ; rdfs:subClassOf :Food .",
           ":PizzaBase a owl:Class ; rdfs:subClassOf :Food ; owl:disjointWith :Pizza, :Topping .",
           ":Topping a owl:Class ; rdfs:subClassOf :Food ; owl:disjointWith :Pizza .",
           ":ThinBase a owl:Class ; rdfs:subClassOf :PizzaBase ; owl:disjointWith :DeepPanBase .",
           ":DeepPanBase a owl:Class ; rdfs:subClassOf :PizzaBase .",
           ":Spiciness a owl:Class ; owl:equivalentClass [ a owl:Class ; owl:unionOf ( "
           + " ".join(f":{s}" for s in SPICINESS) + " ) ] ."]
    out += [f":{s} a owl:Class ; rdfs:subClassOf :Spiciness ." for s in SPICINESS]
    out += _pairwise_disjoint(SPICINESS)
    out += [f":{s}Value a owl:NamedIndividual, :{s} ." for s in SPICINESS]
    out += [":Country a owl:Class ; owl:equivalentClass [ a owl:Class ; owl:oneOf ( "
            + " ".join(f":{c}" for c in COUNTRIES) + " ) ] ."]
    out += [f":{c} a owl:NamedIndividual ." for c in COUNTRIES]
    out += [f":{c}Topping a owl:Class ; rdfs:subClassOf :Topping ." for c in CATEGORIES]
    out += _pairwise_disjoint([f"{c}Topping" for c in CATEGORIES])
    return out


def _toppings(n: int) -> dict[str, list[str]]:
    """Leaf toppings per category, dealt round-robin (at least two per category)."""
    out: dict[str, list[str]] = {c: [] for c in CATEGORIES}
    for i in range(n):
        c = CATEGORIES[i % len(CATEGORIES)]
        out[c].append(f"{c}{len(out[c]) + 1}")
    return out


def _topping_axioms(toppings: dict[str, list[str]]) -> list[str]:
    out = []
    for k, (category, leaves) in enumerate(toppings.items()):
        for i, leaf in enumerate(leaves):
            spice = spiciness(k, i)
            out.append(f":{leaf} a owl:Class ; rdfs:subClassOf :{category}Topping, "
                       f"[ a owl:Restriction ; owl:onProperty :hasSpiciness ; owl:someValuesFrom :{spice} ] .")
        out += _pairwise_disjoint(leaves)
    return out


def spiciness(category: int, leaf: int) -> str:
    """The spiciness class every topping of a leaf class has (``hasSpiciness`` is functional)."""
    return SPICINESS[(category + leaf) % len(SPICINESS)]


def _pizzas(n: int, toppings: dict[str, list[str]]) -> list[str]:
    """Named pizzas: a base, 2-4 toppings (existential), a closure axiom over their union."""
    out, names = [], [f"Pizza{i + 1}" for i in range(n)]
    for i, name in enumerate(names):
        mine = _pizza_leaves(i, toppings)
        base = "ThinBase" if i % 2 else "DeepPanBase"
        some = ", ".join(f"[ a owl:Restriction ; owl:onProperty :hasTopping ; owl:someValuesFrom :{t} ]" for t in mine)
        out.append(f":{name} a owl:Class ; rdfs:subClassOf :NamedPizza, "
                   f"[ a owl:Restriction ; owl:onProperty :hasBase ; owl:someValuesFrom :{base} ], {some}, "
                   f"[ a owl:Restriction ; owl:onProperty :hasTopping ; owl:allValuesFrom "
                   f"[ a owl:Class ; owl:unionOf ( {' '.join(':' + t for t in mine)} ) ] ] .")
        if i % 4 == 0:
            country = COUNTRIES[i % len(COUNTRIES)]
            out.append(f":{name} rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :hasCountryOfOrigin ; "
                       f"owl:hasValue :{country} ] .")
    return out + [":NamedPizza a owl:Class ; rdfs:subClassOf :Pizza ."] + _pairwise_disjoint(names)


def _pizza_leaves(i: int, toppings: dict[str, list[str]]) -> list[str]:
    """The 2-4 leaf toppings of the ``i``-th named pizza (0-based), categories interleaved."""
    leaves = [leaf for category in zip(*toppings.values()) for leaf in category]
    return [leaves[(3 * i + j) % len(leaves)] for j in range(2 + i % 3)]


def pizza_toppings(classes: int) -> dict[str, list[str]]:
    """Each named pizza class of the TBox of ``classes`` classes and the leaf toppings its closure allows."""
    shape = Shape.of(classes)
    toppings = _toppings(shape.toppings)
    return {f"Pizza{i + 1}": _pizza_leaves(i, toppings) for i in range(shape.pizzas)}


def leaf_spiciness(classes: int) -> dict[str, str]:
    """The spiciness class each leaf topping class implies (see :func:`spiciness`)."""
    toppings = _toppings(Shape.of(classes).toppings)
    return {leaf: spiciness(k, i) for k, leaves in enumerate(toppings.values()) for i, leaf in enumerate(leaves)}


def _defined_classes() -> list[str]:
    """The tutorial's defined classes (necessary and sufficient conditions)."""
    def some(p: str, c: str) -> str:
        return f"[ a owl:Restriction ; owl:onProperty :{p} ; owl:someValuesFrom {c} ]"

    def defined(name: str, *parts: str) -> str:
        return (f":{name} a owl:Class ; owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( "
                + " ".join(parts) + " ) ] .")

    veg = " ".join(f":{c}Topping" for c in VEGETARIAN)
    hot = "[ a owl:Class ; owl:intersectionOf ( :Topping [ a owl:Restriction ; owl:onProperty :hasSpiciness ; " \
          "owl:hasValue :HotValue ] ) ]"
    return [defined("CheeseyPizza", ":Pizza", some("hasTopping", ":CheeseTopping")),
            defined("MeatyPizza", ":Pizza", some("hasTopping", ":MeatTopping")),
            defined("SpicyPizza", ":Pizza", some("hasTopping", hot)),
            defined("ThinPizza", ":Pizza", some("hasBase", ":ThinBase")),
            defined("ItalianPizza", ":Pizza", "[ a owl:Restriction ; owl:onProperty :hasCountryOfOrigin ; "
                    "owl:hasValue :Italy ]"),
            defined("VegetarianPizza", ":Pizza", f"[ a owl:Restriction ; owl:onProperty :hasTopping ; "
                    f"owl:allValuesFrom [ a owl:Class ; owl:unionOf ( {veg} ) ] ]"),
            defined("NonVegetarianPizza", ":Pizza", "[ a owl:Class ; owl:complementOf :VegetarianPizza ]"),
            defined("CheeseOrMeatPizza", ":Pizza", some("hasTopping", "[ a owl:Class ; owl:unionOf ( "
                                                                      ":CheeseTopping :MeatTopping ) ]")),
            ":HotTopping a owl:Class ; owl:equivalentClass " + hot + " .",
            ":InterestingFood a owl:Class ; owl:equivalentClass [ a owl:Class ; owl:unionOf ( :SpicyPizza "
            ":CheeseyPizza ) ] ."]


def _individuals(toppings: dict[str, list[str]]) -> list[str]:
    """About ten individuals whose types follow from the definitions (besides the countries)."""
    cheese, meat, veg = toppings["Cheese"][0], toppings["Meat"][0], toppings["Vegetable"][0]
    # each topping's spiciness value is the one its class implies: anything else is inconsistent
    cheese_spice, meat_spice = spiciness(CATEGORIES.index("Cheese"), 0), spiciness(CATEGORIES.index("Meat"), 0)
    return [f":mozzarella1 a owl:NamedIndividual, :{cheese} ; :hasSpiciness :{cheese_spice}Value .",
            f":salami1 a owl:NamedIndividual, :{meat} ; :hasSpiciness :{meat_spice}Value .",
            ":pepper1 a owl:NamedIndividual, :" + veg + " .",
            ":thin1 a owl:NamedIndividual, :ThinBase .",
            ":pizzaA a owl:NamedIndividual, :Pizza ; :hasTopping :mozzarella1, :salami1 ; :hasBase :thin1 .",
            ":pizzaB a owl:NamedIndividual ; :hasTopping :pepper1 ; :hasCountryOfOrigin :Italy .",
            ":pizzaC a owl:NamedIndividual, :Pizza1 .",
            ":snack1 a owl:NamedIndividual ; :isToppingOf :pizzaB ."]


def _functional(n: int) -> list[str]:
    """``n`` more properties, in turn a functional object property whose two values merge, an
    inverse-functional one whose two subjects merge and a functional data property with one value: a
    TBox whose rules grew by several per property before those properties were rows of a table."""
    lines = []
    for i in range(n):
        kind = i % 3
        if kind == 0:
            lines.append(f":fp{i} a owl:ObjectProperty, owl:FunctionalProperty . :fa{i} :fp{i} :fu{i}, :fv{i} .")
        elif kind == 1:
            lines.append(f":fp{i} a owl:ObjectProperty, owl:InverseFunctionalProperty . "
                         f":fa{i} :fp{i} :fo{i} . :fb{i} :fp{i} :fo{i} .")
        else:
            lines.append(f":fp{i} a owl:DatatypeProperty, owl:FunctionalProperty . :fa{i} :fp{i} {i} .")
    return lines


def _pairwise_disjoint(names: list[str]) -> list[str]:
    return [f":{a} owl:disjointWith :{b} ." for i, a in enumerate(names) for b in names[i + 1:]]


def timing(classes: int, folder: Path, functional: int = 0) -> dict[str, float | int]:
    """LOAD (``Ontology.from_file``: parse and compile) and two full REASONs of the TBox of ``classes``
    classes, in seconds of this process's wall clock, with what grows with it (triples, rules and their schema rows)."""
    import logging
    import time
    import warnings

    from topostore import Ontology

    path = write(classes, folder, functional)
    triples = sum(1 for _ in parse(path=str(path), format=RdfFormat.N_TRIPLES))
    notices = logging.getLogger("topostore.load")
    level = notices.level
    with warnings.catch_warnings():
        # the LOAD notices (unions as superclasses, ...) are warned and logged: said, not measured
        warnings.simplefilter("ignore")
        notices.setLevel(logging.ERROR)
        start = time.perf_counter()
        onto = Ontology.from_file(path)
        loaded = time.perf_counter()
        onto.reason(mode="full")
        first = time.perf_counter()
        onto.reason(mode="full")
        second = time.perf_counter()
        notices.setLevel(level)
    rules = onto.rules
    return {"classes": classes, "triples": triples, "rules": len(rules.rules),
            "rows": len(rules.compiled_rules()) - len(rules.rules), "load_s": loaded - start,
            "first_full_s": first - loaded, "second_full_s": second - first}


def timing_table(sizes: list[int], folder: Path, functional: int = 0) -> list[str]:
    """Markdown rows of :func:`timing` per size, then how LOAD grows from the smallest size to the largest."""
    rows = [timing(n, folder, functional) for n in sizes]
    lines = ["| classes | triples | rules (+ schema rows) | LOAD | first full REASON | second full REASON |",
             "|---|---|---|---|---|---|"]
    lines += [f"| {r['classes']} | {r['triples']:,} | {r['rules']:,} (+ {r['rows']:,}) | {r['load_s']:.2f} s "
              f"| {r['first_full_s']:.2f} s "
              f"| {r['second_full_s']:.2f} s |" for r in rows]
    if len(rows) > 1:
        small, big = rows[0], rows[-1]
        lines.append(f"growth from {small['classes']} to {big['classes']} classes: triples "
                     f"×{big['triples'] / small['triples']:.1f}, LOAD ×{big['load_s'] / small['load_s']:.1f}, "
                     f"first full REASON ×{big['first_full_s'] / small['first_full_s']:.1f}")
    return lines


def steps_table(sizes: list[int], steps: int, folder: Path) -> None:
    """Print the table of :mod:`benchmarks.tbox_steps` for each size (in this process); exit 3 on a mismatch."""
    import sys

    from . import tables, tbox_steps

    rows = []
    for n in sizes:
        (folder / str(n)).mkdir()
        rows.append(tbox_steps.run(n, steps, folder / str(n)))
    print(tables.tbox_steps_table(rows))
    if any(r["mismatches"] for r in rows):
        sys.exit(3)


def main(argv: list[str] | None = None) -> None:
    """``python -m benchmarks.tbox [N]`` prints the Turtle of N classes; ``--time N [N ...]`` times the
    LOAD and the full REASONs of each size instead, ``--steps S N [N ...]`` S robot-like steps on each."""
    import argparse
    import tempfile

    parser = argparse.ArgumentParser(prog="python -m benchmarks.tbox", description=main.__doc__)
    parser.add_argument("classes", nargs="*", type=int, help="named classes (default 100)")
    parser.add_argument("--time", action="store_true", help="time LOAD and full REASON per size (a table)")
    parser.add_argument("--steps", type=int, metavar="S",
                        help="time S robot-like steps per size, each checked against a full REASON (a table)")
    parser.add_argument("--functional", type=int, default=0, metavar="F",
                        help="F more functional, inverse-functional and functional data properties, in turn")
    args = parser.parse_args(argv)
    sizes = args.classes or [100]
    if not args.time and not args.steps:
        print(turtle(sizes[0], args.functional), end="")
        return
    from .limits import lift_time_limit

    lift_time_limit()
    with tempfile.TemporaryDirectory() as folder:
        if args.time:
            print("\n".join(timing_table(sizes, Path(folder), args.functional)))
        if args.steps:
            steps_table(sizes, args.steps, Path(folder))


if __name__ == "__main__":
    main()
