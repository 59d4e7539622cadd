"""Refining a mesh into a smooth one for reference renders: Phong tessellation
(Boubekeur and Alexa 2008). Each triangle is split into ``k^2`` smaller ones whose new
points are pulled towards the tangent planes at the corners, giving a curved surface that
meets the vertex normals; normals are interpolated and renormalised."""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError
from .mesh import Mesh

__all__ = ["phong_tessellate"]


def phong_tessellate(mesh: Mesh, level: int = 4, alpha: float = 0.75) -> Mesh:
    """A finer, curved version of ``mesh``: every triangle of its triangulation becomes
    ``level^2`` triangles (vertices are not shared between source triangles). The result
    carries interpolated vertex normals (``normals_from_file``) and texture coordinates.

    Parameters
    ----------
    mesh : Mesh
        The mesh.
    level : int
        Segments a triangle's side.
    alpha : float
        How far towards the curved surface (0: flat, 1: fully curved).
    """
    if int(level) != level or level < 1:
        raise GeometryError(f"level must be an integer >= 1, got {level!r}")
    k = int(level)
    tri, _ = mesh.triangles
    normals = mesh.normals_from_file if mesh.normals_from_file is not None else \
        mesh.vertex_normals
    # barycentric grid of one triangle: points (i, j) with i + j <= k
    ii, jj = np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij")
    keep = ii + jj <= k
    ii, jj = ii[keep], jj[keep]
    bary = np.stack([k - ii - jj, ii, jj], 1) / k  # (P, 3)
    index = -np.ones((k + 1, k + 1), np.int64)
    index[ii, jj] = np.arange(len(ii))
    small = []
    for i in range(k):
        for j in range(k - i):
            small.append((index[i, j], index[i + 1, j], index[i, j + 1]))
            if i + j < k - 1:
                small.append((index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]))
    corners = np.asarray(small)
    p = mesh.vertices[tri]                      # (T, 3, 3)
    n = normals[tri]
    flat = np.einsum("pc,tcx->tpx", bary, p)   # (T, P, 3) linear points
    # projection of the linear point onto each corner's tangent plane
    d = np.einsum("tpcx,tcx->tpc", flat[:, :, None, :] - p[:, None], n)
    proj = flat[:, :, None, :] - d[..., None] * n[:, None]
    curved = (1 - alpha) * flat + alpha * np.einsum("pc,tpcx->tpx", bary, proj)
    nn = np.einsum("pc,tcx->tpx", bary, n)
    nn /= np.maximum(np.linalg.norm(nn, axis=-1, keepdims=True), 1e-300)
    t = len(tri)
    faces = (corners[None] + (np.arange(t) * len(bary))[:, None, None]).reshape(-1, 3)
    uv = None
    if mesh.uv is not None:  # (texture coordinates interpolated like the points)
        points_uv = np.einsum("pc,tcx->tpx", bary, mesh.uv[mesh.corner_triangles])
        uv = points_uv.reshape(-1, 2)[faces.ravel()]
    colors = None
    corner_colors = mesh.corner_colors
    if corner_colors is not None:  # (colours likewise: a polygon's own on each piece)
        points_color = np.einsum("pc,tcx->tpx", bary, corner_colors[mesh.corner_triangles])
        colors = points_color.reshape(-1, 4)
    return Mesh(curved.reshape(-1, 3), faces, normals=nn.reshape(-1, 3), name=mesh.name,
                uv=uv, colors=colors)
