"""Every shader compiles; broken ones name file and line; contexts fail helpfully; both
backends draw the same pixels."""

import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

from glshade import ShaderError
from glshade.modes import ShadingMode
from glshade.render.shaders import PROGRAMS
from glshade.render.shaders import LOOP_BUDGET, ShaderLibrary, assemble, shader_dir

from tests.conftest import BACKEND, ROOT



def test_every_mode_has_a_program_that_compiles(gl_context):
    lib = ShaderLibrary(gl_context)
    try:
        for mode in ShadingMode:
            assert mode in PROGRAMS
            assert lib.program(mode) is lib.program(mode.value)  # compiled once, cached
    finally:
        lib.release()


def test_include_expansion_keeps_line_numbers():
    text, files = assemble("phong.frag")
    assert files[0] == "phong.frag"
    assert "include/lighting.glsl" in files and "include/outputs.glsl" in files
    assert "#include" not in text
    # the one loop budget and the bindings every program is compiled with, then the
    # file's own line 2
    head = text.split("#line 2 0\n")[0].splitlines()
    assert head[0] == "#version 330 core" and f"#define LOOP_BUDGET {LOOP_BUDGET}" in head
    assert all(line.startswith("#define ") for line in head[1:])


def test_broken_shader_names_file_and_line(gl_context, tmp_path):
    root = tmp_path / "shaders"
    shutil.copytree(shader_dir(), root)
    src = (root / "phong.frag").read_text().splitlines()
    line = next(i for i, s in enumerate(src) if "vec3 n = normalize" in s)
    src[line] = "    vec3 n = normalise(v_normal_view);  // typo"
    (root / "broken.frag").write_text("\n".join(src) + "\n")
    lib = ShaderLibrary(gl_context)
    try:
        with pytest.raises(ShaderError) as info:
            lib.compile("smooth.vert", "broken.frag", root=root)
    finally:
        lib.release()
    text = str(info.value)
    assert f"broken.frag:{line + 1}:" in text, text
    assert "normalise(v_normal_view)" in text
    # an error inside an include names the include
    inc = (root / "include" / "lighting.glsl").read_text().replace(
        "float ln = dot(l, n_view);", "float ln = dot(l, n_view)")
    (root / "include" / "lighting.glsl").write_text(inc)
    lib = ShaderLibrary(gl_context)
    try:
        with pytest.raises(ShaderError, match=r"include/lighting\.glsl:\d+"):
            lib.compile("smooth.vert", "phong.frag", root=root)
    finally:
        lib.release()


def test_missing_version_line(tmp_path):
    (tmp_path / "bad.frag").write_text("void main() {}\n")
    with pytest.raises(ShaderError, match="bad.frag:1: the first line must be #version"):
        assemble("bad.frag", tmp_path)


def run_py(code, **env):
    e = dict(os.environ)
    e.update(env)
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=e, cwd=ROOT, timeout=120)


def test_context_error_names_osmesa_reason_and_package():
    code = ("from glshade.render.context import create_context\n"
            "try:\n    create_context()\nexcept Exception as e:\n    print(type(e).__name__)\n"
            "    print(e)\n")
    out = run_py(code, GLSHADE_BACKEND="osmesa", GLSHADE_OSMESA_LIBRARY="/no/libOSMesa.so.8")
    text = out.stdout
    assert text.startswith("ContextError"), out.stderr
    assert "tried osmesa" in text
    assert "cannot load /no/libOSMesa.so.8" in text
    assert "apt-get install libosmesa6" in text


def test_a_missing_egl_device_is_refused_naming_those_present():
    """(An argument error, not a failed backend: auto does not fall back to OSMesa.)"""
    code = ("from glshade.render.context import create_context\n"
            "try:\n    create_context('auto', device=97)\nexcept Exception as e:\n"
            "    print(type(e).__name__); print(e)\n")
    out = run_py(code)
    assert out.stdout.startswith("OptionError"), out.stdout + out.stderr
    assert "EGL device 97 does not exist; present: 0: " in out.stdout


def test_unknown_backend():
    from glshade.render.context import create_context
    from glshade import OptionError

    with pytest.raises(OptionError, match="unknown backend 'vulkan'; choose one of auto, egl"):
        create_context("vulkan")


RENDER_SNIPPET = """
import sys, numpy as np
from glshade import Camera
from glshade.geometry import primitives as P
from glshade.render.renderer import Renderer
from glshade.scene import Scene, Material, PointLight
s = Scene()
s.add(P.teapot(4), Material(color=(0.8, 0.6, 0.4)))
s.add_light(PointLight((4, 5, 6)))
cam = Camera.look_at([4, 3, 6], [0, 1.2, 0])
with Renderer(96, 72, samples=0, backend=sys.argv[1]) as r:
    frames = [r.render(s, cam, m) for m in ("flat", "gouraud", "phong")]
    assert r.backend == sys.argv[1]
np.save(sys.argv[2], np.stack(frames))
"""


def test_both_backends_give_the_same_image(tmp_path):
    """One backend per process: render with each in its own subprocess."""
    images = {}
    for backend in ("egl", "osmesa"):
        path = tmp_path / f"{backend}.npy"
        out = subprocess.run([sys.executable, "-c", RENDER_SNIPPET, backend, str(path)],
                             capture_output=True, text=True, cwd=ROOT, timeout=120)
        assert out.returncode == 0, out.stderr
        images[backend] = np.load(path).astype(int)
    assert (images["egl"][..., :3].sum(-1) > 0).mean() > 0.2  # real pixels, not blank
    assert np.abs(images["egl"] - images["osmesa"]).max() <= 1


def test_doctor_reports_backends():
    out = subprocess.run([sys.executable, "-m", "glshade", "doctor"], capture_output=True,
                         text=True, cwd=ROOT, timeout=120)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "renderer" in out.stdout and f"{BACKEND}" in out.stdout
    assert "egl      ok" in out.stdout


def test_a_context_used_from_another_thread_is_refused_with_the_reason(gl_context):
    """A GL context stays current on the thread that made it (EGL cannot make it current on
    a second one: draws there would go nowhere), so a draw from another thread -- a
    notebook kernel answers widget messages on one -- is a clear error, not a blank image."""
    import threading

    from glshade import Camera, Scene
    from glshade.errors import ContextError
    from glshade.geometry import primitives
    from glshade.render.renderer import Renderer

    scene = Scene()
    scene.add(primitives.cube())
    camera = Camera.look_at((3, 2, 4), (0, 0, 0))
    with Renderer(32, 32, samples=0, context=gl_context) as r:
        errors = []

        def draw():
            try:
                r.render(scene, camera)
            except ContextError as exc:
                errors.append(str(exc))

        t = threading.Thread(target=draw)
        t.start()
        t.join()
        assert len(errors) == 1 and "belongs to the thread that made it" in errors[0]
        assert (r.render(scene, camera)[..., :3] > 0).any()  # its own thread still draws


def test_releasing_a_bound_framebuffer_leaves_the_next_draw_clean(gl_context):
    """A GL object released while its framebuffer is bound: moderngl would bind the deleted
    name again at the next viewport change (GL_INVALID_OPERATION at the next draw); a
    GLResource rests the context on its own framebuffer first -- for every subclass, and
    for a path tracer made next, whose first act is such a viewport change."""
    from glshade.pathtrace import trace
    from glshade.radiosity import cornell_scene
    from glshade.render.base import GLResource

    class Holder(GLResource):
        def __init__(self, context):
            super().__init__(context)
            ctx = context.ctx
            tex = self._keep(ctx.texture((8, 8), 4))
            self.fbo = self._keep(ctx.framebuffer([tex]))

    ctx = gl_context.ctx
    for _ in range(2):
        holder = Holder(gl_context)
        holder.fbo.use()
        holder.release()
        scene, camera = cornell_scene()
        trace(scene, camera, (8, 8), spp=1, context=gl_context, progress=False)
        assert ctx.error == "GL_NO_ERROR"
