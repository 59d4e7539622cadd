"""CSG and octrees: first-frame and steady frame time of the GLSL ray-casting pass at
512x512 against leaf count (a plate with n - 1 holes, 1..1,024 leaves: past 14 leaves one
program per size class, so a first frame is the data upload, not a compile; below, one per
count of leaves of each kind); rays per second for a 7-leaf tree, against rasterising the
same tree's manifold3d mesh (when the ``csg`` extra is installed; its meshing time apart,
and the ratio also as one thread's CPU time, the steadiest measure) and against the numpy
reference; then octree build time and cells per level at depths 4..9 (boundary cells
should grow ~4x a level, not 8x).

Mesa's on-disk shader cache is switched off here, so a first frame that meets a new
program pays its compile, as in a fresh installation.

Run: ``.venv/bin/python benchmarks/csg_bench.py``.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

os.environ.setdefault("MESA_SHADER_CACHE_DISABLE", "true")  # (before any GL context)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import interleaved, table  # noqa: E402

from glshade import Camera, Mesh, Scene  # noqa: E402
from glshade.cpu.csg import render_solids  # noqa: E402
from glshade.octree import Octree  # noqa: E402
from glshade.render.renderer import Renderer  # noqa: E402
from glshade.solids import Box, Cone, Cylinder, Sphere  # noqa: E402

QUARTER_X = [np.sin(np.pi / 4), 0, 0, np.cos(np.pi / 4)]
SIZE = (512, 512)
CAMERA = Camera.look_at((3.5, 3.0, 5.0), (0, 0.2, 0), fov_y=40)


def tree():
    """Seven leaves: a block bored twice, a ball, a cone and a pin, two boolean kinds."""
    bore = Cylinder(0.35, 3.0).rotated(QUARTER_X)
    return ((Box((3, 1, 2)) - bore.translated((-0.75, 0, 0)) - bore.translated((0.75, 0, 0))
             | Sphere(0.7).translated((0, 0.6, 0)) | Cone(0.3, 0.8).translated((1.2, 0.9, 0)))
            - Cylinder(0.15, 3.0).translated((0, 0.6, 0)) - Box(0.3).translated((-1.5, 0.5, 1)))


def manifold_of(radial: int = 96):
    import manifold3d as m

    M = m.Manifold
    bore = M.cylinder(3.0, 0.35, 0.35, radial, True)  # along z, centred
    block = M.cube([3, 1, 2], True)
    ball = M.sphere(0.7, radial).translate([0, 0.6, 0])
    cone = M.cylinder(0.8, 0.3, 0.0, radial, True).rotate([-90, 0, 0]).translate([1.2, 0.9, 0])
    pin = M.cylinder(3.0, 0.15, 0.15, radial, True).rotate([-90, 0, 0]).translate([0, 0.6, 0])
    cube = M.cube([0.3, 0.3, 0.3], True).translate([-1.5, 0.5, 1])
    part = (block - bore.translate([-0.75, 0, 0]) - bore.translate([0.75, 0, 0])) + ball + cone
    mesh = (part - pin - cube).to_mesh()
    return Mesh(np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts))


def plate(leaves: int):
    """A plate with ``leaves - 1`` holes in a grid (the holes a balanced union)."""
    n = leaves - 1
    side = max(int(np.ceil(np.sqrt(n))), 1)
    holes = [Cylinder(0.9 / side, 1.0).translated(((i % side + 0.5) * 3 / side - 1.5, 0,
                                                   (i // side + 0.5) * 3 / side - 1.5))
             for i in range(n)]
    solid = Box((3.2, 0.3, 3.2))
    if holes:
        cut = holes[0]
        for h in holes[1:]:
            cut = cut | h
        solid = solid - cut
    return solid


def _one_thread_cpu(series: dict) -> list[float]:
    """The least CPU time of 30 interleaved frames of each series, in a child process with
    one rasteriser thread: the steadiest measure on a shared machine (wall times here move
    10-30% between runs)."""
    import json
    import subprocess

    code = (
        "import json, sys, time; sys.path.insert(0, %r); import csg_bench as b; "
        "from glshade import Scene; from glshade.render.renderer import Renderer; "
        "s = Scene(); s.add(b.tree()); m = Scene(); m.add(b.manifold_of()); "
        "r = Renderer(*b.SIZE, samples=0); "
        "fs = [lambda: r.render(s, b.CAMERA), lambda: r.render(m, b.CAMERA)]; "
        "[f() for f in fs]; best = [1e9, 1e9]\n"
        "for _ in range(30):\n"
        "    for i, f in enumerate(fs):\n"
        "        t = time.process_time(); f(); best[i] = min(best[i], time.process_time() - t)\n"
        "r.close(); print(json.dumps(best))") % str(Path(__file__).resolve().parent)
    env = {**os.environ, "LP_NUM_THREADS": "0"}
    env.pop("MESA_SHADER_CACHE_DISABLE", None)  # (steady frames, as a user's)
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def by_leaves() -> None:
    rows = []
    with Renderer(*SIZE, samples=0) as r:
        r.render(Scene(), CAMERA)  # (the context and the mesh programs, apart)
        for leaves in (1, 4, 16, 64, 256, 1024):
            scene = Scene()
            scene.add(plate(leaves))
            t = time.perf_counter()
            r.render(scene, CAMERA)
            first = time.perf_counter() - t
            steady = interleaved({"s": lambda s=scene: r.render(s, CAMERA)}, repeats=3)["s"]
            rows.append((f"{leaves:,}", f"{1000 * first:.0f}", f"{1000 * steady:.1f}"))
    print(f"a plate with holes at {SIZE[0]}x{SIZE[1]}: the tree as data (a cold shader cache)")
    print(table(rows, ("leaves", "first frame ms", "steady ms")))
    print()


def main() -> None:
    by_leaves()
    solid = tree()
    scene = Scene()
    scene.add(solid)
    rows = []
    with Renderer(*SIZE, samples=0) as r:
        series = {"GLSL ray casting": lambda: r.render(scene, CAMERA)}
        try:
            t = time.perf_counter()
            mesh = manifold_of()
            meshing = time.perf_counter() - t
            mesh_scene = Scene()
            mesh_scene.add(mesh)
            series[f"manifold3d mesh ({mesh.n_faces:,} triangles), rasterised"] = \
                lambda: r.render(mesh_scene, CAMERA)
        except ImportError:
            meshing = None
        for fn in series.values():
            fn()
        times = interleaved(series, repeats=15)
        cpu = _one_thread_cpu(series) if meshing is not None else None
    t = time.perf_counter()
    render_solids(scene, CAMERA, SIZE)
    times["numpy reference (float64)"] = time.perf_counter() - t
    rays = SIZE[0] * SIZE[1]
    for name, s in times.items():
        rows.append((name, f"{1000 * s:.1f}", f"{rays / s / 1e6:.2f}"))
    print(f"7-leaf tree at {SIZE[0]}x{SIZE[1]} (medians of 15, interleaved)")
    print(table(rows, ("method", "ms a frame", "Mrays/s")))
    if meshing is None or cpu is None:
        print("manifold3d row left out: pip install 'glshade[csg]'")
    else:
        names = list(times)
        print(f"(manifold3d meshing the tree once: {1000 * meshing:.1f} ms)")
        print(f"ray casting / mesh: {times[names[0]] / times[names[1]]:.2f} (wall, all threads);"
              f" {cpu[0] / cpu[1]:.2f} (one thread, CPU time: {1000 * cpu[0]:.1f} vs "
              f"{1000 * cpu[1]:.1f} ms, the least of 30)")
    rows = []
    for depth in range(4, 10):
        t = time.perf_counter()
        o = Octree.from_solid(solid, depth)
        s = time.perf_counter() - t
        c = o.counts()
        growth = c[-1]["boundary"] / max(c[-2]["boundary"], 1)
        rows.append((str(depth), f"{s:.3f}", f"{sum(x['inside'] for x in c):,}",
                     f"{c[-1]['boundary']:,}", f"{growth:.2f}x",
                     f"{sum(x['bytes'] for x in c) / 2**20:.1f}"))
    print("\noctree of the same tree")
    print(table(rows, ("depth", "seconds", "inside cells", "boundary cells (deepest)",
                       "boundary growth", "MiB")))


if __name__ == "__main__":
    main()
