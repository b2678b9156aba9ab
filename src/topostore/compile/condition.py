"""The :class:`Condition` value: one FILTER or BIND of a rule body, as the compiler built it.

The reasoner needs to know, per rule, whether a filter tests the *absence* of
data (the rule is then not monotone and DRed cannot maintain it), whether it
reads graph patterns at all (it then cannot prove facts or flip), and which
variables a BIND introduces (a plan must bind them before using them).  The
compilers know all of that when they write a filter, so they record it here;
the SPARQL text is one rendering of the value (:attr:`Condition.text`), made
in one place, and no module of the reasoner scans it again.

Rule files (``rules/*.rq``) are SPARQL text already: their filter lines are
read with the shared tokenizer (:func:`parse`), once, when the file is loaded.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..rdf import lexer

#: kinds of condition (PATTERN: any other group line of a rule file, e.g. OPTIONAL or VALUES)
TEST, EXISTS, BIND, PATTERN = "test", "exists", "bind", "pattern"


@dataclass(frozen=True)
class Condition:
    """A FILTER or a BIND; ``text`` is its SPARQL.

    ``kind`` is :data:`TEST` (``FILTER(expression)``), :data:`EXISTS`
    (``FILTER [NOT] EXISTS { expression }``, a graph pattern) or :data:`BIND`
    (``BIND(expression AS binds)``); a rule file may also hold other group
    lines (:data:`PATTERN`, kept as written).  ``negated``: it tests the absence of
    data; ``reads_graph``: it holds a graph pattern (an EXISTS of either sign,
    also inside a test's expression).
    """

    kind: str
    expression: str
    binds: str | None = None
    negated: bool = False
    reads_graph: bool = False
    #: the rendering, when the condition was read as text (a rule file) rather than built
    written: str = ""
    #: a graph pattern rendered before the body's atoms (:func:`leading`), not after them
    leads: bool = False
    text: str = field(init=False, compare=False)
    #: the variables mentioned (``?name``), the bound one included
    variables: frozenset[str] = field(init=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "text", self.written or self._render())
        object.__setattr__(self, "variables", lexer.variables(self.text))

    def _render(self) -> str:
        if self.kind == BIND:
            return f"BIND({self.expression} AS {self.binds})"
        if self.kind == EXISTS:
            return f"FILTER {'NOT ' if self.negated else ''}EXISTS {{ {self.expression} }}"
        return f"FILTER({self.expression})"

    @property
    def plain(self) -> bool:
        """A BIND or a FILTER over bound values only (no graph pattern)."""
        return self.kind in (TEST, BIND) and not self.reads_graph


def test(expression: str, reads_graph: bool = False, negated: bool = False) -> Condition:
    """``FILTER(expression)``; say ``reads_graph``/``negated`` when the expression holds an EXISTS."""
    return Condition(TEST, expression, negated=negated, reads_graph=reads_graph or negated)


def exists(pattern: str, negated: bool = False) -> Condition:
    """``FILTER EXISTS { pattern }`` (``FILTER NOT EXISTS`` when ``negated``)."""
    return Condition(EXISTS, pattern, negated=negated, reads_graph=True)


def bind(expression: str, variable: str) -> Condition:
    """``BIND(expression AS variable)``."""
    return Condition(BIND, expression, binds=variable)


def parse(line: str) -> Condition:
    """A filter line of a rule file, read with the shared tokenizer (its text kept as written)."""
    toks = [t for t in lexer.tokens(line) if t.kind != lexer.COMMENT]
    words = [t.word if t.kind == lexer.KEYWORD else "" for t in toks]
    negated, reads = lexer.negates_exists(line), lexer.reads_graph(line)
    if words[:1] == ["BIND"] and len(toks) >= 3 and words[-3:-2] == ["AS"] and toks[-2].kind == lexer.VARIABLE:
        return Condition(BIND, line[toks[1].start + 1:toks[-3].start].strip(), binds=toks[-2].text, written=line)
    if words[:1] == ["FILTER"] and (words[1:2] == ["EXISTS"] or words[1:3] == ["NOT", "EXISTS"]):
        brace = next(t for t in toks if t.text == "{")
        return Condition(EXISTS, line[brace.start + 1:line.rindex("}")].strip(), negated=negated, reads_graph=True,
                         written=line)
    if words[:1] == ["FILTER"] and len(toks) > 2 and toks[1].text == "(" and toks[-1].text == ")":
        return Condition(TEST, line[toks[1].start + 1:toks[-1].start].strip(), negated=negated, reads_graph=reads,
                         written=line)
    return Condition(PATTERN, line, negated=negated, reads_graph=True, written=line)


def leading(pattern: str) -> Condition:
    """A graph pattern written before the body's atoms: a generic rule's schema rows.  Oxigraph joins
    equally estimated patterns in the order written, and a body of n ``ts:notType`` atoms joined
    before the rows that tie their classes together is every n-tuple of an individual's
    non-memberships (a union of four members over thirty of them did not end in a minute); the
    rows first bind every class, and each atom is then a look-up."""
    return Condition(PATTERN, pattern, reads_graph=True, written=pattern, leads=True)


def render(conditions: tuple[Condition, ...]) -> str:
    """The conditions as the lines of a WHERE group (the form every rendering of a rule uses)."""
    return "\n  ".join(c.text for c in conditions)


__all__ = ["BIND", "Condition", "EXISTS", "PATTERN", "TEST", "bind", "exists", "leading", "parse", "render", "test"]
