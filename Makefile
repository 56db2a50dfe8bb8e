# Set-up and everyday commands. Both main targets create .venv on a fresh machine.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
PIP := $(BIN)/python -m pip

.PHONY: demo test bench lint docs clean

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

# Libraries that pin versions the main environment cannot hold run their tests (the files
# named test_*NAME*.py; the main suite skips them) in an environment of their own, .venv-NAME
# with the NAME extra, torch==2.13.0 first as for the main one:
# - RLlib (rllib) pins an older gymnasium; its tests run one at a time: each starts Ray,
#   which is slow to start and uses both cores;
# - BenchMARL (benchmarl) pins an older TorchRL than the clients extra;
# - Tianshou (tianshou) requires virtualenv < 21, which caps filelock below the one the other
#   extras take.
OWN_ENVS := rllib benchmarl tianshou

# (Precious: make would delete the interpreter of a pattern's intermediate target.)
.PRECIOUS: .venv-%/bin/python
.venv-%/bin/python:
	$(PYTHON) -m venv .venv-$*
	.venv-$*/bin/python -m pip install --quiet --upgrade pip

.venv-%/.installed: pyproject.toml | .venv-%/bin/python
	.venv-$*/bin/python -m pip install --quiet torch==2.13.0
	.venv-$*/bin/python -m pip install --quiet -e ".[$*,dev]"
	touch $@

own_tests = $(shell find tests -name 'test_*$(1)*.py' | sort)

.PHONY: $(addprefix test-,$(OWN_ENVS))
test-rllib: .venv-rllib/.installed
	.venv-rllib/bin/python -m pytest $(call own_tests,rllib)

test-benchmarl: .venv-benchmarl/.installed
	.venv-benchmarl/bin/python -m pytest -n auto --dist worksteal $(call own_tests,benchmarl)

test-tianshou: .venv-tianshou/.installed
	.venv-tianshou/bin/python -m pytest $(call own_tests,tianshou)

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
	rm -rf $(VENV) $(addprefix .venv-,$(OWN_ENVS)) demo_output bench_output .pytest_cache site
