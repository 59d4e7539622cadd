"""Shared fixtures. GL: one context per test run, made through create_context.

Where no context can be made the GL tests skip with the collected error text on a
developer's machine, but FAIL when ``CI`` or ``GLSHADE_REQUIRE_GL`` is set, so CI can never
go green by skipping the renderer. ``GLSHADE_TEST_BACKEND`` picks the backend (the README's
test command runs the GL tests once with egl and once with osmesa).
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from glshade.errors import ContextError

pytest_plugins = ["pytester"]

BACKEND = os.environ.get("GLSHADE_TEST_BACKEND", "egl")
ROOT = Path(__file__).resolve().parents[1]


def glshade(*args, timeout=120, **kwargs):
    """Run the command line tool in a subprocess from the repository root."""
    return subprocess.run([sys.executable, "-m", "glshade", *args], capture_output=True,
                          text=True, cwd=ROOT, timeout=timeout, **kwargs)


def closing_factory(build):
    """For a fixture: yield a function that builds objects, and close them all afterwards."""
    made = []

    def make(*args, **kwargs):
        made.append(build(*args, **kwargs))
        return made[-1]

    yield make
    for obj in made:
        obj.close()


@pytest.fixture(scope="session")
def gl_context():
    from glshade.render.context import create_context

    try:
        ctx = create_context(BACKEND)
    except ContextError as exc:
        if os.environ.get("CI") or os.environ.get("GLSHADE_REQUIRE_GL"):
            pytest.fail(f"no GL context in CI ({BACKEND}): {exc}", pytrace=False)
        pytest.skip(f"no GL context ({BACKEND}): {exc}")
    yield ctx
    ctx.release()


@pytest.fixture(autouse=True)
def gl_error_check(request):
    """The GL error flag is clean before and after every GL test."""
    if "gl_context" not in request.fixturenames:
        yield
        return
    ctx = request.getfixturevalue("gl_context").ctx
    assert ctx.error == "GL_NO_ERROR", "GL error left by an earlier test"
    yield
    assert ctx.error == "GL_NO_ERROR"


@pytest.fixture
def make_renderer(gl_context):
    """Renderers of any size on the shared context, closed after the test."""
    from glshade.render.renderer import Renderer

    yield from closing_factory(lambda width=64, height=64, samples=0:
                               Renderer(width, height, samples=samples, context=gl_context))


def pytest_collection_modifyitems(items):
    """Every test that draws (through the shared context, or a subprocess marked ``gl``) is
    a GL test: ``make test`` runs them again on OSMesa with ``-m gl``."""
    for item in items:
        in_render = "tests/render/" in str(item.fspath).replace("\\", "/")
        if in_render or "gl_context" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.gl)


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
