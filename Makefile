# Two commands do all set-up on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test bench bench-quick bench-drift bench-stores demo clean browser vendor-js ros-deps virtuoso java fuzz load conformance

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test]"
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/topostore demo

# Coverage of src/topostore: the code run in the test process and its threads (subprocesses such as
# `topostore serve` or the ROS node are not counted); 93.13% when the floor was last raised.  The floor only
# goes up: when tests raise the figure, set COV_FLOOR to the new value rounded down; never lower it.
COV_FLOOR := 93

# One pytest session on two workers (pytest-xdist, `-n 2 --dist loadgroup` in pyproject.toml), the tests that
# start roscore, Virtuoso, a browser or a JVM (`external`) among the others: the scheduler keeps each ROS
# module's tests (one roscore and node) and the Virtuoso tests on one worker and hands out every other test one
# at a time, the groups first (tests/conftest.py), so that a worker waiting on a server's start-up shares the
# machine with one running the in-process tests and neither waits idle for the other at the end.
test: $(STAMP) browser ros-deps virtuoso java
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/python -m pytest --durations=10 --cov=topostore \
	  --cov-report=term-missing:skip-covered --cov-fail-under=$(COV_FLOOR)

# The live-map page is tested in Debian's chromium (driven by Playwright, a test extra); as
# root on Debian install it (without it that one test is skipped and says what to install).
browser:
	-@if ! command -v chromium >/dev/null 2>&1 && [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium; fi

# Cytoscape.js for the live map page and YASGUI for the inspector's SPARQL console, fetched from
# the npm registry into src/topostore/http/static/.
vendor-js:
	sh scripts/vendor-cytoscape.sh
	sh scripts/vendor-yasgui.sh

# ROS 1 for `topostore ros` and tests/test_ros*.py, from Debian's packages: installed
# when running as root on Debian (CI), skipped elsewhere (the ROS tests then say what
# to install).  The venv sees Debian's /usr/lib/python3/dist-packages through a .pth
# file appended after its own packages (docs/ros.md, "Set-up", says why).
ROS_DEBS := python3-rospy python3-rosservice python3-genpy python3-genmsg ros-core
ros-deps: $(STAMP)
	@missing=$$(for p in $(ROS_DEBS); do dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || echo $$p; done); \
	if [ -n "$$missing" ] && [ "$$(id -u)" = 0 ] && [ -f /etc/debian_version ] && command -v apt-get >/dev/null; then \
	  echo "installing ROS 1 from Debian:" $$missing; \
	  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing >/dev/null) \
	    || echo "warning: could not install $$missing; the ROS tests will be skipped"; \
	fi
	@$(BIN)/python -c 'import sys, sysconfig, pathlib; d = pathlib.Path("/usr/lib/python3/dist-packages"); \
	  same = pathlib.Path("/usr/lib/python%d.%d" % sys.version_info[:2]).is_dir(); \
	  pth = pathlib.Path(sysconfig.get_paths()["purelib"], "debian-ros.pth"); \
	  (d / "rospy").is_dir() and same and pth.write_text(str(d) + "\n")'

# Virtuoso, the second SPARQL 1.1 server of the remote-store tests (Debian's package, installed
# when running as root on Debian; the tests say loudly when it is missing).
virtuoso:
	@command -v virtuoso-t >/dev/null || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && \
	  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq virtuoso-opensource >/dev/null) \
	  || echo "virtuoso-opensource not installed: the Virtuoso remote-store tests will be skipped"; }


# The Pellet peers need a JDK (the benchmark compiles its warm Pellet peer with javac); as root
# on Debian, install it when only a runtime (or nothing) is there.
java:
	@command -v javac >/dev/null || [ "$$(id -u)" != 0 ] || ! command -v apt-get >/dev/null || \
		{ apt-get update -q && apt-get install -y -q openjdk-17-jdk-headless; }

# The W3C OWL 2 test cases (../shared/conformance/owl2-wg/all.rdf, read where they are) against
# topostore and owlrl, a child process per case and engine (60 s each); the table goes to
# docs/conformance.md.  The RL cases also run in `make test` (tests/test_conformance.py).
conformance: $(STAMP)
	$(BIN)/python -m benchmarks.conformance --write docs/conformance.md

# Benchmarks need the `bench` extra (Owlready2 0.49 for the Pellet jars, reasonable for the full-REASON
# peer) and a JDK for the warm Pellet peer.  `bench`: the step table up to 100,000 locations, the
# 4,000-step drift walks, the remote store and the full-REASON rows (about an hour); `bench-quick`:
# the same without 500 and 100,000 locations and without the drift walks (under 10 minutes);
# `bench-drift`: the drift walks alone.  Results go to out/bench/.
bench: $(STAMP) java
	$(BIN)/pip install --quiet -e ".[bench]"
	$(BIN)/python -m benchmarks

# Step latency and full REASON per store (memory, disk, disk --sync, oxigraph serve; Virtuoso if installed).
bench-stores: $(STAMP)
	$(BIN)/python -m benchmarks.stores --sizes seed,100 --steps 20 --virtuoso

bench-quick: $(STAMP) java
	$(BIN)/pip install --quiet -e ".[bench]"
	$(BIN)/python -m benchmarks --quick

bench-drift: $(STAMP)
	$(BIN)/python -m benchmarks --parts drift

# Fuzz every entry point with many more cases than `make test` (>= 100,000 in all); prints
# "fuzz: N cases tried, V violations found".  The property-based suites run their full example
# counts here (`make test` runs half of them, tests/profiles.py).
FUZZ_EXAMPLES ?= 12500
fuzz: $(STAMP) ros-deps
	TOPOSTORE_FUZZ_RANDOM=1 TOPOSTORE_FUZZ_EXAMPLES=$(FUZZ_EXAMPLES) $(BIN)/python -m pytest -p no:cacheprovider -q tests/test_fuzz_armor.py \
		tests/test_fuzz_http.py tests/test_fuzz_files.py tests/test_fuzz_ros.py tests/test_fuzz_tbox.py
	TOPOSTORE_PROPERTY_SCALE=1 $(BIN)/python -m pytest -p no:cacheprovider -q tests/test_incremental.py tests/test_properties.py

# Load test on loopback: concurrent clients mixing manipulations, REASON and queries (benchmarks/load.py),
# then the same against a durable store (--store DIR) killed with kill -9 and restarted 3 times mid-run.
LOAD_ARGS ?= --clients 8 --seconds 60 --durable-seconds 60 --kills 3
load: $(STAMP)
	$(BIN)/python -m benchmarks.load $(LOAD_ARGS)

clean:
	rm -rf $(VENV) out .pytest_cache .hypothesis .coverage
