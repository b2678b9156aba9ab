"""Shared fixtures: the SPARQL servers of the remote-store tests, started once per session; the example map
served for the browser tests; the markers
``external`` and ``slow`` (``pytest -m "not external and not slow"`` is the quick loop; ``make test`` runs
everything); the fuzz figures (cases tried, violations found) printed at the end of a run that fuzzed."""

from __future__ import annotations

import inspect
import json
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from http_support import Live, example_map_server  # noqa: E402
from servers import oxigraph_server, virtuoso_available, virtuoso_server  # noqa: E402


@pytest.fixture
def live_map(tmp_path: Path) -> Iterator[Live]:
    """A service on a real socket (uvicorn in a thread) with the example map loaded as reference ontoRef, for the
    live map page, its events and the inspector in a browser."""
    with example_map_server(tmp_path / "data") as server:
        yield server


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


#: modules whose tests start a program from outside the virtual environment: roscore, a browser, a JVM
EXTERNAL_MODULES = {"test_ros", "test_ros_events", "test_fuzz_ros", "test_live", "test_inspector_browser",
                    "test_pellet_differential", "test_fidelity_pellet", "test_bench"}
#: modules whose tests take seconds each: fuzzing, property suites, kill loops, wheel builds, the W3C cases
SLOW_MODULES = {"test_durable", "test_conformance", "test_fuzz_armor", "test_fuzz_http", "test_fuzz_files",
                "test_fuzz_tbox", "test_incremental", "test_properties", "test_packaging", "test_load_tool"}


#: property suites whose examples run the same reasoning code hundreds of times, code the other tests cover:
#: they run with coverage paused (pytest-cov's ``no_cover``), which costs them half their time under ``--cov``
#: (the C tracer on Python 3.11) and takes no line out of ``make test``'s figure
UNCOVERED_MODULES = {"test_incremental", "test_properties"}


#: modules whose tests share one ROS world (a module-scoped roscore and node): on two workers
#: (``--dist loadgroup``, pyproject.toml) each module stays on one worker, so its world is started once; the
#: scheduler hands out the largest groups first and every ungrouped test on its own
ROS_MODULES = {"test_ros", "test_ros_events", "test_fuzz_ros"}


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    """Run the step tests (those using ``staged_form``, as a module's ``pytestmark``) with the compiled step's
    staged runs generated and interpreted; and every test naming REPLACE twice: with REPLACE's short lane
    (armor/one_value.py) and with every REPLACE on the general path, so that each holds of both (not in a ROS
    world: its service runs in another process; not the lane's own tests, which compare the two themselves)."""
    if "staged_form" in metafunc.fixturenames:
        metafunc.parametrize("staged_form", ["generated", "interpreted"], indirect=True, scope="module")
    if (metafunc.module.__name__ in ROS_MODULES or metafunc.module.__name__ == "test_one_value"
            or "replace_lane" in metafunc.fixturenames):
        return
    try:
        source = inspect.getsource(metafunc.function)
    except (OSError, TypeError):  # pragma: no cover - a test made at run time
        return
    if "REPLACE" in source:
        metafunc.fixturenames.append("replace_lane")
        metafunc.parametrize("replace_lane", ["lane", "general"], indirect=True, scope="module")


@pytest.fixture(autouse=True)
def _replace_lane_set(request: pytest.FixtureRequest) -> None:
    """Set up ``replace_lane`` where :func:`pytest_generate_tests` parametrized it: a name appended to a test's
    fixture names while its tests are generated is parametrized but not set up by itself."""
    callspec = getattr(request.node, "callspec", None)
    if callspec is not None and "replace_lane" in callspec.params:
        request.getfixturevalue("replace_lane")


@contextmanager
def _switched(module: object, name: str, on: bool) -> Iterator[None]:
    """A module's switch set to ``on`` for the block, and back after it."""
    was = getattr(module, name)
    setattr(module, name, on)
    try:
        yield
    finally:
        setattr(module, name, was)


@pytest.fixture(scope="module")
def replace_lane(request: pytest.FixtureRequest) -> Iterator[str]:
    """REPLACE's short lane and the robot's command lanes (armor/lanes.py, queries too) on ("lane") or off
    ("general") for the tests of one module: each such test holds of the general path alone as well."""
    from topostore.armor import lanes, one_value

    on = request.param == "lane"
    with _switched(one_value, "ENABLED", on), _switched(lanes, "ENABLED", on):
        yield request.param


@pytest.fixture(scope="module")
def staged_form(request: pytest.FixtureRequest) -> Iterator[str]:
    """The compiled step's staged runs as generated functions ("generated") or interpreted ("interpreted")."""
    from topostore.reason import staged_code

    with _switched(staged_code, "GENERATED", request.param == "generated"):
        yield request.param


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Mark tests ``external`` (a Virtuoso server counts too, wherever it is used), ``slow`` and ``no_cover`` by
    module; keep the tests of one ROS world, and those of the Virtuoso server, on one worker each
    (``xdist_group``)."""
    for item in items:
        module = item.module.__name__ if getattr(item, "module", None) else ""
        virtuoso = "virtuoso_url" in getattr(item, "fixturenames", ()) or "virtuoso" in item.nodeid
        if module in EXTERNAL_MODULES or virtuoso:
            item.add_marker(pytest.mark.external)
        if module in SLOW_MODULES:
            item.add_marker(pytest.mark.slow)
        if module in UNCOVERED_MODULES:
            item.add_marker(pytest.mark.no_cover)
        if module in ROS_MODULES:
            item.add_marker(pytest.mark.xdist_group(module))
        elif virtuoso:
            item.add_marker(pytest.mark.xdist_group("virtuoso"))


def _group_of(nodeid: str) -> str | None:
    """The worker group of a test by its id: its ROS module's, or "virtuoso" (every Virtuoso test names it in a
    parameter)."""
    module = nodeid.split("::", 1)[0].rsplit("/", 1)[-1].removesuffix(".py")
    if module in ROS_MODULES:
        return module
    return "virtuoso" if "virtuoso" in nodeid else None


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: object) -> object | None:
    """``--dist loadgroup`` that groups by :func:`_group_of` on the controller: xdist 3.8 groups by appending the
    ``xdist_group`` name to each test's id on the workers, which pytest 9.2's ids no longer take (every test of a
    ROS module then ran on both workers, each starting its own roscore and node)."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadGroupScheduling

    class ByGroup(LoadGroupScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return _group_of(nodeid) or super()._split_scope(nodeid)

    return ByGroup(config, log)


def pytest_sessionfinish(session: pytest.Session) -> None:
    """On an xdist worker, hand the fuzz counts of its tests to the controller (which prints them)."""
    output = getattr(session.config, "workeroutput", None)
    if output is None:
        return
    try:
        from fuzz_support import CASES_BY_TEST
    except ImportError:  # pragma: no cover
        return
    output["fuzz_cases"] = json.dumps(dict(CASES_BY_TEST))


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error) -> None:  # noqa: ANN001 - xdist's worker node
    """Add a worker's fuzz counts to the controller's."""
    counts = json.loads(getattr(node, "workeroutput", {}).get("fuzz_cases", "{}"))
    if counts:
        from fuzz_support import CASES, CASES_BY_TEST

        CASES_BY_TEST.update(counts)
        CASES["tried"] += sum(counts.values())


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
