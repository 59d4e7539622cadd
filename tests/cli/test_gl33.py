"""Forcing OpenGL 3.3 core (Mesa held to 3.3 and GLSL 3.30, and to none of the later
extensions: what an old laptop's driver or a VM has): every feature either draws or is
refused in one line naming the version it needs and what to use -- exit 1, no traceback.
And forcing 4.1 (a Mac's): the shipped example scenes that refused before draw."""

import os
import subprocess
import sys

import pytest

from tests.conftest import BACKEND, ROOT

pytestmark = [pytest.mark.gl, pytest.mark.once]


def _held_to(version: str) -> dict:
    """The environment of a process whose GL is ``version`` core, as Mesa can make it."""
    text = (ROOT / "scripts" / "mac-gl41.sh").read_text(encoding="utf-8")
    hidden = text.split('MESA_EXTENSION_OVERRIDE="', 1)[1].split('"', 1)[0]
    major, minor = version.split(".")
    return dict(os.environ, MESA_GL_VERSION_OVERRIDE=version,
                MESA_GLSL_VERSION_OVERRIDE=f"{major}{minor}0",
                MESA_EXTENSION_OVERRIDE=hidden + " -GL_ARB_tessellation_shader "
                "-GL_ARB_gpu_shader5 -GL_ARB_gpu_shader_fp64" * (version == "3.3"),
                GLSHADE_BACKEND=BACKEND)


TEAPOT = str(ROOT / "assets" / "teapot.obj")
#: (arguments, the refusal's words or None: it draws)
FEATURES = [
    (["render", TEAPOT, "--mode", "flat"], None),
    (["render", TEAPOT, "--mode", "gouraud"], None),
    (["render", TEAPOT, "--mode", "phong", "--samples", "4"], None),
    (["render", TEAPOT, "--shadows", "exact"], None),
    (["render", TEAPOT, "--shadows", "map"],
     "shadows='map' needs OpenGL 4.0; this GL is 3.3 .*: use shadows='exact'"),
    (["render", TEAPOT, "--opacity", "0.5"], None),
    (["render", TEAPOT, "--opacity", "0.5", "--transparency", "weighted"],
     r"transparency='weighted' .* need OpenGL 4.3; this GL is 3.3"),
    (["render", TEAPOT, "--opacity", "0.5", "--transparency", "blend"], None),
    (["render", "solid:box(2) - sphere(1.2)"], None),
    (["render", "patches:teapot"], None),
    (["render", str(ROOT / "assets" / "scenes" / "glass.toml")], None),
    (["render", str(ROOT / "assets" / "scenes" / "shadows.toml")], None),
    (["pathtrace", "cornell-box", "--spp", "2", "--size", "32x32", "--kernel", "fragment"],
     None),
    (["pathtrace", "cornell-box", "--spp", "2", "--size", "32x32", "--kernel", "compute"],
     r"kernel='compute' needs OpenGL 4.3; this GL is 3.3 .*: use kernel='fragment'"),
    (["radiosity", "cornell-box", "--size", "32x32", "--patch-size", "200", "--hemicube", "32"],
     None),
]


#: runs each command line of argv[1] (JSON) in one process, as `glshade` would -- its exit
#: status and what it wrote to stderr -- and prints them as JSON (one process: a GL context
#: a command, without a Python start each)
_COMMANDS = """
import contextlib, io, json, sys, traceback
from glshade.cli import main
out = []
for args in json.loads(sys.argv[1]):
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        try:
            code = main(args)
        except BaseException:
            code, _ = 99, traceback.print_exc()
    out.append([code, err.getvalue()])
print(json.dumps(out))
"""


def test_every_feature_draws_or_says_why_at_3_3(tmp_path):
    import json
    import re

    runs = [[*args, "-o", str(tmp_path / f"{k}.png")] for k, (args, _) in enumerate(FEATURES)]
    r = subprocess.run([sys.executable, "-c", _COMMANDS, json.dumps([["doctor"], *runs])],
                       capture_output=True, text=True, cwd=ROOT, env=_held_to("3.3"),
                       timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    (doctor_code, _), *results = json.loads(r.stdout.strip().splitlines()[-1])
    assert doctor_code == 0 and "GL tier 3.3 (OpenGL 3.3)" in r.stdout, r.stdout[-2000:]
    for k, ((args, refusal), (code, err)) in enumerate(zip(FEATURES, results)):
        what = " ".join(args[:6])
        assert "Traceback" not in err, (what, err)
        out = tmp_path / f"{k}.png"
        if refusal is None:
            assert code == 0 and out.stat().st_size > 0, (what, err)
            continue
        lines = [x for x in err.splitlines() if x.strip()]
        assert code == 1 and len(lines) == 1 and re.search(refusal, lines[0]), (what, err)
        assert not out.exists(), what


def test_gpu_tessellation_says_why_at_3_3(tmp_path):
    code = ("import glshade\nfrom glshade.patches import teapot\ns = glshade.Scene()\n"
            "s.add(teapot(), tessellation='gpu')\ns.add_light(glshade.PointLight((4, 5, "
            "6)))\nc = glshade.Camera.look_at((4, 3, 5), (0, 1, 0))\n"
            "with glshade.Renderer(32, 24) as r:\n    r.render(s, c)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       env=_held_to("3.3"), cwd=tmp_path, timeout=300)
    assert r.returncode != 0
    assert "GPU tessellation needs OpenGL 4.0; this GL is 3.3" in r.stderr.splitlines()[-1], \
        r.stderr


def test_the_example_scenes_draw_on_a_mac_s_gl(tmp_path):
    import json

    scenes = ["spider.toml", "glass.toml", "shadows.toml"]
    runs = [["render", str(ROOT / "assets" / "scenes" / name), "-o", str(tmp_path / f"{name}.png")]
            for name in scenes]
    r = subprocess.run([sys.executable, "-c", _COMMANDS, json.dumps(runs)], capture_output=True,
                       text=True, cwd=ROOT, env=_held_to("4.1"), timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    for name, (code, err) in zip(scenes, json.loads(r.stdout.strip().splitlines()[-1])):
        assert code == 0 and (tmp_path / f"{name}.png").stat().st_size > 0, (name, err)
