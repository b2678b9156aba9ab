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
held in one spelling), one a ``VALUES`` block or a ``BIND`` of one literal gives a variable takes the spelling
written there (:mod:`.bound`), and one computed (a function, an expression) has no spelling in the text.  A
template's blank node (``[ k:p "007"^^xsd:long ]``) becomes a fresh node of the scratch store: each is paired
with the added node of the same shape (its values and links, as stored), so two blank nodes holding one value
in two spellings keep one each.

Which of several spellings of one value written at one position stays, and what is said of the others, is read
from the update's evaluation (:mod:`.evaluated`); the reading here gives the spelling of an added literal where
that evaluation shows none (a value bound from the store, computed, or one a ``FILTER`` reads).

The parse runs only when the text may hold a literal Oxigraph stores otherwise (a ``^^`` or a bare number not
in canonical form), so a plain update pays one regular-expression scan.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator

from pyoxigraph import BlankNode, Literal, NamedNode, RdfFormat, Triple, parse

from ..rdf.lexer import KEYWORD, PUNCT, VARIABLE, Token
from ..rdf.terms import Term
from ..rdf.vocab import INTERNAL, SKOLEM_PREFIX
from ..stores.literal_forms import stored_literal
from .bound import Bound, bound_literals, split

#: a bare SPARQL number (INTEGER, DECIMAL or DOUBLE, signed or not), not part of a name or a variable
_NUMBER = re.compile(r"(?<![\w:.?$\-])[+-]?(?:\d+\.\d*[eE][+-]?\d+|\d*\.\d+(?:[eE][+-]?\d+)?|\d+(?:[eE][+-]?\d+)?)")
#: the numbers Oxigraph stores as written (no sign "+", no leading or trailing zero, no exponent)
_CANONICAL = re.compile(r"-?(?:0|[1-9]\d*)(?:\.\d*[1-9])?")
#: what a template's variable becomes in the Turtle read of it (any term, at that position), its name after it
_VARIABLE = INTERNAL + "template-variable/"

#: a template triple: its subject (None: any term; a blank node: the added node paired with it) and predicate
#: (None: any term), and the literal written as its object
Template = tuple[NamedNode | BlankNode | None, NamedNode | None, Literal]


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
    written = _Written(text, added)
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
    """The update's template literals by stored form, and its blank nodes paired with the added ones, read once
    when first asked."""

    def __init__(self, text: str, added: list[Triple]) -> None:
        self._text = text
        self._added = added
        self._by_stored: dict[Literal, list[Template]] | None = None
        self._paired: dict[NamedNode, BlankNode] = {}

    def at(self, t: Triple) -> Literal | None:
        """The literal a template wrote that produces ``t``: one written at ``t``'s own subject (or its paired
        blank node) and predicate before one written under a variable or an unpaired blank node, and of those
        the last operation's."""
        if self._by_stored is None:
            self._by_stored = {}
            shapes: list[Triple] = []
            for s, p, o in reversed(list(_read_templates(self._text, shapes))):
                self._by_stored.setdefault(stored_literal(o), []).append((s, p, o))
            self._paired = paired(shapes, self._added)
        node = self._paired.get(t.subject)  # type: ignore[call-overload]
        best, rank = None, -1
        for s, p, o in self._by_stored.get(t.object, ()):  # type: ignore[call-overload]
            if isinstance(s, BlankNode):
                s = t.subject if s == node else None if node is None else s
            if (s is None or s == t.subject) and (p is None or p == t.predicate):
                score = (s is not None) * 2 + (p is not None)
                if score > rank:
                    best, rank = o, score
        return best


def paired(template: list[Triple], added: list[Triple]) -> dict[NamedNode, BlankNode]:
    """Each added blank node (a skolem IRI) → the template blank node of its shape, where the shape's template
    nodes and added nodes are as many (an ``INSERT DATA``'s nodes; a template run for several solutions makes
    more nodes than it writes, and its literals then stay matched by position alone)."""
    def fresh(term: object) -> bool:
        return isinstance(term, NamedNode) and term.value.startswith(SKOLEM_PREFIX)

    mine = _shapes(template, lambda term: isinstance(term, BlankNode), stored=True)
    theirs = _shapes(added, fresh, stored=False)
    by_shape: dict[tuple, tuple[list, list]] = {}
    for node, shape in mine.items():
        by_shape.setdefault(shape, ([], []))[0].append(node)
    for node, shape in theirs.items():
        if shape in by_shape:
            by_shape[shape][1].append(node)
    out = {}
    for ours, added_nodes in by_shape.values():
        if len(ours) == len(added_nodes):
            out.update(zip(sorted(added_nodes, key=str), ours, strict=True))
    return out


def _shapes(triples: list[Triple], is_node: Callable[[object], bool], stored: bool) -> dict[object, tuple]:
    """Each node's shape: its links in and out (each once: one value written twice is one fact), other nodes as
    one mark, literals in their stored form."""
    def term(x: object) -> str:
        if is_node(x):
            return "[]"
        return str(stored_literal(x) if stored and isinstance(x, Literal) else x)

    links: dict[object, list[str]] = {}
    for t in triples:
        if is_node(t.subject):
            links.setdefault(t.subject, []).append(f"> {t.predicate} {term(t.object)}")
        if is_node(t.object):
            links.setdefault(t.object, []).append(f"< {term(t.subject)} {t.predicate}")
    return {node: tuple(sorted(set(shape))) for node, shape in links.items()
            if not any(_VARIABLE in link for link in shape)}


def insert_templates(text: str) -> Iterator[Template]:
    """The triples with a literal object of each ``INSERT DATA`` and ``INSERT`` block of ``text``, literals as
    written (a block that does not read as Turtle, such as one holding ``GRAPH``, gives none: the update is
    refused or its literals stay as the scratch store gives them)."""
    return _read_templates(text, [])


def _read_templates(text: str, shapes: list[Triple]) -> Iterator[Template]:
    """:func:`insert_templates`, each block's triples (variables as placeholders) also added to ``shapes``; an
    object variable given literals by the operation's ``VALUES`` or ``BIND`` writes each of them there."""
    for op in split(text):
        toks, declarations = op.toks, op.declarations
        bound: Bound | None = None
        i = 0
        while i < len(toks):
            t = toks[i]
            if t.kind == KEYWORD and t.word == "INSERT":
                block = braced(toks, i + 1)
                if block is not None:
                    if bound is None:
                        bound = bound_literals(text, toks, declarations)
                    yield from _templates(text, toks, block, declarations, bound, shapes)
                    i = block[1]
            i += 1


def braced(toks: list[Token], i: int) -> tuple[int, int] | None:
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


def _templates(text: str, toks: list[Token], block: tuple[int, int], declarations: list[str], bound: Bound,
               shapes: list[Triple]) -> Iterator[Template]:
    """The template triples of one block with a literal object, read as Turtle (an object variable: each literal
    ``bound`` gives it)."""
    triples = block_triples(text, toks, block, declarations)
    if triples is None:
        return
    shapes.extend(triples)
    for tr in triples:
        o, p = tr.object, _position(tr.predicate)
        if (name := variable_name(o)) is not None:
            written = [lit for lit in bound.get(name, ()) if isinstance(lit, Literal)]
        else:
            written = [o] if isinstance(o, Literal) else []
        for subject in _subjects(tr.subject, bound) if written else ():
            for lit in written:
                yield subject, p, lit


def block_triples(text: str, toks: list[Token], block: tuple[int, int],
                  declarations: list[str]) -> list[Triple] | None:
    """The triples of the block between the braces ``block`` read as Turtle, in the order written, each
    variable a placeholder IRI (:func:`variable_name` reads it back); None where it does not read as Turtle
    (such as a block holding ``GRAPH``)."""
    opened, closed = block
    parts: list[str] = []
    pos = toks[opened].start + 1
    for t in toks[opened + 1:closed]:
        if t.kind == VARIABLE:
            parts.append(text[pos:t.start] + f" <{_VARIABLE}{t.text[1:]}> ")
            pos = t.start + len(t.text)
    parts.append(text[pos:toks[closed].start])
    body = "".join(parts).rstrip()
    if body and not body.endswith("."):
        body += " ."
    try:
        return [Triple(q.subject, q.predicate, q.object)
                for q in parse("\n".join([*declarations, body]), RdfFormat.TURTLE)]
    except (SyntaxError, ValueError):
        return None


def variable_name(term: object) -> str | None:
    """The variable a template term of :func:`block_triples` stands for (None: a term written as such)."""
    if isinstance(term, NamedNode) and term.value.startswith(_VARIABLE):
        return term.value[len(_VARIABLE):]
    return None


def _subjects(term: object, bound: Bound) -> list[NamedNode | BlankNode | None]:
    """A template's subject: a variable as any term, and as each IRI VALUES or BIND gives it (these place a
    literal before one written under the variable for another subject)."""
    at = _position(term)
    if at is not None or not isinstance(term, NamedNode):
        return [at]
    return [*(iri for iri in bound.get(term.value[len(_VARIABLE):], ()) if isinstance(iri, NamedNode)), None]


def _position(term: object) -> NamedNode | BlankNode | None:
    """A template's subject or predicate: None where any term may stand there (a variable)."""
    if isinstance(term, BlankNode):
        return term
    if not isinstance(term, NamedNode) or term.value.startswith(_VARIABLE):
        return None
    return term


__all__ = ["as_written", "block_triples", "braced", "insert_templates", "may_respell", "paired", "variable_name"]
