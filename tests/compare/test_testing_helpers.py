"""glshade.testing and the pytest plugin, tested with pytest's own pytester."""

import numpy as np
import pytest

from glshade.testing import assert_images_close


def test_assert_images_close_passes_and_fails_with_files(tmp_path):
    a = np.zeros((20, 30, 4), np.uint8)
    b = a.copy()
    b[5:8, 10:12, 0] = 3
    assert_images_close(a, b, max_mean=0.5, max_pixel=4)
    b[6, 11, 1] = 90
    with pytest.raises(AssertionError) as info:
        assert_images_close(a, b, max_mean=0.5, max_pixel=4, save_to=tmp_path)
    text = str(info.value)
    assert "max 90.0 (allowed 4) at row 6, column 11" in text
    assert "1 pixels differ by more than 4, within rows 6..6, columns 11..11" in text
    assert {p.name for p in tmp_path.iterdir()} == {"actual.png", "expected.png", "diff.png"}


PLUGIN_TEST = """
import numpy as np
from glshade import Camera, Scene
from glshade.geometry import primitives

def render(r):
    s = Scene()
    s.add(primitives.icosphere(2))
    return r.render(s, Camera.look_at([0, 0, 3], [0, 0, 0]), "phong")

def test_golden(glshade_renderer, glshade_golden):
    glshade_golden(render(glshade_renderer), "sphere.png")

def test_same_renderer(glshade_renderer):
    assert glshade_renderer.width == 256

def test_broken(glshade_renderer, glshade_golden):
    img = render(glshade_renderer).copy()
    img[100:120, 100:120] = 255
    glshade_golden(img, "sphere.png")
"""


@pytest.mark.once
def test_pytest_plugin_golden_images(pytester, gl_context):
    backend = gl_context.backend.value
    pytester.makepyfile(test_images=PLUGIN_TEST.replace(
        'glshade_golden(img, "sphere.png")', 'glshade_golden(img, "sphere-broken.png")'))
    result = pytester.runpytest_subprocess("--glshade-backend", backend, "-k", "golden")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*no golden image*--glshade-add-missing*"])
    result = pytester.runpytest_subprocess("--glshade-backend", backend, "-k", "golden",
                                           "--glshade-update-golden")
    result.assert_outcomes(passed=1)
    assert (pytester.path / "golden" / "sphere.png").exists()
    assert (pytester.path / "golden" / "sphere.json").exists()  # (its fingerprint)
    import shutil

    shutil.copy(pytester.path / "golden" / "sphere.png",
                pytester.path / "golden" / "sphere-broken.png")
    shutil.copy(pytester.path / "golden" / "sphere.json",
                pytester.path / "golden" / "sphere-broken.json")
    results = pytester.path.parent / "results"
    result = pytester.runpytest_subprocess("--glshade-backend", backend, "--glshade-results",
                                           str(results))
    result.assert_outcomes(passed=2, failed=1)
    result.stdout.fnmatch_lines(["*the same renderer made different bytes*Saved actual.png*",
                                 f"glshade: 1 golden image(s) differ; see {results}*index.html"])
    assert (results / "sphere-broken" / "diff.png").exists()
    assert not (pytester.path / "glshade-failures").exists()  # (never in the source tree)


def test_pytest_plugin_fails_clearly_without_gl(pytester):
    import os
    import subprocess
    import sys

    pytester.makepyfile(test_x="def test_x(glshade_renderer):\n    pass\n")
    env = dict(os.environ, GLSHADE_OSMESA_LIBRARY="/no/libOSMesa.so")
    out = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider",
                          "--glshade-backend", "osmesa", str(pytester.path / "test_x.py")],
                         capture_output=True, text=True, env=env, cwd=pytester.path)
    assert out.returncode == 1
    assert "no headless OpenGL context" in out.stdout
    assert "tried osmesa" in out.stdout and "libosmesa6" in out.stdout
