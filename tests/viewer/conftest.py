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

    made = []

    def make(scene, camera=None, **kw):
        kw.setdefault("size", (240, 180))
        kw.setdefault("samples", 0)
        kw.setdefault("visible", True)
        v = Viewer(scene, camera, screenshot_dir=tmp_path, **kw)
        made.append(v)
        return v

    yield make
    for v in made:
        v.close()


def pytest_collection_modifyitems(items):
    for item in items:
        if "tests/viewer" in str(item.fspath).replace("\\", "/"):
            item.add_marker(pytest.mark.display)
