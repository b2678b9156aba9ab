"""A rule's heads before and after a clean replacement of one atom's value, diffed instead of over-deleted.

Why this exists
---------------
``canReach(r, l) ← isIn(r, x) ∧ connectedTo(x, l)`` with ``isIn(r)`` replaced from ``a`` to ``b``: DRed
writes the heads ``canReach(r, ·)`` present before as candidates, reads them back, rechecks each against
the new state (the body again, one read per atom per candidate), deletes those not proven, then joins
the added ``isIn(r, b)`` for the additions.  Where the change is known to keep one value per pair and
the key has one prover, that is one computation done twice: the rule's heads in the new state with
``r`` are exactly those it derives from ``isIn(r, b)`` (the additions' join), so a present head of
``r`` not among them is no longer derived, and one among them not known yet is new.

:class:`Regroup` does that where :func:`regroupable` holds at compile time: rule ``i`` is its key's one
prover (the program deletes its candidates inside its recheck, :func:`.delta_texts.recheck_one`), the
key has no other change in the program (no other candidates, no flip, no removed asserted fact), atom
``j`` is on a predicate the signature says is cleanly replaced (every changed pair holds one value
before and after it: :func:`.flip.clean_replacements`) and no rule writes, the atom is the rule's only
one on that predicate, and its subject is a head variable (a head binds the pair, whose one value now is
the added one).  Every other atom of the rule is final when the key's part runs (the parts run in
dependency order and the key is not recursive), so the additions' join reads the new state.

At run time it is given the change's removed and added facts of the atom (:meth:`.staged.StagedRun.change_facts`)
and checks them pair by pair (one removed and one added fact per subject); where anything is not as
expected (facts not given, more than FEW, a literal) it does what the candidates' look-up does
(:class:`.direct.Relaxed`) and the part runs as DRed: :data:`REGROUPED` tells the run the recheck and the
atom's additions are done.
"""

from __future__ import annotations

from pyoxigraph import Literal, Triple

from ..compile.rule import Rule
from .direct import Relaxed, _write_new, relaxable
from .look_join import Joined, joinable
from .scratch import CANDIDATES


class _Regrouped:
    """A :class:`Regroup`'s answer (truthy) where it diffed the heads: the part's recheck and the atom's
    additions have nothing left to do."""

    __slots__ = ()

    def __repr__(self) -> str:
        return "REGROUPED"


REGROUPED = _Regrouped()


def regroupable(rule: Rule, j: int, clean, written) -> bool:
    """Whether rule ``rule``'s atom ``j`` meets :class:`Regroup`'s compile-time conditions on the rule (the
    caller checks the part's: one prover, no other candidates, no flip, no removed asserted fact);
    ``clean``: the signature's cleanly replaced predicates, ``written``: whether a rule writes a key."""
    atom, head = rule.body[j], rule.head
    if head is None or atom.p not in clean or written(atom.read_key()):
        return False
    if not atom.s.startswith("?") or atom.s not in head.variables() or not atom.o.startswith("?"):
        return False
    if sum(1 for a in rule.body if a.read_key() == atom.read_key()) != 1:
        return False
    return relaxable(rule, j) and joinable(rule)


class Regroup:
    """Rule ``rule``'s heads with atom ``j`` replaced, diffed (see the module docstring)."""

    def __init__(self, rule: Rule, j: int, graph, graphs_of) -> None:
        self._relaxed = Relaxed(rule, j, graph)
        self._joined = Joined(rule, graph, j, graphs_of)
        self.graph = graph
        #: the keys its look-ups read: the rule's atoms and its head
        self.reads = self._relaxed.reads | self._joined.reads
        #: as the candidates' look-up's: without facts of the other atoms, nothing was derived through the atom
        self.needs = {"run": self._relaxed.needs["run"]}

    def run(self, store, lost: list[Triple] | None = None, added: list[Triple] | None = None) -> object:
        """:data:`REGROUPED` where the heads were diffed (lost ones deleted, new ones added); True where only
        the candidates were written (the part's recheck and additions follow); False: the text runs."""
        candidates = self._relaxed.candidates(store, lost)
        if candidates is None:
            return False
        if lost is None or added is None or not _paired(lost, added):
            store.add_scratch(candidates, CANDIDATES)
            return True
        heads = self._joined.derived(store, added)
        if heads is None or any(isinstance(t.object, Literal) for t in candidates):
            store.add_scratch(candidates, CANDIDATES)
            return True
        now = set(heads)
        if not self._joined.remove([c for c in candidates if c not in now], store):
            store.add_scratch(candidates, CANDIDATES)  # nothing removed yet: the recheck decides
            return True
        _write_new(store, heads, self.graph)
        return REGROUPED


def _paired(lost: list[Triple], added: list[Triple]) -> bool:
    """Whether ``lost`` and ``added`` are one removed and one added fact per subject, the same subjects."""
    if len(lost) != len(added):
        return False
    subjects = {t.subject for t in lost}
    return len(subjects) == len(lost) and subjects == {t.subject for t in added}


__all__ = ["REGROUPED", "Regroup", "regroupable"]
