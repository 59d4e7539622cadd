"""Radiosity: what hemicube form factors cost and how good they are, and how long the
Cornell box takes to converge.

1. Form-factor error against the closed form (parallel unit squares one apart: 0.19982)
   and hemicubes per second, for hemicube resolutions 32..512 (the shooter integrated with
   8x8 points, so that what is left is the hemicube's own error).
2. A CPU reference: the double area integral of cos cos / (pi r^2) by Gauss quadrature
   (numpy, no occlusion), its error and time at growing point counts, beside one GPU row.
3. The Cornell box (published data) by progressive refinement to 99% of the energy shot,
   at three patch sizes: patches, shots, hemicubes, seconds.

Run: ``.venv/bin/python benchmarks/radiosity_bench.py``.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import table  # noqa: E402

from glshade import Mesh  # noqa: E402
from glshade.radiosity import (FormFactors, PatchScene, cornell_scene,  # noqa: E402
                               progressive)
from glshade.render.context import create_context  # noqa: E402
from glshade.scene import Material, Scene  # noqa: E402

EXACT = 0.19982489569838746  # Siegel and Howell's closed form (tests/oracle/formfactors.py)
SQUARE = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
FACING = [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]]


def squares() -> PatchScene:
    s = Scene()
    s.add(Mesh(SQUARE, [[0, 1, 2, 3]]), Material(emission=(1, 1, 1)))
    s.add(Mesh(FACING, [[0, 1, 2, 3]]))
    return PatchScene.from_scene(s, 10.0)


def cpu_reference(n: int) -> float:
    """F from the unit square at z=0 to the one at z=1, n x n Gauss points on each."""
    x, w = np.polynomial.legendre.leggauss(n)
    x, w = (x + 1) / 2, w / 2
    px, py = np.meshgrid(x, x, indexing="ij")
    pw = np.outer(w, w).ravel()
    p = np.stack([px.ravel(), py.ravel()], 1)
    d = p[:, None, :] - p[None, :, :]
    r2 = (d ** 2).sum(2) + 1.0  # cos = cos' = 1 / r
    kernel = 1.0 / (np.pi * r2 ** 2)
    return float(pw @ kernel @ pw)


def main() -> None:
    with create_context() as ctx:
        rows = []
        problem = squares()
        for n in (32, 64, 128, 256, 512):
            with FormFactors(problem, n, quadrature=8, context=ctx) as ff:
                t = time.perf_counter()
                f = ff.row(0)[1]
                per = (time.perf_counter() - t) / ff.quadrature[0] ** 2
            rows.append((str(n), f"{f:.5f}", f"{100 * abs(f - EXACT) / EXACT:.3f}%",
                         f"{1 / per:.0f}"))
        print("form factor of parallel unit squares (exact 0.19982), shooter 8x8 points")
        print(table(rows, ("hemicube N", "F", "error", "hemicubes/s")))

        rows = []
        for n in (2, 4, 8, 16, 32):
            t = time.perf_counter()
            f = cpu_reference(n)
            rows.append((f"{n}x{n} a side", f"{f:.5f}", f"{100 * abs(f - EXACT) / EXACT:.4f}%",
                         f"{1000 * (time.perf_counter() - t):.2f}"))
        with FormFactors(problem, 128, context=ctx) as ff:
            t = time.perf_counter()
            f = ff.row(0)[1]
            q = ff.quadrature[0]
            rows.append((f"GPU row, N=128, {q}x{q} points", f"{f:.5f}",
                         f"{100 * abs(f - EXACT) / EXACT:.4f}%",
                         f"{1000 * (time.perf_counter() - t):.2f}"))
        print("\nCPU reference (double Gauss quadrature, no occlusion) against one GPU row")
        print(table(rows, ("method", "F", "error", "ms")))

        rows = []
        scene, _ = cornell_scene()
        for size in (150.0, 100.0, 70.0):
            problem = PatchScene.from_scene(scene, size)
            with FormFactors(problem, 128, context=ctx) as ff:
                t = time.perf_counter()
                sol = progressive(ff, until=0.01)
                s = time.perf_counter() - t
            shots = len(sol.history) - 1
            rows.append((f"{size:g} mm", f"{problem.n_patches:,}", f"{shots:,}",
                         f"{sol.hemicubes:,}", f"{s:.2f}", f"{shots / s:.0f}"))
        print("\nCornell box, progressive refinement to 99% of the energy shot (N=128)")
        print(table(rows, ("patch size", "patches", "shots", "hemicubes", "seconds",
                           "shots/s")))


if __name__ == "__main__":
    main()
