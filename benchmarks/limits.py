"""The reasoning time limit, lifted for measurements that are meant to take long.

topostore stops a REASON after 120 s by default (``ReasonLimits.max_seconds``): a service must not
hang on one request.  A benchmark that measures how long the full REASON of 100,000 locations takes
needs the answer, not the refusal (the first ``make bench`` with 100,000-location rows stopped there
after 120 s and 6 rounds), so the topostore-only sizes and the full-REASON rows raise it; the
suite's own per-run timeouts still bound them.  The other limits (rounds, derived facts) stay.
"""

from __future__ import annotations

import dataclasses

from topostore.reason import limits

#: seconds one REASON may take in a benchmark run (the suite kills a size long before)
BENCH_MAX_SECONDS = 3600.0


def lift_time_limit(seconds: float = BENCH_MAX_SECONDS) -> limits.ReasonLimits:
    """Raise the time limit of every ontology created from now on in this process; the new defaults."""
    lifted = dataclasses.replace(limits.DEFAULTS, max_seconds=max(seconds, limits.DEFAULTS.max_seconds))
    limits.set_defaults(lifted)
    return lifted
