"""The notes' Table 1 measured: quaternion vs 3x3 matrix in memory, multiplies and time;
and slerp of 1,000,000 interpolations against scipy and pyrr in the same run.

Run: ``.venv/bin/python benchmarks/quaternion_bench.py [--repeats N]``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import interleaved, table  # noqa: E402

from glshade import quaternion as Q  # noqa: E402


class Counted:
    """A number that counts the multiplications done with it."""

    count = 0

    def __init__(self, x):
        self.x = x

    def _wrap(self, other):
        return other.x if isinstance(other, Counted) else other

    def __mul__(self, other):
        Counted.count += 1
        return Counted(self.x * self._wrap(other))

    __rmul__ = __mul__

    def __add__(self, other):
        return Counted(self.x + self._wrap(other))

    __radd__ = __add__

    def __sub__(self, other):
        return Counted(self.x - self._wrap(other))

    def __rsub__(self, other):
        return Counted(self._wrap(other) - self.x)

    def __neg__(self):
        return Counted(-self.x)


def count_multiplies(fn, *arrays) -> int:
    """Multiplications ``fn`` performs on one element, with scalar factors of 2 excluded
    (a shift) as in the notes' count."""
    objs = [np.array([Counted(float(v)) for v in np.ravel(a)], dtype=object).reshape(np.shape(a))
            for a in arrays]
    Counted.count = 0
    fn(*objs)
    return Counted.count


def q_transform(q, v):
    """The sandwich as the notes count it: q v, then (q v) q*, with v a pure quaternion."""
    x, y, z, w = q
    vx, vy, vz = v
    # q v  (v has no O part: 12 multiplies)
    a = -(x * vx + y * vy + z * vz)
    bx = w * vx + (y * vz - z * vy)
    by = w * vy + (z * vx - x * vz)
    bz = w * vz + (x * vy - y * vx)
    # (q v) q*, vector part only (the O part is known to be 0): 16 - 4 multiplies
    return (-a * x + w * bx + (-(by * z) + bz * y),
            -a * y + w * by + (-(bz * x) + bx * z),
            -a * z + w * bz + (-(bx * y) + by * x))


def q_expanded(q, v):
    """glshade's conformal(): (w^2 - u.u) v + 2 (u.v) u + 2 w (u x v), written out."""
    x, y, z, w = q
    vx, vy, vz = v
    a = w * w - (x * x + y * y + z * z)
    b = 2 * (x * vx + y * vy + z * vz)
    c = 2 * w
    cx, cy, cz = y * vz - z * vy, z * vx - x * vz, x * vy - y * vx
    return (a * vx + b * x + c * cx, a * vy + b * y + c * cy, a * vz + b * z + c * cz)


def q_compose(p, q):
    x1, y1, z1, w1 = p
    x2, y2, z2, w2 = q
    return (w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2)


def m_transform(m, v):
    return [m[i, 0] * v[0] + m[i, 1] * v[1] + m[i, 2] * v[2] for i in range(3)]


def m_compose(a, b):
    return [[sum((a[i, k] * b[k, j] for k in range(1, 3)), a[i, 0] * b[0, j]) for j in
             range(3)] for i in range(3)]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("-n", type=int, default=1_000_000)
    args = ap.parse_args()
    n = args.n
    rng = np.random.default_rng(0)
    q = Q.normalize(rng.normal(size=(n, 4)))
    p = Q.normalize(rng.normal(size=(n, 4)))
    m, mp = Q.to_matrix(q), Q.to_matrix(p)
    v = rng.normal(size=(n, 3))

    counts = {
        "q transform": count_multiplies(q_transform, q[0], v[0]),
        "q compose": count_multiplies(q_compose, p[0], q[0]),
        "m transform": count_multiplies(m_transform, m[0], v[0]),
        "m compose": count_multiplies(m_compose, mp[0], m[0]),
        "glshade rotate": count_multiplies(q_expanded, q[0], v[0]),
    }
    t = interleaved({
        "q transform": lambda: Q.conformal(q, v),
        "m transform": lambda: np.einsum("nij,nj->ni", m, v),
        "q compose": lambda: Q.multiply(p, q),
        "m compose": lambda: mp @ m,
    }, args.repeats)
    print(f"Table 1 of the notes, measured ({n:,} elements, median of {args.repeats})")
    print(table([
        ("quaternion", f"4 scalars ({q[0].nbytes} B)",
         f"{counts['q transform']} (notes 28; glshade's expanded sandwich "
         f"{counts['glshade rotate']})", f"{t['q transform']:.3f}",
         f"{counts['q compose']} (notes 16)", f"{t['q compose']:.3f}"),
        ("3x3 matrix", f"9 scalars ({m[0].nbytes} B)", f"{counts['m transform']} (notes 9)",
         f"{t['m transform']:.3f}", f"{counts['m compose']} (notes 27)",
         f"{t['m compose']:.3f}"),
    ], ("", "memory", "multiplies / transform", "s / 1M transforms", "multiplies / compose",
        "s / 1M composes")))

    # ------------------------------------------------------------- slerp vs peers
    t_frac = rng.uniform(0, 1, n)
    series = {"glshade": lambda: Q.slerp(p, q, t_frac)}
    try:
        from scipy.spatial.transform import Rotation, Slerp

        keys = Rotation.from_quat(np.stack([p, q], 1).reshape(-1, 4))
        times = np.arange(2 * n, dtype=float)
        at = 2 * np.arange(n) + t_frac
        series["scipy Slerp"] = lambda: Slerp(times, keys)(at)
    except ImportError:
        Rotation = None
    import pyrr

    med = interleaved(series, args.repeats)
    sub = 20_000  # pyrr works one pair at a time: time a slice and scale up
    med["pyrr"] = interleaved({"pyrr": lambda: [pyrr.quaternion.slerp(a, b, s) for a, b, s in
                                                zip(p[:sub], q[:sub], t_frac[:sub])]},
                              1)["pyrr"] * (n / sub)
    base = med["glshade"]
    rows = [(k.split(" (")[0], f"{v:.3f}", f"{v / base:.1f}x") for k, v in med.items()]

    # accuracy on nearby keys of opposite sign (the same rotations, 0.01 rad apart)
    near = -Q.multiply(p[:1000], Q.from_axis_angle(rng.normal(size=(1000, 3)), 0.01))
    ours = Q.slerp(p[:1000], near, 0.5)
    theirs = np.stack([pyrr.quaternion.slerp(a, b, 0.5) for a, b in zip(p[:1000], near)])
    err_ours = np.degrees(Q.angle_between(Q.slerp(p[:1000], -near, 0.5), ours)).max()
    err_pyrr = np.degrees(Q.angle_between(Q.slerp(p[:1000], -near, 0.5),
                                          Q.normalize(theirs))).max()
    print(f"\nslerp of {n:,} interpolations (pyrr timed on {sub:,} and scaled)")
    print(table(rows, ("implementation", "seconds", "vs glshade")))
    print(f"max error on keys 0.01 rad apart with opposite signs: glshade {err_ours:.2g} deg, "
          f"pyrr {err_pyrr:.1f} deg")

    # drift of a million sequential compositions
    step = Q.from_axis_angle([0.3, 1.0, 0.2], 1e-3)
    raw = kept = Q.identity()
    for _ in range(1_000_000 if n >= 1_000_000 else n):
        raw = Q.multiply(raw, step)
        kept = Q.normalize(Q.multiply(kept, step))
    print(f"\n|q| - 1 after 1,000,000 sequential compositions: {Q.norm(raw) - 1:.2e} without "
          f"normalize, {Q.norm(kept) - 1:.2e} with")


if __name__ == "__main__":
    main()
