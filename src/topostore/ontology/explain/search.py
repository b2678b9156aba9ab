"""Finding why a triple holds: one derivation, found by running the compiled rules backwards.

Every inferred triple was put there by a compiled :class:`~topostore.compile.Rule`
(a W3C OWL 2 RL rule, a SWRL rule, or one of topostore's helper rules), so the
explanation is found by running rules *backwards*: for each rule whose head
matches the triple, the rule's body is evaluated with the head's variables
bound (one SPARQL SELECT over asserted ∪ inferred ∪ helper graphs, the dataset
the reasoner itself reads), and every answer gives the premises of one
derivation.  Premises are explained the same way, recursively.

Which derivation: the search is iterative deepening, so the tree returned is
one of **minimal height**; among those, the first rule in compilation order
(as ``topostore rules`` lists them) and the first answer of its body.  A premise
already on the path from the root is never used again, so cyclic axioms
(``LOCATION ≡ visitedAt exactly 1``, ``URGENT ⊑ LOCATION``) cannot loop.

Helper-graph facts appear in readable form: membership of an anonymous class
expression as ``R1 a (isIn exact 1 LOCATION)``, AllDifferent keys as
``D1 in AllDifferent(D1, D2)``, difference as ``D1 different from D2``.
"""

from __future__ import annotations

import hashlib
import re
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

from pyoxigraph import Literal, NamedNode, Triple

from ...compile.class_expressions import ClassExpressionReader
from ...compile.generic import PREFIXES
from ...compile.rule import Atom, Rule, join_order
from ...compile.snippets import VALUE_CANDIDATE
from ...errors import QueryError, RuleCompileError
from ...rdf.terms import Term, parse_term, sparql, value_key
from ...rdf.vocab import (
    ASSERTED,
    AUX,
    DECLARED_DIFFERENT,
    DIFFERENCE_CANDIDATE,
    DIFFERENT,
    DIFFERENT_KEY_OF,
    ENTAILED,
    ENTAILED_PREFIX,
    INFERRED,
    KEY_PREFIX,
    OWL,
    RDF,
    RDFS,
    SWRL,
    SWRLB,
    TYPE,
    XSD,
    is_skolem,
    owl,
)
from .tree import Explanation

#: The dataset rules read (as in reason/materialize.py): default graph asserted ∪ inferred ∪ helper.
DATASET = [ASSERTED, INFERRED, AUX]
MAX_DEPTH = 40
#: Answers of one rule body considered per triple (each is one candidate derivation).
MAX_CANDIDATES = 20
#: Members of an AllDifferent group named in its readable form.
GROUP_SHOWN = 6
#: Short prefixes of the standard vocabularies, for readable names and for names users type (``rdf:type``).
SHORT_PREFIXES = {RDF: "rdf:", RDFS: "rdfs:", OWL: "owl:", XSD: "xsd:", SWRL: "swrl:", SWRLB: "swrlb:"}
_HELPER_NAMES = {
    DIFFERENCE_CANDIDATE: "difference asked with",
    VALUE_CANDIDATE: "difference by values asked with",
    DECLARED_DIFFERENT: "declared different from",
    DIFFERENT: "different from",
}


@dataclass(frozen=True)
class Candidate:
    """One way a rule derives a triple: the rule, its full variable binding, its premises."""

    rule: Rule
    binding: dict
    premises: tuple[tuple[Triple | None, str], ...]  # (triple, "") or (None, property path)
    atoms: tuple[Atom, ...] = ()


class Explainer:
    """Finds derivations over one store's graphs with one rule set (see the module docstring)."""

    def __init__(self, store, rules: list[Rule], short: Callable[[Term], str]) -> None:
        self.store = store
        self.rules = [r for r in rules if not r.is_check]
        self._short = short
        self._candidates: dict[Triple, list[Candidate]] = {}
        self._proved: dict[Triple, Explanation] = {}
        self._failed: dict[Triple, int] = {}
        self._reader: ClassExpressionReader | None = None
        self._groups: dict[str, tuple[Term, Term]] | None = None
        self._texts: dict[object, str] = {}  # readable forms of AllDifferent groups and keys

    # ------------------------------------------------------------ facts
    def holds(self, t: Triple) -> bool:
        return any(self.store.contains(t, g) for g in (ASSERTED, INFERRED, AUX, ENTAILED))

    def explain(self, t: Triple) -> Explanation:
        if not self.holds(t):
            return Explanation(self.render(t), "not entailed")
        for limit in range(1, MAX_DEPTH + 1):
            found, _ = self._prove(t, limit, frozenset())
            if found is not None:
                return found
        return Explanation(self.render(t), "inferred", origin=f"no derivation found within {MAX_DEPTH} steps")

    def _prove(self, t: Triple, limit: int, path: frozenset) -> tuple[Explanation | None, bool]:
        """A derivation of height ≤ ``limit`` avoiding ``path``; and whether the path pruned the search."""
        if self.store.contains(t, ASSERTED):
            return Explanation(self.render(t), "asserted"), False
        done = self._proved.get(t)
        if done is not None and done.height <= limit:
            return done, False
        if limit <= 1 or self._failed.get(t, 0) >= limit:
            return None, False
        pruned = False
        path = path | {t}
        for c in self.candidates(t):
            premises: list[Explanation] = []
            for (p, _path_text), atom in zip(c.premises, c.atoms):
                if p is None:
                    premises.append(self._path_premise(atom, c.binding))
                    continue
                if p in path:
                    pruned = True
                    break
                sub, sub_pruned = self._prove(p, limit - 1, path)
                pruned |= sub_pruned
                if sub is None:
                    break
                premises.append(sub)
            else:
                node = self._node(t, c, premises)
                self._proved[t] = node
                return node, pruned
        if not pruned:
            self._failed[t] = max(self._failed.get(t, 0), limit)
        return None, pruned

    def _path_premise(self, atom: Atom, binding: dict) -> Explanation:
        """A property-path premise (an AllDifferent's member list, a member of that list), checked by the
        rule's query."""
        s = binding.get(atom.s)
        o = binding.get(atom.o)
        s_text = self.render_term(s) if s is not None else atom.s
        o_text = self.render_term(o) if o is not None else atom.o
        if "distinctMembers" in atom.p:
            return Explanation(f"{s_text} has the member list {self._list_text(o) if o is not None else o_text}",
                               "asserted")
        if "rdf:first" in atom.p:
            return Explanation(f"{o_text} listed in {self._list_text(s) if s is not None else s_text}", "asserted")
        return Explanation(f"{s_text} {self._readable_filters(atom.p)} {o_text}", "condition")

    def _node(self, t: Triple, c: Candidate, premises: list[Explanation]) -> Explanation:
        conditions = " ".join(c.rule.written_filters.split())
        shown = {k: self.render_term(v) for k, v in c.binding.items()} if conditions else {}
        return Explanation(self.render(t), "inferred", c.rule.name, c.rule.origin, premises, shown,
                           self._readable_filters(conditions),
                           1 + max((p.height for p in premises), default=0))

    def _readable_filters(self, text: str) -> str:
        """Filter text with IRIs shortened (``<...#visitedAt>`` → ``visitedAt``)."""
        return re.sub(r"<([^<>\s]*)>", lambda m: self.render_term(NamedNode(m.group(1))), text)

    # ------------------------------------------------------------ rules backwards
    def candidates(self, t: Triple) -> list[Candidate]:
        if t not in self._candidates:
            found: list[Candidate] = []
            if self.store.contains(t, ENTAILED) and isinstance(t.predicate, NamedNode):
                weak = Triple(t.subject, NamedNode(ENTAILED_PREFIX + t.predicate.value), t.object)
                publish = Rule("swrl-entailed", "SWRL conclusion whose individuals are different by entailment only",
                               (Atom("?s", "?weak", "?o", aux=True),), Atom("?s", "?p", "?o"))
                found.append(Candidate(publish, {}, ((weak, ""),), publish.body))
            for rule in self.rules:
                binding = unify(rule.head, t)
                if binding is not None:
                    found += self._instances(rule, binding)
            self._candidates[t] = found
        return self._candidates[t]

    def _instances(self, rule: Rule, binding: dict[str, Term]) -> list[Candidate]:
        """Answers of the rule's body with the head's variables bound (at most MAX_CANDIDATES)."""
        atoms = rule.premises
        order = join_order(atoms, None, bound=binding)
        lines = [_atom_text(atoms[i], binding) for i in order]
        if rule.filters:
            lines.append(rule.filters)
        if binding:
            names = sorted(binding)
            lines.append(f"VALUES ({' '.join(names)}) {{ ({' '.join(sparql(binding[n]) for n in names)}) }}")
        text = "SELECT * WHERE {\n  " + "\n  ".join(lines) + f"\n}} LIMIT {MAX_CANDIDATES}"
        try:
            rows = list(self.store.query(text, graphs=DATASET, prefixes=PREFIXES))
        except QueryError:
            return []
        out = []
        for row in rows:
            full = dict(binding)
            for var in _variables(rule):
                value = row[var[1:]]
                if value is not None:
                    full[var] = value
            premises = tuple(_premise(a, full) for a in atoms)
            out.append(Candidate(rule, full, premises, atoms))
        return out

    # ------------------------------------------------------------ readable text
    def render(self, t: Triple) -> str:
        p = t.predicate
        s, o = self.render_term(t.subject), self.render_term(t.object)
        if p == DIFFERENT_KEY_OF:  # the key is the subject, the member the object
            key = self.render_key(t.subject)
            return f"{o} in {key.split(' in ', 1)[1] if key.startswith('key of ') else key}"
        if p in _HELPER_NAMES:
            return f"{s} {_HELPER_NAMES[p]} {o}"
        if isinstance(p, NamedNode) and p.value.startswith(ENTAILED_PREFIX):
            return f"{s} {self.render_term(NamedNode(p.value[len(ENTAILED_PREFIX):]))} {o} (different by entailment only)"
        return f"{s} {self.render_term(p)} {o}"

    def render_term(self, term: Term) -> str:
        if isinstance(term, Literal):
            return self.store.restore(term).value
        if isinstance(term, NamedNode):
            v = term.value
            if is_skolem(term):
                return self._render_node(term)
            if v.startswith(KEY_PREFIX):
                return self.render_key(term)
            for ns, prefix in SHORT_PREFIXES.items():
                if v.startswith(ns):
                    return prefix + v[len(ns):]
            return self._short(term)
        return str(term)

    def _render_node(self, node: NamedNode) -> str:
        if self.store.contains(Triple(node, TYPE, owl("AllDifferent")), ASSERTED):
            return self._group_text(node)
        if self._reader is None:
            self._reader = ClassExpressionReader(self.store, ASSERTED)
        try:
            return str(self._reader.expr(node))
        except RuleCompileError:  # not a class expression: a plain anonymous node
            return "_:" + node.value.rsplit(":", 1)[-1][:8]

    def _group_text(self, group: Term) -> str:
        if group not in self._texts:
            self._texts[group] = self._group_text_uncached(group)
        return self._texts[group]

    def _group_text_uncached(self, group: Term) -> str:
        members = []
        for p in (owl("distinctMembers"), owl("members")):
            for head in self.store.objects(group, p, ASSERTED):
                members += self.store.list_items(head, ASSERTED)
        return "AllDifferent" + self._members_text(members)

    def _list_text(self, head: Term) -> str:
        """One member list by its members: a key's group is its list, so a node with two lists shows
        only the list that made its members different."""
        if ("list", head) not in self._texts:
            self._texts[("list", head)] = self._members_text(self.store.list_items(head, ASSERTED))
        return self._texts[("list", head)]

    def _members_text(self, members: list) -> str:
        shown = [self.render_term(m) for m in members[:GROUP_SHOWN]]
        if len(members) > GROUP_SHOWN:
            shown.append(f"… {len(members)} members")
        return "(" + ", ".join(shown) + ")"

    def render_key(self, key: Term) -> str:
        """``urn:topostore:key:<md5(list)>:<md5(member)>``, or a member that is its own key where the store
        holds one member list (:mod:`topostore.compile.key_form`) → the member and the AllDifferent group."""
        if key not in self._texts:
            self._texts[key] = self._render_key_uncached(key)
        return self._texts[key]

    def _render_key_uncached(self, key: Term) -> str:
        if self._groups is None:
            self._groups = {}
            for g in self.store.subjects(TYPE, owl("AllDifferent"), ASSERTED):
                for p in (owl("distinctMembers"), owl("members")):
                    for head in self.store.objects(g, p, ASSERTED):
                        self._groups[hashlib.md5(head.value.encode()).hexdigest()] = (g, head)
        if isinstance(key, NamedNode) and not key.value.startswith(KEY_PREFIX) and len(self._groups) == 1:
            _, head = next(iter(self._groups.values()))  # one member list: a member is its own key
            return f"key of {self.render_term(key)} in AllDifferent{self._list_text(head)}"
        digest = key.value.split(":")[3] if isinstance(key, NamedNode) and key.value.count(":") >= 4 else ""
        found = self._groups.get(digest)
        if found is None:
            return "an AllDifferent key"
        group, head = found
        member = key.value.split(":")[4]
        for m in self.store.list_items(head, ASSERTED):
            if hashlib.md5(m.value.encode()).hexdigest() == member:
                return f"key of {self.render_term(m)} in AllDifferent{self._list_text(head)}"
        return f"a key in AllDifferent{self._list_text(head)}"


def _variables(rule: Rule) -> list[str]:
    """Variables of the body atoms and of the filters (a BIND's result, e.g. ?d = ?t - ?v)."""
    names = {v for c in rule.conditions for v in c.variables}
    for a in rule.premises:
        names |= a.variables()
    return sorted(names)


def unify(head: Atom | None, t: Triple) -> dict[str, Term] | None:
    """Variable binding making the rule head equal to ``t``, or None."""
    if head is None:
        return None
    binding: dict[str, Term] = {}
    for pattern, term in ((head.s, t.subject), (head.p, t.predicate), (head.o, t.object)):
        if pattern.startswith("?"):
            if pattern in binding and binding[pattern] != term:
                return None
            binding[pattern] = term
        else:
            const = constant(pattern)
            if const is None or value_key(const) != value_key(term):
                return None
    return binding


@lru_cache(maxsize=4096)
def constant(text: str) -> Term | None:
    """The RDF term a rendered SPARQL constant stands for (None for a property path)."""
    if not text.startswith(("<", '"')) or (text.startswith("<") and not text.endswith(">")):
        return None
    return parse_term(text)


def _atom_text(atom: Atom, binding: dict[str, Term]) -> str:
    terms = [sparql(binding[x]) if x in binding else x for x in (atom.s, atom.p, atom.o)]
    text = " ".join(terms) + " ."
    return f"GRAPH {AUX} {{ {text} }}" if atom.aux else text


def _premise(atom: Atom, binding: dict[str, Term]) -> tuple[Triple | None, str]:
    """The body atom as a triple under ``binding``; a property path atom gives (None, its text)."""
    terms = []
    for x in (atom.s, atom.p, atom.o):
        term = binding.get(x) if x.startswith("?") else constant(x)
        if term is None:
            return None, atom.p  # a property path: shown, not explained further
        terms.append(term)
    try:
        return Triple(*terms), ""
    except TypeError:
        return None, atom.p


__all__ = ["Candidate", "Explainer", "constant", "unify", "DATASET", "MAX_DEPTH"]
