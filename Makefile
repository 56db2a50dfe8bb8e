# Set-up and everyday commands. Both main targets create .venv on a fresh machine.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
PIP := $(BIN)/python -m pip

.PHONY: demo test test-rllib bench lint docs clean

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
# The SSL protocol classes (the ssl extra) are a distribution of their own in third_party/.
$(VENV)/.dev-installed: pyproject.toml third_party/ssl_protocol/pyproject.toml | $(BIN)/python
	$(PIP) install --quiet torch==2.13.0
	$(PIP) install --quiet ./third_party/ssl_protocol
	$(PIP) install --quiet -e ".[dev,render,train,pixels,clients,ssl]"
	touch $@ $(VENV)/.demo-installed

demo: $(VENV)/.demo-installed
	$(BIN)/soccer-env demo --out demo_output

# --dist worksteal: a worker that runs out of tests takes queued ones from the other, instead of
# idling while the other works through a queue of long tests (training, examples, workers).
test: $(VENV)/.dev-installed
	$(BIN)/python -m pytest -n auto --dist worksteal

# RLlib (the rllib extra) pins an older gymnasium than the other extras take, so its tests
# (the files named test_*rllib*.py; the main suite skips them) run in an environment of their
# own, one test at a time: each starts Ray, which is slow to start and uses both cores.
RLLIB_VENV := .venv-rllib
RLLIB_BIN := $(RLLIB_VENV)/bin
RLLIB_TESTS = $(shell find tests -name 'test_*rllib*.py' | sort)

$(RLLIB_BIN)/python:
	$(PYTHON) -m venv $(RLLIB_VENV)
	$(RLLIB_BIN)/python -m pip install --quiet --upgrade pip

$(RLLIB_VENV)/.installed: pyproject.toml | $(RLLIB_BIN)/python
	$(RLLIB_BIN)/python -m pip install --quiet torch==2.13.0
	$(RLLIB_BIN)/python -m pip install --quiet -e ".[rllib,dev]"
	touch $@

test-rllib: $(RLLIB_VENV)/.installed
	$(RLLIB_BIN)/python -m pytest $(RLLIB_TESTS)

# The documentation site (mkdocs.yml, docs/): --strict fails on any warning (a broken link, a
# page missing from the navigation, a reference or docstring that mkdocstrings cannot read).
$(VENV)/.docs-installed: pyproject.toml | $(BIN)/python
	$(PIP) install --quiet -e ".[docs]"
	touch $@

docs: $(VENV)/.docs-installed
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict --site-dir site

bench: $(VENV)/.demo-installed
	$(BIN)/soccer-env bench

lint: $(VENV)/.dev-installed
	$(BIN)/ruff check soccer_env estimators agents soccer_lab tests benchmarks examples

clean:
	rm -rf $(VENV) $(RLLIB_VENV) demo_output bench_output .pytest_cache site
