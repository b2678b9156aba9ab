"""The terms an update's ``VALUES`` and ``BIND`` write for a variable, literals as its text spells them.

Why: an insert template such as ``INSERT { k:r k:p ?v } WHERE { VALUES ?v { "007"^^xsd:long } }`` writes its
literal through a variable: the scratch store that computes the update's delta keeps numbers canonical, so the
spelling is known only from the text.  :mod:`.written` puts these literals at the template positions of their
variable.  A value a ``WHERE`` pattern matches in the store is not read here: it keeps the spelling the store
holds.  A ``BIND`` of anything but one term (an expression, a function) has no spelling in the text.  The IRIs
they give a template's subject variable tell which subject each literal is written for.

The data blocks are read as Turtle, as the templates are: a ``VALUES`` block's rows become nested collections
(``( ( t1 t2 ) ( t3 t4 ) )``, ``UNDEF`` a placeholder), a ``BIND``'s expression the object of one triple.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from pyoxigraph import BlankNode, Literal, NamedNode, RdfFormat, parse

from ..rdf.lexer import IRI, KEYWORD, PUNCT, VARIABLE, Token, tokens
from ..rdf.vocab import INTERNAL, RDF

#: what UNDEF becomes in the Turtle read of a VALUES block (no value written)
_UNDEF = NamedNode(INTERNAL + "undefined-value")
_FIRST, _REST = NamedNode(RDF + "first"), NamedNode(RDF + "rest")

#: a variable's name (without ``?`` or ``$``) → the literals and IRIs VALUES and BIND write for it
Bound = dict[str, list[Literal | NamedNode]]


def bound_literals(text: str, toks: list[Token], declarations: list[str]) -> Bound:
    """The literals and IRIs each variable is given by a ``VALUES`` block or a ``BIND`` of one term in ``toks`` (one
    operation's tokens of ``text``); ``declarations``: the Turtle of the prefixes and base in force.

    Only a block in the ``WHERE`` clause's own group binds every solution: one inside an
    ``OPTIONAL``, a ``UNION`` branch, ``MINUS``, ``EXISTS`` or a subquery may bind none of the rows inserted, whose
    value then comes from the store and keeps the store's spelling, so those are not read."""
    out: Bound = {}
    blocks, binds = where_bindings(text, toks, declarations)
    for block in blocks:
        for row in block.rows:
            for name, cell in zip(block.names, row, strict=True):
                if cell is not None:
                    out.setdefault(name, []).append(cell)
    for name, term in binds:
        out.setdefault(name, []).append(term)
    return out


@dataclass
class ValuesBlock:
    """A ``VALUES`` block of a ``WHERE`` clause's own group: where it is in the text (``start``, ``end``), its
    variables' names and its rows (a term per variable, None for ``UNDEF`` or a cell not read as a term)."""

    start: int
    end: int
    names: list[str]
    rows: list[list[Literal | NamedNode | None]]


def where_bindings(text: str, toks: list[Token],
                   declarations: list[str]) -> tuple[list[ValuesBlock], list[tuple[str, Literal | NamedNode]]]:
    """The ``VALUES`` blocks and the ``BIND`` s of one term (variable name, term) of the ``WHERE`` clause's own
    group in ``toks`` (see :func:`bound_literals`)."""
    blocks: list[ValuesBlock] = []
    binds: list[tuple[str, Literal | NamedNode]] = []
    i, depth, where = 0, 0, False
    while i < len(toks):
        t = toks[i]
        if t.kind == PUNCT and t.text in "{}":
            depth += 1 if t.text == "{" else -1
        elif t.kind == KEYWORD and t.word == "WHERE" and depth == 0:
            where = True
        elif where and depth == 1 and t.kind == KEYWORD and t.word == "VALUES":
            i = _values(text, toks, i + 1, declarations, blocks)
            continue
        elif where and depth == 1 and t.kind == KEYWORD and t.word == "BIND":
            i = _bind(text, toks, i + 1, declarations, binds)
            continue
        i += 1
    return blocks, binds


def _values(text: str, toks: list[Token], i: int, declarations: list[str], out: list[ValuesBlock]) -> int:
    """Read the VALUES block whose variables start at ``toks[i]`` into ``out``; the index after it."""
    start = toks[i - 1].start
    names: list[str] = []
    single = i < len(toks) and toks[i].kind == VARIABLE
    if single:
        names.append(toks[i].text[1:])
        i += 1
    elif i < len(toks) and toks[i].text == "(":
        i += 1
        while i < len(toks) and toks[i].kind == VARIABLE:
            names.append(toks[i].text[1:])
            i += 1
        i += 1  # the ")"
    if not names or i >= len(toks) or toks[i].text != "{":
        return i
    closed = _closing(toks, i)
    if closed is None:
        return i + 1
    rows = _read(text, toks, i, closed, declarations)
    if rows is not None:
        cells = [[row] if single else row if isinstance(row, list) else [] for row in rows]
        out.append(ValuesBlock(start, toks[closed].start + 1, names,
                               [[_term(row[k]) if k < len(row) else None for k in range(len(names))] for row in cells]))
    return closed + 1


def _term(cell: object) -> Literal | NamedNode | None:
    """A VALUES cell's term (None: UNDEF, or a cell not read as one term)."""
    return cell if isinstance(cell, Literal | NamedNode) and cell != _UNDEF else None


def _bind(text: str, toks: list[Token], i: int, declarations: list[str],
          out: list[tuple[str, Literal | NamedNode]]) -> int:
    """Read ``BIND ( term AS ?v )`` starting at its ``(`` (``toks[i]``) into ``out``; the index after it."""
    if i >= len(toks) or toks[i].text != "(":
        return i
    depth, j = 0, i
    while j < len(toks):
        if toks[j].kind == PUNCT and toks[j].text in "()":
            depth += 1 if toks[j].text == "(" else -1
            if depth == 0:
                return j + 1
        elif depth == 1 and toks[j].kind == KEYWORD and toks[j].word == "AS" and j + 1 < len(toks) \
                and toks[j + 1].kind == VARIABLE:
            value = _one_term(text[toks[i].start + 1:toks[j].start], declarations)
            if isinstance(value, Literal | NamedNode):
                out.append((toks[j + 1].text[1:], value))
        j += 1
    return j


def _closing(toks: list[Token], i: int) -> int | None:
    """The index of the ``}`` closing the ``{`` at ``toks[i]``."""
    depth = 0
    for j in range(i, len(toks)):
        if toks[j].kind == PUNCT and toks[j].text in "{}":
            depth += 1 if toks[j].text == "{" else -1
            if depth == 0:
                return j
    return None


def _read(text: str, toks: list[Token], opened: int, closed: int, declarations: list[str]) -> list | None:
    """The terms of the data block between ``toks[opened]`` and ``toks[closed]`` (its rows: terms, or lists of
    terms), read as a Turtle collection; None where the block does not read as one."""
    parts: list[str] = []
    pos = toks[opened].start + 1
    for t in toks[opened + 1:closed]:
        if t.kind == KEYWORD and t.word == "UNDEF":
            parts.append(text[pos:t.start] + f" <{_UNDEF.value}> ")
            pos = t.start + len(t.text)
    parts.append(text[pos:toks[closed].start])
    triples = _parsed(f"<{_UNDEF.value}> <{_UNDEF.value}> ( {''.join(parts)} ) .", declarations)
    if triples is None:
        return None
    heads = [tr.object for tr in triples if tr.subject == _UNDEF]
    links = {(tr.subject, tr.predicate): tr.object for tr in triples}
    return _items(heads[0], links) if heads else None


def _items(node: object, links: dict) -> list:
    """The members of the collection starting at ``node`` (nested collections as lists)."""
    out: list = []
    while isinstance(node, BlankNode) and (node, _FIRST) in links:
        first = links[node, _FIRST]
        out.append(_items(first, links) if isinstance(first, BlankNode) and (first, _FIRST) in links else first)
        node = links.get((node, _REST))
    return out


def _one_term(expression: str, declarations: list[str]) -> object | None:
    """The one RDF term ``expression`` writes, where it is a term alone (not an expression)."""
    triples = _parsed(f"<{_UNDEF.value}> <{_UNDEF.value}> {expression} .", declarations)
    return triples[0].object if triples is not None and len(triples) == 1 else None


def _parsed(body: str, declarations: list[str]) -> list | None:
    try:
        return list(parse("\n".join([*declarations, body]), RdfFormat.TURTLE))
    except (SyntaxError, ValueError):
        return None


def operations(toks: list[Token]) -> Iterator[list[Token]]:
    """``toks`` split into the operations of an update (at each ``;`` outside braces)."""
    depth, start = 0, 0
    for j, t in enumerate(toks):
        if t.kind == PUNCT and t.text in "{}":
            depth += 1 if t.text == "{" else -1
        elif depth == 0 and t.kind == PUNCT and t.text == ";":
            yield toks[start:j]
            start = j + 1
    yield toks[start:]


@dataclass
class Operation:
    """One operation of an update: its text runnable alone (the prologue in force before it), the update's
    text (``source``) and the operation's tokens in it, the Turtle declarations and the SPARQL prologue in
    force in it (its own too), for the queries that read what it writes."""

    text: str
    source: str
    toks: list[Token]
    declarations: list[str]
    prologue: str


def split(text: str) -> list[Operation]:
    """``text``'s operations, each with the ``PREFIX`` and ``BASE`` declarations of those before it."""
    declarations: list[str] = []
    prologue: list[str] = []
    out = []
    for toks in operations([t for t in tokens(text) if t.kind != "comment"]):
        before = " ".join(prologue)
        for i, t in enumerate(toks):
            if t.kind == KEYWORD and t.word == "PREFIX" and i + 2 < len(toks) and toks[i + 2].kind == IRI:
                declarations.append(f"@prefix {toks[i + 1].text} {toks[i + 2].text} .")
                prologue.append(f"PREFIX {toks[i + 1].text} {toks[i + 2].text}")
            elif t.kind == KEYWORD and t.word == "BASE" and i + 1 < len(toks) and toks[i + 1].kind == IRI:
                declarations.append(f"@base {toks[i + 1].text} .")
                prologue.append(f"BASE {toks[i + 1].text}")
        if toks:
            end = toks[-1].start + len(toks[-1].text)
            out.append(Operation(f"{before}\n{text[toks[0].start:end]}", text, toks, list(declarations),
                                 " ".join(prologue)))
    return out


__all__ = ["Bound", "Operation", "ValuesBlock", "bound_literals", "operations", "split", "where_bindings"]
