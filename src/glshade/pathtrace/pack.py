"""The path tracer's scene as the tables its GPU program reads (the numpy half of the GL
seam; :class:`glshade.render.passes.pathtrace.GpuPathTracer` uploads them)."""

from __future__ import annotations

import numpy as np

from ..geometry.bvh import build

__all__ = ["pack", "DATA_WIDTH"]

#: texels a row of the scene texture
DATA_WIDTH = 1024


def _bits(values) -> np.ndarray:
    """Integers carried in float32 texels as their bit patterns (floatBitsToInt reads them)."""
    return np.asarray(values, np.int32).view(np.float32)


def pack(scene) -> tuple[np.ndarray, dict]:
    """A :class:`~glshade.pathtrace.scene.TraceScene` as RGBA32F texels ``(rows *
    DATA_WIDTH, 4)`` and the offset of each table (see the shader's header): BVH nodes,
    triangles in BVH order, materials, emitters."""
    if len(scene.triangles):
        bvh = build(scene.triangles)
        order, depth = bvh.order, bvh.depth
        n_nodes = bvh.n_nodes
        nodes = np.zeros((2 * n_nodes, 4), np.float32)
        nodes[0::2, :3], nodes[1::2, :3] = bvh.lo, bvh.hi
        nodes[0::2, 3], nodes[1::2, 3] = _bits(bvh.first), _bits(bvh.count)
    else:  # (a solid alone: one empty box no ray enters)
        order, depth, n_nodes = np.zeros(0, np.int64), 0, 1
        nodes = np.array([[1, 1, 1, 0], [-1, -1, -1, 0]], np.float32)
    tri = scene.triangles[order]
    n_tris = len(tri)
    tris = np.zeros((3 * n_tris, 4), np.float32)
    tris[0::3, :3] = tri[:, 0]
    tris[0::3, 3] = _bits(scene.material[order])
    tris[1::3, :3] = tri[:, 1] - tri[:, 0]
    tris[2::3, :3] = tri[:, 2] - tri[:, 0]
    m = scene.materials
    mats = np.zeros((2 * len(m), 4), np.float32)
    mats[0::2, :3], mats[0::2, 3] = m[:, :3], m[:, 3]
    mats[1::2, :3], mats[1::2, 3] = m[:, 5:8], m[:, 4]
    where = np.empty(n_tris, np.int64)
    where[order] = np.arange(n_tris)  # (a triangle's place in BVH order)
    norms = np.zeros((3 * n_tris if scene.shading is not None else 1, 4), np.float32)
    if scene.shading is not None:
        norms[:, :3] = scene.shading[order].reshape(-1, 3)
    emit = np.zeros((max(len(scene.emitters), 1), 4), np.float32)
    emit[:len(scene.emitters), 0] = scene.emitter_cdf
    emit[:len(scene.emitters), 1] = _bits(where[scene.emitters])
    emit[:len(scene.emitters), 2] = scene.areas[scene.emitters]
    tables = [nodes, tris, mats, emit, norms]
    offsets = np.cumsum([0] + [len(t) for t in tables])
    data = np.concatenate(tables)
    rows = -(-len(data) // DATA_WIDTH)
    data = np.concatenate([data, np.zeros((rows * DATA_WIDTH - len(data), 4), np.float32)])
    layout = {"u_nodes": int(offsets[0]), "u_tris": int(offsets[1]), "u_mats": int(offsets[2]),
              "u_emit": int(offsets[3]), "u_n_emit": len(scene.emitters),
              "u_norms": int(offsets[4]),
              "depth": depth, "nodes": n_nodes, "width": DATA_WIDTH}
    return data, layout
