"""Hostile values in scene files: each is one clean line naming the file (exit 2), never a
numpy traceback, and no numpy RuntimeWarning line leaks before it."""

import subprocess
import sys

import pytest

CASES = {
    "letters in a transform": ('transform = [["a", 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], '
                               '[0, 0, 0, 1]]', "4x4 list of lists of finite numbers"),
    "a ragged transform": ("transform = [[1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]",
                           "4x4 list of lists"),
    "booleans in a transform": ("transform = [[true, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], "
                                "[0, 0, 0, 1]]", "finite numbers"),
    "a huge scale": ("scale = 1e300", "too large to work with"),
    "a huge transform": ("transform = [[1e200, 0, 0, 0], [0, 1e200, 0, 0], [0, 0, 1e200, 0], "
                         "[0, 0, 0, 1]]", "too large to work with"),
    "a tiny scale": ("scale = 1e-300", "too small to work with"),
    "a flattening scale": ("scale = [1, 1, 1e-14]", "singular or nearly"),
    "a singular transform": ("transform = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0], "
                             "[0, 0, 0, 1]]", "singular or nearly"),
}


def _run(tmp_path, text):
    path = tmp_path / "s.toml"
    path.write_text(text)
    return subprocess.run([sys.executable, "-W", "default", "-m", "glshade", "render",
                           str(path), "-o", str(tmp_path / "x.png"), "--size", "16x16"],
                          capture_output=True, text=True), path


@pytest.mark.parametrize("case", list(CASES))
def test_a_hostile_mesh_value_is_one_clean_line(case, tmp_path):
    body, words = CASES[case]
    out, path = _run(tmp_path, f'[[mesh]]\nsource = "primitive:cube"\n{body}\n')
    assert out.returncode == 2, out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"glshade: error: {path}"), out.stderr
    assert words in lines[0] and "np.float64" not in lines[0]
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize("camera, status, words", [
    ("eye = [1e300, 0, 0]\ntarget = [0, 0, 0]", 2, "too far to compute its projection"),
    ("eye = [0, 0, 5]\ntarget = [1e300, 0, 0]", 0, "blank"),
    ("eye = [0, 0, 5]\ntarget = [0, 0, 0]\nup = [0, 1e300, 0]", 0, None),
    ("eye = [1e30, 0, 0]\ntarget = [0, 0, 0]", 0, "blank"),
])
def test_huge_camera_values_give_a_clean_line_or_a_picture(camera, status, words, tmp_path):
    out, _ = _run(tmp_path, f'[[mesh]]\nsource = "primitive:cube"\n[camera]\n{camera}\n')
    assert out.returncode == status, out.stderr
    assert "RuntimeWarning" not in out.stderr and "encountered" not in out.stderr
    if words:
        assert words in out.stderr
    assert len(out.stderr.strip().splitlines()) <= 1, out.stderr


def test_the_api_names_a_matrix_that_is_not_numbers():
    import numpy as np

    from glshade import GeometryError, Scene
    from glshade.geometry import primitives

    with pytest.raises(GeometryError, match="4x4 .* array of numbers"):
        Scene().add(primitives.cube(), transform=[["a", 0, 0, 0]] * 4)
    with pytest.raises(GeometryError, match="array of numbers"):
        Scene().add(primitives.cube(), transform=[[1, 0, 0], [0, 1]])
    from glshade.solids import Box

    with pytest.raises(GeometryError, match="too large"):
        Box(1).transformed(np.diag([1e200, 1, 1, 1.0]))
