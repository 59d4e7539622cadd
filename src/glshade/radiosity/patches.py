"""Radiosity patches: a mesh's polygons cut into pieces no longer than a target size, each
remembering its source polygon.

A planar quad becomes a grid of ``nu x nv`` quad patches, the counts taken from the lengths
of its edges, so two rectangles that share an edge of one length cut it at the same points;
any other polygon (a non-planar quad included: it is split into its two triangles) is
triangulated and each triangle cut into ``k^2`` similar triangles. Every patch is drawn as
one or two triangles over vertices welded by position, so the display mesh has no cracks
where patches meet. All of it is vectorised: loops run over the few distinct counts, never
over polygons.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import GeometryError
from ..geometry.mesh import Mesh

__all__ = ["Patches", "subdivide"]

#: a quad whose corners leave its plane by more than this fraction of its size is split
PLANARITY = 1e-4
#: degrees: a solution's display averages vertex radiosities only across gentler bends
DISPLAY_CREASE = 30.0


@dataclass
class Patches:
    """Patches of one mesh (or of a whole scene, concatenated).

    vertices (V, 3) welded; triangles (T, 3) into vertices; triangle_patch (T,) the patch
    each triangle belongs to; source (P,) the source polygon of each patch; centers,
    normals (P, 3); areas (P,); split (int) non-planar quads that were split in two.

    Parameters
    ----------
    vertices : ndarray
        ``(V, 3)`` welded positions.
    triangles : ndarray
        ``(T, 3)`` indices into ``vertices``.
    triangle_patch : ndarray
        ``(T,)`` the patch each triangle belongs to.
    source : ndarray
        ``(P,)`` the source polygon of each patch.
    centers, normals : ndarray
        ``(P, 3)`` each patch's centroid and unit normal.
    areas : ndarray
        ``(P,)`` each patch's area.
    corners : ndarray
        Each patch's corners (its quadrature's domain).
    split : int
        Non-planar quads that were split in two.
    """

    vertices: np.ndarray
    triangles: np.ndarray
    triangle_patch: np.ndarray
    source: np.ndarray
    centers: np.ndarray
    normals: np.ndarray
    areas: np.ndarray
    corners: np.ndarray
    split: int = 0

    @property
    def n_patches(self) -> int:
        return len(self.areas)

    def mesh(self, crease: float = DISPLAY_CREASE) -> Mesh:
        """The display mesh: one polygon per triangle, its vertices shared only across
        edges where the surface bends by less than ``crease`` degrees (the rule of
        ``--crease``), so a box's faces keep their own vertices and their own radiosity at
        its edges.

        Parameters
        ----------
        crease : float
            Degrees past which an edge stays sharp.
        """
        cache = self.__dict__.setdefault("_display", {})
        found = cache.get(crease)
        if found is None:
            found = cache[crease] = Mesh(self.vertices, self.triangles).split_creases(crease)
        return found

    def vertex_values(self, values: np.ndarray, crease: float = DISPLAY_CREASE) -> np.ndarray:
        """Per-vertex values ``(V, C)`` of :meth:`mesh` from per-patch ``values (P, C)``:
        the area-weighted mean over the patches of one smooth surface touching each vertex
        (the Gouraud display of a radiosity solution: never averaged across a crease).

        Parameters
        ----------
        values : ndarray
            ``(P, C)`` a value a patch.
        crease : float
            Degrees past which an edge stays sharp.
        """
        values = np.asarray(values, np.float64).reshape(self.n_patches, -1)
        display = self.mesh(crease)
        tri_area = self.areas[self.triangle_patch] / np.bincount(
            self.triangle_patch, minlength=self.n_patches)[self.triangle_patch]
        corner = display.face_indices  # (one triangle per face, in the patches' order)
        w = np.repeat(tri_area, 3)
        total = np.bincount(corner, weights=w, minlength=display.n_vertices)
        per_tri = values[self.triangle_patch]
        out = np.stack([np.bincount(corner, weights=w * np.repeat(per_tri[:, c], 3),
                                    minlength=display.n_vertices)
                        for c in range(values.shape[1])], axis=1)
        return out / np.maximum(total, 1e-300)[:, None]

    def sample_points(self, counts: np.ndarray, only: np.ndarray | None = None,
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Quadrature points over each patch, about ``counts[i]^2`` of them: on a quad patch
        the ``s x s`` Gauss-Legendre points of its bilinear map, on a triangle patch the
        3-point (degree 2) rule on each of ``k^2`` pieces, ``k = ceil(s / sqrt(3))``; the
        centre for 1. Returns (points (S, 3), patch (S,), weight (S,)), each patch's
        weights summing to 1: ``sum w f(x)`` is the mean of ``f`` over the patch. ``only``:
        the patches to sample (``counts`` then one per listed patch).

        Parameters
        ----------
        counts : ndarray
            ``(P,)`` points a side of each patch's triangles.
        only : ndarray or None
            The patches to sample (None: every one).
        """
        counts = np.asarray(counts, np.int64)
        index = np.arange(self.n_patches) if only is None else np.asarray(only, np.int64)
        quad = self.corners[index, 3] >= 0
        pts, owner, weight = [], [], []
        for s in np.unique(counts[quad]):
            sel = np.flatnonzero(quad & (counts == s))
            c = self.vertices[self.corners[index[sel]]]  # (n, 4, 3)
            basis, du, dv, w2 = _square_rule(int(s))
            jac = np.linalg.norm(np.cross(np.einsum("sk,nkd->nsd", du, c),
                                          np.einsum("sk,nkd->nsd", dv, c)), axis=2)
            pts.append(np.einsum("sk,nkd->nsd", basis, c).reshape(-1, 3))
            owner.append(np.repeat(sel, len(w2)))
            weight.append((jac * w2).ravel())
        tri_k = np.where(counts <= 1, 1, np.ceil(counts / np.sqrt(3)).astype(np.int64))
        for k in np.unique(tri_k[~quad]):
            sel = np.flatnonzero(~quad & (tri_k == k))
            rule = _centre_rule() if counts[sel[0]] <= 1 else _pieces_rule(int(k))
            c = self.vertices[self.corners[index[sel], :3]]  # (n, 3, 3)
            pts.append(np.einsum("sc,ncd->nsd", rule, c).reshape(-1, 3))
            owner.append(np.repeat(sel, len(rule)))
            weight.append(np.repeat(self.areas[index[sel]] / len(rule), len(rule)))
        p, o, w = np.concatenate(pts), np.concatenate(owner), np.concatenate(weight)
        w = w / np.maximum(np.bincount(o, weights=w, minlength=len(index))[o], 1e-300)
        order = np.argsort(o, kind="stable")
        return p[order], index[o[order]], w[order]


def _centre_rule() -> np.ndarray:
    return np.full((1, 3), 1 / 3)


@lru_cache(maxsize=64)
def _square_rule(s: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The s x s Gauss-Legendre rule on the unit square as bilinear corner weights:
    (basis, d/du, d/dv (s^2, 4) each, weights (s^2,))."""
    x, w = np.polynomial.legendre.leggauss(s)
    uu, vv = np.meshgrid((x + 1) / 2, (x + 1) / 2, indexing="ij")
    u, v = uu.ravel(), vv.ravel()
    basis = np.stack([(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v], 1)
    du = np.stack([-(1 - v), 1 - v, v, -v], 1)
    dv = np.stack([-(1 - u), -u, u, 1 - u], 1)
    out = (basis, du, dv, np.outer(w, w).ravel() / 4)
    for a in out:
        a.flags.writeable = False
    return out


@lru_cache(maxsize=64)
def _pieces_rule(k: int) -> np.ndarray:
    """Barycentric points of the 3-point degree-2 rule on each of k^2 equal pieces."""
    bary, tris = _triangle_grid(k)
    sub = bary[tris]  # (k^2, 3 corners, 3)
    rule = np.array([[2 / 3, 1 / 6, 1 / 6], [1 / 6, 2 / 3, 1 / 6], [1 / 6, 1 / 6, 2 / 3]])
    out = np.einsum("rc,tcb->trb", rule, sub).reshape(-1, 3)
    out.flags.writeable = False
    return out


def _tri_areas(corners: np.ndarray) -> np.ndarray:
    return 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0],
                                         corners[:, 2] - corners[:, 0]), axis=1)


def _triangle_grid(k: int) -> tuple[np.ndarray, np.ndarray]:
    """Barycentric points of a triangle cut into k^2 (i + j <= k), and the sub-triangles
    (k^2, 3) as indices into them, all counter-clockwise like the triangle."""
    ij = np.array([(i, j) for i in range(k + 1) for j in range(k + 1 - i)])
    index = {tuple(p): n for n, p in enumerate(ij)}
    tris = []
    for i in range(k):
        for j in range(k - i):
            tris.append((index[i, j], index[i + 1, j], index[i, j + 1]))
            if i + j <= k - 2:
                tris.append((index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]))
    bary = np.column_stack([k - ij.sum(1), ij[:, 0], ij[:, 1]]) / k
    return bary, np.array(tris)


def _counts(length: np.ndarray, size: float) -> np.ndarray:
    return np.maximum(1, np.ceil(length / size - 1e-9)).astype(np.int64)


def subdivide(mesh: Mesh, size: float) -> Patches:
    """Cut ``mesh``'s polygons into patches whose edges are at most about ``size`` long.

    Parameters
    ----------
    mesh : Mesh
        The polygons.
    size : float
        The longest a patch's edge should be (scene units).
    """
    size = float(size)
    if not np.isfinite(size) or size <= 0:
        raise GeometryError(f"patch size must be a positive number, got {size!r}")
    v = mesh.vertices
    sizes = np.diff(mesh.face_offsets)
    quads = np.flatnonzero(sizes == 4)
    q = mesh.face_indices[mesh.face_offsets[quads][:, None] + np.arange(4)] if len(quads) \
        else np.zeros((0, 4), np.int64)
    c = v[q] if len(q) else np.zeros((0, 4, 3))
    split = 0
    if len(q):
        n = mesh.face_normals[quads]
        extent = np.linalg.norm(c.max(1) - c.min(1), axis=1)
        off_plane = np.abs(np.einsum("nkd,nd->nk", c - c.mean(1, keepdims=True), n)).max(1)
        planar = (off_plane <= PLANARITY * np.maximum(extent, 1e-300)) & \
            (np.linalg.norm(n, axis=1) > 0)
        split = int((~planar).sum())
        quads, c = quads[planar], c[planar]
    others = np.setdiff1d(np.arange(mesh.n_faces), quads)
    parts = [_grid_quads(c, quads, size)]
    if len(others):
        tri, owner = mesh.triangles
        keep = np.isin(owner, others)
        parts.append(_split_triangles(v[tri[keep]], owner[keep], size))
    return _assemble(parts, split, size)


def _grid_quads(c: np.ndarray, source: np.ndarray, size: float):
    """Corner positions (n, 4, 3) of quad patches, with their source polygons."""
    if not len(c):
        return np.zeros((0, 4, 3)), np.zeros(0, np.int64)
    e = np.linalg.norm(np.roll(c, -1, axis=1) - c, axis=2)  # edges 01, 12, 23, 30
    nu = _counts(np.maximum(e[:, 0], e[:, 2]), size)
    nv = _counts(np.maximum(e[:, 1], e[:, 3]), size)
    out, src = [], []
    for a, b in set(zip(nu.tolist(), nv.tolist())):
        sel = np.flatnonzero((nu == a) & (nv == b))
        u = np.linspace(0, 1, a + 1)
        w = np.linspace(0, 1, b + 1)
        uu, ww = np.meshgrid(u, w, indexing="ij")  # (a+1, b+1)
        basis = np.stack([(1 - uu) * (1 - ww), uu * (1 - ww), uu * ww, (1 - uu) * ww], -1)
        grid = np.einsum("abk,nkd->nabd", basis, c[sel])  # (n, a+1, b+1, 3)
        cell = np.stack([grid[:, :-1, :-1], grid[:, 1:, :-1], grid[:, 1:, 1:],
                         grid[:, :-1, 1:]], axis=3)  # (n, a, b, 4, 3)
        out.append(cell.reshape(-1, 4, 3))
        src.append(np.repeat(source[sel], a * b))
    return np.concatenate(out), np.concatenate(src)


def _split_triangles(corners: np.ndarray, source: np.ndarray, size: float):
    """Corner positions (n, 3, 3) of triangle patches, with their source polygons."""
    e = np.linalg.norm(np.roll(corners, -1, axis=1) - corners, axis=2).max(1)
    k = _counts(e, size)
    out, src = [], []
    for kk in np.unique(k):
        sel = np.flatnonzero(k == kk)
        bary, tris = _triangle_grid(int(kk))
        pts = np.einsum("pc,ncd->npd", bary, corners[sel])  # (n, points, 3)
        out.append(pts[:, tris].reshape(-1, 3, 3))
        src.append(np.repeat(source[sel], len(tris)))
    return np.concatenate(out), np.concatenate(src)


def _assemble(parts, split: int, size: float) -> Patches:
    (quads, qsrc), *rest = parts
    tris, tsrc = rest[0] if rest else (np.zeros((0, 3, 3)), np.zeros(0, np.int64))
    nq, nt = len(quads), len(tris)
    if nq + nt == 0:
        raise GeometryError("nothing to cut into patches: the mesh has no polygons")
    # each quad patch is two triangles (0 1 2, 0 2 3); each triangle patch one
    qt = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]]) if nq else \
        np.zeros((0, 3, 3))
    corners = np.concatenate([qt, tris])  # (T, 3, 3)
    patch = np.concatenate([np.arange(nq), np.arange(nq), nq + np.arange(nt)]).astype(np.int64)
    # weld by position, to a grid set by the geometry's own scale (2^-30 of its largest
    # coordinate: float noise, never a feature -- and never past int64), not by the patch
    # size (tiny patches overflowed the keys, large ones welded distinct corners)
    quantum = max(float(np.abs(corners).max()), 1e-300) * 2.0 ** -30
    keys = np.round(corners.reshape(-1, 3) / quantum).astype(np.int64)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    vertices = corners.reshape(-1, 3)[first]
    triangles = inverse.reshape(-1, 3)
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    tri_area = 0.5 * np.linalg.norm(cross, axis=1)
    n_p = nq + nt
    areas = np.bincount(patch, weights=tri_area, minlength=n_p)
    centers: np.ndarray = np.stack([np.bincount(patch, weights=tri_area * corners[:, :, d].mean(1),
                                    minlength=n_p) for d in range(3)], 1)
    centers = centers / np.maximum(areas, 1e-300)[:, None]
    normals = np.stack([np.bincount(patch, weights=cross[:, d], minlength=n_p)
                        for d in range(3)], 1)
    length = np.linalg.norm(normals, axis=1)
    normals = np.divide(normals, length[:, None], out=np.zeros_like(normals),
                        where=length[:, None] > 0)
    corner_ids = np.concatenate([
        np.column_stack([triangles[:nq], triangles[nq:2 * nq, 2]]),
        np.column_stack([triangles[2 * nq:], np.full(nt, -1)])]).astype(np.int64)
    source = np.concatenate([qsrc, tsrc]).astype(np.int64)
    keep = areas > 0  # degenerate pieces (zero-area source polygons) are dropped
    if not keep.all():
        remap = np.cumsum(keep) - 1
        tkeep = keep[patch]
        triangles, patch = triangles[tkeep], remap[patch[tkeep]]
        areas, centers, normals = areas[keep], centers[keep], normals[keep]
        source, corner_ids = source[keep], corner_ids[keep]
    return Patches(vertices, triangles, patch, source, centers, normals, areas, corner_ids,
                   split)
