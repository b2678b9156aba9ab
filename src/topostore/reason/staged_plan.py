"""A compiled step's program grouped by part once, each operation with what a run looks up about it.

A staged run (:mod:`.staged`) goes through a program part by part, many times between two full runs;
what it would look up about each operation at every run (the key of its part, its look-up equivalent
and the keys that one reads, the form its heads are handed in) depends only on
the program, which is its change signature's: it is bound here once, when the program first runs.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from typing import NamedTuple

from ..compile.rule import ReadKey
from .delta_texts import FLIP_LOST
from .direct import GIVEN, OneAtom, Relaxed, pattern_of
from .look_join import Joined
from .program import StepProgram
from .regroup import Regroup
from .scratch import CANDIDATES, FLIP_GAINED
from .triggers import may_hold

#: operations that run only when a graph holds facts of their key: the key's candidates are rechecked,
#: its flipped-false facts become candidates, its flipped-true facts are added
AFTER = {"recheck": CANDIDATES, "lost": FLIP_LOST, "gained": FLIP_GAINED}
#: operations sent whenever their part runs, and those after which the part's key may have candidates
SENT = frozenset(("always", "seeds", "changes"))
SEEDING = frozenset(("seeds", "minus", "lost"))
#: the operations a part's flips hand their heads to, and the graph each would read them from
HANDED = {"lost": FLIP_LOST, "gained": FLIP_GAINED}
#: the operations left out where a key they join has no facts (:attr:`BoundOp.needs`): the candidates
#: from a key's lost facts (no derivation through them before the change) and the additions from its
#: gained ones, which add to scratch or state graphs only what they find (never a recheck, which deletes
#: what it does not find)
NEEDING = frozenset(("minus", "plus"))


class BoundOp(NamedTuple):
    """One operation of a program with what every run would look up about it, bound once (:func:`_bound`);
    a run unpacks it as a plain tuple."""

    index: int
    kind: str
    key: ReadKey | None
    text: str
    flip: tuple | None
    #: the key of its part (None: of no key's)
    part: ReadKey | None
    #: its look-up equivalent (None: none) and the keys that one reads
    direct: Callable | None
    reads: Collection | None
    has_seeded: bool
    #: for a flip, the keys its part reads (those its window query reads)
    part_reads: Collection | None
    #: a flip's heads found without writing them (:meth:`.look_flip.Flipped.heads`), or a lost or gained
    #: operation given them (:meth:`.direct.Lost.handed`); None: the operation has no such form
    hand: Callable | None = None
    #: keys of the new state without whose facts it finds nothing: a flip's atoms it does not compare
    #: (:attr:`.program.StepProgram.needs`), the premises an addition joins (its look-up's ``needs``); each
    #: as (key, 0 for a predicate or 1 for a class, name) (:func:`_named`)
    needs: tuple | None = None
    #: a ``minus`` or ``plus`` look-up that may be given its key's lost or gained facts from the run's
    #: change (:meth:`.staged.StagedRun.change_facts`), as (its side of the change: 0 added, 1 removed);
    #: None: it reads them from OVERDELETED or NEW_FACTS (see :func:`_given`)
    given: int | None = None
    #: the position of the regrouped candidates operation that does this one where it answers
    #: :data:`.regroup.REGROUPED` (:attr:`.program.StepProgram.covered`); None: none
    covered_by: int | None = None


def _named(keys: Collection | None) -> tuple | None:
    """``keys`` as a run tests them (:meth:`.staged.StagedRun._without_facts`): each with the set of the
    keys with facts it is looked up in (0: predicates, 1: classes) and its name; a key of any predicate
    is left out (it is never without facts), and None where none is left."""
    found = tuple((key, 1 if key[0] == "t" else 0, key[1]) for key in keys or () if key[0] != "*")
    return found or None


class Segment:
    """A key's part of a program (its operations up to its ``end``), or a recursive component, with
    what decides in one set test whether any of its operations can run this time."""

    __slots__ = ("always", "component", "keys", "minus", "ops", "plus")

    def __init__(self, ops: list[BoundOp], component=None) -> None:
        #: per operation, what :meth:`StagedRun._part` reads of it (:func:`_bound`)
        self.ops = ops
        self.component = component
        kinds = {op.kind for op in ops}
        #: an operation runs whatever changed (a flip, the asserted changes, a key's seeds), or the
        #: part has no end (its key is not noted as the run expects): the part always runs
        self.always = any(op.flip is not None for op in ops) or bool(kinds & SENT) or "end" not in kinds
        #: the keys whose lost / gained facts start an operation
        self.minus = frozenset(op.key for op in ops if op.kind == "minus")
        self.plus = frozenset(op.key for op in ops if op.kind == "plus")
        self.keys = self.minus | self.plus


def segments(program: StepProgram, direct: dict | None = None) -> list[Segment]:
    """The program's operations grouped by part, each resolved once to its kind, key, flip tag and what
    a run looks up about it (:func:`_bound`; ``direct``: the look-up operations a run uses, by position).

    Without a flip, the asserted changes or a key's seeds, a part's operations run only after a
    ``minus`` or ``plus`` operation whose key lost or gained facts: its rechecks need candidates
    (seeded by those), its flip results a flip of its own."""
    out: list[Segment] = []
    ops: list[BoundOp] = []
    for index, (tag, text) in enumerate(program.ops):
        if tag[0] == "component":
            if ops:
                out.append(Segment(ops))
                ops = []
            out.append(Segment([], tag[1]))
            continue
        flip = None
        if tag[0] == "flip":
            flip, tag = tag, tag[1]
        ops.append(_bound(program, direct if direct is not None else program.direct, index, tag, text, flip))
        if tag[0] == "end":
            out.append(Segment(ops))
            ops = []
    if ops:
        out.append(Segment(ops))
    return out


def _bound(program: StepProgram, direct: dict, index: int, tag: tuple, text: str, flip: tuple | None) -> BoundOp:
    """Operation ``index`` with what every run would look up about it (:class:`BoundOp`), once per program
    (a program is its change signature's; a TBox or rule change drops them all)."""
    part = program.part[index]
    found = direct.get(index)
    owner = getattr(found, "__self__", None)
    hand = getattr(owner, "heads" if flip is not None else "handed", None) \
        if flip is not None or tag[0] in HANDED else None
    if flip is not None:
        needs = _named(program.needs.get(index))
    else:
        needs = _named(getattr(owner, "needs", {}).get(getattr(found, "__name__", None))) \
            if tag[0] in NEEDING else None
    return BoundOp(index, tag[0], tag[1] if len(tag) > 1 else None, text, flip, part, found,
                   program.reads[index] if found is not None else None, index in program.seeded,
                   (program.reads[part] if part is not None else (None,)) if flip is not None else None, hand,
                   needs, _given(program, tag, found), program.covered.get(index))


#: :attr:`BoundOp.given` of a :class:`.regroup.Regroup`: given both sides of the change (removed, added)
BOTH = 2


def _given(program: StepProgram, tag: tuple, found: Callable | None) -> int | None:
    """:attr:`BoundOp.given` of an operation: its side of the change where it is a ``minus`` or ``plus``
    look-up taking its facts (:data:`.direct.GIVEN`), the program writes the change to OVERDELETED and
    NEW_FACTS itself (its ``changes`` operation) and none of its rules writes the key (no head of the
    program, no part of one, no variable head: :func:`.triggers.may_hold`), so those graphs hold the
    change's facts of it and nothing else all run long, and the look-up's atom names no constant (it binds a fact
    without testing them: :func:`_read_shape`); else None."""
    if tag[0] not in NEEDING or tag[1][0] == "*" or found is None or getattr(found, "__name__", None) not in GIVEN:
        return None
    if not any(t[0] == "changes" for t, _ in program.ops):
        return None
    written = {*program.heads, *(k for k in program.part if k is not None)}
    if may_hold(written, tag[1]):
        return None
    owner = getattr(found, "__self__", None)
    if isinstance(owner, Regroup):
        return BOTH
    shape = _read_shape(owner)
    if shape is None or shape.free != pattern_of(tag[1]):
        return None
    return 1 if tag[0] == "minus" else 0


def _read_shape(owner: object):
    """The atom a look-up binds its key's facts to, or None where it is not one of the kinds that take them.
    A fact is bound without its atom's constants being tested (:class:`.atom_shape.Shape` expects facts read
    by the atom's own pattern), so the change's facts are handed over only to an atom naming no constant
    (its pattern the key's whole pattern): ``isIn(?r, :kitchen)`` must not bind ``isIn(robot, corridor)``."""
    if isinstance(owner, (OneAtom, Relaxed)):
        return owner._body
    if isinstance(owner, Joined):
        return owner._body[owner.delta]
    return None


__all__ = ["AFTER", "BOTH", "HANDED", "NEEDING", "SEEDING", "SENT", "BoundOp", "Segment", "segments"]
