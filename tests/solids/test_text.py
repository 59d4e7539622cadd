"""CSG trees as text: what they parse to, that nothing but solids and numbers is allowed,
scene files with [[solid]] tables, and the command line on solids."""

import numpy as np
import pytest

from glshade.errors import InputError, SceneFormatError
from glshade.solids import parse_solid
from glshade.io.scenefile import load_scene
from glshade.solids import Box, Cylinder, Sphere

from ..conftest import BACKEND, ROOT, glshade


def test_text_builds_the_same_tree_as_python():
    text = "(box(2, 1, 2) - cylinder(0.4, 3).turn(90, [1, 0, 0])) | sphere(0.6).move(0, 0.8, 0)"
    q = [np.sin(np.pi / 4), 0, 0, np.cos(np.pi / 4)]
    python = (Box((2, 1, 2)) - Cylinder(0.4, 3).rotated(q)) | Sphere(0.6).translated((0, .8, 0))
    p = np.random.default_rng(1).uniform(-1.5, 1.5, (50_000, 3))
    assert np.array_equal(parse_solid(text).contains(p), python.contains(p))
    multi = parse_solid("box(2)\n  - sphere(1.2)\n  | cone(0.5, 1).scale(1, 2, 1)")
    assert len(multi.leaves()) == 3


@pytest.mark.parametrize("text, message", [
    ("__import__('os').system('true')", "is not a solid"),
    ("box(2) + sphere(1)", "is not a solid"),
    ("sphere('a')", "expected a number"),
    ("torus(1, 2)", "r < R"),
    ("box(1, 2)", "three sizes"),
    ("box(1", r"not a CSG expression \('\(' was never closed\)"),
    ("box(1) -", r"not a CSG expression \(invalid syntax; it ends too early\)"),
    ("box(1) +* sphere(1)", r"\(invalid syntax; column 9\)"),
    ("box(1)\n  | sphere(1) $ 2", r"\(invalid syntax; line 2, column 15\)"),
    ("sphere(1).turn(90, [0, 0, 0])", "axis"),
])
def test_mistakes_name_where(text, message):
    with pytest.raises(InputError, match=message) as info:
        parse_solid(text, "part.toml:7: tree")
    assert str(info.value).startswith("part.toml:7: tree: ")


def test_scene_files_take_solids(tmp_path):
    scene = load_scene(ROOT / "assets/scenes/csg-part.toml").scene
    assert len(scene.solids) == 1 and len(scene.models) == 1
    assert scene.solids[0].name == "part" and len(scene.solids[0].solid.leaves()) == 4
    bad = tmp_path / "bad.toml"
    bad.write_text('[[solid]]\ncolor = [1, 0, 0]\ntree = "box(2) - sphre(1)"\n')
    with pytest.raises(InputError, match=rf"{bad}:3: tree: 'sphre\(1\)' is not a solid"):
        load_scene(bad)
    bad.write_text('[[solid]]\ncolor = [1, 0, 0]\n')
    with pytest.raises(SceneFormatError, match="needs a 'tree'"):
        load_scene(bad)
    bad.write_text('[[solid]]\ntree = "halfspace([0, 1, 0], 0)"\n')
    with pytest.raises(SceneFormatError, match="bounded"):
        load_scene(bad)


def test_the_command_line_on_solids(tmp_path):
    spec = "solid:box(2) - cylinder(0.5, 3)"
    r = glshade("info", spec, "--json")
    assert r.returncode == 0, r.stderr
    import json

    facts = json.loads(r.stdout)
    exact = 8 - 2 * np.pi * 0.25
    lo, hi = facts["octree_volume_bounds"]
    assert lo <= exact <= hi
    assert abs(facts["volume"] - exact) < 4 * facts["volume_error"]
    assert facts["bounds"] == {"min": [-1.0] * 3, "max": [1.0] * 3}  # (a difference: A's)
    assert [c["level"] for c in facts["octree_levels"]] == list(range(7))
    out = tmp_path / "part.png"
    r = glshade("render", str(ROOT / "assets/scenes/csg-part.toml"), "-o", str(out),
                "--size", "96x72", "--backend", BACKEND)
    assert r.returncode == 0 and out.stat().st_size > 0, r.stderr
    r = glshade("render", "solid:box(2) -", "-o", str(out))
    assert r.returncode == 2 and "not a CSG expression" in r.stderr
