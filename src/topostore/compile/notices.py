"""What a load did not take as written: repaired or skipped rules, queries, incompletely reasoned axioms.

A file is never refused for what can be repaired or set aside, and never accepted
silently either: each such thing is a :class:`Notice` (what kind, which axiom or
rule, why).  Loading publishes them grouped by kind, once per kind and load, as
an :class:`OntologyWarning` (Python ``warnings``) and on the ``topostore`` log; the
aRMOR LOAD reply carries them in ``error_description``; ``topostore check`` prints
them; :attr:`topostore.ReasonReport.incomplete` holds the incompleteness ones.

Every warning topostore gives (an :class:`OntologyWarning` or a subclass) goes through :func:`warn`, so that a
command layer answering them itself (an aRMOR reply's ``error_description``, an HTTP reply's ``warnings``)
collects the texts of the categories its answers do not hold already (:func:`answered`): a warning is no fault
of a command, so one the caller's filter turns into an error (``warnings.simplefilter("error")``,
``python -W error``) is not raised there.  Blocks nest: a layer inside such a command (a reference's
manipulation inside an aRMOR command) opens its own, and the innermost one hears what is said.
"""

from __future__ import annotations

import logging
import warnings
from collections.abc import Iterable
from contextvars import ContextVar
from dataclasses import dataclass, field

logger = logging.getLogger("topostore.load")

#: Kinds of notices.  ``INCOMPLETE`` ones are axioms reasoned only in part (or not at all).
RULE_REPAIRED = "SWRL rule repaired"
RULE_SKIPPED = "SWRL rule skipped"
SQWRL_QUERY = "SQWRL query"
INCOMPLETE = "not reasoned completely"
#: Informative: an entailment every ontology of the kind has, answered by convention instead of stored.
NOT_STORED = "entailed, not stored"
#: Informative: an annotation property's axioms (domain, range, super-property), set aside as OWL 2 and Pellet do.
ANNOTATION = "annotation property axioms without logical meaning"

#: Axiom kinds of the profile report, the ``axiom_kind`` of an ``INCOMPLETE`` notice (the groups of the LOAD
#: warning): :mod:`.profile` and :mod:`.graph_notices`.
UNION = "union or one-of as a superclass"
COMPLEMENT = "complement on the left"
UNIVERSAL = "universal restriction on the left"
MAX_LEFT = "maximum cardinality on the left"
MAX_CASES = "maximum cardinality needing case analysis"
EXISTENTIAL = "existential with consequences for an unnamed value"
DIFFERENCE = "difference entailed by a property characteristic"
UNSUPPORTED = "not supported"
UNCHECKED_DATATYPE = "values of a datatype not checked"
#: the transitivity or chain of a property OWL 2 DL wants simple where it is used, ignored as Pellet ignores it
NON_SIMPLE = "non-simple property where a simple one is wanted"
#: a SWRL rule that cannot be compiled (an unknown built-in, a malformed atom): kept in the graph, not reasoned
RULE_SET_ASIDE = "SWRL rule set aside"


class OntologyWarning(UserWarning):
    """A loaded ontology was repaired, has parts set aside, or is not reasoned completely."""


#: while a command layer answers warnings itself: the texts it puts in its answer, and of which categories
#: (None: no such layer; per thread)
_HEARD: ContextVar[tuple[list[str], tuple[type[Warning], ...]] | None] = ContextVar("topostore_warnings_answered",
                                                                                   default=None)


def warn(text: str, category: type[OntologyWarning], stacklevel: int = 1) -> None:
    """Give ``text`` as a Python warning of ``category`` (``stacklevel`` counted from the caller); inside
    :func:`answered`, not raised where the caller's filter makes it an error, and given to the answer where it
    takes that category."""
    heard = _HEARD.get()
    if heard is None:
        warnings.warn(text, category, stacklevel=stacklevel + 1)
        return
    texts, categories = heard
    if issubclass(category, categories):
        texts.append(text)
    try:
        warnings.warn(text, category, stacklevel=stacklevel + 1)
    except category:  # turned into an error by the caller's filter: the answer carries it, the command stands
        pass


class answered:  # noqa: N801 - used as a function: ``with answered(Category) as heard:``
    """The texts of the warnings of ``categories`` said inside the block, which a command layer puts in its
    answer; no warning raises inside it, whatever the warnings filter (one of another category, such as a
    load's notices, is in the answer already, or said on the log only).  A class, not a generator: every
    aRMOR command opens one."""

    __slots__ = ("heard", "categories", "token")

    def __init__(self, *categories: type[Warning]) -> None:
        self.heard: list[str] = []
        self.categories = categories

    def __enter__(self) -> list[str]:
        self.token = _HEARD.set((self.heard, self.categories))
        return self.heard

    def __exit__(self, *exc: object) -> None:
        _HEARD.reset(self.token)


def unsaid(heard: list[str], said: Iterable[str]) -> list[str]:
    """The texts of ``heard`` that no line of ``said`` (an answer's warnings) holds already, each once."""
    lines = list(said)
    return [text for text in dict.fromkeys(heard) if not any(text in line for line in lines)]


@dataclass(frozen=True)
class Notice:
    """One thing a load did not take as written.

    ``kind``: one of the module's kinds; ``subject``: the rule's name or the axiom
    (readable); ``reason``: what was done or what is missing; ``axiom_kind``: for
    incompleteness, the kind of axiom (e.g. "union as a superclass").
    """

    kind: str
    subject: str
    reason: str
    axiom_kind: str = ""
    #: the rule or axiom node the notice is about (not part of its text)
    node: object = field(default=None, compare=False, repr=False)

    @property
    def incomplete(self) -> bool:
        return self.kind == INCOMPLETE

    @property
    def group(self) -> str:
        """The heading notices are grouped under: the kind, and the axiom kind for incompleteness."""
        return f"{self.kind}: {self.axiom_kind}" if self.axiom_kind else self.kind

    def __str__(self) -> str:
        return f"{self.group}: {self.subject} ({self.reason})"


def grouped(notices: Iterable[Notice]) -> list[str]:
    """One line per group (kind, or kind and axiom kind), naming every subject with its reason."""
    groups: dict[str, list[Notice]] = {}
    for n in notices:
        groups.setdefault(n.group, []).append(n)
    return [f"{group}: " + "; ".join(f"{n.subject} ({n.reason})" for n in members)
            for group, members in groups.items()]


def publish(notices: Iterable[Notice], source: str = "") -> list[str]:
    """Warn (``OntologyWarning``) and log each group once; returns the lines."""
    lines = grouped(notices)
    where = f"{source}: " if source else ""
    for line in lines:
        logger.warning("%s%s", where, line)
        # the caller of Ontology.load/load_data: publish ← _published ← OntologyFiles.load* ← Ontology.load*
        warn(where + line, OntologyWarning, stacklevel=5)
    return lines


__all__ = ["ANNOTATION", "INCOMPLETE", "NOT_STORED",
           "RULE_REPAIRED", "RULE_SET_ASIDE", "RULE_SKIPPED", "SQWRL_QUERY", "Notice", "OntologyWarning", "answered",
           "grouped", "publish", "unsaid", "warn"]
