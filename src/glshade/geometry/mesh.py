"""Polygon meshes with n-gons kept, and their face and vertex normals.

Faces are stored compactly as one flat index array plus offsets (CSR layout): face ``f``
is ``indices[offsets[f]:offsets[f + 1]]``. Work that depends on the polygon size is done
per distinct size (a handful of groups), never per face.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import GeometryError
from .analytic import AnalyticSurface, affine_matrix
from .csr import faces_to_csr
from .edges import EdgeGroups, edge_groups, is_closed_and_oriented
from .polygon import newell_of_indexed, triangulate_groups, unit_normals

__all__ = ["Mesh", "MAX_COORDINATE"]

#: the largest coordinate magnitude a mesh may have: squares (areas, lengths) stay finite
MAX_COORDINATE = 1e150


def _readonly(a: np.ndarray) -> np.ndarray:
    a.setflags(write=False)
    return a


def _colors(value, count: int, name: str, what: str):
    """``(count, 4)`` float64 RGBA from ``(count, 3|4)`` values in [0, 1], read-only; None
    stays None; a GeometryError names the first bad row."""
    if value is None:
        return None
    c = np.array(value, dtype=np.float64)
    if c.ndim != 2 or c.shape[0] != count or c.shape[1] not in (3, 4):
        raise GeometryError(f"{name} must have shape ({count}, 3) or ({count}, 4) (RGB or "
                            f"RGBA a {what}, linear, each in [0, 1]), got {c.shape}")
    bad = ~(np.isfinite(c) & (c >= 0) & (c <= 1)).all(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise GeometryError(f"{name}: {what} {i} has {c[i].tolist()}, not in [0, 1] "
                            f"({int(bad.sum())} such rows; 8-bit colours are divided by 255)")
    if c.shape[1] == 3:
        c = np.hstack([c, np.ones((count, 1))])
    return _readonly(c)


class Mesh:
    """A polygon mesh: vertices ``(V, 3)`` float64 and faces of any size n >= 3.

    Parameters
    ----------
    vertices : (V, 3) array_like
        Vertex positions.
    faces : (F, k) int array_like or sequence of index sequences
        Polygons, counter-clockwise seen from outside; convex or concave.
    normals : (V, 3) array_like, optional
        Vertex normals read from a file; used by smooth shading instead of computed ones.
    groups : mapping of name to face indices, optional
        Named parts (OBJ objects, the Cornell box's walls ...).
    uv : (C, 2) array_like, optional
        Texture coordinates per corner (one per entry of the faces, in order: a vertex on a
        texture seam has one per face, as OBJ's ``vt`` gives them); (0, 0) is an image's
        bottom-left.
    name : str, optional
        The mesh's name (a file's stem; what a scene calls its model by default).
    colors : (V, 3) or (V, 4) array_like, optional
        A colour per vertex, linear RGB (and alpha), each in [0, 1]: the notes' surface
        colour C at the vertex (what a texture would give), multiplying the material's
        ambient and diffuse colours; alpha multiplies its opacity. A PLY's or OBJ's vertex
        colours, a glTF's ``COLOR_0``.
    face_colors : (F, 3) or (F, 4) array_like, optional
        A colour per polygon, likewise (with ``colors`` too, the two multiply).

    Raises
    ------
    GeometryError
        Wrong shapes, non-finite coordinates, a face with fewer than 3 vertices or an index
        out of range; the message names the face or vertex.
    """

    def __init__(
        self,
        vertices: ArrayLike,
        faces,
        *,
        normals: ArrayLike | None = None,
        groups: Mapping[str, ArrayLike] | None = None,
        name: str | None = None,
        uv: ArrayLike | None = None,
        colors: ArrayLike | None = None,
        face_colors: ArrayLike | None = None,
    ):
        v = np.array(vertices, dtype=np.float64)
        if v.ndim != 2 or v.shape[1] != 3:
            if v.size == 0:
                v = v.reshape(0, 3)
            else:
                raise GeometryError(f"vertices must have shape (n, 3), got {v.shape}")
        bad = ~np.isfinite(v).all(axis=1)
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise GeometryError(
                f"vertex {i} has a non-finite coordinate {v[i].tolist()} "
                f"({int(bad.sum())} such vertices)"
            )
        huge = (np.abs(v) > MAX_COORDINATE).any(axis=1)
        if huge.any():
            i = int(np.flatnonzero(huge)[0])
            raise GeometryError(
                f"vertex {i} has a coordinate beyond {MAX_COORDINATE:g}: {v[i].tolist()} (areas "
                "and normals square coordinates; scale the mesh down)")
        if isinstance(faces, tuple) and len(faces) == 2 and all(
            isinstance(x, np.ndarray) for x in faces
        ):
            indices, offsets = (np.asarray(faces[0], np.int64), np.asarray(faces[1], np.int64))
        else:
            indices, offsets = faces_to_csr(faces)
        self._init_arrays(v, indices, offsets)
        self.normals_from_file = None
        if normals is not None:
            n = np.array(normals, dtype=np.float64)
            if n.shape != v.shape:
                raise GeometryError(
                    f"normals must have the shape of vertices {v.shape}, got {n.shape}"
                )
            self.normals_from_file = _readonly(unit_normals(n)[0])
        self.groups = {
            str(k): _readonly(np.asarray(g, dtype=np.int64)) for k, g in (groups or {}).items()
        }
        self.name = name
        #: the exact surface this mesh approximates, when known (sphere primitives carry an
        #: AnalyticSphere): analytic references ray-cast it
        self.analytic: AnalyticSurface | None = None
        self.uv: NDArray[np.float64] | None = None
        if uv is not None:
            t = np.array(uv, dtype=np.float64)
            if t.shape != (len(self.face_indices), 2):
                hint = (f"; coordinates per vertex ({len(v)}, 2) go per corner as "
                        "uv[mesh.face_indices]" if t.shape == (len(v), 2) else "")
                raise GeometryError(f"uv must have one (u, v) per face corner, shape "
                                    f"({len(self.face_indices)}, 2), got {t.shape}{hint}")
            bad = ~np.isfinite(t).all(axis=1)
            if bad.any():
                c = int(np.flatnonzero(bad)[0])
                raise GeometryError(f"texture coordinate of corner {c} (face "
                                    f"{int(self.corner_face[c])}) is not finite: {t[c].tolist()}")
            self.uv = _readonly(t)
        #: ``(V, 4)`` linear RGBA a vertex, or None
        self.colors: NDArray[np.float64] | None = _colors(colors, len(v), "colors", "vertex")
        #: ``(F, 4)`` linear RGBA a polygon, or None
        self.face_colors: NDArray[np.float64] | None = _colors(face_colors, self.n_faces,
                                                                "face_colors", "face")
        #: materials by name and the faces of each (an OBJ's ``usemtl`` parts); a scene
        #: draws each part with its material (Scene.add)
        self.materials: dict[str, object] = {}
        self.material_groups: dict[str, NDArray[np.int64]] = {}
        #: what the material files said that is not drawn ("file:line: statement")
        self.material_notes: list[str] = []

    def _init_arrays(self, v, indices, offsets) -> None:
        sizes = np.diff(offsets)
        small = sizes < 3
        if small.any():
            f = int(np.flatnonzero(small)[0])
            raise GeometryError(
                f"face {f} has {int(sizes[f])} vertices; a polygon needs at least 3 "
                f"({int(small.sum())} such faces)"
            )
        out = (indices < 0) | (indices >= len(v))
        if out.any():
            c = int(np.flatnonzero(out)[0])
            f = int(np.searchsorted(offsets, c, side="right") - 1)
            raise GeometryError(
                f"face {f} refers to vertex {int(indices[c])}, but there are {len(v)} vertices "
                f"(valid indices 0..{len(v) - 1}; {int(out.sum())} bad indices in all)"
            )
        self.vertices: NDArray[np.float64] = _readonly(v)
        self.face_indices: NDArray[np.int64] = _readonly(indices)
        self.face_offsets: NDArray[np.int64] = _readonly(offsets)
        self.face_sizes: NDArray[np.int64] = _readonly(sizes)

    # ------------------------------------------------------------------ basics
    @classmethod
    def from_csr(cls, vertices, indices, offsets, **kwargs) -> Mesh:
        """Build from the flat layout directly (no per-face Python objects).

        Parameters
        ----------
        vertices : array_like
            ``(V, 3)`` positions.
        indices : array_like
            ``(N,)`` the faces' vertex indices, one face after another.
        offsets : array_like
            ``(F + 1,)`` where each face starts in ``indices`` (the last: ``N``).
        **kwargs
            Mesh's other fields (name, normals, uv ...).
        """
        return cls(vertices, (np.asarray(indices), np.asarray(offsets)), **kwargs)

    @property
    def n_vertices(self) -> int:
        return len(self.vertices)

    @property
    def n_faces(self) -> int:
        return len(self.face_sizes)

    @property
    def colored(self) -> bool:
        """Whether the mesh carries colours (per vertex, per polygon or both)."""
        return self.colors is not None or self.face_colors is not None

    @cached_property
    def corner_colors(self) -> NDArray[np.float64] | None:
        """``(C, 4)`` linear RGBA at each face corner: the vertex's colour times its
        polygon's (None without colours)."""
        if not self.colored:
            return None
        c = np.ones((len(self.face_indices), 4))
        if self.colors is not None:
            c = c * self.colors[self.face_indices]
        if self.face_colors is not None:
            c = c * self.face_colors[self.corner_face]
        return _readonly(c)

    @cached_property
    def translucent(self) -> bool:
        """Whether any of its colours has an alpha below 1 (drawn as a transparent surface
        where the material takes its colours)."""
        corners = self.corner_colors
        return corners is not None and bool((corners[:, 3] < 1).any())

    @cached_property
    def polygon_colors(self) -> NDArray[np.float64] | None:
        """``(F, 4)`` each polygon's one colour for uniform (flat) shading: the mean of its
        corners' colours (None without colours)."""
        corners = self.corner_colors
        if corners is None:
            return None
        sums = np.add.reduceat(corners, self.face_offsets[:-1], axis=0)
        return _readonly(sums / self.face_sizes[:, None])

    @cached_property
    def n_edges(self) -> int:
        return len(self.edges)

    def face(self, f: int) -> NDArray[np.int64]:
        """Vertex indices of face ``f``.

        Parameters
        ----------
        f : int
            The face's index.
        """
        return self.face_indices[self.face_offsets[f] : self.face_offsets[f + 1]]

    @property
    def faces(self) -> list[NDArray[np.int64]]:
        """Faces as a list of index arrays (convenient; slow for big meshes)."""
        return np.split(self.face_indices, self.face_offsets[1:-1])

    def __repr__(self) -> str:
        name = f" {self.name!r}" if self.name else ""
        return f"<Mesh{name}: {self.n_vertices} vertices, {self.n_faces} faces>"

    def _repr_html_(self) -> str:
        """In a notebook: a thumbnail and the counts (:mod:`glshade.notebook.display`)."""
        from ..display import bounds_fact, facts_html, picture

        facts = [f"{self.n_vertices:,} vertices, {self.n_faces:,} polygons",
                 "closed and oriented" if self.closed_and_oriented else "open or unoriented",
                 bounds_fact(self.bounds if self.n_vertices else None)]
        return facts_html(repr(self), facts, picture(self) if self.n_faces else None)

    @cached_property
    def size_groups(self) -> dict[int, tuple[NDArray[np.int64], NDArray[np.int64]]]:
        """``{k: (face_ids (n,), indices (n, k))}`` for every polygon size k present."""
        sizes = self.face_sizes
        if len(sizes) and sizes.min() == sizes.max():  # one size: a reshape, no gather
            k = int(sizes[0])
            return {k: (np.arange(len(sizes)), self.face_indices.reshape(-1, k))}
        groups = {}
        for k in np.unique(sizes).tolist():
            ids = np.flatnonzero(self.face_sizes == k)
            idx = self.face_indices[self.face_offsets[ids][:, None] + np.arange(k)]
            groups[int(k)] = (ids, idx)
        return groups

    @cached_property
    def corner_face(self) -> NDArray[np.int64]:
        """Face of each corner ``(C,)``; a corner is one entry of ``face_indices``."""
        return _readonly(np.repeat(np.arange(self.n_faces), self.face_sizes))

    @cached_property
    def corner_next(self) -> NDArray[np.int64]:
        """Index of the next corner around the same face ``(C,)``."""
        nxt = np.arange(1, len(self.face_indices) + 1, dtype=np.int64)
        nxt[self.face_offsets[1:] - 1] = self.face_offsets[:-1]
        return _readonly(nxt)

    @cached_property
    def corner_prev(self) -> NDArray[np.int64]:
        """Index of the previous corner around the same face ``(C,)``."""
        prv = np.arange(-1, len(self.face_indices) - 1, dtype=np.int64)
        prv[self.face_offsets[:-1]] = self.face_offsets[1:] - 1
        return _readonly(prv)

    @cached_property
    def half_edges(self) -> NDArray[np.int64]:
        """Directed edges ``(C, 2)`` (from, to), one per corner, in face order."""
        return _readonly(
            np.stack([self.face_indices, self.face_indices[self.corner_next]], axis=1)
        )

    @cached_property
    def edges(self) -> NDArray[np.int64]:
        """Unique undirected edges ``(E, 2)``, smaller index first."""
        return _readonly(np.stack([self.edge_groups.lo, self.edge_groups.hi], axis=1))

    @cached_property
    def edge_faces(self) -> NDArray[np.int64]:
        """``(E, 2)`` the faces on either side of each edge of :attr:`edges` (a boundary
        edge's one face twice; an edge of more than two faces, its first two), so that an
        edge can be drawn where either of its faces is seen."""
        return _readonly(self.corner_face[self.edge_groups.sides])

    @cached_property
    def edge_side_triangles(self) -> NDArray[np.int64]:
        """``(E, 2)`` the triangle of :attr:`triangles` beside each edge on either side (of
        :attr:`edge_faces`: the one of that face's triangles that holds the edge), -1 where
        the triangulation left it out (a degenerate polygon). A polygon that is not planar
        is drawn as its triangles: next to an edge the surface drawn is that triangle's
        plane, not the polygon's mean (Newell) plane."""
        tri, owner = self.triangles
        sides = self.edge_groups.sides                      # (E, 2) corners
        span = np.int64(self.n_vertices)
        # the directed edges of the triangles and of each side's corner, keyed by (polygon,
        # from * V + to) (one product of the three would pass int64 on a big mesh): sorted
        # together, a side's match is the last triangle edge at or before it (the
        # triangulation keeps each polygon's winding)
        he = self.half_edges[sides.ravel()]
        face = np.concatenate([np.repeat(owner, 3), self.corner_face[sides.ravel()]])
        edge = np.concatenate([tri.ravel() * span + tri[:, [1, 2, 0]].ravel(),
                               he[:, 0] * span + he[:, 1]])
        asked = np.arange(len(face)) >= 3 * len(tri)
        order = np.lexsort((asked, edge, face))
        last = np.maximum.accumulate(np.where(asked[order], -1, np.arange(len(order))))
        where = np.empty(len(order), np.int64)
        where[order] = np.arange(len(order))
        j = last[where[asked]]                 # (each side's last triangle edge, sorted)
        k = order[np.maximum(j, 0)]
        s_face, s_edge = face[asked], edge[asked]
        match = (j >= 0) & (face[k] == s_face) & (edge[k] == s_edge)
        out = np.where(match, k // 3, -1)
        return _readonly(out.reshape(-1, 2))

    @cached_property
    def edge_side_normals(self) -> NDArray[np.float64]:
        """``(E, 2, 3)`` the unit normal of the triangle beside each edge on either side
        (:attr:`edge_side_triangles`): the plane drawn there, which the edge overlay
        recognises in the depth buffer -- the face's own normal where the triangulation
        left that side out or its triangle has no area."""
        tri, _ = self.triangles
        side = self.edge_side_triangles
        corners = self.vertices[tri[side.clip(min=0)]]                  # (E, 2, 3, 3)
        n = np.cross(corners[..., 1, :] - corners[..., 0, :],
                     corners[..., 2, :] - corners[..., 0, :])
        length = np.linalg.norm(n, axis=-1, keepdims=True)
        n = np.divide(n, length, out=np.zeros_like(n), where=length > 0)
        drawn = (side >= 0)[..., None] & (length > 0)
        return _readonly(np.where(drawn, n, self.face_normals[self.edge_faces]))

    @cached_property
    def edge_groups(self) -> EdgeGroups:
        """The half-edges grouped by undirected edge (see :mod:`glshade.geometry.edges`)."""
        he = self.half_edges
        return edge_groups(he[:, 0], he[:, 1], self.n_vertices)

    @cached_property
    def bounds(self) -> NDArray[np.float64]:
        """``(2, 3)``: minimum and maximum corner of the bounding box."""
        if self.n_vertices == 0:
            return np.zeros((2, 3))
        return _readonly(np.stack([self.vertices.min(axis=0), self.vertices.max(axis=0)]))

    @cached_property
    def _area_scale(self) -> float:
        extent = float(np.ptp(self.bounds, axis=0).max()) if self.n_vertices else 0.0
        return max(extent, 1e-300) ** 2

    # ----------------------------------------------------------------- normals
    @cached_property
    def newell_normals(self) -> NDArray[np.float64]:
        """Unnormalised Newell normal of each face ``(F, 3)``; length = 2 * area."""
        groups = list(self.size_groups.values())
        if len(groups) == 1:
            return _readonly(newell_of_indexed(self.vertices, groups[0][1]))
        out = np.zeros((self.n_faces, 3))
        for ids, idx in groups:
            out[ids] = newell_of_indexed(self.vertices, idx)
        return _readonly(out)

    @cached_property
    def _unit_face_normals(self):
        return unit_normals(self.newell_normals, self._area_scale)

    @property
    def face_normals(self) -> NDArray[np.float64]:
        """Unit Newell normal of each face ``(F, 3)``; zero for a degenerate face."""
        return _readonly(self._unit_face_normals[0])

    @property
    def degenerate_faces(self) -> NDArray[np.int64]:
        """Indices of faces with (numerically) zero area, whose normal is zero."""
        return np.flatnonzero(~self._unit_face_normals[1])

    @cached_property
    def face_areas(self) -> NDArray[np.float64]:
        """Area of each face ``(F,)`` (exact for planar polygons, concave included)."""
        return _readonly(0.5 * np.linalg.norm(self.newell_normals, axis=1))

    @cached_property
    def face_centroids(self) -> NDArray[np.float64]:
        """Mean of each face's vertices ``(F, 3)``."""
        sums = np.stack(
            [np.bincount(self.corner_face, self.vertices[self.face_indices, j], self.n_faces)
             for j in range(3)],
            axis=1,
        )
        return _readonly(sums / self.face_sizes[:, None])

    def _scatter_to_vertices(self, per_corner: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.stack(
            [np.bincount(self.face_indices, per_corner[:, j], self.n_vertices) for j in range(3)],
            axis=1,
        )

    @cached_property
    def _normal_sums(self):
        return unit_normals(self._scatter_to_vertices(self.face_normals[self.corner_face]),
                            1e-24)

    @property
    def folded_vertices(self) -> NDArray[np.int64]:
        """Vertices whose faces' normals cancel (a two-sided wall: the same polygon wound
        both ways), where no smooth normal exists; ``split_creases`` separates them."""
        used = np.zeros(self.n_vertices, bool)
        used[self.face_indices[self._unit_face_normals[1][self.corner_face]]] = True
        return np.flatnonzero(used & ~self._normal_sums[1])

    @cached_property
    def vertex_normals(self) -> NDArray[np.float64]:
        """Unit vertex normals ``(V, 3)``: normalised sum of the unit normals of the faces
        around each vertex (the notes' formula). Where the sum vanishes (see
        :attr:`folded_vertices`) the normal of one incident face stands in; zero only for a
        vertex in no valid face."""
        n, ok = self._normal_sums
        if not ok.all():
            valid = self._unit_face_normals[1][self.corner_face]
            fallback = np.zeros_like(n)
            fallback[self.face_indices[valid]] = self.face_normals[self.corner_face[valid]]
            n = np.where(ok[:, None], n, fallback)
        return _readonly(n)

    @cached_property
    def corner_angles(self) -> NDArray[np.float64]:
        """Interior angle of the polygon at each corner ``(C,)``, radians."""
        p = self.vertices[self.face_indices]
        a = self.vertices[self.face_indices[self.corner_prev]] - p
        b = self.vertices[self.face_indices[self.corner_next]] - p
        cross = np.linalg.norm(np.cross(a, b), axis=1)
        return _readonly(np.arctan2(cross, np.einsum("ij,ij->i", a, b)))

    def vertex_normals_weighted(self, by: str = "area") -> NDArray[np.float64]:
        """Vertex normals with each face's unit normal weighted ``by`` "area", "angle" or
        "unit" (equal weights, the same as :attr:`vertex_normals`).

        Parameters
        ----------
        by : str
            ``"area"``, ``"angle"`` or ``"unit"``.
        """
        if by == "unit":
            return self.vertex_normals
        if by == "area":
            w = self.face_areas[self.corner_face]
        elif by == "angle":
            w = self.corner_angles
        else:
            raise GeometryError(f"by must be one of 'area', 'angle', 'unit'; got {by!r}")
        summed = self._scatter_to_vertices(self.face_normals[self.corner_face] * w[:, None])
        return unit_normals(summed, 1e-24)[0]

    # ------------------------------------------------------------- operations
    def triangulate(self) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
        """Triangles for drawing, and the polygon each came from.

        Convex polygons are fanned from their first vertex in bulk; concave ones are ear
        clipped one by one (they are rare, and only they pay for it).

        Returns
        -------
        triangles : (T, 3) int64
            Vertex indices, wound like their polygon.
        face_index : (T,) int64
            The source polygon of each triangle, non-decreasing.
        """
        return triangulate_groups(self.vertices, self.size_groups, self.newell_normals)

    @cached_property
    def triangles(self) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
        """Cached :meth:`triangulate`."""
        return self.triangulate()

    @cached_property
    def corner_triangles(self) -> NDArray[np.int64]:
        """:attr:`triangles` as corners ``(T, 3)`` (entries of ``face_indices``), for data
        kept per corner (texture coordinates): each triangle vertex's corner in its polygon,
        found by sorting the corners by (polygon, vertex) -- no second triangulation."""
        tri, owner = self.triangles
        key_face, key_vertex = self.corner_face, self.face_indices
        order = np.lexsort((key_vertex, key_face))          # corners by (polygon, vertex)
        sorted_face, sorted_vertex = key_face[order], key_vertex[order]
        span = np.int64(self.n_vertices) + 1
        keys = sorted_face * span + sorted_vertex
        want = np.repeat(owner, 3) * span + tri.ravel()
        # (a polygon that repeats a vertex: its first corner of that vertex)
        at = np.searchsorted(keys, want)
        return _readonly(order[at].reshape(-1, 3))

    def subset(self, faces: ArrayLike) -> Mesh:
        """The faces ``faces`` (indices) as a mesh of their own, with only the vertices they
        use (and their normals and texture coordinates); groups are dropped.

        Parameters
        ----------
        faces : array_like
            ``(k,)`` face indices (or a ``(F,)`` bool mask).
        """
        f = np.asarray(faces, np.int64)
        sizes = self.face_sizes[f]
        corners = (np.repeat(self.face_offsets[f], sizes) +
                   np.arange(int(sizes.sum())) - np.repeat(np.cumsum(sizes) - sizes, sizes))
        used, idx = np.unique(self.face_indices[corners], return_inverse=True)
        normals = self.normals_from_file[used] if self.normals_from_file is not None else None
        return Mesh.from_csr(self.vertices[used], idx.astype(np.int64),
                             np.concatenate([[0], np.cumsum(sizes)]), normals=normals,
                             name=self.name,
                             uv=self.uv[corners] if self.uv is not None else None,
                             colors=self.colors[used] if self.colors is not None else None,
                             face_colors=(self.face_colors[f] if self.face_colors is not None
                                          else None))

    def signed_volume(self) -> float:
        """Signed volume enclosed (divergence theorem); positive for outward orientation of
        a closed mesh."""
        tri, _ = self.triangles
        p = self.vertices[tri]
        return float(np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6.0)

    def center_of_mass(self, kind: str = "solid") -> NDArray[np.float64]:
        """Centre of mass ``(3,)`` of the solid a closed mesh bounds (``kind="solid"``, the
        tetrahedra from the origin to each triangle, with signed volumes as masses) or of
        its surface (``"surface"``, triangle centroids weighted by area).

        Parameters
        ----------
        kind : str
            ``"solid"`` (a closed mesh's volume) or ``"surface"``.
        """
        from ..masspoint import mesh_center_of_mass

        return mesh_center_of_mass(self.vertices[self.triangles[0]], kind)

    @property
    def total_area(self) -> float:
        return float(self.face_areas.sum())

    @cached_property
    def closed_and_oriented(self) -> bool:
        """Every edge shared by two faces traversing it in opposite directions (back faces
        of such a surface are never visible, so they can be culled)."""
        return is_closed_and_oriented(self.half_edges, self.n_vertices)

    def transformed(self, matrix: ArrayLike) -> Mesh:
        """A copy mapped by an affine 4x4 (or 3x3) matrix for column vectors. File normals
        follow by the inverse transpose; a mirroring matrix reverses the faces, so they stay
        front faces.

        Parameters
        ----------
        matrix : array_like
            ``(4, 4)`` affine or ``(3, 3)`` linear map, for column vectors.
        """
        m = affine_matrix(matrix)
        v = self.vertices @ m[:3, :3].T + m[:3, 3]
        normals = None
        if self.normals_from_file is not None:
            normals = self.normals_from_file @ np.linalg.inv(m[:3, :3])
        flip = np.linalg.det(m[:3, :3]) < 0
        analytic = self.analytic.transformed(m) if self.analytic is not None else None
        return self._replace(v, flip=flip, normals=normals, analytic=analytic)

    def flipped(self) -> Mesh:
        """The same mesh with every face's orientation reversed (file normals negated)."""
        normals = -self.normals_from_file if self.normals_from_file is not None else None
        analytic = self.analytic.flipped() if self.analytic is not None else None
        return self._replace(self.vertices, flip=True, normals=normals, analytic=analytic)

    def oriented(self) -> Mesh:
        """A copy with faces wound consistently (see :func:`glshade.geometry.merge.oriented`)."""
        from .merge import oriented

        return oriented(self)

    def _replace(self, vertices, flip=False, normals=None, analytic=None) -> Mesh:
        """A copy with new vertices; ``flip`` (True, or a mask per face) reverses faces."""
        idx = self.face_indices
        flip_face = np.broadcast_to(np.asarray(flip, bool), (self.n_faces,))
        if flip_face.any():
            # reverse each chosen face's order, keeping its first vertex first
            start = np.repeat(self.face_offsets[:-1], self.face_sizes)
            local = np.arange(len(idx)) - start
            rev = np.where(local == 0, 0, np.repeat(self.face_sizes, self.face_sizes) - local)
            rev = np.where(flip_face[self.corner_face], rev, local)
            idx = idx[start + rev]
            uv = self.uv[start + rev] if self.uv is not None else None
        else:
            uv = self.uv
        out = Mesh.from_csr(vertices, idx.copy(), self.face_offsets.copy(), normals=normals,
                            groups=self.groups, name=self.name, uv=uv, colors=self.colors,
                            face_colors=self.face_colors)
        out.analytic = analytic
        out.materials, out.material_groups = self.materials, self.material_groups
        return out

    @classmethod
    def from_trimesh(cls, tm, name: str | None = None, linear_colors: bool = False) -> Mesh:
        """From a ``trimesh.Trimesh`` or ``trimesh.Scene`` (the ``formats`` extra), with its
        texture coordinates, vertex and face colours, and its materials' colours, factors
        and maps as material parts (:attr:`materials`, described as plain data: ``Scene.add``
        draws each part with the material made from it).

        Parameters
        ----------
        tm : trimesh.Trimesh or trimesh.Scene
            The mesh (a scene's geometry is joined, each part a group).
        name : str or None
            The mesh's name (None: trimesh's).
        linear_colors : bool
            trimesh's colour bytes are linear (a glTF's ``COLOR_0``) rather than
            sRGB-encoded (as trimesh shows them and PLY files hold them).
        """
        from .trimesh_bridge import from_trimesh

        return from_trimesh(tm, name, linear_colors)

    def to_trimesh(self, image=None):
        """A ``trimesh.Trimesh`` of the triangulation (the ``formats`` extra), with the
        mesh's colours and texture coordinates
        (:func:`~glshade.geometry.trimesh_bridge.to_trimesh`).

        Parameters
        ----------
        image : PIL.Image.Image or None
            The texture image its texture visual shows (a material's map).
        """
        from .trimesh_bridge import to_trimesh

        return to_trimesh(self, image)

    def split_creases(self, angle_deg: float = 30.0) -> Mesh:
        """Duplicate vertices along edges sharper than ``angle_deg``, so smooth shading
        keeps creases (see :func:`glshade.geometry.merge.split_creases`).

        Parameters
        ----------
        angle_deg : float
            Edges whose faces meet at more than this many degrees stay sharp.
        """
        from .merge import split_creases

        return split_creases(self, angle_deg)

    def weld(self, tolerance: float | None = None) -> Mesh:
        """Merge vertices closer than ``tolerance`` (see :func:`glshade.geometry.merge.weld`).

        Parameters
        ----------
        tolerance : float or None
            The distance in scene units under which vertices merge (None: a millionth of the
            bounding box's diagonal).
        """
        from .merge import weld

        return weld(self, tolerance)
