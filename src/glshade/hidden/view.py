"""The view every hidden-surface algorithm of the lab shares: the scene as triangles in view
space, clipped to the near plane, with their source polygon ids and draw order, and the
pixel rays (:meth:`Camera.rays`) through pixel centres.

Conventions are the GPU renderer's (``Renderer.render_frame``): row 0 at the top, pixel
centres at half-integers, ``face_id`` the source polygon (ids continue from one model to
the next; -1 for background), ``depth`` the distance along the view axis (``inf`` for
background); nothing nearer than the near plane or beyond the far plane is seen; ties of
equal depth go to the polygon drawn first (GL_LESS). No back faces are culled.
"""

from __future__ import annotations

from typing import Any

import time
from dataclasses import dataclass

import numpy as np

from ..errors import GeometryError
from ..geometry.mesh import Mesh
from .result import HiddenResult

__all__ = ["Prepared", "prepare", "split_by_plane", "takes_scene", "timed"]


@dataclass
class Prepared:
    """Triangles ``tris (T, 3, 3)`` in view space (near-clipped), their screen positions
    ``screen (T, 3, 2)`` in pixels (x right, y down), ``ids (T,)`` source polygons and
    ``order (T,)`` the draw order of the triangle each came from; the image ``size``; the
    pixel rays (``ray_origin``, ``ray_dir`` (H*W, 3), view space); ``near``/``far``.

    Parameters
    ----------
    tris : ndarray
        ``(T, 3, 3)`` triangles in view space, near-clipped.
    screen : ndarray
        ``(T, 3, 2)`` their pixel positions (x right, y down).
    ids : ndarray
        ``(T,)`` their source polygons.
    order : ndarray
        ``(T,)`` the draw order of the triangle each came from.
    size : (int, int)
        The image's width and height.
    proj : ndarray
        ``(4, 4)`` the projection.
    ray_origin, ray_dir : ndarray
        ``(H*W, 3)`` the pixel rays, view space.
    near, far : float
        The clip distances.
    n_polygons : int
        The source polygons.
    eye : tuple
        The eye in view space (the origin; an orthographic camera's is at infinity).
    src : ndarray or None
        Each triangle's source triangle (pieces split by an algorithm).
    cut : ndarray or None
        Which triangles were cut.
    """

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
        where the eye is in front of the plane, zero where it sees it edge-on.

        Parameters
        ----------
        normal : ndarray
            ``(n, 3)`` the planes' normals.
        offset : ndarray
            ``(n,)`` their offsets: ``n.x = d``.
        """
        e = self.eye
        return np.asarray(normal) @ np.asarray(e[:3]) - np.asarray(offset) * e[3]

    @property
    def n_pixels(self) -> int:
        return self.size[0] * self.size[1]

    def to_screen(self, points: np.ndarray) -> np.ndarray:
        """View-space points (..., 3) to pixel coordinates (..., 2).

        Parameters
        ----------
        points : ndarray
            ``(..., 3)`` view-space points.
        """
        p = points @ self.proj[:3, :3].T + self.proj[:3, 3]
        w = points @ self.proj[3, :3] + self.proj[3, 3]
        ndc = p[..., :2] / w[..., None]
        width, height = self.size
        return np.stack([(ndc[..., 0] + 1) * 0.5 * width, (1 - ndc[..., 1]) * 0.5 * height], -1)

    def subset(self, tris, ids, order) -> Prepared:
        """The same view with other triangles (pieces split by an algorithm).

        Parameters
        ----------
        tris : ndarray
            ``(n, 3, 3)`` the new triangles.
        ids : ndarray
            ``(n,)`` their source polygons.
        order : ndarray
            ``(n,)`` their draw order.
        """
        return Prepared(tris, self.to_screen(tris), ids, order, self.size, self.proj,
                        self.ray_origin, self.ray_dir, self.near, self.far, self.n_polygons,
                        self.eye)

    def empty_result(self, name: str) -> HiddenResult:
        """A result of this view with nothing drawn yet (ids -1, depth inf).

        Parameters
        ----------
        name : str
            The algorithm's name.
        """
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
    of the plane count as on it; a triangle wholly on the plane goes to neither side.

    Parameters
    ----------
    tris : ndarray
        ``(n, 3, 3)`` triangles.
    normal : ndarray
        ``(n, 3)`` (or ``(3,)``) the planes' normals.
    offset : ndarray
        ``(n,)`` (or a number) the planes' offsets: ``dot(normal, x) = offset``.
    eps : float
        How far from a plane a corner still counts as on it.
    cut : ndarray or None
        ``(n,)`` bool: which triangles to split (None: every one).
    """
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
    """The view of ``scene_or_mesh`` (a Scene or a Mesh) from ``camera`` at ``size``.

    Parameters
    ----------
    scene_or_mesh : Scene or Mesh
        What to view.
    camera : Camera
        From where.
    size : (int, int)
        The image's width and height in pixels.
    """
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


def takes_scene(algorithm):
    """Let an algorithm of a Prepared view also take ``(scene or mesh, camera, size)``.

    Parameters
    ----------
    algorithm : callable
        ``algorithm(prepared) -> HiddenResult``.
    """
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
    """Run ``run(result)`` on an empty result and time it.

    Parameters
    ----------
    name : str
        The algorithm's name.
    p : Prepared
        The view.
    run : callable
        ``run(result)``: fills the result in.
    """
    result = p.empty_result(name)
    start = time.perf_counter()
    run(result)
    result.seconds = time.perf_counter() - start
    for key in ("_order", "_depth64", "_rank"):
        result.__dict__.pop(key, None)
    return result
