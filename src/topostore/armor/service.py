"""``ArmorService``: the aRMOR command interface as an in-process object.

>>> from topostore.armor import ArmorService
>>> service = ArmorService()
>>> service.call({"reference_name": "ref", "command": "GET", "primary_command_spec": "ALL",
...               "secondary_command_spec": "REFS"}).queried_objects
[]

``call`` never raises and always answers: every failure becomes a
``success=false`` reply with a documented exit code (:mod:`topostore.armor.codes`).
Transports (ROS bridge, HTTP) only translate messages to and from this object.
"""

from __future__ import annotations

import logging
import os
import sys
import threading
import urllib.parse
import urllib.request
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from ..compile.notices import answered, unsaid
from ..errors import LoadError, RuleCompileError, TopostoreError
from ..ontology.facade import Ontology
from ..ontology.pellet_values import PelletDifferenceWarning
from ..rdf.safeio import open_log
from ..stores import StoreSpec
from ..stores import kind as store_kind
from ..stores.base import guess_format
from . import codes, lanes
from .codes import CommandError
from .commands import COMMANDS, Context, Reply
from .durable import DurableReferences
from .lanes import LANES
from .reference import Reference
from .reference import consistent as _consistent
from .render import Renderer
from .types import ArmorRequest, ArmorResponse, ArmorResponseList

logger = logging.getLogger("topostore.armor")

_WEB_TIMEOUT_SECONDS = 20.0
_WEB_MAX_BYTES = 64 * 1024 * 1024
DEFAULT_MAX_QUERY_SECONDS = 30.0
_ONTOLOGY_SUFFIXES = {".owl", ".rdf", ".xml", ".ttl", ".turtle", ".nt", ".ntriples", ".n3", ".jsonld", ".nq", ".trig"}



class ArmorService:
    """Named references and the aRMOR command table.

    ``data_dir``: when set, every LOAD/SAVE/LOG path is resolved inside it and
    paths escaping it are refused (210).  ``short_names``: answer with local
    names and bare lexical forms instead of ``<IRI>`` and ``"lex"^^xsd:T``.
    ``allow_web``: permit LOAD WEB (off by default: it makes the service fetch
    arbitrary URLs).  ``store``: where references live (None: memory; a directory:
    one RocksDB store per reference; an http(s) URL: a SPARQL 1.1 server), see
    :mod:`topostore.stores`; a durable store's references are reopened here
    (:mod:`topostore.armor.durable`).  ``sync``: flush each commit to disk (directory stores), send each
    commit before the reply instead of with the next request (remote stores).
    ``strict``: LOAD refuses a file with axioms not reasoned completely (209, naming them) instead of
    loading it and naming them in ``error_description``.
    """

    def __init__(self, data_dir: str | os.PathLike[str] | None = None, short_names: bool = False,
                 allow_web: bool = False, store: StoreSpec = None, sync: bool = False,
                 store_query_url: str | None = None, store_update_url: str | None = None,
                 strict: bool = False) -> None:
        #: LOAD refuses (exit code 209) files with axioms not reasoned completely (the reply names them)
        self.strict = strict
        self.data_dir = Path(data_dir).resolve() if data_dir is not None else None
        self.short_names = short_names
        self.allow_web = allow_web
        self.renderer = Renderer(short_names)
        self._references: dict[str, Reference] = {}
        self._registry_lock = threading.RLock()
        #: longest a QUERY SPARQL may run, also when the client asks for no limit (seconds)
        self.max_query_seconds = DEFAULT_MAX_QUERY_SECONDS
        self._file_handler: logging.StreamHandler | None = None
        self._ontology_files: set[Path] = set()
        self._screen_handler: logging.Handler | None = None
        self.durable = None if store_kind(store) == "memory" else DurableReferences(
            store, sync, store_query_url, store_update_url)
        if self.durable is not None:
            self._references.update(self.durable.restore(self))

    def close(self) -> None:
        """Release durable stores and writer locks (a clean shutdown; a kill loses nothing acknowledged)."""
        if self.durable is not None:
            with self._registry_lock:
                self.durable.close(dict(self._references))

    # ------------------------------------------------------------ entry points
    def call(self, request: ArmorRequest | Mapping[str, Any]) -> ArmorResponse:
        """Execute one request and return its response; never raises."""
        try:  # a request object (every in-process client's) is taken as it is
            req = request if type(request) is ArmorRequest else ArmorRequest.from_dict(request)
        except (TypeError, ValueError) as exc:
            return ArmorResponse(False, codes.INVALID_ARGUMENT, f"malformed request: {exc}")
        try:
            lane = LANES.get((req.command, req.primary_command_spec, req.secondary_command_spec))
            response = None
            if lane is not None and lanes.ENABLED:  # the short path of a robot's command shape (:mod:`.lanes`):
                try:  # None where it is not the plain case (nothing done: the command table runs it)
                    response = lane(self, req)
                except CommandError as exc:
                    response = self._failure(req, exc.code, exc.message)
            if response is None:  # the command table's general path
                with answered(PelletDifferenceWarning) as heard:  # a warning is no fault: it is answered, whatever the warnings filter
                    response = self._dispatch(req)
                if heard and response.success:
                    _answer(req, response, heard)
        # The protocol's one boundary: ArmorService.call never raises (a ROS service or an HTTP route
        # waits on its reply), so anything unexpected, i.e. a bug, becomes a logged 209 reply.
        except Exception as exc:
            logger.exception("internal error while executing %s", _describe(req))
            response = ArmorResponse(False, codes.REASONER_OR_QUERY_FAILURE, f"internal error: {type(exc).__name__}: {exc}")
            response.is_consistent = self._consistency(req.reference_name)
        level = logging.DEBUG if response.success else logging.INFO
        if logger.isEnabledFor(level):  # the line is built only for a log that keeps it
            logger.log(level, "%s -> %s %s %s", _describe(req), response.exit_code, response.error_description,
                       response.queried_objects)
        return response

    def call_many(self, requests: Iterable[ArmorRequest | Mapping[str, Any]]) -> ArmorResponseList:
        """The serialized service as intended: run in order, one response each.

        ``success`` is true only if every command succeeded; ``is_consistent``
        is the consistency after the last command.
        """
        responses = [self.call(r) for r in requests]
        return ArmorResponseList(
            success=all(r.success for r in responses),
            is_consistent=responses[-1].is_consistent if responses else False,
            armor_responses=responses,
        )

    # ------------------------------------------------------------ dispatch
    def reply_consistency(self, req: ArmorRequest, ref: Reference) -> bool:
        """``is_consistent`` of a reply to ``req`` whose handler holds ``ref``'s lock (read without locking it
        again, while the name still stands for it)."""
        return _consistent(ref) if self._references.get(req.reference_name) is ref else \
            self._consistency(req.reference_name)

    def _dispatch(self, req: ArmorRequest) -> ArmorResponse:
        if req.reference_name == "":
            return ArmorResponse(False, codes.EMPTY_REFERENCE, "reference_name is empty; every command needs one")
        if req.command == "":
            return self._failure(req, codes.EMPTY_COMMAND, "command is empty")
        key = (req.command, req.primary_command_spec, req.secondary_command_spec)
        command = COMMANDS.get(key)  # a client spelling the table's upper case (every robot) finds it at once
        if command is None:
            key = (key[0].upper(), key[1].upper(), key[2].upper())
            command = COMMANDS.get(key)
        if command is None:
            return self._failure(req, codes.UNKNOWN_COMMAND, f"unknown command {' '.join(repr(k) for k in key)}: "
                                 "check the spelling and that unused specs are empty strings")
        try:
            # aRMOR ignores the arguments of argument-less commands; rosservice YAML and tutorials send args: ['']
            count = 0 if command.max_args == 0 and not any(req.args) else len(req.args)
            if count < command.min_args or (command.max_args is not None and count > command.max_args):
                command.check_arity(count)  # says what it expected
            ctx = Context(self, req)
            if not command.needs_ref:
                reply = command.handler(ctx)
                return self._reply(req, reply)
            # one dictionary read (atomic): the registry's lock guards its changes; a name not loaded is 207
            ref = ctx.ref = self._references.get(req.reference_name) or self.reference(req.reference_name)
            with ref.lock:
                if command.manipulation and self.durable is not None and not self.durable.held(req.reference_name):
                    raise CommandError(codes.MOUNTED_BY_OTHER, f"reference {req.reference_name!r}: this service lost "
                                       "its writer lock to another topostore process; it may be queried, not changed")
                if command.manipulation and ctx.ref.owner is not None and ctx.ref.owner != req.client_name:
                    raise CommandError(codes.MOUNTED_BY_OTHER, f"reference {req.reference_name!r} is mounted by client "
                                       f"{ctx.ref.owner!r}; client {req.client_name!r} may query it but not change it")
                reply = command.handler(ctx)
                return self._reply(req, reply, ctx.ref)
        except CommandError as exc:
            return self._failure(req, exc.code, exc.message)

    def _reply(self, req: ArmorRequest, reply: Reply, ref: Reference | None = None) -> ArmorResponse:
        """The response to ``req``; ``ref``: its reference, when the caller holds its lock (its consistency
        is read without locking it again, while the name still stands for it)."""
        consistent = self.reply_consistency(req, ref) if ref is not None else self._consistency(req.reference_name)
        warnings = reply.warnings
        # the fields in their order (ArmorResponse's): success, exit_code, error_description, is_consistent,
        # timeout, queried_objects, sparql_queried_objects
        return ArmorResponse(reply.success, reply.exit_code, "; ".join(warnings) if warnings else "", consistent,
                             reply.timeout, reply.queried_objects, reply.sparql_queried_objects)

    def _failure(self, req: ArmorRequest, code: int, message: str) -> ArmorResponse:
        return ArmorResponse(False, code, message, is_consistent=self._consistency(req.reference_name))

    def _consistency(self, name: str) -> bool:
        """``is_consistent`` of spec §2.6: the reference's state at its last reasoning; false if unknown."""
        ref = self._references.get(name)
        if ref is None:
            return False
        with ref.lock:
            return _consistent(ref)

    # ------------------------------------------------------------ registry
    def reference(self, name: str) -> Reference:
        """The loaded reference ``name``, or 207."""
        with self._registry_lock:
            ref = self._references.get(name)
        if ref is None:
            raise CommandError(codes.UNKNOWN_REFERENCE, f"reference {name!r} is not loaded; LOAD it first")
        return ref

    def reference_names(self) -> list[str]:
        with self._registry_lock:
            return list(self._references)

    def drop_reference(self, name: str) -> bool:
        with self._registry_lock:
            ref = self._references.pop(name, None)
        if ref is not None and self.durable is not None:
            with ref.lock:
                self.durable.discard(name, ref.ontology.store)
        return ref is not None

    def load_reference(self, name: str, source: str, location: str, iri: str, buffered_manipulation: bool,
                       reasoner: str, buffered_reasoner: bool) -> tuple[Reference, bool]:
        """(reference, created): load a new reference, or return the existing one untouched."""
        with self._registry_lock:
            existing = self._references.get(name)
        if existing is not None:
            return existing, False
        reopened = self.durable.reopen(self, name) if self.durable is not None else None
        if reopened is not None:
            with self._registry_lock:
                existing = self._references.setdefault(name, reopened)
            return existing, False
        store = self.durable.new_store(name) if self.durable is not None else None
        try:
            onto, path = self._load_ontology(store, source, location, iri)
            ref = Reference(name, onto, iri, path, buffered_manipulation, reasoner, buffered_reasoner)
            if self.durable is not None:
                ref.persist = self.durable.persist
                ref.save_state()  # the reference exists (durably) from here on
        except BaseException:
            if store is not None:  # nothing of a failed LOAD stays in a durable store
                self.durable.discard(name, store)
            raise
        with self._registry_lock:
            existing = self._references.setdefault(name, ref)
        return existing, existing is ref

    def _load_ontology(self, store, source: str, location: str, iri: str) -> tuple[Ontology, Path | None]:
        """A reasoned ontology from a file or URL, on ``store`` (None: memory); aRMOR errors on failure."""
        path: Path | None = None
        try:
            onto = Ontology(prefix=iri + "#", store=store, strict=self.strict)
            if source == "FILE":
                path = self.resolve_path(location)
                self.note_ontology_file(path)
                onto.load(path)
            else:
                data, fmt = self._fetch(location)
                onto.load_data(data, fmt)
            onto.reason()
        except LoadError as exc:
            raise CommandError(codes.FILE_ERROR, f"cannot load {location!r}: {exc}") from None
        except RuleCompileError as exc:
            raise CommandError(codes.REASONER_OR_QUERY_FAILURE, f"cannot reason on {location!r}: {exc}") from None
        except TopostoreError as exc:
            raise CommandError(codes.INVALID_ARGUMENT, f"cannot load {location!r}: {exc}") from None
        return onto, path

    def add_reference(self, ref: Reference) -> tuple[Reference, bool]:
        """(reference, created): register a reference built elsewhere (an HTTP upload) unless the name is taken."""
        with self._registry_lock:
            existing = self._references.setdefault(ref.name, ref)
        return existing, existing is ref

    # ------------------------------------------------------------ files, web, logging
    def resolve_path(self, text: str) -> Path:
        """A file path for LOAD/SAVE/LOG; confined to ``data_dir`` when one is set (210 otherwise)."""
        if text == "" or "\x00" in text:
            raise CommandError(codes.INVALID_ARGUMENT, "the path is empty or contains a NUL character")
        if self.data_dir is None:
            return Path(text)
        candidate = Path(text)
        if not candidate.is_absolute():
            candidate = self.data_dir / candidate
        resolved = candidate.resolve()  # follows symlinks, so a link pointing out is caught
        if resolved != self.data_dir and self.data_dir not in resolved.parents:
            raise CommandError(codes.FILE_ERROR, f"path {text!r} is outside the data directory {str(self.data_dir)!r}")
        return resolved

    def _fetch(self, url: str) -> tuple[bytes, Any]:
        """Download an ontology for LOAD WEB (http/https only, size- and time-limited)."""
        if not self.allow_web:
            raise CommandError(codes.FILE_ERROR, "LOAD WEB is disabled on this service (start it with allow_web=True); "
                               "download the file and use LOAD FILE instead")
        scheme = urllib.parse.urlparse(url).scheme.lower()
        if scheme not in ("http", "https"):
            raise CommandError(codes.INVALID_ARGUMENT, f"argument 1: {url!r} is not an http(s) URL")
        try:
            with urllib.request.urlopen(url, timeout=_WEB_TIMEOUT_SECONDS) as answer:  # noqa: S310 - scheme checked
                data = answer.read(_WEB_MAX_BYTES + 1)
        except OSError as exc:
            raise CommandError(codes.FILE_ERROR, f"cannot download {url!r}: {exc}") from None
        if len(data) > _WEB_MAX_BYTES:
            raise CommandError(codes.FILE_ERROR, f"{url!r} is larger than {_WEB_MAX_BYTES} bytes")
        return data, guess_format(urllib.parse.urlparse(url).path)

    def note_ontology_file(self, path: Path) -> None:
        """Remember a file LOAD read or SAVE wrote, so LOG FILE never appends to it."""
        self._ontology_files.add(Path(path).resolve())

    def log_to_file(self, path: Path | None) -> None:
        """LOG FILE ON/OFF: send this service's log to ``path`` (None stops).

        The new file is opened first; if that fails the current log stays as it was.
        """
        handler: logging.StreamHandler | None = None
        if path is not None:
            if Path(path).resolve() in self._ontology_files or Path(path).suffix.lower() in _ONTOLOGY_SUFFIXES:
                raise CommandError(codes.FILE_ERROR, f"{str(path)!r} is an ontology file; choose a log file name "
                                   "that is not a loaded or saved ontology (e.g. armor.log)")
            try:
                stream = open_log(path)
            except OSError as exc:
                raise CommandError(codes.FILE_ERROR, f"cannot open log file {str(path)!r}: {exc.strerror or exc}") from None
            handler = logging.StreamHandler(stream)
            handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
        if self._file_handler is not None:
            logger.removeHandler(self._file_handler)
            self._file_handler.close()
            self._file_handler.stream.close()  # StreamHandler.close leaves the stream open
        self._file_handler = handler
        if handler is not None:
            logger.addHandler(handler)
        self._update_level()

    def log_to_screen(self, on: bool) -> None:
        """LOG SCREEN ON/OFF: send this service's log to standard error."""
        if self._screen_handler is not None:
            logger.removeHandler(self._screen_handler)
            self._screen_handler = None
        if on:
            self._screen_handler = logging.StreamHandler(sys.stderr)
            self._screen_handler.setFormatter(logging.Formatter("[armor] %(levelname)s: %(message)s"))
            logger.addHandler(self._screen_handler)
        self._update_level()

    def _update_level(self) -> None:
        """Debug detail only while a log destination is switched on."""
        on = self._file_handler is not None or self._screen_handler is not None
        logger.setLevel(logging.DEBUG if on else logging.NOTSET)


def _answer(req: ArmorRequest, response: ArmorResponse, heard: list[str]) -> None:
    """Put what a command's REASON warned of (:class:`~topostore.PelletDifferenceWarning`) in its reply's
    ``error_description`` where it does not hold it already (a load's notices are there by design), and log it."""
    said = response.error_description
    for text in unsaid(heard, [said]):
        logger.warning("%s: %s", _describe(req), text)
        said = f"{said}; {text}" if said else text
    response.error_description = said


def _describe(req: ArmorRequest) -> str:
    return f"[{req.client_name}@{req.reference_name}] {req.command} {req.primary_command_spec} {req.secondary_command_spec} {req.args}"


__all__ = ["ArmorService"]
