"""What a load did not take as written: repaired or skipped rules, queries, incompletely reasoned axioms.

A file is never refused for what can be repaired or set aside, and never accepted
silently either: each such thing is a :class:`Notice` (what kind, which axiom or
rule, why).  Loading publishes them grouped by kind, once per kind and load, as
an :class:`OntologyWarning` (Python ``warnings``) and on the ``topostore`` log; the
aRMOR LOAD reply carries them in ``error_description``; ``topostore check`` prints
them; :attr:`topostore.ReasonReport.incomplete` holds the incompleteness ones.
"""

from __future__ import annotations

import logging
import warnings
from collections.abc import Iterable
from dataclasses import dataclass, field

logger = logging.getLogger("topostore.load")

#: Kinds of notices.  ``INCOMPLETE`` ones are axioms reasoned only in part (or not at all).
RULE_REPAIRED = "SWRL rule repaired"
RULE_SKIPPED = "SWRL rule skipped"
SQWRL_QUERY = "SQWRL query"
INCOMPLETE = "not reasoned completely"
#: Informative: an entailment every ontology of the kind has, answered by convention instead of stored.
NOT_STORED = "entailed, not stored"

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


class OntologyWarning(UserWarning):
    """A loaded ontology was repaired, has parts set aside, or is not reasoned completely."""


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
        warnings.warn(where + line, OntologyWarning, stacklevel=5)
    return lines


__all__ = ["INCOMPLETE", "NOT_STORED", "RULE_REPAIRED", "RULE_SKIPPED", "SQWRL_QUERY", "Notice", "OntologyWarning", "grouped",
           "publish"]
