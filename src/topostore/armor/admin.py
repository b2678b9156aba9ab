"""The aRMOR administration commands (spec §3.6): LOAD, MOUNT/UNMOUNT, SAVE, DROP, GET ALL REFS/REF CLIENT, LOG.

They act on the service and its references (creating, owning, saving,
dropping them) rather than on an ontology's content.
"""

from __future__ import annotations

from ..errors import InvalidNameError
from ..rdf import terms
from . import codes
from .codes import CommandError
from .context import Context, Handler, Reply
from .reference import REASONERS, Reference


def _mount(ref: Reference, client: str) -> Reply:
    """Mount ``client`` on ``ref`` unless another client holds it (203)."""
    if ref.owner is not None and ref.owner != client:
        raise CommandError(
            codes.CANNOT_MOUNT, f"reference {ref.name!r} is mounted by client {ref.owner!r}; it must UNMOUNT first"
        )
    already = ref.owner == client
    ref.owner = client
    ref.save_state()
    return Reply(warnings=[f"client {client!r} was already mounted on {ref.name!r}"] if already else [])


def mount(ctx: Context) -> Reply:
    return _mount(ctx.reference, ctx.request.client_name)


def unmount(ctx: Context) -> Reply:
    """UNMOUNT: only the mounted client can unmount; anyone else gets a warning (success, as in aRMOR)."""
    ref, client = ctx.reference, ctx.request.client_name
    if ref.owner == client:
        ref.owner = None
        ref.save_state()
        return Reply()
    holder = "nobody" if ref.owner is None else f"client {ref.owner!r}"
    return Reply(warnings=[f"client {client!r} is not mounted on {ref.name!r} ({holder} is); nothing changed"])


def load(source: str, mounted: bool) -> Handler:
    """LOAD FILE|WEB [MOUNTED] [location, iri, buffered manipulation, reasoner, buffered reasoner]."""

    def handler(ctx: Context) -> Reply:
        req = ctx.request
        try:
            base = terms.iri(ctx.args[1])
        except InvalidNameError as exc:
            raise CommandError(codes.INVALID_ARGUMENT, f"argument 2 (ontology IRI): {exc}") from None
        buffered_manipulation = ctx.flag(2, "buffered manipulation")
        reasoner = ctx.args[3].strip().upper()
        if reasoner not in REASONERS:
            raise CommandError(
                codes.INVALID_ARGUMENT,
                f"argument 4: unknown reasoner {ctx.args[3]!r}; use one of "
                + ", ".join(repr(r) for r in sorted(REASONERS)),
            )
        buffered_reasoner = ctx.flag(4, "buffered reasoner")
        ref, created = ctx.service.load_reference(
            req.reference_name,
            source,
            ctx.args[0],
            base.value,
            buffered_manipulation,
            reasoner or "PELLET",
            buffered_reasoner,
        )
        ctx.ref = ref
        if created:  # what the file's load repaired, set aside or does not reason completely: never silent
            with ref.lock:
                warnings = ref.ontology.notice_lines()
        else:
            warnings = [
                f"reference {ref.name!r} already exists and was reused as is; "
                "the LOAD arguments were ignored (DROP it first to reload)"
            ]
        if mounted:
            with ref.lock:
                warnings += _mount(ref, req.client_name).warnings
        return Reply(warnings=warnings)

    handler.__name__ = f"load_{source.lower()}{'_mounted' if mounted else ''}"
    return handler


def save(inferred: bool) -> Handler:
    """SAVE [path] / SAVE INFERENCE [path]: write the applied ontology; the reference is unchanged."""

    def handler(ctx: Context) -> Reply:
        ref = ctx.reference
        if ctx.args[0] == "":
            if ref.source is None:
                raise CommandError(
                    codes.INVALID_ARGUMENT,
                    "argument 1 (path) is empty and the reference has no source file to overwrite",
                )
            target = ref.source
        else:
            target = ctx.service.resolve_path(ctx.args[0])
        ctx.service.note_ontology_file(target)
        try:
            ref.ontology.save(target, inferred=inferred)
        except OSError as exc:
            raise CommandError(codes.FILE_ERROR, f"cannot write {target}: {exc.strerror or exc}") from None
        pending = len(ref.buffer)
        return Reply(warnings=[f"{pending} buffered manipulation(s) not applied yet were not saved"] if pending else [])

    handler.__name__ = "save_inference" if inferred else "save"
    return handler


def get_all_refs(ctx: Context) -> Reply:
    return Reply(queried_objects=sorted(ctx.service.reference_names()))


def get_ref_client(ctx: Context) -> Reply:
    """GET REF CLIENT [ref]: the mounted client of ``args[0]``, ``none`` when unmounted."""
    ref = ctx.service.reference(ctx.args[0])
    return Reply(queried_objects=["none" if ref.owner is None else ref.owner])


def drop(ctx: Context) -> Reply:
    dropped = ctx.service.drop_reference(ctx.request.reference_name)
    return Reply(
        warnings=[] if dropped else [f"reference {ctx.request.reference_name!r} was not loaded; nothing dropped"]
    )


def log_file_on(ctx: Context) -> Reply:
    """LOG FILE ON [path]: copy the service log to a file; ``none`` switches file logging off."""
    if ctx.args[0].strip().lower() == "none":
        ctx.service.log_to_file(None)
    else:
        ctx.service.log_to_file(ctx.service.resolve_path(ctx.args[0]))
    return Reply()


def log_file_off(ctx: Context) -> Reply:
    ctx.service.log_to_file(None)
    return Reply()


def log_screen(on: bool) -> Handler:
    def handler(ctx: Context) -> Reply:
        ctx.service.log_to_screen(on)
        return Reply()

    handler.__name__ = f"log_screen_{'on' if on else 'off'}"
    return handler


def invalid_command(ctx: Context) -> Reply:
    raise CommandError(codes.UNKNOWN_COMMAND, "INVALID COMMAND is registered only to be refused")
