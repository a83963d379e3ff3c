# Two commands do all the set-up on a fresh machine (Python >= 3.11 with venv):
#   make verify   creates .venv, installs shtaerman, runs the main job
#   make test     creates .venv, installs shtaerman with its test tools, runs ruff and pytest
VENV ?= .venv
PYTHON ?= python3
BIN := $(VENV)/bin

.PHONY: verify test bench lint clean

$(BIN)/shtaerman: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test,bench]"
	touch $@

verify: $(BIN)/shtaerman
	$(BIN)/shtaerman verify

test: $(BIN)/shtaerman
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/python -m pytest

bench: $(BIN)/shtaerman
	for script in benchmarks/bench_*.py; do $(BIN)/python $$script || exit 1; done

lint: $(BIN)/shtaerman
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks

clean:
	rm -rf $(VENV) .pytest_cache .ruff_cache .benchmarks
