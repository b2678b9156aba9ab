"""The stored-form probe over a robot's life: ``python -m benchmarks.probe_drift [--probes N]``.

A REPLACE with a new clock value asks how Oxigraph stores the literal
(:func:`topostore.stores.literal_forms.stored_literal`, once per robot step).  This prints the time of a
probe of a fresh literal, per block of probes, from the first to the ``N``-th: a probe that slows down as
probes pile up shows in the later blocks.
"""

from __future__ import annotations

import argparse
import time

from pyoxigraph import Literal, NamedNode

from topostore.stores import literal_forms

LONG = NamedNode("http://www.w3.org/2001/XMLSchema#long")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--probes", type=int, default=100_000, help="probes in all")
    parser.add_argument("--sample", type=int, default=2_000, help="probes timed at the start of each block")
    parser.add_argument("--blocks", type=int, default=6, help="blocks the probes are cut into")
    args = parser.parse_args()
    size = args.probes // args.blocks
    for block in range(args.blocks):
        start = block * size
        began = time.perf_counter()
        for i in range(start, start + args.sample):
            literal_forms.stored_literal(Literal(str(i), datatype=LONG))
        took = (time.perf_counter() - began) / args.sample * 1e6
        for i in range(start + args.sample, start + size):
            literal_forms.stored_literal(Literal(str(i), datatype=LONG))
        print(f"after {start:>7,} probes: {took:5.1f} µs a probe")


if __name__ == "__main__":
    main()
