"""``glshade info``: counts, polygon sizes, bounds, area and topology of a mesh."""

from __future__ import annotations

import json

from ..errors import EXIT_OK, UsageError
from ..io.meshes import load_source

__all__ = ["info", "mesh_summary", "topology_summary"]


def mesh_summary(mesh) -> dict:
    """Counts, polygon sizes, bounds and area of a mesh, as plain JSON-able data."""
    import numpy as np

    sizes, counts = np.unique(mesh.face_sizes, return_counts=True)
    return {
        "name": mesh.name,
        "vertices": mesh.n_vertices,
        "faces": mesh.n_faces,
        "edges": mesh.n_edges,
        "polygon_sizes": {int(k): int(c) for k, c in zip(sizes, counts)},
        "bounds": {"min": mesh.bounds[0].tolist(), "max": mesh.bounds[1].tolist()},
        "total_area": mesh.total_area,
        "degenerate_faces": int(len(mesh.degenerate_faces)),
        "euler_characteristic": mesh.n_vertices - mesh.n_edges + mesh.n_faces,
        "signed_volume": mesh.signed_volume(),
    }


def topology_summary(mesh) -> dict:
    """Euler's formula and the validity checks of the mesh's winged-edge structure."""
    from ..geometry.brep import WingedEdge

    w = WingedEdge.from_mesh(mesh, strict=False)
    out = w.euler().as_dict()
    out["problems"] = w.report.message() or None
    return out


def solid_summary(solid, depth: int = 6) -> dict:
    """Volume (Monte Carlo, and the octree's bounds), bounds, leaves and the octree's
    cells and memory per level."""
    from ..geometry.octree import Octree

    volume, error = solid.volume()
    tree = Octree.from_solid(solid, depth)
    inner, outer = tree.volume_bounds()
    b = solid.bounds
    return {"kind": "CSG solid", "leaves": len(solid.leaves()),
            "bounds": {"min": b[0].tolist(), "max": b[1].tolist()},
            "volume": volume, "volume_error": error, "octree_depth": depth,
            "octree_volume_bounds": [inner, outer], "octree_levels": tree.counts()}


def _solid_info(args, solid) -> int:
    s = solid_summary(solid)
    s["source"] = args.mesh
    if args.json:
        print(json.dumps(s, indent=2))
        return EXIT_OK
    lo, hi = s["bounds"]["min"], s["bounds"]["max"]
    print(f"source        {args.mesh}")
    print(f"kind          CSG solid, {s['leaves']} leaves")
    print(f"bounding box  [{', '.join(f'{x:.4g}' for x in lo)}] .. "
          f"[{', '.join(f'{x:.4g}' for x in hi)}]")
    print(f"volume        {s['volume']:.6g} +- {s['volume_error']:.2g} (Monte Carlo); "
          f"octree depth {s['octree_depth']}: {s['octree_volume_bounds'][0]:.6g} .. "
          f"{s['octree_volume_bounds'][1]:.6g}")
    print("octree:  level    inside   outside  boundary     bytes")
    for c in s["octree_levels"]:
        print(f"         {c['level']:>5} {c['inside']:>9,} {c['outside']:>9,} "
              f"{c['boundary']:>9,} {c['bytes']:>9,}")
    return EXIT_OK


def info(args) -> int:
    from ..geometry.solids import Solid
    from .inputs import is_scene_file

    if is_scene_file(args.mesh):
        raise UsageError(f"{args.mesh}: a scene file; glshade info describes one mesh: give "
                         "one of the scene's mesh files (its [[mesh]] source)")
    mesh = load_source(args.mesh)
    if isinstance(mesh, Solid):
        return _solid_info(args, mesh)
    info = mesh_summary(mesh)
    info["source"] = args.mesh
    info["topology"] = topology_summary(mesh)
    if args.json:
        print(json.dumps(info, indent=2))
        return EXIT_OK
    lo, hi = info["bounds"]["min"], info["bounds"]["max"]
    rows = [
        ("source", args.mesh),
        ("vertices", f"{info['vertices']:,}"),
        ("faces", f"{info['faces']:,}"),
        ("edges", f"{info['edges']:,}"),
        ("V - E + F", str(info["euler_characteristic"])),
        ("bounding box", f"[{', '.join(f'{x:.4g}' for x in lo)}] .. "
                         f"[{', '.join(f'{x:.4g}' for x in hi)}]"),
        ("total area", f"{info['total_area']:.6g}"),
        ("signed volume", f"{info['signed_volume']:.6g}"),
        ("degenerate faces", str(info["degenerate_faces"])),
    ]
    width = max(len(k) for k, _ in rows)
    for k, v in rows:
        print(f"{k:<{width}}  {v}")
    print("polygon sizes:")
    total = max(info["faces"], 1)
    for k, c in info["polygon_sizes"].items():
        bar = "#" * max(1, round(40 * c / total))
        print(f"  {k:>4}-gon  {c:>10,}  {bar}")
    t = info["topology"]
    print("topology (winged edge):")
    print("     V       E       F     H    C    G  closed  manifold  oriented  boundary loops")
    g = "?" if t["G"] is None else t["G"]
    print(f"  {t['V']:>4} {t['E']:>7} {t['F']:>7} {t['H']:>5} {t['C']:>4} {g:>4}  "
          f"{'yes' if t['closed'] else 'no':>6}  {'yes' if t['manifold'] else 'no':>8}  "
          f"{'yes' if t['oriented'] else 'no':>8}  {t['boundary_loops']:>14}")
    kind = ("for closed surfaces" if t["closed"] else
             "for surfaces with boundary (each boundary loop counts as a face, B)")
    print(f"  Euler's formula {kind} {'holds' if t['euler_holds'] else 'does NOT hold'}: "
          f"{t['formula']}")
    if t["problems"]:
        print(f"  problems: {t['problems']}")
    return EXIT_OK


