"""``glshade render``: each mode writes a PNG; bad input is one line and exit 2."""


import numpy as np
import pytest
from PIL import Image

from tests.conftest import BACKEND, glshade

pytestmark = pytest.mark.gl  # renders, also in subprocesses: run on every backend




@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong", "normals", "depth"])
def test_each_mode_renders(tmp_path, mode):
    out = tmp_path / f"{mode}.png"
    r = glshade("render", "assets/teapot.obj", "-o", str(out), "--mode", mode, "--size",
                "120x90", "--backend", BACKEND, "--samples", "0")
    assert r.returncode == 0, r.stderr
    img = np.asarray(Image.open(out))
    assert img.shape == (90, 120, 4)
    lit = img[..., :3].max(-1) > 20
    assert 0.05 < lit.mean() < 0.9  # the teapot is in the picture, not filling it


def test_eye_and_light_each_go_where_the_options_say(tmp_path):
    """A plane facing +z, flat-shaded: the centre pixel is the notes' formula at the origin
    with V towards --eye and L towards --light, so moving either is told apart."""
    from glshade import Material
    from tests.oracle.raycast import shade

    def centre(eye, light):
        out = tmp_path / "plane.png"
        r = glshade("render", "primitive:plane", "-o", str(out), "--mode", "flat", "--size",
                    "65x65", "--samples", "0", f"--eye={eye}", "--target", "0,0,0",
                    f"--light={light}", "--backend", BACKEND)
        assert r.returncode == 0, r.stderr
        return np.asarray(Image.open(out))[32, 32, :3] / 255

    def expected(eye, light):
        vec = [np.array([float(x) for x in t.split(",")]) for t in (eye, light)]
        return shade(np.zeros(3), np.array([0.0, 0, 1]), vec[0], [(vec[1], (1, 1, 1))],
                     Material(), (1, 1, 1))

    cases = [("0,0,4", "1,0.5,3"), ("0,0,4", "-2,1,1"), ("0.6,0,4", "1,0.5,3")]
    got = [centre(*c) for c in cases]
    for c, g in zip(cases, got):
        np.testing.assert_allclose(g, expected(*c), atol=1 / 255 + 1e-6)
    assert np.abs(got[0] - got[1]).max() > 0.05  # the light moved
    assert np.abs(got[0] - got[2]).max() > 0.02  # the eye moved (the highlight follows V)


def test_flat_and_phong_differ(tmp_path):
    paths = []
    for mode in ("flat", "phong"):
        p = tmp_path / f"{mode}.png"
        r = glshade("render", "primitive:icosphere:2", "-o", str(p), "--mode", mode, "--size",
                    "64x64", "--backend", BACKEND)
        assert r.returncode == 0, r.stderr
        paths.append(np.asarray(Image.open(p)).astype(int))
    assert np.abs(paths[0] - paths[1]).max() > 10


@pytest.mark.parametrize("args, message", [
    (("--size", "big"), "expected WIDTHxHEIGHT such as 800x600"),
    (("--mode", "toon"), "unknown shading mode 'toon'; choose one of flat"),
    (("--eye", "1,2"), "expected three numbers x,y,z"),
    (("--ka", "2"), "expected a number in [0, 1]"),
    (("--backend", "dx12"), "invalid choice: 'dx12'"),
])
def test_bad_arguments_exit_2_with_one_line(tmp_path, args, message):
    r = glshade("render", "primitive:cube", "-o", str(tmp_path / "x.png"), *args)
    assert r.returncode == 2
    assert message in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "x.png").exists()


def test_malformed_mesh_exits_2(tmp_path):
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    r = glshade("render", str(bad), "-o", str(tmp_path / "x.png"))
    assert r.returncode == 2
    assert str(bad) in r.stderr and "truncated" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == [bad]


def test_an_output_into_a_missing_folder_exits_2_before_any_work(tmp_path):
    """(A path given wrong is bad input, checked first; the system refusing a write --
    permissions, a full disk -- is the environment's: status 1.)"""
    r = glshade("render", "primitive:cube", "-o", str(tmp_path / "no" / "dir" / "x.png"),
                "--size", "16x16", "--backend", BACKEND)
    assert r.returncode == 2
    assert "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_a_blank_render_is_one_warning_line_and_exit_0(tmp_path):
    r = glshade("render", "primitive:cube", "--eye", "0,0,5", "--target", "0,0,10", "-o",
                str(tmp_path / "blank.png"), "--size", "32x32", "--backend", BACKEND)
    assert r.returncode == 0
    assert r.stderr.strip().splitlines() == [
        "glshade: warning: the render is blank: no part of the scene lies in the camera's "
        "view (between its near and far planes, inside its field of view)"]
