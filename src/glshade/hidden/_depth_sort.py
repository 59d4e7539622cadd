"""Depth sort, the painter's algorithm of Newell, Newell and Sancha (object space).

Polygons are sorted by their farthest depth, farthest first. Before the farthest, P, is
painted, every polygon Q whose depth range overlaps P's is checked, the tests in order of
cost -- any that holds means P may go first:

1. the screen x-extents of P and Q do not overlap;
2. their y-extents do not overlap;
3. P lies wholly on the far side of Q's plane (seen from the eye);
4. Q lies wholly on the near side of P's plane;
5. their projections do not overlap (separating axes of the two triangles).

If every test fails for some Q, Q moves to the front of the list and is checked in turn;
a polygon that would move twice is part of a cycle (mutually overlapping bars, or
polygons that pierce each other), and is split by the other's plane, its pieces going back
into the list. With ``split=False`` a cycle is an error that names the polygons.

One Python step per polygon painted or moved (the resolution is sequential by nature);
each step checks P against all its overlapping Q at once.
"""

from __future__ import annotations

import numpy as np

from ..errors import DepthSortCycle
from ._bsp import Pieces, paint
from .result import HiddenResult
from .view import Prepared, split_by_plane, takes_scene, timed

__all__ = ["depth_sort", "DepthSortCycle"]


def _sat_separated(a: np.ndarray, b: np.ndarray, eps: float) -> np.ndarray:
    """Whether triangles ``a`` (3, 2) and each of ``b`` (n, 3, 2) are separated in 2D by an
    axis normal to one of their edges (touching counts as separated)."""
    n = len(b)
    out = np.zeros(n, bool)
    tris = [np.broadcast_to(a, (n, 3, 2)), b]
    for t in tris:
        for k in range(3):
            e = t[:, (k + 1) % 3] - t[:, k]
            axis = np.stack([-e[:, 1], e[:, 0]], 1)
            pa = np.einsum("nkd,nd->nk", tris[0], axis)
            pb = np.einsum("nkd,nd->nk", tris[1], axis)
            scale = eps * (np.abs(axis).sum(1) + 1e-300)
            out |= (pa.max(1) <= pb.min(1) + scale) | (pb.max(1) <= pa.min(1) + scale)
    return out


@takes_scene
def depth_sort(p: Prepared, split: bool = True) -> HiddenResult:
    """Newell, Newell and Sancha's depth sort (the painter's algorithm made right): polygons
    sorted far to near, overlapping pairs tested and reordered, cycles broken by splitting
    (``split``) -- then painted back to front. Same inputs and result as :func:`zbuffer`,
    with the paint order kept for its steps."""
    counters = {"polygons": p.n_polygons, "triangles": len(p.tris), "comparisons": 0,
                "tests": 0, "moves": 0, "splits": 0, "pieces painted": 0}
    extent = float(np.abs(p.tris).max()) if len(p.tris) else 1.0
    eps = 1e-9 * extent

    def run(result: HiddenResult):
        pieces = Pieces(p.tris, np.arange(len(p.tris)))
        sequence = _resolve(p, pieces, split, eps, counters)
        counters["pieces painted"] = len(sequence)
        result.painted = paint(p, result, pieces, np.array(sequence, np.int64), counters)

    result = timed("depth-sort", p, run)
    result.counters = counters
    return result


def _resolve(p: Prepared, pieces: Pieces, split: bool, eps: float, counters) -> list[int]:
    """The painting order (piece indices, far to near)."""
    t_all, _, _ = pieces.arrays()
    cache = _Cache(p, pieces)
    depth = -t_all[:, :, 2]
    # the list, farthest first (ties: in draw order, so that the first drawn is painted
    # last among equals)
    todo = list(np.lexsort((-np.arange(len(t_all)), -depth.max(1))))
    moved: set[int] = set()
    out: list[int] = []
    while todo:
        P = todo[0]
        rest = np.array(todo[1:], np.int64)
        blocker = _first_blocker(cache, P, rest, eps, counters) if len(rest) else None
        if blocker is None:
            out.append(P)
            todo.pop(0)
            continue
        Q = int(rest[blocker])
        # the tests again with P and Q swapped: may Q be painted before P?
        counters["tests"] += 2
        swapped = _swapped_ok(cache, P, Q, eps)
        straddling = _choose_split(cache, P, Q, eps)
        if swapped and (Q not in moved or straddling is None):
            # Q goes first (a second move without a plane to split by is allowed, up to a
            # bound: a true cycle always has a polygon that straddles another's plane)
            moved.add(Q)
            counters["moves"] += 1
            # (the bound grows with the pieces that splitting makes: each may move)
            if counters["moves"] > 20 * pieces.size + 100:
                raise DepthSortCycle("depth sort keeps reordering the same polygons (an "
                                     "unresolved cycle); use the BSP or the z-buffer")
            todo.remove(Q)
            todo.insert(0, Q)
            continue
        if not split:
            raise DepthSortCycle(
                f"polygons {int(p.ids[cache.src(P)])} and {int(p.ids[cache.src(Q)])} "
                "overlap cyclically (or pierce each other): depth sort cannot order them "
                "without splitting (use split=True)")
        if straddling is None:  # (cannot happen for a true cycle: see above)
            raise DepthSortCycle(f"polygons {int(p.ids[cache.src(P)])} and "
                                 f"{int(p.ids[cache.src(Q)])} cannot be ordered or split")
        # a cycle, or polygons piercing each other: split one by the other's plane
        victim, by = straddling
        n, d = cache.plane(by)
        t, s, c = pieces.arrays()
        ft, fs, fc, bt, bs, bc = split_by_plane(t[victim][None], n, np.array([d]), eps,
                                                c[victim][None])
        counters["splits"] += 1
        new = list(pieces.add(np.concatenate([ft, bt]), s[[victim] * (len(ft) + len(bt))],
                              np.concatenate([fc, bc])))
        cache.grow()
        todo.remove(victim)
        moved.discard(victim)
        # back into the list (farthest first) by their farthest depth
        far = cache.zmax
        for k in new:
            pos = 0
            while pos < len(todo) and far[todo[pos]] >= far[k]:
                pos += 1
            todo.insert(pos, k)
    return out


class _Cache:
    """Per-piece data the tests need (screen triangle, extents, planes)."""

    def __init__(self, p: Prepared, pieces: Pieces):
        self.p, self.pieces = p, pieces
        self.grow()

    def grow(self):
        t, s, _ = self.pieces.arrays()
        self.t = t
        self._src = s
        self.screen = self.p.to_screen(t)
        self.lo, self.hi = self.screen.min(1), self.screen.max(1)
        self.zmin, self.zmax = (-t[:, :, 2]).min(1), (-t[:, :, 2]).max(1)
        self.n = self.pieces._n[:self.pieces.size, :3]
        self.d = self.pieces._n[:self.pieces.size, 3]

    def src(self, k):
        return self._src[k]

    def plane(self, k):
        return self.n[k], self.d[k]


def _behind(c: _Cache, a: int, b: int, eps: float) -> bool:
    """Whether polygon ``a`` lies wholly on the far side of ``b``'s plane from the eye."""
    n, d = c.plane(b)
    eye = c.p.eye_side(n, d)
    if abs(eye) <= eps:
        return True  # b is seen edge-on
    return bool(((c.t[a] @ n - d) * np.sign(eye) <= eps).all())


def _in_front(c: _Cache, a: int, b: int, eps: float) -> bool:
    """Whether polygon ``a`` lies wholly on the eye's side of ``b``'s plane."""
    n, d = c.plane(b)
    eye = c.p.eye_side(n, d)
    if abs(eye) <= eps:
        return True
    return bool(((c.t[a] @ n - d) * np.sign(eye) >= -eps).all())


def _swapped_ok(c: _Cache, P: int, Q: int, eps: float) -> bool:
    """Tests 3 and 4 with P and Q exchanged (1, 2 and 5 are symmetric)."""
    return _behind(c, Q, P, eps) or _in_front(c, P, Q, eps)


def _first_blocker(c: _Cache, P: int, rest: np.ndarray, eps: float, counters):
    """The first Q in ``rest`` that P must not be painted before (every test fails), or
    None."""
    # only polygons reaching farther than P's nearest point are compared
    q = rest[c.zmax[rest] > c.zmin[P] + eps]
    if not len(q):
        return None
    counters["comparisons"] += len(q)
    ok = (c.hi[q, 0] <= c.lo[P, 0]) | (c.lo[q, 0] >= c.hi[P, 0])          # 1: x
    ok |= (c.hi[q, 1] <= c.lo[P, 1]) | (c.lo[q, 1] >= c.hi[P, 1])         # 2: y
    left = q[~ok]
    counters["tests"] += len(q) + len(left)
    if len(left):
        # 3: P wholly on the far side of Q's plane
        nq, dq = c.n[left], c.d[left]
        side = np.einsum("kd,nd->nk", c.t[P], nq) - dq[:, None]   # (n, 3)
        eye = c.p.eye_side(nq, dq)                                 # the eye's side
        far = np.where(np.abs(eye) <= eps, True, (side * np.sign(eye)[:, None] <= eps).all(1))
        # 4: Q wholly on the near side of P's plane
        n_p, d_p = c.n[P], c.d[P]
        side_q = np.einsum("nkd,d->nk", c.t[left], n_p) - d_p
        eye_p = float(c.p.eye_side(n_p, d_p))
        near = (side_q * np.sign(eye_p) >= -eps).all(1) if abs(eye_p) > eps else \
            np.ones(len(left), bool)
        sub_ok = far | near
        rem = left[~sub_ok]
        counters["tests"] += len(left) + len(rem)
        if len(rem):
            sub_ok[~sub_ok] = _sat_separated(c.screen[P], c.screen[rem], 1e-12)  # 5
        ok[~ok] = sub_ok
    blocked = np.flatnonzero(~ok)
    if not len(blocked):
        return None
    return int(np.flatnonzero(np.isin(rest, q[blocked[0]]))[0])


def _choose_split(c: _Cache, P: int, Q: int, eps: float):
    """(polygon to split, polygon whose plane splits it): one that straddles the other's
    plane, preferring to split Q; None if neither does."""
    for victim, by in ((Q, P), (P, Q)):
        n, d = c.plane(by)
        side = c.t[victim] @ n - d
        if (side > eps).any() and (side < -eps).any():
            return victim, by
    return None
