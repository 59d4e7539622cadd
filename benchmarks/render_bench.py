"""Rendering speed: frames per second (draw + RGBA read-back) at 512x512 and 1024x1024 for
about 1k, 100k and 1M triangles, per shading mode, against the floor -- a bare moderngl
program drawing the same buffers with the same Phong shader -- and against pyrender's
OffscreenRenderer when it is installed. All series run interleaved in one process (the
machine is noisy) and the table shows medians and ratios.

Run: ``.venv/bin/python benchmarks/render_bench.py [--rounds N] [--sizes 512,1024]``.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import moderngl
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import table  # noqa: E402

from glshade import Camera, Mesh  # noqa: E402
from glshade.scene import default_camera  # noqa: E402
from glshade.geometry import primitives  # noqa: E402
from glshade.geometry.transforms import gl_bytes  # noqa: E402
from glshade.render.renderer import Renderer  # noqa: E402
from glshade.render.shaders import assemble  # noqa: E402
from glshade.scene import Material, PointLight, Scene  # noqa: E402

SIZES_TRIANGLES = {"1k": (25, 20), "100k": (250, 200), "1M": (1000, 500)}


def triangle_torus(n, m) -> Mesh:
    t = primitives.torus(1.0, 0.35, n, m)
    tri, _ = t.triangulate()
    return Mesh(t.vertices, tri)


class BareFloor:
    """The same Phong shader and buffers drawn with moderngl directly: no glshade code
    between the frames."""

    def __init__(self, renderer: Renderer, scene: Scene, camera: Camera):
        ctx = renderer.ctx
        self.ctx = ctx
        vs, _ = assemble("smooth.vert")
        fs, _ = assemble("phong.frag")  # the colour-only variant, as Renderer.render uses
        self.prog = ctx.program(vertex_shader=vs, fragment_shader=fs)
        gpu = renderer._gpu_mesh(scene.models[0].mesh)
        self.vao = ctx.vertex_array(self.prog, [(gpu.vbo, "3f 3f", "in_position", "in_normal")],
                                    gpu.ibo, 4)
        size = (renderer.width, renderer.height)
        self.fbo = ctx.framebuffer([ctx.renderbuffer(size, 4)], ctx.depth_renderbuffer(size))
        view = camera.view_matrix()
        p = self.prog
        p["u_model"].write(gl_bytes(np.eye(4)))
        p["u_view"].write(gl_bytes(view))
        p["u_proj"].write(gl_bytes(camera.projection_matrix(size[0] / size[1])))
        # the normal matrix (inverse transpose of the rigid view: the rotation itself), handed
        # to GLSL's column-major mat3 transposed, as the renderer does
        p["u_normal_view"].write(np.ascontiguousarray(view[:3, :3].T.astype("f4")).tobytes())
        p["u_light_count"].value = 1
        pos = np.zeros((8, 4), "f4")
        pos[0] = view @ np.append(scene.lights[0].position, 1)
        p["u_light_pos_view"].write(pos.tobytes())
        col = np.zeros((8, 3), "f4")
        col[0] = 1
        p["u_light_color"].write(col.tobytes())
        att = np.zeros((8, 3), "f4")
        att[:, 0] = 1
        p["u_light_attenuation"].write(att.tobytes())
        p["u_ambient"].value = (1, 1, 1)
        for k, v in (("u_ka", 0.2), ("u_kd", 0.7), ("u_ks", 0.3), ("u_shininess", 32.0)):
            p[k].value = v
        p["u_material_color"].value = (0.8, 0.8, 0.8)

    def frame(self):
        ctx = self.ctx
        self.fbo.use()
        self.fbo.clear(0, 0, 0, 1, depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.vao.render()
        data = self.fbo.read(components=4)
        ctx.disable(moderngl.CULL_FACE)
        return data

    def release(self):
        for o in (self.vao, self.prog, self.fbo):
            o.release()


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
            scene.add_light(PointLight(tuple(camera.position + [2, 3, 0])))
            with r.ctx:
                floor = BareFloor(r, scene, camera)
            series = {m: current(lambda m=m, r=r, scene=scene, camera=camera:
                                 r.render(scene, camera, m))
                      for m in ("flat", "gouraud", "phong")}
            series["floor"] = current(floor.frame)
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
                floor.release()
            row = [f"{size}x{size}", f"{mesh.n_faces:,}"]
            row += [f"{med[m]:.1f}" for m in ("flat", "gouraud", "phong", "floor")]
            row += [f"{med['phong'] / med['floor']:.2f}"]
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
    print(table(rows, ("image", "triangles", "flat", "gouraud", "phong", "bare moderngl",
                       "phong / bare", "pyrender (phong / it)")))


if __name__ == "__main__":
    main()
