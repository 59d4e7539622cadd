"""The z-buffer (image space): every polygon is rasterised in draw order; a pixel takes a
fragment when it is nearer than what the pixel holds (GL_LESS). Vectorised over all the
fragments of a chunk of triangles; the count of writes is the one a sequential z-buffer
makes (a fragment is written when nearer than every earlier one at its pixel)."""

from __future__ import annotations

import numpy as np

from .raster import fragments, resolve_nearest
from .result import HiddenResult
from .view import Prepared, takes_scene, timed

__all__ = ["zbuffer"]


def _writes(pix, depth, order, held) -> int:
    """Sequential depth-test passes: per pixel, in draw order, strictly nearer than all
    before it (``held``: the depth each pixel holds before these fragments)."""
    if not len(pix):
        return 0
    key = np.lexsort((order, pix))
    pix, depth = pix[key], depth[key]
    start = np.flatnonzero(np.r_[True, pix[1:] != pix[:-1]])
    # per pixel: what it holds, then its fragments in draw order
    values = np.insert(depth, start, held[pix[start]])
    is_held = np.zeros(len(values), bool)
    is_held[start + np.arange(len(start))] = True
    group = np.cumsum(is_held) - 1
    # exact ranks (ties: the earlier keeps the lower rank); shifting each pixel's ranks
    # below every earlier pixel's lets one running minimum restart at each pixel
    rank = np.empty(len(values), np.int64)
    rank[np.argsort(values, kind="stable")] = np.arange(len(values))
    shifted = rank - group * (len(values) + 1)
    before = np.minimum.accumulate(shifted)
    wrote = shifted[1:] < before[:-1]
    return int((wrote & ~is_held[1:]).sum())


@takes_scene
def zbuffer(p: Prepared) -> HiddenResult:
    """The notes' z-buffer in numpy: every triangle's pixels, nearest depth kept per pixel.
    Takes a :class:`Prepared` view or ``(scene or mesh, camera, size (W, H))``; returns ids
    (H, W), depth (view units) and the counts of fragments and pixels written."""
    counters = {"polygons": p.n_polygons, "triangles": len(p.tris), "fragments": 0,
                "pixels written": 0}

    def run(result: HiddenResult):
        # (the float64 depths resolve_nearest keeps: one array, there from the start, so a
        # view where no fragment falls on a pixel centre is simply blank)
        exact = result.__dict__.setdefault("_depth64", np.full(p.n_pixels, np.inf))
        for pix, tri, depth in fragments(p, p.screen, p.tris, counters):
            order = p.order[tri]
            counters["fragments"] += len(pix)
            counters["pixels written"] += _writes(pix, depth, order, exact)
            resolve_nearest(p, result, pix, tri, depth, order)
        counters["depth tests"] = counters.pop("fragments")
        counters["inside tests"] = counters.pop("inside tests", 0)
        counters.pop("inside", None)

    result = timed("zbuffer", p, run)
    result.counters = counters
    return result
