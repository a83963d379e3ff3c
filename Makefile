# Two commands do all the set-up on a fresh machine (Python >= 3.11 with venv):
#   make verify   creates .venv, installs shtaerman (the package alone), runs the main job
#   make test     creates .venv, installs shtaerman with its test and docs tools, runs ruff and pytest
#                 (with CI=true pytest runs twice: then with two BLAS threads and in reverse order)
VENV ?= .venv
PYTHON ?= python3
BIN := $(VENV)/bin

.PHONY: verify test bench lint docs clean

$(BIN)/shtaerman: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e .
	touch $@

# One stamp per set of extras, redone when pyproject.toml changes.
$(VENV)/.extras-test: $(BIN)/shtaerman
	$(BIN)/python -m pip install --quiet -e ".[test,docs]"
	touch $@

$(VENV)/.extras-bench: $(BIN)/shtaerman
	$(BIN)/python -m pip install --quiet -e ".[bench]"
	touch $@

verify: $(BIN)/shtaerman
	$(BIN)/shtaerman verify

# CI (CI=true) runs the suite a second time with two BLAS threads per process instead of one
# and the tests in the reverse order (tests/conftest.py): a result that holds only for one
# rounding of the BLAS, or a test that leans on another having run first, fails one pass.
# Two workers of two threads on two cores: measured up to 1.7x the first pass's wall time.
SECOND_PASS := OMP_NUM_THREADS=2 OPENBLAS_NUM_THREADS=2 MKL_NUM_THREADS=2 SHTAERMAN_TEST_ORDER=reversed
# Each pass ends with its 30 slowest test phases, so a CI log shows where the suite's time goes.
PYTEST := $(BIN)/python -m pytest --durations=30

test: $(VENV)/.extras-test
	$(BIN)/ruff check src tests benchmarks docs
	$(PYTEST)
ifeq ($(CI),true)
	$(SECOND_PASS) $(PYTEST)
endif

bench: $(VENV)/.extras-bench
	for script in benchmarks/bench_*.py; do $(BIN)/python $$script || exit 1; done

lint: $(VENV)/.extras-test
	$(BIN)/ruff check src tests benchmarks docs
	$(BIN)/ruff format --check src tests benchmarks docs

# The tutorials run while the site builds, so that their pages show each cell's output.
docs: $(VENV)/.extras-test
	SHTAERMAN_DOCS_EXECUTE=1 $(BIN)/mkdocs build --strict

clean:
	rm -rf $(VENV) .pytest_cache .ruff_cache .benchmarks site
