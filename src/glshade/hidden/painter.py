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
each step checks P against all its overlapping Q at once. The overlaps are found through a
screen grid the first time P is at the head of the list; after that, P remembers the Q it
has not yet passed and is tested only against those and the pieces split off since (a
pair's answer depends on the pair alone), so a polygon met again costs little.
"""

from __future__ import annotations

import bisect

import numpy as np

from ..errors import DepthSortCycle
from ._bsp import Pieces, paint
from .result import HiddenResult
from .view import Prepared, takes_scene, timed

__all__ = ["depth_sort", "DepthSortCycle"]


def _edge_axes(screen: np.ndarray):
    """Each screen triangle's (n, 3, 2) edge normals (the separating axes of test 5), its
    own extent along them (n, 3) twice, and the tolerance of each axis (n, 3)."""
    e = screen[:, [1, 2, 0]] - screen
    axes = np.stack([-e[..., 1], e[..., 0]], -1)
    own = axes @ screen.transpose(0, 2, 1)                      # (n, axis, vertex)
    return axes, own.min(-1), own.max(-1), 1e-12 * (np.abs(axes).sum(-1) + 1e-300)


def _sat_separated(c, P: int, b: np.ndarray) -> np.ndarray:
    """Whether triangle ``P`` and each of ``b`` are separated on screen by an axis normal
    to one of their edges (touching counts as separated): all six axes of every pair at
    once, each triangle's extent along its own axes computed once (``c.axes``, ...)."""
    on_p = c.screen[b] @ c.axes[P].T                           # (n, vertex, P's axis)
    lo, hi = on_p.min(1), on_p.max(1)
    apart = ((c.own_hi[P] <= lo + c.tol[P]) | (hi <= c.own_lo[P] + c.tol[P])).any(1)
    on_b = c.axes[b] @ c.screen[P].T                           # (n, b's axis, vertex)
    lo, hi = on_b.min(2), on_b.max(2)
    return apart | ((hi <= c.own_lo[b] + c.tol[b]) | (c.own_hi[b] <= lo + c.tol[b])).any(1)


@takes_scene
def depth_sort(p: Prepared, split: bool = True) -> HiddenResult:
    """Newell, Newell and Sancha's depth sort (the painter's algorithm made right): polygons
    sorted far to near, overlapping pairs tested and reordered, cycles broken by splitting
    (``split``) -- then painted back to front. Same inputs and result as :func:`zbuffer`,
    with the paint order kept for its steps.

    Parameters
    ----------
    p : Prepared
        The view.
    split : bool
        Split polygons whose order is cyclic (else they are drawn in some order).
    """
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


class _Todo:
    """The list still to paint: ``front``, the polygons moved to its head (most recent
    first), then ``main``, sorted by farthest depth, farthest first (``keys``: minus that
    depth, ascending). Each piece's place in it as sortable numbers (``group``: 0 front,
    1 main; ``key``; ``seq``: ties, in insertion order), so a set of pieces is put in list
    order without scanning the list."""

    def __init__(self, order: np.ndarray, zmax: np.ndarray, capacity: int):
        self.front: list[int] = []
        self.main = [int(k) for k in order]
        self.keys = [float(-zmax[k]) for k in order]
        self.group = np.ones(capacity, np.int8)
        self.key = np.zeros(capacity)
        self.seq = np.zeros(capacity, np.int64)
        self.alive = np.zeros(capacity, bool)
        self.key[order], self.seq[order], self.alive[order] = -zmax[order], \
            np.arange(len(order)), True
        self._next, self._stamp = len(order), 0

    def __bool__(self) -> bool:
        return bool(self.front or self.main)

    def head(self) -> int:
        return self.front[0] if self.front else self.main[0]

    def pop_head(self) -> None:
        k = self.head()
        if self.front:
            self.front.pop(0)
        else:
            self.main.pop(0)
            self.keys.pop(0)
        self.alive[k] = False

    def in_order(self, ids: np.ndarray) -> np.ndarray:
        """``ids`` (repeats allowed) in list order, each once."""
        ids = ids[np.lexsort((ids, self.seq[ids], self.key[ids], self.group[ids]))]
        keep = np.ones(len(ids), bool)
        keep[1:] = ids[1:] != ids[:-1]
        return ids[keep]

    def remove(self, k: int) -> None:
        self.alive[k] = False
        if self.group[k] == 0:
            self.front.remove(k)
            return
        i = bisect.bisect_left(self.keys, self.key[k])
        while self.main[i] != k:
            i += 1
        del self.main[i], self.keys[i]

    def to_front(self, k: int) -> None:
        self.remove(k)
        self.front.insert(0, k)
        self._stamp += 1
        self.group[k], self.key[k], self.alive[k] = 0, -self._stamp, True

    def insert(self, k: int, zmax: float) -> None:
        """Into ``main`` after every polygon reaching as far or farther."""
        if k >= len(self.alive):
            cap = max(k + 1, 2 * len(self.alive))
            for name in ("group", "key", "seq", "alive"):
                old = getattr(self, name)
                new = np.zeros(cap, old.dtype)
                new[:len(old)] = old
                setattr(self, name, new)
        i = bisect.bisect_right(self.keys, -zmax)
        self.main.insert(i, k)
        self.keys.insert(i, -zmax)
        self.group[k], self.key[k], self.seq[k], self.alive[k] = 1, -zmax, self._next, True
        self._next += 1


class _Grid:
    """The spatial index of the overlap tests: square screen cells, each listing the
    pieces whose screen box meets it (pieces painted or split stay listed, and are
    filtered out when met)."""

    def __init__(self, size, lo: np.ndarray, hi: np.ndarray):
        width, height = size
        span = np.maximum(hi - lo, 1e-9)
        typical = float(np.median(span.max(1))) if len(span) else 1.0
        self.cell = max(typical, max(width, height) / 256, 1.0)
        self.nx = int(np.ceil(width / self.cell)) + 1
        self.ny = int(np.ceil(height / self.cell)) + 1
        self.cells: list[list[int]] = [[] for _ in range(self.nx * self.ny)]
        self.add(np.arange(len(lo)), lo, hi)

    def _range(self, lo, hi):
        """The cells' x and y index ranges of boxes (clamped to the image's cells)."""
        a = np.clip(np.floor(lo / self.cell), 0, [self.nx - 1, self.ny - 1]).astype(np.int64)
        b = np.clip(np.floor(hi / self.cell), 0, [self.nx - 1, self.ny - 1]).astype(np.int64)
        return a, b

    def add(self, ids: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> None:
        if len(ids) <= 4:   # a split's pieces: plain loops cost less than the sort
            c, nx, ny = self.cell, self.nx - 1, self.ny - 1
            for k, (x0, y0), (x1, y1) in zip(ids.tolist(), lo.tolist(), hi.tolist()):
                for y in range(min(max(int(y0 // c), 0), ny), min(max(int(y1 // c), 0), ny) + 1):
                    row = y * self.nx
                    for x in range(min(max(int(x0 // c), 0), nx),
                                   min(max(int(x1 // c), 0), nx) + 1):
                        self.cells[row + x].append(k)
            return
        a, b = self._range(lo, hi)
        count = (b - a + 1).prod(1)
        piece = np.repeat(ids, count)
        k = np.arange(len(piece)) - np.repeat(np.cumsum(count) - count, count)
        w = np.repeat(b[:, 0] - a[:, 0] + 1, count)
        x = np.repeat(a[:, 0], count) + k % w
        y = np.repeat(a[:, 1], count) + k // w
        cell = y * self.nx + x
        order = np.argsort(cell, kind="stable")
        cell, piece = cell[order], piece[order]
        cuts = np.flatnonzero(np.diff(cell)) + 1
        for c, group in zip(cell[np.r_[0, cuts]] if len(cell) else [],
                            np.split(piece, cuts)):
            self.cells[int(c)].extend(group.tolist())

    def near(self, lo, hi, alive: np.ndarray) -> np.ndarray:
        """The ``alive`` pieces listed in the cells a box meets (with repeats; a cell's
        list is rewritten without the others as it is read)."""
        c, nx, ny = self.cell, self.nx - 1, self.ny - 1
        x0, y0 = min(max(int(lo[0] // c), 0), nx), min(max(int(lo[1] // c), 0), ny)
        x1, y1 = min(max(int(hi[0] // c), 0), nx), min(max(int(hi[1] // c), 0), ny)
        parts = []
        for y in range(y0, y1 + 1):
            for x in range(x0, x1 + 1):
                k = y * self.nx + x
                ids = np.array(self.cells[k], np.int64)
                keep = ids[alive[ids]]
                if len(keep) < len(ids):
                    self.cells[k] = keep.tolist()
                parts.append(keep)
        return np.concatenate(parts) if parts else np.zeros(0, np.int64)


class _Met:
    """What each polygon met when it was last at the head of the list: the pieces it has
    not passed the tests against (its blocker and those not yet tested) and the number of
    pieces then. Met again -- after the polygons moved before it are painted, or a piece
    split off -- it is tested only against those and the pieces made since (a pair's
    answer depends on the pair alone; pieces are numbered as they are made)."""

    def __init__(self) -> None:
        self.undecided: dict[int, tuple[np.ndarray, int]] = {}

    def candidates(self, P: int, c: _Cache, alive: np.ndarray, grid: _Grid, eps: float,
                   counters) -> np.ndarray:
        """The alive pieces P may have to wait for (repeats allowed), tests 1 and 2 done."""
        seen = self.undecided.get(P)
        if seen is None:
            near = grid.near(c.lo[P], c.hi[P], alive)
        else:
            ids, size = seen
            near = np.concatenate((ids[alive[ids]], np.flatnonzero(alive[size:c.size]) + size))
        near = near[(near != P) & (c.zmax[near] > c.zmin[P] + eps)]
        counters["comparisons"] += len(near)
        near = near[_overlap_xy(c, P, near)]                           # tests 1 and 2
        counters["tests"] += 2 * len(near)
        return near

    def note(self, P: int, undecided: np.ndarray, size: int) -> None:
        self.undecided[P] = (undecided, size)


def _resolve(p: Prepared, pieces: Pieces, split: bool, eps: float, counters) -> list[int]:
    """The painting order (piece indices, far to near)."""
    cache = _Cache(p, pieces, eps)
    # the list, farthest first (ties: in draw order, so that the first drawn is painted
    # last among equals)
    n = pieces.size
    todo = _Todo(np.lexsort((-np.arange(n), -cache.zmax[:n])), cache.zmax[:n], 2 * n + 16)
    grid = _Grid(p.size, cache.lo[:n], cache.hi[:n])
    moved: set[int] = set()
    out: list[int] = []
    met = _Met()
    while todo:
        P = todo.head()
        near = met.candidates(P, cache, todo.alive, grid, eps, counters)
        Q, undecided = _first_blocker(cache, P, todo.in_order(near), eps, counters) \
            if len(near) else (None, near)
        met.note(P, undecided, cache.size)
        if Q is None:
            out.append(P)
            todo.pop_head()
            continue
        # the tests again with P and Q swapped: may Q be painted before P?
        counters["tests"] += 2
        swapped = _swapped_ok(cache, P, Q, eps)
        straddling = _choose_split(cache, P, Q, eps)
        if straddling is None and Q in moved and Q in todo.front:
            # a cycle through the polygons moved since Q was (P .. Q at the list's
            # head): P and Q are ordered, so some other pair of it straddles a plane
            straddling = _cycle_split(cache, todo.front[:todo.front.index(Q) + 1], eps)
            swapped = swapped and straddling is None
        if swapped and (Q not in moved or straddling is None):
            # Q goes first (a second move without a plane to split by is allowed, up to a
            # bound: a true cycle always has a polygon that straddles another's plane)
            moved.add(Q)
            counters["moves"] += 1
            # (the bound grows with the pieces that splitting makes: each may move)
            if counters["moves"] > 20 * pieces.size + 100:
                raise DepthSortCycle("depth sort keeps reordering the same polygons (an "
                                     "unresolved cycle); use the BSP or the z-buffer")
            todo.to_front(Q)
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
        n_by, d_by = cache.plane(by)
        t, s, c = pieces.arrays()
        tris, cuts = split_one(t[victim].tolist(), n_by.tolist(), float(d_by), eps,
                                c[victim].tolist())
        counters["splits"] += 1
        new = pieces.add(tris, np.full(len(tris), s[victim]), cuts, pieces._n[victim])
        cache.grow()
        todo.remove(victim)
        moved.discard(victim)
        for k in new:  # back into the list (farthest first) by their farthest depth
            todo.insert(int(k), cache.zmax[k])
        grid.add(new, cache.lo[new], cache.hi[new])
    return out


class _Cache:
    """Per-piece data the tests need (screen triangle, extents, planes), grown with the
    pieces (only the new ones computed)."""

    def __init__(self, p: Prepared, pieces: Pieces, eps: float):
        self.p, self.pieces, self.eps = p, pieces, eps
        self.size = 0
        cap = max(16, 2 * pieces.size)
        self.screen = np.empty((cap, 3, 2))
        self.lo, self.hi = np.empty((cap, 2)), np.empty((cap, 2))
        self.box = np.empty((cap, 4))   # lo, hi: one gather for tests 1 and 2
        self.axes = np.empty((cap, 3, 2))
        self.own_lo, self.own_hi, self.tol = (np.empty((cap, 3)) for _ in range(3))
        self.zmin, self.zmax = np.empty(cap), np.empty(cap)
        self.eye = np.empty(cap)  # the eye's side of each plane (zero: seen edge-on)
        self.sgn = np.empty(cap)  # its sign, 0 within eps (edge-on: no side to be on)
        self.grow()

    def grow(self):
        start, stop = self.size, self.pieces.size
        if stop > len(self.zmin):
            cap = max(stop, 2 * len(self.zmin))
            for name in ("screen", "lo", "hi", "zmin", "zmax", "eye", "sgn", "box", "axes",
                         "own_lo", "own_hi", "tol"):
                old = getattr(self, name)
                new = np.empty((cap, *old.shape[1:]))
                new[:start] = old[:start]
                setattr(self, name, new)
        t, s, _ = self.pieces.arrays()
        self.t, self._src = t, s
        self.screen[start:stop] = self.p.to_screen(t[start:stop])
        self.lo[start:stop] = self.screen[start:stop].min(1)
        self.hi[start:stop] = self.screen[start:stop].max(1)
        self.box[start:stop, :2], self.box[start:stop, 2:] = self.lo[start:stop], \
            self.hi[start:stop]
        self.axes[start:stop], self.own_lo[start:stop], self.own_hi[start:stop], \
            self.tol[start:stop] = _edge_axes(self.screen[start:stop])
        self.zmin[start:stop] = (-t[start:stop, :, 2]).min(1)
        self.zmax[start:stop] = (-t[start:stop, :, 2]).max(1)
        self.n = self.pieces._n[:stop, :3]
        self.d = self.pieces._n[:stop, 3]
        self.eye[start:stop] = self.p.eye_side(self.n[start:stop], self.d[start:stop])
        self.sgn[start:stop] = np.where(np.abs(self.eye[start:stop]) <= self.eps, 0.0,
                                        np.sign(self.eye[start:stop]))
        self.size = stop

    def src(self, k):
        return self._src[k]

    def plane(self, k):
        return self.n[k], self.d[k]


def _behind(c: _Cache, a: int, b: int, eps: float) -> bool:
    """Whether polygon ``a`` lies wholly on the far side of ``b``'s plane from the eye."""
    n, d = c.plane(b)
    eye = c.eye[b]
    if abs(eye) <= eps:
        return True  # b is seen edge-on
    return bool(((c.t[a] @ n - d) * np.sign(eye) <= eps).all())


def _in_front(c: _Cache, a: int, b: int, eps: float) -> bool:
    """Whether polygon ``a`` lies wholly on the eye's side of ``b``'s plane."""
    n, d = c.plane(b)
    eye = c.eye[b]
    if abs(eye) <= eps:
        return True
    return bool(((c.t[a] @ n - d) * np.sign(eye) >= -eps).all())


def _swapped_ok(c: _Cache, P: int, Q: int, eps: float) -> bool:
    """Tests 3 and 4 with P and Q exchanged (1, 2 and 5 are symmetric)."""
    return _behind(c, Q, P, eps) or _in_front(c, P, Q, eps)


def _overlap_xy(c: _Cache, P: int, q: np.ndarray) -> np.ndarray:
    """Tests 1 and 2 failed: the screen x- and y-extents of P and each Q overlap."""
    b = c.box[q]
    return ((b[:, 2:] > c.lo[P]) & (b[:, :2] < c.hi[P])).all(1)


def _first_blocker(c: _Cache, P: int, left: np.ndarray, eps: float, counters):
    """The first Q in ``left`` (list order; tests 1 and 2 already failed for each) that P
    must not be painted before (every test fails), or None. Tests 3 and 4 run on all of
    them at once; test 5, the costliest, a chunk at a time, stopping at the first chunk
    with a blocker. Also the Q of ``left`` it has not passed (the blocker, the rest of its
    chunk that failed, the chunks not tested)."""
    # 3: P wholly on the far side of Q's plane; 4: Q wholly on the near side of P's plane
    # (a plane seen edge-on has no side: its sign is 0, and both tests hold)
    far = ((c.t[P] @ c.n[left].T - c.d[left]) * c.sgn[left] <= eps).all(0)
    near = ((c.t[left] @ c.n[P] - c.d[P]) * c.sgn[P] >= -eps).all(1)
    rem = left[~(far | near)]
    counters["tests"] += len(left) + len(rem)
    for start in range(0, len(rem), _CHUNK):
        chunk = rem[start:start + _CHUNK]
        apart = _sat_separated(c, P, chunk)                                   # 5
        blocked = np.flatnonzero(~apart)
        if len(blocked):
            return int(chunk[blocked[0]]), np.concatenate((chunk[blocked], rem[start + _CHUNK:]))
    return None, rem[:0]


#: Q tested at a time by tests 3-5 (a blocker is often among the first)
_CHUNK = 64


def split_one(tri: list, n: list, d: float, eps: float, cut: list):
    """One triangle split by the plane ``n.p = d`` (it straddles it): the pieces on each
    side as triangles (fans of the clipped polygons) and their edges' cut flags (a split
    line or a diagonal, or the original edge's flag) -- as ``view.split_by_plane`` does for
    many, in plain floats for one (the painter splits one at a time)."""
    dist = [sum(a * b for a, b in zip(v, n)) - d for v in tri]
    dist = [0.0 if abs(x) <= eps else x for x in dist]
    tris, cuts = [], []
    for sign in (1.0, -1.0):
        poly, flags = [], []   # the clipped polygon; flags[k]: edge k -> k + 1 is a cut
        for i in range(3):
            j = (i + 1) % 3
            a, b = tri[i], tri[j]
            sa, sb = sign * dist[i], sign * dist[j]
            if sa >= 0:
                poly.append(a)
                flags.append(cut[i] if (sb >= 0 or sa > 0) else True)
            if sa * sb < 0:   # a crossing on edge i: the point, then along the edge or the cut
                f = sa / (sa - sb)
                poly.append([a[k] + (b[k] - a[k]) * f for k in range(3)])
                flags.append(cut[i] if sa < 0 else True)
        m = len(poly)
        for k in range(1, m - 1):   # fan from vertex 0: edges 0-k, k-(k+1), (k+1)-0
            tris.append([poly[0], poly[k], poly[k + 1]])
            cuts.append([flags[0] if k == 1 else True, flags[k],
                         flags[m - 1] if k + 1 == m - 1 else True])
    return tris, cuts


def _cycle_split(c: _Cache, cycle: list[int], eps: float):
    """(polygon to split, polygon whose plane splits it) among the members of a cycle:
    the first pair where one straddles the other's plane; None if none does."""
    ids = np.array(cycle, np.int64)
    side = np.einsum("akd,bd->abk", c.t[ids], c.n[ids]) - c.d[ids][None, :, None]
    straddles = (side > eps).any(2) & (side < -eps).any(2)    # (a, b): a across b's plane
    np.fill_diagonal(straddles, False)
    hit = np.argwhere(straddles)
    if not len(hit):
        return None
    a, b = hit[0]
    return int(ids[a]), int(ids[b])


def _choose_split(c: _Cache, P: int, Q: int, eps: float):
    """(polygon to split, polygon whose plane splits it): one that straddles the other's
    plane, preferring to split Q; None if neither does."""
    for victim, by in ((Q, P), (P, Q)):
        n, d = c.plane(by)
        side = c.t[victim] @ n - d
        if (side > eps).any() and (side < -eps).any():
            return victim, by
    return None
