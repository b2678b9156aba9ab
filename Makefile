# Two commands do all set-up on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test bench bench-full bench-stores demo clean virtuoso

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test]"
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/topostore demo

test: $(STAMP) virtuoso
	$(BIN)/python -m pytest

# Virtuoso, the second SPARQL 1.1 server of the remote-store tests (Debian's package, installed
# when running as root on Debian; the tests say loudly when it is missing).
virtuoso:
	@command -v virtuoso-t >/dev/null || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && \
	  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq virtuoso-opensource >/dev/null) \
	  || echo "virtuoso-opensource not installed: the Virtuoso remote-store tests will be skipped"; }

# Benchmarks need the `bench` extra (matplotlib for the plot; Owlready2 for the
# optional Pellet peer, which also needs `java`).  Results go to out/bench/.
bench: $(STAMP)
	-$(BIN)/pip install --quiet -e ".[bench]"
	$(BIN)/python -m benchmarks --quick

bench-full: $(STAMP)
	-$(BIN)/pip install --quiet -e ".[bench]"
	$(BIN)/python -m benchmarks

# Step latency and full REASON per store (memory, disk, disk --sync, oxigraph serve; Virtuoso if installed).
bench-stores: $(STAMP)
	$(BIN)/python -m benchmarks.stores --sizes seed,100 --steps 20 --virtuoso

clean:
	rm -rf $(VENV) out .pytest_cache .hypothesis
