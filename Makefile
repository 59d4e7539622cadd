# The two commands of the README: `make demo` and `make test`. Each sets up .venv itself.
VENV ?= .venv
PY := $(VENV)/bin/python

.PHONY: setup setup-demo demo test lint bench assets docs clean

setup:
	@scripts/setup.sh test

setup-demo:
	@scripts/setup.sh demo

demo: setup-demo
	$(VENV)/bin/glshade info assets/teapot.obj
	@mkdir -p out
	for mode in flat gouraud phong; do \
		$(VENV)/bin/glshade render assets/teapot.obj --mode $$mode --size 640x480 \
			--color 0.85,0.55,0.3 --background 0.12,0.12,0.14 -o out/teapot-$$mode.png || exit 1; \
	done

# Everything on EGL; then the tests of what a backend or a GL's version can change (marked
# backend: the renderer's passes, the tracer's and tessellation's programs, each against its
# oracle -- tests/conftest.py says which) on what a Mac has: the platform's own context
# (GLX under Xvfb, as CGL is on macOS and WGL on Windows) held to 4.1 core without the later
# extensions (scripts/mac-gl41.sh), where the passes take their 4.1 paths; and on OSMesa
# (one backend per process), which is the same Mesa driver as EGL made another way, the
# tests that run every pass's and program's code once (the renderer, the pipeline's
# combinations of outputs, the programs, the context, the tracer, tessellation), not every
# sweep over their parameters (43 s -> 16 s); the slow ones and those whose point does not depend on
# the backend (marked once) run once, on EGL -- among them the 4.1 paths against their 4.3
# twins (tests/render/test_gl_tiers.py) and 3.3 core (tests/cli/test_gl33.py); then the
# viewer in a real window under Xvfb.
# The headless passes run on every core (pytest-xdist; each llvmpipe context renders on all
# cores itself): the first with 4 worker processes at most, as many of its tests wait on
# subprocesses, servers and files; the backend passes, all drawing, with one a core (on 2
# cores: 54 s and 58 s against 72 s and 88 s with 4). The viewer's tests share one display.
XDIST := -n auto --maxprocesses 4 --dist worksteal --durations=15
XDIST_DRAWING := -n auto --dist worksteal --durations=15
# (the backend tests' own files, tests/conftest.py's BACKEND_PATHS: collecting the whole
# suite to deselect nine tenths of it cost each worker 8 s)
BACKEND_TESTS := tests/render tests/pathtrace/test_pathtrace.py \
	tests/patches/test_gpu_tessellation.py
BACKEND_MARKS := -m "gl and backend and not slow and not once"
OSMESA_TESTS := tests/render/test_renderer.py tests/render/test_pipeline.py \
	tests/render/test_programs.py tests/render/test_shaders_and_context.py \
	tests/pathtrace/test_pathtrace.py tests/patches/test_gpu_tessellation.py
test: setup
	$(PY) -m pytest -q $(XDIST) --ignore=tests/viewer
	GLSHADE_TEST_BACKEND=native GLSHADE_TEST_TIER=4.1 scripts/with-display.sh \
		scripts/mac-gl41.sh $(PY) -m pytest -q $(XDIST_DRAWING) $(BACKEND_MARKS) \
		$(BACKEND_TESTS)
	GLSHADE_TEST_BACKEND=osmesa $(PY) -m pytest -q $(XDIST_DRAWING) $(BACKEND_MARKS) \
		$(OSMESA_TESTS)
	scripts/with-display.sh $(PY) -m pytest -q tests/viewer

lint: setup
	$(PY) -m pip install -q ruff
	$(PY) -m ruff check src tests benchmarks scripts
	$(PY) -m mypy  # src/ and tests/typing/user_api.py (pyproject.toml [tool.mypy])

# Every benchmark in benchmarks/, at quick sizes (a few minutes); FULL=1 for the sizes the
# guide's tables were measured at (docs/guide/speed.md says which command made each).
ifdef FULL
QUICK_RENDER :=
QUICK_TRACE :=
QUICK_HIDDEN :=
QUICK_INTERRUPT := --load
QUICK_DATASET := --frames 50
QUICK_INSTANCES := --counts 1000,10000 --frames 5
QUICK_SCALE :=
else
QUICK_RENDER := --sizes 512 --meshes 1k,100k --rounds 2
QUICK_TRACE := --scenes cornell --rounds 1 --reference-spp 1024 --ld-spp 256
QUICK_HIDDEN := --budget 5
QUICK_INTERRUPT := --tries 10
QUICK_DATASET := --frames 10
QUICK_INSTANCES := --counts 1000,10000 --frames 2
QUICK_SCALE := --points 1M --instances 2000 --triangles 2M --rounds 1
endif
bench: setup
	$(PY) benchmarks/geometry_bench.py
	$(PY) benchmarks/quaternion_bench.py
	$(PY) benchmarks/brep_bench.py
	$(PY) benchmarks/startup_bench.py
	$(PY) benchmarks/render_bench.py $(QUICK_RENDER)
	$(PY) benchmarks/animate_bench.py
	$(PY) benchmarks/batch_bench.py
	$(PY) benchmarks/csg_bench.py
	$(PY) benchmarks/hidden_bench.py $(QUICK_HIDDEN)
	$(PY) benchmarks/patch_bench.py
	$(PY) benchmarks/radiosity_bench.py
	$(PY) benchmarks/shadows_bench.py
	$(PY) benchmarks/transparency_bench.py
	$(PY) benchmarks/pbr_bench.py
	$(PY) benchmarks/pyrender_units.py
	$(PY) benchmarks/pathtrace_bench.py $(QUICK_TRACE)
	$(PY) benchmarks/pathtrace_materials_bench.py
	$(PY) benchmarks/interrupt_bench.py $(QUICK_INTERRUPT)
	$(PY) benchmarks/dataset_bench.py $(QUICK_DATASET)
	$(PY) benchmarks/instances_bench.py $(QUICK_INSTANCES)
	$(PY) -m pip install -q -e ".[peers]"  # (polyscope, the peer measured beside glshade)
	$(PY) benchmarks/geometry_scale_bench.py $(QUICK_SCALE)

# The documentation site: the README, the chapter notebooks (executed) and the API reference
# from the docstrings, warnings as errors; open docs/_build/html/index.html
docs: setup
	$(PY) -m sphinx -W --keep-going -b html docs docs/_build/html

assets: setup
	$(PY) scripts/make_assets.py

clean:
	rm -rf $(VENV) build dist .pytest_cache
