"""The typed literals a SPARQL update writes, as its text spells them.

Why: an update's delta is computed on a scratch Oxigraph store (:func:`.execute.update_delta`), which keeps
numbers canonical: ``"6"^^xsd:long`` comes out as ``"6"^^xsd:integer``.  The asserted graph would then
remember ``xsd:integer`` as the spelling its user wrote, where every other path (a change, a load, a Graph
Store write) keeps ``xsd:long``.  The literals typed in the text are read here (the one SPARQL tokenizer,
:mod:`topostore.rdf.lexer`), so that each added literal the scratch store changed is given back as written.
A literal an expression computes (``BIND``, a function) has no spelling in the text and stays as computed.
"""

from __future__ import annotations

from collections.abc import Iterator

from pyoxigraph import Literal, RdfFormat, Triple, parse

from ..rdf.lexer import IRI, KEYWORD, NAME, PUNCT, STRING, Token, tokens
from ..stores.literal_forms import stored_literal


def written_literals(text: str) -> dict[Literal, Literal]:
    """Each typed literal of ``text`` that Oxigraph stores otherwise, keyed by its stored form (the first spelling
    written, where two spellings of the text are stored as one term)."""
    out: dict[Literal, Literal] = {}
    for lit in _typed_literals(text):
        stored = stored_literal(lit)
        if stored != lit:
            out.setdefault(stored, lit)
    return out


def as_written(added: list[Triple], text: str) -> list[Triple]:
    """``added`` (an update's added triples, as the scratch store gave them) with each literal the text typed
    given back in its spelling."""
    if "^^" not in text:
        return added
    written = written_literals(text)
    if not written:
        return added
    return [t if (w := written.get(t.object)) is None else Triple(t.subject, t.predicate, w) for t in added]  # type: ignore[arg-type]


def _typed_literals(text: str) -> Iterator[Literal]:
    """The literals of ``text`` written as ``"lexical"^^datatype`` (an IRI, or a prefixed name its PREFIX
    declarations resolve)."""
    toks = [t for t in tokens(text) if t.kind != "comment"]
    prefixes: dict[str, str] = {}
    for i, t in enumerate(toks):
        if t.kind == KEYWORD and t.word == "PREFIX" and i + 2 < len(toks) and toks[i + 2].kind == IRI:
            prefixes[toks[i + 1].text] = toks[i + 2].text[1:-1]
        elif t.kind == STRING and i + 3 < len(toks) and _carets(toks[i + 1], toks[i + 2]):
            datatype = _datatype(toks[i + 3], prefixes)
            if datatype is not None:
                lit = _literal(t.text, datatype)
                if lit is not None:
                    yield lit


def _carets(a: Token, b: Token) -> bool:
    return a.kind == PUNCT and b.kind == PUNCT and a.text == "^" and b.text == "^" and b.start == a.start + 1


def _datatype(t: Token, prefixes: dict[str, str]) -> str | None:
    if t.kind == IRI:
        return t.text[1:-1]
    if t.kind in (NAME, KEYWORD) and ":" in t.text:
        prefix, _, local = t.text.partition(":")
        base = prefixes.get(prefix + ":")
        return None if base is None else base + local
    return None


def _literal(quoted: str, datatype: str) -> Literal | None:
    """The literal of a SPARQL string token and a datatype (SPARQL's string escapes are Turtle's)."""
    try:
        triples = list(parse(f"<x:s> <x:p> {quoted}^^<{datatype}> .", RdfFormat.TURTLE))
    except (SyntaxError, ValueError):
        return None
    o = triples[0].object if len(triples) == 1 else None
    return o if isinstance(o, Literal) else None


__all__ = ["as_written", "written_literals"]
