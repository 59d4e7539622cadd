"""A bounding-volume hierarchy over triangles, built in numpy for the GPU (the path
tracer and the exact shadow rays).

Median splits, built a level at a time: every node of a level that holds more than
``leaf_size`` triangles sorts its triangles by centroid along the longest axis of their
centroids' box (one ``lexsort`` for the whole level, keyed by node) and hands each half to
a child. So the build is O(T log T) with a Python loop per *level* (about log2(T / 4) of
them), never per node or triangle. Children are numbered consecutively (the right child is
the left one plus one) and leaves point into the triangles in their sorted order, which is
what a stack traversal on the GPU wants."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["BVH", "build"]


@dataclass(frozen=True)
class BVH:
    """``lo``, ``hi`` (N, 3) node boxes; ``first`` (N,) the left child of an inner node or
    the first triangle of a leaf; ``count`` (N,) 0 for an inner node, else the leaf's
    triangles; ``order`` (T,) the triangles' sorted order (leaf ranges index into it);
    ``depth`` the number of levels."""

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


def build(triangles: np.ndarray, leaf_size: int = 4) -> BVH:
    """The hierarchy of ``triangles`` ``(T, 3, 3)``."""
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
        perm = np.lexsort((c[np.arange(len(idx)), axis[seg]], seg))
        order[idx] = order[idx][perm]
        mid = (s + e) // 2
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
