"""Every request of a full REASON, timed at two sizes: ``python -m benchmarks.full_trace 10000 100000``.

:mod:`benchmarks.full_profile` sums the CPU per rule name; this module keeps each request apart, so that
the requests of two sizes can be set side by side in their order and the growth of each read off: the one
that grows more than the store's own floor (:mod:`benchmarks.full_floor`) is the one to look at.  What is
timed is a full REASON itself with ``profile=True`` (one evaluation per request): its schema tables, the
checks it starts beside the fixpoint and its closing reads, each request's CPU that of the thread that sent
it, so that a request of the second thread is not charged the first thread's work.
Each size runs in a process of its own, after LOAD and a first REASON; both sizes send the same
requests on the chain maps (:mod:`benchmarks.maps`), which the report matches by their text.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import time
import warnings
from typing import Any

from .limits import lift_time_limit

#: requests under this many seconds at the larger size are left out of the report
SHOWN = 0.02


def trace(size: str) -> dict[str, Any]:
    """The CPU seconds and text of every request of a full run's rules and checks at ``size`` locations."""
    from . import maps

    warnings.simplefilter("ignore")  # the map's notices are not what is measured
    lift_time_limit()
    onto, _ = maps.loaded(size)
    onto.reason()
    store = onto.store
    start = time.process_time()
    onto.reason(mode="full")
    whole = time.process_time() - start
    log: list[tuple[float, str]] = []
    update, query = store.update, store.query

    def timed_update(text: str, *args: Any, **kwargs: Any) -> None:
        began = time.thread_time()
        update(text, *args, **kwargs)
        log.append((time.thread_time() - began, text))

    def timed_query(text: str, *args: Any, **kwargs: Any) -> Any:
        began = time.thread_time()
        result = query(text, *args, **kwargs)
        try:
            result = list(result)
        except TypeError:  # an ASK answers a bool
            pass
        log.append((time.thread_time() - began, "QUERY " + text))
        return result

    store.update, store.query = timed_update, timed_query
    try:
        onto.reason(mode="full", profile=True)  # the path a REASON takes, one evaluation per request
    finally:
        del store.update, store.query  # the instance attributes go, the methods are back
    return {"size": size, "full_cpu_s": whole, "requests": log}


def short(text: str) -> str:
    """A request on one line, without its dataset clauses and with the map's and store's names shortened."""
    text = re.sub(r"\s+", " ", text)
    text = re.sub(r"USING [^W]*WHERE", "WHERE", text)
    for long, brief in (("http://bnc/exp-rob-lab/2022-23#", ":"), ("urn:topostore:graph:", "g:"),
                        ("http://www.w3.org/1999/02/22-rdf-syntax-ns#type", "a")):
        text = text.replace(long, brief)
    return text


def report(small: dict[str, Any], large: dict[str, Any], width: int = 150) -> str:
    """The requests of the two sizes side by side (those of at least :data:`SHOWN` s at the larger)."""
    a, b = small["requests"], large["requests"]
    out = [f"full REASON CPU: {small['full_cpu_s']:.3f} s at {small['size']}, {large['full_cpu_s']:.3f} s at "
           f"{large['size']} ({large['full_cpu_s'] / small['full_cpu_s']:.1f}x)"]
    if len(a) != len(b):
        out.append(f"the sizes sent {len(a)} and {len(b)} requests: their order is not comparable")
        return "\n".join(out)
    out.append(f"{'#':>3} {small['size']:>9} {large['size']:>9} {'growth':>7}  request (ms)")
    smaller = dict(zip(_keyed(a), (d for d, _ in a), strict=True))
    for n, (key, (db, text)) in enumerate(zip(_keyed(b), b, strict=True)):
        da = smaller.get(key)
        if db >= SHOWN:
            growth = f"{db / da:6.1f}x" if da else "      -"
            shown = "      -" if da is None else f"{da * 1e3:9.1f}"
            out.append(f"{n:>3} {shown:>9} {db * 1e3:9.1f} {growth}  {short(text)[:width]}")
    out.append(f"sum {sum(d for d, _ in a) * 1e3:9.1f} {sum(d for d, _ in b) * 1e3:9.1f}")
    return "\n".join(out)


def _keyed(requests: list[tuple[float, str]]) -> list[tuple[str, int]]:
    """Each request as its text and how many times that text came before: the second thread's requests
    interleave with the first's in an order of their own, so the sizes are matched by text, not position."""
    seen: dict[str, int] = {}
    out = []
    for _, text in requests:
        text = re.sub(r"urn:topostore:bnode:[0-9a-f]+", "_:", text)  # a blank node is named anew per load
        seen[text] = seen.get(text, 0) + 1
        out.append((text, seen[text]))
    return out


def _child(size: str) -> dict[str, Any]:
    out = subprocess.run([sys.executable, "-m", "benchmarks.full_trace", "--one", size],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("sizes", nargs="+", help="two numbers of locations (even); with --one, one")
    parser.add_argument("--one", action="store_true", help="trace the one size here and print JSON")
    args = parser.parse_args(argv)
    if args.one:
        print(json.dumps(trace(args.sizes[0])))
        return
    if len(args.sizes) != 2:
        parser.error("two sizes: the smaller first")
    print(report(_child(args.sizes[0]), _child(args.sizes[1])))


if __name__ == "__main__":
    main()
