"""Polygon normals by Newell's formula, and triangulation of convex and concave polygons.

Newell's formula ``N = sum_k P_k x P_(k+1)`` (``P_(n+1) = P_0``) is exact for concave
polygons, well defined when consecutive vertices are collinear (where the two-edge cross
product is zero), and gives a best-fit normal for a non-planar polygon. For a planar polygon
``|N|`` is twice its area.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._vec import cross
from ..errors import GeometryError
from .tolerance import tol

__all__ = ["newell_normal", "unit_normals", "polygon_area", "convex_mask", "ear_clip",
           "triangulate_groups"]




def newell_of_indexed(vertices: NDArray[np.float64], faces: NDArray[np.int64]):
    """Newell normals of polygons given by indices ``(n, K)`` into ``vertices`` ``(V, 3)``,
    without materialising ``(n, K, 3)`` for triangles and quads."""
    k = faces.shape[1]
    if k == 3:
        p0 = vertices[faces[:, 0]]
        return cross(vertices[faces[:, 1]] - p0, vertices[faces[:, 2]] - p0)
    if k == 4:
        return cross(vertices[faces[:, 2]] - vertices[faces[:, 0]],
                     vertices[faces[:, 3]] - vertices[faces[:, 1]])
    return newell_normal(vertices[faces])


def newell_normal(points: ArrayLike) -> NDArray[np.float64]:
    """Unnormalised Newell normal of polygons.

    Parameters
    ----------
    points : (..., K, 3) array_like
        Vertices of polygons in order, K >= 3 (counter-clockwise seen from the side the
        normal points to).

    Returns
    -------
    normal : (..., 3) float64
        ``sum_k P_k x P_(k+1)``; its length is twice the area of a planar polygon.
    """
    p = np.asarray(points, dtype=np.float64)
    if p.ndim < 2 or p.shape[-1] != 3 or p.shape[-2] < 3:
        raise GeometryError(f"points must have shape (..., K, 3) with K >= 3, got {p.shape}")
    if p.shape[-2] == 3:
        # For a triangle Newell's sum equals one cross product of two edges.
        return cross(p[..., 1, :] - p[..., 0, :], p[..., 2, :] - p[..., 0, :])
    if p.shape[-2] == 4:
        # For a quad it equals the cross product of the diagonals.
        return cross(p[..., 2, :] - p[..., 0, :], p[..., 3, :] - p[..., 1, :])
    # Shift by the first vertex: the sum is translation invariant, and this keeps
    # far-from-origin polygons accurate.
    q = p - p[..., :1, :]
    return cross(q, np.roll(q, -1, axis=-2)).sum(axis=-2)


def unit_normals(
    normals: NDArray[np.float64], scale: float = 1.0
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Normalise rows; (near) zero-length rows become zero and are marked invalid (never NaN).

    ``scale`` is the squared size of the data (a Newell normal is an area), so that the
    degeneracy test does not depend on the units.

    Parameters
    ----------
    normals : ndarray
        ``(n, 3)`` vectors.
    scale : float
        The geometry's size, against which a length counts as zero.

    Returns
    -------
    unit : (n, 3) float64
    valid : (n,) bool
    """
    length = np.sqrt(np.einsum("...i,...i->...", normals, normals))
    valid = length > tol.zero_length * scale
    inverse = np.divide(1.0, length, out=np.zeros_like(length), where=valid)
    return normals * inverse[..., None], valid


def polygon_area(points: ArrayLike) -> NDArray[np.float64]:
    """Area of planar polygons ``(..., K, 3) -> (...)``: half the Newell normal's length.

    Parameters
    ----------
    points : array_like
        ``(..., K, 3)`` the polygons' corners in order.
    """
    return 0.5 * np.linalg.norm(newell_normal(points), axis=-1)


def convex_mask(points: NDArray[np.float64], normal: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Which polygons ``(n, K, 3)`` are convex (no reflex corner) about their normals ``(n, 3)``.

    Collinear corners count as convex, so a fan triangulation stays valid (possibly with
    zero-area triangles) for every polygon marked True.

    Parameters
    ----------
    points : ndarray
        ``(n, K, 3)`` polygons' corners in order.
    normal : ndarray
        ``(n, 3)`` their normals.
    """
    edge = np.roll(points, -1, axis=-2) - points
    turn = np.cross(np.roll(edge, 1, axis=-2), edge)
    side = np.einsum("nkj,nj->nk", turn, normal)
    scale = np.einsum("nkj,nkj->nk", edge, edge).max(axis=-1, initial=0.0)
    return (side >= -tol.convexity * scale[:, None]).all(axis=-1)


def ear_clip(points: NDArray[np.float64], normal: NDArray[np.float64]) -> NDArray[np.int64]:
    """Triangulate ONE simple polygon (convex or concave) by ear clipping.

    This is the slow reference used only for concave polygons; convex ones are fanned in
    bulk. Returns local vertex indices ``(K - 2, 3)``, each triangle wound like the polygon.

    Parameters
    ----------
    points : ndarray
        ``(K, 3)`` one polygon's corners in order.
    normal : ndarray
        ``(3,)`` its normal.
    """
    k = len(points)
    n = np.asarray(normal, dtype=np.float64)
    # Project to the plane most perpendicular to the normal, keeping orientation.
    axis = int(np.argmax(np.abs(n)))
    u, v = [(1, 2), (2, 0), (0, 1)][axis]
    xy = points[:, [u, v]]
    if n[axis] < 0:
        xy = xy[:, ::-1]
    remaining = list(range(k))
    triangles: list[tuple[int, int, int]] = []

    def cross2(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    guard = 0
    while len(remaining) > 3 and guard < 4 * k * k:
        guard += 1
        m = len(remaining)
        clipped = False
        for i in range(m):
            ia, ib, ic = remaining[i - 1], remaining[i], remaining[(i + 1) % m]
            a, b, c = xy[ia], xy[ib], xy[ic]
            if cross2(a, b, c) <= 0:
                continue  # reflex or degenerate corner: not an ear
            inside = False
            for j in remaining:
                if j in (ia, ib, ic):
                    continue
                p = xy[j]
                if cross2(a, b, p) >= 0 and cross2(b, c, p) >= 0 and cross2(c, a, p) >= 0:
                    inside = True
                    break
            if not inside:
                triangles.append((ia, ib, ic))
                remaining.pop(i)
                clipped = True
                break
        if not clipped:
            # Numerically degenerate remainder: drop the flattest corner as a sliver.
            i = min(range(m), key=lambda t: abs(cross2(xy[remaining[t - 1]], xy[remaining[t]],
                                                       xy[remaining[(t + 1) % m]])))
            triangles.append((remaining[i - 1], remaining[i], remaining[(i + 1) % m]))
            remaining.pop(i)
    triangles.append(tuple(remaining))  # type: ignore[arg-type]
    return np.asarray(triangles, dtype=np.int64).reshape(-1, 3)


def triangulate_groups(vertices, size_groups, newell_normals):
    """Triangles ``(T, 3)`` and their source polygons ``(T,)`` for polygons grouped by size
    (``Mesh.size_groups``): convex ones fanned in bulk, concave ones ear clipped.

    Parameters
    ----------
    vertices : ndarray
        ``(V, 3)`` positions.
    size_groups : dict
        ``Mesh.size_groups``: polygon size to (face ids, ``(n, K)`` indices).
    newell_normals : ndarray
        ``(F, 3)`` each face's Newell normal.
    """
    tris, owner = [], []
    for k, (ids, idx) in size_groups.items():
        if k == 3:
            tris.append(idx)
            owner.append(ids)
            continue
        convex = convex_mask(vertices[idx], newell_normals[ids])
        j = np.arange(1, k - 1)
        fan = np.stack([np.zeros_like(j), j, j + 1], axis=1)  # (k-2, 3) local
        cidx = idx[convex]
        tris.append(cidx[:, fan].reshape(-1, 3))
        owner.append(np.repeat(ids[convex], k - 2))
        for f, face in zip(ids[~convex], idx[~convex]):
            local = ear_clip(vertices[face], newell_normals[f])
            tris.append(face[local])
            owner.append(np.full(len(local), f))
    if not tris:
        return np.zeros((0, 3), np.int64), np.zeros(0, np.int64)
    tri = np.concatenate(tris)
    own = np.concatenate(owner)
    order = np.argsort(own, kind="stable")
    return tri[order], own[order]
