"""Ground-truth throughput: frames a second at 640x480 of colour + depth + instance mask for
10 spheres of 10k triangles in view, 50 cameras on a circle -- Renderer.render_many, with
MSAA 4 and without, and the data-set writers (BOP, COCO) on the same views; with depth
exactness beside speed (glshade's depth is at pixel centres and agrees with its mask
everywhere: every pixel with a depth has an instance and the reverse). Peers (pyrender,
PyVista, Open3D) run in venvs of their own (``benchmarks/peers.sh`` makes them under
``.peers/``; ``--peer NAME=PYTHON`` names another), in turn, each in its own process.

    bash benchmarks/peers.sh   # once: .peers/{pyrender,pyvista,open3d}
    .venv/bin/python benchmarks/dataset_bench.py [--frames 50] [--size 640x480]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from _timing import table  # noqa: E402

import glshade  # noqa: E402
from glshade import Camera, Outputs, Scene  # noqa: E402
from glshade.geometry import primitives as P  # noqa: E402


def workload(frames: int):
    """10 spheres of 10,240 triangles (icosphere 4... 5 is 20,480: uv 64x80 is 10,240) on a
    ring, and ``frames`` cameras on a circle around them looking at the centre."""
    scene = Scene()
    ball = P.uv_sphere(64, 80)
    for k in range(10):
        a = 2 * np.pi * k / 10
        scene.add(ball, label=f"ball{k % 3}", translation=(3 * np.cos(a), 0.3 * (k % 2),
                                                            3 * np.sin(a)), scale=0.8)
    cameras = [Camera.look_at((9 * np.cos(t), 4.0, 9 * np.sin(t)), (0, 0, 0))
               for t in np.linspace(0, 2 * np.pi, frames, endpoint=False)]
    return scene, cameras


def glshade_rate(scene, cameras, size, samples) -> tuple[float, int]:
    """Frames a second of render_many (colour, depth, instance), and the pixels where the
    depth and the mask disagree (a depth without an instance or the reverse)."""
    outputs = Outputs.COLOR | Outputs.DEPTH | Outputs.INSTANCE
    with glshade.Renderer(*size, samples=samples) as r:
        for _ in r.render_many(scene, cameras[:2], "phong", outputs=outputs):
            pass  # (programs compiled, meshes uploaded: as a data set's second view finds)
        start = time.perf_counter()
        bad = 0
        for frame in r.render_many(scene, cameras, "phong", outputs=outputs):
            bad += int((np.isfinite(frame.depth) != (frame.instance > 0)).sum())
        return len(cameras) / (time.perf_counter() - start), bad


def cold_rate(scene, cameras, size) -> float:
    """Frames a second of render_many as a writer runs it: a new renderer (its context,
    programs and uploads counted), MSAA 4 -- what a writer's rate is compared with."""
    outputs = Outputs.COLOR | Outputs.DEPTH | Outputs.INSTANCE
    start = time.perf_counter()
    with glshade.Renderer(*size, samples=4) as r:
        for _ in r.render_many(scene, cameras, outputs=outputs):
            pass
    return len(cameras) / (time.perf_counter() - start)


def writer_rate(scene, cameras, size, fmt: str) -> float:
    from glshade import dataset

    write = dataset.write_bop if fmt == "bop" else dataset.write_coco
    with tempfile.TemporaryDirectory() as folder:
        start = time.perf_counter()
        write(scene, folder, cameras=cameras, size=size, progress=False)
        return len(cameras) / (time.perf_counter() - start)


#: the end of every peer's script: ``one(view)`` -> (depth, mask) for each of ``views``,
#: two first (its programs and uploads made), then all of them timed; frame 0's depth and
#: mask saved with the rate
TIMED = """
for view in views[:2]:
    one(view)
start = time.perf_counter()
for view in views:
    depth, mask = one(view)
rate = len(views) / (time.perf_counter() - start)
depth, mask = one(views[0])
np.savez(sys.argv[2], depth=depth, mask=mask, rate=rate)
"""

#: pyrender's side of the workload, run by the peer's own python (PYOPENGL_PLATFORM=egl):
#: the same triangles and cameras from an .npz, colour + depth in one draw and the instance
#: mask in a second (RenderFlags.SEG, a colour a node), its default MSAA 4; frame 0's depth
#: and mask saved for the exactness check
PYRENDER = """
import sys, time, numpy as np, pyrender, trimesh
data = np.load(sys.argv[1])
w, h = int(data["size"][0]), int(data["size"][1])
scene = pyrender.Scene(ambient_light=[0.2, 0.2, 0.2], bg_color=[0, 0, 0, 0])
tm = trimesh.Trimesh(data["vertices"], data["faces"], process=False)
nodes = {}
for k, m in enumerate(data["models"]):
    nodes[scene.add(pyrender.Mesh.from_trimesh(tm, smooth=True), pose=m)] = k + 1
camera = pyrender.PerspectiveCamera(yfov=float(np.radians(data["fov"])), aspectRatio=w / h)
cam_node = scene.add(camera, pose=data["poses"][0])
scene.add(pyrender.DirectionalLight(intensity=3.0), pose=data["poses"][0])
colours = {n: np.array([k, 0, 0], np.uint8) for n, k in nodes.items()}
r = pyrender.OffscreenRenderer(w, h)
def one(pose):
    scene.set_pose(cam_node, pose)
    color, depth = r.render(scene)
    seg, _ = r.render(scene, pyrender.RenderFlags.SEG, colours)
    return depth, seg[..., 0]
views = data["poses"]
""" + TIMED


#: PyVista's side (VTK, off screen; VTK picks EGL without a display): colour and depth
#: (get_image_depth: negative distances along the view axis, NaN on the background) of one
#: plotter, the mask a second plotter's render of the same meshes unlit in id colours; its
#: default theme's MSAA
PYVISTA = """
import sys, time, numpy as np, pyvista as pv
data = np.load(sys.argv[1])
w, h = int(data["size"][0]), int(data["size"][1])
faces = np.hstack([np.full((len(data["faces"]), 1), 3), data["faces"]]).ravel()
ball = pv.PolyData(data["vertices"], faces)
shaded = pv.Plotter(off_screen=True, window_size=(w, h))
masks = pv.Plotter(off_screen=True, window_size=(w, h))
masks.background_color = (0, 0, 0)
for k, m in enumerate(data["models"]):
    shaded.add_mesh(ball.transform(m, inplace=False), color="white", smooth_shading=True)
    masks.add_mesh(ball.transform(m, inplace=False), color=((k + 1) / 255, 0, 0),
                   lighting=False)
def one(eye):
    for pl in (shaded, masks):
        pl.camera.position, pl.camera.focal_point = tuple(eye), (0.0, 0.0, 0.0)
        pl.camera.up, pl.camera.view_angle = (0.0, 1.0, 0.0), float(data["fov"])
        pl.camera.clipping_range = (1.0, 30.0)
    color = shaded.screenshot(return_img=True)
    depth = -shaded.get_image_depth()
    mask = masks.screenshot(return_img=True)[..., 0]
    return np.nan_to_num(depth, nan=0.0), mask
views = data["eyes"]
""" + TIMED

#: Open3D's side (Filament through EGL, EGL_PLATFORM=surfaceless; one renderer a process):
#: colour and depth (render_to_depth_image, z in view space, inf on the background), then
#: the mask: the same meshes unlit in id colours, shown in their place, without
#: post-processing
OPEN3D = """
import sys, time, numpy as np, open3d as o3d
R = o3d.visualization.rendering
data = np.load(sys.argv[1])
w, h = int(data["size"][0]), int(data["size"][1])
r = R.OffscreenRenderer(w, h)
r.scene.set_background([0, 0, 0, 1])
names = []
for k, m in enumerate(data["models"]):
    ball = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(data["vertices"]),
                                     o3d.utility.Vector3iVector(data["faces"]))
    ball.transform(m)
    ball.compute_vertex_normals()
    lit, flat = R.MaterialRecord(), R.MaterialRecord()
    lit.shader, flat.shader = "defaultLit", "defaultUnlit"
    flat.base_color = [(k + 1) * 20 / 255, 0, 0, 1]  # (read as sRGB, written linear:
    # 20 levels apart, ids stay distinct and non-zero -- 1/255 came out 0)
    r.scene.add_geometry(f"lit{k}", ball, lit)
    r.scene.add_geometry(f"id{k}", ball, flat)
    names.append((f"lit{k}", f"id{k}"))
def show(ids):
    for lit, flat in names:
        r.scene.show_geometry(lit, not ids)
        r.scene.show_geometry(flat, ids)
    r.scene.view.set_post_processing(not ids)
def one(eye):
    r.setup_camera(float(data["fov"]), [0, 0, 0], list(eye), [0, 1, 0])
    show(False)
    color = np.asarray(r.render_to_image())
    depth = np.asarray(r.render_to_depth_image(z_in_view_space=True))
    show(True)
    mask = np.asarray(r.render_to_image())[..., 0]
    return np.where(np.isfinite(depth), depth, 0.0), mask
views = data["eyes"]
""" + TIMED

#: each peer's script and the environment it draws headless with
PEERS = {"pyrender": (PYRENDER, {"PYOPENGL_PLATFORM": "egl"}),
         "pyvista": (PYVISTA, {}),
         "open3d": (OPEN3D, {"EGL_PLATFORM": "surfaceless"})}


def peer_rate(name: str, python: str, scene, cameras, size):
    """A peer's frames a second in its own venv, its version, and its frame 0 (depth,
    mask)."""
    import os
    import subprocess

    script, env = PEERS[name]
    ball = scene.models[0].mesh
    tris, _ = ball.triangulate()
    with tempfile.TemporaryDirectory() as folder:
        data, out = Path(folder) / "work.npz", Path(folder) / "out.npz"
        np.savez(data, vertices=ball.vertices, faces=tris, size=np.array(size),
                 models=np.stack([m.transform for m in scene.models]),
                 poses=np.stack([np.linalg.inv(c.view_matrix()) for c in cameras]),
                 eyes=np.stack([c.position for c in cameras]), fov=cameras[0].fov_y)
        run = subprocess.run([python, "-c", script, str(data), str(out)],
                             env={**os.environ, **env}, timeout=1200, cwd=folder,
                             capture_output=True, text=True)
        if run.returncode:
            raise SystemExit(f"{name} ({python}) failed with status {run.returncode}:\n"
                             + "\n".join(run.stderr.splitlines()[-8:]))
        version = subprocess.run(
            [python, "-c", f"from importlib.metadata import version as v; "
             f"print(v({PACKAGES[name]!r}))"], capture_output=True, text=True).stdout.strip()
        got = np.load(out)
        return float(got["rate"]), version, got["depth"], got["mask"]


#: the distribution each peer is installed as (benchmarks/peers.sh makes their venvs)
PACKAGES = {"pyrender": "pyrender", "pyvista": "pyvista", "open3d": "open3d-cpu"}


def exactness(depth, mask, truth) -> tuple[float, float, int]:
    """A peer's depth against glshade's pixel-centre depth where both see a surface
    (median and 99th percentile of the difference), and the pixels where its depth and
    its own mask disagree (a depth but no id, or the reverse)."""
    seen = (depth > 0) & np.isfinite(truth.depth)
    diff = np.abs(depth[seen] - truth.depth[seen])
    return (float(np.median(diff)), float(np.percentile(diff, 99)),
            int(((depth > 0) != (mask > 0)).sum()))


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--frames", type=int, default=50)
    p.add_argument("--size", default="640x480")
    p.add_argument("--peer", action="append", default=[], metavar="NAME=PYTHON",
                   help="a peer (pyrender, pyvista, open3d) and the python of its venv; "
                   "default: those benchmarks/peers.sh made under .peers/")
    p.add_argument("--only-glshade", action="store_true", help="measure no peer")
    args = p.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    peers = {n: str(py) for n in PEERS
             if (py := Path(__file__).parents[1] / ".peers" / n / "bin" / "python").exists()}
    for item in args.peer:
        name, _, python = item.partition("=")
        if name not in PEERS or not python:
            p.error(f"--peer {item!r}: NAME=PYTHON, NAME one of {', '.join(PEERS)}")
        peers[name] = str(Path(python).absolute()) if "/" in python else python
    if args.only_glshade:
        peers = {}
    scene, cameras = workload(args.frames)
    rows = []
    rates = {}
    for samples in (4, 0):
        rate, bad = glshade_rate(scene, cameras, size, samples)
        rates[samples] = rate
        rows.append((f"glshade render_many, MSAA {samples}", f"{rate:.1f}", f"{bad:,}"))
    cold = cold_rate(scene, cameras, size)
    rows.append(("glshade render_many, MSAA 4, a new renderer", f"{cold:.1f}",
                 "(its context, programs and uploads counted, as a writer's are)"))
    for fmt in ("bop", "coco"):
        rate = writer_rate(scene, cameras, size, fmt)
        rows.append((f"glshade write_{fmt} (MSAA 4)", f"{rate:.1f}",
                     f"0 (the masks are the ids'); {cold / rate:.2f}x render_many"))
    truth = None
    best = 0.0
    for name, python in peers.items():
        rate, version, depth, mask = peer_rate(name, python, scene, cameras, size)
        if truth is None:
            with glshade.Renderer(*size, samples=0) as r:
                truth = r.render_frame(scene, cameras[0], "phong",
                                       outputs=Outputs.DEPTH | Outputs.INSTANCE)
        med, p99, bad = exactness(depth, mask, truth)
        best = max(best, rate)
        rows.append((f"{name} {version} (its MSAA, mask a second draw)", f"{rate:.1f}",
                     f"{bad:,} (depth off by median {med:.2g}, 99th pct {p99:.2g})"))
    if best:
        rows.append(("glshade / fastest peer", f"{rates[4] / best:.1f}x at MSAA 4, "
                     f"{rates[0] / best:.1f}x without", f"(fastest {best:.1f})"))
    print(f"{args.frames} frames at {size[0]}x{size[1]}, 10 spheres x 10,240 triangles, "
          f"colour + depth + instance mask")
    print(table(rows, ("renderer", "frames/s", "depth/mask disagreements")))


if __name__ == "__main__":
    main()
