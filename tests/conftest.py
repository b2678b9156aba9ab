"""Shared fixtures: the SPARQL servers of the remote-store tests, started once per session; the fuzz
figures (cases tried, violations found) printed at the end of a run that fuzzed."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from servers import oxigraph_server, virtuoso_available, virtuoso_server  # noqa: E402


@pytest.fixture(scope="session")
def oxigraph_url() -> Iterator[str]:
    """A real ``oxigraph serve`` on a free loopback port."""
    with oxigraph_server() as url:
        yield url


@pytest.fixture(scope="session")
def virtuoso_url() -> Iterator[str]:
    """A real Virtuoso on free loopback ports; skipped loudly where Debian's package is not installed."""
    if not virtuoso_available():
        pytest.skip("VIRTUOSO NOT INSTALLED: the second SPARQL server is missing; "
                    "apt-get install virtuoso-opensource (make test does this as root on Debian)")
    with virtuoso_server() as url:
        yield url


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    try:
        from fuzz_support import CASES, CASES_BY_TEST
    except ImportError:  # pragma: no cover
        return
    if not CASES["tried"]:
        return
    failed = [r for r in terminalreporter.stats.get("failed", []) if "test_fuzz" in r.nodeid]
    for name, tried in sorted(CASES_BY_TEST.items()):
        broken = sum(1 for r in failed if r.nodeid.split("::")[-1].split("[")[0] == name)
        terminalreporter.write_line(f"fuzz: {name}: {tried} cases, {broken} violations")
    terminalreporter.write_line(f"fuzz: {CASES['tried']} cases tried, {len(failed)} violations found")
