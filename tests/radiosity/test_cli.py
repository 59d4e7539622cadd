"""glshade radiosity on the command line: the picture, the plot, the steps, and errors."""

import numpy as np
import pytest
from PIL import Image

from ..conftest import BACKEND, ROOT, glshade

pytestmark = pytest.mark.gl

SCENE = str(ROOT / "assets" / "scenes" / "cornell-box.toml")


def test_cornell_box_image_plot_and_steps(tmp_path):
    out = tmp_path / "box.png"
    r = glshade("radiosity", SCENE, "-o", str(out), "--patch-size", "150", "--size",
                "96x96", "--steps", str(tmp_path / "steps.gif"), "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    assert "unshot" in r.stdout and "patches" in r.stdout
    image = np.asarray(Image.open(out).convert("RGB")).astype(int)
    # the red wall is on the left of the published view, the green one on the right
    left, right = image[40:60, 4:10].mean((0, 1)), image[40:60, -10:-4].mean((0, 1))
    assert left[0] > 2 * left[1] and right[1] > 1.3 * right[0]  # (sRGB-encoded)
    assert Image.open(tmp_path / "box-convergence.png").size[0] > 100
    with Image.open(tmp_path / "steps.gif") as gif:
        assert gif.n_frames > 5


def test_bad_input_is_one_line(tmp_path):
    r = glshade("radiosity", "primitive:cube", "-o", str(tmp_path / "x.png"))
    assert r.returncode == 2 and "needs a scene file" in r.stderr
    dark = tmp_path / "dark.toml"
    dark.write_text('[[mesh]]\nsource = "primitive:cube"\n')
    r = glshade("radiosity", str(dark), "-o", str(tmp_path / "x.png"), "--backend", BACKEND)
    assert r.returncode == 2 and "no emitter" in r.stderr, r.stderr
    assert r.stderr.count("\n") == 1
    hot = tmp_path / "hot.toml"
    hot.write_text('[[mesh]]\nsource = "primitive:cube"\nreflectance = [0.5, 1.5, 0.5]\n')
    r = glshade("radiosity", str(hot), "-o", str(tmp_path / "x.png"))
    assert r.returncode == 2 and f"{hot}:3" in r.stderr and "[0, 1]" in r.stderr, r.stderr
    r = glshade("radiosity", SCENE, "-o", str(tmp_path / "x.png"), "--hemicube", "33")
    assert r.returncode == 2 and "even whole number" in r.stderr
    assert not (tmp_path / "x.png").exists()


def test_monte_carlo_from_the_command_line_agrees_with_the_hemicubes(tmp_path):
    """--method monte-carlo: the independent solution, drawn at the same exposure as the
    hemicube one, shows the same walls (means within 3%); --steps is refused with it."""
    images = {}
    for method in ("progressive", "monte-carlo"):
        out = tmp_path / f"{method}.png"
        extra = ["--particles", "150000"] if method == "monte-carlo" else []
        r = glshade("radiosity", SCENE, "-o", str(out), "--patch-size", "150", "--size",
                    "64x64", "--exposure", "1", "--method", method, "--no-ambient",
                    "--until", "0.001", *extra, "--backend", BACKEND)
        assert r.returncode == 0, r.stderr
        images[method] = np.asarray(Image.open(out).convert("RGB")).astype(float)
    assert "particles" in r.stdout and "standard error" in r.stdout
    a, b = images["progressive"], images["monte-carlo"]
    for rows, cols in ((slice(25, 40), slice(2, 6)), (slice(25, 40), slice(-6, -2)),
                       (slice(8, 14), slice(24, 40))):  # red wall, green wall, ceiling
        ma, mb = a[rows, cols].mean((0, 1)), b[rows, cols].mean((0, 1))
        assert np.abs(ma - mb).max() <= 0.03 * ma.max() + 2, (ma, mb)
    r = glshade("radiosity", SCENE, "-o", str(tmp_path / "x.png"), "--method",
                "monte-carlo", "--steps", str(tmp_path / "s.gif"))
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "monte-carlo" in r.stderr
