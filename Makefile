# Set-up and everyday commands. Both main targets create .venv on a fresh machine.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
PIP := $(BIN)/python -m pip

.PHONY: demo test bench lint clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(PIP) install --quiet --upgrade pip

# The demo needs the package and its rendering extra.
$(VENV)/.demo-installed: pyproject.toml | $(BIN)/python
	$(PIP) install --quiet -e ".[render]"
	touch $@

# Tests need everything, the RL client libraries of examples/ included. torch==2.13.0 goes
# first so that stable-baselines3 and torchrl take the CPU build that is on disk instead of
# downloading a CUDA build of several GB.
$(VENV)/.dev-installed: pyproject.toml | $(BIN)/python
	$(PIP) install --quiet torch==2.13.0
	$(PIP) install --quiet -e ".[dev,render,train,pixels,clients]"
	touch $@ $(VENV)/.demo-installed

demo: $(VENV)/.demo-installed
	$(BIN)/soccer-env demo --out demo_output

test: $(VENV)/.dev-installed
	$(BIN)/python -m pytest -n auto

bench: $(VENV)/.demo-installed
	$(BIN)/soccer-env bench

lint: $(VENV)/.dev-installed
	$(BIN)/ruff check soccer_env estimators agents soccer_lab tests benchmarks examples

clean:
	rm -rf $(VENV) demo_output bench_output .pytest_cache
