# make demo : create .venv with pinned dependencies, run the built-in demo
# make test : create .venv with pinned dependencies + test tools, run make lint, then the tests
# make lint : ruff (lint + format check) and mypy, configured in pyproject.toml
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
DEMO_OUT ?= demo-output

.PHONY: demo test lint bench clean

$(VENV)/.runtime: requirements.txt pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -r requirements.txt
	$(PY) -m pip install -q --no-deps -e .
	touch $@

$(VENV)/.dev: $(VENV)/.runtime requirements-dev.txt
	$(PY) -m pip install -q -r requirements-dev.txt
	touch $@

demo: $(VENV)/.runtime
	$(VENV)/bin/smtmvt demo --out $(DEMO_OUT)

test: lint
	$(PY) -m pytest -q -n 2 --dist loadfile

lint: $(VENV)/.dev
	$(VENV)/bin/ruff check .
	$(VENV)/bin/ruff format --check .
	$(VENV)/bin/mypy

bench: $(VENV)/.runtime
	$(PY) bench/bench_tracker.py

clean:
	rm -rf $(VENV) $(DEMO_OUT) build src/*.egg-info
