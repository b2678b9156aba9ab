"""The warm Pellet peer: compile ``pellet/PelletStep.java`` and drive it one robot step at a time.

The jars are the ones Owlready2 0.49 bundles (Pellet 2.3.1, OWL API 3.4.3), found through the
installed package; the classes are compiled at bench time into a folder the caller gives (nothing
compiled is kept in the source tree).  The JVM runs as a child process reading moves on stdin and
answering one JSON line per step; it times each step itself, so the pipe is not in the figures.

A fresh JVM is not the JVM aRMOR has been running for hours: until the JIT has compiled Pellet's
hot paths its steps on the example map are 2-5x slower.  The peer is therefore warmed first, on a
scratch copy of the map walked for ``warm_seconds`` (see PelletStep.java), and the heap is fixed
(``-Xms`` = ``-Xmx``) so that G1 does not grow it in the middle of the timed steps.
"""

from __future__ import annotations

import importlib.util
import json
import os
import queue
import re
import shutil
import signal
import subprocess
import threading
from pathlib import Path
from typing import IO, Any

from .walk import Move

SOURCE = Path(__file__).with_name("pellet") / "PelletStep.java"
#: Pellet 2.3.1 on the 500-location chain holds a few GiB; a fixed heap (pages are touched only when
#: used) keeps G1 from resizing it between steps, which made steps at 200 locations 1.5-2x slower
JVM_OPTIONS = ["-Xms6g", "-Xmx6g"]
#: moves walked on the scratch copy at most (the seconds run out first: 600 steps of the example map
#: under load left its last steps at 6 ms where a longer walk reaches 1.5 ms)
WARM_STEPS = 2000


class PeerError(RuntimeError):
    """The peer could not answer (crash, timeout, bad output)."""


def pellet_jars() -> Path:
    """Owlready2's ``pellet/`` folder of jars (where the installed package keeps them)."""
    spec = importlib.util.find_spec("owlready2")
    if spec is None or not spec.submodule_search_locations:
        raise PeerError("owlready2 is not installed (pip install -e '.[bench]')")
    folder = Path(next(iter(spec.submodule_search_locations))) / "pellet"
    if not any(folder.glob("pellet-*.jar")):
        raise PeerError(f"no Pellet jar in {folder}")
    return folder


def unavailable() -> str:
    """Why the peer cannot run here ('' when it can)."""
    for tool in ("java", "javac"):
        if shutil.which(tool) is None:
            return f"{tool} not found (install a JDK, e.g. Debian's openjdk-17-jdk-headless)"
    try:
        pellet_jars()
    except PeerError as exc:
        return str(exc)
    return ""


def java_version() -> str:
    """The JVM's version line, e.g. 'openjdk version "17.0.15" 2025-04-15'."""
    if shutil.which("java") is None:
        return "not found"
    done = subprocess.run(["java", "-version"], capture_output=True, text=True, timeout=60)
    return (done.stderr.strip().splitlines() or ["unknown"])[0]


def compile_peer(classes: Path) -> Path:
    """``javac`` PelletStep.java against Owlready2's jars into ``classes``; returns ``classes``."""
    why = unavailable()
    if why:
        raise PeerError(why)
    classes.mkdir(parents=True, exist_ok=True)
    cmd = ["javac", "-nowarn", "-d", str(classes), "-cp", str(pellet_jars() / "*"), str(SOURCE)]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        raise PeerError(f"javac failed:\n{done.stderr[-2000:]}")
    return classes


class WarmPellet:
    """One JVM holding one ontology and one buffering Pellet reasoner; ``with`` stops it."""

    def __init__(self, classes: Path, map_file: Path, namespace: str, log: Path, ready_timeout: float,
                 warmup: list[Move] | None = None, warm_seconds: float = 0.0) -> None:
        """Start the JVM; with ``warmup`` moves it first walks a scratch copy of the map for up to
        ``warm_seconds`` (``ready_timeout`` is for the load and first REASON after that)."""
        cmd = ["java", *JVM_OPTIONS, "-cp", f"{pellet_jars() / '*'}{os.pathsep}{classes}", "PelletStep",
               str(map_file), namespace]
        if warmup:
            moves = log.with_suffix(".warmup")
            moves.write_text("".join(step_line(m) for m in warmup))
            cmd += ["--warmup", str(moves), "--warm-seconds", str(warm_seconds)]
            ready_timeout += warm_seconds
        self._log = log.open("w")
        self._proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=self._log,
                                      text=True, start_new_session=True)
        self._lines: queue.Queue[str | None] = queue.Queue()
        threading.Thread(target=_pump, args=(self._proc.stdout, self._lines), daemon=True).start()
        self.log = log
        try:
            self.ready = self._answer(ready_timeout, "loading the map and the first REASON")
        except PeerError:
            self.close()
            raise

    def step(self, move: Move, timeout: float) -> dict[str, Any]:
        """Send one move; the peer's answer {step, ms, flush_ms, queries_ms, canReach, urgent}."""
        assert self._proc.stdin is not None
        self._proc.stdin.write(step_line(move))
        self._proc.stdin.flush()
        return self._answer(timeout, f"a step to {move.to}")

    def _answer(self, timeout: float, doing: str) -> dict[str, Any]:
        try:
            line = self._lines.get(timeout=timeout)
        except queue.Empty:
            raise PeerError(f"timeout: no answer within {timeout:.0f} s ({doing})") from None
        if line is None:
            raise PeerError(f"Pellet stopped ({doing}): {self.tail()}")
        try:
            return json.loads(line)
        except ValueError:
            raise PeerError(f"unexpected output from Pellet: {line[:200]!r}") from None

    def tail(self) -> str:
        """The end of the JVM's standard error (why it stopped)."""
        self._log.flush()
        text = self.log.read_text(errors="replace").strip()
        return re.sub(r"\s+", " ", text[-600:]) or "no error output"

    def close(self) -> None:
        """End the JVM: EOF first, then kill its process group if it does not go."""
        if self._proc.poll() is None:
            try:
                assert self._proc.stdin is not None
                self._proc.stdin.close()
                self._proc.wait(timeout=10)
            except (OSError, subprocess.TimeoutExpired):
                os.killpg(self._proc.pid, signal.SIGKILL)
                self._proc.wait()
        self._log.close()

    def __enter__(self) -> WarmPellet:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def step_line(move: Move) -> str:
    """The peer's STEP line for a move (``-``: the place had no visit time, REPLACE is an ADD)."""
    old_visit = "-" if move.old_visit is None else str(move.old_visit)
    return f"STEP {move.to} {move.frm} {move.now} {move.old_now} {old_visit}\n"


def _pump(stream: IO[str] | None, lines: queue.Queue[str | None]) -> None:
    """Move the JVM's JSON lines into a queue, so that a slow answer can time out; None at EOF."""
    assert stream is not None
    for line in stream:
        if line.startswith("{"):
            lines.put(line)
    lines.put(None)
