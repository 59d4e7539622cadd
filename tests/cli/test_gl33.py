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


def _run(env, *args, timeout=300):
    return subprocess.run([sys.executable, "-m", "glshade", *args], capture_output=True,
                          text=True, cwd=ROOT, env=env, timeout=timeout)


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
    (["radiosity", "cornell-box", "--size", "32x32"], None),
]


def test_the_context_is_the_one_asked_for():
    said = _run(_held_to("3.3"), "doctor").stdout
    assert "GL tier 3.3 (OpenGL 3.3)" in said, said


@pytest.mark.parametrize("args, refusal", FEATURES, ids=lambda x: " ".join(x[:4])
                         if isinstance(x, list) else "")
def test_every_feature_draws_or_says_why_at_3_3(tmp_path, args, refusal):
    import re

    out = tmp_path / "out.png"
    r = _run(_held_to("3.3"), *args, "-o", str(out))
    assert "Traceback" not in r.stderr, r.stderr
    if refusal is None:
        assert r.returncode == 0 and out.stat().st_size > 0, r.stderr
        return
    lines = [x for x in r.stderr.splitlines() if x.strip()]
    assert r.returncode == 1 and len(lines) == 1 and re.search(refusal, lines[0]), r.stderr
    assert not out.exists()


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


@pytest.mark.parametrize("scene", ["spider.toml", "glass.toml", "shadows.toml"])
def test_the_example_scenes_draw_on_a_mac_s_gl(tmp_path, scene):
    out = tmp_path / "out.png"
    r = _run(_held_to("4.1"), "render", str(ROOT / "assets" / "scenes" / scene),
             "-o", str(out))
    assert r.returncode == 0 and out.stat().st_size > 0, r.stderr
