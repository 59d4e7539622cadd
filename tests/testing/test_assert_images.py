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
    # (a folder per test node id, then per golden)
    assert [p.relative_to(results).as_posix() for p in results.glob("*/*/diff.png")] == \
        ["test_images.py.test_broken/sphere-broken/diff.png"]
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


def test_every_comparison_reads_an_image_one_way(tmp_path):
    """Integers of any type are 8-bit levels as they are (an int64 image equal to a uint8
    one is equal); floats are [0, 1]; what fits neither is refused, never rescaled."""
    from glshade.testing import levels
    from glshade.testing.golden import as_rgba

    img = np.arange(48, dtype=np.uint8).reshape(4, 4, 3) * 5
    assert_images_close(img.astype(np.int64), img, max_mean=0, max_pixel=0)
    assert (as_rgba(img.astype(np.int16)) == as_rgba(img)).all()
    assert (levels(img / 255.0) == levels(img)).all()
    ones = np.ones((2, 2), np.int32)  # (level 1, not white: an int image is never scaled)
    assert levels(ones)[0, 0, 0] == 1.0
    with pytest.raises(AssertionError, match="differ"):
        assert_images_close(ones, ones * 255, max_mean=0.5, max_pixel=4, save_to=tmp_path)
    for bad, words in ((img.astype(np.int64) * 300, "0..255"), (img * 2.0, "floats are read"),
                       (np.zeros((2, 2, 2)), "shape")):
        with pytest.raises(ValueError, match=words):
            levels(bad)


def test_results_go_to_the_given_folder_before_any_golden_fails(pytester):
    """assert_images_close in a test run with --glshade-results saves its failure images
    there, in the test's own folder (its node id), though no golden check ever ran (the
    folder was told to glshade only after a golden failed)."""
    pytester.makepyfile(test_plain='''
import numpy as np
from glshade.testing import assert_images_close

def test_close():
    a = np.zeros((8, 8, 4), np.uint8)
    b = a.copy()
    b[2, 3, 0] = 99
    assert_images_close(a, b)
''')
    results = pytester.path / "results"
    out = pytester.runpytest_subprocess("--glshade-results", str(results))
    out.assert_outcomes(failed=1)
    saved = sorted(p.relative_to(results).as_posix() for p in results.rglob("*.png"))
    assert saved == [f"test_plain.py.test_close/{n}.png" for n in ("actual", "diff", "expected")]
