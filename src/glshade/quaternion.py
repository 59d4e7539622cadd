"""Quaternions as in the course notes, vectorized over leading dimensions.

Layout is scalar LAST: ``q = [x, y, z, w] = x i + y j + z k + w O``, where ``O`` is the
identity (the mass-point at the origin), as in the notes, pyrr and scipy. Every function
takes arrays shaped ``(..., 4)`` (quaternions) and ``(..., 3)`` (vectors) and broadcasts.

The product is equation (3.7) of the notes::

    (a O + u)(b O + v) = (a b - u.v) O + (a v + b u + u x v)

Sandwiching ``v -> q v q*`` with ``q(N, phi) = cos(phi/2) O + sin(phi/2) N`` rotates ``v`` by
``phi`` about the unit axis ``N`` (right-hand rule); with any non-zero ``q`` it rotates by
``q``'s direction and scales by ``|q|^2`` (Theorem 3.1: every conformal map of vectors).
``q`` and ``-q`` are the same rotation.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._vec import cross
from .errors import GeometryError

__all__ = [
    "multiply", "conjugate", "norm", "normalize", "inverse", "dot", "identity", "canonical",
    "from_axis_angle", "to_axis_angle", "rotate", "conformal", "mirror", "scale", "compose",
    "transform_points", "mirror_points", "to_matrix", "from_matrix", "slerp", "exp", "log",
    "angle_between", "spline", "squad", "same_hemisphere",
]

Array = NDArray[np.float64]


def _q(q: ArrayLike, name: str = "q") -> Array:
    a = np.asarray(q, dtype=np.float64)
    if a.shape[-1:] != (4,):
        raise GeometryError(f"{name} must have shape (..., 4) [x, y, z, w], got {a.shape}")
    return a


def _v(v: ArrayLike, name: str = "v") -> Array:
    a = np.asarray(v, dtype=np.float64)
    if a.shape[-1:] != (3,):
        raise GeometryError(f"{name} must have shape (..., 3), got {a.shape}")
    return a


def _dot3(a, b):
    return np.einsum("...i,...i->...", a, b)


def identity(shape: tuple[int, ...] = ()) -> Array:
    """The identity quaternion ``O`` = [0, 0, 0, 1], broadcast to ``shape + (4,)``.

    Parameters
    ----------
    shape : tuple of int
        The leading shape of the result.
    """
    q = np.zeros(tuple(shape) + (4,))
    q[..., 3] = 1.0
    return q


def multiply(p: ArrayLike, q: ArrayLike) -> Array:
    """Quaternion product ``p q`` by equation (3.7); not commutative.

    Parameters
    ----------
    p, q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, broadcast against each other.
    """
    p, q = _q(p, "p"), _q(q, "q")
    a, u = p[..., 3], p[..., :3]
    b, v = q[..., 3], q[..., :3]
    out = np.empty(np.broadcast_shapes(p.shape, q.shape))
    out[..., 3] = a * b - _dot3(u, v)
    out[..., :3] = a[..., None] * v + b[..., None] * u + cross(u, v)
    return out


def compose(*qs: ArrayLike) -> Array:
    """The product ``qs[0] qs[1]`` and so on to ``qs[-1]``: sandwiching with it applies
    the LAST one first, as with matrix products.

    Parameters
    ----------
    *qs : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, applied last to first (as matrices are).
    """
    if not qs:
        return identity()
    out = _q(qs[0])
    for q in qs[1:]:
        out = multiply(out, q)
    return out


def conjugate(q: ArrayLike) -> Array:
    """``q* = w O - (x i + y j + z k)``.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``.
    """
    q = _q(q)
    return q * np.array([-1.0, -1.0, -1.0, 1.0])


def dot(p: ArrayLike, q: ArrayLike) -> Array:
    """4-D dot product; the cosine of the angle between unit quaternions.

    Parameters
    ----------
    p, q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, broadcast against each other.
    """
    return np.einsum("...i,...i->...", _q(p, "p"), _q(q, "q"))


def norm(q: ArrayLike) -> Array:
    """``|q|``, shape ``(...)``.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``.
    """
    q = _q(q)
    return np.sqrt(np.einsum("...i,...i->...", q, q))


def normalize(q: ArrayLike) -> Array:
    """``q / |q|``; raises for a zero quaternion.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, none zero.
    """
    if isinstance(q, np.ndarray) and q.shape == (4,) or \
            isinstance(q, (list, tuple)) and len(q) == 4:  # one (a camera's): plain floats
        x, y, z, w = (float(c) for c in q)
        n = math.hypot(x, y, z, w)  # (no overflow for huge components)
        if not 0 < n < math.inf:
            raise GeometryError("cannot normalize a zero or non-finite quaternion")
        return np.array([x / n, y / n, z / n, w / n])
    q = _q(q)
    with np.errstate(over="ignore", invalid="ignore"):
        big = np.abs(q).max(axis=-1, keepdims=True)  # (scaled first: no overflow)
        scaled = q / np.where(big > 0, big, 1.0)
        lengths = norm(scaled)
    if np.any(lengths == 0) or not np.all(np.isfinite(lengths)):
        raise GeometryError("cannot normalize a zero or non-finite quaternion")
    return scaled / lengths[..., None]


def inverse(q: ArrayLike) -> Array:
    """``q^-1 = q* / |q|^2``; raises for a zero quaternion.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, none zero.
    """
    q = _q(q)
    n2 = np.einsum("...i,...i->...", q, q)
    if np.any(n2 == 0):
        raise GeometryError("a zero quaternion has no inverse")
    return conjugate(q) / n2[..., None]


def canonical(q: ArrayLike) -> Array:
    """The representative with ``w >= 0`` (``q`` and ``-q`` are the same rotation).

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``.
    """
    q = _q(q)
    return np.where(q[..., 3:4] < 0, -q, q)


def from_axis_angle(axis: ArrayLike, angle: ArrayLike) -> Array:
    """``q(N, a) = cos(a/2) O + sin(a/2) N`` with ``N`` the normalised axis; radians.

    Parameters
    ----------
    axis : array_like
        ``(..., 3)`` rotation axes, non-zero (normalised here).
    angle : array_like
        ``(...)`` angles in radians, counter-clockwise looking down the axis.
    """
    axis = _v(axis, "axis")
    length = np.linalg.norm(axis, axis=-1)
    if np.any(length == 0):
        raise GeometryError("the rotation axis must not be the zero vector")
    half = 0.5 * np.asarray(angle, dtype=np.float64)
    n = axis / length[..., None]
    shape = np.broadcast_shapes(n.shape[:-1], half.shape)
    out = np.empty(shape + (4,))
    out[..., :3] = np.sin(half)[..., None] * n
    out[..., 3] = np.cos(half)
    return out


def to_axis_angle(q: ArrayLike) -> tuple[Array, Array]:
    """Unit axis ``(..., 3)`` and angle in ``[0, pi]`` ``(...)`` of the rotation ``q``
    (normalised first). The identity gives the axis ``[1, 0, 0]`` and angle 0.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, rotations (normalised first).
    """
    q = canonical(normalize(q))
    s = np.linalg.norm(q[..., :3], axis=-1)
    angle = 2.0 * np.arctan2(s, q[..., 3])
    axis = np.where(s[..., None] > 0, q[..., :3] / np.where(s > 0, s, 1)[..., None],
                    np.array([1.0, 0.0, 0.0]))
    return axis, angle


def conformal(q: ArrayLike, v: ArrayLike) -> Array:
    """The sandwich ``q v q*`` for any quaternion: rotation by ``q``'s direction and uniform
    scaling by ``|q|^2``. Expanded: ``(w^2 - u.u) v + 2 (u.v) u + 2 w (u x v)``.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, any (not only unit).
    v : array_like
        ``(..., 3)`` vectors.
    """
    q, v = _q(q), _v(v)
    w, u = q[..., 3:4], q[..., :3]
    return (w * w - _dot3(u, u)[..., None]) * v + 2.0 * _dot3(u, v)[..., None] * u + \
        2.0 * w * cross(u, v)


def rotate(q: ArrayLike, v: ArrayLike) -> Array:
    """Rotate vectors ``v`` by the rotation ``q`` (normalised first): ``q v q*``.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, rotations.
    v : array_like
        ``(..., 3)`` vectors, broadcast against ``q``.
    """
    return conformal(normalize(q), v)


def mirror(normal: ArrayLike, v: ArrayLike) -> Array:
    """``N v N``: the mirror image of ``v`` in the plane through the origin perpendicular to
    ``normal`` (normalised first). Equals ``v - 2 (v.N) N``.

    Parameters
    ----------
    normal : array_like
        ``(..., 3)`` the mirror plane's normals, non-zero.
    v : array_like
        ``(..., 3)`` vectors.
    """
    n = _v(normal, "normal")
    length = np.linalg.norm(n, axis=-1, keepdims=True)
    if np.any(length == 0):
        raise GeometryError("the mirror normal must not be the zero vector")
    n = n / length
    v = _v(v)
    return v - 2.0 * _dot3(v, n)[..., None] * n


def scale(c: ArrayLike, v: ArrayLike) -> Array:
    """Sandwich with ``sqrt(c) O``: ``c v``. ``c`` must be >= 0 (a quaternion sandwich
    cannot reverse orientation).

    Parameters
    ----------
    c : array_like
        ``(...)`` factors, >= 0.
    v : array_like
        ``(..., 3)`` vectors.
    """
    c = np.asarray(c, dtype=np.float64)
    if np.any(c < 0):
        raise GeometryError(f"scale factor must be >= 0 for a quaternion sandwich, got {c}")
    root = np.sqrt(c)
    q = np.zeros(root.shape + (4,))
    q[..., 3] = root
    return conformal(q, v)


def transform_points(q: ArrayLike, points: ArrayLike, center: ArrayLike = (0, 0, 0)) -> Array:
    """Conformal map of points about a fixed point ``Q``: ``Q + q (P - Q) q*``.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``.
    points : array_like
        ``(..., 3)`` positions.
    center : array_like
        ``(3,)`` the fixed point ``Q``.
    """
    center = _v(center, "center")
    return center + conformal(q, _v(points, "points") - center)


def mirror_points(normal: ArrayLike, points: ArrayLike, through: ArrayLike = (0, 0, 0)) -> Array:
    """Mirror points in the plane through ``through`` perpendicular to ``normal``.

    Parameters
    ----------
    normal : array_like
        ``(3,)`` the plane's normal, non-zero.
    points : array_like
        ``(..., 3)`` positions.
    through : array_like
        ``(3,)`` a point of the plane.
    """
    through = _v(through, "through")
    return through + mirror(normal, _v(points, "points") - through)


def to_matrix(q: ArrayLike, convention: str = "column") -> Array:
    """Rotation matrix ``(..., 3, 3)`` of ``q`` (normalised first).

    ``convention="column"`` (default) gives ``R`` with ``R @ v == rotate(q, v)``, what GLSL's
    ``mat * vec`` does. ``"row"`` gives the notes' layout for row vectors, ``v' = v R``: the
    transpose.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``.
    convention : str
        ``"column"`` (matrices act on column vectors, ``R @ v``) or ``"row"`` (``v @ R``).
    """
    if convention not in ("column", "row"):
        raise GeometryError(f"convention must be 'column' or 'row', got {convention!r}")
    a = np.asarray(q, dtype=np.float64)
    if a.shape == (4,):  # one quaternion (a camera's, every frame): plain floats
        x, y, z, w = a.tolist()
        n = math.hypot(x, y, z, w)
        if not 0 < n < math.inf:
            raise GeometryError("cannot normalize a zero or non-finite quaternion")
        x, y, z, w = x / n, y / n, z / n, w / n
        r = np.array([[w * w + x * x - y * y - z * z, 2 * (x * y - z * w), 2 * (x * z + y * w)],
                      [2 * (x * y + z * w), w * w - x * x + y * y - z * z, 2 * (y * z - x * w)],
                      [2 * (x * z - y * w), 2 * (y * z + x * w), w * w - x * x - y * y + z * z]])
        return r if convention == "column" else r.T
    x, y, z, w = np.moveaxis(normalize(q), -1, 0)
    r = np.empty(x.shape + (3, 3))
    r[..., 0, 0] = w * w + x * x - y * y - z * z
    r[..., 0, 1] = 2 * (x * y - z * w)
    r[..., 0, 2] = 2 * (x * z + y * w)
    r[..., 1, 0] = 2 * (x * y + z * w)
    r[..., 1, 1] = w * w - x * x + y * y - z * z
    r[..., 1, 2] = 2 * (y * z - x * w)
    r[..., 2, 0] = 2 * (x * z - y * w)
    r[..., 2, 1] = 2 * (y * z + x * w)
    r[..., 2, 2] = w * w - x * x - y * y + z * z
    return r if convention == "column" else np.swapaxes(r, -1, -2)


def from_matrix(r: ArrayLike, convention: str = "column") -> Array:
    """Unit quaternion ``(..., 4)`` (with ``w >= 0``) of rotation matrices ``(..., 3, 3)``.

    Shepperd's method: branch on the largest of ``trace, R00, R11, R22``, so the square root
    is never of a small number; exact for every rotation, 180-degree turns included (where
    the notes' ``sqrt(trace + 1)`` formula divides by zero).

    Parameters
    ----------
    r : array_like
        ``(..., 3, 3)`` rotation matrices.
    convention : str
        ``"column"`` or ``"row"``, as :func:`to_matrix`.
    """
    if convention not in ("column", "row"):
        raise GeometryError(f"convention must be 'column' or 'row', got {convention!r}")
    r = np.asarray(r, dtype=np.float64)
    if r.shape[-2:] != (3, 3):
        raise GeometryError(f"matrices must have shape (..., 3, 3), got {r.shape}")
    if convention == "row":
        r = np.swapaxes(r, -1, -2)
    if r.shape == (3, 3):  # (one matrix, a camera's every frame: plain floats)
        return _from_one_matrix(r.tolist())
    det = np.linalg.det(r)  # (the smallest determinant is the one to name, if any)
    worst = tuple(int(k) for k in np.unravel_index(np.argmin(det), det.shape))
    _check_turns(float(det[worst]), f"matrix {worst}")
    d0, d1, d2 = r[..., 0, 0], r[..., 1, 1], r[..., 2, 2]
    trace = d0 + d1 + d2
    pick = np.argmax(np.stack([trace, d0, d1, d2], -1), axis=-1)
    # four candidate solutions, each using the big diagonal term for its square root
    s_w = np.sqrt(np.maximum(1 + trace, 0)) * 2  # 4 w
    s_x = np.sqrt(np.maximum(1 + d0 - d1 - d2, 0)) * 2  # 4 x
    s_y = np.sqrt(np.maximum(1 - d0 + d1 - d2, 0)) * 2  # 4 y
    s_z = np.sqrt(np.maximum(1 - d0 - d1 + d2, 0)) * 2  # 4 z
    r21_m_r12, r02_m_r20 = r[..., 2, 1] - r[..., 1, 2], r[..., 0, 2] - r[..., 2, 0]
    r10_m_r01, r01_p_r10 = r[..., 1, 0] - r[..., 0, 1], r[..., 0, 1] + r[..., 1, 0]
    r02_p_r20, r12_p_r21 = r[..., 0, 2] + r[..., 2, 0], r[..., 1, 2] + r[..., 2, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        cand = np.stack([
            np.stack([r21_m_r12 / s_w, r02_m_r20 / s_w, r10_m_r01 / s_w, s_w / 4], -1),
            np.stack([s_x / 4, r01_p_r10 / s_x, r02_p_r20 / s_x, r21_m_r12 / s_x], -1),
            np.stack([r01_p_r10 / s_y, s_y / 4, r12_p_r21 / s_y, r02_m_r20 / s_y], -1),
            np.stack([r02_p_r20 / s_z, r12_p_r21 / s_z, s_z / 4, r10_m_r01 / s_z], -1),
        ], -2)
    q = np.take_along_axis(cand, pick[..., None, None], axis=-2)[..., 0, :]
    return canonical(q / np.linalg.norm(q, axis=-1, keepdims=True))


def _check_turns(det: float, name: str = "the matrix") -> None:
    if not det > 0:  # a mirror, or a degenerate frame, has no quaternion: say so
        raise GeometryError(f"{name} is not a rotation: its determinant is {det:.3g} (a "
                            "mirror or a flat frame); a quaternion turns, it cannot mirror "
                            "-- quaternion.mirror(normal, v) sandwiches a vector instead")


def _from_one_matrix(m) -> Array:
    """Shepperd's method for one matrix (nested lists) in plain floats: a camera is made
    every frame, and numpy's per-call overhead would dwarf the arithmetic."""
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = m
    _check_turns(r00 * (r11 * r22 - r12 * r21) - r01 * (r10 * r22 - r12 * r20)
                 + r02 * (r10 * r21 - r11 * r20))
    trace = r00 + r11 + r22
    big = max(trace, r00, r11, r22)
    if big == trace:
        s = math.sqrt(max(1 + trace, 0.0)) * 2
        q = ((r21 - r12) / s, (r02 - r20) / s, (r10 - r01) / s, s / 4)
    elif big == r00:
        s = math.sqrt(max(1 + r00 - r11 - r22, 0.0)) * 2
        q = (s / 4, (r01 + r10) / s, (r02 + r20) / s, (r21 - r12) / s)
    elif big == r11:
        s = math.sqrt(max(1 - r00 + r11 - r22, 0.0)) * 2
        q = ((r01 + r10) / s, s / 4, (r12 + r21) / s, (r02 - r20) / s)
    else:
        s = math.sqrt(max(1 - r00 - r11 + r22, 0.0)) * 2
        q = ((r02 + r20) / s, (r12 + r21) / s, s / 4, (r10 - r01) / s)
    n = math.sqrt(sum(c * c for c in q))
    sign = -1.0 if q[3] < 0 else 1.0
    return np.array([sign * c / n for c in q])


def angle_between(p: ArrayLike, q: ArrayLike) -> Array:
    """Rotation angle (radians, in [0, pi]) taking ``p`` to ``q``; sign-blind, accurate for
    nearby and nearly opposite rotations.

    Parameters
    ----------
    p, q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, rotations.
    """
    p, q = normalize(p), normalize(q)
    q = np.where((dot(p, q) < 0)[..., None], -q, q)
    return 4.0 * np.arctan2(np.linalg.norm(p - q, axis=-1), np.linalg.norm(p + q, axis=-1))


def _sin_ratio(a: Array, phi: Array, sin_phi: Array) -> Array:
    """``sin(a phi) / sin(phi)``, by its series where ``phi`` is tiny (no division by a
    tiny number; the series' error is below 1e-18 there)."""
    small = phi < 1e-3
    safe = np.where(small, 1.0, sin_phi)
    exact = np.sin(a * phi) / safe
    if not small.any():
        return exact
    a2, p2 = a * a, phi * phi
    series = a * (1.0 + (1.0 - a2) * p2 / 6.0 + (1.0 - a2) * (7.0 - 3.0 * a2) * p2 * p2 / 360.0)
    return np.where(small, series, exact)


def slerp(q0: ArrayLike, q1: ArrayLike, t: ArrayLike) -> Array:
    """Spherical linear interpolation, the notes' formula::

        q(t) = sin((1 - t) phi) / sin(phi) q0 + sin(t phi) / sin(phi) q1

    along the shorter arc (``q1`` is negated when ``q0 . q1 < 0``). ``t = 0`` gives ``q0``
    exactly; ``t = 1`` gives ``q1`` or ``-q1`` (the same rotation). Where the keys are nearly
    or exactly equal the ratios come from their series, so the result stays accurate and
    unit length (no division by a tiny ``sin(phi)``). ``t`` outside ``[0, 1]`` extrapolates
    along the same great circle at the same angular speed.

    ``q0, q1 : (..., 4)`` unit quaternions; ``t`` broadcasts against their leading shape, so
    one key pair can be sampled at many times or many pairs at once.

    Parameters
    ----------
    q0, q1 : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, the ends.
    t : array_like
        ``(...)`` fractions of the way, 0 at ``q0``, 1 at ``q1``.
    """
    q0, q1 = _q(q0, "q0"), _q(q1, "q1")
    t = np.asarray(t, dtype=np.float64)
    d = np.einsum("...i,...i->...", q0, q1)
    sign = np.where(d < 0, -1.0, 1.0)
    # An error in phi only enters through phi^2 terms when phi is small, so arccos of the
    # dot product is accurate enough everywhere it matters.
    phi = np.arccos(np.minimum(np.abs(d), 1.0))
    sin_phi = np.sin(phi)
    c0 = _sin_ratio(1.0 - t, phi, sin_phi)
    c1 = _sin_ratio(t, phi, sin_phi) * sign
    return c0[..., None] * q0 + c1[..., None] * q1


def exp(v: ArrayLike) -> Array:
    """Quaternion exponential of a pure quaternion (vector) ``v``: ``cos|v| O + sin|v| v/|v|``,
    a rotation by ``2 |v|`` about ``v``.

    Parameters
    ----------
    v : array_like
        ``(..., 3)`` vectors (pure quaternions).
    """
    v = _v(v)
    theta = np.linalg.norm(v, axis=-1)
    out = np.empty(v.shape[:-1] + (4,))
    out[..., :3] = np.sinc(theta / np.pi)[..., None] * v  # sin(theta)/theta * v
    out[..., 3] = np.cos(theta)
    return out


def log(q: ArrayLike) -> Array:
    """Logarithm of a unit quaternion: the vector ``(phi/2) N`` with ``q = exp(that)``.

    Parameters
    ----------
    q : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, unit.
    """
    q = normalize(q)
    s = np.linalg.norm(q[..., :3], axis=-1)
    half = np.arctan2(s, q[..., 3])
    factor = np.where(s > 1e-300, half / np.where(s > 1e-300, s, 1.0), 1.0)
    return factor[..., None] * q[..., :3]


def squad(q0: ArrayLike, q1: ArrayLike, s0: ArrayLike, s1: ArrayLike, t: ArrayLike) -> Array:
    """Shoemake's spherical quadrangle interpolation between keys ``q0, q1`` with inner
    control quaternions ``s0, s1``: ``slerp(slerp(q0, q1, t), slerp(s0, s1, t), 2t(1-t))``.

    Parameters
    ----------
    q0, q1 : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, the segment's keys.
    s0, s1 : array_like
        ``(..., 4)`` quaternions ``(x, y, z, w)``, their inner control points.
    t : array_like
        ``(...)`` fractions of the segment.
    """
    t = np.asarray(t, dtype=np.float64)
    return slerp(slerp(q0, q1, t), slerp(s0, s1, t), 2.0 * t * (1.0 - t))


def same_hemisphere(keys: ArrayLike) -> Array:
    """Key rotations ``(K, 4)`` with signs flipped so that consecutive keys lie in the same
    hemisphere: every segment between them then takes the shorter arc.

    Parameters
    ----------
    keys : array_like
        ``(K, 4)`` key rotations in order.
    """
    keys = _q(keys, "keys")
    flips = np.concatenate([[1.0], np.sign(np.einsum("ij,ij->i", keys[1:], keys[:-1]))])
    flips[flips == 0] = 1.0
    return keys * np.cumprod(flips)[:, None]


def spline(times: ArrayLike, keys: ArrayLike, t: ArrayLike) -> Array:
    """A C1 quaternion spline through key rotations at (increasing) key times.

    Each segment is a cubic Bezier curve on the quaternion sphere evaluated by De
    Casteljau's construction with slerps (Shoemake). Its inner control points are set from
    the angular velocity at each key, a time-weighted average of the neighbouring segments'
    constant velocities (Catmull-Rom for uneven key times), so angular velocity is
    continuous through the keys: no jerk there, unlike piecewise slerp. Times outside the
    keys are clamped. ``keys (K, 4)``, ``t (...)`` -> ``(..., 4)``.

    Parameters
    ----------
    times : array_like
        ``(K,)`` the keys' times, increasing.
    keys : array_like
        ``(K, 4)`` the key rotations.
    t : array_like
        ``(...)`` the times to evaluate at.
    """
    times = np.asarray(times, dtype=np.float64)
    keys = same_hemisphere(normalize(keys))
    t = np.asarray(t, dtype=np.float64)
    k = len(keys)
    if k == 1:
        return np.broadcast_to(keys[0], t.shape + (4,)).copy()
    h = np.diff(times)
    # body-frame log-velocity of each segment: q(t) = q_i exp(v_i (t - t_i))
    v = log(multiply(conjugate(keys[:-1]), keys[1:])) / h[:, None]
    omega = np.empty((k, 3))
    omega[0], omega[-1] = v[0], v[-1]
    if k > 2:
        w_prev, w_next = h[1:], h[:-1]  # parabola slope at the middle point
        omega[1:-1] = (w_prev[:, None] * v[:-1] + w_next[:, None] * v[1:]) / \
            (w_prev + w_next)[:, None]
    a = multiply(keys[:-1], exp(omega[:-1] * h[:, None] / 3.0))
    b = multiply(keys[1:], exp(-omega[1:] * h[:, None] / 3.0))
    seg = np.clip(np.searchsorted(times, t, side="right") - 1, 0, k - 2)
    u = np.clip((t - times[seg]) / h[seg], 0.0, 1.0)
    p0, p1, p2, p3 = keys[seg], a[seg], b[seg], keys[seg + 1]
    l01, l12, l23 = slerp(p0, p1, u), slerp(p1, p2, u), slerp(p2, p3, u)
    return slerp(slerp(l01, l12, u), slerp(l12, l23, u), u)
