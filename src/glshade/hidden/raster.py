"""A vectorised rasteriser for the hidden-surface lab: for a batch of triangles, the pixels
whose centres they cover (GL's top-left rule, vertices snapped to the GPU's subpixel grid)
and the exact depth of their plane there; the nearest (z-buffer) and last (painter's)
fragment of each pixel; the pixels on a polygon's edge."""

from __future__ import annotations

import numpy as np

from .result import HiddenResult
from .view import Prepared

__all__ = ["fragments", "resolve_nearest", "resolve_last", "edge_pixels", "SUBPIXEL",
           "CHUNK"]

#: candidate pixel-triangle pairs handled at once (memory, not speed)
CHUNK = 4_000_000
#: GPUs rasterise vertex positions snapped to 1/256 pixel (8 bits of subpixel precision)
SUBPIXEL = 256.0


def fragments(p: Prepared, tris_screen: np.ndarray, tris_view: np.ndarray, counters=None,
              piece_screen: np.ndarray | None = None, cut: np.ndarray | None = None):
    """Yield, per chunk, ``(pixel, triangle, depth)`` for every pixel centre inside each
    triangle (screen ``(T, 3, 2)``, snapped to 1/256 pixel like a GPU's), with the exact
    depth of its view-space plane along the pixel's ray, within [near, far]. Edges: a
    centre exactly on an edge is inside for edges whose outward normal points left or up
    (the top-left rule, image coordinates).

    Pieces of split triangles: ``tris_*`` are then each piece's *source* triangle and
    ``piece_screen`` (unsnapped) with ``cut`` flags the piece; a pixel is the piece's when
    its source covers it (exactly as the GPU covers the source) and it lies on the inner
    side of the piece's cut edges -- so the pieces of a triangle share its pixels out
    with no crack or overlap.

    Parameters
    ----------
    p : Prepared
        The view.
    tris_screen : ndarray
        ``(n, 3, 2)`` the triangles in pixel coordinates.
    tris_view : ndarray
        ``(n, 3, 3)`` the same in view space (their depth).
    counters : dict or None
        Counts to add to (``"inside tests"``, ``"inside"``: pairs tested, pairs inside).
    piece_screen : ndarray or None
        Pieces of triangles to rasterize instead (split by an algorithm).
    cut : ndarray or None
        Which triangles are cut.
    """
    width, height = p.size
    n = len(tris_screen)
    if n == 0:
        return
    tris_screen = np.round(tris_screen * SUBPIXEL) / SUBPIXEL
    box = tris_screen if piece_screen is None else piece_screen
    margin = 0.0 if piece_screen is None else 1 / SUBPIXEL
    lo = np.floor(box.min(1) - margin - 0.5).astype(np.int64) + 1  # first centre >= min
    hi = np.floor(box.max(1) + margin - 0.5).astype(np.int64)      # last centre <= max
    lo = np.maximum(lo, 0)
    hi = np.minimum(hi, [width - 1, height - 1])
    span = np.maximum(hi - lo + 1, 0)
    boxes = span[:, 0] * span[:, 1]
    normal = np.cross(tris_view[:, 1] - tris_view[:, 0], tris_view[:, 2] - tris_view[:, 0])
    offset = np.einsum("nd,nd->n", normal, tris_view[:, 0])
    # signed area in screen space: orientation of each triangle as drawn
    e1, e2 = tris_screen[:, 1] - tris_screen[:, 0], tris_screen[:, 2] - tris_screen[:, 0]
    area = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    start = 0
    while start < n:
        total = np.cumsum(boxes[start:])
        stop = start + max(1, int(np.searchsorted(total, CHUNK, side="right")))
        idx = np.arange(start, stop)
        counts = boxes[idx]
        if counts.sum() == 0:
            start = stop
            continue
        tri = np.repeat(idx, counts)
        local = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        sx = span[tri, 0]
        px = lo[tri, 0] + local % np.maximum(sx, 1)
        py = lo[tri, 1] + local // np.maximum(sx, 1)
        cx, cy = px + 0.5, py + 0.5
        s = tris_screen[tri]
        sign = np.sign(area[tri])
        inside = sign != 0
        for k in range(3):
            a, b = s[:, k], s[:, (k + 1) % 3]
            ex, ey = b[:, 0] - a[:, 0], b[:, 1] - a[:, 1]
            f = (ex * (cy - a[:, 1]) - ey * (cx - a[:, 0])) * sign
            # on the edge: inside for a "top" or "left" edge (image coordinates, y down)
            top_left = ((ey * sign == 0) & (ex * sign < 0)) | (ey * sign > 0)
            inside &= (f > 0) | ((f == 0) & top_left)
        if cut is not None and piece_screen is not None:
            q = piece_screen[tri]
            q1, q2 = q[:, 1] - q[:, 0], q[:, 2] - q[:, 0]
            qsign = np.sign(q1[:, 0] * q2[:, 1] - q1[:, 1] * q2[:, 0])
            inside &= qsign != 0
            for k in range(3):
                a, b = q[:, k], q[:, (k + 1) % 3]
                f = ((b[:, 0] - a[:, 0]) * (cy - a[:, 1]) - (b[:, 1] - a[:, 1]) * (cx - a[:, 0]))
                inside &= ~cut[tri, k] | (f * qsign >= 0)
        if counters is not None:  # (what was done: pairs tested, pairs found inside)
            counters["inside tests"] = counters.get("inside tests", 0) + len(tri)
            counters["inside"] = counters.get("inside", 0) + int(inside.sum())
        tri, pix = tri[inside], (py * width + px)[inside]
        o, dvec = p.ray_origin[pix], p.ray_dir[pix]
        denom = np.einsum("nd,nd->n", normal[tri], dvec)
        t = (offset[tri] - np.einsum("nd,nd->n", normal[tri], o)) / np.where(denom == 0, np.nan,
                                                                            denom)
        depth = -(o[:, 2] + t * dvec[:, 2])
        ok = np.isfinite(depth) & (depth >= p.near) & (depth <= p.far)
        yield pix[ok], tri[ok], depth[ok]
        start = stop


def resolve_nearest(p: Prepared, result: HiddenResult, pix, tri, depth, order) -> int:
    """Keep, per pixel, the nearest fragment (ties: lowest ``order``) against what the
    result holds. Returns how many pixels changed.

    Parameters
    ----------
    p : Prepared
        The view.
    result : HiddenResult
        Where the ids and depth go.
    pix, tri, depth, order : ndarray
        The fragments: pixel, triangle, depth, and submission order (ties).
    """
    if not len(pix):
        return 0
    key = np.lexsort((order, depth, pix))
    pix, tri, depth, order = pix[key], tri[key], depth[key], order[key]
    first = np.r_[True, pix[1:] != pix[:-1]]
    pix, tri, depth = pix[first], tri[first], depth[first]
    flat_d = result.depth.reshape(-1)
    flat_i = result.face_id.reshape(-1)
    held = result.__dict__.setdefault("_order", np.full(flat_d.size, np.iinfo(np.int64).max))
    # depth is compared in float64 here: keep the exact depth alongside the float32 image
    exact = result.__dict__.setdefault("_depth64", np.full(flat_d.size, np.inf))
    o = order[first]
    better = (depth < exact[pix]) | ((depth == exact[pix]) & (o < held[pix]))
    pix, tri, depth, o = pix[better], tri[better], depth[better], o[better]
    exact[pix], held[pix] = depth, o
    flat_d[pix] = depth
    flat_i[pix] = p.ids[tri]
    return len(pix)


def resolve_last(p: Prepared, result: HiddenResult, pix, tri, depth, rank) -> None:
    """Painter's resolution: per pixel, the fragment painted last (highest ``rank``).

    Parameters
    ----------
    p : Prepared
        The view.
    result : HiddenResult
        Where the ids go.
    pix, tri, depth, rank : ndarray
        The fragments: pixel, triangle, depth, and painting rank.
    """
    if not len(pix):
        return
    key = np.lexsort((rank, pix))
    pix, tri, depth, rank = pix[key], tri[key], depth[key], rank[key]
    last = np.r_[pix[1:] != pix[:-1], True]
    flat_d = result.depth.reshape(-1)
    flat_i = result.face_id.reshape(-1)
    held = result.__dict__.setdefault("_rank", np.full(flat_d.size, -1, np.int64))
    pix, tri, depth, rank = pix[last], tri[last], depth[last], rank[last]
    later = rank > held[pix]
    pix, tri, depth, rank = pix[later], tri[later], depth[later], rank[later]
    held[pix] = rank
    flat_d[pix] = depth
    flat_i[pix] = p.ids[tri]


def edge_pixels(p: Prepared, tolerance: float = 1e-3) -> np.ndarray:
    """``(H, W) bool``: pixels whose centre lies within ``tolerance`` pixels of an edge of
    any triangle of the view (where two correct rasterisers may differ).

    Parameters
    ----------
    p : Prepared
        The view.
    tolerance : float
        Pixels from an edge.
    """
    width, height = p.size
    mask = np.zeros(width * height, bool)
    s = p.screen
    if not len(s):
        return mask.reshape(height, width)
    for k in range(3):
        a, b = s[:, k], s[:, (k + 1) % 3]
        lo = np.maximum(np.floor(np.minimum(a, b) - 0.5 - tolerance).astype(np.int64) + 1, 0)
        hi = np.minimum(np.ceil(np.maximum(a, b) - 0.5 + tolerance).astype(np.int64),
                        [width - 1, height - 1])
        span = np.maximum(hi - lo + 1, 0)
        counts = span[:, 0] * span[:, 1]
        seg = np.repeat(np.arange(len(a)), counts)
        local = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        sx = np.maximum(span[seg, 0], 1)
        px, py = lo[seg, 0] + local % sx, lo[seg, 1] + local // sx
        d = b[seg] - a[seg]
        rel = np.stack([px + 0.5, py + 0.5], 1) - a[seg]
        length = np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300)
        dist = np.abs(d[:, 0] * rel[:, 1] - d[:, 1] * rel[:, 0]) / length
        mask[(py * width + px)[dist <= tolerance]] = True
    return mask.reshape(height, width)
