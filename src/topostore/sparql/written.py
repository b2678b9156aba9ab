"""The literals a SPARQL update writes into its insert templates, as its text spells them, at their positions.

Why: an update's delta is computed on a scratch Oxigraph store (:func:`.execute.update_delta`), which keeps
numbers canonical: ``"6"^^xsd:long`` comes out as ``"6"^^xsd:integer``, a bare ``1.50`` as ``1.5``.  The asserted
graph would then remember the canonical form as the spelling its user wrote, where every other path (a change, a
load, a Graph Store write) keeps ``xsd:long`` and ``1.50``.  So the insert templates (``INSERT DATA`` and
``INSERT`` blocks) are read here as triples: each block's text, variables standing for any term, is parsed as
Turtle (whose literals are SPARQL's and which keeps their spelling), and an added triple takes the spelling its
template wrote for it: the literal written at the position (subject, predicate) that produced it.  A literal
written anywhere else (a ``FILTER``, a ``DELETE``) spells nothing added; a value bound from the store by
``WHERE`` takes the spelling the store holds for that value (as a query's answer shows it, where the value is
held in one spelling), and one computed (``BIND``, a function) has no spelling in the text.

The parse runs only when the text may hold a literal Oxigraph stores otherwise (a ``^^`` or a bare number not
in canonical form), so a plain update pays one regular-expression scan.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator

from pyoxigraph import BlankNode, Literal, NamedNode, RdfFormat, Triple, parse

from ..rdf.lexer import IRI, KEYWORD, PUNCT, VARIABLE, Token, tokens
from ..rdf.terms import Term
from ..rdf.vocab import INTERNAL
from ..stores.literal_forms import stored_literal

#: a bare SPARQL number (INTEGER, DECIMAL or DOUBLE, signed or not), not part of a name or a variable
_NUMBER = re.compile(r"(?<![\w:.?$\-])[+-]?(?:\d+\.\d*[eE][+-]?\d+|\d*\.\d+(?:[eE][+-]?\d+)?|\d+(?:[eE][+-]?\d+)?)")
#: the numbers Oxigraph stores as written (no sign "+", no leading or trailing zero, no exponent)
_CANONICAL = re.compile(r"-?(?:0|[1-9]\d*)(?:\.\d*[1-9])?")
#: what a template's variable becomes in the Turtle read of it (any term, at that position)
_ANY = NamedNode(INTERNAL + "template-variable")

#: a template triple: its subject and predicate (None: any term) and the literal written as its object
Template = tuple[NamedNode | None, NamedNode | None, Literal]


def may_respell(text: str) -> bool:
    """Whether ``text`` may write a literal Oxigraph stores otherwise (a typed literal, a bare number not in
    canonical form): the cheap test before the templates are read."""
    return "^^" in text or any(not _canonical(m.group(0)) for m in _NUMBER.finditer(text))


def _canonical(number: str) -> bool:
    return number != "-0" and _CANONICAL.fullmatch(number) is not None


def as_written(added: list[Triple], text: str, held: Callable[[Literal], Term] | None = None) -> list[Triple]:
    """``added`` (an update's added triples, as the scratch store gave them) with each literal the update's
    insert template wrote for it given back in that spelling; ``held``: the spelling the store holds for a
    value (:meth:`.Store.restore`), given to a literal no template wrote (bound from the store by ``WHERE``).

    The templates are read where the text may spell a literal otherwise than Oxigraph stores it, or where the
    store holds an added value in another spelling (a template writing it there keeps what it wrote)."""
    written = _Written(text)
    respell = may_respell(text)
    out = []
    for t in added:
        o = t.object
        spelled = written.at(t) if respell and isinstance(o, Literal) else None
        if spelled is None and held is not None and isinstance(o, Literal):
            kept = held(o)
            if isinstance(kept, Literal) and kept != o:
                spelled = written.at(t) or kept
        out.append(t if spelled is None or spelled == o else Triple(t.subject, t.predicate, spelled))
    return out


class _Written:
    """The update's template literals by stored form, read once when first asked."""

    def __init__(self, text: str) -> None:
        self._text = text
        self._by_stored: dict[Literal, list[Template]] | None = None

    def at(self, t: Triple) -> Literal | None:
        """The literal a template wrote that produces ``t``: one written at ``t``'s own subject and predicate
        before one written under a variable or a blank node, and of those the last operation's."""
        if self._by_stored is None:
            self._by_stored = {}
            for s, p, o in reversed(list(insert_templates(self._text))):
                self._by_stored.setdefault(stored_literal(o), []).append((s, p, o))
        best, rank = None, -1
        for s, p, o in self._by_stored.get(t.object, ()):  # type: ignore[call-overload]
            if (s is None or s == t.subject) and (p is None or p == t.predicate):
                score = (s is not None) * 2 + (p is not None)
                if score > rank:
                    best, rank = o, score
        return best


def insert_templates(text: str) -> Iterator[Template]:
    """The triples with a literal object of each ``INSERT DATA`` and ``INSERT`` block of ``text``, literals as
    written (a block that does not read as Turtle, such as one holding ``GRAPH``, gives none: the update is
    refused or its literals stay as the scratch store gives them)."""
    toks = [t for t in tokens(text) if t.kind != "comment"]
    declarations: list[str] = []
    i = 0
    while i < len(toks):
        t = toks[i]
        if t.kind == KEYWORD and t.word == "PREFIX" and i + 2 < len(toks) and toks[i + 2].kind == IRI:
            declarations.append(f"@prefix {toks[i + 1].text} {toks[i + 2].text} .")
        elif t.kind == KEYWORD and t.word == "BASE" and i + 1 < len(toks) and toks[i + 1].kind == IRI:
            declarations.append(f"@base {toks[i + 1].text} .")
        elif t.kind == KEYWORD and t.word == "INSERT":
            block = _block(toks, i + 1)
            if block is not None:
                yield from _templates(text, toks, block, declarations)
                i = block[1]
        i += 1


def _block(toks: list[Token], i: int) -> tuple[int, int] | None:
    """The indices of the braces of the block that starts at ``toks[i]`` (after an optional ``DATA``)."""
    if i < len(toks) and toks[i].kind == KEYWORD and toks[i].word == "DATA":
        i += 1
    if i >= len(toks) or toks[i].text != "{":
        return None
    depth = 0
    for j in range(i, len(toks)):
        if toks[j].kind == PUNCT and toks[j].text in "{}":
            depth += 1 if toks[j].text == "{" else -1
            if depth == 0:
                return i, j
    return None


def _templates(text: str, toks: list[Token], block: tuple[int, int], declarations: list[str]) -> Iterator[Template]:
    """The template triples of one block with a literal object, read as Turtle."""
    opened, closed = block
    parts: list[str] = []
    pos = toks[opened].start + 1
    for t in toks[opened + 1:closed]:
        if t.kind == VARIABLE:
            parts.append(text[pos:t.start] + f" <{_ANY.value}> ")
            pos = t.start + len(t.text)
    parts.append(text[pos:toks[closed].start])
    body = "".join(parts).rstrip()
    if body and not body.endswith("."):
        body += " ."
    try:
        triples = list(parse("\n".join([*declarations, body]), RdfFormat.TURTLE))
    except (SyntaxError, ValueError):
        return
    for tr in triples:
        if isinstance(tr.object, Literal):
            yield _position(tr.subject), _position(tr.predicate), tr.object


def _position(term: object) -> NamedNode | None:
    """A template's subject or predicate, None where any term may stand there (a variable, a blank node)."""
    if isinstance(term, BlankNode) or term == _ANY or not isinstance(term, NamedNode):
        return None
    return term


__all__ = ["as_written", "insert_templates", "may_respell"]
