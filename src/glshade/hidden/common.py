"""What every hidden-surface algorithm of the lab shares: the scene as triangles in view
space, clipped to the near plane, with their source polygon ids and draw order; pixel rays
through pixel centres; and a vectorised rasteriser that yields, for a batch of triangles,
the pixels whose centres they cover and the exact depth of their plane there.

Conventions are the GPU renderer's (``Renderer.render_frame``): row 0 at the top, pixel
centres at half-integers, ``face_id`` the source polygon (ids continue from one model to
the next; -1 for background), ``depth`` the distance along the view axis (``inf`` for
background); nothing nearer than the near plane or beyond the far plane is seen; ties of
equal depth go to the polygon drawn first (GL_LESS). No back faces are culled.
"""

from __future__ import annotations

from typing import Any

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import GeometryError
from ..geometry.mesh import Mesh

__all__ = ["Prepared", "HiddenResult", "prepare", "fragments", "resolve_nearest",
           "resolve_last", "edge_pixels", "split_by_plane"]

#: candidate pixel-triangle pairs handled at once (memory, not speed)
CHUNK = 4_000_000
#: GPUs rasterise vertex positions snapped to 1/256 pixel (8 bits of subpixel precision)
SUBPIXEL = 256.0


@dataclass
class HiddenResult:
    """What one algorithm produced: ``face_id (H, W) int32`` (-1 background), ``depth
    (H, W) float32`` (inf background), its ``counters`` and the ``seconds`` it took."""

    name: str
    face_id: np.ndarray
    depth: np.ndarray
    counters: dict = field(default_factory=dict)
    seconds: float = 0.0
    steps: list = field(default_factory=list)  # (label, face_id) snapshots, for teaching
    #: the object-space algorithms' paint order (depth sort, BSP), for their steps
    painted: Any = None

    def __repr__(self) -> str:
        h, w = self.face_id.shape
        return (f"<HiddenResult {self.name} {w}x{h}: {self.seconds:.3g} s, "
                f"{int((self.face_id >= 0).sum()):,} pixels drawn>")

    def _repr_html_(self) -> str:
        """In a notebook: the polygon ids it found, and its counters."""
        from .._display import id_colours, facts_html

        facts = [f"{k}: {v:,}" if isinstance(v, int) else f"{k}: {v}"
                 for k, v in self.counters.items()]
        return facts_html(repr(self), facts, id_colours(self.face_id))


@dataclass
class Prepared:
    """Triangles ``tris (T, 3, 3)`` in view space (near-clipped), their screen positions
    ``screen (T, 3, 2)`` in pixels (x right, y down), ``ids (T,)`` source polygons and
    ``order (T,)`` the draw order of the triangle each came from; the image ``size``; the
    pixel rays (``ray_origin``, ``ray_dir`` (H*W, 3), view space); ``near``/``far``."""

    tris: np.ndarray
    screen: np.ndarray
    ids: np.ndarray
    order: np.ndarray
    size: tuple
    proj: np.ndarray
    ray_origin: np.ndarray
    ray_dir: np.ndarray
    near: float
    far: float
    n_polygons: int
    #: the eye, homogeneous, in view space: the origin (0, 0, 0, 1) for a perspective
    #: camera; the point at infinity along +z (0, 0, 1, 0) for an orthographic one, whose
    #: rays are parallel. Which side of a plane n.x = d faces the eye: n.e - d w.
    eye: tuple = (0.0, 0.0, 0.0, 1.0)
    #: after splitting (BSP, depth sort): each piece's source triangle and whether it was cut
    src: Any = None
    cut: Any = None

    def eye_side(self, normal: np.ndarray, offset) -> np.ndarray:
        """``n.e - d w`` for planes ``n.x = d`` (rows of ``normal``, ``offset``): positive
        where the eye is in front of the plane, zero where it sees it edge-on."""
        e = self.eye
        return np.asarray(normal) @ np.asarray(e[:3]) - np.asarray(offset) * e[3]

    @property
    def n_pixels(self) -> int:
        return self.size[0] * self.size[1]

    def to_screen(self, points: np.ndarray) -> np.ndarray:
        """View-space points (..., 3) to pixel coordinates (..., 2)."""
        p = points @ self.proj[:3, :3].T + self.proj[:3, 3]
        w = points @ self.proj[3, :3] + self.proj[3, 3]
        ndc = p[..., :2] / w[..., None]
        width, height = self.size
        return np.stack([(ndc[..., 0] + 1) * 0.5 * width, (1 - ndc[..., 1]) * 0.5 * height], -1)

    def subset(self, tris, ids, order) -> Prepared:
        """The same view with other triangles (pieces split by an algorithm)."""
        return Prepared(tris, self.to_screen(tris), ids, order, self.size, self.proj,
                        self.ray_origin, self.ray_dir, self.near, self.far, self.n_polygons,
                        self.eye)

    def empty_result(self, name: str) -> HiddenResult:
        w, h = self.size
        return HiddenResult(name, np.full((h, w), -1, np.int32), np.full((h, w), np.inf,
                                                                          np.float32))


def _scene_triangles(scene_or_mesh, view: np.ndarray):
    """View-space triangles of every visible model, their polygon ids and draw order."""
    from ..scene import Scene

    if isinstance(scene_or_mesh, Mesh):
        models = [(scene_or_mesh, np.eye(4), True)]
    elif isinstance(scene_or_mesh, Scene):
        models = [(m.mesh, m.transform, m.visible) for m in scene_or_mesh.models]
    else:
        raise GeometryError(f"expected a Scene or a Mesh, got {type(scene_or_mesh).__name__}")
    tris, ids, base = [], [], 0
    for mesh, transform, visible in models:
        tri, owner = mesh.triangles
        if visible and len(tri):
            m = view @ transform
            v = mesh.vertices @ m[:3, :3].T + m[:3, 3]
            tris.append(v[tri])
            ids.append(owner + base)
        base += mesh.n_faces
    if not tris:
        return np.zeros((0, 3, 3)), np.zeros(0, np.int64), base
    return np.concatenate(tris), np.concatenate(ids), base


def split_by_plane(tris: np.ndarray, normal: np.ndarray, offset: np.ndarray, eps: float = 0.0,
                   cut: np.ndarray | None = None):
    """Split triangles (n, 3, 3) by planes ``dot(normal, p) = offset`` (one per triangle, or one
    for all). Returns (front, front_src, front_cut, back, back_src, back_cut): the pieces
    on each side (re-triangulated), the index of the triangle each came from, and for each
    piece's edges (k to k+1) whether it is a cut (a split line or a diagonal) rather than
    part of an edge of the original (``cut``: the input's flags). Vertices within ``eps``
    of the plane count as on it; a triangle wholly on the plane goes to neither side."""
    n = len(tris)
    normal = np.broadcast_to(normal, (n, 3))
    offset = np.broadcast_to(offset, (n,))
    cut = np.zeros((n, 3), bool) if cut is None else cut
    d = np.einsum("nkd,nd->nk", tris, normal) - offset[:, None]
    d = np.where(np.abs(d) <= eps, 0.0, d)
    out: dict[bool, tuple[list, list, list]] = {True: ([], [], []), False: ([], [], [])}
    for side in (True, False):
        s = d if side else -d
        inside = s >= 0
        count = inside.sum(1)
        strict = (s > 0).any(1)
        whole = (count == 3) & strict  # wholly on this side (and not wholly on the plane)
        pieces, sources, cuts = out[side]
        pieces.append(tris[whole])
        sources.append(np.flatnonzero(whole))
        cuts.append(cut[whole])
        for k in (1, 2):  # k vertices on this side: clip (1 -> a triangle, 2 -> a quad)
            sel = np.flatnonzero((count == k) & strict)
            if not len(sel):
                continue
            t, sd, ins, c = tris[sel], s[sel], inside[sel], cut[sel]
            # rotate each triangle so that the odd vertex (the lone in/out one) comes first
            odd = np.argmax(ins if k == 1 else ~ins, axis=1)
            idx = (odd[:, None] + np.arange(3)) % 3
            t = np.take_along_axis(t, idx[..., None], 1)
            sd = np.take_along_axis(sd, idx, 1)
            c = np.take_along_axis(c, idx, 1)  # edges a-b, b-c, c-a of the rotated triangle
            a, b, cc = t[:, 0], t[:, 1], t[:, 2]
            da, db, dc = sd[:, 0], sd[:, 1], sd[:, 2]
            ab = a + (b - a) * (da / (da - db))[:, None]
            ac = a + (cc - a) * (da / (da - dc))[:, None]
            yes = np.ones(len(sel), bool)
            if k == 1:  # a is in: the triangle a, ab, ac
                pieces.append(np.stack([a, ab, ac], 1))
                sources.append(sel)
                cuts.append(np.stack([c[:, 0], yes, c[:, 2]], 1))
            else:  # a is out: the quad ab, b, c, ac as two triangles
                pieces.extend([np.stack([ab, b, cc], 1), np.stack([ab, cc, ac], 1)])
                sources.extend([sel, sel])
                cuts.extend([np.stack([c[:, 0], c[:, 1], yes], 1),
                             np.stack([yes, c[:, 2], yes], 1)])

    def join(parts, sources, cuts):
        if not parts:
            return np.zeros((0, 3, 3)), np.zeros(0, np.int64), np.zeros((0, 3), bool)
        return (np.concatenate(parts), np.concatenate(sources).astype(np.int64),
                np.concatenate(cuts))

    return (*join(*out[True]), *join(*out[False]))


def prepare(scene_or_mesh, camera, size=(256, 256)) -> Prepared:
    """The view of ``scene_or_mesh`` (a Scene or a Mesh) from ``camera`` at ``size``."""
    width, height = (int(size[0]), int(size[1]))
    if width < 1 or height < 1:
        raise GeometryError(f"image size must be at least 1x1, got {size!r}")
    if hasattr(scene_or_mesh, "bounds"):  # (clip planes not given: fitted, as the GPU's)
        camera = camera.with_planes(scene_or_mesh.bounds)
    view = camera.view_matrix()
    proj = np.asarray(camera.projection_matrix(width / height), np.float64)
    tris, ids, n_polygons = _scene_triangles(scene_or_mesh, view)
    order = np.arange(len(tris))
    # clip to the near plane (z_view <= -near), as the GPU's clipper does
    front, src = split_by_plane(tris, np.array([0.0, 0.0, -1.0]), np.full(
        len(tris), camera.near))[:2] if len(tris) else (tris, order)
    keep = np.argsort(src, kind="stable")  # (pieces of one triangle stay together)
    tris, src = front[keep], src[keep]
    # zero-area triangles cover no pixel anywhere, and have no plane to sort by
    solid = np.linalg.norm(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]),
                           axis=1) > 0
    tris, src = tris[solid], src[solid]
    # pixel rays (Camera.rays), in view space, from the near plane where the GPU's start
    o, d = camera.rays((width, height))
    o_view = o.reshape(-1, 3) @ view[:3, :3].T + view[:3, 3]
    direction = d.reshape(-1, 3) @ view[:3, :3].T
    a = o_view + direction * ((camera.near + o_view[:, 2]) / -direction[:, 2])[:, None]
    prepared = Prepared(tris, np.zeros((len(tris), 3, 2)), ids[src], order[src],
                        (width, height), proj, a, direction, camera.near, camera.far,
                        n_polygons, (0.0, 0.0, 1.0, 0.0) if camera.projection ==
                        "orthographic" else (0.0, 0.0, 0.0, 1.0))
    prepared.screen = prepared.to_screen(tris) if len(tris) else prepared.screen
    return prepared


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
    with no crack or overlap."""
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
    result holds. Returns how many pixels changed."""
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
    """Painter's resolution: per pixel, the fragment painted last (highest ``rank``)."""
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
    any triangle of the view (where two correct rasterisers may differ)."""
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


def takes_scene(algorithm):
    """Let an algorithm of a Prepared view also take ``(scene or mesh, camera, size)``."""
    import functools

    @functools.wraps(algorithm)
    def wrapper(view, camera=None, size=(256, 256), **kwargs):
        if not isinstance(view, Prepared):
            if camera is None:
                raise GeometryError(f"{algorithm.__name__} needs a camera with a scene or "
                                    "mesh (or a view made by prepare())")
            view = prepare(view, camera, size)
        return algorithm(view, **kwargs)

    return wrapper


def timed(name: str, p: Prepared, run) -> HiddenResult:
    """Run ``run(result)`` on an empty result and time it."""
    result = p.empty_result(name)
    start = time.perf_counter()
    run(result)
    result.seconds = time.perf_counter() - start
    for key in ("_order", "_depth64", "_rank"):
        result.__dict__.pop(key, None)
    return result
