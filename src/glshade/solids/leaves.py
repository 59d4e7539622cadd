"""The leaves of CSG trees (:mod:`glshade.solids`): primitive solids in their own
frame -- centred at the origin, axis along y -- each with its inside test, bounds and the
boundary events of a ray (Roth)."""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError
from .tree import (Events, Solid, _by_distance, _convex, _finite, _interval, _positive,
                   _quadratic, _vec)

__all__ = ["Sphere", "Box", "Cylinder", "Cone", "Torus", "HalfSpace"]


class _Leaf(Solid):
    def _leaf_events(self, o: np.ndarray, d: np.ndarray, leaf: int) -> Events:
        raise NotImplementedError

    def _events(self, o, d, cast) -> Events:
        return self._leaf_events(o, d, cast.leaves[id(self)])

    def _classify(self, lo, hi):
        return _by_distance(self.distance, lo, hi)


class Sphere(_Leaf):
    """A ball of ``radius`` about the origin.

    Parameters
    ----------
    radius : float
        > 0.
    """

    def __init__(self, radius: float = 1.0):
        self.radius = _positive(radius, "sphere radius")

    def _contains(self, p):
        return np.einsum("nd,nd->n", p, p) <= self.radius ** 2

    def _bounds(self):
        return np.array([[-self.radius] * 3, [self.radius] * 3])

    def distance(self, p):
        """The signed distance from points to the leaf's surface (negative inside): exact,
        or a bound never above the true distance.

        Parameters
        ----------
        p : ndarray
            ``(N, 3)`` points in the leaf's own frame.
        """
        return np.linalg.norm(p, axis=1) - self.radius

    def _leaf_events(self, o, d, leaf):
        t0, t1 = _quadratic(np.einsum("nd,nd->n", d, d), 2 * np.einsum("nd,nd->n", o, d),
                            np.einsum("nd,nd->n", o, o) - self.radius ** 2)
        t0 = np.where(t0 < t1, t0, np.nan)  # (tangent rays touch no volume)
        p0, p1 = o + np.nan_to_num(t0)[:, None] * d, o + np.nan_to_num(t1)[:, None] * d
        return _interval(len(o), t0, t1, p0, p1, leaf)


class Box(_Leaf):
    """An axis-aligned box centred at the origin: ``size`` one edge length or three (x, y,
    z).

    Parameters
    ----------
    size : float or (float, float, float)
        Edge lengths, > 0.
    """

    def __init__(self, size=1.0):
        s = np.broadcast_to(np.asarray(size, np.float64), (3,))
        for v in s:
            _positive(v, "box size")
        self.half = s / 2

    def _contains(self, p):
        return (np.abs(p) <= self.half).all(1)

    def _bounds(self):
        return np.array([-self.half, self.half])

    def distance(self, p):
        """The signed distance from points to the leaf's surface (negative inside): exact,
        or a bound never above the true distance.

        Parameters
        ----------
        p : ndarray
            ``(N, 3)`` points in the leaf's own frame.
        """
        q = np.abs(p) - self.half
        return np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(1), 0)

    def _leaf_events(self, o, d, leaf):
        with np.errstate(divide="ignore", invalid="ignore"):
            a = (-self.half - o) / d
            b = (self.half - o) / d
        lo, hi = np.fmin(a, b), np.fmax(a, b)
        parallel = d == 0
        outside = parallel & (np.abs(o) > self.half)
        lo = np.where(parallel, -np.inf, lo)
        hi = np.where(parallel, np.inf, hi)
        i0, i1 = np.argmax(lo, axis=1), np.argmin(hi, axis=1)
        rows = np.arange(len(o))
        t0, t1 = lo[rows, i0], hi[rows, i1]
        t0 = np.where((t0 < t1) & ~outside.any(1), t0, np.nan)
        n0, n1 = np.zeros((len(o), 3)), np.zeros((len(o), 3))
        n0[rows, i0] = -np.sign(d[rows, i0])
        n1[rows, i1] = np.sign(d[rows, i1])
        return _interval(len(o), t0, t1, n0, n1, leaf)


class Cylinder(_Leaf):
    """Radius ``radius`` around the y axis, from y = -height/2 to height/2.

    Parameters
    ----------
    radius : float
        > 0.
    height : float
        > 0, along y, centred at the origin.
    """

    def __init__(self, radius: float = 1.0, height: float = 2.0):
        self.radius = _positive(radius, "cylinder radius")
        self.h = _positive(height, "cylinder height") / 2

    def _contains(self, p):
        return (p[:, 0] ** 2 + p[:, 2] ** 2 <= self.radius ** 2) & (np.abs(p[:, 1]) <= self.h)

    def _bounds(self):
        r, h = self.radius, self.h
        return np.array([[-r, -h, -r], [r, h, r]])

    def distance(self, p):
        """The signed distance from points to the leaf's surface (negative inside): exact,
        or a bound never above the true distance.

        Parameters
        ----------
        p : ndarray
            ``(N, 3)`` points in the leaf's own frame.
        """
        q = np.c_[np.hypot(p[:, 0], p[:, 2]) - self.radius, np.abs(p[:, 1]) - self.h]
        return np.minimum(q.max(1), 0) + np.linalg.norm(np.maximum(q, 0), axis=1)

    def _gradient(self, p):
        side = np.abs(np.hypot(p[:, 0], p[:, 2]) - self.radius)
        cap = np.abs(np.abs(p[:, 1]) - self.h)
        return np.where((side <= cap)[:, None], p * [1, 0, 1],
                        np.c_[0 * p[:, 0], np.sign(p[:, 1]), 0 * p[:, 0]])

    def _leaf_events(self, o, d, leaf):
        r1, r2 = _quadratic(d[:, 0] ** 2 + d[:, 2] ** 2,
                            2 * (o[:, 0] * d[:, 0] + o[:, 2] * d[:, 2]),
                            o[:, 0] ** 2 + o[:, 2] ** 2 - self.radius ** 2)
        with np.errstate(divide="ignore", invalid="ignore"):
            c1, c2 = (-self.h - o[:, 1]) / d[:, 1], (self.h - o[:, 1]) / d[:, 1]
        cand = np.c_[r1, r2, c1, c2]
        cand = np.where(np.isfinite(cand), cand, np.inf)
        return _convex(o, d, cand, self._contains, self._gradient, leaf)


class Cone(_Leaf):
    """Apex at y = height/2 above a base of ``radius`` at y = -height/2.

    Parameters
    ----------
    radius : float
        The base's radius, > 0.
    height : float
        > 0, along y, centred at the origin.
    """

    def __init__(self, radius: float = 1.0, height: float = 2.0):
        self.radius = _positive(radius, "cone radius")
        self.height = _positive(height, "cone height")
        self.apex = self.height / 2
        self.k = self.radius / self.height

    def _contains(self, p):
        y = p[:, 1]
        return ((p[:, 0] ** 2 + p[:, 2] ** 2 <= (self.k * (self.apex - y)) ** 2)
                & (y <= self.apex) & (y >= -self.apex))

    def _bounds(self):
        r, h = self.radius, self.apex
        return np.array([[-r, -h, -r], [r, h, r]])

    def distance(self, p):
        """A bound: the larger of the distances to the side's line (extended) and to the
        slab -- never more than the true distance (an intersection's rule).

        Parameters
        ----------
        p : ndarray
            ``(N, 3)`` points in the leaf's own frame.
        """
        y = p[:, 1]
        side = (np.hypot(p[:, 0], p[:, 2]) - self.k * (self.apex - y)) / np.hypot(1, self.k)
        return np.maximum(side, np.abs(y) - self.apex)

    def _gradient(self, p):
        y = p[:, 1]
        rho = np.hypot(p[:, 0], p[:, 2])
        side = np.abs(rho - self.k * (self.apex - y))
        base = np.abs(y + self.apex)
        radial = p * [1, 0, 1] / np.maximum(rho, 1e-300)[:, None]
        slant = radial + np.c_[0 * y, np.full(len(y), self.k), 0 * y]
        return np.where((side <= base)[:, None], slant, np.c_[0 * y, -np.ones(len(y)), 0 * y])

    def _leaf_events(self, o, d, leaf):
        k2, ya = self.k ** 2, self.apex
        u = ya - o[:, 1]  # (apex height minus y) = u - t d_y
        r1, r2 = _quadratic(d[:, 0] ** 2 + d[:, 2] ** 2 - k2 * d[:, 1] ** 2,
                            2 * (o[:, 0] * d[:, 0] + o[:, 2] * d[:, 2] + k2 * u * d[:, 1]),
                            o[:, 0] ** 2 + o[:, 2] ** 2 - k2 * u ** 2)
        with np.errstate(divide="ignore", invalid="ignore"):
            c1 = (-ya - o[:, 1]) / d[:, 1]
            c2 = (ya - o[:, 1]) / d[:, 1]
        cand = np.c_[r1, r2, c1, c2]
        cand = np.where(np.isfinite(cand), cand, np.inf)
        return _convex(o, d, cand, self._contains, self._gradient, leaf)


class Torus(_Leaf):
    """Tube of radius ``r`` around a circle of radius ``R`` in the xz plane.

    Parameters
    ----------
    R : float
        The circle's radius, > r.
    r : float
        The tube's radius, > 0.
    """

    def __init__(self, R: float = 1.0, r: float = 0.25):
        self.R, self.r = _positive(R, "torus R"), _positive(r, "torus r")
        if self.r >= self.R:
            raise GeometryError(f"torus needs r < R (a ring), got R={R}, r={r}")

    def _contains(self, p):
        q = np.hypot(p[:, 0], p[:, 2]) - self.R
        return q * q + p[:, 1] ** 2 <= self.r ** 2

    def _bounds(self):
        a, r = self.R + self.r, self.r
        return np.array([[-a, -r, -a], [a, r, a]])

    def distance(self, p):
        """The signed distance from points to the leaf's surface (negative inside): exact,
        or a bound never above the true distance.

        Parameters
        ----------
        p : ndarray
            ``(N, 3)`` points in the leaf's own frame.
        """
        return np.hypot(np.hypot(p[:, 0], p[:, 2]) - self.R, p[:, 1]) - self.r

    def _gradient(self, p):
        rho = np.maximum(np.hypot(p[:, 0], p[:, 2]), 1e-300)
        centre = p * [1, 0, 1] * (self.R / rho)[:, None]
        return p - centre

    def _leaf_events(self, o, d, leaf):
        """The quartic (|p|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + z^2) along the ray: its real
        roots, all rays at once (eigenvalues of companion matrices), polished by Newton,
        paired into up to two intervals."""
        n = len(o)
        R2, r2 = self.R ** 2, self.r ** 2
        dd, od, oo = (np.einsum("nd,nd->n", d, d), np.einsum("nd,nd->n", o, d),
                      np.einsum("nd,nd->n", o, o))
        k = oo + R2 - r2
        c4 = dd * dd
        c3 = 4 * dd * od
        c2 = 2 * dd * k + 4 * od * od - 4 * R2 * (d[:, 0] ** 2 + d[:, 2] ** 2)
        c1 = 4 * od * k - 8 * R2 * (o[:, 0] * d[:, 0] + o[:, 2] * d[:, 2])
        c0 = k * k - 4 * R2 * (o[:, 0] ** 2 + o[:, 2] ** 2)
        comp = np.zeros((n, 4, 4))
        comp[:, 0, :] = -np.c_[c3, c2, c1, c0] / c4[:, None]
        comp[:, 1, 0] = comp[:, 2, 1] = comp[:, 3, 2] = 1.0
        roots = np.linalg.eigvals(comp)
        real = np.abs(roots.imag) <= 1e-6 * (1 + np.abs(roots.real))
        t = np.where(real, roots.real, np.nan)
        coeffs = (c4, c3, c2, c1, c0)
        for _ in range(3):  # Newton polish
            f = sum(c[:, None] * t ** (4 - i) for i, c in enumerate(coeffs))
            df = sum((4 - i) * c[:, None] * t ** (3 - i) for i, c in enumerate(coeffs[:-1]))
            with np.errstate(divide="ignore", invalid="ignore"):
                step = np.where(df != 0, f / df, 0.0)
            t = t - np.nan_to_num(step)
        t = np.sort(np.where(np.isnan(t), np.inf, t), axis=1)
        ev = Events.empty(n, 4)
        # real roots come in pairs (enter, leave); a double root (tangent) pairs with itself
        count = np.isfinite(t).sum(1)
        valid = (count == 2) | (count == 4)
        for j in range(4):
            ok = valid & (j < count)
            ev.t[ok, j] = t[ok, j]
            ev.kind[ok, j] = 1 if j % 2 == 0 else -1
            p = o[ok] + t[ok, j][:, None] * d[ok]
            ev.normal[ok, j] = self._gradient(p)
            ev.leaf[ok, j] = leaf
        with np.errstate(invalid="ignore"):  # (inf - inf in unused slots)
            touch = ev.t[:, 1::2] - ev.t[:, ::2] <= 0
        for j in range(2):  # tangent pairs enclose no volume
            z = touch[:, j]
            ev.t[z, 2 * j:2 * j + 2] = np.inf
            ev.kind[z, 2 * j:2 * j + 2] = 0
        return ev.sorted()

    width = 4


class HalfSpace(_Leaf):
    """Everything on the side of the plane ``dot(normal, p) = offset`` away from ``normal``.

    Parameters
    ----------
    normal : array_like
        ``(3,)`` the plane's normal, non-zero: the solid lies away from it.
    offset : float
        The plane's distance along the unit normal from the origin.
    """

    def __init__(self, normal=(0.0, 1.0, 0.0), offset: float = 0.0):
        n = _vec(normal, "half-space normal")
        length = np.linalg.norm(n)
        if length == 0:
            raise GeometryError("half-space normal must not be zero")
        self.normal, self.offset = n / length, _finite(offset, "half-space offset") / length

    def _contains(self, p):
        return p @ self.normal <= self.offset

    def _bounds(self):
        return None

    def distance(self, p):
        """The signed distance from points to the leaf's surface (negative inside): exact,
        or a bound never above the true distance.

        Parameters
        ----------
        p : ndarray
            ``(N, 3)`` points in the leaf's own frame.
        """
        return p @ self.normal - self.offset

    def _leaf_events(self, o, d, leaf):
        n = len(o)
        nd, no = d @ self.normal, o @ self.normal
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (self.offset - no) / nd
        inside_all = (nd == 0) & (no <= self.offset)
        t0 = np.where(nd < 0, t, np.where(nd > 0, -np.inf, np.where(inside_all, -np.inf,
                                                                      np.nan)))
        t1 = np.where(nd > 0, t, np.inf)
        normal = np.broadcast_to(self.normal, (n, 3))
        return _interval(n, t0, t1, normal, normal, leaf)
