"""Request and response messages of the aRMOR protocol (spec §1.1-§1.3).

Plain dataclasses with the field names of ``armor_msgs`` so a ROS bridge, an
HTTP service and the in-process client all exchange the same shapes.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from ..ontology.named_queries import QueryItem


def _text(data: Mapping[str, Any], key: str) -> str:
    """A string field of a request dict; ``None``/missing become ``""`` (the ROS default)."""
    value = data.get(key, "")
    if value is None:
        return ""
    if not isinstance(value, str):
        raise TypeError(f"{key} must be a string, got {type(value).__name__}")
    return _unicode(value, key)


def _unicode(value: str, what: str) -> str:
    """``value`` if it is valid Unicode text; lone surrogates (not encodable as UTF-8) are refused."""
    try:
        value.encode("utf-8")
    except UnicodeEncodeError as exc:
        raise ValueError(f"{what} contains a lone surrogate code point at index {exc.start}; "
                         "send valid Unicode text") from None
    return value


@dataclass
class ArmorRequest:
    """``ArmorDirectiveReq``: one command addressed to a reference."""

    client_name: str = ""
    reference_name: str = ""
    command: str = ""
    primary_command_spec: str = ""
    secondary_command_spec: str = ""
    args: list[str] = field(default_factory=list)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> ArmorRequest:
        """Build from a dict (JSON body, ROS message dict); missing fields default to empty.

        Raises ``TypeError`` for fields of the wrong type, so a transport can
        reject a malformed message instead of executing a guess.
        """
        if isinstance(data, ArmorRequest):
            return data
        data = _as_mapping(data)
        args = data.get("args") or []
        if isinstance(args, (str, bytes)) or not isinstance(args, (list, tuple)):
            raise TypeError("args must be a list of strings")
        if not all(isinstance(a, str) for a in args):
            raise TypeError("every element of args must be a string")
        for k, a in enumerate(args):
            _unicode(a, f"argument {k + 1}")
        return cls(
            client_name=_text(data, "client_name"),
            reference_name=_text(data, "reference_name"),
            command=_text(data, "command"),
            primary_command_spec=_text(data, "primary_command_spec"),
            secondary_command_spec=_text(data, "secondary_command_spec"),
            args=list(args),
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "client_name": self.client_name,
            "reference_name": self.reference_name,
            "command": self.command,
            "primary_command_spec": self.primary_command_spec,
            "secondary_command_spec": self.secondary_command_spec,
            "args": list(self.args),
        }


@dataclass
class ArmorResponse:
    """``ArmorDirectiveRes``; a fresh response is all false/0/empty as in ROS."""

    success: bool = False
    exit_code: int = 0
    error_description: str = ""
    is_consistent: bool = False
    timeout: bool = False
    queried_objects: list[str] = field(default_factory=list)
    sparql_queried_objects: list[QueryItem] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return {
            "success": self.success,
            "exit_code": self.exit_code,
            "error_description": self.error_description,
            "is_consistent": self.is_consistent,
            "timeout": self.timeout,
            "queried_objects": list(self.queried_objects),
            "sparql_queried_objects": [item.to_dict() for item in self.sparql_queried_objects],
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> ArmorResponse:
        """Rebuild a response received as a dict (e.g. over HTTP)."""
        items = [QueryItem(str(i["key"]), str(i["value"])) for i in data.get("sparql_queried_objects") or []]
        return cls(
            success=bool(data.get("success", False)),
            exit_code=int(data.get("exit_code", 0)),
            error_description=str(data.get("error_description", "")),
            is_consistent=bool(data.get("is_consistent", False)),
            timeout=bool(data.get("timeout", False)),
            queried_objects=[str(o) for o in data.get("queried_objects") or []],
            sparql_queried_objects=items,
        )


_REQUEST_FIELDS = ("client_name", "reference_name", "command", "primary_command_spec", "secondary_command_spec", "args")


def _as_mapping(data: Any) -> Mapping[str, Any]:
    """A request as a mapping: a dict, a ROS-style message object with the request
    fields as attributes, or either wrapped in ``armor_request`` (the service's
    request message)."""
    inner = data.get("armor_request") if isinstance(data, Mapping) else getattr(data, "armor_request", None)
    if inner is not None:
        data = inner
    if isinstance(data, Mapping):
        return data
    if all(hasattr(data, f) for f in _REQUEST_FIELDS):
        return {f: (list(getattr(data, f)) if f == "args" else getattr(data, f)) for f in _REQUEST_FIELDS}
    raise TypeError(f"a request must be a mapping or a message with the fields {', '.join(_REQUEST_FIELDS)}, "
                    f"got {type(data).__name__}")


@dataclass
class ArmorResponseList:
    """Reply of the serialized service (``ArmorDirectiveList``)."""

    success: bool = False
    is_consistent: bool = False
    armor_responses: list[ArmorResponse] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return {
            "success": self.success,
            "is_consistent": self.is_consistent,
            "armor_responses": [r.to_dict() for r in self.armor_responses],
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> ArmorResponseList:
        return cls(
            success=bool(data.get("success", False)),
            is_consistent=bool(data.get("is_consistent", False)),
            armor_responses=[ArmorResponse.from_dict(r) for r in data.get("armor_responses") or []],
        )


__all__ = ["ArmorRequest", "ArmorResponse", "ArmorResponseList", "QueryItem"]
