"""The ontology-independent rules, read from the ``.rq`` files in ``rules/``.

Each file is a valid SPARQL query (CONSTRUCT for an inference rule, SELECT for
a consistency check) preceded by ``# key: value`` header lines:

* ``name`` — the W3C rule name; ``origin`` — where the rule comes from;
* ``reads`` — read keys of FILTER/path lines (``p <iri-or-prefixed>``, ``t <class>``);
* ``message`` — for checks, the explanation, with ``{var}`` placeholders;
* ``head-graph: aux`` — the head goes to the helper graph;
* ``stratum`` — the rule's evaluation stratum (default 0): a rule with a negated premise ("not known
  different") runs once what it negates has reached its fixpoint;
* ``schema`` — for the OWL rules of ``rules/owl/``, the schema table the rule joins;
  ``generic-rows`` — above how many instantiations a full REASON runs such a rule generically
  (default: :data:`.schema_program.GENERIC_ROWS`).

Inside WHERE, a line ``s p o .`` (or ``GRAPH ts:graph:aux { s p o . }``) is a
body atom, so the reasoner can evaluate it against the delta graph; a line
``GRAPH ts:graph:schema { s p o . }`` is a *schema atom*, a row of the TBox's
schema tables (see :mod:`.schema`); any other line is kept as a filter.  The
files of ``rules/`` are rules every ontology gets; those of ``rules/owl/`` join
schema atoms and are read by :mod:`.schema`.
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

from ..errors import RuleCompileError
from ..rdf.vocab import INTERNAL, OWL, RDF, RDFS, XSD
from ..resources import rules_dir
from .condition import Condition, parse
from .rule import Atom, Rule

PREFIXES = {
    "owl": OWL,
    "rdf": RDF,
    "rdfs": RDFS,
    "xsd": XSD,
    "ts": INTERNAL,
}
_ATOM = re.compile(r"^(\S+)\s+(\S+)\s+(\S+)\s*\.$")
_AUX_ATOM = re.compile(r"^GRAPH\s+ts:graph:aux\s*\{\s*(\S+)\s+(\S+)\s+(\S+)\s*\.?\s*\}$")
_SCHEMA_ATOM = re.compile(r"^GRAPH\s+ts:graph:schema\s*\{\s*(\S+)\s+(\S+)\s+(\S+)\s*\.?\s*\}$")


def expand(token: str) -> str:
    """``owl:sameAs`` → ``<http://www.w3.org/2002/07/owl#sameAs>``; other tokens unchanged."""
    if token.startswith(("?", "<", '"')) or ":" not in token:
        return token
    prefix, local = token.split(":", 1)
    if prefix in PREFIXES:
        return f"<{PREFIXES[prefix]}{local}>"
    return token


def parse_rule_file(path: Path, text: str | None = None) -> Rule:
    """The rule of a file of ``rules/`` (a schema atom there is an error: see :func:`parse_schema_rule_file`);
    ``text``: the file's text with its constants filled in, when they are the ontology's."""
    rule, schema, _ = parse_rule_text(path, text)
    if schema:
        raise RuleCompileError(f"{path}: a schema atom belongs to a rule of rules/owl/")
    return rule


def parse_rule_text(path: Path, text: str | None = None) -> tuple[Rule, tuple[Atom, ...], dict[str, str]]:
    """(the rule without its schema atoms, the schema atoms, the header lines) of a rule file (``text``:
    read from ``path`` when None)."""
    text = path.read_text() if text is None else text
    headers = {k: v.strip() for k, v in re.findall(r"^#\s*([a-z-]+):\s*(.*)$", text, re.M)}
    match = re.search(r"\bWHERE\s*\{(.*)\}\s*$", text, re.S)
    if not match or "name" not in headers:
        raise RuleCompileError(f"{path}: a rule file needs a '# name:' header and a WHERE clause")
    body: list[Atom] = []
    schema: list[Atom] = []
    filters: list[Condition] = []
    for line in (l.strip() for l in match.group(1).splitlines()):
        if not line or line.startswith("#"):
            continue
        m = _ATOM.match(line)
        aux = _AUX_ATOM.match(line)
        table = _SCHEMA_ATOM.match(line)
        if m:
            body.append(Atom(*(expand(t) for t in m.groups())))
        elif aux:
            body.append(Atom(*(expand(t) for t in aux.groups()), aux=True))
        elif table:
            schema.append(Atom(*(expand(t) for t in table.groups())))
        else:
            filters.append(parse(line))
    reads = frozenset(
        (kind, expand(term)) for kind, term in (r.split() for r in headers.get("reads", "").split(",") if r.strip())
    )
    head = None
    violation: tuple[str, ...] = ()
    construct = re.search(r"\bCONSTRUCT\s*\{\s*(\S+)\s+(\S+)\s+(\S+)\s*\.?\s*\}", text)
    if construct:
        head = Atom(*(expand(t) for t in construct.groups()))
    else:
        select = re.search(r"\bSELECT\s+(.*?)\s+WHERE", text, re.S)
        if not select:
            raise RuleCompileError(f"{path}: expected CONSTRUCT {{ s p o }} or SELECT ... WHERE")
        violation = tuple(select.group(1).split())
    aux_head = True if headers.get("head-graph", "") == "aux" else None
    rule = Rule(headers["name"], headers.get("origin", path.name), tuple(body), head,
                tuple(filters), reads, violation, headers.get("message", ""), aux_head,
                _stratum(path, headers.get("stratum")))
    return rule, tuple(schema), headers


def _stratum(path: Path, text: str | None) -> int:
    """The ``# stratum:`` header, a number (its first word; 0 when absent)."""
    if text is None:
        return 0
    word = text.split()[0] if text.split() else ""
    if not word.isdigit():
        raise RuleCompileError(f"{path}: '# stratum:' needs a number, not {text!r}")
    return int(word)


@cache
def generic_rules(folder: Path | None = None) -> tuple[Rule, ...]:
    folder = folder or rules_dir()
    return tuple(parse_rule_file(p) for p in sorted(folder.glob("*.rq")))
