"""The one check every piece of user SPARQL passes before anything parses it.

Three kinds of danger, one lexical scan (:func:`scan`):

* **Reaching out.**  Oxigraph evaluates ``SERVICE <url>`` in queries and
  ``LOAD <url>`` in updates by fetching the URL itself.  Exposed over HTTP,
  that would let any client make the robot's ontology service issue requests
  to arbitrary hosts (server-side request forgery).  aRMOR has no such feature,
  so both keywords are refused.
* **Internal functions.**  The compiled rules call extension functions in
  ``urn:topostore:fn:`` (e.g. ``pow``); they are not part of the public query
  language, so an IRI in that namespace is refused (user queries are also run
  without them, see :meth:`topostore.ontology.facade.Ontology.sparql`).
* **Parser and planner exhaustion.**  Oxigraph's parser and optimizer recurse
  on the query's structure: about 2,200 nested ``{`` or 900 nested function
  calls overflow the native stack and kill the whole process (SIGSEGV), and
  about 3,000 chained operators (``1+1+…``, ``UNION``) do the same.  No
  Python ``except`` can catch that, so the nesting depth, the number of tokens
  and the length are bounded *before* parsing (:class:`SparqlLimits`).

The scan follows SPARQL's own lexing rules (``\\uXXXX`` escapes are decoded
first, as the grammar requires; IRIs, strings and comments are skipped) and
keywords are looked for outside them and not as parts of prefixed names or
variables.  A false alarm only refuses a query; the scanner never lets a
keyword through.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import QueryError
from ..rdf.lexer import CLOSE, COMMENT, IRI, KEYWORD, OPEN, PUNCT, decode_escapes, tokens
from ..rdf.vocab import FUNCTION_PREFIX

FORBIDDEN = ("SERVICE", "LOAD")
#: namespace of the extension functions only compiled rules may call
INTERNAL_FUNCTIONS = FUNCTION_PREFIX


@dataclass(frozen=True)
class SparqlLimits:
    """Bounds on user SPARQL text, checked before parsing (defaults far below the crash points)."""

    #: characters of query or update text
    max_length: int = 256 * 1024
    #: nesting of ``(``, ``{`` and ``[`` (the parser crashes near 900 nested calls)
    max_depth: int = 64
    #: IRIs, literals, names, variables and punctuation (operator chains crash near 3,000)
    max_tokens: int = 2000


#: the limits every entry point uses; change with :func:`set_limits` (``topostore serve --sparql-max-*``)
LIMITS = SparqlLimits()


def set_limits(limits: SparqlLimits) -> None:
    """Replace the process-wide SPARQL limits (called once at start-up by the CLI)."""
    global LIMITS
    if limits.max_length < 1 or limits.max_depth < 1 or limits.max_tokens < 1:
        raise ValueError("SPARQL limits must be positive")
    LIMITS = limits


class UnsafeOperationError(QueryError):
    """The request uses an operation this service refuses (SERVICE, LOAD, internal functions)."""


class QueryTooComplex(QueryError):
    """The text is longer, deeper or has more tokens than :class:`SparqlLimits` allows."""


@dataclass
class Scan:
    """What the lexer saw: bare keywords (upper case), IRIs, deepest nesting, token count."""

    keywords: list[str] = field(default_factory=list)
    iris: list[str] = field(default_factory=list)
    depth: int = 0
    tokens: int = 0


def scan(text: str, stop_tokens: int | None = None) -> Scan:
    """Lex ``text`` once (:func:`topostore.rdf.lexer.tokens`); stops early (the answer is already
    "too many") past ``stop_tokens``."""
    out = Scan()
    depth = 0
    for token in tokens(decode_escapes(text)):
        if token.kind == COMMENT:
            continue  # a comment is not a token
        out.tokens += 1
        if stop_tokens is not None and out.tokens > stop_tokens:
            return out
        if token.kind == IRI:
            out.iris.append(token.text[1:-1])
        elif token.kind == KEYWORD:
            out.keywords.append(token.word)
        elif token.kind == PUNCT and token.text in OPEN:
            depth += 1
            out.depth = max(out.depth, depth)
        elif token.kind == PUNCT and token.text in CLOSE:
            depth -= 1
    return out


def keywords(text: str) -> list[str]:
    """The bare words of a query outside IRIs, strings and comments, upper-cased."""
    return scan(text).keywords


def check_size(text: str, limits: SparqlLimits | None = None) -> Scan:
    """Raise :class:`QueryTooComplex` unless ``text`` is within the limits; returns the scan."""
    limits = limits or LIMITS
    if not isinstance(text, str):
        raise QueryError(f"SPARQL text must be a string, not {type(text).__name__}")
    if len(text) > limits.max_length:
        raise QueryTooComplex(f"the SPARQL text has {len(text)} characters, more than the limit of {limits.max_length}")
    found = scan(text, stop_tokens=limits.max_tokens)
    if found.tokens > limits.max_tokens:
        raise QueryTooComplex(f"the SPARQL text has more than {limits.max_tokens} tokens; split it into smaller "
                              "queries (the limit protects the parser, which would crash the service)")
    if found.depth > limits.max_depth:
        raise QueryTooComplex(f"the SPARQL text nests brackets {found.depth} deep, more than the limit of "
                              f"{limits.max_depth} (the limit protects the parser, which would crash the service)")
    return found


def check_safe(text: str) -> None:
    """Raise :class:`UnsafeOperationError` if ``text`` uses SERVICE, LOAD or an internal function."""
    _check_found(text, scan(text))


def _check_found(text: str, found: Scan) -> None:
    used = sorted(set(found.keywords) & set(FORBIDDEN))
    if used:
        raise UnsafeOperationError(
            f"{' and '.join(used)} is not allowed on this endpoint: it would make the service fetch remote data")
    if any(iri.startswith(INTERNAL_FUNCTIONS[:-1]) for iri in found.iris) or INTERNAL_FUNCTIONS in decode_escapes(text):
        raise UnsafeOperationError(f"IRIs in {INTERNAL_FUNCTIONS} name internal functions of the reasoner; "
                                   "they cannot be called from user SPARQL")


def check_user_sparql(text: str, limits: SparqlLimits | None = None) -> None:
    """The single gate for user SPARQL (queries and updates): size, nesting, then safety."""
    _check_found(text, check_size(text, limits))


__all__ = ["UnsafeOperationError", "QueryTooComplex", "SparqlLimits", "LIMITS", "set_limits", "check_safe",
           "check_size", "check_user_sparql", "keywords", "scan", "decode_escapes", "FORBIDDEN", "INTERNAL_FUNCTIONS"]
