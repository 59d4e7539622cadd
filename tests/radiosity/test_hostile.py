"""Hostile radiosity scenes and arguments, through the command line: refused up front in
one line naming the scene file (exit 2), with nothing written."""

import subprocess
import sys

import pytest

from tests.conftest import ROOT

pytestmark = pytest.mark.gl

BOX = str(ROOT / "assets" / "scenes" / "cornell-box.toml")

WALLS = """
[[mesh]]
source = "{wall}"
name = "wall"
reflectance = [0.5, 0.5, 0.5]
"""
LIGHT = """
[[mesh]]
source = "{light}"
name = "light"
emission = [10, 10, 10]
"""


def _files(tmp_path):
    wall = tmp_path / "wall.obj"
    wall.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
    flat = tmp_path / "flat.obj"  # a quad of collinear corners: no area
    flat.write_text("v 0 0 1\nv 1 0 1\nv 2 0 1\nv 3 0 1\nf 1 2 3 4\n")
    lamp = tmp_path / "lamp.obj"
    lamp.write_text("v 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\nf 1 2 3 4\n")
    return wall, flat, lamp


def _run(tmp_path, *args):
    out = tmp_path / "out"
    out.mkdir(exist_ok=True)
    r = subprocess.run([sys.executable, "-m", "glshade", "radiosity", *args, "-o",
                        str(out / "r.png"), "--size", "32x32", "-q"], capture_output=True,
                       text=True, cwd=tmp_path)
    return r, out


@pytest.mark.parametrize("case, extra, words", [
    ("a microscopic patch size", ["--patch-size", "1e-6"], "more than the 200,000"),
    ("an absurd patch size", ["--patch-size", "1e-300"], "more patches than can be counted"),
    ("a patch size of 1e-3 mm", ["--patch-size", "1e-3"], "use a patch size of at least"),
    ("a negative seed", ["--seed", "-1"], "argument --seed: expected a whole number >= 0"),
    ("a plot into a missing folder", ["--plot", "nowhere/p.png"], "does not exist"),
    ("steps into a missing folder", ["--steps", "nowhere/s.gif"], "does not exist"),
    # (it refused after writing the image: checked with the other outputs, by argparse)
    ("a plot that is no image", ["--plot", "out/p.gif"], "'.gif' is not an image extension"),
])
def test_hostile_arguments_are_refused_before_the_solve(tmp_path, case, extra, words):
    r, out = _run(tmp_path, BOX, *extra)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and words in lines[0], r.stderr
    assert "np.float64" not in lines[0]
    assert list(out.iterdir()) == []


@pytest.mark.parametrize("exposure", ["1e300"])
def test_an_exposure_past_what_shading_holds_is_named_not_an_internal_array(tmp_path,
                                                                            exposure):
    """``--exposure 1e300`` was refused as "vertex_colors must be ... 7.128e+297": the
    option is named, with the brightest patch it makes and the largest exposure that
    shows, and nothing is written."""
    r, out = _run(tmp_path, BOX, "--exposure", exposure, "--patch-size", "250")
    assert r.returncode == 2, r.stderr
    (line,) = r.stderr.strip().splitlines()
    assert line.startswith(f"glshade: error: exposure {float(exposure):g} makes the "
                           "brightest patch") and "vertex_colors" not in line, line
    largest = float(line.rsplit(" ", 1)[1])
    assert 0 < largest < float(exposure)
    assert list(out.iterdir()) == []


def test_the_plot_may_not_replace_the_image(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    r = subprocess.run([sys.executable, "-m", "glshade", "radiosity", BOX, "-o",
                        str(out / "r.png"), "--plot", str(out / "r.png"), "-q"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "must be different files" in r.stderr
    assert list(out.iterdir()) == []


def test_zero_area_polygons_are_left_out_and_a_vanished_emitter_is_no_emitter(tmp_path):
    wall, flat, lamp = _files(tmp_path)
    only_flat = tmp_path / "a.toml"
    only_flat.write_text(WALLS.format(wall=wall) + LIGHT.format(light=flat))
    r, out = _run(tmp_path, str(only_flat))
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"glshade: error: {only_flat}: the scene "
                                                   "has no emitter (light: 1 of its 1 "), r.stderr
    assert list(out.iterdir()) == []
    # a flat receiver beside a real lamp: left out with a warning; the solve goes on
    both = tmp_path / "b.toml"
    both.write_text(WALLS.format(wall=wall) + LIGHT.format(light=lamp) +
                    WALLS.format(wall=flat).replace('"wall"', '"sliver"'))
    r, out = _run(tmp_path, str(both))
    assert r.returncode == 0, r.stderr
    assert "sliver: 1 of its 1 polygons have no area" in r.stderr
    assert (out / "r.png").exists()


def test_a_scene_with_a_reflectance_above_one_says_it_in_plain_numbers(tmp_path):
    wall, _, lamp = _files(tmp_path)
    scene = tmp_path / "c.toml"
    scene.write_text(WALLS.format(wall=wall).replace("reflectance = [0.5, 0.5, 0.5]",
                                                     "color = [1.2, 1.08, 1.08]\nkd = 1")
                     + LIGHT.format(light=lamp))
    r, _ = _run(tmp_path, str(scene))
    assert r.returncode == 2
    assert f"{scene}: wall: diffuse reflectance kd * color = (1.2, 1.08, 1.08) exceeds 1" \
        in r.stderr, r.stderr


def test_gauss_seidel_reports_the_sweeps_it_made_and_a_dark_exposure_is_said(tmp_path):
    out = tmp_path / "r.png"
    r = subprocess.run([sys.executable, "-m", "glshade", "radiosity", BOX, "-o", str(out),
                        "--size", "32x32", "--patch-size", "200", "--method", "gauss-seidel",
                        "--iterations", "3", "--exposure", "1e-9"], capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    assert "3 sweeps" in r.stdout, r.stdout
    assert "the picture is black at exposure 1e-09" in r.stderr


def test_zero_area_polygons_leave_the_others_as_they_were():
    """Polygons of every size around degenerate ones: the kept faces are exactly the
    original faces of nonzero area, in order (checked face by face here)."""
    import numpy as np

    from glshade import Mesh
    from glshade.radiosity.problem import without_zero_area

    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [3, 0, 0],
                  [0.5, 2, 0], [2, 1, 0.0]])
    faces = [[0, 1, 2, 3], [0, 1, 4], [1, 4, 7, 2, 6], [4, 5, 1], [0, 2, 6]]
    mesh = Mesh(v, faces)
    kept, note = without_zero_area(mesh, "m", 4.0)
    expected = [f for f in faces if mesh.face_areas[faces.index(f)] > 1e-9]
    assert [list(kept.face(k)) for k in range(kept.n_faces)] == expected
    assert "2 of its 5 polygons have no area" in note


ROOM = """[render]
size = [16, 16]
[[mesh]]
source = "primitive:cube"
scale = 2.0
color = [1.0, 1.0, 1.0]
kd = {kd}
ks = 0.0
[[mesh]]
source = "primitive:cube"
scale = 0.2
color = [1.0, 1.0, 1.0]
kd = {kd}
ks = 0.0
emission = [1.0, 1.0, 1.0]
"""


@pytest.mark.parametrize("kd", [1.0, 0.5])
def test_a_room_that_loses_no_light_stops_at_its_cap_and_says_so(kd, tmp_path):
    """A closed room of reflectance 1 around a lamp of reflectance 1: Russian roulette
    never ends a particle (it ran without end); each stops at MAX_BOUNCES, counted -- every
    one of them, and the solution is not converged. A room of 0.5 loses light: none is cut
    (a particle reaches its thousandth surface with odds 0.5^1000)."""
    from glshade import load_scene
    from glshade.radiosity import PatchScene
    from glshade.radiosity.montecarlo import light_trace

    room = tmp_path / "room.toml"
    room.write_text(ROOM.format(kd=kd))
    mc = light_trace(PatchScene.from_scene(load_scene(room).scene, patch_size=1.0), 8, 2, seed=1)
    assert mc.cut == (8 if kd == 1.0 else 0) and mc.converged == (kd != 1.0)


def test_the_command_says_a_capped_monte_carlo_solution_did_not_converge(tmp_path):
    room = tmp_path / "room.toml"
    room.write_text(ROOM.format(kd=1.0))
    out = tmp_path / "r.png"
    r = subprocess.run([sys.executable, "-m", "glshade", "radiosity", str(room), "-o",
                        str(out), "--method", "monte-carlo", "--particles", "16", "-q"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 1, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "did not converge: 16 of 16 particles were still going " \
        "after 1,000 surfaces" in lines[0], r.stderr
    assert out.exists()  # (how far it got)


def test_a_patch_size_past_the_scene_is_warned_of(tmp_path):
    """--patch-size 1e9 made every polygon one patch, lit evenly, without a word: the
    picture is made, with one warning naming the size and the scene's diagonal."""
    r, out = _run(tmp_path, BOX, "--patch-size", "1e9", "--method", "monte-carlo",
                  "--particles", "20000")
    assert r.returncode == 0, r.stderr
    warned = [x for x in r.stderr.splitlines() if x.startswith("glshade: warning:")]
    assert len(warned) == 1 and "a patch size of 1e+09 is more than the scene's whole " \
        "diagonal" in warned[0], r.stderr
    assert (out / "r.png").exists()
