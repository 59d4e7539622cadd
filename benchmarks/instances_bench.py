"""Instances: frames a second of K copies of a 512-triangle part (a torus, 16 x 16 quads)
at 640x480 Phong, one instanced draw against the same K models added one by one (the same
picture to the byte: tests/render/test_instances.py), and the time to build each scene.
Peers (polyscope, PyVista, pygfx) are not installed here.

    .venv/bin/python benchmarks/instances_bench.py [--counts 1000,10000] [--frames 5]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from _timing import table  # noqa: E402

import glshade  # noqa: E402
from glshade import Camera, Material, Scene  # noqa: E402
from glshade.geometry import primitives as P  # noqa: E402


def placements(k: int) -> tuple[np.ndarray, np.ndarray]:
    """``k`` small parts on a square grid, turned about y, and their colours."""
    side = int(np.ceil(np.sqrt(k)))
    i = np.arange(k)
    t = np.tile(np.eye(4), (k, 1, 1))
    angle = i * 0.37
    c, s = np.cos(angle), np.sin(angle)
    t[:, 0, 0], t[:, 0, 2], t[:, 2, 0], t[:, 2, 2] = c, s, -s, c
    t[:, :3, :3] *= 0.4
    t[:, 0, 3] = (i % side - side / 2) * 1.0
    t[:, 2, 3] = (i // side - side / 2) * 1.0
    rng = np.random.default_rng(0)
    return t, rng.uniform(0.2, 1.0, (k, 3))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--counts", default="1000,10000")
    parser.add_argument("--frames", type=int, default=5)
    args = parser.parse_args()
    part = P.torus(1.0, 0.35, 16, 16)
    r = glshade.Renderer(640, 480)
    rows = []
    for k in (int(x) for x in args.counts.split(",")):
        t, colors = placements(k)
        side = np.sqrt(k)
        camera = Camera.look_at((0.0, 0.9 * side, 0.9 * side), (0, 0, 0), fov_y=50)
        start = time.perf_counter()
        grouped = Scene()
        grouped.add(part, Material(), instances=t, colors=colors)
        build_grouped = time.perf_counter() - start
        start = time.perf_counter()
        single = Scene()
        for placement, colour in zip(t, colors):
            single.add(part, Material(color=tuple(colour)), transform=placement)
        build_single = time.perf_counter() - start
        speeds = {}
        for name, scene in (("instanced", grouped), ("one by one", single)):
            r.render(scene, camera, "phong")  # (compiled, uploaded)
            start = time.perf_counter()
            for _ in range(args.frames):
                r.render(scene, camera, "phong")
            speeds[name] = args.frames / (time.perf_counter() - start)
        same = np.array_equal(r.render(grouped, camera, "phong"),
                              r.render(single, camera, "phong"))
        rows.append((f"{k:,} x {part.triangles[0].shape[0]} tris", f"{build_grouped:.3f}",
                     f"{build_single:.3f}", f"{speeds['instanced']:.2f}",
                     f"{speeds['one by one']:.2f}",
                     f"{speeds['instanced'] / speeds['one by one']:.2f}x", str(same)))
    print(table(rows, ("scene", "build inst. s", "build 1-by-1 s", "inst. fps",
                       "1-by-1 fps", "speed-up", "same bytes")))


if __name__ == "__main__":
    main()
