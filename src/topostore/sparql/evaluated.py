"""The spellings a SPARQL update wrote of each value at each (subject, predicate), read from its evaluation.

Why: a load keeps the first spelling a document writes of one value at one subject and property and says each
other one; a change says a spelling the graph holds in another.  An update's delta is computed on a scratch
Oxigraph store, which keeps one canonical term per value, so which spellings reached a triple, and in which
order, is known only from what the update's evaluation instantiated, never from its text alone (a ``VALUES``
row, a ``FILTER`` or an empty ``WHERE`` decides whether a template's literal is written at all).  So the update
runs here one operation at a time, and before each one what it writes and removes is evaluated over the state
it sees: an ``INSERT DATA`` writes its own triples; an ``INSERT`` template is instantiated from the solutions
of its ``WHERE`` (a ``SELECT``, each top-level ``VALUES`` block given a row number so that a variable it binds
takes the spelling of the row that bound it); a ``DELETE`` template is evaluated as a ``CONSTRUCT``, ``DELETE
DATA`` removes its triples, and ``CLEAR`` / ``DROP`` of the default graph everything: a value removed starts
its count again.

A spelling is counted only where the evaluation shows it written: a template's literal, a ``VALUES`` cell or a
``BIND`` of one literal whose variable nothing else in the ``WHERE`` reads (Oxigraph compares and filters the
canonical value, so a ``FILTER(str(?v) = "7")`` could let a row pass that the written spelling would not).
Any other write of a value (bound from the store, computed, or read elsewhere) makes its position unsure: the
delta there is given as :func:`.written.as_written` gives it, and nothing is said of it.  An operation this
reading does not follow (``WITH``, ``USING``, ``ADD``, ``MOVE``, ``COPY``) leaves the whole update so.
Each step is linear in the triples the operation writes or removes.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

import pyoxigraph as ox
from pyoxigraph import BlankNode, DefaultGraph, Literal, NamedNode, QuerySolutions, RdfFormat, Triple, parse

from ..rdf.lexer import KEYWORD, NAME, VARIABLE, tokens
from ..rdf.terms import Term, value_key
from .bound import Operation, ValuesBlock, split, where_bindings
from .written import as_written, block_triples, braced, paired, variable_name

#: a position's value: (subject, predicate, value key); an INSERT DATA's blank node subject is keyed as written
Key = tuple[object, object, tuple]
#: the name of the row number given to the n-th VALUES block of a WHERE
_ROW = "topostore_spelled_row_"


@dataclass
class Spellings:
    """What the operations wrote so far: at each position the first spelling since its value was last removed
    (None: unsure), each other one in the order written, the positions removed, and whether every one was."""

    first: dict[Key, Literal | None] = field(default_factory=dict)
    others: dict[Key, list[Literal]] = field(default_factory=dict)
    removed: set[Key] = field(default_factory=set)
    cleared: bool = False
    followed: bool = True
    #: the blank nodes of the INSERT DATA operations' triples, and those triples (their shapes pair them)
    nodes: list[Triple] = field(default_factory=list)

    def write(self, s: object, p: object, lit: Literal, sure: bool) -> None:
        key = (s, p, value_key(lit))
        if key not in self.first:
            self.first[key] = lit if sure else None
        elif sure and (kept := self.first[key]) is not None and kept != lit:
            others = self.others.setdefault(key, [])
            if lit not in others:
                others.append(lit)

    def remove(self, s: object, p: object, o: object) -> None:
        if isinstance(o, Literal):
            key = (s, p, value_key(o))
            self.first.pop(key, None)
            self.others.pop(key, None)
            self.removed.add(key)

    def clear(self) -> None:
        self.first.clear()
        self.others.clear()
        self.cleared = True


def run(scratch: ox.Store, text: str) -> Spellings | None:
    """Apply the update ``text`` to ``scratch`` one operation at a time, what each writes and removes read
    first; None where an operation does not run alone (the caller runs the whole text, whose error is the
    user's)."""
    seen = Spellings()
    ops = split(text)
    if not _runs_apart(ops):
        return None
    for op in ops:
        try:
            _read(scratch, op, seen)
            scratch.update(op.text)
        except (SyntaxError, OSError, RuntimeError, ValueError):
            return None
    return seen


def _runs_apart(ops: list[Operation]) -> bool:
    """Whether each operation run alone is what the whole text does: not where a blank node label is written
    in two operations (the request is refused as a whole: a label may not be shared by two blocks) nor where a
    later operation declares a prefix or base (Oxigraph refuses a prologue after ``;``).  Elsewhere the text's
    own error is the user's, and the whole text is run to give it."""
    labels: set[str] = set()
    for n, op in enumerate(ops):
        if n and any(t.kind == KEYWORD and t.word in ("PREFIX", "BASE") for t in op.toks):
            return False
        own = {t.text for t in op.toks if t.kind == NAME and t.text.startswith("_:")}
        if not labels.isdisjoint(own):
            return False
        labels |= own
    return True


def _read(scratch: ox.Store, op: Operation, seen: Spellings) -> None:
    """Record what ``op`` writes and removes, over the state it sees."""
    words = [t.word for t in op.toks if t.kind == KEYWORD]
    head = next((w for w in words if w not in ("PREFIX", "BASE")), None)
    if head is None or head in ("CREATE", "LOAD"):
        return
    if head in ("CLEAR", "DROP"):
        target = next((w for w in words[words.index(head) + 1:] if w != "SILENT"), None)
        if target not in ("GRAPH", "NAMED"):
            seen.clear()
        return
    if head in ("WITH", "USING") or "USING" in words or head not in ("INSERT", "DELETE"):
        seen.clear()
        seen.followed = False
        return
    start = next(i for i, t in enumerate(op.toks) if t.kind == KEYWORD and t.word == head)
    after = op.toks[start + 1].word if start + 1 < len(op.toks) and op.toks[start + 1].kind == KEYWORD else None
    if after == "DATA":
        _data(op, start, head, seen)
    elif head == "DELETE" and after == "WHERE":
        _removed(scratch, op, braced(op.toks, start + 2), None, seen)
    else:
        _modify(scratch, op, seen)


def _data(op: Operation, start: int, head: str, seen: Spellings) -> None:
    """An ``INSERT DATA`` writes its triples in order, a ``DELETE DATA`` removes them."""
    block = braced(op.toks, start + 1)
    triples = block_triples(op.source, op.toks, block, op.declarations) if block is not None else None
    if head == "DELETE":
        removed = triples if triples is not None else _default_graph(op, block)
        if removed is None:
            seen.clear()
        for t in removed or ():
            seen.remove(t.subject, t.predicate, t.object)
        return
    if triples is None:
        seen.clear()
        seen.followed = False
        return
    fresh: dict[BlankNode, BlankNode] = {}  # the blank nodes of one operation are its own
    for t in triples:
        s = fresh.setdefault(t.subject, BlankNode()) if isinstance(t.subject, BlankNode) else t.subject
        o = fresh.setdefault(t.object, BlankNode()) if isinstance(t.object, BlankNode) else t.object
        if s is not t.subject or o is not t.object:
            seen.nodes.append(Triple(s, t.predicate, o))
        if isinstance(o, Literal):
            seen.write(s, t.predicate, o, sure=True)


def _default_graph(op: Operation, block: tuple[int, int] | None) -> list[Triple] | None:
    """The default graph's triples of a ``DELETE DATA`` block that names graphs too (read as TriG); None where
    it does not read so (each value written so far then counts as removed)."""
    if block is None:
        return None
    body = op.source[op.toks[block[0]].start + 1:op.toks[block[1]].start]
    try:
        return [Triple(q.subject, q.predicate, q.object)
                for q in parse("\n".join([*op.declarations, body]), RdfFormat.TRIG)
                if isinstance(q.graph_name, DefaultGraph)]
    except (SyntaxError, ValueError):
        return None


#: the operations that may remove triples of the default graph
_REMOVING = frozenset({"DELETE", "CLEAR", "DROP", "MOVE", "COPY"})


def data_document(text: str) -> str:
    """The triples of ``text``'s ``INSERT DATA`` operations as one Turtle document (the prefixes and base in
    force declared before each): what a load of them reads, language tags as written.  Empty where the request
    also removes (``DELETE``, ``CLEAR``, ``DROP``, ``MOVE``, ``COPY``): a removal between two writes starts
    their count again, which a document of the writes alone cannot show, so no tag note is given there."""
    parts = []
    ops = split(text)
    if any(t.kind == KEYWORD and t.word in _REMOVING for op in ops for t in op.toks):
        return ""
    for op in ops:
        for i, t in enumerate(op.toks[:-1]):
            if t.kind == KEYWORD and t.word == "INSERT" and op.toks[i + 1].kind == KEYWORD \
                    and op.toks[i + 1].word == "DATA" and (block := braced(op.toks, i + 1)) is not None:
                body = op.source[op.toks[block[0]].start + 1:op.toks[block[1]].start].rstrip()
                parts.extend([*op.declarations, body if not body or body.endswith(".") else f"{body} ."])
    return "\n".join(parts)


def _modify(scratch: ox.Store, op: Operation, seen: Spellings) -> None:
    """A ``DELETE`` / ``INSERT`` … ``WHERE``: its removals, then its writes, over the solutions of its ``WHERE``."""
    toks, depth, at = op.toks, 0, {}
    for i, t in enumerate(toks):
        if t.text in "{}" and t.kind != KEYWORD:
            depth += 1 if t.text == "{" else -1
        elif depth == 0 and t.kind == KEYWORD and t.word in ("DELETE", "INSERT", "WHERE"):
            at.setdefault(t.word, i)
    if "WHERE" not in at:
        seen.clear()
        seen.followed = False
        return
    where = op.source[toks[at["WHERE"]].start:toks[-1].start + len(toks[-1].text)]
    if "DELETE" in at:
        _removed(scratch, op, braced(toks, at["DELETE"] + 1), where, seen)
    if "INSERT" in at:
        _inserted(scratch, op, braced(toks, at["INSERT"] + 1), at["WHERE"], seen)


def _removed(scratch: ox.Store, op: Operation, block: tuple[int, int] | None, where: str | None,
             seen: Spellings) -> None:
    """A ``DELETE`` template removes what it gives over the ``WHERE``'s solutions (``where`` None: the
    template is its own pattern, a ``DELETE WHERE``); one not evaluated removes everything."""
    if block is None:
        seen.clear()
        return
    template = op.source[op.toks[block[0]].start + 1:op.toks[block[1]].start]
    query = f"{op.prologue}\nCONSTRUCT {{ {template} }} " + (where if where is not None else f"WHERE {{ {template} }}")
    try:
        triples = list(scratch.query(query))
    except (SyntaxError, OSError, RuntimeError, ValueError):
        seen.clear()
        return
    for t in triples:
        if isinstance(t.subject, BlankNode):  # a node an INSERT DATA made: its positions are not keyed so
            seen.clear()
            return
        seen.remove(t.subject, t.predicate, t.object)


def _inserted(scratch: ox.Store, op: Operation, block: tuple[int, int] | None, where_at: int,
              seen: Spellings) -> None:
    """An ``INSERT`` template writes, for each solution of the ``WHERE`` in order, each of its triples whose
    terms are bound; its literal objects as spelled where the evaluation shows the spelling (see the module)."""
    template = block_triples(op.source, op.toks, block, op.declarations) if block is not None else None
    if template is None:
        seen.clear()
        seen.followed = False
        return
    template = [t for t in template if isinstance(t.object, Literal) or variable_name(t.object) is not None]
    if not template:
        return
    blocks, binds = where_bindings(op.source, op.toks, op.declarations)
    mentions: dict[str, int] = {}
    for t in op.toks[where_at:]:
        if t.kind == VARIABLE:
            mentions[t.text[1:]] = mentions.get(t.text[1:], 0) + 1
    blocks = [b for b in blocks if _numbered(op.source, b)]
    where = _with_rows(op.source, op.toks[where_at].start, op.toks[-1].start + len(op.toks[-1].text), blocks)
    try:
        solutions = scratch.query(f"{op.prologue}\nSELECT * {where}")
    except (SyntaxError, OSError, RuntimeError, ValueError):
        seen.clear()
        seen.followed = False
        return
    if not isinstance(solutions, QuerySolutions):
        return
    spelled = _Spelled(blocks, dict(binds), {name for name, n in mentions.items() if n == 1})
    for solution in solutions:
        for t in template:
            s, p = _bound(t.subject, solution), _bound(t.predicate, solution)
            if s is None or p is None or isinstance(s, Literal) or not isinstance(p, NamedNode):
                continue
            name = variable_name(t.object)
            if name is None:
                seen.write(s, p, t.object, sure=True)
            elif isinstance(value := _value(solution, name), Literal):
                written = spelled.at(name, value, solution)
                seen.write(s, p, written or value, sure=written is not None)


def _bound(term: object, solution: ox.QuerySolution) -> Term | None:
    """A template's subject or predicate in one solution (None: unbound, or a blank node of the template)."""
    if isinstance(term, BlankNode):
        return None
    name = variable_name(term)
    return term if name is None else _value(solution, name)  # type: ignore[return-value]


def _value(solution: ox.QuerySolution, name: str) -> Term | None:
    try:
        return solution[name]
    except (KeyError, IndexError):
        return None


def _numbered(source: str, block: ValuesBlock) -> bool:
    """Whether each row of ``block`` reads as terms (its ``UNDEF`` s as many as its cells read as none), so
    that it can be written again with a row number."""
    undef = sum(1 for t in tokens(source[block.start:block.end]) if t.kind == KEYWORD and t.word == "UNDEF")
    return undef == sum(cell is None for row in block.rows for cell in row)


def _with_rows(source: str, start: int, end: int, blocks: list[ValuesBlock]) -> str:
    """``source[start:end]`` (a WHERE clause) with each of ``blocks`` given a row number, ``?{_ROW}n``."""
    parts, pos = [], start
    for n, block in enumerate(blocks):
        rows = " ".join("(" + " ".join("UNDEF" if c is None else str(c) for c in row) + f" {r})"
                        for r, row in enumerate(block.rows))
        names = " ".join(f"?{name}" for name in block.names)
        parts.append(source[pos:block.start] + f"VALUES ({names} ?{_ROW}{n}) {{ {rows} }}")
        pos = block.end
    parts.append(source[pos:end])
    return "".join(parts)


@dataclass
class _Spelled:
    """The spellings a WHERE's own VALUES rows and BINDs of one literal give the variables nothing else reads."""

    blocks: list[ValuesBlock]
    binds: dict[str, Literal | NamedNode]
    alone: set[str]

    def at(self, name: str, value: Literal, solution: ox.QuerySolution) -> Literal | None:
        """The spelling ``solution`` bound ``name`` to (``value`` as evaluated), None where not shown."""
        if name not in self.alone:
            return None
        for n, block in enumerate(self.blocks):
            if name in block.names and isinstance(row := _value(solution, f"{_ROW}{n}"), Literal):
                cell = block.rows[int(row.value)][block.names.index(name)]
                return cell if isinstance(cell, Literal) and value_key(cell) == value_key(value) else None
        lit = self.binds.get(name)
        return lit if isinstance(lit, Literal) and value_key(lit) == value_key(value) else None


def added_as_written(added: list[Triple], seen: Spellings, text: str, held: Callable[[Literal], Term] | None,
                     present: Callable[[object, object], Iterable[Triple]]) -> tuple[list[Triple], list[Triple]]:
    """The update's added triples (as the scratch store gave them), each value at a position the evaluation
    followed given as first written there, followed by each other spelling written there (for the change to
    say it is not stored), and the positions whose value the graph held and the update wrote again: those
    spellings too (said as held), and where the update removed the value first, the held triple as removed
    (said as removed and added in one change).  ``present``: the triples the scratch store ends with at a
    subject and predicate.  Returns (added, also removed)."""
    nodes = paired(seen.nodes, added) if seen.nodes else {}
    keys = [(nodes.get(t.subject, t.subject), t.predicate, value_key(t.object)) if isinstance(t.object, Literal)
            else None for t in added]
    unsure = [t for t, key in zip(added, keys, strict=True) if seen.first.get(key) is None]  # type: ignore[arg-type]
    given = iter(as_written(unsure, text, held))  # the text's reading, where the evaluation showed no spelling
    out: list[Triple] = []
    emitted: set[Key] = set()
    for t, key in zip(added, keys, strict=True):
        first = seen.first.get(key) if key is not None else None
        if first is None:
            out.append(next(given))
        elif key not in emitted:  # a second term of the value (7, 7.0) is one of the spellings given here
            emitted.add(key)  # type: ignore[arg-type]
            out.extend(Triple(t.subject, t.predicate, lit) for lit in (first, *seen.others.get(key, ())))
    return out, _held(seen, emitted, present, out)


def _held(seen: Spellings, used: set[Key], present: Callable[[object, object], Iterable[Triple]],
          out: list[Triple]) -> list[Triple]:
    """Add to ``out`` the spellings written of each value the graph held and holds (no triple added for it);
    the held triples of those the update removed and wrote again."""
    by_pair: dict[tuple[object, object], list[Key]] = {}
    for key, first in seen.first.items():
        if first is not None and key not in used and isinstance(key[0], NamedNode):
            by_pair.setdefault((key[0], key[1]), []).append(key)
    removed: list[Triple] = []
    for (s, p), keys in by_pair.items():
        holding = {value_key(t.object): t for t in present(s, p) if isinstance(t.object, Literal)}
        for key in keys:
            kept = holding.get(key[2])
            if kept is None:
                continue
            out.extend(Triple(s, p, lit) for lit in (seen.first[key], *seen.others.get(key, ())))  # type: ignore[misc]
            if seen.cleared or key in seen.removed:
                removed.append(kept)
    return removed


__all__ = ["Operation", "Spellings", "added_as_written", "data_document", "run", "split"]
