"""Viewer tests run in a real window. The README's test command runs them under Xvfb; where
no display is available they skip on a developer's machine but FAIL in CI (``CI`` or
``GLSHADE_REQUIRE_DISPLAY`` set)."""

import os

import pytest


@pytest.fixture
def viewer_factory(tmp_path):
    if not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        if os.environ.get("CI") or os.environ.get("GLSHADE_REQUIRE_DISPLAY"):
            pytest.fail("no DISPLAY for the viewer tests in CI (run them under xvfb-run)",
                        pytrace=False)
        pytest.skip("no DISPLAY: run the viewer tests under xvfb-run")
    from glshade.viewer.window import Viewer
    from tests.conftest import closing_factory

    def build(scene, camera=None, size=(240, 180), samples=0, visible=True, **kw):
        return Viewer(scene, camera, size=size, samples=samples, visible=visible,
                      screenshot_dir=tmp_path, **kw)

    yield from closing_factory(build)


def pytest_collection_modifyitems(items):
    for item in items:
        if "tests/viewer" in str(item.fspath).replace("\\", "/"):
            item.add_marker(pytest.mark.display)
