"""Parametric patches: surface points evaluated per second (Bernstein form, and de
Casteljau for comparison), triangles tessellated per second (uniform levels and adaptive
tolerances, crack-free with exact normals), the adaptive triangle count against the
uniform one that meets the same tolerance, and the frame time of the tessellated teapot on
this GL: the CPU tessellation (the default) against the GL 4.0 tessellation shaders.

Run: ``.venv/bin/python benchmarks/patch_bench.py``.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import interleaved, table  # noqa: E402

from glshade import Camera, Scene  # noqa: E402
from glshade import patches as G  # noqa: E402
from glshade.render.renderer import Renderer  # noqa: E402


def evaluation() -> None:
    t = G.teapot()
    rng = np.random.default_rng(0)
    u, v = rng.random(4096), rng.random(4096)
    small_u, small_v = u[:64], v[:64]
    times = interleaved({"bernstein": lambda: t.evaluate(u, v),
                         "normals": lambda: t.normals(u, v),
                         "de casteljau": lambda: t.evaluate_de_casteljau(small_u, small_v)},
                        repeats=3)
    rows = [("Bernstein points", f"{32 * 4096 / times['bernstein'] / 1e6:.2f}"),
            ("exact normals (2nd derivatives)", f"{32 * 4096 / times['normals'] / 1e6:.2f}"),
            ("de Casteljau points", f"{32 * 64 / times['de casteljau'] / 1e6:.3f}")]
    print("teapot (32 bicubic patches), points a second")
    print(table(rows, ("evaluation", "M points/s")))
    print()


def tessellation() -> None:
    surface = G.named("teapot")
    rows = []
    for level in (4, 8, 16, 32, 64):
        t0 = time.perf_counter()
        tess = G.tessellate(surface, level)
        s = time.perf_counter() - t0
        rows.append((f"uniform level {level}", f"{tess.n_triangles:,}", f"{s * 1000:.0f}",
                     f"{tess.n_triangles / s / 1e6:.2f}"))
    for tol in (1e-2, 1e-3, 1e-4):
        t0 = time.perf_counter()
        tess = G.tessellate(surface, tolerance=tol)
        s = time.perf_counter() - t0
        uniform = int(tess.levels.max())  # (the uniform level that meets it everywhere)
        rows.append((f"adaptive {tol:g} (uniform: level {uniform}, "
                     f"{2 * 32 * uniform * uniform:,} triangles)", f"{tess.n_triangles:,}",
                     f"{s * 1000:.0f}", f"{tess.n_triangles / s / 1e6:.2f}"))
    print("teapot tessellation, crack-free, exact normals")
    print(table(rows, ("levels", "triangles", "ms", "M triangles/s")))
    print()


def frames() -> None:
    """A frame of the teapot at each level: the CPU's mesh (tessellated once, then drawn)
    and the GPU's tessellation shaders (tessellating at every draw), interleaved; and the
    CPU's tessellation time itself."""
    camera = Camera.look_at((4.5, 3.5, 6.0), (0, 1.2, 0))
    teapot = G.teapot()
    rows = []
    with Renderer(512, 512, samples=0) as r:
        for level in (4, 8, 16, 32, 64):
            cpu, gpu = Scene(), Scene()
            cpu.add(G.tessellate(teapot, level).mesh)
            gpu.add(teapot, tessellation="gpu", level=level)
            r.render(cpu, camera)
            r.render(gpu, camera)
            t = interleaved({"cpu": lambda s=cpu: r.render(s, camera),
                             "gpu": lambda s=gpu: r.render(s, camera),
                             "tess": lambda lv=level: G.tessellate(teapot, lv)}, repeats=5)
            rows.append((str(level), f"{2 * 32 * level * level:,}", f"{1000 * t['tess']:.1f}",
                         f"{1000 * t['cpu']:.1f}", f"{1000 * t['gpu']:.1f}",
                         f"{t['gpu'] / t['cpu']:.2f}"))
    print("the teapot at 512x512, phong: CPU tessellation (once) and its frame, against GL 4.0 "
          "tessellation shaders (every frame)")
    print(table(rows, ("level", "triangles", "CPU tess ms", "CPU mesh frame ms",
                       "GPU tess frame ms", "GPU / CPU")))


if __name__ == "__main__":
    evaluation()
    tessellation()
    frames()
