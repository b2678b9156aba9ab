"""The durable phase of ``make load``: the same clients against ``topostore serve --store DIR``, killed with kill -9.

    python -m benchmarks.load --clients 8 --seconds 60 --durable-seconds 60 --kills 3

The server keeps its references in a RocksDB directory (``--store``).  While
the clients run, the server is killed with SIGKILL ``kills`` times, each after
a random stretch of up time under load, then restarted on the same port and
the same store (``seconds`` is the time the server is up, restarts excluded);
the clients keep going (requests that get no answer are not acknowledged, and
are counted as unanswered).  Right after each restart,
every ADD IND acknowledged before the kill is looked up; at the end, every ADD
IND acknowledged during the whole run.  Both counts must be "all of them".
"""

from __future__ import annotations

import random
import shutil
import signal
import tempfile
import threading
import time
from pathlib import Path

from .load import SHARED, Stats, load_references, missing_writes, phase_outcome, start_clients, start_server


def _snapshot(stats: Stats) -> dict[str, list[str]]:
    with stats.lock:
        return {ref: list(names) for ref, names in stats.acked.items()}


def _await_new_write(stats: Stats, seen: int, timeout: float = 60.0) -> None:
    """Wait (bounded) until a write was acknowledged since the last kill, so every kill has something to lose."""
    deadline = time.monotonic() + timeout
    while sum(len(n) for n in _snapshot(stats).values()) <= seen and time.monotonic() < deadline:
        time.sleep(0.01)


def kill_and_restart(proc, data: Path, store: Path, port: int, url: str, stats: Stats) -> tuple[object, dict]:
    """SIGKILL the server, restart it on the same store and port; what was acknowledged before, found after."""
    acked = _snapshot(stats)  # every write acknowledged before this instant must survive the kill
    proc.send_signal(signal.SIGKILL)
    proc.wait(30)
    killed = time.monotonic()
    proc, _ = start_server(data, "--store", str(store), port=port)
    restart = time.monotonic() - killed
    total = sum(len(n) for n in acked.values())
    lost = missing_writes(url, acked)
    return proc, {"acknowledged_before_kill": total, "found_after_restart": total - lost,
                  "restart_seconds": round(restart, 2)}


def run_durable(clients: int, seconds: float, kills: int, seed: int = 7) -> dict:
    """The durable phase; see the module docstring."""
    rng = random.Random(seed)
    work = Path(tempfile.mkdtemp(prefix="topostore-load-durable-"))
    data, store = work / "data", work / "store"
    data.mkdir()
    shutil.copy(SHARED / "topological_map_abox.owl", data / "map.owl")
    proc, url = start_server(data, "--store", str(store))
    port = int(url.rsplit(":", 1)[1])
    stats = Stats()
    events: list[dict] = []
    try:
        load_references(url, clients, stats)
        start, stop = time.monotonic(), threading.Event()
        threads = start_clients(url, clients, stats, stop)
        slice_ = seconds / (kills + 1)
        for _ in range(kills):
            time.sleep(slice_ * rng.uniform(0.5, 1.5))  # the server up and under load, then killed at a random instant
            _await_new_write(stats, sum(e["acknowledged_before_kill"] for e in events[-1:]))
            proc, event = kill_and_restart(proc, data, store, port, url, stats)
            events.append(event)
        time.sleep(max(0.0, seconds - (time.monotonic() - start - sum(e["restart_seconds"] for e in events))))
        stop.set()
        for t in threads:
            t.join()
        elapsed = time.monotonic() - start
        lost = missing_writes(url, stats.acked)
        alive = proc.poll() is None
    finally:
        proc.terminate()
        proc.wait(30)
        shutil.rmtree(work, ignore_errors=True)
    return {
        "clients": clients, "seconds": round(elapsed, 1),
        "seconds_up": round(elapsed - sum(e["restart_seconds"] for e in events), 1),
        "store": "directory (RocksDB)", **phase_outcome(stats, lost, alive),
        "unanswered_during_restarts": stats.unreachable, "kills": events,
    }


def print_report(report: dict) -> bool:
    """Print the durable phase's figures; True when nothing acknowledged was lost."""
    print(f"durable store, {report['clients']} clients, {report['seconds']} s ({report['seconds_up']} s up), "
          f"{len(report['kills'])} x kill -9: "
          f"{report['requests_served']} requests answered, {report['unanswered_during_restarts']} unanswered while "
          f"restarting, errors {report['errors']}, lost writes {report['lost_writes']} of "
          f"{report['acknowledged_writes']} acknowledged, mount violations {report['mount_violations']}")
    for i, kill in enumerate(report["kills"], 1):
        print(f"  kill -9 #{i}: {kill['found_after_restart']} of {kill['acknowledged_before_kill']} acknowledged "
              f"writes found after restart (restart {kill['restart_seconds']} s)")
    print(f"{'command':<28}{'n':>8}{'p50 ms':>10}{'p99 ms':>10}")
    for name, row in report["per_command_ms"].items():
        print(f"{name:<28}{row['n']:>8}{row['p50']:>10}{row['p99']:>10}")
    for sample in report["error_samples"]:
        print("error:", sample)
    kills_ok = all(k["found_after_restart"] == k["acknowledged_before_kill"] for k in report["kills"])
    return (kills_ok and report["lost_writes"] == 0 and report["errors"] == 0 and report["mount_violations"] == 0
            and report["server_alive"])


__all__ = ["run_durable", "print_report", "kill_and_restart"]
