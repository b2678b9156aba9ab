"""Repairing SWRL rules as the OWL API's RDF/XML writer leaves them (aRMOR SAVE, old Protégé).

The OWL API shares the blank nodes of equal structures when it writes RDF/XML,
and some of its versions write a rule's atom list *inside* another atom list (an
``swrl:AtomList`` whose ``rdf:first`` is itself an ``swrl:AtomList``), sometimes
the body of another rule appended to a body.  Read literally such a rule has an
atom "of type swrl:AtomList", which means nothing; Protégé says "Don't know how
to translate SWRL Atom" and Pellet drops the rule.

:func:`repair_rules` works on a document's triples before they are stored:

* a nested atom list is flattened in place (its atoms, in order, where it stood);
* a nested list that is another rule's whole body (the same node, or the same
  atoms) beside atoms of the rule's own is recognised as carried over and removed;
* a rule whose lists cannot be read (a list cell with two ``rdf:first``, a list
  that loops or is cut short) is skipped: its triples are not loaded;
* a repaired rule that still cannot be compiled is skipped by the loader
  (:mod:`topostore.ontology.files`); an untouched one refuses the file as before;

and says what it did in :class:`~topostore.compile.notices.Notice` s.  The repaired rule
is written back as a flat list, and list cells no rule reaches any more are
dropped, so a SAVE afterwards writes only well-formed rules.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from pyoxigraph import Literal, NamedNode, Triple

from ..rdf.skolem import fresh_skolem
from ..rdf.terms import Term
from ..rdf.vocab import FIRST, NIL, REST, SWRL, TYPE, is_skolem, rdf, rdfs, swrl
from .notices import RULE_REPAIRED, RULE_SKIPPED, Notice
from .reach import reachable_all

#: Atom kinds of the SWRL RDF vocabulary.
ATOM_KINDS = frozenset(SWRL + k for k in (
    "ClassAtom", "IndividualPropertyAtom", "DatavaluedPropertyAtom", "SameIndividualAtom",
    "DifferentIndividualsAtom", "DataRangeAtom", "BuiltinAtom"))
_LIST_TYPES = (swrl("AtomList"), rdf("List"))
_PARTS = (swrl("body"), swrl("head"))
#: Predicates leading from a rule to the nodes that are part of it.
_STRUCTURE = (swrl("body"), swrl("head"), FIRST, REST, swrl("arguments"))


def _imps(triples: Iterable[Triple]) -> dict[Term, None]:
    """The subjects typed swrl:Imp, in the order of their typing triples."""
    imp = swrl("Imp")
    return {t.subject: None for t in triples if t.object == imp and t.predicate == TYPE}


class _Unreadable(Exception):
    """A rule's structure that cannot be read; the message says where."""


class _Index:
    """Subject → predicate → objects (in document order) of a document's triples.

    Triples are grouped by subject in one pass; a subject's predicate table is built when the
    subject is first read, so a big ABox beside a few rules costs one pass, not a table each.
    """

    def __init__(self, triples: list[Triple], imps: dict[Term, None] | None = None) -> None:
        """``imps``: the rules, when the caller has found them already; else they are found when first
        asked (:meth:`imps`): an index only walked for reachability never needs them."""
        self._raw: dict[Term, list[Triple]] = {}
        self._triples = triples
        self._imps = imps
        raw = self._raw
        for t in triples:
            s = t.subject
            group = raw.get(s)
            if group is None:
                raw[s] = [t]
            else:
                group.append(t)
        self._nodes: dict[Term, dict[NamedNode, list[Term]]] = {}

    def node(self, s: Term) -> dict[NamedNode, list[Term]]:
        """The predicates and objects of ``s`` (each object once, in document order)."""
        table = self._nodes.get(s)
        if table is None:
            table = self._nodes[s] = {}
            for t in self._raw.get(s, ()):
                objs = table.setdefault(t.predicate, [])
                if t.object not in objs:
                    objs.append(t.object)
        return table

    def imps(self) -> list[Term]:
        """The rules (subjects typed swrl:Imp), in the order their subjects first appear."""
        if self._imps is None:
            self._imps = _imps(self._triples)
        if len(self._imps) < 2:
            return list(self._imps)
        return [s for s in self._raw if s in self._imps]

    def objects(self, s: Term, p: NamedNode) -> list[Term]:
        return self.node(s).get(p, [])

    def one(self, s: Term, p: NamedNode) -> Term | None:
        v = self.objects(s, p)
        return v[0] if v else None

    def is_list(self, node: Term) -> bool:
        types = self.objects(node, TYPE)
        return node == NIL or any(t in types for t in _LIST_TYPES) or bool(self.objects(node, FIRST))

    def is_atom(self, node: Term) -> bool:
        return any(isinstance(t, NamedNode) and t.value in ATOM_KINDS for t in self.objects(node, TYPE))

    def signature(self, atom: Term) -> tuple:
        """What an atom says (kind, predicate, arguments), independent of its node."""
        def pick(p: str) -> tuple[Term, ...]:
            return tuple(self.objects(atom, swrl(p)))
        args = ()
        lst = self.one(atom, swrl("arguments"))
        if lst is not None:
            try:
                args = tuple(self.walk(lst, lambda e: e))
            except _Unreadable:
                args = (lst,)
        return (tuple(sorted(str(t) for t in self.objects(atom, TYPE))), pick("classPredicate"),
                pick("propertyPredicate"), pick("dataRange"), pick("builtin"), pick("argument1"),
                pick("argument2"), args)

    def walk(self, head: Term, element) -> list:
        """The elements of a list (``element(node)`` each); _Unreadable when it is not one list."""
        out, seen, cell = [], set(), head
        while cell != NIL:
            if cell in seen:
                raise _Unreadable("a list that loops back on itself")
            seen.add(cell)
            firsts, rests = self.objects(cell, FIRST), self.objects(cell, REST)
            if len(firsts) != 1 or len(rests) != 1:
                raise _Unreadable(f"a list cell with {len(firsts)} rdf:first and {len(rests)} rdf:rest "
                                  "(two lists merged, or one cut short)")
            out.append(element(firsts[0]))
            cell = rests[0]
        return out


@dataclass
class _Part:
    """A rule's body or head as read: its atoms in order, and what reading it found."""

    atoms: list[Term] = field(default_factory=list)
    #: nested lists met (node, their atoms), outermost first
    nested: list[tuple[Term, list[Term]]] = field(default_factory=list)


def _read_part(ix: _Index, head: Term) -> _Part:
    """Atoms of a body or head, nested atom lists flattened where they stand."""
    part = _Part()

    def element(e: Term) -> list[Term]:
        if ix.is_list(e) and not ix.is_atom(e):
            inner = [a for sub in ix.walk(e, element) for a in sub]
            part.nested.append((e, inner))
            return inner
        return [e]  # an atom, or something the compiler names when it refuses it

    part.atoms = [a for sub in ix.walk(head, element) for a in sub]
    return part


def rule_name(ix: _Index, imp: Term) -> str:
    label = ix.one(imp, rdfs("label"))
    if isinstance(label, Literal):
        return label.value
    return "an unnamed SWRL rule" if is_skolem(imp) else imp.value


@dataclass
class _Outcome:
    """What repairing one rule decided: new parts, or a reason to skip it."""

    parts: dict[NamedNode, list[Term]] = field(default_factory=dict)
    what: list[str] = field(default_factory=list)
    skip: str = ""


def _decide(ix: _Index, imp: Term, bodies: dict[Term, tuple[Term, tuple]], names: dict[Term, str]) -> _Outcome:
    """How to repair one rule (``bodies``: every rule's body node and atom signatures)."""
    out = _Outcome()
    for p in _PARTS:
        lists = ix.objects(imp, p)
        if len(lists) > 1:
            out.skip = f"it has {len(lists)} {p.value[len(SWRL):]}s"
            return out
        if not lists:
            continue
        try:
            part = _read_part(ix, lists[0])
        except _Unreadable as exc:
            out.skip = f"its {p.value[len(SWRL):]} holds {exc}"
            return out
        if not part.nested:
            continue
        atoms = part.atoms
        for node, inner in part.nested:
            donor = _carried_from(ix, imp, node, inner, bodies)
            if donor is not None and len(inner) < len(atoms):
                atoms = _without(atoms, inner)
                out.what.append(f"removed the atoms of rule {names[donor]!r} carried in its "
                                f"{p.value[len(SWRL):]}")
        out.parts[p] = atoms
        out.what.append(f"flattened {len(part.nested)} nested atom list(s) in its {p.value[len(SWRL):]}")
    return out


def _carried_from(ix: _Index, imp: Term, node: Term, inner: list[Term],
                  bodies: dict[Term, tuple[Term, tuple]]) -> Term | None:
    """The other rule whose whole body a nested list is (the same node, or the same atoms)."""
    sig = tuple(ix.signature(a) for a in inner)
    for other, (body, other_sig) in bodies.items():
        if other != imp and (body == node or (sig and sig == other_sig)):
            return other
    return None


def _without(atoms: list[Term], inner: list[Term]) -> list[Term]:
    """``atoms`` without one occurrence of the run ``inner`` (the last one: carried atoms are appended)."""
    n = len(inner)
    for k in range(len(atoms) - n, -1, -1):
        if atoms[k:k + n] == inner:
            return atoms[:k] + atoms[k + n:]
    return atoms


def _reachable(ix: _Index, roots: Iterable[Term]) -> set[Term]:
    """Nodes reachable from ``roots`` through rule structure (lists, atoms, argument lists)."""
    return reachable_all(roots, lambda n: [o for p in _STRUCTURE for o in ix.objects(n, p) if is_skolem(o)])


def _flat_list(atoms: list[Term]) -> tuple[Term, list[Triple]]:
    """A fresh atom list (cells typed swrl:AtomList, as Protégé writes them)."""
    if not atoms:
        return NIL, []
    cells = [fresh_skolem() for _ in atoms]
    triples = []
    for k, (cell, atom) in enumerate(zip(cells, atoms)):
        triples += [Triple(cell, TYPE, swrl("AtomList")), Triple(cell, FIRST, atom),
                    Triple(cell, REST, cells[k + 1] if k + 1 < len(cells) else NIL)]
    return cells[0], triples


def repair_rules(triples: list[Triple]) -> tuple[list[Triple], list[Notice]]:
    """A document's triples with its SWRL rules repaired (or skipped), and what was done."""
    found = _imps(triples)
    if not found:
        return triples, []  # no rule: nothing to index (large ABox loads pay one scan)
    ix = _Index(triples, found)
    imps = ix.imps()  # every rule found is a subject of the index: never empty here
    names = {imp: rule_name(ix, imp) for imp in imps}
    bodies = {}
    for imp in imps:
        body = ix.one(imp, swrl("body"))
        if body is not None:
            try:
                bodies[imp] = (body, tuple(ix.signature(a) for a in _read_part(ix, body).atoms))
            except _Unreadable:
                continue
    outcomes = {imp: _decide(ix, imp, bodies, names) for imp in imps}
    if not any(o.skip or o.parts for o in outcomes.values()):
        return triples, []
    return _rewrite(ix, triples, imps, outcomes, names)


def needs_repair(read: Callable[[Term], Iterable[Triple]], imps: Iterable[Term]) -> bool:
    """Whether :func:`repair_rules` would repair or skip any of the rules ``imps``, asking only for their
    nodes (``read(node)``: its triples, e.g. from the graph they were written to): the nodes reached from
    each rule through its body, head, lists and argument lists, every node the repair reads."""
    todo = list(dict.fromkeys(imps))
    seen = set(todo)
    triples: list[Triple] = []
    while todo:
        for t in read(todo.pop()):
            triples.append(t)
            o = t.object
            if t.predicate in _STRUCTURE and not isinstance(o, Literal) and o not in seen:
                seen.add(o)
                todo.append(o)
    return bool(repair_rules(triples)[1])


def _rewrite(ix: _Index, triples: list[Triple], imps: list[Term], outcomes: dict[Term, _Outcome],
             names: dict[Term, str]) -> tuple[list[Triple], list[Notice]]:
    """Apply the outcomes: new flat parts, skipped rules out, structure no rule reaches any more dropped."""
    before = _reachable(ix, imps)
    drop: set[Triple] = set()
    add: list[Triple] = []
    notices = []
    for imp in imps:
        o = outcomes[imp]
        if o.skip:
            drop.update(Triple(imp, p, v) for p, vs in ix.node(imp).items() for v in vs)
            notices.append(Notice(RULE_SKIPPED, names[imp], f"not loaded: {o.skip}", node=imp))
            continue
        for p, atoms in o.parts.items():
            head, cells = _flat_list(atoms)
            drop.update(Triple(imp, p, v) for v in ix.objects(imp, p))
            add += [Triple(imp, p, head), *cells]
        if o.parts:
            notices.append(Notice(RULE_REPAIRED, names[imp], "; ".join(o.what), node=imp))
    kept = [t for t in triples if t not in drop] + add
    after = _reachable(_Index(kept), [imp for imp in imps if not outcomes[imp].skip])
    orphans = before - after
    return [t for t in kept if t.subject not in orphans], notices


def skip_rule(triples: list[Triple], imp: Term, why: str) -> tuple[list[Triple], Notice]:
    """``triples`` without the rule ``imp`` and the structure only it used; the notice saying so."""
    ix = _Index(triples)
    imps = ix.imps()
    outcomes = {i: _Outcome(skip=why if i == imp else "") for i in imps}
    kept, notices = _rewrite(ix, triples, imps, outcomes, {i: rule_name(ix, i) for i in imps})
    return kept, notices[0]


def rule_triples(triples: list[Triple]) -> tuple[list[Triple], list[Triple]]:
    """(the SWRL rules' triples: rules, their lists and atoms, variable declarations; the others)."""
    ix = _Index(triples)
    imps = ix.imps()
    nodes = _reachable(ix, imps)
    variable = swrl("Variable")
    rules, rest = [], []
    for t in triples:
        is_rule = t.subject in nodes or (t.predicate == TYPE and t.object == variable)
        (rules if is_rule else rest).append(t)
    return rules, rest


def replace_rules(saved: list[Triple], original: list[Triple]) -> tuple[list[Triple], int, int]:
    """``saved`` with its SWRL rules replaced by those of ``original``: (triples, rules removed, rules put back).

    What aRMOR users did by hand after a SAVE damaged the rules: the world (the
    individuals and their facts) from the saved file, the rules from the file they
    were written in."""
    old, kept = rule_triples(saved)
    new, _ = rule_triples(original)
    count = sum(1 for t in old if t.predicate == TYPE and t.object == swrl("Imp"))
    put = sum(1 for t in new if t.predicate == TYPE and t.object == swrl("Imp"))
    present = set(kept)
    return kept + [t for t in new if t not in present], count, put


__all__ = ["ATOM_KINDS", "needs_repair", "repair_rules", "replace_rules", "rule_name", "rule_triples", "skip_rule"]
