# make demo : create .venv with pinned dependencies, run the built-in demo
# make test : create .venv with pinned dependencies + test tools, run make lint, then the tests
# make lint : ruff (lint + format check) and mypy, configured in pyproject.toml
# make mutation : mutation testing of the core modules with mutmut (slow: hours
#   on 2 cores; not part of make test). Results in mutants/ (summary.txt,
#   survivors.diff); configuration in pyproject.toml [tool.mutmut].
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
DEMO_OUT ?= demo-output

.PHONY: demo test lint bench mutation clean

$(VENV)/.runtime: requirements.txt pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -r requirements.txt
	$(PY) -m pip install -q --no-deps -e .
	touch $@

$(VENV)/.dev: $(VENV)/.runtime requirements-dev.txt
	$(PY) -m pip install -q -r requirements-dev.txt
	touch $@

$(VENV)/.mutation: $(VENV)/.dev requirements-mutation.txt
	$(PY) -m pip install -q -r requirements-mutation.txt
	touch $@

demo: $(VENV)/.runtime
	$(VENV)/bin/smtmvt demo --out $(DEMO_OUT)

test: lint
	$(PY) -m pytest -q -n 2 --dist loadfile

lint: $(VENV)/.dev
	$(VENV)/bin/ruff check .
	$(VENV)/bin/ruff format --check .
	$(VENV)/bin/mypy

# One worker, low priority and single-threaded BLAS by default: the machine is shared.
MUTATION_JOBS ?= 1
mutation: $(VENV)/.mutation
	rm -rf mutants
	OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 \
	  nice -n 15 $(VENV)/bin/mutmut run --max-children $(MUTATION_JOBS)
	$(VENV)/bin/mutmut results --all true > mutants/results.txt
	$(PY) tools/mutation_summary.py mutants/results.txt | tee mutants/summary.txt
	for m in $$(awk '$$2 == "survived" {sub(":$$", "", $$1); print $$1}' mutants/results.txt); do \
	  $(VENV)/bin/mutmut show $$m; done > mutants/survivors.diff

bench: $(VENV)/.runtime
	$(PY) bench/bench_tracker.py

clean:
	rm -rf $(VENV) $(DEMO_OUT) build src/*.egg-info mutants
