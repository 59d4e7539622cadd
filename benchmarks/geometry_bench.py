"""Geometry speed: Newell face normals, vertex normals and OBJ loading at 1M faces,
against trimesh in the same run when it is installed.

Run: ``make bench`` (or ``.venv/bin/python benchmarks/geometry_bench.py [--repeats N]``).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import interleaved, table  # noqa: E402

from glshade import Mesh, load_mesh  # noqa: E402
from glshade.geometry import primitives  # noqa: E402

try:
    import trimesh
except ImportError:  # a peer, measured only where installed
    trimesh = None


def grid_quads(n_side: int) -> Mesh:
    """A wavy height field of n_side^2 quads."""
    x, z = np.meshgrid(np.linspace(0, 1, n_side + 1), np.linspace(0, 1, n_side + 1))
    y = 0.05 * np.sin(20 * x) * np.cos(17 * z)
    v = np.stack([x, y, z], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n_side), np.arange(n_side), indexing="ij")
    a = i * (n_side + 1) + j
    quads = np.stack([a, a + 1, a + n_side + 2, a + n_side + 1], -1).reshape(-1, 4)
    return Mesh(v, quads)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()

    quads = grid_quads(1000)  # 1,000,000 quads
    tri, _ = primitives.torus(1, 0.3, 1000, 500).triangulate()  # 1,000,000 triangles
    torus = primitives.torus(1, 0.3, 1000, 500)
    tris = Mesh(torus.vertices, tri)
    v, q = quads.vertices, quads.face_indices.reshape(-1, 4)
    t3 = tri

    tmp = Path(tempfile.mkdtemp())
    obj = tmp / "t1m.obj"
    # written the way common exporters write OBJ (six decimals), not glshade's exact %.17g
    with open(obj, "w") as f:
        f.write(("v %.6f %.6f %.6f\n" * tris.n_vertices) % tuple(tris.vertices.ravel()))
        f.write(("f %d %d %d\n" * tris.n_faces) % tuple((t3 + 1).ravel()))

    rows = []

    def compare(label, ours, theirs):
        series = {"glshade": ours}
        if trimesh is not None and theirs is not None:
            series["trimesh"] = theirs
        med = interleaved(series, args.repeats)
        peer = med.get("trimesh")
        ratio = f"{med['glshade'] / peer:.2f}x" if peer else "-"
        rows.append((label, f"{med['glshade']:.3f}", f"{peer:.3f}" if peer else "-", ratio))

    compare("face normals, 1M triangles",
            lambda: Mesh.from_csr(tris.vertices, tris.face_indices, tris.face_offsets)
            .face_normals,
            (lambda: trimesh.triangles.normals(tris.vertices[t3])) if trimesh else None)
    compare("face normals, 1M quads",
            lambda: Mesh.from_csr(v, quads.face_indices, quads.face_offsets).face_normals,
            (lambda: trimesh.triangles.normals(v[trimesh.geometry.triangulate_quads(q)]))
            if trimesh else None)
    compare("vertex normals, 1M triangles",
            lambda: Mesh.from_csr(tris.vertices, tris.face_indices, tris.face_offsets)
            .vertex_normals,
            (lambda: trimesh.Trimesh(tris.vertices, t3, process=False).vertex_normals)
            if trimesh else None)
    compare("load OBJ, 1M faces (%.0f MB)" % (obj.stat().st_size / 1e6),
            lambda: load_mesh(obj),
            (lambda: trimesh.load(obj, process=False)) if trimesh else None)

    print(f"median of {args.repeats} interleaved runs, seconds; ratio = glshade / trimesh "
          f"(trimesh {'%s' % trimesh.__version__ if trimesh else 'not installed'})")
    print(table(rows, ("task", "glshade s", "trimesh s", "ratio")))
    obj.unlink()


if __name__ == "__main__":
    main()
