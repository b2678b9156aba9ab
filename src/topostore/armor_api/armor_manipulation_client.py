"""``client.manipulation``: armor_py_api's manipulation methods (spec §6.3), bugs of §7 item 25 fixed.

Each method returns the reply's ``is_consistent`` unless documented otherwise
and raises :class:`ArmorServiceInternalError` when the service refuses.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

from ..armor.codes import SEVERAL_VALUES
from .armor_exceptions import ArmorServiceInternalError
from .armor_query_client import lexical_form

if TYPE_CHECKING:  # pragma: no cover
    from .armor_client import ArmorClient


class ArmorManipulationClient:
    def __init__(self, client: ArmorClient) -> None:
        self._client = client

    def add_ind_to_class(self, ind_name: str, class_name: str) -> bool:
        return self._client._checked("ADD", "IND", "CLASS", [ind_name, class_name]).is_consistent

    def disj_inds_of_class(self, class_name: str) -> bool:
        """Declare all current instances of ``class_name`` different (one AllDifferent)."""
        return self._client._checked("DISJOINT", "IND", "CLASS", [class_name]).is_consistent

    def add_objectprop_to_ind(self, objectprop_name: str, ind_name: str, value_obj_name: str) -> bool:
        return self._client._checked("ADD", "OBJECTPROP", "IND", [objectprop_name, ind_name, value_obj_name]).is_consistent

    def add_dataprop_to_ind(self, dataprop_name: str, ind_name: str, value_type: str, value: str) -> bool:
        """An unsupported ``value_type`` raises (code 101) instead of passing silently."""
        return self._client._checked("ADD", "DATAPROP", "IND", [dataprop_name, ind_name, value_type, str(value)]).is_consistent

    def add_batch_dataprop_to_ind(self, ind_name: str, dataprops: Iterable[Sequence[str]]) -> bool:
        """Add ``[prop, type, value]`` triples in order; ``False`` at the first inconsistent reply."""
        for prop, value_type, value in dataprops:
            if not self.add_dataprop_to_ind(prop, ind_name, value_type, value):
                return False
        return True

    def replace_objectprop_b2_ind(self, objectprop_name: str, ind_name: str, new_value: str, old_value: str) -> bool:
        return self._client._checked("REPLACE", "OBJECTPROP", "IND",
                                     [objectprop_name, ind_name, new_value, old_value]).is_consistent

    def replace_dataprop_b2_ind(self, dataprop_name: str, ind_name: str, value_type: str, new_value: str,
                                old_value: str) -> bool:
        return self._client._checked("REPLACE", "DATAPROP", "IND",
                                     [dataprop_name, ind_name, value_type, str(new_value), str(old_value)]).is_consistent

    def replace_one_dataprop_b2_ind(self, dataprop_name: str, ind_name: str, value_type: str, new_value: str) -> bool:
        """Set the single value of a data property (add if none; 206 if several).

        The old value is sent as its lexical form (the original client sent the
        rendered literal back, which the service cannot match).
        """
        values = self._client.query.dataprop_b2_ind(dataprop_name, ind_name)
        if len(values) > 1:
            raise ArmorServiceInternalError(
                f"{dataprop_name} of {ind_name} has {len(values)} values {values}; cannot replace just one", SEVERAL_VALUES)
        if not values:
            return self.add_dataprop_to_ind(dataprop_name, ind_name, value_type, new_value)
        return self.replace_dataprop_b2_ind(dataprop_name, ind_name, value_type, new_value, lexical_form(values[0]))

    def replace_one_objectprop_b2_ind(self, objectprop_name: str, ind_name: str, new_value: str) -> bool:
        """Set the single value of an object property (add if none; 206 if several)."""
        values = self._client.query.objectprop_b2_ind(objectprop_name, ind_name)
        if len(values) > 1:
            raise ArmorServiceInternalError(
                f"{objectprop_name} of {ind_name} has {len(values)} values {values}; cannot replace just one", SEVERAL_VALUES)
        if not values:
            return self.add_objectprop_to_ind(objectprop_name, ind_name, new_value)
        return self.replace_objectprop_b2_ind(objectprop_name, ind_name, new_value, values[0])

    def remove_dataprop_from_ind(self, dataprop_name: str, ind_name: str, value_type: str, value: str) -> bool:
        return self._client._checked("REMOVE", "DATAPROP", "IND", [dataprop_name, ind_name, value_type, str(value)]).is_consistent

    def remove_objectprop_from_ind(self, objectprop_name: str, ind_name: str, value: str) -> bool:
        return self._client._checked("REMOVE", "OBJECTPROP", "IND", [objectprop_name, ind_name, value]).is_consistent

    def remove_batch_dataprop_to_ind(self, ind_name: str, dataprops: Iterable[Sequence[str]]) -> bool:
        """Remove ``[prop, type, value]`` triples in order; ``False`` at the first inconsistent reply."""
        for prop, value_type, value in dataprops:
            if not self.remove_dataprop_from_ind(prop, ind_name, value_type, value):
                return False
        return True

    def remove_ind_from_class(self, ind_name: str, class_name: str) -> bool:
        return self._client._checked("REMOVE", "IND", "CLASS", [ind_name, class_name]).is_consistent


__all__ = ["ArmorManipulationClient"]
