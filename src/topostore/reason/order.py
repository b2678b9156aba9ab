"""In which order a full REASON evaluates its rules, and which rules it can leave out.

The rules' dependency graph (a rule reads what another writes) is split into strongly connected
components, evaluated writers first; inside a component, rules run in an order where most readers
follow their writers (:func:`within`), so that only the rules read before them need a delta.  Rules
that cannot fire at all from the asserted keys (:func:`reachable`) stay out of the order.  Kept apart
from :mod:`.materialize`, which runs what this module orders, and from :mod:`.implied_passes`, which
reads the order for what the writers of a key imply (the first passes that can read less).
"""

from __future__ import annotations

from collections.abc import Callable

from pyoxigraph import NamedNode

from ..compile.rule import Atom, ReadKey, Rule
from ..rdf.vocab import TYPE
from .triggers import Present, Triggers

#: the read key of ``rdf:type`` as a predicate (an atom or head ``?x rdf:type ?c``)
TYPE_KEY = str(TYPE)


def reachable(triggers: Triggers, indexes: list[int], present: Present) -> Present:
    """The predicates and classes that may get facts when the rules ``indexes`` run from ``present``.

    A rule that can match (every key its body needs may have facts) adds the key it writes; a
    head of any class (``?x rdf:type ?c``) or any predicate may write every key, and the result
    says so by holding every key the rules need.  A rule not feasible in the result can never
    match in those rules' fixpoint.
    """
    preds, classes = set(present[0]), set(present[1])
    needed = triggers.needed_keys()
    waiting = list(indexes)
    grew = True
    while grew:
        grew = False
        for i in [i for i in waiting if triggers.feasible(i, (preds, classes))]:
            waiting.remove(i)
            grew = True
            key = triggers.rules[i].writes()
            if key is None:
                continue
            if key[0] == "t":
                classes.add(key[1])
                preds.add(TYPE_KEY)
            else:
                preds.add(key[1] if key[0] == "p" else TYPE_KEY)
                if key[0] == "*":
                    preds.update(k[1] for k in needed if k[0] == "p")
                if key[0] == "*" or key[1] == TYPE_KEY:
                    classes.update(k[1] for k in needed if k[0] == "t")
    return preds, classes


def single_graphs(rules: list[Rule], writers: list[int], needed: set[tuple[str, str]], asserted: Present,
                  graph_of: Callable[[Rule], NamedNode], asserted_graph: NamedNode) -> dict[ReadKey, NamedNode]:
    """The read keys whose facts all lie in one graph while only the rules ``writers`` write.

    A key's facts lie in the asserted graph when it has an asserted fact (``asserted``: exact for
    the ``needed`` keys) and in the graph each of its writers writes to (``graph_of``); a rule
    writing ``?x rdf:type ?c`` may write every class.  Keys with facts in two graphs, or in none
    (their readers cannot match), are left out, as is ``rdf:type`` with a variable class.  Only
    valid while no other rule writes: a rule of a variable predicate, or of an upper stratum, may
    write any key anywhere.
    """
    found: dict[ReadKey, set[NamedNode]] = {}
    any_class: set[NamedNode] = set()
    for i in writers:
        key = rules[i].writes()
        if key is None:
            continue
        if key == ("p", TYPE_KEY):
            any_class.add(graph_of(rules[i]))
        found.setdefault(key, set()).add(graph_of(rules[i]))
    out: dict[ReadKey, NamedNode] = {}
    for kind, name in needed:
        if kind not in ("p", "t") or (kind, name) == ("p", TYPE_KEY):
            continue
        graphs = set(found.get((kind, name), ()))
        if kind == "t":
            graphs |= any_class
        if name in asserted[0 if kind == "p" else 1]:
            graphs.add(asserted_graph)
        if len(graphs) == 1:
            out[(kind, name)] = graphs.pop()
    return out


def evaluation_order(rules: list[Rule], indexes: list[int]) -> tuple[list[list[int]], list[int], set[int]]:
    """Strongly connected components of the rules' dependency graph, writers first, each in an
    order where most readers come after the writers they read (:func:`within`).

    Rules that read or write a variable predicate (``*``) depend on everything
    and are returned apart (second value), to run after the ordered pass; the
    third value holds the rules whose facts a rule at or before them in their
    component reads (the edges that make the component recursive).
    """
    wild = [i for i in indexes if rules[i].writes() == ("*",) or ("*",) in rules[i].reads()]
    skipped = set(wild)
    nodes = [i for i in indexes if i not in skipped]
    # readers per key, so that the edges cost their number, not rules² (a TBox of 100 classes
    # compiles to thousands of rules).  A written key reaches the readers of the same key; a class
    # membership also reaches patterns ``?x rdf:type ?c``, and those reach every class reader.
    readers: dict[tuple, list[int]] = {}
    for b in nodes:
        for key in rules[b].reads():
            readers.setdefault(key, []).append(b)
    type_key = ("p", str(TYPE))
    class_readers = [b for key, bs in readers.items() if key[0] == "t" for b in bs]
    position = {b: n for n, b in enumerate(nodes)}
    succ: dict[int, list[int]] = {}
    for a in nodes:
        w = rules[a].writes()
        found = set(readers.get(w, ()))
        if w[0] == "t":
            found.update(readers.get(type_key, ()))
        elif w == type_key:
            found.update(class_readers)
        succ[a] = sorted(found, key=position.__getitem__)
    components = [within(c, succ) for c in strongly_connected(nodes, succ)]
    at = {a: n for c in components for n, a in enumerate(c)}
    comp = {a: k for k, c in enumerate(components) for a in c}
    back = {a for a in nodes if any(comp[b] == comp[a] and at[b] <= at[a] for b in succ[a])}
    return components, wild, back


def within(component: list[int], succ: dict[int, list[int]]) -> list[int]:
    """The rules of a component in reverse post-order of a depth-first walk inside it: a
    topological order where the component has no cycle, and few readers before their writers
    where it has (each such edge makes a rule's facts go through a delta)."""
    if len(component) == 1:
        return component
    members = set(component)
    seen: set[int] = set()
    post: list[int] = []
    for root in component:
        if root in seen:
            continue
        seen.add(root)
        work = [(root, iter(succ[root]))]
        while work:
            node, children = work[-1]
            child = next((c for c in children if c in members and c not in seen), None)
            if child is None:
                work.pop()
                post.append(node)
                continue
            seen.add(child)
            work.append((child, iter(succ[child])))
    post.reverse()
    return post


def strongly_connected(nodes: list[int], succ: dict[int, list[int]]) -> list[list[int]]:
    """The strongly connected components of a graph (each sorted), in topological order: a
    component comes before every component it has an edge to.

    Tarjan's algorithm, iterative (rule sets are deep enough to exhaust Python's recursion).
    Written here rather than taken from networkx, which is not a dependency of topostore: the
    core install is kept to what the service needs (pyproject.toml), and networkx would be
    imported by every CLI start for these thirty lines.  tests/test_rule_structure.py checks
    the result against the definition (mutual reachability) and the order on random graphs.
    """
    # components come out of Tarjan's algorithm in reverse topological order
    index: dict[int, int] = {}
    low: dict[int, int] = {}
    on_stack: set[int] = set()
    stack: list[int] = []
    components: list[list[int]] = []
    counter = 0
    for root in nodes:
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            v, k = work.pop()
            if k == 0:
                index[v] = low[v] = counter
                counter += 1
                stack.append(v)
                on_stack.add(v)
            if k < len(succ[v]):
                work.append((v, k + 1))
                w = succ[v][k]
                if w not in index:
                    work.append((w, 0))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            for w in succ[v]:
                if w in on_stack:
                    low[v] = min(low[v], low[w])
            if low[v] == index[v]:
                component = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    component.append(w)
                    if w == v:
                        break
                components.append(sorted(component))
    components.reverse()
    return components


def is_path(atom: Atom) -> bool:
    """A property path in the predicate's place (neither an IRI nor a variable)."""
    return not atom.p.startswith(("<", "?"))


def asserted_paths(rules: list[Rule], ordered: list[int]) -> set[int]:
    """The rules of the ordered pass whose property paths (the AllDifferent keys walk a list) read only
    keys no ordered rule writes, so that every fact a path reads is asserted while the pass runs (the
    inferred and helper graphs are empty when a full run starts).

    Such a path is read in the asserted graph alone: one index instead of the whole default dataset
    (the keys of 10,000 AllDifferent members: 131 → 116 ms by hand).  The keys are the ones the rule
    declares it reads (``# reads:``); a rule declaring none keeps its paths as written.
    """
    written = {rules[i].writes() for i in ordered}
    out: set[int] = set()
    for i in ordered:
        rule = rules[i]
        if rule.filter_reads and any(is_path(a) for a in rule.body) and all(
                _unwritten(key, written) for key in rule.filter_reads):
            out.add(i)
    return out


def _unwritten(key: ReadKey, written: set) -> bool:
    """Whether no rule writing the keys ``written`` may write a fact of ``key`` (an IRI predicate)."""
    if key[0] != "p" or key[1] == TYPE_KEY or not key[1].startswith("<") or ("*",) in written:
        return False
    return key not in written
