"""``client.query``: armor_py_api's query methods (spec §6.4), bugs of §7 item 25 fixed.

Answers are checked for ``success`` before they are parsed and names are
stripped without ever raising on IRIs that have no ``#``.  Data values come
back exactly as aRMOR renders them (``'"1665579740"^^xsd:long'``), as the
original client returns them, so code that slices the lexical form out
(``value[1:-11]``) keeps working; :func:`lexical_form` does it for any type.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .armor_exceptions import ArmorServiceInternalError

if TYPE_CHECKING:  # pragma: no cover
    from .armor_client import ArmorClient


def strip_uri(full_name: str) -> str:
    """``<http://x#E>`` → ``E``; ``<http://x/E>`` → ``E``; anything not bracketed is returned as is."""
    if full_name.startswith("<") and full_name.endswith(">"):
        iri = full_name[1:-1]
        if "#" in iri:
            return iri.split("#", 1)[1]
        return iri.rstrip("/").rsplit("/", 1)[-1]
    return full_name


def lexical_form(rendered: str) -> str:
    """The lexical form of a rendered literal (``"7"^^xsd:long`` → ``7``; bare text unchanged)."""
    if not rendered.startswith('"'):
        return rendered
    out, i = [], 1
    while i < len(rendered):
        c = rendered[i]
        if c == "\\" and i + 1 < len(rendered):
            out.append(rendered[i + 1])
            i += 2
            continue
        if c == '"':
            return "".join(out)
        out.append(c)
        i += 1
    return rendered  # unterminated: not a rendered literal


class ArmorQueryClient:
    def __init__(self, client: ArmorClient) -> None:
        self._client = client

    def ind_b2_class(self, class_name: str, with_URI: bool = False) -> list[str]:  # noqa: N803 (original name)
        res = self._client._checked("QUERY", "IND", "CLASS", [class_name])
        return list(res.queried_objects) if with_URI else [strip_uri(o) for o in res.queried_objects]

    def dataprop_b2_ind(self, dataprop_name: str, ind_name: str) -> list[str]:
        """Values as aRMOR renders them (``'"1665579740"^^xsd:long'``); :func:`lexical_form` gives ``'1665579740'``."""
        res = self._client._checked("QUERY", "DATAPROP", "IND", [dataprop_name, ind_name])
        return list(res.queried_objects)

    def objectprop_b2_ind(self, objectprop_name: str, ind_name: str, with_URI: bool = False) -> list[str]:  # noqa: N803
        res = self._client._checked("QUERY", "OBJECTPROP", "IND", [objectprop_name, ind_name])
        return list(res.queried_objects) if with_URI else [strip_uri(o) for o in res.queried_objects]

    def check_ind_exists(self, ind_name: str) -> bool:
        """True iff the individual occurs in the ontology; only transport errors raise."""
        res = self._client._unchecked("QUERY", "IND", "", [ind_name])
        return bool(res.success and res.queried_objects)

    def _strip_URI(self, full_name: str) -> str:  # noqa: N802 (original name)
        return strip_uri(full_name)


__all__ = ["ArmorQueryClient", "ArmorServiceInternalError", "strip_uri", "lexical_form"]
