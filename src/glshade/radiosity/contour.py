"""The exact factor from a point to a polygon (Lambert's contour integral), for the pairs of
patches too near each other for a few hemicubes to integrate over the shooter.

From a point x with unit normal n, a planar polygon with corners v_k subtends::

    F = 1/(2 pi) abs(sum_k theta_k  n . (a_k x a_k+1) / norm(a_k x a_k+1)),   a_k = v_k - x,

theta_k the angle between a_k and a_k+1 (Sparrow; Cohen and Wallace 4.3). It holds for a
polygon wholly on the front side of x's plane, seen from its own front; so the polygon is
first clipped to the shooter's plane (one plane for every point of a planar shooter) and a
point behind the receiver's plane gets 0 (it sees the receiver's back, which gives nothing).
Repeated corners (the padding of a clipped polygon) are edges of length 0 and add nothing.
"""

from __future__ import annotations

import numpy as np

from .._vec import cross

__all__ = ["clip_to_plane", "point_polygon_factors"]


def clip_to_plane(polygons: np.ndarray, origin: np.ndarray, normal: np.ndarray,
                  ) -> np.ndarray:
    """The part of each polygon (N, K, 3) in front of its plane ``(origin (N, 3), normal
    (N, 3))``: (N, K+1, 3), short results padded by repeating their last corner, all-behind
    polygons collapsed to one point (factor 0). Sutherland-Hodgman against one plane, for
    all polygons at once.

    Parameters
    ----------
    polygons : ndarray
        ``(N, K, 3)``.
    origin : ndarray
        ``(N, 3)`` a point of each plane.
    normal : ndarray
        ``(N, 3)`` each plane's normal.
    """
    n, k = polygons.shape[:2]
    side = np.einsum("nkd,nd->nk", polygons - origin[:, None], normal)
    nxt = np.roll(np.arange(k), -1)
    s0, s1 = side, side[:, nxt]
    p0, p1 = polygons, polygons[:, nxt]
    differ = s0 != s1
    t = np.where(differ, s0 / np.where(differ, s0 - s1, 1.0), 0.0)
    cross = p0 + t[..., None] * (p1 - p0)
    # each edge emits: its start if in front, then the crossing if it changes side
    keep_start = s0 >= 0
    keep_cross = (s0 >= 0) != (s1 >= 0)
    cand = np.stack([p0, cross], axis=2).reshape(n, 2 * k, 3)
    keep = np.stack([keep_start, keep_cross], axis=2).reshape(n, 2 * k)
    out_len = k + 1
    order = np.argsort(~keep, axis=1, kind="stable")[:, :out_len]
    count = keep.sum(axis=1)
    picked = np.take_along_axis(cand, order[..., None], axis=1)
    last = np.take_along_axis(picked, np.maximum(count - 1, 0)[:, None, None]
                              .repeat(3, axis=2), axis=1)
    slot = np.arange(out_len)[None, :]
    out = np.where((slot < count[:, None])[..., None], picked, last)
    return np.where((count > 0)[:, None, None], out, origin[:, None])


def point_polygon_factors(points: np.ndarray, normal: np.ndarray, polygons: np.ndarray,
                          polygon_normals: np.ndarray) -> np.ndarray:
    """Factors (J, S) from points (S, 3) of unit ``normal`` (3,) to each of ``polygons``
    (J, K, 3), whose fronts face ``polygon_normals`` (J, 3), already clipped to the
    points' plane.

    Parameters
    ----------
    points : ndarray
        ``(S, 3)`` on one patch.
    normal : ndarray
        ``(3,)`` its unit normal.
    polygons : ndarray
        ``(J, K, 3)`` the receivers.
    polygon_normals : ndarray
        ``(J, 3)`` their unit normals.
    """
    a = polygons[:, None, :, :] - points[None, :, None, :]      # (J, S, K, 3)
    b = np.roll(a, -1, axis=2)
    c = cross(a, b)
    size = np.sqrt(np.einsum("jskd,jskd->jsk", c, c))
    dot = np.einsum("jskd,jskd->jsk", a, b)
    theta = np.arctan2(size, dot)
    with np.errstate(invalid="ignore", divide="ignore"):
        term = np.where(size > 0, theta * (c @ normal) / size, 0.0)
    f = np.abs(term.sum(axis=2)) / (2 * np.pi)
    front = np.einsum("jsd,jd->js", points[None] - polygons[:, :1], polygon_normals) > 0
    return np.where(front, f, 0.0)
