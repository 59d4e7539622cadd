"""--shadows on the command line: render's line names the method (a map's sizes and
footprint), scene files and per-light opt-outs say the same as the option, compare shows
the methods with their differences, and every misuse is one line."""

import re

import numpy as np
import pytest
from PIL import Image

from tests.conftest import BACKEND, glshade

pytestmark = pytest.mark.gl

SCENE = "assets/scenes/shadows.toml"


def pixels(path):
    return np.asarray(Image.open(path)).astype(int)


def test_render_says_how_it_shadowed(tmp_path):
    runs = {}
    for method in ("exact", "map", "off"):
        out = tmp_path / f"{method}.png"
        done = glshade("render", SCENE, "-o", str(out), "--size", "200x125", "--shadows",
                       method, "--backend", BACKEND)
        assert done.returncode == 0, done.stderr
        runs[method] = (done.stdout, pixels(out))
    assert runs["exact"][0].rstrip().endswith("; exact shadows (a ray a pixel and light)")
    found = re.search(r"shadow maps: 6x1024x1024 \(cube, a texel ([\d.]+) px\); 2048x2048 "
                      r"\(2D, a texel ([\d.]+) px\); 6x1024x1024 \(cube, a texel [\d.]+ px\), "
                      r"PCF 3x3", runs["map"][0])
    assert found, runs["map"][0]
    assert 0 < float(found.group(1)) < 1 and 0 < float(found.group(2)) < 1
    assert runs["off"][0].rstrip().endswith(f"polygons ({BACKEND})")  # (nothing on shadows)
    dark = np.abs(runs["exact"][1] - runs["off"][1]).max(-1) > 30
    assert dark.mean() > 0.05  # the teapot's shadows on the floor
    differ = np.abs(runs["exact"][1] - runs["map"][1]).max(-1) > 30
    assert differ.mean() < 0.01


def test_the_scene_file_key_equals_the_option(tmp_path):
    text = open(SCENE).read()
    (tmp_path / "off.toml").write_text(text.replace('shadows = "exact"', 'shadows = "off"'))
    a, b = tmp_path / "a.png", tmp_path / "b.png"
    assert glshade("render", SCENE, "-o", str(a), "--size", "160x100").returncode == 0
    done = glshade("render", str(tmp_path / "off.toml"), "-o", str(b), "--size", "160x100",
                   "--shadows", "exact")
    assert done.returncode == 0, done.stderr
    assert np.array_equal(pixels(a), pixels(b))


def test_a_light_that_casts_no_shadow_is_off_for_that_light(tmp_path):
    """Every light opted out: the exact render is the unshadowed one, byte for byte."""
    text = open(SCENE).read().replace("shadows = false\n", "")
    text = text.replace("[[light]]\n", "[[light]]\nshadows = false\n")
    (tmp_path / "s.toml").write_text(text)
    a, b = tmp_path / "a.png", tmp_path / "b.png"
    assert glshade("render", str(tmp_path / "s.toml"), "-o", str(a), "--size",
                   "160x100").returncode == 0
    assert glshade("render", str(tmp_path / "s.toml"), "-o", str(b), "--size", "160x100",
                   "--shadows", "off").returncode == 0
    assert np.array_equal(pixels(a), pixels(b))


def test_compare_shows_the_methods_and_what_differs(tmp_path):
    out = tmp_path / "grid.png"
    done = glshade("compare", SCENE, "--shadows", "exact,map,off", "-o", str(out),
                   "--size", "160x100", "--backend", BACKEND)
    assert done.returncode == 0, done.stderr
    rows = {line.split()[0]: line.split() for line in done.stdout.splitlines()
            if line.split()[:1] in (["exact"], ["map"], ["off"])}
    assert rows["exact"][2:] == ["-", "-"]
    assert float(rows["map"][-1].rstrip("%")) < 3.0      # a map is close to exact
    assert float(rows["off"][-1].rstrip("%")) > 10.0     # no shadows is not
    w, h = Image.open(out).size
    assert w == 3 * 160 and h > 2 * 100  # three renders over three heat maps


@pytest.mark.parametrize("args, words", [
    (["render", SCENE, "--shadows", "exact,map"], "--shadows: one method here"),
    (["render", SCENE, "--shadows", "soft"], "argument --shadows: expected off, exact, map"),
    (["pathtrace", SCENE, "--shadows", "exact"], "--shadows is an option of the raster "
     "modes"),
    (["compare", SCENE, "--shadows", "exact,map", "--modes", "normals"],
     "--shadows compares its methods in a lit mode"),
])
def test_misuse_is_one_line(tmp_path, args, words):
    done = glshade(*args, "-o", str(tmp_path / "x.png"))
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and words in done.stderr, \
        done.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_bad_shadows_key_names_the_file_and_line(tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text('[render]\nshadows = "soft"\n[[mesh]]\nsource = "primitive:cube"\n')
    done = glshade("render", str(scene), "-o", str(tmp_path / "x.png"))
    assert done.returncode == 2
    assert done.stderr.startswith(f"glshade: error: {scene}:2:") and "shadows" in \
        done.stderr, done.stderr


@pytest.mark.parametrize("command", ["animate", "batch"])
def test_animate_and_batch_cast_shadows(tmp_path, command):
    out = tmp_path / ("a.gif" if command == "animate" else "out")
    source = SCENE if command == "animate" else "assets/teapot.obj"
    extra = ["--frames", "2"] if command == "animate" else []
    done = glshade(command, source, "-o", str(out), "--size", "64x40", "--shadows", "map",
                   "-q", "--jobs", "1", *extra)
    assert done.returncode == 0, done.stderr
    assert out.exists()
