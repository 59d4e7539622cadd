"""A bounding-volume hierarchy over triangles, built in numpy for the GPU (the path
tracer and the exact shadow rays).

Built a level at a time: every node of a level that holds more than ``leaf_size``
triangles is split along the longest axis of its triangles' centroids, at the plane of
SAH_BINS - 1 evenly spaced ones that minimises the surface-area heuristic (the children's
box areas times their triangle counts: what a ray that enters the node expects to pay),
or at the median where no plane separates anything (all centroids in one bin). One
``lexsort`` orders the whole level, keyed by node, so the build is O(T log T) with a
Python loop per *level*, never per node or triangle. Children are numbered consecutively
(the right child is the left one plus one) and leaves point into the triangles in their
sorted order, which is what a stack traversal on the GPU wants."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["BVH", "build", "PackedChildren", "packed_children", "NO_CHILDREN"]


@dataclass(frozen=True)
class BVH:
    """``lo``, ``hi`` (N, 3) node boxes; ``first`` (N,) the left child of an inner node or
    the first triangle of a leaf; ``count`` (N,) 0 for an inner node, else the leaf's
    triangles; ``order`` (T,) the triangles' sorted order (leaf ranges index into it);
    ``depth`` the number of levels.

    Parameters
    ----------
    lo, hi : ndarray
        ``(N, 3)`` node boxes.
    first : ndarray
        ``(N,)`` an inner node's left child, or a leaf's first triangle.
    count : ndarray
        ``(N,)`` 0 for an inner node, else the leaf's triangles.
    order : ndarray
        ``(T,)`` the triangles' sorted order (leaf ranges index into it).
    depth : int
        The levels.
    """

    lo: np.ndarray
    hi: np.ndarray
    first: np.ndarray
    count: np.ndarray
    order: np.ndarray
    depth: int

    @property
    def n_nodes(self) -> int:
        return len(self.first)


def _ranges(starts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """The indices of consecutive ranges ``[s, s + c)``, concatenated."""
    offsets = np.cumsum(counts) - counts
    return np.arange(counts.sum()) - np.repeat(offsets - starts, counts)


#: candidate split planes a node's surface-area heuristic weighs, along its longest axis
SAH_BINS = 16


def _sah_splits(c: np.ndarray, box_lo: np.ndarray, box_hi: np.ndarray, seg: np.ndarray,
                offsets: np.ndarray, n_seg: int) -> tuple[np.ndarray, np.ndarray]:
    """For the triangles of ``n_seg`` nodes (their centroids ``c`` along each node's axis,
    their boxes, ``seg`` the node of each, nodes' ranges starting at ``offsets``): each
    triangle's side (True: right) and each node's left count, by the binned surface-area
    heuristic (the plane of SAH_BINS - 1 that minimises the children's area x count);
    nodes where no plane separates anything get the median (count 0 returned: the caller's)."""
    cmin = np.minimum.reduceat(c, offsets)
    width = np.maximum.reduceat(c, offsets) - cmin
    scale = np.where(width > 0, SAH_BINS / np.where(width > 0, width, 1.0), 0.0)
    b = np.minimum(((c - cmin[seg]) * scale[seg]).astype(np.int64), SAH_BINS - 1)
    key = seg * SAH_BINS + b
    count = np.bincount(key, minlength=n_seg * SAH_BINS).reshape(n_seg, SAH_BINS)
    flat_lo = np.full((n_seg * SAH_BINS, 3), np.inf)
    flat_hi = np.full((n_seg * SAH_BINS, 3), -np.inf)
    np.minimum.at(flat_lo, key, box_lo)
    np.maximum.at(flat_hi, key, box_hi)
    lo, hi = flat_lo.reshape(n_seg, SAH_BINS, 3), flat_hi.reshape(n_seg, SAH_BINS, 3)

    def area(a, z):
        d = np.maximum(z - a, 0.0)
        return d[..., 0] * d[..., 1] + d[..., 1] * d[..., 2] + d[..., 2] * d[..., 0]

    left = area(np.minimum.accumulate(lo, 1), np.maximum.accumulate(hi, 1))
    right = area(np.minimum.accumulate(lo[:, ::-1], 1), np.maximum.accumulate(hi[:, ::-1], 1))
    n_left = np.cumsum(count, 1)
    n_right = np.cumsum(count[:, ::-1], 1)[:, ::-1]
    # plane k: bins [0, k] left, (k, SAH_BINS) right
    cost = left[:, :-1] * n_left[:, :-1] + right[:, ::-1][:, 1:] * n_right[:, 1:]
    cost = np.where((n_left[:, :-1] > 0) & (n_right[:, 1:] > 0), cost, np.inf)
    plane = cost.argmin(1)
    ok = np.isfinite(cost[np.arange(n_seg), plane])
    side = b > plane[seg]
    side &= ok[seg]
    return side, np.where(ok, n_left[np.arange(n_seg), plane], 0)


def build(triangles: np.ndarray, leaf_size: int = 4, sah: bool = True) -> BVH:
    """The hierarchy of ``triangles`` ``(T, 3, 3)``: nodes split by the binned surface-area
    heuristic (``sah``) or at the median along their longest axis.

    Parameters
    ----------
    triangles : ndarray
        ``(T, 3, 3)`` positions.
    leaf_size : int
        The most triangles a leaf holds (the GPU's packing allows 15).
    sah : bool
        Split by the binned surface-area heuristic (else at the median).
    """
    tri = np.asarray(triangles, np.float64)
    n = len(tri)
    if n == 0:
        raise ValueError("no triangles to build a hierarchy over")
    tlo, thi = tri.min(1), tri.max(1)
    centre = 0.5 * (tlo + thi)
    order = np.arange(n)
    start, end, first = [np.array([0])], [np.array([n])], []
    level = [np.array([0])]
    total = 1
    while True:
        s, e = start[-1], end[-1]
        split = (e - s) > leaf_size
        child = np.full(len(s), -1)
        if not split.any():
            first.append(child)
            break
        s, e = s[split], e[split]
        counts = e - s
        idx = _ranges(s, counts)
        seg = np.repeat(np.arange(len(s)), counts)
        c = centre[order[idx]]
        offsets = np.cumsum(counts) - counts
        extent = np.maximum.reduceat(c, offsets) - np.minimum.reduceat(c, offsets)
        axis = extent.argmax(1)
        along = c[np.arange(len(idx)), axis[seg]]
        mid = (s + e) // 2
        side = np.zeros(len(idx), bool)
        if sah:
            tri_ids = order[idx]
            side, n_left = _sah_splits(along, tlo[tri_ids], thi[tri_ids], seg, offsets, len(s))
            mid = np.where(n_left > 0, s + n_left, mid)
        perm = np.lexsort((along, side, seg))
        order[idx] = order[idx][perm]
        child[split] = total + 2 * np.arange(len(s))
        first.append(child)
        start.append(np.stack([s, mid], 1).ravel())
        end.append(np.stack([mid, e], 1).ravel())
        level.append(total + np.arange(2 * len(s)))
        total += 2 * len(s)
    starts, ends = np.concatenate(start), np.concatenate(end)
    child = np.concatenate(first)
    lo, hi = np.empty((total, 3)), np.empty((total, 3))
    slo, shi = tlo[order], thi[order]
    for ids, s, e in zip(level, start, end):
        # the ranges of one level are disjoint: one reduceat over their bounds (and gaps)
        cuts = np.unique(np.concatenate([s, e]))
        cuts = cuts[cuts < n]
        at = np.searchsorted(cuts, s)
        lo[ids] = np.minimum.reduceat(slo, cuts)[at]
        hi[ids] = np.maximum.reduceat(shi, cuts)[at]
    leaf = child < 0
    return BVH(lo, hi, np.where(leaf, starts, child), np.where(leaf, ends - starts, 0),
               order, len(level))


#: a child's box is kept in 16-bit steps of the root box (and its triangle or node index in
#: 28 bits, its triangle count in 4)
QUANTUM_STEPS = 65535
MAX_PACKED_COUNT, MAX_PACKED_INDEX = 15, (1 << 28) - 1


@dataclass(frozen=True)
class PackedChildren:
    """A hierarchy as a GPU ray reads it: ``entries`` ``(I, 8)`` uint32, a row per inner
    node holding its two children -- each child four words:
    its box's corners as 16-bit steps of the root box (``base + q * step`` in float32 lies
    at or outside the true corner: rounded outward with a margin for float32's own
    rounding), then ``index << 4 | count`` (count 0: an inner node, its row; else a
    leaf's triangles from index). A step loads 32 bytes instead of three 32-byte nodes.

    Parameters
    ----------
    entries : ndarray
        ``(I, 8)`` uint32, a row an inner node: its two children, four words each (the box
        as 16-bit steps of the root's, then ``index << 4 | count``).
    base, step : ndarray
        ``(3,)`` float32: a corner q (in steps) lies at ``base + q * step``.
    root : ndarray
        ``(4,)`` uint32 the root, packed as a child.
    """

    entries: np.ndarray
    base: np.ndarray
    step: np.ndarray
    root: np.ndarray  # (4,) the root packed as a child

    def uniforms(self) -> dict:
        """The root and the boxes' quantum as the shaders take them (``u_root``,
        ``u_qbase``, ``u_qstep``)."""
        return {"u_root": tuple(int(w) for w in self.root),
                "u_qbase": tuple(float(v) for v in self.base),
                "u_qstep": tuple(float(v) for v in self.step)}


#: the stand-in for no hierarchy (no triangles, or all compiled in: the shaders skip the
#: walk, HIERARCHY undefined or ``u_has_triangles``): one row of zeros, a root of zeros
NO_CHILDREN = PackedChildren(np.zeros((1, 8), np.uint32), np.zeros(3, np.float32),
                             np.ones(3, np.float32), np.zeros(4, np.uint32))


def packed_children(bvh: BVH, first_triangle: int = 0) -> PackedChildren:
    """``bvh``'s children packed for the GPU (``first_triangle``: added to leaves' triangle
    indices, for triangles stored after others).

    Parameters
    ----------
    bvh : BVH
        The hierarchy.
    first_triangle : int
        Added to the leaves' triangle indices (the triangles' place in a larger table).
    """
    if int(bvh.count.max(initial=0)) > MAX_PACKED_COUNT:
        raise ValueError(f"a leaf holds more than {MAX_PACKED_COUNT} triangles")
    lo32, hi32 = bvh.lo[0].astype(np.float32), bvh.hi[0].astype(np.float32)
    reach = float(np.abs(np.concatenate([lo32, hi32])).max())
    # (float32's error in base + q * step is a few ulps of the coordinates: padded)
    ulp = float(np.spacing(np.float32(reach))) + 1e-30
    base = (lo32.astype(np.float64) - 8 * ulp).astype(np.float32)
    top = hi32.astype(np.float64) + 8 * ulp
    step = ((top - base) / QUANTUM_STEPS * (1 + 1e-6)).astype(np.float32)
    margin = 1 + np.ceil(4 * ulp / step.astype(np.float64))
    scale = step.astype(np.float64)
    q_lo = np.clip(np.floor((bvh.lo - base) / scale) - margin, 0, QUANTUM_STEPS)
    q_hi = np.clip(np.ceil((bvh.hi - base) / scale) + margin, 0, QUANTUM_STEPS)
    q_lo, q_hi = q_lo.astype(np.uint32), q_hi.astype(np.uint32)
    n = bvh.n_nodes
    leaf = bvh.count > 0
    inner = np.flatnonzero(~leaf)
    rank = np.cumsum(~leaf) - 1  # (an inner node's row: leaves have none)
    index = np.where(leaf, bvh.first + first_triangle, rank)
    if n and int(index.max()) > MAX_PACKED_INDEX:
        raise ValueError(f"more than {MAX_PACKED_INDEX:,} triangles or nodes to pack")
    child = np.empty((n, 4), np.uint32)
    child[:, 0] = q_lo[:, 0] | (q_lo[:, 1] << 16)
    child[:, 1] = q_lo[:, 2] | (q_hi[:, 0] << 16)
    child[:, 2] = q_hi[:, 1] | (q_hi[:, 2] << 16)
    child[:, 3] = (index.astype(np.uint32) << 4) | np.asarray(bvh.count, np.uint32)
    entries = np.zeros((max(len(inner), 1), 8), np.uint32)
    entries[:len(inner), :4] = child[bvh.first[inner]]
    entries[:len(inner), 4:] = child[bvh.first[inner] + 1]
    return PackedChildren(entries, base, step, child[0].copy())
