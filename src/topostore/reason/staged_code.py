"""A staged run's program written once as one Python function: its parts inline, no dispatch per operation.

Why this exists
---------------
A robot step runs the same program (its change signature's) hundreds of times between two full runs.
Interpreted (:meth:`.staged.StagedRun.run`), every run walks the program's parts and operations again:
each operation's bound tuple unpacked, its kind found among a chain of string tests, the part's flags
re-read.  What that walk decides — which kind each operation is, which key it starts from, whether its
part can hand a flip's heads over, which tests a part's run depends on — is the program's, so it is
decided here once and written out as straight-line code: a part's test an ``if`` over the run's sets,
each operation the few statements its kind needs, the bound values (texts, look-ups, keys) constants
of the function's namespace.

What runs stays the interpreted run's: the same look-ups in the same order, the same notes, and where an
operation's look-up gives up, the same methods of :class:`.staged.StagedRun` queue its text.  A run on a
store where a look-up is a round trip, and a switched-off generator (:data:`GENERATED`), take the
interpreted form; :func:`run` says which one ran, for :class:`.stats.ReasonStats`.
"""

from __future__ import annotations

from collections.abc import Callable
from itertools import islice

from .component import run_component
from .delta_texts import FLIP_LOST, KEEP
from .direct import ALL_KEPT, pattern_of
from .regroup import REGROUPED
from .scratch import CANDIDATES, FLIP_GAINED, NEW_FACTS, OVERDELETED
from .staged import FEW
from .staged_plan import AFTER, BOTH, HANDED, SEEDING, SENT, BoundOp, Segment, segments

#: False runs every program interpreted (the reference the generated form is tested against)
GENERATED = True


def run(staged) -> str:
    """Run ``staged`` (a :class:`.staged.StagedRun`) through its program's generated function where one
    applies, else interpreted; which form ran (``"generated"``, or ``"interpreted: why"``)."""
    if not GENERATED:
        staged.run()
        return "interpreted: generated form switched off"
    if staged.direct is not staged.program.direct:
        staged.run()
        return "interpreted: look-ups are round trips"
    program = staged.program
    fused = program.fused
    if fused is None:
        if program.segments is None:
            program.segments = segments(program, staged.direct)
        fused = program.fused = generate(program.segments)
    fused(staged)
    return "generated"


def generate(plan: list[Segment]) -> Callable:
    """The function running ``plan`` (a program's :func:`.staged_plan.segments`) as
    :meth:`.staged.StagedRun.run` would: ``fused(staged)``."""
    code = _Code()
    for segment in plan:
        if segment.component is not None:
            code.component(segment.component)
        else:
            code.segment(segment)
    code.line("r.flush()")
    namespace = dict(code.consts, run_component=run_component, islice=islice, FEW=FEW, CANDIDATES=CANDIDATES,
                     ALL_KEPT=ALL_KEPT, REGROUPED=REGROUPED,
                     KEEP=KEEP, FLIP_GAINED=FLIP_GAINED, FLIP_LOST=FLIP_LOST, NEW_FACTS=NEW_FACTS,
                     OVERDELETED=OVERDELETED)
    text = "def fused(r):\n" + "\n".join(code.lines) + "\n"
    exec(compile(text, "<topostore staged>", "exec"), namespace)  # noqa: S102 - text made above, no input
    return namespace["fused"]


class _Code:
    """The lines of one generated run and the constants they name."""

    def __init__(self) -> None:
        self.lines = ["    store = r.store", "    has = store.has_match",
                      "    minus, plus, unnoted, dirty = r.minus, r.plus, r.unnoted, r.dirty"]
        self.consts: dict[str, object] = {}

    def const(self, value: object) -> str:
        """A name for ``value`` in the function's namespace."""
        name = f"c{len(self.consts)}"
        self.consts[name] = value
        return name

    def line(self, text: str, depth: int = 1) -> None:
        self.lines.append("    " * depth + text)

    def component(self, component) -> None:
        """A recursive component: what is queued sent, every unnoted key noted, its rounds run."""
        self.line("r.flush()")
        self.line("for key in list(unnoted):")
        self.line("r._changed(key, minus)", 2)
        self.line(f"run_component(r, {self.const(component)})")

    def segment(self, segment: Segment) -> None:
        """A key's part: its one set test (none where it always runs), then its operations."""
        depth = 1
        if not segment.always:
            tests = []
            if segment.minus:
                tests.append(f"{self.const(segment.minus)}.isdisjoint(minus)")
            if segment.plus:
                tests.append(f"{self.const(segment.plus)}.isdisjoint(plus)")
            if segment.keys:
                tests.append(f"{self.const(segment.keys)}.isdisjoint(unnoted)")
            if not tests:
                return  # nothing starts it: it never runs
            self.line(f"if not ({' and '.join(tests)}):")
            depth = 2
        _Part(self, depth).write(segment.ops)


class _Part:
    """The operations of one part as statements, with the part's flags as locals (``_part``'s)."""

    def __init__(self, code: _Code, depth: int) -> None:
        self.code = code
        self.depth = depth
        #: whether a flip before this operation may have kept its heads (``handed`` may be a dictionary)
        self.may_hand = False
        #: ``_part``'s ``found`` as locals: by (graph or "kept" / "many", key), the local's name
        self.found: dict[tuple, str] = {}

    def line(self, text: str, extra: int = 0) -> None:
        self.code.line(text, self.depth + extra)

    def write(self, ops: list[BoundOp]) -> None:
        self.line("seeded = queued = flipped = False")
        self.line("mark = r.sent")
        self.line("handed = None")
        self.line("taken = set()")
        start = len(self.code.lines)
        for op in ops:
            if op.flip is not None:
                self._flip(op)
            else:
                self._op(op, "T", "True", "None", 0)
        if self.found:
            self.code.lines.insert(start, "    " * self.depth + " = ".join(self.found.values()) + " = None")
        if self.may_hand:
            self.line("if handed and len(taken) < len(handed):")
            self.line("r._spill(handed, taken)", 1)

    def _flip(self, op: BoundOp) -> None:
        """A flip: its text for this run, its heads handed over where its look-up finds them, else
        its look-up or text run as its kind's (``seeds``)."""
        c = self.code.const
        text, tag, part_reads = c(op.text), c(op.flip), c(op.part_reads)
        extra = 0
        if op.needs:
            self.line(f"if not r._without_facts({c(op.needs)}):")
            extra = 1
        lazy = op.direct is not None
        self.line(f"text = r._flip({part_reads}, {tag}, {text}, {lazy})", extra)
        self.line("if text:", extra)
        extra += 1
        self.line("flipped = True", extra)
        self.line(f"look_up = text is {text}", extra)
        fallback = f"({tag}, {text}, {part_reads})" if lazy else "None"
        if op.hand is not None:
            self.may_hand = True
            self.line("heads = None", extra)
            self.line("if look_up and handed is not False:", extra)
            self.line(f"heads = r._heads({c(op.hand)}, {c(op.reads)})", extra + 1)
            self.line("if heads is not None:", extra + 1)
            self.line("if handed is None:", extra + 2)
            self.line("handed = {FLIP_GAINED: {}, FLIP_LOST: {}}", extra + 3)
            self.line("handed[FLIP_GAINED].update(dict.fromkeys(heads[0]))", extra + 2)
            self.line("handed[FLIP_LOST].update(dict.fromkeys(heads[1]))", extra + 2)
            self.line("if heads is None:", extra)
            extra += 1
        if self.may_hand:
            self.line("if handed:", extra)
            self.line("r._spill(handed)", extra + 1)
        self.line("handed = False", extra)
        self._op(op, "text", "look_up", fallback, extra)

    def _op(self, op: BoundOp, text: str, look_up: str, fallback: str, extra: int) -> None:
        """One operation as ``_part`` runs it, its kind decided here (``text``, ``look_up``, ``fallback``:
        the flip's run values, or the operation's own)."""
        c = self.code.const
        kind, key = op.kind, c(op.key)
        if text == "T":
            text = c(op.text)
        if op.covered_by is not None:  # done by the part's regrouped candidates operation where it diffed
            self.line(f"if not {self._local('regrouped', op.covered_by)}:", extra)
            extra += 1
        if op.flip is None and kind in HANDED and self.may_hand:
            self._handed(op, key, text, extra)
            self.line("else:", extra)
            extra += 1
        if kind == "changes":
            self.line("if r.changes is not None:", extra)
            self.line("store.add_scratch(r.changes[0], NEW_FACTS)", extra + 1)
            self.line("store.add_scratch(r.changes[1], OVERDELETED)", extra + 1)
            self.line("else:", extra)
            self._send(op, text, look_up, fallback, extra + 1)
        elif kind == "keep":
            self._keep(op, text, extra)
        elif kind == "delete":
            kept = self._local("kept", op.key)
            holds = self._holds(CANDIDATES, op.key, extra, f"not {kept}")
            self.line(f"if not {kept} and {holds}:", extra)
            self._send(op, text, look_up, fallback, extra + 1, needs=False)
        elif kind in SENT:
            self._send(op, text, look_up, fallback, extra)
        elif kind in ("minus", "plus"):
            self._note(op.key, extra)
            self.line(f"if {key} in {kind}:", extra)
            self._send(op, text, look_up, fallback, extra + 1)
        elif kind in AFTER:
            flipped = "" if kind == "recheck" else "flipped"
            holds = self._holds(AFTER[kind], op.key, extra, flipped)
            self.line(f"if {flipped + ' and ' if flipped else ''}{holds}:", extra)
            self._send(op, text, look_up, fallback, extra + 1)
        elif kind == "end":
            if self.may_hand:
                self.line("if handed and len(taken) < len(handed):", extra)
                self.line("r._spill(handed, taken)", extra + 1)
                self.line("handed = False", extra + 1)
            self.line("if queued or r.sent != mark:", extra)
            self.line(f"unnoted.add({key})", extra + 1)
        else:
            self.line("pass", extra)

    def _local(self, what: object, key: object) -> str:
        """The local standing for ``found[(what, key)]``."""
        name = self.found.get((what, key))
        if name is None:
            name = self.found[(what, key)] = f"f{len(self.found)}"
        return name

    def _has(self, key: object, graph: str) -> str:
        """An expression: whether ``graph`` (a name) holds a fact of ``key`` (``StagedRun.has``, its pattern made now)."""
        return f"has(*{self.code.const(pattern_of(key))}, {graph})"

    def _holds(self, graph: object, key: object, extra: int, first: str = "") -> str:
        """``StagedRun._holds``: lines looking up once per part whether ``graph`` holds facts of ``key``
        (only where ``first``, an expression, holds), and the expression of the answer."""
        name = self._local(graph, key)
        tests = [first] if first else []
        if graph is CANDIDATES:
            tests.append("seeded")  # nothing could have made candidates
        self.line(f"if {' and '.join([*tests, f'{name} is None'])}:", extra)
        self.line("if dirty:", extra + 1)
        self.line(f"r._reading({self.code.const((key,))})", extra + 2)
        self.line(f"{name} = {self._has(key, self.code.const(graph))}", extra + 1)
        return f"seeded and {name}" if graph is CANDIDATES else name

    def _note(self, key: object, extra: int) -> None:
        """``StagedRun._changed``'s look-up: where ``key``'s part ran unnoted, whether it lost or gained facts."""
        name = self.code.const(key)
        self.line(f"if {name} in unnoted:", extra)
        self.line(f"unnoted.discard({name})", extra + 1)
        self.line("if dirty:", extra + 1)
        self.line(f"r._reading({self.code.const((key,))})", extra + 2)
        self.line(f"if {self._has(key, 'OVERDELETED')}:", extra + 1)
        self.line(f"minus.add({name})", extra + 2)
        self.line(f"if {self._has(key, 'NEW_FACTS')}:", extra + 1)
        self.line(f"plus.add({name})", extra + 2)

    def _keep(self, op: BoundOp, text: str, extra: int) -> None:
        """``StagedRun._keep``: one recheck of a key unless every candidate is kept already; while the key has
        few candidates, the candidates and kept ones compared after it (term by term)."""
        c = self.code.const
        kept, many = self._local("kept", op.key), self._local("many", op.key)
        holds = self._holds(CANDIDATES, op.key, extra, f"not {kept}")
        self.line(f"if not {kept} and {holds}:", extra)
        self.line("q = False", extra + 1)
        self._send(op, text, "True", "None", extra + 1, needs=False, key=op.key, into="q", kept=kept)
        self.line(f"if {many}:", extra + 1)
        self.line("queued |= q", extra + 2)  # else it is looked up (sent) below: ``_keep`` answers False
        self.line(f"elif not {kept}:", extra + 1)  # its look-up kept every candidate (ALL_KEPT): nothing to read
        self.line("if dirty:", extra + 2)
        self.line(f"r._reading({c((op.key,))})", extra + 3)
        pattern = c(pattern_of(op.key))
        self.line(f"candidates = list(islice(store.triples(*{pattern}, CANDIDATES), FEW))", extra + 2)
        self.line("if len(candidates) >= FEW:", extra + 2)
        self.line(f"{many} = True", extra + 3)
        self.line(f"elif set(candidates) <= set(islice(store.triples(*{pattern}, KEEP), FEW)):", extra + 2)
        self.line(f"{kept} = True", extra + 3)

    def _handed(self, op: BoundOp, key: str, text: str, extra: int) -> None:
        """A lost or gained operation given the part's flips' heads (while they were all kept here)."""
        graph = self.code.const(HANDED[op.kind])
        self.line("if handed:", extra)
        self.line(f"facts = list(handed[{graph}])", extra + 1)
        self.line(f"taken.add({graph})", extra + 1)
        self.line("if facts:", extra + 1)
        self.line("if dirty:", extra + 2)
        self.line(f"r._reading({self.code.const(op.reads)})", extra + 3)
        inner = extra + 2
        if op.hand is not None:
            self.line(f"if {self.code.const(op.hand)}(store, facts):", extra + 2)
            self.line("r.sent += 1", extra + 3)
            self.line("else:", extra + 2)
            inner += 1
        self.line(f"store.add_scratch(facts, {graph})", inner)  # its text reads them from the graph
        self.line(f"queued |= r._queue({text}, {self.code.const(op.part)}, False)", inner)
        if op.kind in SEEDING:
            self.line("seeded = True", extra + 2)

    def _has_seeded(self, op: BoundOp) -> str:
        """The operation's position where it has a seeded text (``_part``'s ``has_seeded and index``)."""
        return repr(op.index) if op.has_seeded else "False"

    def _send(self, op: BoundOp, text: str, look_up: str, fallback: str, extra: int, needs: bool = True,
              key: object = None, into: str = "queued", kept: str | None = None) -> None:
        """``_part``'s send of one operation: left out where a key it joins has no facts, through its look-up
        where one answers (inline), else queued by :meth:`.staged.StagedRun._queue`; ``kept``: a recheck's
        local set where its look-up answers that every candidate of its key is kept (:data:`.direct.ALL_KEPT`)."""
        c = self.code.const
        if needs and op.needs is not None:
            self.line(f"if not r._without_facts({c(op.needs)}):", extra)
            extra += 1
        position = self._has_seeded(op)
        part, reads = c(op.part if key is None else key), c(op.reads)
        # a flip's keys of the new state, looked up before its text is queued (``StagedRun._finds_nothing``)
        joins = f", {c(op.needs)}" if op.flip is not None and op.needs is not None else ""
        if op.direct is None:
            self.line(f"{into} |= r._queue({text}, {part}, {position}, {look_up}, None{joins})", extra)
        else:
            inner = extra
            if look_up != "True":  # a flip whose text a window narrowed runs its text, not its look-up
                self.line(f"if not {look_up}:", extra)
                self.line(f"{into} |= r._queue({text}, {part}, {position}, False, None{joins})", extra + 1)
                self.line("else:", extra)
                inner += 1
            self.line("if dirty:", inner)
            self.line(f"r._reading({reads})", inner + 1)
            if op.given == BOTH:  # a regrouped candidates operation: where it diffed, what it does is done
                name = self._local("regrouped", op.index)
                key = c(op.key)
                self.line(f"answer = {c(op.direct)}(store, r.change_facts({key}, 1), r.change_facts({key}, 0))",
                          inner)
                self.line("if answer:", inner)
                self.line("r.sent += 1", inner + 1)
                self.line(f"{name} = answer is REGROUPED", inner + 1)
            elif kept is None:
                given = "" if op.given is None else f", r.change_facts({c(op.key)}, {op.given})"
                self.line(f"if {c(op.direct)}(store{given}):", inner)
                self.line("r.sent += 1", inner + 1)
            else:
                self.line(f"answer = {c(op.direct)}(store)", inner)
                self.line("if answer:", inner)
                self.line("r.sent += 1", inner + 1)
                self.line(f"{kept} = answer is ALL_KEPT", inner + 1)
            self.line("else:", inner)
            self.line(f"{into} |= r._queue({text}, {part}, {position}, {look_up}, {fallback}{joins})", inner + 1)
        if op.kind in SEEDING:
            self.line("seeded = True", extra)
