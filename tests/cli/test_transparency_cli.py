"""--transparency and --opacity on the command line: render's line, scene file keys,
compare's table and grid, and misuse in one line."""

import numpy as np
import pytest
from PIL import Image

from tests.conftest import BACKEND, glshade

pytestmark = pytest.mark.gl

SCENE = "assets/scenes/glass.toml"


def test_render_reports_the_transparent_fragments(tmp_path):
    out = tmp_path / "glass.png"
    done = glshade("render", SCENE, "-o", str(out), "--size", "160x100", "--backend",
                   BACKEND)
    assert done.returncode == 0, done.stderr
    assert "; transparency exact: " in done.stdout and "transparent fragments" in done.stdout
    opaque = tmp_path / "opaque.png"
    text = open(SCENE).read().replace("opacity = ", "# opacity = ")
    (tmp_path / "opaque.toml").write_text(text)
    assert glshade("render", str(tmp_path / "opaque.toml"), "-o", str(opaque), "--size",
                   "160x100").returncode == 0
    a, b = (np.asarray(Image.open(p)).astype(int) for p in (out, opaque))
    assert (np.abs(a - b).max(-1) > 20).mean() > 0.03  # (the glass shows what is behind)


def test_opacity_on_a_mesh_and_the_methods_on_the_command_line(tmp_path):
    runs = {}
    for method in ("exact", "weighted", "blend"):
        out = tmp_path / f"{method}.png"
        done = glshade("render", "primitive:icosphere:2", "-o", str(out), "--size", "96x72",
                       "--opacity", "0.4", "--transparency", method)
        assert done.returncode == 0, done.stderr
        runs[method] = np.asarray(Image.open(out)).astype(int)
    assert not np.array_equal(runs["exact"], runs["weighted"])


def test_compare_shows_the_methods_against_exact(tmp_path):
    out = tmp_path / "grid.png"
    done = glshade("compare", SCENE, "--transparency", "exact,weighted,blend", "-o",
                   str(out), "--size", "160x100", "--backend", BACKEND)
    assert done.returncode == 0, done.stderr
    rows = {line.split()[0]: line.split() for line in done.stdout.splitlines()
            if line.split()[:1] in (["exact"], ["weighted"], ["blend"])}
    assert rows["exact"][2:] == ["-", "-"]
    assert float(rows["weighted"][-1].rstrip("%")) > 0.5  # (an estimate: it differs)
    assert Image.open(out).size[0] == 3 * 160


@pytest.mark.parametrize("args, words", [
    (["render", SCENE, "--transparency", "exact,blend"], "--transparency: one method here"),
    (["render", SCENE, "--transparency", "sorted"], "argument --transparency: expected "
     "exact, weighted, blend"),
    (["render", "primitive:cube", "--opacity", "1.5"], "argument --opacity"),
    (["compare", SCENE, "--transparency", "exact,blend", "--shadows", "exact,map"],
     "compare one option's methods at a time"),
])
def test_misuse_is_one_line(tmp_path, args, words):
    done = glshade(*args, "-o", str(tmp_path / "x.png"))
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and words in done.stderr, \
        done.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_bad_opacity_in_a_scene_file_names_its_line(tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text('[[mesh]]\nsource = "primitive:cube"\nopacity = 2\n')
    done = glshade("render", str(scene), "-o", str(tmp_path / "x.png"))
    assert done.returncode == 2 and done.stderr.startswith(f"glshade: error: {scene}:3"), \
        done.stderr
