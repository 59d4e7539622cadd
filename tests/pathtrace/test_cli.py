"""``glshade pathtrace`` from the command line: a picture and its numbers, one line for a
refused scene, and a Ctrl-C that keeps the image made so far."""

import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from PIL import Image

from ..conftest import BACKEND, ROOT, glshade

pytestmark = pytest.mark.gl


def test_the_cornell_box_from_the_command_line(tmp_path):
    out = tmp_path / "box.png"
    r = glshade("pathtrace", "cornell-box", "-o", str(out), "--spp", "8", "--size", "48x48",
                "--backend", BACKEND, "-q")
    assert r.returncode == 0, r.stderr
    img = np.asarray(Image.open(out))
    assert img.shape[:2] == (48, 48)
    red, green = img[24, 2, :3].astype(int), img[24, 45, :3].astype(int)
    assert red[0] > red[1] and green[1] > green[0]  # (the walls bleed their colours)


def test_the_sobol_sampler_from_the_command_line(tmp_path):
    """--sampler sobol (with --coherent, --control and --adaptive): the summary names them,
    the mean agrees with pcg's within noise, and an unknown sampler is one line naming the
    choices."""
    means = {}
    for sampler in ("pcg", "sobol"):
        out = tmp_path / f"{sampler}.png"
        r = glshade("pathtrace", "cornell-box", "-o", str(out), "--spp", "16", "--size",
                    "32x32", "--backend", BACKEND, "--sampler", sampler, "--exposure", "1",
                    *(["--no-mis"] if sampler == "pcg" else
                      ["--coherent", "--control", "--adaptive"]))
        assert r.returncode == 0, r.stderr
        said = f"{sampler}, coherent, control, adaptive)" if sampler == "sobol" else \
            f"{sampler})"
        assert f"M paths/s, {said}" in r.stdout + r.stderr
        means[sampler] = np.asarray(Image.open(out))[..., :3].astype(float).mean()
    assert abs(means["sobol"] - means["pcg"]) < 0.03 * means["pcg"], means
    r = glshade("pathtrace", "cornell-box", "-o", str(tmp_path / "x.png"), "--sampler",
                "halton")
    assert r.returncode == 2 and "invalid choice: 'halton'" in r.stderr
    assert "Traceback" not in r.stderr


@pytest.mark.parametrize("option", [["--samples", "4"], ["--edges"], ["--shadows", "exact"],
                                    ["--opacity", "0.2"], ["--transparency", "weighted"],
                                    ["--texture-filter", "nearest"]])
def test_a_raster_option_is_refused_by_the_parser(tmp_path, option):
    """An option the path tracer does not apply is one line naming it, exit 2, before any
    work -- never accepted and ignored."""
    r = glshade("pathtrace", "cornell-box", "-o", str(tmp_path / "x.png"), *option)
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert lines[0].startswith(f"glshade pathtrace: error: {option[0]} is an option of the "
                               "raster modes")
    assert list(tmp_path.iterdir()) == []


def test_what_the_tracer_cannot_trace_is_refused_by_name(tmp_path):
    """A map the tracer does not read would be traced without it: the trace refuses it,
    naming the scene and the model (opacity, colour maps and glTF's factors are traced:
    tests/pathtrace/test_materials.py)."""
    from PIL import Image

    Image.new("RGB", (2, 2), (200, 200, 200)).save(tmp_path / "s.png")
    scene = tmp_path / "shiny.toml"
    scene.write_text('[[mesh]]\nname = "tile"\nsource = "primitive:plane"\n'
                     'specular_texture = "s.png"\nemission = [1, 1, 1]\n')
    r = glshade("pathtrace", str(scene), "-o", str(tmp_path / "x.png"), "--spp", "1")
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert str(scene) in lines[0] and "tile: its texture maps (specular) are not traced" \
        in lines[0]
    assert not (tmp_path / "x.png").exists()


def test_an_energy_making_material_is_one_line_naming_the_scene(tmp_path):
    r = glshade("pathtrace", "primitive:cube", "-o", str(tmp_path / "x.png"), "--kd", "0.9",
                "--ks", "0.5", "--color", "1,1,1", "--backend", BACKEND)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "primitive:cube" in lines[0] and "rho_d + k_s" in lines[0]
    assert not (tmp_path / "x.png").exists()


@pytest.mark.once
def test_ctrl_c_keeps_the_image_so_far(tmp_path, spawn):
    out = tmp_path / "long.png"
    proc = spawn([sys.executable, "-m", "glshade", "pathtrace", "cornell-box", "-o", str(out),
                  "--spp", "1000000", "--size", "64x64", "--backend", BACKEND, "-q"], cwd=ROOT,
                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(6)
    assert proc.poll() is None, proc.stderr.read()
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "the image so far is in" in err, err
    assert np.asarray(Image.open(out)).mean() > 10  # (a picture, not a blank)


def test_compare_against_the_path_tracer(tmp_path):
    out = tmp_path / "grid.png"
    r = glshade("compare", "primitive:icosphere:3", "-o", str(out), "--reference", "pathtrace",
                "--spp", "4", "--size", "64x64", "--modes", "gouraud,phong", "--backend",
                BACKEND)
    assert r.returncode == 0, r.stderr
    assert "phong" in r.stdout and out.exists()
    assert np.asarray(Image.open(out)).shape[1] >= 3 * 64  # (two modes and the reference)


@pytest.mark.slow
def test_radiosity_and_phong_against_the_path_tracer_with_per_surface_numbers(tmp_path):
    """compare --modes radiosity,phong --reference pathtrace on the Cornell box: the
    radiosity solution (drawn at exposure 1: radiosities; patches of 60, a 16th of the box's
    diagonal) is far closer to the path tracer than Phong's local model, and per surface the
    two solutions agree within 10%; --patch-size without the radiosity mode is refused."""
    r = glshade("compare", "cornell-box", "-o", str(tmp_path / "grid.png"), "--reference",
                "pathtrace", "--modes", "phong", "--patch-size", "60", "--backend", BACKEND)
    assert r.returncode == 2 and r.stderr.strip() == (
        "glshade: error: --patch-size is the radiosity mode's: add radiosity to --modes"), \
        r.stderr
    assert not (tmp_path / "grid.png").exists()
    r = glshade("compare", "cornell-box", "-o", str(tmp_path / "grid.png"), "--reference",
                "pathtrace", "--modes", "radiosity,phong", "--spp", "16", "--size", "64x64",
                "--patch-size", "60", "--backend", BACKEND, timeout=300)
    assert r.returncode == 0, r.stderr
    rows = {line.split()[0]: line.split() for line in r.stdout.splitlines() if line.strip()}
    assert float(rows["radiosity"][1]) < 0.5 * float(rows["phong"][1])
    for surface in ("floor", "ceiling", "back_wall", "red_wall", "green_wall"):
        assert abs(float(rows[surface][-1].rstrip("%"))) < 10, rows[surface]


def test_a_black_path_traced_picture_says_why(tmp_path):
    """A camera that sees nothing: the picture is written, with the one-line reason render
    gives for a blank image (it was silent), and no 'inf%' error."""
    scene = tmp_path / "away.toml"
    scene.write_text('[[mesh]]\nsource = "primitive:cube"\nemission = [1.0, 1.0, 1.0]\n'
                     '[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 10]\n')
    out = tmp_path / "away.png"
    r = glshade("pathtrace", str(scene), "-o", str(out), "--spp", "2", "--size", "16x16",
                "--backend", BACKEND)
    assert r.returncode == 0 and out.exists(), r.stderr
    assert r.stderr.strip() == ("glshade: warning: the picture is black: no part of the "
                                "scene lies in the camera's view (between its near and far "
                                "planes, inside its field of view)")
    assert "inf%" not in r.stdout and "relative error none (nothing lit)" in r.stdout


@pytest.mark.parametrize("sampler,spp,adaptive", [("pcg", "8", False), ("sobol", "8", False),
                                                  ("sobol", "64", True), ("sobol", "1", False)])
def test_the_error_printed_says_how_it_was_figured(tmp_path, sampler, spp, adaptive):
    """Sobol points' error is figured by halves (adaptive counts too); where no halves
    serve -- one sample a pixel -- the summary says it is the samples' spread, too high
    for them."""
    out = tmp_path / "s.png"
    r = glshade("pathtrace", "primitive:icosphere:2", "-o", str(out), "--spp", spp,
                "--size", "16x16", "--sampler", sampler, "--backend", BACKEND,
                *(["--adaptive"] if adaptive else []))
    assert r.returncode == 0, r.stderr
    caveat = "(figured as for independent samples: Sobol points' own is lower)"
    assert (caveat in r.stdout) == (sampler == "sobol" and spp == "1"), r.stdout
