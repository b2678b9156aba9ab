"""Child process of tests/test_fuzz_tbox.py: LOADs and REASONs the TBoxes it is sent, one per line.

Reads JSON lines ``{"ttl": text, "max_seconds": s}`` on stdin; for each, writes the Turtle to a
file in a fresh data directory, sends the aRMOR commands LOAD FILE (reasoner not buffered) and REASON to
a new service under those reasoning limits, and answers one JSON line with the exit codes and
error descriptions.  The parent watches it: a case after which this process is gone killed it, a
case with no answer in time hung it.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

from topostore.armor import ArmorService
from topostore.reason.limits import ReasonLimits, set_defaults

IRI = "http://example.org/fuzz"


def run_case(ttl: str, max_seconds: float) -> dict:
    set_defaults(ReasonLimits(max_seconds=max_seconds))
    with tempfile.TemporaryDirectory() as tmp:
        data = Path(tmp)
        (data / "t.ttl").write_text(ttl)
        service = ArmorService(data_dir=data)
        replies = []
        for command, spec, args in (("LOAD", "FILE", ["t.ttl", IRI, "false", "PELLET", "false"]),
                                    ("REASON", "", [])):
            res = service.call({"reference_name": "r", "command": command, "primary_command_spec": spec,
                                "args": args})
            replies.append({"code": res.exit_code, "error": res.error_description})
    return {"load": replies[0], "reason": replies[1]}


def main() -> None:
    for line in sys.stdin:
        case = json.loads(line)
        print(json.dumps(run_case(case["ttl"], case["max_seconds"])), flush=True)


if __name__ == "__main__":
    main()
