"""One vocabulary: no module but vocab.py spells an IRI by hand.

A typo in a namespace would silently make a rule never fire, so every IRI
topostore uses is a constant of :mod:`topostore.rdf.vocab`.  The check reads the
source with :mod:`ast`: string literals count, docstrings (prose and examples
for people) do not, and neither do URL schemes alone (``"http://"`` in
``startswith(("http://", "https://"))`` or in ``f"http://{host}:{port}"``),
which name no resource.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

from pyoxigraph import BlankNode, Literal, NamedNode

from topostore.rdf import vocab
from topostore.rdf.skolem import fresh_skolem, skolem, unskolem

PACKAGE = Path(vocab.__file__).parents[1]
#: a scheme followed by the start of a name: an IRI, not just the scheme
IRI = re.compile(r"(?:https?://|urn:)[A-Za-z0-9]")


def docstring_nodes(tree: ast.AST) -> set[int]:
    """ids of the string constants that are docstrings (module, class, function)."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                found.add(id(first.value))
    return found


def iri_literals(source: str) -> list[tuple[int, str]]:
    """(line, text) of every string literal in ``source`` that spells an IRI, docstrings left out."""
    tree = ast.parse(source)
    docs = docstring_nodes(tree)
    return [(node.lineno, node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs
            and IRI.search(node.value)]


def test_the_check_finds_iri_literals_and_skips_docstrings() -> None:
    source = '''
"""Module text naming urn:topostore:bnode:x is prose."""
PREFIX = "urn:topostore:bnode:"
def f(host):
    """See http://example.org/doc."""
    url = f"http://{host}:8080"
    return "<http://www.w3.org/2001/XMLSchema#long>", url.startswith(("http://", "https://"))
'''
    assert iri_literals(source) == [(3, "urn:topostore:bnode:"), (7, "<http://www.w3.org/2001/XMLSchema#long>")]


def test_no_module_but_vocab_spells_an_iri() -> None:
    offenders = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if path == PACKAGE / "rdf" / "vocab.py":
            continue
        for line, text in iri_literals(path.read_text(encoding="utf-8")):
            offenders.append(f"{path.relative_to(PACKAGE)}:{line}: {text!r}")
    assert offenders == []


def test_is_skolem() -> None:
    node = fresh_skolem()
    assert vocab.is_skolem(node) and vocab.is_skolem(node.value)
    assert skolem(BlankNode("b1")) == NamedNode(vocab.SKOLEM_PREFIX + "b1")
    assert unskolem(skolem(BlankNode("b1"))) == BlankNode("b1")
    assert not vocab.is_skolem(NamedNode(vocab.MAP_NS + "R1"))
    assert not vocab.is_skolem(NamedNode(vocab.EXPR_PREFIX + "1"))
    assert not vocab.is_skolem(Literal(vocab.SKOLEM_PREFIX + "x"))   # text that looks like one is not a node
    assert not vocab.is_skolem(BlankNode("b1"))
