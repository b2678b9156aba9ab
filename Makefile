# Two commands do all set-up on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test bench bench-full demo clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test]"
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/topostore demo

test: $(STAMP)
	$(BIN)/python -m pytest

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
