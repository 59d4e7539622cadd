"""The exact quadrics as rational Bezier patches: surfaces of revolution about the y axis,
each the tensor product of a profile in the (r, y) plane and four quarter circles (the
rational quadratic with middle weight cos 45 degrees is exactly a circular arc). Every
point evaluated lies on the exact surface (to rounding); normals point outward.
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError
from .bezier import PatchSet

__all__ = ["revolve", "sphere", "cylinder", "cone", "torus", "QUARTER"]

_H = np.sqrt(0.5)
#: a quarter of the unit circle from +x to +z: control points (cos, sin) and weights
QUARTER = (np.array([[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), np.array([1.0, _H, 1.0]))


def _positive(name: str, value) -> float:
    v = float(value)
    if not (np.isfinite(v) and v > 0):
        raise GeometryError(f"{name} must be a positive number, got {value!r}")
    return v


def _quarter(q: int) -> np.ndarray:
    """The quarter circle's control points ``(3, 2)`` turned by ``q`` exact quarter turns."""
    c, s = [(1, 0), (0, 1), (-1, 0), (0, -1)][q % 4]
    return QUARTER[0] @ np.array([[c, s], [-s, c]])


def revolve(profile, weights=None) -> PatchSet:
    """The surface swept by profile curves about the y axis: ``profile (S, m+1, 2)`` Bezier
    control points ``(r, y)`` (r >= 0) with ``weights (S, m+1)``; 4 S patches of degree
    (m, 2), u along the profile, v around the axis (from +x towards +z). The normal
    ``Su x Sv`` points away from the axis where the profile rises.

    Parameters
    ----------
    profile : array_like
        ``(S, m+1, 2)`` Bezier control points ``(r, y)`` of the profile's pieces, r >= 0.
    weights : array_like or None
        ``(S, m+1)`` their weights (None: all 1).
    """
    prof = np.asarray(profile, dtype=np.float64)
    if prof.ndim == 2:
        prof = prof[None]
    w = np.ones(prof.shape[:2]) if weights is None else \
        np.asarray(weights, dtype=np.float64).reshape(prof.shape[:2])
    if (prof[..., 0] < 0).any():
        raise GeometryError("a profile's radii must be >= 0")
    rot = np.stack([_quarter(q) for q in range(4)])  # (4, 3, 2): (cos, sin) around
    r, y = prof[..., 0], prof[..., 1]  # (S, m+1)
    # patch (quarter, profile): P_ij = (r_i cos_j, y_i, r_i sin_j), weight w_i times the arc's
    pts = np.stack([r[None, :, :, None] * rot[:, None, None, :, 0],
                    np.broadcast_to(y[None, :, :, None], (4,) + r.shape + (3,)),
                    r[None, :, :, None] * rot[:, None, None, :, 1]], -1)
    pw = w[None, :, :, None] * QUARTER[1][None, None, None, :]
    return PatchSet(pts.reshape((-1,) + pts.shape[2:]),
                    np.broadcast_to(pw, pts.shape[:-1]).reshape((-1,) + pts.shape[2:4]))


def _arcs(centre, radius, start_quarter: int, quarters: int):
    """Quarter arcs of a circle in the (r, y) plane, counter-clockwise from ``start_quarter``
    (0: from +r): ``(quarters, 3, 2)`` and weights."""
    # (the ring's (cos, sin) read as (r, y), turned by q quarters)
    arcs = [np.asarray(centre) + radius * _quarter(q)
            for q in range(start_quarter, start_quarter + quarters)]
    return np.array(arcs), np.tile(QUARTER[1], (quarters, 1))


def sphere(radius: float = 1.0) -> PatchSet:
    """8 biquadratic rational patches; the poles are collapsed edges.

    Parameters
    ----------
    radius : float
        > 0.
    """
    r = _positive("radius", radius)
    arcs, w = _arcs((0.0, 0.0), r, 3, 2)  # from the south pole up to the north pole
    return revolve(arcs, w)


def _segments(points):
    p = np.asarray(points, dtype=np.float64)
    return np.stack([p[:-1], p[1:]], 1)  # (S, 2, 2): degree-1 profiles


def cylinder(radius: float = 1.0, height: float = 2.0, caps: bool = True) -> PatchSet:
    """The side (4 patches) and, with ``caps``, the two discs (4 each, collapsed at their
    centres), closed; degree (1, 2); centred on the origin along y.

    Parameters
    ----------
    radius : float
        > 0.
    height : float
        > 0, along y, centred at the origin.
    caps : bool
        Close the ends with discs.
    """
    r, h = _positive("radius", radius), _positive("height", height) / 2
    chain = [(r, -h), (r, h)] if not caps else [(0, -h), (r, -h), (r, h), (0, h)]
    return revolve(_segments(chain))


def cone(radius: float = 1.0, height: float = 2.0, cap: bool = True) -> PatchSet:
    """A cone with its apex at y = height/2 over a base of ``radius`` at y = -height/2 (the
    same placement as :class:`glshade.solids.Cone`); degree (1, 2).

    Parameters
    ----------
    radius : float
        The base's radius, > 0.
    height : float
        > 0, along y, centred at the origin.
    cap : bool
        Close the base with a disc.
    """
    r, h = _positive("radius", radius), _positive("height", height) / 2
    chain = [(r, -h), (0, h)] if not cap else [(0, -h), (r, -h), (0, h)]
    return revolve(_segments(chain))


def torus(R: float = 1.0, r: float = 0.25) -> PatchSet:
    """16 biquadratic rational patches: a tube of radius ``r`` about a circle of radius
    ``R`` in the xz plane.

    Parameters
    ----------
    R : float
        The circle's radius, > r.
    r : float
        The tube's radius, > 0.
    """
    R, r = _positive("R", R), _positive("r", r)
    if r >= R:
        raise GeometryError(f"a ring torus needs r < R, got R={R}, r={r}")
    arcs, w = _arcs((R, 0.0), r, 0, 4)
    return revolve(arcs, w)
