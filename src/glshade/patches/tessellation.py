"""Patches to a mesh, uniformly or to an error bound, with no cracks and exact normals.

**Levels.** Each patch gets ``(nu, nv)`` samples a side: given, or the fewest that the
flatness bound of its control net guarantees within ``tolerance`` (Filip, Magedson and
Markot 1986): the piecewise-linear interpolant on a uniform nu x nv grid is within
``(M_uu / nu^2 + 2 M_uv / (nu nv) + M_vv / nv^2) / 8`` of the patch, where ``M_uu = m (m-1)
max |second u-difference of the control points|`` (and so on); for a rational patch the
differences of its mass-points ``(w P, w)`` about the patch's centre, over its least weight.
A tolerance in screen pixels for a camera becomes one in world units at each patch's
nearest distance.

**No cracks.** A boundary curve is sampled once, in one canonical direction, from its own
control points, and both patches that share it copy those samples: every shared boundary
vertex is bit-identical between neighbours. Both patches must then sample it equally often:
each edge takes the larger of its two patches' counts, and a patch the larger of its
opposite edges', repeated until nothing changes (counts only grow, so the error bound still
holds). There are no T-junctions to stitch.

**Normals.** Every vertex carries its own patch's exact unit normal (the limit at a
collapsed edge: the teapot's lid and bottom), so a crease between patches -- the handle's --
stays a crease; a shared boundary point is one vertex per patch, at one position.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import GeometryError
from ..geometry.mesh import Mesh
from .bezier import PatchSet, de_casteljau
from .surface import PatchSurface

__all__ = ["Tessellation", "tessellate", "flatness_levels", "MAX_LEVEL", "MAX_TRIANGLES"]

#: samples a patch side may take
MAX_LEVEL = 512
#: triangles a tessellation may make
MAX_TRIANGLES = 20_000_000


@dataclass(frozen=True)
class Tessellation:
    """The mesh (triangles, two a grid cell, one where a side collapses; ``normals`` the
    exact ones), each vertex's ``uv (V, 2)`` and ``patch (V,)``, and the ``levels (P, 2)`` used.

    Parameters
    ----------
    mesh : Mesh
        The triangles, their ``normals`` the surface's exact ones.
    uv : ndarray
        ``(V, 2)`` each vertex's parameters.
    patch : ndarray
        ``(V,)`` each vertex's patch.
    levels : ndarray
        ``(P, 2)`` the segments a side used for each patch.
    """

    mesh: Mesh
    uv: np.ndarray
    patch: np.ndarray
    levels: np.ndarray

    @property
    def n_triangles(self) -> int:
        return len(self.mesh.triangles[0])


def flatness_levels(patches: PatchSet, tolerance) -> np.ndarray:
    """``(P, 2)`` the fewest samples per side that keep each patch within ``tolerance``
    (world units: a number, or one per patch) of its piecewise-linear interpolant.

    Parameters
    ----------
    patches : PatchSet
        The patches.
    tolerance : float or array_like
        World units, one number or one a patch.
    """
    try:
        given = np.asarray(tolerance, dtype=np.float64)
    except (TypeError, ValueError):
        raise GeometryError(f"a tolerance must be a positive number, got {tolerance!r}") \
            from None
    if given.ndim > 1 or (given.ndim == 1 and len(given) != len(patches)):
        raise GeometryError(f"tolerance: one number, or one per patch ({len(patches):,}), "
                            f"got {given.size:,} numbers")
    tol = np.broadcast_to(given, (len(patches),))
    if not (np.isfinite(tol).all() and (tol > 0).all()):
        bad = float(tol[~(np.isfinite(tol) & (tol > 0))][0])
        raise GeometryError(f"a tolerance must be a positive number, got {bad:g}")
    h = patches.homogeneous.copy()
    centre = patches.bounds().mean(1)  # (P, 3): differences about it, for rational ones
    h[..., :3] = (patches.points - centre[:, None, None]) * patches.weights[..., None]
    m, n = patches.degree

    def most(d):
        return np.linalg.norm(d, axis=-1).reshape(len(h), -1).max(1) if d.size else \
            np.zeros(len(h))

    # (a degree-1 direction has no second differences: empty, so zero)
    muu = m * (m - 1) * most(h[:, 2:] - 2 * h[:, 1:-1] + h[:, :-2])
    mvv = n * (n - 1) * most(h[:, :, 2:] - 2 * h[:, :, 1:-1] + h[:, :, :-2])
    muv = m * n * most(h[:, 1:, 1:] - h[:, 1:, :-1] - h[:, :-1, 1:] + h[:, :-1, :-1])
    wmin = patches.weights.reshape(len(h), -1).min(1)
    scale = 1.0 / wmin
    with np.errstate(over="ignore"):  # (a tolerance of 1e-308: inf, past the cap below)
        nu = np.ceil(np.sqrt((muu + muv) * scale / (4 * tol)))
        nv = np.ceil(np.sqrt((mvv + muv) * scale / (4 * tol)))
    # (past MAX_LEVEL + 1 it is past what is allowed, by however much: a tolerance of
    # 1e-300 asks for 1e150, which an int64 cannot hold)
    return np.clip(np.nan_to_num(np.stack([nu, nv], 1), nan=MAX_LEVEL + 1.0), 1,
                   MAX_LEVEL + 1).astype(np.int64)


def _world_tolerance(patches: PatchSet, pixels: float, camera, height: int) -> np.ndarray:
    """A screen tolerance in world units at each patch's nearest point to the camera."""
    b = patches.bounds()
    if camera.projection.value == "orthographic":
        per_px = camera.height / height
        return np.full(len(patches), pixels * per_px)
    nearest = np.clip(camera.position, b[:, 0], b[:, 1])
    d = np.linalg.norm(nearest - camera.position, axis=1)
    near = camera.near or 1e-3 * max(float(np.ptp(b.reshape(-1, 3), 0).max()), 1e-12)
    return pixels * 2 * np.maximum(d, near) * np.tan(np.radians(camera.fov_y) / 2) / height


def _balance(levels: np.ndarray, surface: PatchSurface) -> np.ndarray:
    """Raise counts until each edge's two patches sample it equally: ``(P, 2)``."""
    e = surface.edges
    lv = levels.copy()
    along = np.array([1, 1, 0, 0])  # u0/u1 sides run along v (count nv), v0/v1 along u
    sides = e.side_edge
    has = sides >= 0
    p_idx, s_idx = np.nonzero(has)
    edge = sides[has]
    axis = along[s_idx]
    while True:
        count = np.zeros(len(e.uses), np.int64)
        np.maximum.at(count, edge, lv[p_idx, axis])
        new = lv.copy()
        np.maximum.at(new, (p_idx, axis), count[edge])
        if (new == lv).all():
            return lv
        lv = new


def tessellate(model, level: int | None = None, *, tolerance: float | None = None,
               pixels: float | None = None, camera=None, height: int = 512) -> Tessellation:
    """A mesh of a :class:`PatchSurface` (or :class:`PatchSet`): ``level`` samples a side
    for every patch, or the fewest for ``tolerance`` (world units), or for ``pixels`` in an
    image ``height`` pixels tall seen by ``camera``. Crack-free, with exact normals.

    Parameters
    ----------
    model : PatchSurface or PatchSet
        The patches.
    level : int or None
        Samples a side for every patch.
    tolerance : float or None
        World units the mesh may stray from the surface.
    pixels : float or None
        Pixels it may stray in an image ``height`` tall seen by ``camera``.
    camera : Camera or None
        The view, for ``pixels``.
    height : int
        The image's height, for ``pixels``.
    """
    surface = model if isinstance(model, PatchSurface) else PatchSurface(model)
    patches = surface.patches
    P = len(patches)
    given = sum(x is not None for x in (level, tolerance, pixels))
    if given != 1:
        raise GeometryError("give one of level, tolerance or pixels (with camera)")
    if level is not None:
        if isinstance(level, bool) or not isinstance(level, (int, np.integer)) or \
                not 1 <= level <= MAX_LEVEL:
            raise GeometryError(f"level must be a whole number from 1 to {MAX_LEVEL}, got "
                                f"{level!r}")
        levels = np.full((P, 2), int(level))
    elif tolerance is not None:
        levels = flatness_levels(patches, tolerance)
    else:
        if camera is None:
            raise GeometryError("a tolerance in pixels needs the camera it is seen by")
        if not (isinstance(pixels, (int, float)) and np.isfinite(pixels) and pixels > 0):
            raise GeometryError(f"pixels must be a positive number, got {pixels!r}")
        levels = flatness_levels(patches, _world_tolerance(patches, float(pixels), camera,
                                                            height))
    if (levels > MAX_LEVEL).any():
        asked = f"{tolerance:g} " if tolerance is not None else ""
        raise GeometryError(f"the tolerance {asked}asks for more samples a patch side than "
                            f"the {MAX_LEVEL} allowed: use a larger one")
    levels = _balance(levels, surface)
    if int(2 * (levels[:, 0] * levels[:, 1]).sum()) > MAX_TRIANGLES:
        raise GeometryError(f"the tessellation would make more than {MAX_TRIANGLES:,} "
                            "triangles: use a larger tolerance or level")
    return _build(surface, levels)


def _edge_samples(surface: PatchSurface, levels: np.ndarray):
    """Every edge's points at its count, in its canonical direction, each evaluated once
    from the edge's own control points: ``(flat (S, 3), offset (E,))``, edge k's samples
    ``flat[offset[k]:offset[k] + count[k] + 1]``."""
    e = surface.edges
    along = np.array([1, 1, 0, 0])
    count = np.zeros(len(e.uses), np.int64)
    p_idx, s_idx = np.nonzero(e.side_edge >= 0)
    count[e.side_edge[p_idx, s_idx]] = levels[p_idx, along[s_idx]]
    offset = np.concatenate([[0], np.cumsum(count + 1)[:-1]]).astype(np.int64)
    flat = np.empty((int((count + 1).sum()), 3))
    lengths = np.array([len(c) for c in e.control])
    for k, n in {(int(k), int(n)) for k, n in zip(count, lengths)}:  # (edges by size)
        which = np.flatnonzero((count == k) & (lengths == n))
        nets = np.stack([e.control[w] for w in which])  # (W, n, 4)
        h = de_casteljau(nets, np.arange(k + 1) / k, axis=1)  # (W, k+1, 4): mass-points
        rows = offset[which][:, None] + np.arange(k + 1)
        flat[rows.ravel()] = (h[..., :3] / h[..., 3:]).reshape(-1, 3)
    return flat, offset


def _build(surface: PatchSurface, levels: np.ndarray) -> Tessellation:
    patches = surface.patches
    e = surface.edges
    flat, offset = _edge_samples(surface, levels)
    if not len(flat):  # (every side collapsed: no edge samples, each side its corner)
        flat = np.zeros((1, 3))
    corner_h = np.stack([patches.homogeneous[:, 0, 0], patches.homogeneous[:, -1, 0],
                         patches.homogeneous[:, -1, -1], patches.homogeneous[:, 0, -1]], 1)
    corner_pts = corner_h[..., :3] / corner_h[..., 3:]  # (P, 4, 3)
    verts, normals, uvs, owners, faces = [], [], [], [], []
    base = 0
    keys = levels[:, 0] * (MAX_LEVEL + 1) + levels[:, 1]
    for key in np.unique(keys):  # (patches of one grid size at once)
        idx = np.flatnonzero(keys == key)
        nu, nv = int(levels[idx[0], 0]), int(levels[idx[0], 1])
        su, sv = np.arange(nu + 1) / nu, np.arange(nv + 1) / nv
        U, V = np.meshgrid(su, sv, indexing="ij")
        uu, vv = U.ravel(), V.ravel()
        sub = patches[idx]
        pts = sub.evaluate(uu, vv).reshape(len(idx), nu + 1, nv + 1, 3)
        nrm = sub.normals(uu, vv).reshape(len(idx), nu + 1, nv + 1, 3)
        # the boundary rows: the edges' shared samples, copied (a collapsed side: its point)
        for side, (axis, end, corner) in enumerate(((0, 0, 0), (0, -1, 1), (1, 0, 0),
                                                    (1, -1, 3))):
            length = nv + 1 if axis == 0 else nu + 1
            k = e.side_edge[idx, side]
            ok = k >= 0
            step = np.arange(length)
            at = offset[np.maximum(k, 0)][:, None] + \
                np.where(e.side_reversed[idx, side][:, None], length - 1 - step, step)
            row = np.where(ok[:, None, None], flat[np.where(ok[:, None], at, 0)],
                           corner_pts[idx, corner][:, None])
            if axis == 0:
                pts[:, end, :] = row
            else:
                pts[:, :, end] = row
        n_per = (nu + 1) * (nv + 1)
        i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
        a, b = i * (nv + 1) + j, (i + 1) * (nv + 1) + j
        c, d = (i + 1) * (nv + 1) + j + 1, i * (nv + 1) + j + 1
        tri = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3),
                              np.stack([a, c, d], -1).reshape(-1, 3)])
        offsets = base + n_per * np.arange(len(idx))
        faces.append((tri[None] + offsets[:, None, None]).reshape(-1, 3))
        verts.append(pts.reshape(-1, 3))
        normals.append(nrm.reshape(-1, 3))
        uvs.append(np.tile(np.stack([uu, vv], 1), (len(idx), 1)))
        owners.append(np.repeat(idx, n_per))
        base += n_per * len(idx)
    vertices = np.concatenate(verts)
    tris = np.concatenate(faces)
    # a triangle at a collapsed side has two corners at one point: none of the surface
    p = vertices[tris]
    flat_tri = (p[:, 0] == p[:, 1]).all(1) | (p[:, 1] == p[:, 2]).all(1) | \
        (p[:, 2] == p[:, 0]).all(1)
    # ... and a patch whose control points all coincide is a point: none of its triangles
    # (its inner samples, evaluated, differ from that point in the last bits)
    owner = np.concatenate(owners)
    point = np.ptp(patches.points.reshape(len(patches), -1, 3), axis=1).max(1) == 0
    flat_tri |= point[owner[tris[:, 0]]]
    if flat_tri.all():
        raise GeometryError(f"{surface.name or 'the patches'}: every patch collapses to a "
                            "point (all its control points coincide): no surface to tessellate")
    mesh = Mesh(vertices, tris[~flat_tri], normals=np.concatenate(normals), name=surface.name)
    return Tessellation(mesh, np.concatenate(uvs), owner, levels)
