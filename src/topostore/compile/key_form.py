"""The form of the AllDifferent keys: the members of the one member list the asserted graph holds are their own keys.

Why
---
Two individuals are different by ``owl:AllDifferent`` when they hold two different keys of one group
(``rules/different-by-group.rq``); a group is one member list of an AllDifferent node (OWL 2 RL's
eq-diff2/eq-diff3 read each list apart).  In general a key names its list and its member
(``urn:topostore:key:<md5(list)>:<md5(member)>``, ``rules/all-different-key.rq``): a term made for
every member, which at 100,000 locations is 199,999 new IRIs to build and write, the longest part of the
chain of evaluations beside the fixpoint.  A map has one ``owl:AllDifferent`` over its locations and
doors: its one list is the only group, and each member can be its own key
(``rules/one-list/all-different-key.rq``, compiled with that list): the same walk of the list, no term
made.  The rule walks every list of a node typed AllDifferent, asserted or inferred; a list it reaches other
than the counted one (a member link or a type only inferred, a node typed AllDisjointClasses too, reached
through sameAs) keys by list and member as in the general form, a group of its own, never joined to the
counted list's group.

Same answers
------------
With one member list ``L``, the keys ``(L, m)`` of the general form and the members ``m`` of this one
name each other one to one, and every key fact ``k ts:differentKeyOf x`` of one form is a key fact of
the other with its key renamed (``all-different`` writes one per member, ``eq-rep-s`` copies a key to
what is the same as its holder, as it is, in either form).  Every reader of the keys compares two keys
by term (``!sameTerm``) and by group part (:func:`.counting.group_of`, the text between the key prefix
and the next colon): two members differ as their keys do, and a member's group part is empty for every
member (a member is no key IRI), as the one list's group part is one for all of its keys.  So every
rule matches the same bindings, the keys renamed, and concludes the same facts (a key is never in a
conclusion the user sees).

Lists are counted in the asserted graph, every list of an ``owl:members`` or ``owl:distinctMembers``
link but those of ``owl:AllDisjointClasses`` and ``owl:AllDisjointProperties`` (a TBox's; a node linked
to a list and typed AllDifferent only by a later inference counts from the start).  The count is the
compiled rules' (:attr:`.rule.RuleSet.one_list`): a change adding or removing a member link is noted
(:func:`touches_groups`), and the next REASON compiles the rules again when the count crossed one
(:func:`form_changed`); new rules make a full REASON, which clears the helper graph and writes the keys
in the new form.  Rules compiled right after a first document was streamed into the empty graph
(``ontology/files.py``) are that graph's own: the next REASON does not count its lists again.  A durable
store records the form it wrote (``ontology/state.py``).
"""

from __future__ import annotations

from collections.abc import Iterable
from functools import lru_cache

from pyoxigraph import NamedNode, Triple

from ..rdf.vocab import FIRST, ONE_MEMBER_LIST, REST, TYPE, owl
from ..resources import rules_dir
from ..stores.base import Store
from .generic import parse_rule_file
from .rule import Rule

#: the links from an n-ary axiom's node to its member list
MEMBER_LINKS = frozenset({owl("members"), owl("distinctMembers")})
#: the n-ary axioms of a TBox whose member lists are not AllDifferent groups
_TBOX = (owl("AllDisjointClasses"), owl("AllDisjointProperties"))
#: the name of the rule writing the keys (both forms)
KEY_RULE = "all-different"


def one_member_list(store: Store, graph: NamedNode) -> NamedNode | None:
    """The one member list of an ``owl:AllDifferent`` ``graph`` holds, None when it holds none or several
    (see the module); read by look-ups, which see an open transaction's writes without sending them (a
    query would send them, and a failed transaction could then no longer be undone)."""
    lists: set = set()
    for p in sorted(MEMBER_LINKS, key=str):
        for t in store.triples(None, p, None, graph):
            if t.object not in lists and not any(store.contains(Triple(t.subject, TYPE, kind), graph) for kind in _TBOX):
                lists.add(t.object)
                if len(lists) > 1:
                    return None
    found = next(iter(lists), None)
    return found if isinstance(found, NamedNode) else None


#: the term the one-list key rule's file names its list by, replaced by the list when it is compiled
LIST_PLACEHOLDER = f"<{ONE_MEMBER_LIST.value}>"


@lru_cache(maxsize=32)  # one small rule per list seen; a service with many references keeps the last few
def one_list_rule(the_list: NamedNode | None = None) -> Rule:
    """The key rule of the one-list form (``rules/one-list/all-different-key.rq``) for ``the_list`` (None:
    as the file writes it, its list a placeholder): only that list's members are their own keys, and a
    list the rule reaches otherwise (a member link or an AllDifferent type only inferred, a node typed
    AllDisjointClasses too) keys by list and member as in the general form, a group of its own."""
    path = rules_dir() / "one-list" / "all-different-key.rq"
    if the_list is None:
        return parse_rule_file(path)
    return parse_rule_file(path, path.read_text().replace(LIST_PLACEHOLDER, f"<{the_list.value}>"))


def key_rule_form(rules: Iterable[Rule], the_list: NamedNode | None) -> list[Rule]:
    """``rules`` with the generic key rule in the form of ``the_list`` (:func:`one_member_list`; None: the
    general form, the one read from ``rules/``)."""
    if the_list is None:
        return list(rules)
    special = one_list_rule(the_list)
    return [special if r.name == KEY_RULE and r.head_aux() else r for r in rules]


def touches_groups(triples: Iterable[Triple]) -> bool:
    """Whether a change adds or removes a member link, which may change how many member lists there are
    (a type of ``owl:AllDisjointClasses`` or ``owl:AllDisjointProperties`` is a schema triple: it compiles
    the rules again anyway), or a list cell, which may make a member list malformed or well formed again
    (:func:`.graph_notices.malformed_now`: a notice the rules were compiled with)."""
    for t in triples:  # a loop, not any() over a generator: a manipulation changes one or two triples
        if t.predicate in _GROUP_LINKS:
            return True
    return False


#: the predicates :func:`touches_groups` looks for
_GROUP_LINKS = MEMBER_LINKS | {FIRST, REST}


def form_changed(store: Store, graph: NamedNode, the_list: NamedNode | None) -> bool:
    """Whether the keys' form of rules compiled for ``the_list`` is no longer the one ``graph`` gives (a
    list added or removed, or the one list another)."""
    return one_member_list(store, graph) != the_list


__all__ = ["KEY_RULE", "LIST_PLACEHOLDER", "MEMBER_LINKS", "form_changed", "key_rule_form", "one_list_rule", "one_member_list",
           "touches_groups"]
