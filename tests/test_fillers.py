"""The filler index (topostore.compile.fillers) finds exactly the restrictions a pairwise test finds."""

from __future__ import annotations

import random

from pyoxigraph import NamedNode

from topostore.compile.fillers import FillerIndex
from topostore.compile.model import Expr, Prop, TBox
from topostore.compile.owl import OwlCompiler

EX = "http://e.org/f#"
P = Prop(NamedNode(EX + "p"))


def named(i: int) -> Expr:
    return Expr(NamedNode(f"{EX}C{i}"), "named")


class Fillers:
    """Random class expressions over a few named classes: named, unions, intersections, nested."""

    def __init__(self, rng: random.Random) -> None:
        self.rng = rng
        self.count = 0

    def node(self) -> NamedNode:
        self.count += 1
        return NamedNode(f"{EX}e{self.count}")

    def filler(self, depth: int = 0) -> Expr:
        kind = self.rng.choice(["named", "named", "or", "and", "not"] if depth < 2 else ["named"])
        if kind == "named":
            return named(self.rng.randrange(6))
        if kind == "not":
            return Expr(self.node(), "not", members=(self.filler(depth + 1),))
        members = tuple(self.filler(depth + 1) for _ in range(self.rng.randrange(1, 4)))
        return Expr(self.node(), kind, members=members)

    def restriction(self, fillers: list[Expr]) -> Expr:
        roll = self.rng.random()
        if roll < 0.1:
            return Expr(self.node(), "some", prop=P)  # no filler: every value
        if roll < 0.2:
            return Expr(self.node(), "some", prop=P, datatype=NamedNode("http://www.w3.org/2001/XMLSchema#int"))
        return Expr(self.node(), "some", prop=P, filler=self.rng.choice(fillers))


def test_the_index_finds_what_the_pairwise_test_finds() -> None:
    through_unions = 0  # subsumptions by a union of another node: the case the index narrows most
    for seed in range(40):
        rng = random.Random(seed)
        tb = TBox()
        tb.subclass = [(named(a), named(b)) for a in range(6) for b in range(6) if a != b and rng.random() < 0.2]
        make = Fillers(rng)
        fillers = [make.filler() for _ in range(12)]
        fillers += [f.members[0] for f in fillers if f.kind == "not"]  # a union's member may be shared
        restrictions = [make.restriction(fillers) for _ in range(30)]
        owl = OwlCompiler(tb)
        index = FillerIndex(owl.subsumption, restrictions)
        for a in restrictions:
            expected = [b for b in restrictions if owl.filler_subsumed(a, b)]
            assert index.subsuming(a) == expected, (seed, a)
            through_unions += sum(1 for b in expected if b.filler is not None and b.filler.kind == "or"
                                  and a.filler is not None and a.filler.node != b.filler.node)
    assert through_unions > 20
