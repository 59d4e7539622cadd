"""``glshade info``: the numbers, the JSON, and one-line errors with exit status 2."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

ASSETS = Path(__file__).resolve().parents[2] / "assets"


def run(*args):
    return subprocess.run([sys.executable, "-m", "glshade", *args], capture_output=True,
                          text=True)


def test_info_json_cube():
    out = run("info", "primitive:cube", "--json")
    assert out.returncode == 0, out.stderr
    info = json.loads(out.stdout)
    assert (info["vertices"], info["edges"], info["faces"]) == (8, 12, 6)
    assert info["polygon_sizes"] == {"4": 6}
    assert info["total_area"] == pytest.approx(6.0)
    assert info["bounds"] == {"min": [-0.5] * 3, "max": [0.5] * 3}
    assert info["euler_characteristic"] == 2


def test_info_table_on_bundled_asset():
    out = run("info", str(ASSETS / "lprism.obj"))
    assert out.returncode == 0, out.stderr
    assert "6-gon" in out.stdout and "4-gon" in out.stdout
    assert "total area        14" in out.stdout


@pytest.mark.parametrize("args, message", [
    (("info", "missing.obj"), "missing.obj: no such file"),
    (("info", "primitive:sphere"), "unknown primitive 'sphere'"),
    (("info",), "required: MESH"),
    (("frobnicate",), "invalid choice: 'frobnicate'"),
    (("animate", "assets/teapot.obj", "-o", "x.avi"), "x.avi"),
])
def test_bad_input_exits_2_with_one_line(args, message):
    out = run(*args)
    assert out.returncode == 2
    assert message in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1, out.stderr
    assert "Traceback" not in out.stderr


def test_malformed_file_exits_2_naming_the_line(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    out = run("info", str(bad))
    assert out.returncode == 2
    assert f"{bad}:4: face index 9" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1


def test_view_without_display_exits_1_in_one_line():
    """A missing display is the machine's lack, not the user's mistake: exit 1."""
    import os

    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    out = subprocess.run([sys.executable, "-m", "glshade", "view", "primitive:cube"],
                         capture_output=True, text=True, env=env)
    assert out.returncode == 1
    assert "no display" in out.stderr and "xvfb-run" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1


def test_info_on_a_scene_file_lists_models_lights_and_path():
    out = run("info", "assets/scenes/spheres.toml", "--json")
    assert out.returncode == 0, out.stderr
    info = json.loads(out.stdout)
    # icospheres 1, 2 and 4: 20 * 4^level faces, 10 * 4^level + 2 vertices, closed
    assert [m["faces"] for m in info["models"]] == [80, 320, 5120]
    assert [m["vertices"] for m in info["models"]] == [42, 162, 2562]
    assert all(m["closed"] for m in info["models"])
    assert info["models"][0]["bounds"] == {"min": [-3.4, -1.0, -1.0], "max": [-1.4, 1.0, 1.0]}
    assert [x["kind"] for x in info["lights"]] == ["point"]
    box = run("info", "assets/scenes/cornell-box.toml")
    assert box.returncode == 0, box.stderr
    emitting = [line.split()[0] for line in box.stdout.splitlines()[3:11]
                if line.split()[4] == "yes"]
    assert emitting == ["light"]
    assert "a headlight at the camera" in box.stdout


def test_a_reader_that_goes_away_ends_the_output_quietly():
    """`glshade info ... | head -1`: no error about a broken pipe, status 141 as from SIGPIPE."""
    import os

    read, write = os.pipe()
    os.close(read)  # (the reader is already gone)
    try:
        out = subprocess.run([sys.executable, "-m", "glshade", "info", "primitive:torus"],
                             stdout=write, stderr=subprocess.PIPE, text=True, timeout=60)
    finally:
        os.close(write)
    assert (out.returncode, out.stderr) == (141, "")


def test_info_on_a_scene_file_names_each_models_lighting_model(tmp_path):
    (tmp_path / "two.toml").write_text(
        '[[mesh]]\nname = "gold"\nsource = "primitive:uv_sphere"\n'
        'pbr = { base_color = [0.9, 0.6, 0.2], metallic = 1.0, roughness = 0.3 }\n'
        '[[mesh]]\nname = "chalk"\nsource = "primitive:cube"\nkd = 0.5\n'
        '[[light]]\ntype = "spot"\nposition = [0, 4, 0]\ndirection = [0, -1, 0]\n')
    out = run("info", str(tmp_path / "two.toml"))
    assert out.returncode == 0, out.stderr
    assert "gold" in out.stdout and "PBR base (0.9, 0.6, 0.2), metallic 1, roughness 0.3" \
        in out.stdout
    chalk = [line for line in out.stdout.splitlines() if line.startswith("  chalk")][-1]
    assert "PBR" not in chalk and "(0.4, 0.4, 0.4)" in chalk  # (kd 0.5 x the colour 0.8)
    assert "spot        at (0, 4, 0)" in out.stdout
