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


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--frames", type=int, default=50)
    p.add_argument("--size", default="640x480")
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
    print(f"{args.frames} frames at {size[0]}x{size[1]}, 10 spheres x 10,240 triangles, "
          f"colour + depth + instance mask")
    print(table(rows, ("renderer", "frames/s", "depth/mask disagreements")))


if __name__ == "__main__":
    main()
