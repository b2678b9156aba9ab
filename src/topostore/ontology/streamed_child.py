"""A big document parsed in a child process while the store takes what the child writes, on the second core.

Writing a document as it is parsed (:mod:`.streamed`) makes one Python object per term the store is to hold,
then the store indexes them: both on one core, the Python part (parse, skolem IRIs, literal checks) about
as long as the store's.  For a big document the parse and the Python pass run in a child interpreter that
writes N-Triples to a pipe, serialised by pyoxigraph as it pulls them, while the parent's ``bulk_load`` reads the
pipe into the asserted graph.  What the pass found (predicates, notices, the literal forms written, each
later spelling of a value with the first) comes back on a second pipe when the document is done.

The child runs this very pass: :class:`.streamed._Literals` validates each literal, puts an rdf:XMLLiteral in
canonical form and keeps the first spelling of a value; blank nodes become the skolem IRIs the ordinary load
gives them; RDF/XML declaring entities is refused before a byte is parsed (:func:`..rdf.syntax.parsed_quads`).
The document reaches the child as bytes on its standard input: it reads no path and fetches nothing.

Any failure (a syntax error, an invalid value, a child that died or could not start) is a :class:`LoadError`
raised once the child is gone; the caller takes the graph back to empty and loads the document the ordinary
way, whose answer (the same ``file:line: cause``) is the one given.  No child outlives the call.

Below :data:`CHILD_FROM` bytes the child's start (an interpreter and 0.16 s of imports) and its extra work (the
text written and read again: about 20 % more CPU in all) cost more than the second core gives back, and the
document is written in the parent; so it is where no core is free (:func:`core_free`).
The child is off unless asked for: on this 2-core machine, quiet, a 100,000-location map (100 MB of RDF/XML)
took 7.6-8.1 s of wall time through the child against 5.8-6.1 s in process (docs/benchmarks.md), so the second
core does not pay for the text written and read again.  ``TOPOSTORE_LOAD_CHILD=auto`` in the environment
takes it for a big document when a core is free, ``=1`` for every big document (:data:`ENABLED`,
:data:`FORCED`): for machines where it may pay, and to measure it.
"""

from __future__ import annotations

import gc
import io
import logging
import os
import pickle
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import IO, Any

import pyoxigraph as ox
from pyoxigraph import Literal, NamedNode, RdfFormat, Triple

from ..errors import LoadError
from ..rdf.syntax import PROGRESS_EVERY, parsed_quads
from ..rdf.terms import value_key
from ..rdf.vocab import ASSERTED
from ..stores.base import Store
from ..stores.cores import busy_cores, spare
from ..stores.cores import cpu_times as _cpu_times
from .streamed import StreamedDocument, _Literals, written_triples

log = logging.getLogger(__name__)

#: documents of this many bytes or more are parsed in a child process (measured: docs/benchmarks-history.md)
CHILD_FROM = 16_000_000
#: ``TOPOSTORE_LOAD_CHILD``: unset or ``0`` never a child, ``auto`` a child for a big document when a core is
#: free, ``1`` a child for every big document even on busy cores (to measure it)
_SETTING = os.environ.get("TOPOSTORE_LOAD_CHILD", "")
#: whether a child is used at all
ENABLED = _SETTING in ("1", "auto")
#: whether a big document goes to a child whatever the load of the machine
FORCED = _SETTING == "1"


def child_wanted(store: Store, data: bytes | str) -> bool:
    """Whether ``data`` goes through a child: big enough, a store that streams N-Triples in memory, and a
    core to spare (:func:`core_free`)."""
    return (ENABLED and bool(sys.executable) and len(data) >= CHILD_FROM
            and callable(getattr(store, "bulk_stream", None)) and store.bulk_stream_possible()
            and (FORCED or core_free()))


def core_free() -> bool:
    """Whether the machine has a core the child may take beside this process: the other processes busy
    less than the cores less one and a half (two cores: under half a core).  The child costs about 20 %
    more CPU in all (a second interpreter, the text written and read again); where the cores are busy it
    lengthens the load instead of shortening it (docs/benchmarks-history.md).

    Measured over :data:`_SAMPLE_S` of ``/proc/stat`` while this process sleeps, so that its own work (the
    document just read, a map just made) does not count, as it would in the load average; where there
    is no ``/proc/stat``, the one-minute load average less this process's one core."""
    busy = _others_busy()
    if busy is None:
        try:
            busy = os.getloadavg()[0] - 1
        except (OSError, AttributeError):  # pragma: no cover - no load average here: no core known to be free
            return False
    return spare(busy)


#: how long :func:`core_free` watches the machine's cores (seconds)
_SAMPLE_S = 0.05


def _others_busy() -> float | None:
    """How many cores the machine kept busy over :data:`_SAMPLE_S` (None: no ``/proc/stat`` to read)."""
    first = _cpu_times()
    if first is None:
        return None
    time.sleep(_SAMPLE_S)
    second = _cpu_times()
    if second is None:
        return None
    return busy_cores(first, second)


def stream_through_child(store: Store, data: bytes | str, fmt: RdfFormat, base_iri: str | None, source: str,
                         progress: Callable[[int], None] | None = None) -> StreamedDocument:
    """Write a document into the empty asserted graph of ``store`` as a child parses it; what it found.
    :class:`LoadError` on any failure, the graph then holding part of the document (the caller empties it)."""
    if isinstance(data, str):
        data = data.encode("utf-8", errors="surrogatepass")
    summary_read, summary_write = os.pipe()
    try:
        proc = subprocess.Popen(
            _command(fmt, base_iri, source, summary_write), stdin=subprocess.PIPE, stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL, pass_fds=(summary_write,))
    except OSError as exc:
        os.close(summary_read)
        os.close(summary_write)
        log.warning("LOAD %s: no child process to parse it (%s); parsed the ordinary way", source, exc)
        raise LoadError(f"{source}: no child process to parse it: {exc}") from exc
    os.close(summary_write)
    feeder = threading.Thread(target=_feed, args=(proc.stdin, data), name="topostore-load-feed", daemon=True)
    watchdog = _Watchdog(proc, child_deadline(len(data)), source)
    read_whole = False
    try:
        feeder.start()
        watchdog.start()
        gained = _bulk_loaded(store, proc.stdout, progress, source)
        with os.fdopen(summary_read, "rb") as summary:
            summary_read = -1
            raw = summary.read()
        read_whole = True
        result = _summary(raw, source)
    finally:
        watchdog.cancel()
        _end(proc, feeder, read_whole)
        if summary_read >= 0:
            os.close(summary_read)
    return _found(store, gained, result)


#: a child gets this long at least, and :data:`CHILD_SECONDS_PER_MB` more per megabyte of its document
#: (it parses 100 MB of RDF/XML in 3-4 s: the bound is for a child that hangs, not a slow one)
CHILD_MIN_SECONDS = 30.0
CHILD_SECONDS_PER_MB = 1.0


def child_deadline(size: int) -> float:
    """How long a child may take over a document of ``size`` bytes before it is killed (its document is
    then loaded the ordinary way)."""
    return CHILD_MIN_SECONDS + CHILD_SECONDS_PER_MB * size / 1_000_000


class _Watchdog:
    """Kills a child that has not finished by its deadline: the parent's read of the pipe then ends, the
    load is a LoadError, and the document is parsed the ordinary way (a stopped or hung child must not
    hold LOAD for ever)."""

    def __init__(self, proc: subprocess.Popen, seconds: float, source: str) -> None:
        self._timer = threading.Timer(seconds, self._kill, args=(proc, seconds, source))
        self._timer.daemon = True

    def start(self) -> None:
        self._timer.start()

    def cancel(self) -> None:
        self._timer.cancel()

    @staticmethod
    def _kill(proc: subprocess.Popen, seconds: float, source: str) -> None:
        if proc.poll() is None:
            log.warning("LOAD %s: the parsing child did not finish in %.0f s; killed, parsed the ordinary way",
                        source, seconds)
            proc.kill()


def _bulk_loaded(store: Store, pipe: IO[bytes], progress: Callable[[int], None] | None, source: str) -> int:
    """The child's N-Triples read into the asserted graph; the quads gained.  A truncated stream (a child
    that died mid-line) is a LoadError."""
    reader: Any = pipe if progress is None else _Counted(pipe, progress)
    try:
        before = store.quad_total()
        store.bulk_stream(reader, ASSERTED)
        return store.quad_total() - before
    except (SyntaxError, OSError, ValueError) as exc:  # the child's own text never breaks off: it died
        log.warning("LOAD %s: the parsing child's output broke off (%s); parsed the ordinary way", source, exc)
        raise LoadError(f"{source}: the parsing child's output broke off: {exc}") from exc


def _summary(raw: bytes, source: str) -> dict:
    """What the child reported: its findings, or the error that stopped it (raised here as a LoadError)."""
    if not raw:
        log.warning("LOAD %s: the parsing child ended without a report; parsed the ordinary way", source)
        raise LoadError(f"{source}: the parsing child ended without a report")
    result = pickle.loads(raw)  # written by this module in the child just started, never by anything else
    if "error" in result:
        raise LoadError(result["error"])
    return result


def _found(store: Store, gained: int, result: dict) -> StreamedDocument:
    """The child's findings as a :class:`StreamedDocument`, its literal forms recorded."""
    found = StreamedDocument(predicates={NamedNode(p) for p in result["predicates"]}, notices=result["notices"])
    spelled = [((t.subject, t.predicate, value_key(t.object)), t.object)
               for t in ox.parse(result["spelled"], format=RdfFormat.N_TRIPLES)]
    extra = store.forms.record_loaded(ASSERTED, spelled)
    if extra:  # pragma: no cover - bulk_stream is for in-memory stores, which persist no forms
        store._commit(extra, [])
    found.triples = gained  # one quad per fact: a value's first spelling
    firsts, laters = (ox.parse(result["again"][i], format=RdfFormat.N_TRIPLES) for i in (0, 1))
    found.again = [(first.triple, later.triple) for first, later in zip(firsts, laters, strict=True)]
    return found


def _feed(pipe: IO[bytes] | None, data: bytes) -> None:
    """The document into the child's standard input, in a thread (the write releases the GIL)."""
    assert pipe is not None
    try:
        pipe.write(data)
    except (BrokenPipeError, OSError):  # the child stopped reading: its report says why
        pass
    finally:
        try:
            pipe.close()
        except OSError:
            pass


def _end(proc: subprocess.Popen, feeder: threading.Thread, read_whole: bool) -> None:
    """No child left behind: one whose output was read whole is given a moment to exit, any other (the parent
    stopped early: an error, an interrupt) is killed at once; always waited for."""
    if proc.poll() is None:
        try:
            proc.wait(timeout=5 if read_whole else 0)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
    feeder.join()
    if proc.stdout is not None:
        proc.stdout.close()


#: The child's program: ``topostore``, ``topostore.ontology`` and ``topostore.compile`` made empty packages over
#: their folders, so that importing this module's few leaves does not run their ``__init__`` (which import
#: the whole service: 0.40 s where these leaves take 0.16 s, on the child's path before the first triple).
_LAUNCH = """
import sys, types
root = sys.argv.pop(1)
for name in ("topostore", "topostore.ontology", "topostore.compile"):
    package = types.ModuleType(name)
    package.__path__ = [root + "/" + name.replace(".", "/")[len("topostore/"):] if "." in name else root]
    sys.modules[name] = package
from topostore.ontology.streamed_child import child_main
sys.exit(child_main(sys.argv[1:]))
"""


def _command(fmt: RdfFormat, base_iri: str | None, source: str, report_fd: int) -> list[str]:
    """The child's command line: :data:`_LAUNCH` run by this interpreter, told where this package is."""
    root = str(Path(__file__).resolve().parents[1])
    return [sys.executable, "-c", _LAUNCH, root, fmt.media_type, base_iri or "", source, str(report_fd)]


class _Counted:
    """The child's pipe, telling ``progress`` every ``PROGRESS_EVERY`` lines (triples) read through it."""

    def __init__(self, pipe: IO[bytes], progress: Callable[[int], None]) -> None:
        self.pipe, self.progress, self.lines, self.told = pipe, progress, 0, 0

    def read(self, size: int = -1) -> bytes:
        block = self.pipe.read(size)
        self.lines += block.count(b"\n")
        if self.lines - self.told >= PROGRESS_EVERY:
            self.told = self.lines - self.lines % PROGRESS_EVERY
            self.progress(self.told)
        return block

    def readable(self) -> bool:
        return True


# ------------------------------------------------------------------------------------------------ the child
def _spelled_text(spelled: dict[tuple, Literal]) -> bytes:
    """The literal triples written, as N-Triples: pyoxigraph writes and reads them back far faster than
    pickle does its terms (100,000 literals: 0.05 s against 0.96 s to pickle)."""
    return _triples_text(Triple(s, p, lit) for (s, p, _), lit in spelled.items())


def _triples_text(triples: Iterable[Triple]) -> bytes:
    """``triples`` as N-Triples, in order (one line each)."""
    text = io.BytesIO()
    ox.serialize(triples, text, RdfFormat.N_TRIPLES)
    return text.getvalue()


def child_main(argv: list[str]) -> int:
    """The child: the document from standard input, N-Triples to standard output, then the report (a pickle)
    to the descriptor named last.  Exit status 0 with a report, whatever the document held."""
    media_type, base_iri, source, fd = argv
    gc.disable()  # no cycles are made here; a collection walking the literal sets is pure cost
    out = _own_stdout()
    found = StreamedDocument()
    literals = _Literals(found)
    report: dict
    try:
        fmt = RdfFormat.from_media_type(media_type)
        if fmt is None:
            raise LoadError(f"{source}: unknown RDF media type {media_type!r}")
        data = sys.stdin.buffer.read()
        ox.serialize(written_triples(parsed_quads(data, fmt, base_iri or None, source), literals), out,
                     RdfFormat.N_TRIPLES)
        out.flush()
        report = {"predicates": [p.value for p in found.predicates], "notices": found.notices,
                  "spelled": _spelled_text(literals.spelled),
                  "again": tuple(_triples_text(pair[i] for pair in found.again) for i in (0, 1))}
    except BaseException as exc:  # every failure is reported, never a traceback on a closed stream
        report = {"error": str(exc) if str(exc).startswith(source) else f"{source}: {exc}"}
    try:
        out.close()
    except OSError:
        pass
    with os.fdopen(int(fd), "wb") as summary:
        summary.write(pickle.dumps(report, protocol=pickle.HIGHEST_PROTOCOL))
    return 0


def _own_stdout() -> IO[bytes]:
    """Standard output as a file this child closes (end of stream for the parent while the report is still
    to come): ``sys.stdout`` never closes descriptor 1, so that goes to /dev/null."""
    out = os.fdopen(os.dup(1), "wb", buffering=1 << 20)
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    os.close(null)
    return out


if __name__ == "__main__":
    raise SystemExit(child_main(sys.argv[1:]))


__all__ = ["CHILD_FROM", "ENABLED", "FORCED", "child_wanted", "core_free", "stream_through_child"]
