"""Octrees, the notes' "efficient spatial enumeration": a cube cut into eight, and each
part that the boundary may cross cut again, down to a depth; every cell is inside,
outside or boundary.

Built level by level in numpy -- the boundary cells of a level become the next level's
cells, classified all at once -- from a CSG solid (each leaf's distance bound and the
booleans' three-valued logic: a cell is never called inside or outside by mistake) or from
a closed mesh (a cell whose centre is farther from every triangle than its half-diagonal
is inside or outside by the generalised winding number of its centre, vectorised and
robust on edges and vertices; the rest is boundary). So ``volume_bounds()`` brackets the
true volume at every depth, and the gap halves with each level.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import GeometryError
from .geometry.mesh import Mesh

__all__ = ["Octree", "winding_number", "point_chunks", "OUTSIDE", "INSIDE", "BOUNDARY",
           "CHUNK_SIZE", "CHUNKED_FROM"]

OUTSIDE, INSIDE, BOUNDARY = 0, 1, 2
#: a mesh of at least CHUNKED_FROM triangles (a cloud of as many points) is drawn in spatial
#: chunks of at most CHUNK_SIZE -- cells of the octree over its triangles' centroids or its
#: points (:func:`point_chunks`) -- each chunk's box tested against the view at every draw:
#: a camera that sees a tenth of a big mesh draws about a tenth of its triangles
CHUNK_SIZE = 65_536
CHUNKED_FROM = 4 * CHUNK_SIZE
_CHILDREN = np.array([[i >> 2 & 1, i >> 1 & 1, i & 1] for i in range(8)], np.int64)


@dataclass
class Level:
    """The cells of one level: integer ``coords`` (n, 3) on a 2^level grid and ``state``."""

    coords: np.ndarray
    state: np.ndarray

    @property
    def nbytes(self) -> int:
        return self.coords.nbytes + self.state.nbytes


class Octree:
    """Levels 0..depth; level 0 is the root cube ``origin`` + [0, size]^3.

    Parameters
    ----------
    origin : array_like
        ``(3,)`` the root cube's minimum corner.
    size : float
        The root cube's edge.
    levels : list of Level
        Each level's cells, 0 to depth.
    """

    def __init__(self, origin, size: float, levels: list[Level]):
        self.origin, self.size, self.levels = np.asarray(origin, np.float64), float(size), \
            levels

    @property
    def depth(self) -> int:
        return len(self.levels) - 1

    # ------------------------------------------------------------------ building
    @classmethod
    def build(cls, classify, bounds, depth: int) -> Octree:
        """Refine with ``classify(lo, hi) -> states`` over a cube around ``bounds``.

        Parameters
        ----------
        classify : callable
            ``(lo, hi) -> states``: each box ``(N, 3)`` INSIDE, OUTSIDE or BOUNDARY.
        bounds : array_like
            ``(2, 3)`` what to cover.
        depth : int
            The deepest level.
        """
        if int(depth) != depth or not 0 <= depth <= 12:
            raise GeometryError(f"octree depth must be a whole number from 0 to 12, got "
                                f"{depth!r}")
        b = np.asarray(bounds, np.float64)
        if b.shape != (2, 3) or not np.isfinite(b).all():
            raise GeometryError("an octree needs finite bounds: the solid is unbounded (cut "
                                "a half-space with a bounded solid)")
        size = float((b[1] - b[0]).max()) * (1 + 1e-9) or 1.0
        origin = (b[0] + b[1]) / 2 - size / 2
        coords = np.zeros((1, 3), np.int64)
        levels = []
        for level in range(int(depth) + 1):
            cell = size / 2 ** level
            lo = origin + coords * cell
            state = np.asarray(classify(lo, lo + cell), np.int8)
            levels.append(Level(coords, state))
            split = coords[state == BOUNDARY]
            coords = (2 * split[:, None, :] + _CHILDREN[None]).reshape(-1, 3)
        return cls(origin, size, levels)

    @classmethod
    def from_solid(cls, solid, depth: int) -> Octree:
        """The octree of a CSG solid, its boxes classified conservatively
        (:meth:`Solid.classify_boxes`: a box is boundary unless surely in or out).

        Parameters
        ----------
        solid : Solid
            The solid (bounded).
        depth : int
            The deepest level.
        """
        return cls.build(solid.classify_boxes, solid.bounds, depth)

    @classmethod
    def from_mesh(cls, mesh: Mesh, depth: int) -> Octree:
        """Of a closed, oriented mesh (an open one has no inside: an error).

        Parameters
        ----------
        mesh : Mesh
            A closed, consistently oriented mesh.
        depth : int
            The deepest level.
        """
        if not mesh.closed_and_oriented:
            raise GeometryError("octree from a mesh needs a closed, consistently oriented "
                                "mesh (its inside is otherwise undefined)")
        tri = mesh.vertices[mesh.triangles[0]]

        def classify(lo, hi):
            centre, half = (lo + hi) / 2, np.linalg.norm(hi - lo, axis=1) / 2
            near = _distance_below(centre, tri, half)
            state = np.full(len(lo), BOUNDARY, np.int8)
            far = ~near
            if far.any():
                w = winding_number(centre[far], tri)
                state[far] = np.where(w > 0.5, INSIDE, OUTSIDE)
            return state

        return cls.build(classify, mesh.bounds, depth)

    # ------------------------------------------------------------------ queries
    def cell_size(self, level: int) -> float:
        """A cell's edge length at ``level``.

        Parameters
        ----------
        level : int
            0 (the root) to the depth.
        """
        return self.size / 2 ** level

    def __repr__(self) -> str:
        inner, outer = self.volume_bounds()
        return (f"<Octree: depth {self.depth}, {self.counts()[-1]['boundary']:,} boundary "
                f"cells at the deepest; volume {inner:.4g} .. {outer:.4g}>")

    def _repr_html_(self) -> str:
        """In a notebook: its inside cells drawn, and the cells per level."""
        from .display import facts_html, picture

        inside = self.to_mesh("inside")
        image = picture(inside, mode="flat") if inside.n_faces else None
        facts = [f"level {c['level']}: {c['inside']:,} in, {c['boundary']:,} boundary"
                 for c in self.counts()]
        return facts_html(repr(self), facts, image)

    def counts(self) -> list[dict]:
        """Per level: cells inside, outside, boundary and the bytes they take."""
        return [{"level": k, "inside": int((lv.state == INSIDE).sum()),
                 "outside": int((lv.state == OUTSIDE).sum()),
                 "boundary": int((lv.state == BOUNDARY).sum()), "bytes": lv.nbytes}
                for k, lv in enumerate(self.levels)]

    def volume_bounds(self) -> tuple[float, float]:
        """(inside cells' volume, that plus the deepest level's boundary cells'): the
        solid's volume lies between them."""
        inner = sum(int((lv.state == INSIDE).sum()) * self.cell_size(k) ** 3
                    for k, lv in enumerate(self.levels))
        boundary = int((self.levels[-1].state == BOUNDARY).sum()) * \
            self.cell_size(self.depth) ** 3
        return inner, inner + boundary

    def _lookup(self, level: int, coords: np.ndarray) -> np.ndarray:
        """State of cells (n, 3) at ``level``: their own, or their nearest stored
        ancestor's; OUTSIDE beyond the root."""
        n = 2 ** level
        out = np.full(len(coords), OUTSIDE, np.int8)
        valid = ((coords >= 0) & (coords < n)).all(1)
        pending = np.flatnonzero(valid)
        for k in range(level, -1, -1):
            if not len(pending):
                break
            c = coords[pending] >> (level - k)
            lv = self.levels[k] if k < len(self.levels) else None
            if lv is None:
                continue
            m = 2 ** k
            keys = (lv.coords[:, 0] * m + lv.coords[:, 1]) * m + lv.coords[:, 2]
            order = np.argsort(keys)
            q = (c[:, 0] * m + c[:, 1]) * m + c[:, 2]
            pos = np.clip(np.searchsorted(keys[order], q), 0, max(len(keys) - 1, 0))
            found = len(keys) > 0
            hit = found & (keys[order][pos] == q) if found else np.zeros(len(q), bool)
            st = lv.state[order][pos]
            settled = hit & (st != BOUNDARY) | hit & (k == min(level, self.depth))
            out[pending[settled]] = st[settled]
            pending = pending[~settled]
        return out

    def classify(self, points) -> np.ndarray:
        """``(N,) int8``: INSIDE, OUTSIDE or BOUNDARY (a deepest-level boundary cell) for
        each point.

        Parameters
        ----------
        points : array_like
            ``(N, 3)`` positions.
        """
        p = np.asarray(points, np.float64)
        if p.ndim != 2 or p.shape[1] != 3:
            raise GeometryError(f"points must have shape (N, 3), got {p.shape}")
        cell = np.floor((p - self.origin) / self.cell_size(self.depth)).astype(np.int64)
        return self._lookup(self.depth, cell)

    def neighbours(self, level: int, coords) -> np.ndarray:
        """States ``(n, 6)`` of the face neighbours (-x, +x, -y, +y, -z, +z) of cells at
        ``level`` (an unrefined neighbour answers for its part).

        Parameters
        ----------
        level : int
            The cells' level.
        coords : array_like
            ``(n, 3)`` integer cell coordinates at that level.
        """
        c = np.asarray(coords, np.int64).reshape(-1, 3)
        steps = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1],
                          [0, 0, 1]])
        nb = (c[:, None, :] + steps[None]).reshape(-1, 3)
        return self._lookup(int(level), nb).reshape(-1, 6)

    def occupancy(self, which: str = "inside") -> np.ndarray:
        """Dense ``(n, n, n) bool`` at the deepest level, n = 2^depth: the cells that are
        inside (or inside or boundary, ``which="inside+boundary"``).

        Parameters
        ----------
        which : str
            ``"inside"`` or ``"inside+boundary"``.
        """
        if which not in ("inside", "inside+boundary"):
            raise GeometryError(f"which must be 'inside' or 'inside+boundary', got {which!r}")
        if self.depth > 9:
            raise GeometryError(f"a dense grid of depth {self.depth} has "
                                f"{8 ** self.depth:,} cells; mesh depths up to 9")
        n = 2 ** self.depth
        occ = np.zeros((n, n, n), bool)
        for k, lv in enumerate(self.levels):
            keep = (lv.state == INSIDE) | ((lv.state == BOUNDARY) & (k == self.depth) &
                                           (which != "inside"))
            c = lv.coords[keep]
            f = 2 ** (self.depth - k)
            # each kept cell fills an f^3 block: spread its corner over the block's offsets
            offsets = np.stack(np.meshgrid(*[np.arange(f)] * 3, indexing="ij"), -1)
            cells = (c[:, None, :] * f + offsets.reshape(1, -1, 3)).reshape(-1, 3)
            occ[cells[:, 0], cells[:, 1], cells[:, 2]] = True
        return occ

    def to_mesh(self, which: str = "inside") -> Mesh:
        """The cells as one closed surface of quads (for rendering voxels).

        Parameters
        ----------
        which : str
            ``"inside"`` or ``"inside+boundary"``.
        """
        from .geometry.primitives import voxels

        occ = self.occupancy(which)
        if not occ.any():
            raise GeometryError(f"no {which} cells to mesh")
        m = voxels(occ, self.cell_size(self.depth))
        return m.transformed(np.block([[np.eye(3), self.origin[:, None]],
                                       [np.zeros((1, 3)), np.ones((1, 1))]]))


def point_chunks(points, max_count: int, depth: int = 10
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Points grouped by the octree's spatial enumeration: the cube around them cut into
    eight, and each cell holding more than ``max_count`` points cut again, down to
    ``depth`` -- so each group is one octree cell, as compact in space as its count allows
    (what a draw culls by: a cell's box outside the view skips all its triangles).

    Vectorised level by level: the points are sorted by the Morton code of their cell at
    ``depth`` (a cell's points are then contiguous, its children's in order within it), and
    at each level the runs of one cell's code that are small enough are closed.

    Parameters
    ----------
    points : array_like
        ``(N, 3)`` the points (a mesh's triangle centroids).
    max_count : int
        The most points a group holds (past ``depth``, a cell keeps all it has).
    depth : int
        The deepest level, 1 to 20.

    Returns
    -------
    order : ndarray
        ``(N,)`` int64: the points in group order (each group's in Morton order).
    starts : ndarray
        ``(G + 1,)`` int64: group g is ``order[starts[g]:starts[g + 1]]``.
    """
    p = np.asarray(points, np.float64)
    if p.ndim != 2 or p.shape[1] != 3 or not len(p):
        raise GeometryError(f"point_chunks needs (N, 3) points with N >= 1, got {p.shape}")
    if int(max_count) < 1 or not 1 <= int(depth) <= 20:
        raise GeometryError(f"point_chunks needs max_count >= 1 and depth 1 to 20, got "
                            f"{max_count!r} and {depth!r}")
    lo = p.min(0)
    size = float((p.max(0) - lo).max()) or 1.0
    cells = np.clip(((p - lo) / size * 2 ** depth).astype(np.int64), 0, 2 ** depth - 1)
    code = np.zeros(len(p), np.int64)
    for bit in range(depth):  # (interleave: x, y, z bits of each level, coarsest first)
        for axis in range(3):
            code |= ((cells[:, axis] >> bit) & 1) << (3 * bit + 2 - axis)
    order = np.argsort(code, kind="stable")
    code = code[order]
    active = np.ones(len(p), bool)
    starts = []
    for level in range(depth + 1):
        idx = np.flatnonzero(active)
        if not len(idx):
            break
        key = code[idx] >> (3 * (depth - level))
        new = np.r_[True, (key[1:] != key[:-1]) | (idx[1:] != idx[:-1] + 1)]
        first = np.flatnonzero(new)
        length = np.diff(np.r_[first, len(idx)])
        close = (length <= max_count) | (level == depth)
        starts.append(idx[first[close]])
        active[idx[np.repeat(close, length)]] = False
    return order, np.r_[np.sort(np.concatenate(starts)), len(p)].astype(np.int64)


def winding_number(points, triangles) -> np.ndarray:
    """Generalised winding number of each point (N, 3) about triangles (T, 3, 3): the sum
    of their solid angles over 4 pi (Van Oosterom and Strackee), chunked. 1 inside a
    closed outward mesh, 0 outside, and it degrades gracefully near edges and vertices.

    Parameters
    ----------
    points : array_like
        ``(N, 3)`` positions.
    triangles : array_like
        ``(T, 3, 3)`` a closed surface's triangles.
    """
    p = np.asarray(points, np.float64)
    out = np.zeros(len(p))
    step = max(1, 2_000_000 // max(len(triangles), 1))
    for s in range(0, len(p), step):
        a = triangles[None, :, 0] - p[s:s + step, None]
        b = triangles[None, :, 1] - p[s:s + step, None]
        c = triangles[None, :, 2] - p[s:s + step, None]
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        det = np.einsum("ntd,ntd->nt", a, np.cross(b, c))
        den = la * lb * lc + np.einsum("ntd,ntd->nt", a, b) * lc + \
            np.einsum("ntd,ntd->nt", b, c) * la + np.einsum("ntd,ntd->nt", c, a) * lb
        out[s:s + step] = np.arctan2(det, den).sum(1) / (2 * np.pi)
    return out


def _distance_below(points, triangles, limit) -> np.ndarray:
    """Whether each point is within ``limit`` (N,) of some triangle: a cheap test against
    the triangles' boxes first, the exact point-triangle distance only for the pairs it
    keeps (chunked)."""
    near = np.zeros(len(points), bool)
    lo, hi = triangles.min(1), triangles.max(1)
    step = max(1, 4_000_000 // max(len(triangles), 1))
    for s in range(0, len(points), step):
        p, lim = points[s:s + step], limit[s:s + step]
        gap = np.maximum(np.maximum(lo[None] - p[:, None], p[:, None] - hi[None]), 0)
        pi, ti = np.nonzero(np.einsum("ntd,ntd->nt", gap, gap) <= lim[:, None] ** 2)
        if not len(pi):
            continue
        d2 = _point_triangle_d2(p[pi], triangles[ti])
        hit = np.zeros(len(p), bool)
        hit[pi[d2 <= lim[pi] ** 2]] = True
        near[s:s + step] = hit
    return near


def _point_triangle_d2(p, t) -> np.ndarray:
    """Squared distances from points (..., 3) to triangles (..., 3, 3), broadcast
    (Ericson's region tests: the face, else the nearest edge point)."""
    a, b, c = t[..., 0, :], t[..., 1, :], t[..., 2, :]
    ab, ac, ap = b - a, c - a, p - a
    bp, cp = p - b, p - c

    def dot(x, y):
        return (x * y).sum(-1)

    d1, d2 = dot(ab, ap), dot(ac, ap)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = 1.0 / (va + vb + vc)
        v, w = vb * denom, vc * denom
        q = a + ab * v[..., None] + ac * w[..., None]  # inside the face
        tab = np.clip(d1 / (d1 - d3), 0, 1)
        tac = np.clip(d2 / (d2 - d6), 0, 1)
        tbc = np.clip((d4 - d3) / ((d4 - d3) + (d5 - d6)), 0, 1)
    edges = [a + ab * np.nan_to_num(tab)[..., None], a + ac * np.nan_to_num(tac)[..., None],
             b + (c - b) * np.nan_to_num(tbc)[..., None]]
    face_ok = (va >= 0) & (vb >= 0) & (vc >= 0) & np.isfinite(v) & np.isfinite(w)
    best = np.where(face_ok, ((p - q) ** 2).sum(-1), np.inf)
    for e in edges:
        best = np.minimum(best, ((p - e) ** 2).sum(-1))
    return best
