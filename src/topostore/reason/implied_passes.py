"""What the writers of the ordered first stratum imply, so that a first pass can read less.

A full REASON's first pass of a rule reads every fact of its keys.  Where every rule writing a key
(a *writer*) already implies what a rule concludes, or what one of its class atoms tests, the pass
can read the asserted facts alone (:func:`implied_first_passes`) or leave the class atom out
(:func:`implied_atoms`, from the classes every fact of a key carries on its subject:
:func:`subject_classes`).  Decided over the order :mod:`.order` gives; applied by :mod:`.first_pass`.
"""

from __future__ import annotations

from collections.abc import Callable

from ..compile.implied import classes_of, position_classes
from ..compile.rule import ReadKey, Rule
from .guarded import Guarded, guarded_classes, guarded_rules
from .order import TYPE_KEY
from .triggers import Present


def implied_first_passes(rules: list[Rule], ordered: list[int], asserted: Present | None = None) -> set[int]:
    """The rules of the ordered first stratum whose first pass needs only the asserted facts it reads.

    A rule ``A ⟹ C(v)`` of one atom (a domain, a range, a subclass, an intersection's part) reads
    key K; when every rule writing K in the ordered pass (a *writer*) already implies ``C`` of the
    term it puts at ``v``'s place, the rule's conclusions on derived K facts hold anyway, and its
    first pass (which reads every fact of K: 20,000 connectedTo links at 10,000 locations, all
    concluding what the locations' doors concluded before) can read the asserted facts alone.
    "Implies" is read off the writer's evaluated body: ``C`` of the term as an atom, or through a
    rule of one atom over a key no ordered rule writes (``hasDoor(x, y) ⟹ LOCATION(x)``, whose own
    evaluation reads every fact of its key), or a base rule whose one condition is a non-literal guard the
    writer's body meets (:mod:`.guarded`: ``hasDoor(x, y1) ⟹ ∃hasDoor.DOOR(x)`` for the writers of
    ``≥2 hasDoor.DOOR``).  Those *base* rules are never restricted themselves,
    which keeps the argument from resting on a restricted rule (``D ⟹ C`` justified by ``q ⟹ D``
    and itself would leave the derived ``D`` facts without ``C``).  Later facts of K (from rules of a
    variable predicate or an upper stratum) reach the rule through its delta evaluations, which read
    every graph as before: the closure is the same.  With ``asserted`` (the keys with asserted facts),
    a writer that only returns K facts already held (:func:`_returns`) needs to imply nothing.
    """
    written, implied = _writers(rules, ordered)
    guarded = guarded_rules(rules[i] for i in ordered
                            if len(rules[i].body) == 1 and not written(rules[i].body[0].read_key()))
    out: set[int] = set()
    for i in ordered:
        rule = rules[i]
        if not _one_atom_to_class(rule):
            continue
        key = rule.body[0].read_key()
        ws = written(key)
        if ws and i not in ws and all(_implies(rules[w], rule, implied, guarded)
                                      or _returns(rules[w], key, written, rules, asserted)
                                      or _implied_through(rules[w], rule, written, rules, implied, guarded, asserted)
                                      for w in ws):
            out.add(i)
    return out


def _writers(rules: list[Rule], ordered: list[int]) -> tuple[Callable[[ReadKey], list[int]], dict]:
    """The ordered rules writing each key (a head of any class writes every class), and the classes
    each position implies through the *base* rules: one atom over a key no ordered rule writes,
    whose evaluation reads every fact of it (:func:`implied_first_passes` says why only those)."""
    writers: dict[ReadKey, list[int]] = {}
    for i in ordered:
        writers.setdefault(rules[i].writes(), []).append(i)
    any_class = writers.get(("p", TYPE_KEY), [])

    def written(key: ReadKey) -> list[int]:
        return writers.get(key, []) + (any_class if key[0] == "t" else [])

    base = [rules[i] for i in ordered if len(rules[i].body) == 1 and not written(rules[i].body[0].read_key())]
    return written, position_classes(base)


def implied_atoms(rules: list[Rule], ordered: list[int], asserted: Present) -> dict[int, tuple[int, ...]]:
    """Per rule of the ordered first stratum, the class atoms its first pass can leave out.

    ``C(v) ∧ K(v, …) ∧ … ⟹ H`` where every fact of K the ordered rules can write before the pass
    carries ``C`` on its subject (:func:`subject_classes`): the pass may then read K alone
    (``LOCATION ⊓ ≥2 hasDoor.DOOR``: the 5,000 members of the restriction instead of the 10,000
    LOCATIONs, each looked up in the other).  Sound by induction over the writes: each fact an
    evaluation writes has its rule's whole body in the closure (a first pass matching fewer atoms
    matches only where the left-out atom holds there); complete because fewer atoms match more.
    Facts of K written later (a rule of a variable predicate, an upper stratum) reach the rule
    through delta evaluations of its whole body.  An atom left out never vouches for another.
    """
    candidates = [i for i in ordered if _has_class_atom_beside(rules[i])]
    if not candidates:
        return {}  # the table below reads every rule: not built where no body could use it
    carried = subject_classes(rules, ordered, asserted)
    out: dict[int, tuple[int, ...]] = {}
    for i in candidates:
        rule = rules[i]
        dropped: list[int] = []
        for j, atom in enumerate(rule.body):
            if atom.p != TYPE_KEY or atom.o.startswith("?") or not atom.s.startswith("?"):
                continue
            if any(atom.o in carried.get(rule.body[k].read_key(), ()) and rule.body[k].s == atom.s
                   and rule.writes() != rule.body[k].read_key()
                   for k in range(len(rule.body)) if k != j and k not in dropped):
                dropped.append(j)
        if dropped:
            out[i] = tuple(dropped)
    return out


def _has_class_atom_beside(rule: Rule) -> bool:
    """A rule of the first stratum, positive, with a class atom and another atom on its subject."""
    if len(rule.body) < 2 or rule.is_check or rule.stratum or rule.negates or rule.conditions_read_graph:
        return False
    return any(a.p == TYPE_KEY and not a.o.startswith("?") and a.s.startswith("?")
               and any(b is not a and b.s == a.s for b in rule.body) for a in rule.body)


def subject_classes(rules: list[Rule], ordered: list[int], asserted: Present) -> dict[ReadKey, frozenset[str]]:
    """Per key the ordered rules write, the classes the subject of every fact of it has in the closure.

    A key with an asserted fact, or written by a rule of any class, carries nothing; otherwise what
    each writer's body says of the subject it writes, through its atoms (a class atom, a position a
    one-atom rule types) and through what the keys of its atoms on that subject carry, in common to
    all writers.  The greatest such table: true of every fact by induction over the writes (a fact's
    writer read facts written before it), so a cycle of keys that only feed each other carries what
    the cycle implies (it has no fact unless something outside it vouches).
    """
    written, _ = _writers(rules, ordered)
    implied = position_classes(rules)  # the closure is closed under every rule
    keys = {rules[i].writes() for i in ordered} - {None, ("*",), ("p", TYPE_KEY)}
    keys = {k for k in keys if k[0] in ("p", "t") and k[1] not in asserted[0 if k[0] == "p" else 1]}
    writers = {k: written(k) for k in keys}
    # a key written by a rule whose head puts no variable at the subject, or by a rule of any class, carries nothing
    keys = {k for k in keys if all(_writes_key(rules[w], k) for w in writers[k])}
    carried: dict[ReadKey, frozenset[str] | None] = dict.fromkeys(keys)  # None: not yet bounded (every class)
    readers: dict[ReadKey, set[ReadKey]] = {}
    for k in keys:
        for w in writers[k]:
            for atom in rules[w].body:
                readers.setdefault(atom.read_key(), set()).add(k)
    work = list(keys)
    while work:
        k = work.pop()
        found = None
        for w in writers[k]:
            got = _writer_classes(rules[w], implied, carried)
            found = got if found is None else (found if got is None else found & got)
        if found is not None and found != carried[k]:
            carried[k] = found
            work.extend(r for r in readers.get(k, ()) if r not in work)
    return {k: v for k, v in carried.items() if v is not None}


def _writes_key(rule: Rule, key: ReadKey) -> bool:
    """Whether ``rule`` writes ``key`` itself (not any class or predicate) with a variable subject."""
    head = rule.head
    return head is not None and head.read_key() == key and head.s.startswith("?")


def _writer_classes(rule: Rule, implied: dict, carried: dict) -> frozenset[str] | None:
    """The classes ``rule``'s body gives the subject of its head (None: every class, from a key not
    yet bounded in ``carried``)."""
    term = rule.head.s
    out = set(classes_of(term, rule.body, implied))
    for atom in rule.body:
        key = atom.read_key()
        if atom.s == term and key in carried:
            if carried[key] is None:
                return None
            out |= carried[key]
    return frozenset(out)


def _one_atom_to_class(rule: Rule) -> bool:
    """``A ⟹ C(v)``: one atom of a named predicate, a class head on one of its variables, stratum 0."""
    if rule.is_check or rule.stratum or len(rule.body) != 1 or rule.negates or rule.conditions_read_graph:
        return False
    (atom,), head = rule.body, rule.head
    return (head.p == TYPE_KEY and not head.o.startswith("?") and head.s.startswith("?")
            and not atom.p.startswith("?") and head.s in (atom.s, atom.o))


def _implies(writer: Rule, rule: Rule, implied: dict, guarded: list[Guarded] = ()) -> bool:
    """Whether ``writer``'s body implies ``rule``'s head class of the term its head puts at the head's place
    (through the one-atom rules ``implied`` follows, or a base rule with a non-literal guard, :mod:`.guarded`)."""
    (atom,), head = rule.body, rule.head
    wrote = writer.head
    if wrote is None or wrote.p != atom.p or (atom.p == TYPE_KEY and wrote.o != atom.o):
        return False
    term = wrote.s if head.s == atom.s else wrote.o
    return term.startswith("?") and (head.o in classes_of(term, writer.body, implied)
                                      or head.o in guarded_classes(term, writer, guarded, implied))


def _returns(writer: Rule, key: ReadKey, written: Callable[[ReadKey], list[int]], rules: list[Rule],
             asserted: Present | None) -> bool:
    """Whether ``writer`` (``B(x) ⟹ A(x)``, ``key`` being A's) writes no fact of A that is not held already.

    So it is where B has no asserted fact and every rule writing B concludes it of a term its body
    holds an A atom of (an intersection's part back to a member: ``CORRIDOR ⟹ ≥2 hasDoor.DOOR`` where
    CORRIDOR's one writer reads ``LOCATION(x) ∧ ≥2 hasDoor.DOOR(x)``): each B fact then stands on an A
    fact of its subject, which is the fact the writer writes.  Unknown asserted keys (None) say no.
    """
    if asserted is None or key[0] != "t" or len(writer.body) != 1 or writer.head is None:
        return False
    (atom,), head = writer.body, writer.head
    if (atom.p != TYPE_KEY or atom.o.startswith("?") or atom.s != head.s or not head.s.startswith("?")
            or atom.o in asserted[1]):
        return False
    for w in written(atom.read_key()):
        back = rules[w].head
        if back is None or back.read_key() != atom.read_key() or not back.s.startswith("?"):
            return False  # a rule of any class, or of a constant subject
        if not any(a.p == TYPE_KEY and a.o == key[1] and a.s == back.s for a in rules[w].body):
            return False
    return True


def _implied_through(writer: Rule, rule: Rule, written: Callable[[ReadKey], list[int]], rules: list[Rule],
                     implied: dict, guarded: list[Guarded], asserted: Present | None) -> bool:
    """Whether ``writer`` (``B(x) ⟹ A(x)``, ``rule`` being ``A ⟹ C``) writes A only of terms C holds of already.

    So it is where B has no asserted fact and every rule writing B implies C of the term it concludes B of
    (:func:`_implies`' reading of a body: its atoms and the *base* rules): each B fact then stands on a
    body that gives its subject C, the subject of the A fact the writer writes (``CORRIDOR ⟹ ROOM`` for
    ``ROOM ⟹ LOCATION``, CORRIDOR's one writer reading ``hasDoor(x, y1)``, whose domain is LOCATION: the
    first pass of ``ROOM ⟹ LOCATION`` read 100,000 ROOMs at 100,000 locations to write none).  Unknown
    asserted keys (None) say no.
    """
    if asserted is None or len(writer.body) != 1 or writer.head is None:
        return False
    (atom,), head = writer.body, writer.head
    if (atom.p != TYPE_KEY or atom.o.startswith("?") or atom.s != head.s or not head.s.startswith("?")
            or atom.o in asserted[1] or rule.head.s != rule.body[0].s):
        return False
    writers = written(atom.read_key())
    for w in writers:
        back = rules[w].head
        if back is None or back.read_key() != atom.read_key() or not back.s.startswith("?"):
            return False  # a rule of any class, or of a constant subject
        if rule.head.o not in (classes_of(back.s, rules[w].body, implied)
                               | guarded_classes(back.s, rules[w], guarded, implied)):
            return False
    return bool(writers)
