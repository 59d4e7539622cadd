"""Bezier and rational Bezier curves and tensor-product patches of any degree, in numpy.

A rational patch is a net of mass-points (Goldman): ``(w P, w)`` in homogeneous form; de
Casteljau on them, then projection, evaluates it, which is how the exact sphere, cylinder,
cone and torus become patches (:mod:`.quadrics`). A polynomial patch is the case w = 1.

Shapes: a set of P patches of degree (m, n) is ``points (P, m+1, n+1, 3)`` with
``weights (P, m+1, n+1)`` (all ones for polynomial patches); parameters ``u, v`` in
[0, 1], either ``(K,)`` (the same for every patch) or ``(P, K)``. Everything is vectorised
over patches and parameters.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import comb

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import GeometryError

__all__ = ["bernstein", "curve_point", "de_casteljau", "PatchSet", "elevate", "MAX_DEGREE",
           "MAX_WEIGHT_RATIO", "MAX_COORDINATE"]

#: the highest degree a side of a patch may have (binomials and Bernstein sums stay exact
#: in float64 well past it; a patch of higher degree is a mistake, not a surface)
MAX_DEGREE = 32
#: the most a patch's largest weight may be of its smallest: past it the homogeneous
#: coordinates lose every digit of the smaller masses (and 1e-300 .. 1e300 overflow)
MAX_WEIGHT_RATIO = 1e12
#: the largest control-point coordinate (a point's square must stay finite in float64 and
#: the renderer's float32 must still tell neighbouring samples apart)
MAX_COORDINATE = 1e15

#: ``norm(Su x Sv)`` below this fraction of the patch's size squared counts as degenerate (a
#: collapsed edge or pole, where the normal is taken as its limit)
DEGENERATE = 1e-12


def bernstein(n: int, t: ArrayLike) -> NDArray[np.float64]:
    """The Bernstein polynomials of degree ``n`` at ``t``: ``(..., n + 1)``.

    Parameters
    ----------
    n : int
        The degree.
    t : array_like
        Parameters in [0, 1], any shape.
    """
    t = np.asarray(t, dtype=np.float64)[..., None]
    i = np.arange(n + 1)
    c = np.array([comb(n, k) for k in range(n + 1)], np.float64)
    return c * t ** i * (1 - t) ** (n - i)


def de_casteljau(control: ArrayLike, t: ArrayLike, axis: int = -2) -> NDArray[np.float64]:
    """De Casteljau's algorithm along ``axis`` of a control net (repeated linear
    interpolation: stable, and what subdivision splits at): the points at ``t``, one per
    value; ``control (..., n+1, d)`` with ``t (K,)`` gives ``(..., K, d)``.

    Parameters
    ----------
    control : array_like
        A control net (homogeneous points last).
    t : array_like
        The parameter, broadcast against the net's other axes.
    axis : int
        The axis the net's degree runs along.
    """
    c = np.moveaxis(np.asarray(control, dtype=np.float64), axis, 0)  # (n+1, ..., d)
    t = np.asarray(t, dtype=np.float64)
    pts = np.broadcast_to(c[:, None], (c.shape[0], len(t)) + c.shape[1:]).copy()
    tt = t.reshape((len(t),) + (1,) * (c.ndim - 1))
    for r in range(c.shape[0] - 1, 0, -1):
        pts = (1 - tt) * pts[:r] + tt * pts[1:r + 1]
    return np.moveaxis(pts[0], 0, axis)  # (..., K, d) for axis -2


def curve_point(control: ArrayLike, t: ArrayLike, weights: ArrayLike | None = None):
    """Points of a (rational) Bezier curve ``control (n+1, 3)`` at ``t (K,)``: ``(K, 3)``, by
    de Casteljau on the mass-points ``(w P, w)``.

    Parameters
    ----------
    control : array_like
        ``(n+1, 3)`` control points.
    t : array_like
        ``(K,)`` parameters in [0, 1].
    weights : array_like or None
        ``(n+1,)`` positive weights (None: a polynomial curve).
    """
    p = np.asarray(control, dtype=np.float64)
    w = np.ones(len(p)) if weights is None else np.asarray(weights, dtype=np.float64)
    h = de_casteljau(np.concatenate([p * w[:, None], w[:, None]], 1), t, axis=0)
    return h[:, :3] / h[:, 3:]


def _split(h: np.ndarray, t: float, axis: int) -> tuple[np.ndarray, np.ndarray]:
    """De Casteljau subdivision of homogeneous nets along ``axis`` at ``t``: the two halves'
    nets (the left edges of the triangle of intermediate points)."""
    c = np.moveaxis(h, axis, 0)
    n = c.shape[0] - 1
    left, right = [c[0]], [c[n]]
    pts = c
    for r in range(n, 0, -1):
        pts = (1 - t) * pts[:r] + t * pts[1:r + 1]
        left.append(pts[0])
        right.append(pts[-1])
    a = np.moveaxis(np.stack(left), 0, axis)
    b = np.moveaxis(np.stack(right[::-1]), 0, axis)
    return a, b


def elevate(h: np.ndarray, axis: int) -> np.ndarray:
    """Degree elevation by one along ``axis`` of homogeneous nets (the same surface with one
    more control row): ``Q_i = i/(n+1) P_{i-1} + (1 - i/(n+1)) P_i``.

    Parameters
    ----------
    h : ndarray
        Homogeneous control nets (weighted points and weights last).
    axis : int
        The axis to raise the degree along.
    """
    c = np.moveaxis(h, axis, 0)
    n = c.shape[0] - 1
    out = np.empty((n + 2,) + c.shape[1:])
    out[0], out[n + 1] = c[0], c[n]
    for i in range(1, n + 1):
        a = i / (n + 1)
        out[i] = a * c[i - 1] + (1 - a) * c[i]
    return np.moveaxis(out, 0, axis)


def _check_patch_numbers(p: np.ndarray, w: np.ndarray) -> None:
    """Refuse, naming the first patch at fault, numbers no tessellation can use."""
    def first(bad) -> int:
        return int(np.flatnonzero(bad)[0])

    finite = np.isfinite(p).all((1, 2, 3)) & np.isfinite(w).all((1, 2))
    if not finite.all():
        raise GeometryError(f"patch {first(~finite)}: control points and weights must be "
                            "finite numbers")
    if (w <= 0).any():
        k = first((w <= 0).any((1, 2)))
        raise GeometryError(f"patch {k}: weights must be positive (a mass-point of mass 0 is "
                            "a vector: no point of the surface)")
    ratio = w.max((1, 2)) / w.min((1, 2))
    if (ratio > MAX_WEIGHT_RATIO).any():
        k = first(ratio > MAX_WEIGHT_RATIO)
        raise GeometryError(f"patch {k}: weights span {float(w[k].min()):g} to "
                            f"{float(w[k].max()):g}, more than {MAX_WEIGHT_RATIO:g} apart")
    big = np.abs(p).max((1, 2, 3)) > MAX_COORDINATE
    if big.any():
        k = first(big)
        raise GeometryError(f"patch {k}: a control point coordinate of "
                            f"{float(np.abs(p[k]).max()):g} is over the limit of "
                            f"{MAX_COORDINATE:g}")
    # (a patch whose control points differ by less than this: its normals' and areas'
    # products underflow -- 1e-320 apart they are subnormal -- so its triangles would all
    # be flat; one of no extent at all is a point, dropped where it is tessellated)
    span = np.ptp(p.reshape(len(p), -1, 3), axis=1).max(1)
    tiny = (span > 0) & (span < 1 / MAX_COORDINATE)
    if tiny.any():
        k = first(tiny)
        raise GeometryError(f"patch {k}: its control points span {float(span[k]):g}, under "
                            f"the least extent of {1 / MAX_COORDINATE:g} (scale it up)")


@dataclass(frozen=True)
class PatchSet:
    """P tensor-product (rational) Bezier patches of one degree: ``points (P, m+1, n+1, 3)``
    and ``weights (P, m+1, n+1)`` (positive; ones for polynomial patches; kept scaled so
    each patch's largest is 1). Refused, naming the patch: no patches, a degree over
    MAX_DEGREE, weights not one per point, not positive or spanning more than
    MAX_WEIGHT_RATIO, coordinates over MAX_COORDINATE, numbers that are not finite.

    Parameters
    ----------
    points : array_like
        ``(P, m+1, n+1, 3)`` control points.
    weights : array_like or None
        ``(P, m+1, n+1)`` positive weights (None: polynomial patches).
    """

    points: np.ndarray
    weights: np.ndarray

    def __init__(self, points: ArrayLike, weights: ArrayLike | None = None):
        p = np.array(points, dtype=np.float64)
        if p.ndim == 3:
            p = p[None]
        if p.ndim != 4 or p.shape[-1] != 3 or min(p.shape[1:3]) < 2:
            raise GeometryError("patch control points must have shape (P, m+1, n+1, 3) "
                                f"with m, n >= 1, got {p.shape}")
        if not len(p):
            raise GeometryError("a PatchSet needs at least one patch, got none")
        if max(p.shape[1:3]) - 1 > MAX_DEGREE:
            raise GeometryError(f"patch degree ({p.shape[1] - 1}, {p.shape[2] - 1}) is over "
                                f"the limit of {MAX_DEGREE} a side")
        if weights is None:
            w = np.ones(p.shape[:3])
        else:
            w = np.array(weights, dtype=np.float64)
            if w.size != np.prod(p.shape[:3]):
                raise GeometryError(f"patch weights must be one per control point, shape "
                                    f"{p.shape[:3]}, got shape {w.shape}")
            w = w.reshape(p.shape[:3])
        _check_patch_numbers(p, w)
        # (a rational patch is the same surface with all its weights scaled alike: scaled so
        # the largest is 1, 1e-300 or 1e300 weights neither underflow nor overflow)
        w = w / w.max((1, 2), keepdims=True)
        p.setflags(write=False)
        w.setflags(write=False)
        object.__setattr__(self, "points", p)
        object.__setattr__(self, "weights", w)

    @classmethod
    def from_masspoints(cls, masspoints) -> PatchSet:
        """From a net of :class:`~glshade.masspoint.MassPoint` ``(P, m+1, n+1)``: control
        points ``weighted / mass``, weights ``mass``.

        Parameters
        ----------
        masspoints : MassPoint
            ``(P, m+1, n+1)`` mass-points.
        """
        return cls(masspoints.weighted / masspoints.mass[..., None], masspoints.mass)

    @classmethod
    def _from_homogeneous(cls, h: np.ndarray) -> PatchSet:
        return cls(h[..., :3] / h[..., 3:], h[..., 3])

    # ------------------------------------------------------------------ facts
    def __len__(self) -> int:
        return len(self.points)

    @property
    def degree(self) -> tuple[int, int]:
        return self.points.shape[1] - 1, self.points.shape[2] - 1

    @property
    def rational(self) -> bool:
        return not np.all(self.weights == self.weights[..., :1, :1])

    @property
    def homogeneous(self) -> np.ndarray:
        """``(P, m+1, n+1, 4)``: the mass-points ``(w P, w)``."""
        return np.concatenate([self.points * self.weights[..., None],
                               self.weights[..., None]], -1)

    def __getitem__(self, index) -> PatchSet:
        idx = np.atleast_1d(np.arange(len(self))[index])
        return PatchSet(self.points[idx], self.weights[idx])

    def bounds(self) -> np.ndarray:
        """Each patch's box ``(P, 2, 3)``: its control points' (a patch with positive weights
        lies in their convex hull)."""
        return np.stack([self.points.min((1, 2)), self.points.max((1, 2))], 1)

    # ------------------------------------------------------------------ evaluation
    def _params(self, u, v):
        u = np.asarray(u, dtype=np.float64)
        v = np.asarray(v, dtype=np.float64)
        u, v = np.broadcast_arrays(u, v)
        if u.ndim == 1:
            u = np.broadcast_to(u, (len(self),) + u.shape)
            v = np.broadcast_to(v, (len(self),) + v.shape)
        if u.shape[0] != len(self):
            raise GeometryError(f"parameters must be (K,) or (P, K) for {len(self)} patches, "
                                f"got {u.shape}")
        return u, v

    def _h_deriv(self, u, v, du: int, dv: int) -> np.ndarray:
        """The ``(du, dv)`` partial derivative of the homogeneous surface ``(P, K, 4)`` (the
        hodograph: control differences times the degree, in Bernstein form)."""
        m, n = self.degree
        h = self.homogeneous
        scale = 1.0
        for _ in range(du):
            if h.shape[1] == 1:
                return np.zeros(u.shape + (4,))
            scale *= h.shape[1] - 1
            h = h[:, 1:] - h[:, :-1]
        for _ in range(dv):
            if h.shape[2] == 1:
                return np.zeros(u.shape + (4,))
            scale *= h.shape[2] - 1
            h = h[:, :, 1:] - h[:, :, :-1]
        bu = bernstein(h.shape[1] - 1, u)  # (P, K, m'+1)
        bv = bernstein(h.shape[2] - 1, v)
        return scale * np.einsum("pki,pkj,pijc->pkc", bu, bv, h)

    def evaluate(self, u: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
        """Surface points ``(P, K, 3)`` by the Bernstein form.

        Parameters
        ----------
        u, v : array_like
            ``(K,)`` parameters in [0, 1], pairs.
        """
        u, v = self._params(u, v)
        h = self._h_deriv(u, v, 0, 0)
        return h[..., :3] / h[..., 3:]

    def evaluate_de_casteljau(self, u: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
        """Surface points ``(P, K, 3)`` by de Casteljau on the mass-points, rows then the
        column (the same surface as :meth:`evaluate`, by another algorithm).

        Parameters
        ----------
        u, v : array_like
            ``(K,)`` parameters in [0, 1], pairs.
        """
        uu, vv = self._params(u, v)
        h = self.homogeneous  # (P, m+1, n+1, 4)
        pts = np.broadcast_to(h[:, None], uu.shape + h.shape[1:])  # (P, K, m+1, n+1, 4)
        tv = vv[..., None, None, None]
        for r in range(h.shape[2] - 1, 0, -1):  # along v: each row to one point
            pts = (1 - tv) * pts[..., :r, :] + tv * pts[..., 1:r + 1, :]
        pts = pts[..., 0, :]  # (P, K, m+1, 4)
        tu = uu[..., None, None]
        for r in range(h.shape[1] - 1, 0, -1):  # then the column
            pts = (1 - tu) * pts[..., :r, :] + tu * pts[..., 1:r + 1, :]
        out = pts[..., 0, :]
        return out[..., :3] / out[..., 3:]

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> dict:
        """The surface and its partial derivatives at (u, v): ``{"S", "Su", "Sv"}`` and with
        ``order=2`` also ``"Suu", "Suv", "Svv"``, each ``(P, K, 3)`` (quotient rule on the
        homogeneous derivatives).

        Parameters
        ----------
        u, v : array_like
            ``(K,)`` parameters in [0, 1], pairs.
        order : int
            1 or 2.
        """
        u, v = self._params(u, v)
        H = {(a, b): self._h_deriv(u, v, a, b) for a in range(order + 1)
             for b in range(order + 1 - a)}
        w = {k: x[..., 3:] for k, x in H.items()}
        h = {k: x[..., :3] for k, x in H.items()}
        S = h[0, 0] / w[0, 0]
        out = {"S": S}
        Su = (h[1, 0] - w[1, 0] * S) / w[0, 0]
        Sv = (h[0, 1] - w[0, 1] * S) / w[0, 0]
        out.update(Su=Su, Sv=Sv)
        if order >= 2:
            out["Suu"] = (h[2, 0] - w[2, 0] * S - 2 * w[1, 0] * Su) / w[0, 0]
            out["Svv"] = (h[0, 2] - w[0, 2] * S - 2 * w[0, 1] * Sv) / w[0, 0]
            out["Suv"] = (h[1, 1] - w[1, 1] * S - w[1, 0] * Sv - w[0, 1] * Su) / w[0, 0]
        return out

    def normals(self, u: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
        """Exact unit normals ``(P, K, 3)``, along ``Su x Sv``. Where that vanishes (an edge
        collapsed to a point: the teapot's lid and bottom, a sphere's poles) the normal is
        its limit there, ``Su x Suv`` (from ``Sv ~ u Suv`` near a collapsed u = 0 edge;
        negated at u = 1) or ``Suv x Sv`` (a collapsed v edge), then ``Suu x Svv``.

        Parameters
        ----------
        u, v : array_like
            ``(K,)`` parameters in [0, 1], pairs.
        """
        d = self.derivatives(u, v, order=2)
        size = np.ptp(self.points, axis=(1, 2)).max(-1)[:, None, None]  # (P, 1, 1)
        small = (DEGENERATE * size ** 2) ** 2  # (|n|^2 below it: degenerate)
        n = np.cross(d["Su"], d["Sv"])
        bad = np.einsum("...i,...i->...", n, n)[..., None] <= small
        if bad.any():
            # near a collapsed u = 0 side Sv ~ u Suv, near u = 1 Sv ~ -(1 - u) Suv (and so
            # for v): the limit's sign depends on the end
            uu, vv = self._params(u, v)
            su = np.where(uu < 0.5, 1.0, -1.0)[..., None]
            sv = np.where(vv < 0.5, 1.0, -1.0)[..., None]
            limit = su * np.cross(d["Su"], d["Suv"]) + sv * np.cross(d["Suv"], d["Sv"])
            n = np.where(bad, limit, n)
            bad = np.einsum("...i,...i->...", n, n)[..., None] <= small
            if bad.any():
                n = np.where(bad, np.cross(d["Suu"], d["Svv"]), n)
        length = np.linalg.norm(n, axis=-1, keepdims=True)
        return n / np.where(length > 0, length, 1.0)

    # ------------------------------------------------------------------ subdivision
    def subdivide(self, t: float = 0.5, direction: str = "u") -> tuple[PatchSet, PatchSet]:
        """Split every patch at ``t`` in u or v (de Casteljau): two sets whose union is the
        same surface, ``[0, t]`` and ``[t, 1]`` rescaled to [0, 1].

        Parameters
        ----------
        t : float
            Where to split, in (0, 1).
        direction : str
            ``"u"`` or ``"v"``.
        """
        axis = {"u": 1, "v": 2}[direction]
        a, b = _split(self.homogeneous, float(t), axis)
        return PatchSet._from_homogeneous(a), PatchSet._from_homogeneous(b)

    def elevated(self, m: int, n: int) -> PatchSet:
        """The same patches at degree (m, n) >= their own (degree elevation).

        Parameters
        ----------
        m, n : int
            The new degrees, at least the patches' own.
        """
        h = self.homogeneous
        mm, nn = self.degree
        if m < mm or n < nn:
            raise GeometryError(f"cannot lower degree {self.degree} to {(m, n)}")
        for _ in range(m - mm):
            h = elevate(h, 1)
        for _ in range(n - nn):
            h = elevate(h, 2)
        return PatchSet._from_homogeneous(h)

    @staticmethod
    def concatenate(sets) -> PatchSet:
        """One set of several, each raised to the largest degree.

        Parameters
        ----------
        sets : iterable of PatchSet
            The sets, in order.
        """
        sets = list(sets)
        m = max(s.degree[0] for s in sets)
        n = max(s.degree[1] for s in sets)
        raised = [s.elevated(m, n) for s in sets]
        return PatchSet(np.concatenate([s.points for s in raised]),
                        np.concatenate([s.weights for s in raised]))
