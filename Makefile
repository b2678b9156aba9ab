# Two commands do all set-up on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test bench bench-full demo clean browser vendor-js

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test]"
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/topostore demo

test: $(STAMP) browser
	$(BIN)/python -m pytest

# The live-map page is tested in Debian's chromium (driven by Playwright, a test extra); as
# root on Debian install it (without it that one test is skipped and says what to install).
browser:
	-@if ! command -v chromium >/dev/null 2>&1 && [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium; fi

# Cytoscape.js for the live map page, fetched from the npm registry into src/topostore/static/.
vendor-js:
	sh scripts/vendor-cytoscape.sh

# Benchmarks need the `bench` extra (matplotlib for the plot; Owlready2 for the
# optional Pellet peer, which also needs `java`).  Results go to out/bench/.
bench: $(STAMP)
	-$(BIN)/pip install --quiet -e ".[bench]"
	$(BIN)/python -m benchmarks --quick

bench-full: $(STAMP)
	-$(BIN)/pip install --quiet -e ".[bench]"
	$(BIN)/python -m benchmarks

clean:
	rm -rf $(VENV) out .pytest_cache .hypothesis
