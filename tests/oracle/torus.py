"""An independent torus ray caster in float64: the quartic of a ray against a torus
(R about the y axis, tube r), its roots as the eigenvalues of companion matrices (every
ray at once), each polished by bisection on the sign of the implicit function
(rho - R)^2 + y^2 - r^2 in a bracket about it. Shares nothing with glshade's code."""

import numpy as np


def first_hits(o, d, R, r, t_min):
    """For rays ``o + t d`` (N, 3) (d unit): the smallest root t > ``t_min`` (N,) of the
    torus's surface (inf where none), and how well separated it is from the nearest other
    root (N,) (small: a grazing ray, where float32 cannot tell the two apart)."""
    o, d = np.asarray(o, np.float64), np.asarray(d, np.float64)
    k = (o * o).sum(1) + R * R - r * r
    od = (o * d).sum(1)
    # (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + z^2), |d| = 1: t^4 + c3 t^3 + c2 t^2 + c1 t + c0
    c3 = 4 * od
    c2 = 2 * k + 4 * od * od - 4 * R * R * (d[:, 0] ** 2 + d[:, 2] ** 2)
    c1 = 4 * k * od - 8 * R * R * (o[:, 0] * d[:, 0] + o[:, 2] * d[:, 2])
    c0 = k * k - 4 * R * R * (o[:, 0] ** 2 + o[:, 2] ** 2)
    companion = np.zeros((len(o), 4, 4))
    companion[:, 0] = -np.stack([c3, c2, c1, c0], 1)
    companion[:, 1, 0] = companion[:, 2, 1] = companion[:, 3, 2] = 1
    roots = np.linalg.eigvals(companion)
    real = np.abs(roots.imag) <= 1e-6 * (1 + np.abs(roots.real))
    t = np.where(real, roots.real, np.inf)
    t = np.sort(_polish(o, d, R, r, t), 1)
    with np.errstate(invalid="ignore"):  # (inf - inf past the last root)
        gap = np.diff(np.concatenate([np.full((len(o), 1), -np.inf), t,
                                      np.full((len(o), 1), np.inf)], 1), axis=1)
    after = t > t_min[:, None]
    first = np.where(after.any(1), np.argmax(after, 1), 0)
    hit = np.where(after.any(1), t[np.arange(len(o)), first], np.inf)
    sep = np.minimum(gap[np.arange(len(o)), first], gap[np.arange(len(o)), first + 1])
    return hit, np.where(np.isfinite(hit), sep, np.inf)


def _g(o, d, R, r, t):
    p = o[:, None, :] + t[..., None] * d[:, None, :]
    w = np.hypot(p[..., 0], p[..., 2]) - R
    return w * w + p[..., 1] ** 2 - r * r


def _polish(o, d, R, r, t):
    """Bisection in [t - h, t + h] where the sign changes there (else the root stays)."""
    finite = np.isfinite(t)
    h = 1e-4 * (1 + np.abs(np.where(finite, t, 0)))
    a, b = np.where(finite, t - h, 0), np.where(finite, t + h, 0)
    ga, gb = _g(o, d, R, r, a), _g(o, d, R, r, b)
    bracket = finite & ((ga < 0) != (gb < 0))
    for _ in range(60):
        m = 0.5 * (a + b)
        gm = _g(o, d, R, r, m)
        left = (gm < 0) == (ga < 0)
        a, ga = np.where(left, m, a), np.where(left, gm, ga)
        b = np.where(left, b, m)
    return np.where(bracket, 0.5 * (a + b), t)
