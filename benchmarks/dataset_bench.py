"""Ground-truth throughput: frames a second at 640x480 of colour + depth + instance mask for
10 spheres of 10k triangles in view, 50 cameras on a circle -- Renderer.render_many, with
MSAA 4 and without, and the data-set writers (BOP, COCO) on the same views; with depth
exactness beside speed (glshade's depth is at pixel centres and agrees with its mask
everywhere: every pixel with a depth has an instance and the reverse). Peers (pyrender,
PyVista, Open3D) run in venvs of their own, where installed: ``--peer NAME=PYTHON``.

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


def writer_rate(scene, cameras, size, fmt: str) -> float:
    from glshade import dataset

    write = dataset.write_bop if fmt == "bop" else dataset.write_coco
    with tempfile.TemporaryDirectory() as folder:
        start = time.perf_counter()
        write(scene, folder, cameras=cameras, size=size, progress=False)
        return len(cameras) / (time.perf_counter() - start)


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
for pose in data["poses"][:2]:
    one(pose)
start = time.perf_counter()
for pose in data["poses"]:
    depth, mask = one(pose)
rate = len(data["poses"]) / (time.perf_counter() - start)
depth, mask = one(data["poses"][0])
np.savez(sys.argv[2], depth=depth, mask=mask, rate=rate)
"""


def peer_pyrender(python: str, scene, cameras, size) -> tuple[float, np.ndarray, np.ndarray]:
    """pyrender's frames a second in its own venv, and its frame 0 (depth, mask)."""
    import os
    import subprocess

    ball = scene.models[0].mesh
    tris, _ = ball.triangulate()
    with tempfile.TemporaryDirectory() as folder:
        data, out = Path(folder) / "work.npz", Path(folder) / "out.npz"
        np.savez(data, vertices=ball.vertices, faces=tris, size=np.array(size),
                 models=np.stack([m.transform for m in scene.models]),
                 poses=np.stack([np.linalg.inv(c.view_matrix()) for c in cameras]),
                 fov=cameras[0].fov_y)
        subprocess.run([python, "-c", PYRENDER, str(data), str(out)], check=True,
                       env={**os.environ, "PYOPENGL_PLATFORM": "egl"}, timeout=1200)
        got = np.load(out)
        return float(got["rate"]), got["depth"], got["mask"]


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
    p.add_argument("--pyrender", metavar="PYTHON", help="a python whose venv has pyrender "
                   "(0.1.45 or pyrender-maintained) and its EGL")
    args = p.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    scene, cameras = workload(args.frames)
    rows = []
    for samples in (4, 0):
        rate, bad = glshade_rate(scene, cameras, size, samples)
        rows.append((f"glshade render_many, MSAA {samples}", f"{rate:.1f}", f"{bad:,}"))
    for fmt in ("bop", "coco"):
        rate = writer_rate(scene, cameras, size, fmt)
        rows.append((f"glshade write_{fmt} (MSAA 4)", f"{rate:.1f}",
                     "0 (the masks are the ids')"))
    if args.pyrender:
        rate, depth, mask = peer_pyrender(args.pyrender, scene, cameras, size)
        with glshade.Renderer(*size, samples=0) as r:
            truth = r.render_frame(scene, cameras[0], "phong",
                                   outputs=Outputs.DEPTH | Outputs.INSTANCE)
        med, p99, bad = exactness(depth, mask, truth)
        best = max(float(rows[0][1]), float(rows[1][1]))
        rows.append(("pyrender 0.1.45 (MSAA 4, mask a second draw)", f"{rate:.1f}",
                     f"{bad:,} (depth off by median {med:.2g}, 99th pct {p99:.2g})"))
        rows.append(("glshade / pyrender", f"{float(rows[0][1]) / rate:.1f}x at MSAA 4, "
                     f"{float(rows[1][1]) / rate:.1f}x without", f"(best {best:.1f})"))
    print(f"{args.frames} frames at {size[0]}x{size[1]}, 10 spheres x 10,240 triangles, "
          f"colour + depth + instance mask")
    print(table(rows, ("renderer", "frames/s", "depth/mask disagreements")))


if __name__ == "__main__":
    main()
