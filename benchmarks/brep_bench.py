"""Winged-edge build time (and Euler counts) for 10k, 100k and 1M faces.

Run: ``.venv/bin/python benchmarks/brep_bench.py``.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import interleaved, table  # noqa: E402

from glshade.geometry import primitives  # noqa: E402
from glshade.brep import WingedEdge  # noqa: E402

SIZES = {"10k": (125, 80), "100k": (400, 250), "1M": (1250, 800)}


def main() -> None:
    rows = []
    for label, (n, m) in SIZES.items():
        mesh = primitives.torus(1.0, 0.3, n, m)
        med = interleaved({"build": lambda mesh=mesh: WingedEdge.from_mesh(mesh),
                           "euler": lambda mesh=mesh: WingedEdge.from_mesh(mesh).euler()},
                          repeats=3 if label != "1M" else 1)
        r = WingedEdge.from_mesh(mesh).euler()
        rows.append((label, f"{mesh.n_faces:,}", f"{med['build']:.3f}", f"{med['euler']:.3f}",
                     f"V-E+F={r.V - r.E + r.F}, G={r.G}"))
    print("winged-edge build of a quad torus, seconds (median)")
    print(table(rows, ("size", "faces", "build s", "build + euler s", "check")))


if __name__ == "__main__":
    main()
