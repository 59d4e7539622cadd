# The two commands of the README: `make demo` and `make test`. Each sets up .venv itself.
VENV ?= .venv
PY := $(VENV)/bin/python

.PHONY: setup demo test bench assets clean

setup:
	@scripts/setup.sh

demo: setup
	$(VENV)/bin/glshade info assets/teapot.obj

test: setup
	$(PY) -m pytest -q

bench: setup
	$(PY) benchmarks/geometry_bench.py

assets: setup
	$(PY) scripts/make_assets.py

clean:
	rm -rf $(VENV) build dist .pytest_cache
