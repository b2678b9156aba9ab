"""A rule's BINDs and FILTERs compiled into one generated Python function, for the look-up path.

Why this exists
---------------
The conditions of a look-up join or flip (:mod:`.look_join`, :mod:`.look_flip`) are decided for every
solution: the robot step's clock comparison and canReach's key test, a few dozen times a step.  As
closures (:func:`.look_filters.closure`) each node of an expression is a call, each variable three (the
node, the solution's look-up, its value), and the BINDs copy the solution.  Here the expression trees
of :func:`.look_filters.parse_expression` are written out once as the statements of one function: each
variable read from the solution once into a local, each node a line computing its value, a BIND's
result a local the later conditions read.

The values and answers are the closures' exactly (:mod:`.look_values`): UNKNOWN (None) where the
closures answer it, SPARQL's three-valued ``&&`` / ``||`` (every operand is evaluated here, where the
closures stop at the first decisive one: the operands have no effects and the answer depends only on
their values), an arithmetic result outside 64 bits UNKNOWN.  A test compares the two on random
expressions and values (``tests/test_look_code.py``).  The text holds no term: constants are in the
function's namespace, variables' names only as string literals.
"""

from __future__ import annotations

from collections.abc import Callable

from pyoxigraph import BlankNode, Literal, NamedNode

from .look_values import MAX, VALUES, Str, term_of, value

_MIN = -(2 ** 63)
_KINDS = {"ISIRI": NamedNode, "ISURI": NamedNode, "ISBLANK": BlankNode, "ISLITERAL": Literal}
_PY = {"=": "==", "!=": "!=", "<": "<", "<=": "<=", ">": ">", ">=": ">="}


def compile_conditions(binds: list[tuple[str, tuple]], tests: list[tuple]) -> tuple[Callable, Callable]:
    """``holds(solution)``: the tests together in SPARQL's logic after the BINDs in order (True, False,
    or None where a BIND or the answer is not exact), as :meth:`.look_join.Conditions.holds`; and
    ``exact(solution)``: True / False where every BIND is exact and every test's value a boolean, else
    None (a flip needs each test decided, see :mod:`.look_flip`)."""
    code = _Code()
    results = _conditions(code, binds, tests)
    shared = code.lines
    holds = _function("holds", shared, _holds(results), code.namespace)
    exact = _function("exact", shared, _exact(results), code.namespace)
    return holds, exact


def compile_exact_over(binds: list[tuple[str, tuple]], tests: list[tuple], names: list[str]) -> Callable:
    """:func:`compile_conditions`'s ``exact`` taking the solution's values as arguments, one per name of
    ``names`` in that order (a variable not among them is unbound), instead of a dictionary: a generated
    flip branch (:func:`.join_code.compile_flip`) calls it with its locals, twice per solution (the new
    values and the old), where a dictionary per call cost more than the test."""
    return _over("exact", binds, tests, names)


def compile_holds_over(binds: list[tuple[str, tuple]], tests: list[tuple], names: list[str]) -> Callable:
    """:func:`compile_conditions`'s ``holds`` taking the solution's values as arguments, as
    :func:`compile_exact_over` (a generated join deciding its solutions: :func:`.join_code.compile_join`)."""
    return _over("holds", binds, tests, names)


def _over(name: str, binds: list[tuple[str, tuple]], tests: list[tuple], names: list[str]) -> Callable:
    code = _Code({var: f"a{i}" for i, var in enumerate(names)})
    results = _conditions(code, binds, tests)
    tail = _exact(results) if name == "exact" else _holds(results)
    return _function(name, code.lines, tail, code.namespace, ", ".join(f"a{i}" for i in range(len(names))))


def _conditions(code: _Code, binds: list[tuple[str, tuple]], tests: list[tuple]) -> list[str]:
    """The BINDs' statements (returning None where one is not exact) and the tests' locals."""
    for var, node in binds:
        local = code.node(node)
        code.line(f"if {local} is None:")
        code.line("    return None")
        code.binds[var] = local
    return [code.node(node) for node in tests]


def _ebv(x: str) -> str:
    """:func:`.look_values.ebv` of local ``x`` written out (no call per test of a solution)."""
    return (f"({x} if type({x}) is bool else (({x} != 0) if type({x}) is int else "
            f"((len({x}) > 0) if type({x}) is Str else None)))")


def _holds(results: list[str]) -> list[str]:
    if not results:
        return ["return True"]
    flags = [_ebv(r) for r in results]
    return [f"e{i} = {f}" for i, f in enumerate(flags)] + [
        f"if {' or '.join(f'e{i} is False' for i in range(len(flags)))}:",
        "    return False",
        f"return None if {' or '.join(f'e{i} is None' for i in range(len(flags)))} else True"]


def _exact(results: list[str]) -> list[str]:
    if not results:
        return ["return True"]
    return [f"if {' or '.join(f'type({r}) is not bool' for r in results)}:",
            "    return None",
            f"return {' and '.join(results)}"]


def _function(name: str, body: list[str], tail: list[str], namespace: dict, parameters: str = "s") -> Callable:
    text = "\n".join([f"def {name}({parameters}):", *("    " + line for line in body + tail)])
    scope = dict(namespace)
    exec(compile(text, f"<topostore {name}>", "exec"), scope)  # noqa: S102 - text made here, no term in it
    return scope[name]


#: the string functions whose value :meth:`_Code._kept` keeps per term
_STRINGS = frozenset(("str", "substring"))
#: terms whose string value one expression keeps (then forgotten together)
KEPT_MAX = 4096
_MISS = object()


def _children(node: tuple) -> list[tuple]:
    """The expression nodes directly under ``node``."""
    out = []
    for arg in node[1:]:
        if type(arg) is tuple:
            out.append(arg)
        elif type(arg) is list:
            out.extend(a for a in arg if type(a) is tuple)
    return [] if node[0] == "const" else out


def _kinds(node: tuple) -> set[str]:
    """The kinds of ``node`` and of every node under it."""
    found = {node[0]}
    for child in _children(node):
        found |= _kinds(child)
    return found


def _variables(node: tuple) -> set[str]:
    """The variables ``node``'s value reads (as values or as terms)."""
    if node[0] in ("var", "term_of"):
        return {node[1]}
    found: set[str] = set()
    for child in _children(node):
        found |= _variables(child)
    return found


class _Code:
    """The statements of one function over a solution ``s``; each node's value in a local ``xN``."""

    def __init__(self, arguments: dict[str, str] | None = None) -> None:
        #: a solution variable's parameter, where the values are arguments rather than a dictionary ``s``
        self.arguments = arguments
        self.lines: list[str] = []
        self.namespace: dict[str, object] = {"value": value, "VALUES": VALUES, "term_of": term_of, "Str": Str,
                                             "NamedNode": NamedNode, "BlankNode": BlankNode,
                                             "Literal": Literal, "MIN": _MIN, "MAX": MAX, "MISS": _MISS,
                                             "KEPT_MAX": KEPT_MAX}
        #: a solution variable's value and term, each read once
        self.values: dict[str, str] = {}
        self.terms: dict[str, str] = {}
        #: a BIND's variable -> the local holding its value (the later conditions read it)
        self.binds: dict[str, str] = {}
        self.count = 0
        #: the statements' indentation (a kept string's statements run only where it is not kept yet)
        self.indent = ""
        #: a solution variable's term, each read once (its local)
        self.read_terms: dict[str, str] = {}

    def read(self, name: str) -> str:
        """The local of a solution variable's term, read once."""
        if name not in self.read_terms:
            if self.arguments is not None:
                self.read_terms[name] = self.arguments.get(name, "None")
            else:
                self.read_terms[name] = self.new(f"s.get({name!r})")
        return self.read_terms[name]

    def line(self, text: str) -> None:
        self.lines.append(self.indent + text)

    def new(self, expression: str) -> str:
        local = f"x{self.count}"
        self.count += 1
        self.line(f"{local} = {expression}")
        return local

    def const(self, found: object) -> str:
        name = f"k{len(self.namespace)}"
        self.namespace[name] = found
        return name

    def node(self, node: tuple) -> str:
        """The local holding ``node``'s value (None: UNKNOWN)."""
        if node[0] in _STRINGS and not self.indent:
            names = _variables(node)
            if len(names) == 1 and not names & self.binds.keys():
                return self._kept(node, next(iter(names)))
        return getattr(self, "_" + node[0])(*node[1:])

    def _kept(self, node: tuple, name: str) -> str:
        """A string function of one variable's term (an AllDifferent key's group, read from its IRI by
        STRBEFORE(STRAFTER(STR(?k), ...))) computed once per term and kept (:data:`KEPT_MAX` per
        expression): every one of them is a function of the term alone, and making its strings costs
        a microsecond per solution.  The variable's value and term are read before (the statements
        after this one read those locals whether or not the string was kept)."""
        kinds = _kinds(node)
        if "var" in kinds:
            self._var(name)
        if "term_of" in kinds:
            self._term_of(name)
        term = self.read(name)
        kept = self.const({})
        out = self.new(f"{kept}.get({term}, MISS)")
        self.line(f"if {out} is MISS:")
        self.indent = "    "
        found = getattr(self, "_" + node[0])(*node[1:])
        self.line(f"{out} = {found}")
        self.line(f"if len({kept}) >= KEPT_MAX:")
        self.line(f"    {kept}.clear()")
        self.line(f"{kept}[{term}] = {out}")
        self.indent = ""
        return out

    def _var(self, name: str) -> str:
        if name in self.binds:
            return self.binds[name]  # a BIND's value is one already (value() of it is itself)
        if name not in self.values:
            term = self.read(name)
            # a literal's value read from value()'s own cache where it is there (no call), an IRI's is itself
            self.values[name] = self.new(f"{term} if type({term}) is not Literal else "
                                         f"(VALUES.get({term}) or value({term}))")
        return self.values[name]

    def _term_of(self, name: str) -> str:
        if name in self.binds:
            return self._as_term(self.binds[name])
        if name not in self.terms:
            self.terms[name] = self._as_term(self.read(name))
        return self.terms[name]

    def _as_term(self, x: str) -> str:
        """:func:`.look_values.term_of` of local ``x``, called only for a computed value (a term is itself)."""
        return self.new(f"term_of({x}) if type({x}) is bool or type({x}) is int or type({x}) is Str else {x}")

    def _const(self, found: object) -> str:
        return self.const(found)

    def _and(self, parts: list) -> str:
        return self._junction([self.node(p) for p in parts], False)

    def _or(self, parts: list) -> str:
        return self._junction([self.node(p) for p in parts], True)

    def _junction(self, locals_: list[str], decisive: bool) -> str:
        flags = [self.new(_ebv(x)) for x in locals_]
        return self.new(f"{decisive} if ({' or '.join(f'{f} is {decisive}' for f in flags)}) else "
                        f"(None if ({' or '.join(f'{f} is None' for f in flags)}) else {not decisive})")

    def _compare(self, op: str, left: tuple, right: tuple) -> str:
        a, b = self.node(left), self.node(right)
        py = _PY[op]
        ints = f"type({a}) is int and type({b}) is int"
        if op not in ("=", "!="):
            return self.new(f"({a} {py} {b}) if {ints} else None")
        strings = f"type({a}) is Str and type({b}) is Str"
        named = (f"isinstance({a}, (NamedNode, BlankNode)) and isinstance({b}, (NamedNode, BlankNode))")
        return self.new(f"({a} {py} {b}) if {ints} else ((str({a}) {py} str({b})) if {strings} else "
                        f"(({a} {py} {b}) if {named} else None))")

    def _arith(self, op: str, left: tuple, right: tuple) -> str:
        a, b = self.node(left), self.node(right)
        raw = self.new(f"({a} {op} {b}) if type({a}) is int and type({b}) is int else None")
        return self.new(f"{raw} if {raw} is not None and MIN <= {raw} <= MAX else None")

    def _negate(self, arg: tuple) -> str:
        a = self.node(arg)
        raw = self.new(f"-{a} if type({a}) is int else None")
        return self.new(f"{raw} if {raw} is not None and MIN <= {raw} <= MAX else None")

    def _plus(self, arg: tuple) -> str:
        a = self.node(arg)
        return self.new(f"{a} if type({a}) is int else None")

    def _not(self, arg: tuple) -> str:
        flag = self.new(_ebv(self.node(arg)))
        return self.new(f"None if {flag} is None else not {flag}")

    def _term_test(self, name: str, args: list) -> str:
        found = [self.node(a) for a in args]
        if name == "SAMETERM":
            a, b = found
            return self.new(f"None if {a} is None or {b} is None else {a} == {b}")
        kind = self.const(_KINDS[name])
        return self.new(f"None if {found[0]} is None else isinstance({found[0]}, {kind})")

    def _str(self, arg: tuple) -> str:
        a = self.node(arg)
        return self.new(f"Str({a}.value) if isinstance({a}, NamedNode) else ({a} if type({a}) is Str else None)")

    def _substring(self, before: bool, text: tuple, sep: tuple) -> str:
        a, b = self.node(text), self.node(sep)
        at = self.new(f"{a}.find({b}) if type({a}) is Str and type({b}) is Str else None")
        part = f"{a}[:{at}]" if before else f"{a}[{at} + len({b}):]"
        return self.new(f"None if {at} is None else (Str('') if {at} < 0 else Str({part}))")


__all__ = ["compile_conditions", "compile_exact_over", "compile_holds_over"]
