"""``client.utils``: armor_py_api's utility methods (spec §6.5), bugs of §7 item 25 fixed."""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING

from .armor_exceptions import ArmorServiceCallError

if TYPE_CHECKING:  # pragma: no cover
    from .armor_client import ArmorClient

logger = logging.getLogger("topostore.armor_api")


class ArmorUtilsClient:
    def __init__(self, client: ArmorClient) -> None:
        self._client = client

    def _run(self, command: str, first: str, second: str, args: list[str], done: str):
        res = self._client._checked(command, first, second, args)
        logger.info("%s (reference %s)", done, self._client.reference_name)
        return res

    def apply_buffered_changes(self) -> bool:
        return self._run("APPLY", "", "", [], "buffered changes applied").is_consistent

    def sync_buffered_reasoner(self) -> bool:
        return self._run("REASON", "", "", [], "reasoner synchronised").is_consistent

    def save(self, filepath: str, inference: bool = False) -> None:
        self._run("SAVE", "INFERENCE" if inference else "", "", [filepath], f"saved to {filepath}")

    def save_ref_with_inferences(self, filepath: str) -> None:
        self.save(filepath, True)

    def load_ref_from_file(self, owl_file_path: str, iri: str, buffered_manipulation: bool = False,
                           reasoner: str = "PELLET", buffered_reasoner: bool = False, mounted: bool = False) -> None:
        args = [owl_file_path, iri, str(buffered_manipulation), reasoner, str(buffered_reasoner)]
        self._run("LOAD", "FILE", "MOUNTED" if mounted else "", args, f"loaded {owl_file_path}")

    def mount_on_ref(self) -> None:
        self._run("MOUNT", "", "", [], f"client {self._client.client_id} mounted")

    def unmount_from_ref(self) -> None:
        self._run("UNMOUNT", "", "", [], f"client {self._client.client_id} unmounted")

    def set_log_to_terminal(self, switch: bool) -> None:
        self._run("LOG", "SCREEN", "ON" if switch else "OFF", [], f"terminal log {'on' if switch else 'off'}")

    def set_log_to_file(self, switch: bool, filepath: str = "") -> None:
        """``switch`` with a path starts file logging; without one it is an error; ``False`` stops it."""
        if switch and not filepath:
            raise ArmorServiceCallError("set_log_to_file(True) needs a file path")
        if switch:
            self._run("LOG", "FILE", "ON", [filepath], f"file log on ({filepath})")
        else:
            self._run("LOG", "FILE", "OFF", [], "file log off")


__all__ = ["ArmorUtilsClient"]
