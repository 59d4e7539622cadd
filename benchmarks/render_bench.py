"""Rendering speed: frames per second (draw + RGBA read-back) at 512x512 and 1024x1024 for
about 1k, 100k and 1M triangles, per shading mode, against two floors drawing the same
buffers with moderngl directly: "bare" runs glshade's own specialised Phong program with no
glshade code between frames (what the Python side costs), "textbook" a hand-written program
with the textbook per-fragment Phong formula and one directional light (what glshade's
shaders cost). pyrender's OffscreenRenderer runs too when it is installed. All series run
interleaved in one process (the machine is noisy); the table shows medians and ratios, and
the per-frame overhead of glshade's Python at 1k triangles (an 8x8 image, so the GPU's share
is nil).

Run: ``.venv/bin/python benchmarks/render_bench.py [--rounds N] [--sizes 512,1024]``.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import moderngl
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import table  # noqa: E402

from glshade import Camera, Mesh  # noqa: E402
from glshade.scene import default_camera  # noqa: E402
from glshade.render.programs import FLAT_CONSTANTS_PIXELS  # noqa: E402
from glshade.geometry import primitives  # noqa: E402
from glshade.geometry.transforms import gl_bytes  # noqa: E402
from glshade.render.renderer import Renderer  # noqa: E402
from glshade.render.state import DrawState  # noqa: E402
from glshade.options import DrawOptions  # noqa: E402
from glshade.scene import DirectionalLight, Material, Scene  # noqa: E402

SIZES_TRIANGLES = {"1k": (25, 20), "100k": (250, 200), "1M": (1000, 500)}


def triangle_torus(n, m) -> Mesh:
    t = primitives.torus(1.0, 0.35, n, m)
    tri, _ = t.triangulate()
    return Mesh(t.vertices, tri)


TEXTBOOK_VERT = """
#version 330 core
uniform mat4 u_mvp;
in vec3 in_pos;
in vec3 in_norm;
out vec3 v_pos;
out vec3 v_norm;
void main() {
    v_pos = in_pos;
    v_norm = in_norm;
    gl_Position = u_mvp * vec4(in_pos, 1.0);
}
"""
TEXTBOOK_FRAG = """
#version 330 core
uniform vec3 u_eye;
uniform vec3 u_light_dir;
uniform vec3 u_color;
in vec3 v_pos;
in vec3 v_norm;
out vec4 f_color;
void main() {
    vec3 n = normalize(v_norm);
    vec3 v = normalize(u_eye - v_pos);
    float ln = dot(n, u_light_dir);
    vec3 r = 2.0 * ln * n - u_light_dir;
    float spec = ln > 0.0 ? pow(max(dot(r, v), 0.0), 32.0) : 0.0;
    f_color = vec4(0.2 * u_color + 0.7 * max(ln, 0.0) * u_color + 0.3 * spec, 1.0);
}
"""


class Floor:
    """The same buffers drawn by moderngl directly into an RGBA8 + depth framebuffer, read
    back each frame: with glshade's own (specialised) Phong program ("bare": its uniforms
    left as a glshade draw set them), or with the textbook program."""

    def __init__(self, renderer: Renderer, scene: Scene, camera: Camera, textbook: bool):
        ctx = renderer.ctx
        self.ctx = ctx
        gpu = renderer.meshes.gpu_mesh(scene.models[0].mesh)
        if textbook:
            self.prog = ctx.program(vertex_shader=TEXTBOOK_VERT, fragment_shader=TEXTBOOK_FRAG)
            size = (renderer.width, renderer.height)
            mvp = camera.projection_matrix(size[0] / size[1]) @ camera.view_matrix()
            self.prog["u_mvp"].write(gl_bytes(mvp))
            self.prog["u_eye"].value = tuple(camera.position)
            self.prog["u_light_dir"].value = tuple(-np.asarray(scene.lights[0].direction))
            self.prog["u_color"].value = (0.8, 0.8, 0.8)
            self.owned = [self.prog]
            names = ("in_pos", "in_norm")
        else:
            renderer.render(scene, camera, "phong", cull=False)  # sets the program's uniforms
            # (the program that draw used: its key depends on the machine and the mesh)
            flat = renderer.flat_constants and \
                gpu.n_triangles * FLAT_CONSTANTS_PIXELS <= renderer.width * renderer.height
            state = DrawState.of(SimpleNamespace(width=renderer.width, height=renderer.height,
                                                 rows_top_down=True),
                                 scene, camera.with_planes(scene.bounds),
                                 DrawOptions.of("phong", cull=False))
            self.prog = renderer.meshes.program(state.variant, True, flat)
            self.owned = []
            names = ("in_position", "in_normal")
        self.vao = ctx.vertex_array(self.prog, [(gpu.vbo, "3f 3f", *names)], gpu.ibo, 4)
        size = (renderer.width, renderer.height)
        self.fbo = ctx.framebuffer([ctx.renderbuffer(size, 4)], ctx.depth_renderbuffer(size))

    def frame(self):
        ctx = self.ctx
        self.fbo.use()
        self.fbo.clear(0, 0, 0, 1, depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.CULL_FACE)
        self.vao.render()
        return self.fbo.read(components=4)

    def release(self):
        for o in (self.vao, self.fbo, *self.owned):
            o.release()


def python_overhead_ms(backend: str) -> float:
    """Median time of one render of 1k triangles at 8x8 pixels: all but nothing of it is
    the GPU's, the rest is glshade's Python per frame (uniforms, camera, read-back)."""
    mesh = triangle_torus(*SIZES_TRIANGLES["1k"])
    scene = Scene()
    scene.add(mesh, Material())
    scene.add_light(DirectionalLight((-1.0, -1.0, -1.0)))
    with Renderer(8, 8, samples=0, backend=backend) as r:
        base = default_camera(mesh.bounds)
        times = []
        for i in range(300):
            cam = base.orbit([0.0, np.sin(i * 1e-3), 0.0, np.cos(i * 1e-3)])
            t = time.perf_counter()
            r.render(scene, cam, "phong")
            times.append(time.perf_counter() - t)
    return statistics.median(times[50:]) * 1000


def pyrender_series(mesh: Mesh, camera: Camera, size: int):
    import os

    os.environ.setdefault("PYOPENGL_PLATFORM", "egl")
    try:
        import pyrender
        import trimesh
    except ImportError:
        return None
    tm = trimesh.Trimesh(mesh.vertices, mesh.face_indices.reshape(-1, 3), process=False)
    scene = pyrender.Scene()
    scene.add(pyrender.Mesh.from_trimesh(tm, smooth=True))
    cam = pyrender.PerspectiveCamera(yfov=np.radians(camera.fov_y))
    pose = np.linalg.inv(camera.view_matrix())
    scene.add(cam, pose=pose)
    scene.add(pyrender.PointLight(intensity=10.0), pose=pose)
    r = pyrender.OffscreenRenderer(size, size)
    return lambda: r.render(scene), r.delete


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--sizes", default="512,1024")
    ap.add_argument("--meshes", default="1k,100k,1M")
    ap.add_argument("--backend", default="egl")
    ap.add_argument("--seconds", type=float, default=0.3, help="time per series per round")
    ap.add_argument("--tune-malloc", action="store_true",
                    help="pin glibc's malloc thresholds first (glshade.tune_malloc)")
    args = ap.parse_args()
    if args.tune_malloc:
        from glshade.render.context import tune_malloc

        print(f"tune_malloc: {tune_malloc()}", file=sys.stderr)
    rows = []
    info = None
    peers_to_delete = []  # pyrender's clean-up runs last, after every glshade context
    for size in [int(s) for s in args.sizes.split(",")]:
        r = Renderer(size, size, samples=0, backend=args.backend)
        info = info or r.info()

        def current(fn, r=r):
            def run():  # pyrender makes its own EGL context current: take ours back
                with r.ctx:
                    return fn()
            return run

        for label in args.meshes.split(","):
            mesh = triangle_torus(*SIZES_TRIANGLES[label])
            scene = Scene()
            scene.add(mesh, Material())
            camera = default_camera(mesh.bounds)
            scene.add_light(DirectionalLight((-1.0, -1.0, -1.0)))
            with r.ctx:
                bare = Floor(r, scene, camera, textbook=False)
                textbook = Floor(r, scene, camera, textbook=True)
            series = {m: current(lambda m=m, r=r, scene=scene, camera=camera:
                                 r.render(scene, camera, m))
                      for m in ("flat", "gouraud", "phong")}
            series["phong nocull"] = current(lambda r=r, scene=scene, camera=camera:
                                             r.render(scene, camera, "phong", cull=False))
            series["bare"] = current(bare.frame)
            series["textbook"] = current(textbook.frame)
            peer = pyrender_series(mesh, camera, size)
            if peer:
                series["pyrender"] = peer[0]
                peers_to_delete.append(peer[1])
            counts = {}
            for name, fn in series.items():  # warm up, and pick frames per round
                fn()
                t = time.perf_counter()
                fn()
                counts[name] = max(1, int(args.seconds / (time.perf_counter() - t)))
            fps = {name: [] for name in series}
            for _ in range(args.rounds):
                for name, fn in series.items():
                    t = time.perf_counter()
                    for _ in range(counts[name]):
                        fn()
                    fps[name].append(counts[name] / (time.perf_counter() - t))
            med = {k: statistics.median(v) for k, v in fps.items()}
            with r.ctx:
                bare.release()
                textbook.release()
            row = [f"{size}x{size}", f"{mesh.n_faces:,}"]
            row += [f"{med[m]:.1f}" for m in ("flat", "gouraud", "phong", "phong nocull",
                                              "bare", "textbook")]
            row += [f"{med['phong nocull'] / med['bare']:.2f}",
                    f"{med['phong nocull'] / med['textbook']:.2f}",
                    f"{med['phong'] / med['textbook']:.2f}"]
            row += [f"{med['pyrender']:.1f} ({med['phong'] / med['pyrender']:.1f}x)"
                    if "pyrender" in med else "not installed"]
            rows.append(row)
            print(".", end="", flush=True, file=sys.stderr)
        r.ctx.__enter__()  # make ours current to free it; the context goes with it
        r.close()
    # pyrender's own clean-up cannot make its context current once ours are gone; its
    # objects go with the process.
    del peers_to_delete
    print(file=sys.stderr)
    print(f"frames per second with RGBA read-back, no MSAA, median of {args.rounds} "
          f"interleaved rounds; {info['renderer']} via {info['backend']}")
    print(table(rows, ("image", "triangles", "flat", "gouraud", "phong", "phong nocull",
                       "bare", "textbook", "nocull/bare", "nocull/textbook", "phong/textbook",
                       "pyrender (phong / it)")))
    print("(phong culls the hidden half of these closed meshes; nocull/... compares the same "
          "work)")
    print(f"glshade's Python per frame (1k triangles, 8x8): {python_overhead_ms(args.backend):.3f}"
          " ms")


if __name__ == "__main__":
    main()
