# A thin front for the standard commands; CI calls these same targets.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed-stamp
BUILD ?= build

.PHONY: run test test-slow test-all lint notebooks bench lab clean peers pooltool docs browser

# pytest-xdist over every core; a file's tests stay on one worker (a notebook's cells
# share one kernel, in order)
PARALLEL := -n auto --dist loadfile

# the package's bytecode is compiled at install, as a wheel's install does (an editable
# one does not): a command's first start does not compile it, nor every start where
# Python may not write it
$(STAMP): pyproject.toml constraints.txt
	@echo "Setting up $(VENV) with the pinned packages (once; about a minute where pip's cache is warm)"
	@$(PYTHON) -m venv $(VENV)
	@$(PY) -m pip install --quiet --upgrade pip
	@$(PY) -m pip install --quiet -c constraints.txt -e '.[dev]'
	@$(PY) -m compileall -q src
	@touch $(STAMP)

run: $(STAMP)  ## derive and verify the paper's results; write LaTeX, PDF and figures to build/
	@echo "Deriving and verifying the paper's results into $(BUILD)/ (under a minute)"
	@$(PY) derivations/run_all.py --out $(BUILD)

test: $(STAMP)  ## unit tests, doctests and notebooks (nbval), over every core
	@echo "Running the tests, doctests and notebooks on every core (about five minutes)"
	@$(PY) -m pytest $(PARALLEL)

test-slow: $(STAMP)  ## the slow tier alone: wide grids, whole benches, 1,000-disc clusters
	$(PY) -m pytest $(PARALLEL) -m slow

test-all: test test-slow  ## both tiers, as CI runs them

lint: $(STAMP)  ## ruff, the import layers (import-linter), and mypy over the package
	$(PY) -m ruff check src tests derivations notebooks docs tools
	$(VENV)/bin/lint-imports --no-cache
	$(PY) -m mypy

notebooks: $(STAMP)  ## re-execute the notebooks in place; read the diff before committing
	$(PY) notebooks/refresh.py notebooks/*.ipynb

# pooltool 0.6.0 pins a development build of panda3d that no registry serves: it is
# installed without its pins, then its requirements with a released panda3d
$(VENV)/.pooltool-stamp: $(STAMP)
	$(PY) -m pip install --quiet --no-deps pooltool-billiards==0.6.0 2>$(VENV)/pip-pooltool.log \
		|| { cat $(VENV)/pip-pooltool.log >&2; exit 1; }
	$(PY) -m pip install --quiet -c constraints.txt panda3d==1.10.16 panda3d-gltf==1.3.0 \
		panda3d-simplepbr==0.13.1 numpy-quaternion==2024.0.13 cattrs h5py msgpack \
		msgpack-numpy rich 'h11>=0.16' pyyaml 2>>$(VENV)/pip-pooltool.log \
		|| { cat $(VENV)/pip-pooltool.log >&2; exit 1; }
	$(PY) tools/pip_check.py
	touch $@

pooltool: $(VENV)/.pooltool-stamp  ## pooltool, so make test runs the billiards comparison

$(VENV)/.peers-stamp: $(VENV)/.pooltool-stamp
	$(PY) -m pip install --quiet -c constraints.txt -e '.[dev,peers]' 2>$(VENV)/pip-peers.log \
		|| { cat $(VENV)/pip-peers.log >&2; exit 1; }
	$(PY) tools/pip_check.py
	touch $@

peers: $(VENV)/.peers-stamp  ## the peers (pymunk, pooltool, Pinocchio): make test then runs their comparisons

bench: $(VENV)/.peers-stamp  ## accuracy against time (with pymunk as a peer), the maps beside Pinocchio; the Performance page; slow checks
	$(PY) -m rigidimpact bench --out $(BUILD)/bench
	$(PY) derivations/beside_pinocchio.py --kernel 100000 --json > $(BUILD)/bench/pinocchio.json
	$(PY) tools/performance_page.py $(BUILD)/bench "rigidimpact bench" \
		$(BUILD)/bench/pinocchio.json "python derivations/beside_pinocchio.py --kernel 100000"
	$(PY) -m pytest $(PARALLEL) -m slow

$(VENV)/.lab-stamp: $(STAMP)
	$(PY) -m pip install --quiet -c constraints.txt -e '.[dev,lab]' 2>$(VENV)/pip-lab.log \
		|| { cat $(VENV)/pip-lab.log >&2; exit 1; }
	$(PY) tools/pip_check.py
	touch $@

$(VENV)/.docs-stamp: $(STAMP)
	$(PY) -m pip install --quiet -c constraints.txt -e '.[dev,docs]' 2>$(VENV)/pip-docs.log \
		|| { cat $(VENV)/pip-docs.log >&2; exit 1; }
	$(PY) tools/pip_check.py
	touch $@

docs: $(VENV)/.docs-stamp  ## the documentation site in build/docs (warnings are errors; reads offline)
	$(PY) -m sphinx -W --keep-going -q -b html docs $(BUILD)/docs
	@echo "the site: $(BUILD)/docs/index.html"
	$(PY) docs/browse.py $(BUILD)/docs

# Debian's chromium, for the site's browser test (docs/browse.py, tests/test_site.py)
SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

browser:  ## install Debian's chromium, so make docs reads the site in a real browser
	$(SUDO) apt-get update -qq
	DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends chromium

# root (a container) must say so to Jupyter; anyone else needs no flag
LAB_FLAGS ?= $(if $(filter 0,$(shell id -u)),--allow-root)

lab: $(VENV)/.lab-stamp  ## open the notebooks in JupyterLab (installed on first use)
	$(PY) -m jupyter lab $(LAB_FLAGS) notebooks/

clean:  ## remove build outputs (the site and its generated gallery too)
	rm -rf $(BUILD) docs/gallery .pytest_cache .ruff_cache .hypothesis
	find . -name __pycache__ -prune -exec rm -rf {} +
