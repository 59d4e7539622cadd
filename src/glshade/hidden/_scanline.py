"""The scan-line algorithm (image space): an edge table (ET) of the polygons' edges bucketed
by the first scan line they cross; an active edge list (AEL) of the edges crossing the
current line, each with its x there, updated incrementally (``x += dx/dy`` per line); on
each line, every polygon with two active edges spans between them, and along a span the
depth is stepped incrementally too. In perspective it is ``1/z`` that is linear across the
screen (``1/z = A x + B y + C`` per polygon), so that is what is stepped; a line keeps, per
pixel, the nearest span (ties: the polygon drawn first).

One Python step per scan line (the sweep is sequential); within a line, all active edges
and spans at once."""

from __future__ import annotations

import numpy as np

from .raster import SUBPIXEL, resolve_nearest
from .result import HiddenResult
from .view import Prepared, takes_scene, timed

__all__ = ["scanline"]


def _inverse_depth_planes(p: Prepared) -> tuple[np.ndarray, bool]:
    """Per triangle ``(A, B, C)`` with ``q = A x + B y + C`` at screen (x, y): q = 1/depth
    in perspective (depth itself for an orthographic camera), fitted exactly from three
    screen points by the plane along their rays."""
    perspective = p.proj[3, 3] == 0
    inv = np.linalg.inv(p.proj)
    width, height = p.size
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    ndc = np.c_[pts[:, 0] / width * 2 - 1, 1 - pts[:, 1] / height * 2]

    def unproject(z):
        h = np.c_[ndc, np.full(3, z), np.ones(3)] @ inv.T
        return h[:, :3] / h[:, 3:]

    a, b = unproject(-1.0), unproject(1.0)
    direction = b - a
    t = p.tris
    normal = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    offset = np.einsum("nd,nd->n", normal, t[:, 0])
    # depth at the three points, for every triangle
    with np.errstate(divide="ignore", invalid="ignore"):  # (a triangle seen edge on: its
        s = (offset[:, None] - normal @ a.T) / (normal @ direction.T)  # plane has no depth
        depth = -(a[None, :, 2] + s * direction[None, :, 2])         # there; it covers no
        q = 1.0 / depth if perspective else depth                   # pixel centre either)
    coeff = np.stack([q[:, 1] - q[:, 0], q[:, 2] - q[:, 0], q[:, 0]], 1)
    return coeff, perspective


@takes_scene
def scanline(p: Prepared, steps: int = 0) -> HiddenResult:
    """``steps``: keep that many snapshots of the image as the line sweeps down."""
    width, height = p.size
    counters = {"polygons": p.n_polygons, "triangles": len(p.tris), "edges": 0,
                "AEL insertions": 0, "spans": 0, "span pixels": 0, "pixels written": 0}

    def run(result: HiddenResult):
        if not len(p.tris):
            return
        s = np.round(p.screen * SUBPIXEL) / SUBPIXEL  # the GPU's snapped vertices
        coeff, perspective = _inverse_depth_planes(p)
        # the edge table: non-horizontal edges, with the rows whose centres they cross
        a = s.reshape(-1, 2)
        b = np.roll(s, -1, axis=1).reshape(-1, 2)
        tri = np.repeat(np.arange(len(s)), 3)
        top = np.where((a[:, 1] <= b[:, 1])[:, None], a, b)
        bot = np.where((a[:, 1] <= b[:, 1])[:, None], b, a)
        keep = bot[:, 1] > top[:, 1]
        top, bot, tri = top[keep], bot[keep], tri[keep]
        first = np.maximum(np.ceil(top[:, 1] - 0.5).astype(np.int64), 0)
        last = np.minimum(np.ceil(bot[:, 1] - 0.5).astype(np.int64) - 1, height - 1)
        live = first <= last
        top, bot, tri, first, last = top[live], bot[live], tri[live], first[live], last[live]
        dxdy = (bot[:, 0] - top[:, 0]) / (bot[:, 1] - top[:, 1])
        order = np.argsort(first, kind="stable")
        top, dxdy, tri, first, last = top[order], dxdy[order], tri[order], first[order], \
            last[order]
        counters["edges"] = len(tri)
        # the active edge list
        ael_x = np.zeros(0)
        ael_dx = np.zeros(0)
        ael_tri = np.zeros(0, np.int64)
        ael_last = np.zeros(0, np.int64)
        nxt = 0
        every = max(1, height // steps) if steps else 0
        for row in range(int(first[0]) if len(first) else height, height):
            # edges that start on this line join; x at this line's centre
            stop = np.searchsorted(first, row, side="right")
            if stop > nxt:
                new = slice(nxt, stop)
                x0 = top[new, 0] + (row + 0.5 - top[new, 1]) * dxdy[new]
                ael_x = np.r_[ael_x, x0]
                ael_dx = np.r_[ael_dx, dxdy[new]]
                ael_tri = np.r_[ael_tri, tri[new]]
                ael_last = np.r_[ael_last, last[new]]
                counters["AEL insertions"] += int(stop - nxt)
                nxt = int(stop)
            if not len(ael_x) and nxt >= len(first):
                break
            if len(ael_x):
                _spans(p, result, row, ael_x, ael_tri, coeff, perspective, counters)
                # step to the next line; edges that end here leave
                ael_x = ael_x + ael_dx
                stay = ael_last > row
                ael_x, ael_dx, ael_tri, ael_last = ael_x[stay], ael_dx[stay], \
                    ael_tri[stay], ael_last[stay]
            if every and row % every == every - 1:
                result.steps.append((f"line {row + 1}", result.face_id.copy()))

    result = timed("scanline", p, run)
    result.counters = counters
    return result


def _spans(p, result, row, ael_x, ael_tri, coeff, perspective, counters) -> None:
    """The spans of one scan line, resolved nearest-first into the image."""
    width = p.size[0]
    order = np.argsort(ael_tri, kind="stable")
    t, x = ael_tri[order], ael_x[order]
    # each polygon crossing the line has two active edges: its span lies between them
    start = np.flatnonzero(np.r_[True, t[1:] != t[:-1]])
    pairs = start[np.diff(np.r_[start, len(t)]) >= 2]
    tri = t[pairs]
    left = np.minimum(x[pairs], x[pairs + 1])
    right = np.maximum(x[pairs], x[pairs + 1])
    c0 = np.maximum(np.ceil(left - 0.5).astype(np.int64), 0)     # first centre >= left
    c1 = np.minimum(np.ceil(right - 0.5).astype(np.int64), width)  # centres < right
    n = np.maximum(c1 - c0, 0)
    counters["spans"] += int((n > 0).sum())
    if not n.sum():
        return
    span = np.repeat(np.arange(len(tri)), n)
    col = c0[span] + np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)
    k = tri[span]
    # the depth, stepped along the span: q = q(left end) + A per pixel
    q = coeff[k, 0] * (col + 0.5) + coeff[k, 1] * (row + 0.5) + coeff[k, 2]
    depth = 1.0 / q if perspective else q
    ok = np.isfinite(depth) & (depth >= p.near) & (depth <= p.far)
    counters["span pixels"] += int(ok.sum())
    pix = row * width + col
    counters["pixels written"] += resolve_nearest(p, result, pix[ok], k[ok], depth[ok],
                                                  p.order[k[ok]])
