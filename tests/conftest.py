"""Prints the fuzz figures (cases tried, violations found) at the end of a run that fuzzed."""

from __future__ import annotations

import pytest


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    try:
        from fuzz_support import CASES
    except ImportError:  # pragma: no cover
        return
    if not CASES["tried"]:
        return
    failed = [r for r in terminalreporter.stats.get("failed", []) if "test_fuzz" in r.nodeid]
    terminalreporter.write_line(f"fuzz: {CASES['tried']} cases tried, {len(failed)} violations found")
