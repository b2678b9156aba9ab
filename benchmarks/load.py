"""Load test on loopback: concurrent clients against a real ``topostore serve`` process.

    python -m benchmarks.load --clients 8 --seconds 60      (make load)

Each client loops over a mix of aRMOR commands over HTTP, on one reference
shared by every client and on a reference of its own: ADD IND (each a unique
individual, remembered once acknowledged), ADD/REPLACE DATAPROP, REASON,
QUERY IND / QUERY SPARQL, and SPARQL endpoint queries.  Two clients also
compete for the mount of a third reference: a client that mounted it checks
that GET REF CLIENT names it until it unmounts (mount exclusivity).

At the end every acknowledged individual is looked up: **lost writes** are
acknowledged ADD INDs the server does not know.  Printed: requests served,
p50/p99 latency per command, errors (non-200 answers, unexpected exit codes),
lost writes, mount violations; also written to out/load.json.  Then the
durable phase (benchmarks/load_durable.py): the same clients against a server
with ``--store DIR``, killed with kill -9 and restarted mid-run, counting the
acknowledged writes found after each restart.
"""

from __future__ import annotations

import argparse
import http.client
import json
import random
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.parse
import urllib.request
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared" / "ontology"
IRI = "http://bnc/exp-rob-lab/2022-23"
OK_FAILURES = {("QUERY", "IND")}  # success=false with exit 0 when the individual does not occur


@dataclass
class Stats:
    latencies: dict[str, list[float]] = field(default_factory=lambda: defaultdict(list))
    errors: list[str] = field(default_factory=list)
    acked: dict[str, list[str]] = field(default_factory=lambda: defaultdict(list))
    mount_violations: int = 0
    mounts: int = 0
    unreachable: int = 0  # requests that got no answer (only expected while a killed server restarts)
    lock: threading.Lock = field(default_factory=threading.Lock)


class Client:
    """One HTTP client (one connection per request, as a ROS bridge would open)."""

    def __init__(self, url: str, name: str, stats: Stats) -> None:
        self.url, self.name, self.stats = url, name, stats

    def post(self, path: str, body: bytes, ctype: str) -> tuple[int, bytes]:
        """(status, body); status 0 when the server could not be reached or dropped the connection."""
        req = urllib.request.Request(self.url + path, data=body, headers={"Content-Type": ctype}, method="POST")
        try:
            with urllib.request.urlopen(req, timeout=120) as res:
                return res.status, res.read()
        except urllib.error.HTTPError as exc:
            return exc.code, exc.read()
        except (OSError, http.client.HTTPException):  # refused, reset, or cut off by a kill -9
            with self.stats.lock:
                self.stats.unreachable += 1
            time.sleep(0.05)  # the server is down (restarting): do not spin
            return 0, b""

    def armor(self, ref: str, command: str, spec1: str = "", spec2: str = "", args: list[str] | None = None,
              label: str | None = None) -> dict:
        payload = {"client_name": self.name, "reference_name": ref, "command": command,
                   "primary_command_spec": spec1, "secondary_command_spec": spec2, "args": args or []}
        start = time.perf_counter()
        status, body = self.post("/armor", json.dumps(payload).encode(), "application/json")
        elapsed = time.perf_counter() - start
        if status == 0:
            return {}  # not answered, so not acknowledged
        key = label or " ".join(x for x in (command, spec1, spec2) if x)
        with self.stats.lock:
            self.stats.latencies[key].append(elapsed)
        if status != 200:
            self.error(f"{key}: HTTP {status} {body[:200]!r}")
            return {}
        answer = json.loads(body)
        if answer["exit_code"] != 0 and not (answer["exit_code"] in (102, 203) and ref == "mounted"):
            # 203/102: another client holds the mount, the refusal mount exclusivity requires
            self.error(f"{key} on {ref}: exit {answer['exit_code']} {answer['error_description'][:200]}")
        return answer

    def sparql(self, ref: str, query: str) -> None:
        start = time.perf_counter()
        status, body = self.post(f"/references/{ref}/sparql", query.encode(), "application/sparql-query")
        if status == 0:
            return
        with self.stats.lock:
            self.stats.latencies["SPARQL endpoint"].append(time.perf_counter() - start)
        if status != 200:
            self.error(f"SPARQL endpoint: HTTP {status} {body[:200]!r}")

    def error(self, text: str) -> None:
        with self.stats.lock:
            self.stats.errors.append(text)

    # ------------------------------------------------------------ workloads
    def step(self, ref: str, seq: int, rng: random.Random) -> None:
        """One mixed step on ``ref``."""
        roll = rng.random()
        if roll < 0.30:
            ind = f"w_{self.name}_{seq}"
            if self.armor(ref, "ADD", "IND", "", [ind]).get("success"):
                with self.stats.lock:
                    self.stats.acked[ref].append(ind)
        elif roll < 0.45:
            self.armor(ref, "REPLACE", "DATAPROP", "IND", ["visitedAt", "R1", "LONG", str(1665579800 + seq),
                                                            str(1665579740)])
        elif roll < 0.55:
            self.armor(ref, "REASON")
        elif roll < 0.75:
            self.armor(ref, "QUERY", "SPARQL", "", [f"SELECT ?x WHERE {{ ?x a <{IRI}#URGENT> }}", "5000"])
        elif roll < 0.90:
            self.armor(ref, "QUERY", "IND", "CLASS", ["URGENT"])
        else:
            self.sparql(ref, f"SELECT ?x ?y WHERE {{ ?x <{IRI}#canReach> ?y }}")

    def mount_step(self) -> None:
        """Try to take the mount of "mounted"; while held, nobody else may hold it."""
        answer = self.armor("mounted", "MOUNT")
        if not answer.get("success"):
            return  # 203: another client holds it (the expected refusal)
        with self.stats.lock:
            self.stats.mounts += 1
        for _ in range(3):
            answer = self.armor("mounted", "GET", "REF", "CLIENT", ["mounted"])
            if answer and answer.get("queried_objects") != [self.name]:  # {}: unanswered (a restart)
                with self.stats.lock:
                    self.stats.mount_violations += 1
            self.armor("mounted", "ADD", "IND", "", [f"m_{self.name}"])
        self.armor("mounted", "UNMOUNT")


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(data_dir: Path, *extra: str, port: int | None = None) -> tuple[subprocess.Popen, str]:
    """`topostore serve` on ``port`` (a free one by default) with ``extra`` options; returns once it answers."""
    port = port or free_port()
    proc = subprocess.Popen([sys.executable, "-m", "topostore.cli", "serve", "--port", str(port), "--data-dir",
                             str(data_dir), *extra], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        try:
            with urllib.request.urlopen(url + "/health", timeout=2):
                return proc, url
        except OSError:
            time.sleep(0.1)
    proc.kill()
    raise RuntimeError("the server did not start in 30 s")


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


REFS = ("shared", "mounted")


def load_references(url: str, clients: int, stats: Stats) -> None:
    setup = Client(url, "setup", stats)
    for ref in [*REFS, *(f"own{i}" for i in range(clients))]:
        setup.armor(ref, "LOAD", "FILE", "", ["map.owl", IRI, "false", "PELLET", "false"])
    stats.latencies.clear()


def start_clients(url: str, clients: int, stats: Stats, stop: float | threading.Event) -> list[threading.Thread]:
    """``clients`` threads running the mixed workload until ``stop`` (a monotonic time, or an event being set)."""
    def running() -> bool:
        return not stop.is_set() if isinstance(stop, threading.Event) else time.monotonic() < stop

    def work(i: int) -> None:
        client, rng, seq = Client(url, f"c{i}", stats), random.Random(i), 0
        while running():
            seq += 1
            if i < 2 and seq % 5 == 0:
                client.mount_step()
            else:
                client.step("shared" if seq % 2 else f"own{i}", seq, rng)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(clients)]
    for t in threads:
        t.start()
    return threads


def missing_writes(url: str, acked: dict[str, list[str]]) -> int:
    """How many acknowledged ADD IND individuals the server does not know."""
    lost = 0
    checker = Client(url, "checker", Stats())
    for ref, names in acked.items():
        query = "SELECT ?x WHERE { ?x a <http://www.w3.org/2002/07/owl#Thing> }"
        answer = checker.armor(ref, "QUERY", "SPARQL", "FORMATTED", [query, "60000"])
        if not answer:
            return sum(len(n) for n in acked.values())  # the server does not answer: nothing is found
        present = {item["value"].strip("<>").rsplit("#", 1)[-1] for item in answer.get("sparql_queried_objects", [])}
        lost += sum(1 for n in names if n not in present)
    return lost


def latency_table(stats: Stats) -> dict:
    return {k: {"n": len(v), "p50": round(statistics.median(v) * 1000, 1), "p99": round(percentile(v, 0.99) * 1000, 1)}
            for k, v in sorted(stats.latencies.items())}


def run(clients: int, seconds: float) -> dict:
    data = Path(tempfile.mkdtemp(prefix="topostore-load-"))
    shutil.copy(SHARED / "topological_map_abox.owl", data / "map.owl")
    proc, url = start_server(data)
    stats = Stats()
    try:
        load_references(url, clients, stats)
        start = time.monotonic()
        for t in start_clients(url, clients, stats, start + seconds):
            t.join()
        elapsed = time.monotonic() - start
        lost = missing_writes(url, stats.acked)
        alive = proc.poll() is None
    finally:
        proc.terminate()
        proc.wait(10)
        shutil.rmtree(data, ignore_errors=True)
    outcome = phase_outcome(stats, lost, alive)
    return {
        "clients": clients, "seconds": round(elapsed, 1), **outcome,
        "requests_per_second": round(outcome["requests_served"] / elapsed, 1),
        "errors": len(stats.errors) + stats.unreachable, "unanswered": stats.unreachable,
    }


def phase_outcome(stats: Stats, lost: int, alive: bool) -> dict:
    """The figures every load phase reports: requests, latencies, writes acknowledged and lost, mounts."""
    return {
        "requests_served": sum(len(v) for v in stats.latencies.values()),
        "per_command_ms": latency_table(stats), "errors": len(stats.errors), "error_samples": stats.errors[:5],
        "acknowledged_writes": sum(len(v) for v in stats.acked.values()), "lost_writes": lost,
        "mounts_taken": stats.mounts, "mount_violations": stats.mount_violations, "server_alive": alive,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--clients", type=int, default=8)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--durable-seconds", type=float, default=None,
                        help="length of the durable phase (--store DIR, kill -9); default --seconds, 0 skips it")
    parser.add_argument("--kills", type=int, default=3, help="kill -9 restarts during the durable phase")
    parser.add_argument("--output", default="out/load.json")
    args = parser.parse_args(argv)
    report = run(args.clients, args.seconds)
    ok = print_report(report)
    durable_seconds = args.seconds if args.durable_seconds is None else args.durable_seconds
    if durable_seconds > 0:
        from .load_durable import print_report as print_durable
        from .load_durable import run_durable

        report["durable"] = run_durable(args.clients, durable_seconds, args.kills)
        ok = print_durable(report["durable"]) and ok
    Path(args.output).parent.mkdir(parents=True, exist_ok=True)
    Path(args.output).write_text(json.dumps(report, indent=2))
    return 0 if ok else 1


def print_report(report: dict) -> bool:
    """Print the in-memory phase's figures; True when there were no errors, lost writes or mount violations."""
    print(f"{report['clients']} clients, {report['seconds']} s: {report['requests_served']} requests served "
          f"({report['requests_per_second']}/s), errors {report['errors']}, lost writes {report['lost_writes']} "
          f"of {report['acknowledged_writes']} acknowledged, mounts {report['mounts_taken']} "
          f"(violations {report['mount_violations']}), server alive: {report['server_alive']}")
    print(f"{'command':<28}{'n':>8}{'p50 ms':>10}{'p99 ms':>10}")
    for name, row in report["per_command_ms"].items():
        print(f"{name:<28}{row['n']:>8}{row['p50']:>10}{row['p99']:>10}")
    for sample in report["error_samples"]:
        print("error:", sample)
    return (report["errors"] == 0 and report["lost_writes"] == 0 and report["mount_violations"] == 0
            and report["server_alive"])


if __name__ == "__main__":
    sys.exit(main())
