"""GL fixtures: one context per test run, made through create_context.

Where no context can be made the GL tests skip with the collected error text on a
developer's machine, but FAIL when ``CI`` or ``GLSHADE_REQUIRE_GL`` is set, so CI can never
go green by skipping the renderer. ``GLSHADE_TEST_BACKEND`` picks the backend (the README's
test command runs this folder once with egl and once with osmesa).
"""

import os

import pytest

from glshade.errors import ContextError

BACKEND = os.environ.get("GLSHADE_TEST_BACKEND", "egl")


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

    made = []

    def make(width=64, height=64, samples=0):
        r = Renderer(width, height, samples=samples, context=gl_context)
        made.append(r)
        return r

    yield make
    for r in made:
        r.close()


def pytest_collection_modifyitems(items):
    for item in items:
        if "tests/render" in str(item.fspath).replace("\\", "/"):
            item.add_marker(pytest.mark.gl)
