# Two commands do all set-up on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test bench bench-full demo clean fuzz load

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

# Fuzz every entry point with many more cases than `make test` (>= 100,000 in all); prints
# "fuzz: N cases tried, V violations found".
FUZZ_EXAMPLES ?= 11000
fuzz: $(STAMP)
	TOPOSTORE_FUZZ_RANDOM=1 TOPOSTORE_FUZZ_EXAMPLES=$(FUZZ_EXAMPLES) $(BIN)/python -m pytest -p no:cacheprovider -q tests/test_fuzz_armor.py \
		tests/test_fuzz_http.py tests/test_fuzz_files.py

# Load test on loopback: concurrent clients mixing manipulations, REASON and queries (benchmarks/load.py).
LOAD_ARGS ?= --clients 8 --seconds 60
load: $(STAMP)
	$(BIN)/python -m benchmarks.load $(LOAD_ARGS)

clean:
	rm -rf $(VENV) out .pytest_cache .hypothesis
