"""What a remote store knows of (subject, predicate, graph) values without asking (stores/listings.py)."""

from __future__ import annotations

import pytest
from pyoxigraph import Literal, NamedNode, Quad

from topostore.rdf.terms import value_key
from topostore.stores import listings as listings_module
from topostore.stores.listings import Listings

G, H = NamedNode("urn:x:g"), NamedNode("urn:x:h")
P, Q = NamedNode("urn:x:p"), NamedNode("urn:x:q")
A, B, C = NamedNode("urn:x:a"), NamedNode("urn:x:b"), NamedNode("urn:x:c")


def key(q: Quad):
    o = q.object
    return (q.subject, q.predicate, value_key(o), q.graph_name) if isinstance(o, Literal) else q


def lit(v: int, dt: str = "long") -> Literal:
    return Literal(str(v), datatype=NamedNode("http://www.w3.org/2001/XMLSchema#" + dt))


def test_a_listing_follows_own_writes_and_knows_absence() -> None:
    known = Listings(key)
    assert known.get(A, P, G) is None and known.presence(Quad(A, P, B, G), key(Quad(A, P, B, G))) is None
    known.learn(A, P, G, [Quad(A, P, lit(1), G)])
    known.committed([Quad(A, P, lit(2), G), Quad(C, P, B, G)], [Quad(A, P, lit(1, "int"), G)], lambda q: q)
    assert known.get(A, P, G) == [Quad(A, P, lit(2), G)]  # the removal matched by value
    assert known.get(C, P, G) is None  # C was never read: a write does not make its listing complete
    assert known.presence(Quad(A, P, lit(1), G), key(Quad(A, P, lit(1), G))) is False


def test_a_predicate_read_whole_answers_for_every_subject_until_a_write_it_cannot_follow() -> None:
    known = Listings(key)
    assert not known.missed(P, G) and known.missed(P, G) and not known.missed(P, G)  # the second miss only
    known.learn_whole(P, G, [Quad(A, P, B, G)])
    assert known.get(C, P, G) == [] and known.presence(Quad(C, P, B, G), key(Quad(C, P, B, G))) is False
    known.committed([Quad(C, P, B, G)], [], lambda q: q)
    assert known.get(C, P, G) == [Quad(C, P, B, G)]
    assert known.get(A, Q, G) is None  # another predicate is not known
    with known.keeping([G]):
        known.updated()  # an update that leaves G alone
    assert known.get(C, P, G) == [Quad(C, P, B, G)]
    known.updated()  # any other update may have changed G
    assert known.get(C, P, G) is None and known.get(B, P, G) is None


def test_eviction_ends_knowing_a_predicate_whole(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(listings_module, "MAX_LISTINGS", 4)
    known = Listings(key)
    known.learn_whole(P, G, [Quad(A, P, B, G), Quad(B, P, C, G)])
    known.learn(A, Q, H, [])
    known.learn(B, Q, H, [])
    assert known.get(C, P, G) == []
    known.learn(C, Q, H, [])  # the oldest listing (A P G) goes: P is no longer known whole
    assert known.get(A, P, G) is None and known.get(C, P, G) is None and known.get(B, P, G) is not None
    known.learn_whole(Q, G, [Quad(s, Q, C, G) for s in (A, B, C)])  # more subjects than half the room: not kept
    assert known.get(NamedNode("urn:x:d"), Q, G) is None
    known.forget()
    assert len(known) == 0
