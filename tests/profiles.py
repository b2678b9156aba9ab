"""How many examples the property-based suites (tests/test_incremental.py, tests/test_properties.py) try.

``make test`` runs half of them (``TOPOSTORE_PROPERTY_SCALE``, 0.5 by default) so that the suite stays
well under its time budget; ``make fuzz`` runs them in full (scale 1) with the fuzz suites.  Hypothesis
draws new examples on every run, so the shares of many CI runs still cover the full space over time.
"""

from __future__ import annotations

import os

#: share of each property test's full example count run by this session
PROPERTY_SCALE = float(os.environ.get("TOPOSTORE_PROPERTY_SCALE", "0.5"))


def property_examples(full: int) -> int:
    """Examples to try of a property test whose full run is ``full`` examples (at least 10)."""
    return max(10, round(full * PROPERTY_SCALE))
