# Everything a newcomer needs: `make serve` and `make test` each create the
# virtual environment they need (.venv, Python >= 3.12) on a fresh machine.

SHELL := /bin/bash
VENV  := .venv
PY    := $(VENV)/bin/python
PORT  ?= 5006

# A working Python >= 3.12: an explicit PYTHON=..., else the first candidate
# that really runs (pyenv shims answer on PATH but fail without PYENV_VERSION).
PYTHON ?= $(shell for p in python3.13 python3.12 \
	"$$(pyenv root 2>/dev/null)/versions/3.12.1/bin/python3.12" \
	$$(ls -d "$$(pyenv root 2>/dev/null)"/versions/3.1[2-9]*/bin/python3 2>/dev/null) python3; do \
	"$$p" -c 'import sys; sys.exit(sys.version_info < (3, 12))' >/dev/null 2>&1 && { echo "$$p"; break; }; done)

.PHONY: venv serve test test-fast test-core test-app lint bench bench-charts browser docker-smoke clean lock

$(VENV)/.installed: pyproject.toml constraints.txt
	@test -n "$(PYTHON)" || { echo "error: no Python >= 3.12 found; install one or pass PYTHON=/path/to/python3.12" >&2; exit 1; }
	@echo "using $(PYTHON) ($$($(PYTHON) --version))"
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -c constraints.txt -e '.[app,test,bench,study]'
	@touch $@

venv: $(VENV)/.installed

serve: venv
	$(PY) -m app.serve --port $(PORT)

# Debian's Chromium for the browser tests (no browser download works here).
browser:
	@command -v chromium >/dev/null 2>&1 || { \
		SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
		$$SUDO apt-get update -qq && $$SUDO apt-get install -y -qq chromium >/dev/null; }
	@chromium --version

# Debian's LAMMPS (lmp with the GRANULAR package) for the DEM bench (core.dem_check).
.PHONY: lammps
lammps:
	@command -v lmp >/dev/null 2>&1 || { \
		SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
		$$SUDO apt-get update -qq && $$SUDO env DEBIAN_FRONTEND=noninteractive \
			apt-get install -y -qq lammps >/dev/null; }
	@lmp -h | sed -n '2p'

lint: venv
	$(VENV)/bin/ruff check .

# (the compiled kernels first, into numba's cache: the servers the browser tests start
# then load them rather than compile them while the tests run)
test: venv browser lammps nginx
	$(VENV)/bin/ruff check .
	$(PY) -m core.warm
	$(VENV)/bin/pytest

# Every test that needs no browser (core, numerics, the app's document, export, wire,
# sessions and server security; not the browser tests nor the nginx replicas): ~5 min here.
test-fast: venv
	$(VENV)/bin/ruff check .
	$(VENV)/bin/pytest -q -m "not browser and not slow"

test-core: venv
	$(VENV)/bin/pytest tests/core tests/numerics

bench: venv
	$(PY) -m benchmarks.core.core_throughput

# The charts of the methods' benchmarks (benchmarks/core/methods.py and stability_map.py
# write benchmarks/results/*.csv): their HTML pages there, and the two CSV files the
# Methods card shows copied into the app's package data (app/results/).
bench-charts: venv
	$(PY) -m app.methods.publish benchmarks/results --publish

docker-smoke:
	bash docker/smoke.sh

# Design studies on a real Dask deployment: a `dask scheduler` and two `dask worker`
# processes on loopback (a free port), the example study through --scheduler, its store
# compared bit for bit with a LocalCluster's; the processes are stopped also on failure
# (core/motor/study/smoke.py, docs/study.md).
.PHONY: study-smoke
study-smoke: venv
	$(PY) -m core.motor.study.smoke

# Re-pin the stack after a change of pyproject's requirements: a fresh environment
# with the newest versions pyproject allows, frozen into constraints.txt.
lock:
	rm -rf .venv-lock && $(PYTHON) -m venv .venv-lock
	.venv-lock/bin/pip install --quiet -e '.[app,test,bench,study]'
	{ sed -n '1,/^$$/p' constraints.txt | grep '^#'; .venv-lock/bin/pip freeze --exclude-editable | grep -v '^-e'; } > constraints.txt.new
	mv constraints.txt.new constraints.txt && rm -rf .venv-lock

clean:
	rm -rf $(VENV) .pytest_cache .ruff_cache .hypothesis

# ---- deployment: replicas behind nginx, load test (docs/deploy.md) -----------
.PHONY: nginx replica-smoke load-test load-test-replicas soak page-load

# Debian's nginx for the replica smoke test (installed only; no service is started).
nginx:
	@command -v nginx >/dev/null 2>&1 || [ -x /usr/sbin/nginx ] || { \
		SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
		$$SUDO apt-get update -qq && $$SUDO env DEBIAN_FRONTEND=noninteractive RUNLEVEL=1 \
			apt-get install -y -qq nginx >/dev/null; }
	@PATH="$$PATH:/usr/sbin" nginx -v

# Two replicas behind nginx with docker/nginx.conf, on loopback: sticky sessions,
# foreign origin refused, one replica killed (also tests/deploy/test_replicas.py).
replica-smoke: venv nginx
	$(PY) docker/replicas.py smoke

# 10, 25, 50, 100 sessions moving the psi slider every 0.3 s (about 6 minutes) on the
# deployment for more than one process: two single-process replicas behind nginx with
# docker/nginx.conf.  Per level: latency, CPU per serving process (max/mean), sessions
# per replica, CPU per move; at the end the students per core at p95 <= 200 ms.
load-test: venv nginx
	$(PY) -m benchmarks.app.load_test --replicas 2

load-test-replicas: load-test

# Server memory: 50 + 50 page loads and their cleanup, then 10,000 psi moves in one
# session (RSS sampled every 500; about 20 minutes on 2 cores).
soak: venv
	$(PY) -m benchmarks.app.soak

# Server time of a page load: median of 20 sequential GETs of /main on an idle server.
page-load: venv
	$(PY) -m benchmarks.app.page_load
