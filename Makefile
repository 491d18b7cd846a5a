# navlib: reproducible low-cost inertial navigation notebooks.
# `make reproduce` and `make test` each do all set-up from a fresh clone.

PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
PIP    := $(PY) -m pip --disable-pip-version-check
STAMP  := $(VENV)/.installed
BENCH_STAMP := $(VENV)/.bench-installed

# Headless, deterministic runs.
export PYTHONHASHSEED := 0
# Python's bytecode cache on (in the gitignored __pycache__ folders, beside numba's): where the environment turns it
# off, every notebook kernel, test worker and test subprocess compiled navlib and every test module from source again
# (~3 s of CPU per pytest worker's collection, ~0.2 s per navlib import).
unexport PYTHONDONTWRITEBYTECODE
reproduce test: export MPLBACKEND := Agg
# Executed notebooks keep no progress bars (navlib.montecarlo reads it).
export NAVLIB_PROGRESS := 0

# Two workers (this machine has two cores); conftest.py shares the tests out: a file with a module-scoped fixture
# on one worker, the longest tests of the last run first.
PYTEST_FLAGS ?= -q -ra --durations=10 -n 2 --dist loadgroup

.DEFAULT_GOAL := help
.PHONY: help venv reproduce readme docs test lint typecheck lab bench strip clean determinism fuzz test-min build-check

help:
	@echo "make reproduce  execute every notebook, write build/ (executed notebooks, figures, results)"
	@echo "make readme     regenerate the README results section (claims by verdict), quoted numbers and figures from build/"
	@echo "make test       unit/property tests + every notebook run to the end, also in teaching mode (each execution reused while up to date)"
	@echo "make lint       ruff over the code (also part of make test)"
	@echo "make typecheck  mypy over navlib/ at the level configured in pyproject.toml [tool.mypy]"
	@echo "make fuzz       tools/fuzz.py: every public callable with bad and unusual arguments (build/fuzz.json)"
	@echo "make lab        JupyterLab on notebooks/"
	@echo "make bench      install bench-only peers (requirements-bench.txt), run bench/run.py"
	@echo "make strip      strip outputs from notebooks/*.ipynb before committing (nbstripout)"
	@echo "make test-min   unit tests at the declared lowest versions of every requirement (nox -s tests_min)"
	@echo "make build-check  sdist + wheel in dist/, twine check --strict, check-manifest (nox -s build)"
	@echo "make determinism  run reproduce twice; fail unless results and PNGs are byte-identical"
	@echo "make docs       the documentation site in build/site/ (from the last make reproduce), checked in headless Chromium"
	@echo "make venv       create .venv from environment.txt and install navlib (done by all targets)"
	@echo "make clean      remove build/"

venv: $(STAMP)

# Re-installs only when the pins or the package metadata change. The exact pins of environment.txt are
# installed with uv (the version pinned there; ~10x faster than pip) when it can be installed, else with pip.
# --compile-bytecode: uv (unlike pip) writes no .pyc, and where PYTHONDONTWRITEBYTECODE is set nothing
# else does, so every kernel and test worker compiled numpy/scipy/matplotlib/pandas from source (8.4 s
# per import of the stack instead of 2.2 s).
UV_VERSION := $(shell sed -n 's/^uv==//p' environment.txt)
$(STAMP): environment.txt pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	if $(PIP) install -q uv==$(UV_VERSION) && $(VENV)/bin/uv --version; then \
	  $(VENV)/bin/uv pip install --python $(PY) --compile-bytecode -r environment.txt && \
	  $(VENV)/bin/uv pip install --python $(PY) --no-deps -e . ; \
	else \
	  $(PIP) install -r environment.txt && $(PIP) install --no-deps -e . ; \
	fi
	touch $@

reproduce: $(STAMP)
	$(PY) tools/reproduce.py
	$(PY) tools/readme.py

readme: $(STAMP)
	$(PY) tools/readme.py

# The seed sweep: every Monte Carlo notebook at full scale once per seed (the first SEEDS of tools/reproduce.py's
# SWEEP_SEEDS, or SEED_LIST=7,123,9999); fails on any failed check or verdict flip; writes build/seeds.json.
.PHONY: seeds
SEEDS ?= 5
seeds: $(STAMP)
	$(PY) tools/reproduce.py $(if $(SEED_LIST),--seed-list $(SEED_LIST),--seeds $(SEEDS))

# Two full runs; the second compares SHA-256 of every results.json and PNG with the first.
determinism: $(STAMP)
	$(PY) tools/reproduce.py
	cp build/manifest.json build/manifest.run1.json
	$(PY) tools/reproduce.py --check-against build/manifest.run1.json

# The documentation site: tools/build_site.py assembles build/site-src/ from the executed notebooks of the last
# `make reproduce` (run first when there is none) and builds build/site/ with Sphinx (docs/conf.py); MathJax
# comes from npm (docs/package.json, exact lock), the browser test (tests/test_site.py) from Debian's
# chromium, installed here when missing.
DOCS_STAMP := docs/node_modules/.installed
$(DOCS_STAMP): docs/package.json docs/package-lock.json
	npm ci --prefix docs --no-audit --no-fund
	touch $@

docs: $(STAMP) $(DOCS_STAMP)
	test -f build/summary.json || $(MAKE) reproduce
	command -v chromium >/dev/null || (apt-get update -qq && apt-get install -y -qq chromium)
	$(PY) tools/build_site.py
	$(PY) -m pytest -q -p no:cacheprovider tests/test_site.py

# Each notebook is executed once per run: reproduce.py --stale executes those whose execution into build/ is
# missing, failed or out of date (all of them on a fresh clone, none right after `make reproduce`), two at a
# time, and tests/test_notebook_runs.py reads their records; then likewise the teaching runs (each notebook in
# teaching + fast mode once per parameter change it invites; build/teaching/), which tests/test_teaching.py reads.
# tests/test_isolation.py records its isolated execution of one notebook the same way (build/isolation/run.json):
# a warm `make test` executes no notebook. pytest exits 5 when it collected no tests: a failure.
# nbmake (for running one notebook by hand) is not loaded: make test runs none with it, and its import cost each
# pytest process ~1 s (nbformat's validator building IRI parsers; conftest.py keeps test modules from paying it).
test: $(STAMP)
	@rc=0; $(PY) tools/reproduce.py --stale || rc=$$?; \
	NAVLIB_CHECK_README=1 $(PY) -m pytest tests -p no:nbmake $(PYTEST_FLAGS) || { r=$$?; [ $$r -ne 5 ] || echo "make test: pytest collected no tests" >&2; rc=$$r; }; \
	exit $$rc

lint: $(STAMP)
	$(VENV)/bin/ruff check .

typecheck: $(STAMP)
	$(VENV)/bin/mypy

# Every public callable, every argument mutated (tools/fuzz.py); fails on a bad outcome not documented as by design.
fuzz: $(STAMP)
	$(PY) tools/fuzz.py --jobs 2

lab: $(STAMP)
	$(PY) -m jupyter lab notebooks/

# Bench-only peers go into the same .venv; -c keeps the project's pins intact.
$(BENCH_STAMP): requirements-bench.txt environment.txt $(STAMP)
	$(PIP) install -r requirements-bench.txt -c environment.txt
	touch $@

bench: $(BENCH_STAMP)
	$(PY) bench/run.py

# The flags of the pre-commit hook: keep the meaningful cell ids, drop execution timing and widget state.
NBSTRIPOUT_FLAGS := --keep-id --extra-keys "cell.metadata.execution metadata.widgets"
strip: $(STAMP)
	$(VENV)/bin/nbstripout $(NBSTRIPOUT_FLAGS) notebooks/*.ipynb

# noxfile.py's sessions, in environments of their own under .nox/ (made with uv).
test-min: $(STAMP)
	$(VENV)/bin/nox -s tests_min

build-check: $(STAMP)
	$(VENV)/bin/nox -s build

clean:
	rm -rf build/
