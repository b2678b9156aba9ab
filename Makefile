# Two commands do all set-up on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test bench bench-quick demo clean java

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test]"
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/topostore demo

test: $(STAMP) java
	$(BIN)/python -m pytest

# The Pellet peers need a JDK (the benchmark compiles its warm Pellet peer with javac); as root
# on Debian, install it when only a runtime (or nothing) is there.
java:
	@command -v javac >/dev/null || [ "$$(id -u)" != 0 ] || ! command -v apt-get >/dev/null || \
		{ apt-get update -q && apt-get install -y -q openjdk-17-jdk-headless; }

# Benchmarks need the `bench` extra (Owlready2 0.49 for the Pellet jars) and a JDK for the warm
# Pellet peer.  `bench`: every size up to 100,000 locations; `bench-quick`: a few minutes, no 100,000.
# Results go to out/bench/.
bench: $(STAMP) java
	$(BIN)/pip install --quiet -e ".[bench]"
	$(BIN)/python -m benchmarks

bench-quick: $(STAMP) java
	$(BIN)/pip install --quiet -e ".[bench]"
	$(BIN)/python -m benchmarks --quick

clean:
	rm -rf $(VENV) out .pytest_cache .hypothesis
