"""GPU copies of one mesh: vertex and index buffers, the triangle-to-polygon table, and a
vertex array per program. Uploaded once; drawing with another camera touches none of it."""

from __future__ import annotations

from typing import Any, NamedTuple

import weakref

import numpy as np

from ..errors import GlshadeError
from ..geometry.transforms import box_corners, outside_frustum
from ..geometry.mesh import Mesh
from ..modes import ShadingMode
from ..octree import CHUNK_SIZE, CHUNKED_FROM
from .base import GLResource

__all__ = ["GpuMesh", "drawable_normals", "gpu_bytes", "Chunks", "UPLOAD_BYTES",
           "POLYGON_ROW_WIDTH"]

#: the most host memory an upload converts at once (float32 rows made slice by slice and
#: written into a reserved buffer): a 10M-triangle mesh needs no whole float32 copy
UPLOAD_BYTES = 64 << 20
#: texels a row of a big mesh's polygon tables (shaders/include/polygon_fetch.glsl)
POLYGON_ROW_WIDTH = 4096

def drawable_normals(mesh: Mesh) -> np.ndarray:
    """Vertex normals for the GPU, never zero or NaN (normalize(0) is NaN in GLSL: black
    pixels): file normals where usable, computed ones elsewhere, +z for a vertex that only
    degenerate faces use (their triangles cover no pixel).

    Parameters
    ----------
    mesh : Mesh
        The mesh.
    """
    n = mesh.vertex_normals
    if mesh.normals_from_file is not None:
        f = mesh.normals_from_file
        usable = np.isfinite(f).all(axis=1) & (np.abs(f).sum(axis=1) > 0)
        n = np.where(usable[:, None], f, n)
    zero = np.abs(n).sum(axis=1) == 0
    return np.where(zero[:, None], np.array([0.0, 0.0, 1.0]), n)


class Chunks(NamedTuple):
    """A big mesh's spatial chunks: chunk k is triangles ``starts[k]:starts[k + 1]`` of
    the uploaded order; ``corners`` ``(C, 8, 3)`` each chunk's box, model space.

    Parameters
    ----------
    starts : ndarray
        ``(C + 1,)`` the chunks' first triangles, and the count.
    corners : ndarray
        ``(C, 8, 3)`` each chunk's box corners.
    """

    starts: np.ndarray
    corners: np.ndarray

    @classmethod
    def of(cls, starts: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> Chunks:
        """The chunks of elements in chunk order whose own extents are ``lo`` and ``hi``
        ``(N, 3)``: each chunk's box the extent of its elements'.

        Parameters
        ----------
        starts : ndarray
            ``(C + 1,)`` the chunks' first elements, and the count.
        lo, hi : ndarray
            ``(N, 3)`` each element's smallest and largest coordinates, in chunk order.
        """
        boxes = np.stack([np.minimum.reduceat(lo, starts[:-1]),
                          np.maximum.reduceat(hi, starts[:-1])], 1)        # (C, 2, 3)
        return cls(starts, box_corners(boxes))

    def in_view(self, view_proj: np.ndarray) -> tuple[list[tuple[int, int]], int]:
        """The draw calls a view needs, ``(first, count)`` each, and how many chunks it
        skips: those whose box lies wholly outside the view (``view_proj``: model to clip).

        Parameters
        ----------
        view_proj : ndarray
            ``(4, 4)`` model space to clip space.
        """
        hidden = outside_frustum(view_proj, self.corners)
        return self.ranges(~hidden), int(hidden.sum())

    def ranges(self, visible: np.ndarray) -> list[tuple[int, int]]:
        """``(first triangle, count)`` of each run of consecutive ``visible`` chunks (one
        draw call a run).

        Parameters
        ----------
        visible : ndarray
            ``(C,)`` bool.
        """
        edges = np.diff(np.r_[0, visible.astype(np.int8), 0])
        first, stop = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
        return [(int(self.starts[a]), int(self.starts[b] - self.starts[a]))
                for a, b in zip(first, stop)]


def _layout(mesh: Mesh):
    """What a GpuMesh uploads, without GL: ``(mesh, source, uv, color, tri, owner)`` -- the
    mesh as drawn (a two-sided wall's sides split), the mesh vertex each GPU vertex copies
    (None: one to one; a texture seam or a polygon's own colour splits vertices by their
    (vertex, uv, colour) rows), its uv and its RGBA colour (None where the mesh has none),
    the triangles over GPU vertices and each triangle's polygon."""
    if len(mesh.folded_vertices) and mesh.normals_from_file is None:
        # a two-sided wall: give each side its own vertices, so each has its own normal
        mesh = mesh.split_creases(179.0)
    tri, owner = mesh.triangles
    source: np.ndarray | None = None
    uv: np.ndarray | None = None
    color: np.ndarray | None = None
    if mesh.uv is not None or mesh.face_colors is not None:
        parts: list[np.ndarray] = [mesh.face_indices[:, None].astype(np.float64)]
        if mesh.uv is not None:
            parts.append(mesh.uv)
        if mesh.corner_colors is not None and mesh.face_colors is not None:
            parts.append(mesh.corner_colors)
        unique, corner_vertex = np.unique(np.hstack(parts), axis=0, return_inverse=True)
        source = unique[:, 0].astype(np.int64)
        uv = unique[:, 1:3] if mesh.uv is not None else None
        color = unique[:, -4:] if mesh.face_colors is not None else None
        tri = corner_vertex.ravel()[mesh.corner_triangles]
    if mesh.colors is not None and color is None:
        color = mesh.colors if source is None else mesh.colors[source]
    return mesh, source, uv, color, tri, owner


def uv_tangents(positions: np.ndarray, normals: np.ndarray, uv: np.ndarray,
                tri: np.ndarray) -> np.ndarray:
    """``(V, 4)`` a tangent frame a vertex for tangent-space normal maps: the direction of
    increasing u on the surface (the triangles' uv derivatives summed at each vertex, made
    perpendicular to its normal), and in w the handedness (+1 or -1: the bitangent is
    w N x T, toward increasing v). A vertex whose triangles' uv are degenerate gets any
    tangent perpendicular to its normal.

    Parameters
    ----------
    positions, normals : ndarray
        ``(V, 3)`` each vertex's position and unit normal.
    uv : ndarray
        ``(V, 2)`` each vertex's texture coordinate.
    tri : ndarray
        ``(T, 3)`` triangles over the vertices.
    """
    tangent, bitangent = triangle_frames(positions[tri], uv[tri])
    n_v = len(positions)
    sums = np.zeros((2, n_v, 3))
    for k in range(3):  # (each corner of every triangle at once)
        for axis in range(3):
            sums[0, :, axis] += np.bincount(tri[:, k], tangent[:, axis], n_v)
            sums[1, :, axis] += np.bincount(tri[:, k], bitangent[:, axis], n_v)
    return _orthonormal_frame(normals, *sums)


def polygon_tangents(mesh: Mesh) -> np.ndarray:
    """``(F, 4)`` each polygon's tangent frame (its triangles' uv derivatives summed, made
    perpendicular to its Newell normal; w the handedness), for flat shading's normal map.

    Parameters
    ----------
    mesh : Mesh
        A mesh with texture coordinates.
    """
    tri, owner = mesh.triangles
    assert mesh.uv is not None
    tangent, bitangent = triangle_frames(mesh.vertices[tri], mesh.uv[mesh.corner_triangles])
    sums = np.stack([np.stack([np.bincount(owner, f[:, axis], mesh.n_faces)
                               for axis in range(3)], 1) for f in (tangent, bitangent)])
    return _orthonormal_frame(mesh.face_normals, *sums)


def triangle_frames(p: np.ndarray, t: np.ndarray):
    """Each triangle's dP/du and dP/dv (``(T, 3)`` each) from its corners ``p`` and uv
    ``t``; zero where its uv are degenerate (the rasterizer's tangents and the path
    tracer's are made from these).

    Parameters
    ----------
    p : ndarray
        ``(T, 3, 3)`` the triangles' corners.
    t : ndarray
        ``(T, 3, 2)`` their texture coordinates.
    """
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    d1, d2 = t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]
    det = d1[:, 0] * d2[:, 1] - d2[:, 0] * d1[:, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(np.abs(det) > 1e-20, 1.0 / det, 0.0)[:, None]
    return (e1 * d2[:, 1:2] - e2 * d1[:, 1:2]) * r, (e2 * d1[:, 0:1] - e1 * d2[:, 0:1]) * r


def _orthonormal_frame(normals: np.ndarray, tv: np.ndarray, bv: np.ndarray) -> np.ndarray:
    """``(N, 4)``: ``tv`` made unit and perpendicular to ``normals`` (any such direction
    where it vanishes), and the handedness of (N, T, ``bv``)."""
    tv = tv - normals * np.einsum("ij,ij->i", normals, tv)[:, None]
    length = np.linalg.norm(tv, axis=1)
    # (no uv gradient there: any direction in the tangent plane)
    other = np.where(np.abs(normals[:, 0:1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    fallback = np.cross(normals, other)
    fallback /= np.maximum(np.linalg.norm(fallback, axis=1, keepdims=True), 1e-300)
    tv = np.where((length > 1e-20)[:, None], tv / np.maximum(length, 1e-300)[:, None],
                  fallback)
    hand = np.where(np.einsum("ij,ij->i", np.cross(normals, tv), bv) < 0, -1.0, 1.0)
    return np.column_stack([tv, hand])


def gpu_bytes(mesh: Mesh) -> int:
    """The bytes a mesh's GPU copy takes for the smooth modes' colour draws (what Phong
    reads): float32 position and normal (and uv with a tangent frame, and RGBA colour) a GPU
    vertex, three uint32 indices a triangle. Flat draws and draws with polygon ids add
    per-corner copies (36 to 84 bytes a corner, made on their first use).

    Parameters
    ----------
    mesh : Mesh
        The mesh.
    """
    drawn, source, uv, color, tri, _ = _layout(mesh)
    n = drawn.n_vertices if source is None else len(source)
    # (uv brings a tangent frame: 8 + 16 bytes)
    return n * (24 + 24 * (uv is not None) + 16 * (color is not None)) + 12 * len(tri)


class GpuMesh(GLResource):
    """Buffers for one Mesh in one RenderContext; ``release()`` frees them all.

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    mesh : Mesh
        The mesh uploaded.
    """

    def __init__(self, context, mesh: Mesh):
        super().__init__(context)
        self._vaos: dict[Any, Any] = {}
        self._flat_vbo: Any = None
        # (colour array, vbo, ibo, {program id: vao}) of the radiosity mode
        self._colors: Any = None
        try:
            self._upload(mesh)
        except BaseException:
            self.release()  # nothing half-made stays registered with the context
            raise

    def _upload(self, mesh: Mesh) -> None:
        self._mesh = weakref.ref(mesh)  # the renderer's cache must not keep meshes alive
        mesh, source, uv, color, tri, owner = _layout(mesh)
        if len(tri) == 0:
            raise GlshadeError("a GpuMesh needs at least one triangle (the renderer skips "
                               "empty meshes)")
        self.n_triangles = len(tri)
        self.n_polygons = mesh.n_faces
        self.closed = mesh.closed_and_oriented
        self._corners = np.vstack([box_corners(mesh.bounds).T, np.ones(8)])  # (homogeneous)
        #: whether the vertices carry texture coordinates (``in_uv``)
        self.textured = mesh.uv is not None
        #: whether the vertices carry colours (``in_color``, RGBA)
        self.colored = color is not None
        columns = [mesh.vertices, drawable_normals(mesh)]
        if source is not None:
            columns = [c[source] for c in columns]
        columns += [c for c in (uv, color) if c is not None]
        if uv is not None:  # (a tangent frame a vertex, for normal maps: in_tangent)
            columns.append(uv_tangents(columns[0], columns[1], uv, tri))
        #: a big mesh's spatial chunks (None: drawn whole), in the order uploaded
        self.chunks: Chunks | None = None
        self._order: np.ndarray | None = None
        if len(tri) >= CHUNKED_FROM:
            self._order, self.chunks = _chunked(columns[0], tri)
            tri, owner = tri[self._order], owner[self._order]
        self._columns = columns
        ctx = self.context.ctx
        self.vbo = self._keep(_upload_rows(ctx, len(columns[0]), self._vertex_rows))
        self.ibo = self._keep(_upload_rows(ctx, len(tri),
                                           lambda rows: tri[rows].astype("u4")))
        # (kept for the draws with polygon ids, made on their first use)
        self._indexed = (tri, owner)
        self._per_corner: Any = None
        self._tables: list[Any] = [None, None]  # (a big mesh's: polygon_tables)

    def _vertex_rows(self, rows) -> np.ndarray:
        """float32 position, normal (and uv, colour) of GPU vertices ``rows`` (a slice or
        indices)."""
        return np.hstack([c[rows] for c in self._columns]).astype("f4")

    @property
    def nbytes(self) -> int:
        """The bytes its buffers and tables take on the GPU now (per-corner copies and a
        big mesh's polygon tables included once made)."""
        import moderngl

        return sum(o.size if isinstance(o, moderngl.Buffer) else
                   o.width * o.height * o.components * 4 for o in self._objects
                   if isinstance(o, (moderngl.Buffer, moderngl.Texture)))

    def triangles_in_order(self, mesh: Mesh) -> tuple[np.ndarray, np.ndarray]:
        """``mesh.triangles`` in the order uploaded (a big mesh's by chunk).

        Parameters
        ----------
        mesh : Mesh
            The mesh this GpuMesh copies.
        """
        tri, owner = mesh.triangles
        if self._order is not None:
            return tri[self._order], owner[self._order]
        return tri, owner

    @property
    def corners(self) -> np.ndarray:
        """``(4, 8)`` the mesh's bounding-box corners, homogeneous columns (model space)."""
        return self._corners

    def beyond(self, model_view: np.ndarray, near: float) -> bool:
        """Whether the mesh lies wholly beyond a camera's near plane (``model_view``: model
        to view space), so that the camera sees a closed mesh from outside -- where culling
        its back faces cannot change the picture.

        Parameters
        ----------
        model_view : ndarray
            ``(4, 4)`` model to view space.
        near : float
            The near plane's distance.
        """
        return bool((model_view[2] @ self._corners < -near).all())

    def _flat_buffer(self):
        """Per-corner copies with the polygon's Newell normal and centroid (flat mode) -- and
        its colour, the mean of its corners' --, and each corner's polygon id."""
        if self._flat_vbo is None:
            m = self._mesh()
            if m is None:
                raise GlshadeError("the mesh of this GpuMesh no longer exists")
            tri, owner = self.triangles_in_order(m)
            corner_uv = m.corner_triangles if self.textured else None
            if corner_uv is not None and self._order is not None:
                corner_uv = corner_uv[self._order]

            colors = m.polygon_colors if self.colored else None
            centre_uv = face_tangent = None
            if m.uv is not None:  # (each polygon's mean uv: where flat reads glTF's maps)
                centre_uv = np.add.reduceat(m.uv, m.face_offsets[:-1], axis=0) / \
                    m.face_sizes[:, None]
                face_tangent = polygon_tangents(m)

            def rows(sl):
                corners, face = tri[sl].ravel(), np.repeat(owner[sl], 3)
                parts = [m.vertices[corners], m.face_normals[face], m.face_centroids[face]]
                if corner_uv is not None:
                    parts.append(m.uv[corner_uv[sl].ravel()])
                    parts.append(centre_uv[face])
                if colors is not None:  # (uniform shading: the polygon's one colour)
                    parts.append(colors[face])
                if face_tangent is not None:
                    parts.append(face_tangent[face])
                return np.hstack(parts).astype("f4")

            ctx = self.context.ctx
            self._flat_vbo = (self._keep(_upload_rows(ctx, len(tri), rows)),
                              self._keep(_upload_rows(ctx, len(tri),
                                                      lambda sl: np.repeat(owner[sl], 3)
                                                      .astype("i4"))))
        return self._flat_vbo

    def _corner_buffers(self):
        """The smooth modes' vertices copied per triangle corner, and each corner's polygon
        id: what a draw with polygon ids reads (polygon_id.glsl), no vertex shared."""
        if self._per_corner is None:
            tri, owner = self._indexed
            self._per_corner = tuple(self._keep(b) for b in self._corner_copies(
                self._vertex_rows, tri, owner))
        return self._per_corner

    def _corner_copies(self, vertex_rows, tri: np.ndarray, polygon: np.ndarray):
        """Buffers of the vertices (``vertex_rows(indices)``: float32 rows) copied to every
        corner of ``tri`` (T, 3), and each corner's polygon id from ``polygon`` (T,); the
        caller owns them."""
        ctx = self.context.ctx
        return (_upload_rows(ctx, len(tri), lambda sl: vertex_rows(tri[sl].ravel())),
                _upload_rows(ctx, len(tri), lambda sl: np.repeat(polygon[sl], 3)
                             .astype("i4")))

    def color_array(self, program, colors: np.ndarray):
        """The VAO of the ``radiosity`` mode: positions, normals and ``colors`` (V, 3) of the
        mesh as given (never split), cached for the same colour array.

        Parameters
        ----------
        program : moderngl.Program
            The radiosity mode's program.
        colors : ndarray
            ``(V, 3)`` float32 a vertex.
        """
        self._check()
        if self._colors is None or self._colors[0] is not colors:
            self._drop_colors()
            m = self._mesh()
            if m is None:
                raise GlshadeError("the mesh of this GpuMesh no longer exists")
            data = np.hstack([m.vertices, drawable_normals(m), colors]).astype("f4")
            tri, owner = self.triangles_in_order(m)
            ctx = self.context.ctx
            # (indexed; per corner with polygon ids made for the first draw that writes them)
            self._colors = (colors, [ctx.buffer(data.tobytes()),
                                     ctx.buffer(tri.astype("u4").tobytes())], {},
                            (data, tri, owner))
        _, buffers, vaos, (data, tri, owner) = self._colors
        vao = vaos.get(id(program))
        if vao is None:
            names = [n for n in ("in_position", "in_normal", "in_color") if n in program]
            fmt = " ".join("3f" if n in names else "12x"
                           for n in ("in_position", "in_normal", "in_color"))
            ctx = self.context.ctx
            if "in_polygon" in program:
                if len(buffers) == 2:
                    buffers += self._corner_copies(lambda rows: data[rows], tri, owner)
                vao = ctx.vertex_array(program, [(buffers[2], fmt, *names),
                                                 (buffers[3], "i", "in_polygon")])
            else:
                vao = ctx.vertex_array(program, [(buffers[0], fmt, *names)], buffers[1], 4)
            vaos[id(program)] = vao
        return vao

    def _drop_colors(self) -> None:
        if self._colors is not None:
            _, buffers, vaos, _ = self._colors
            for vao in vaos.values():
                vao.release()
            for buf in buffers:
                buf.release()
            self._colors = None

    def edge_array(self, program):
        """The VAO of the mesh's polygon edges (each polygon's boundary, never its
        triangulation's diagonals) as lines, for ``edges.vert``; made on first use. Each
        end carries the unit normals of the edge's two sides -- the planes of the triangles
        drawn beside it (``Mesh.edge_side_triangles``; a polygon that is not planar is not
        its Newell plane there) -- which ``edges.frag`` recognises in the depth buffer.

        Parameters
        ----------
        program : moderngl.Program
            The edges' program.
        """
        self._check()
        key = ("edges", id(program))
        vao = self._vaos.get(key)
        if vao is None:
            m = self._mesh()
            if m is None:
                raise GlshadeError("the mesh of this GpuMesh no longer exists")
            ctx = self.context.ctx
            ends = m.vertices[m.edges]                                  # (E, 2, 3)
            planes = m.edge_side_normals.reshape(-1, 1, 6)              # (E, 1, 6)
            data = np.concatenate([ends, np.broadcast_to(planes, (len(ends), 2, 6))], -1)
            vbo = self._keep(ctx.buffer(data.astype("f4").tobytes()))
            names = [n for n in ("in_position", "in_normal_a", "in_normal_b") if n in program]
            fmt = " ".join(f if n in names else "12x" for n, f in
                           (("in_position", "3f"), ("in_normal_a", "3f"),
                            ("in_normal_b", "3f")))
            vao = self._vaos[key] = ctx.vertex_array(program, [(vbo, fmt, *names)])
        return vao

    def vertex_array(self, program, mode: ShadingMode):
        """The VAO binding this mesh's buffers to ``program`` (cached).

        Parameters
        ----------
        program : moderngl.Program
            The program.
        mode : ShadingMode
            Its shading mode (flat draws use the polygon's corners as their own vertices).
        """
        self._check()
        key = id(program)
        vao = self._vaos.get(key)
        if vao is None:
            ctx = self.context.ctx
            ids = None
            if "in_face_normal" in program:  # (flat: a corner copy a polygon's corner)
                layout = [("in_position", "3f"), ("in_face_normal", "3f"),
                          ("in_face_centroid", "3f")]
                (buffer, ids), ibo = self._flat_buffer(), None
            elif "in_polygon" in program:  # (polygon ids: per corner)
                layout = [("in_position", "3f"), ("in_normal", "3f")]
                (buffer, ids), ibo = self._corner_buffers(), None
            else:
                layout = [("in_position", "3f"), ("in_normal", "3f")]
                buffer, ibo = self.vbo, self.ibo
            if self.textured:
                layout.append(("in_uv", "2f"))
                if "in_face_normal" in program:  # (flat's copies: the polygon's mean uv too)
                    layout.append(("in_face_uv", "2f"))
            if self.colored:
                layout.append(("in_color", "4f"))
            if self.textured:  # (a tangent frame: a vertex's, or flat's polygon's)
                layout.append(("in_face_tangent" if "in_face_normal" in program else
                               "in_tangent", "4f"))
            names = [n for n, _ in layout if n in program]
            fmt = " ".join(f if n in names else f"{4 * int(f[0])}x" for n, f in layout)
            content = [(buffer, fmt, *names)]
            if "in_polygon" in program:
                content.append((ids, "i", "in_polygon"))
            vao = ctx.vertex_array(program, content, ibo, 4)
            self._vaos[key] = vao
        return vao

    def polygon_tables(self, planes: bool):
        """A big mesh's tables for draws over its shared vertices (polygon_fetch.glsl):
        each triangle's polygon (int32, in the order uploaded), and with ``planes`` each
        polygon's Newell normal and centroid (two float32 texels) -- POLYGON_ROW_WIDTH
        texels a row; made on first use (4 bytes a triangle, 32 a polygon).

        Parameters
        ----------
        planes : bool
            Also the polygons' normals and centroids (a flat draw's).
        """
        self._check()
        ctx = self.context.ctx
        if self._tables[0] is None:
            self._tables[0] = self._keep(_table(ctx, self._indexed[1].astype(np.int32), 1,
                                                "i4"))
        if planes and self._tables[1] is None:
            m = self._mesh()
            if m is None:
                raise GlshadeError("the mesh of this GpuMesh no longer exists")
            rows = np.zeros((m.n_faces, 2, 4), np.float32)
            rows[:, 0, :3], rows[:, 1, :3], rows[:, 1, 3] = m.face_normals, \
                m.face_centroids, 1.0
            self._tables[1] = self._keep(_table(ctx, rows.reshape(-1, 4), 4, "f4"))
        return self._tables[0], self._tables[1]

    def _release_extra(self) -> None:
        self._drop_colors()
        self._columns = []
        for vao in self._vaos.values():
            vao.release()
        self._vaos.clear()


def _chunked(positions: np.ndarray, tri: np.ndarray) -> tuple[np.ndarray, Chunks]:
    """The triangles' order by octree chunk (their centroids' cells,
    :func:`glshade.octree.point_chunks`) and the chunks' boxes (their triangles' corners'
    extent, model space)."""
    from ..octree import point_chunks

    centroids = (positions[tri[:, 0]] + positions[tri[:, 1]] + positions[tri[:, 2]]) / 3
    order, starts = point_chunks(centroids, CHUNK_SIZE)
    a, b, c = (positions[tri[order, k]] for k in range(3))
    return order, Chunks.of(starts, np.minimum(np.minimum(a, b), c),
                            np.maximum(np.maximum(a, b), c))


def _upload_rows(ctx, n: int, rows):
    """A buffer of ``n`` rows, each slice's bytes made by ``rows(slice)`` (an array) and
    written in turn: at most about UPLOAD_BYTES of them converted at once."""
    first = np.ascontiguousarray(rows(slice(0, min(n, 1))))
    row_bytes = first.nbytes // max(min(n, 1), 1)
    buffer = ctx.buffer(reserve=max(n * row_bytes, 1))
    step = max(1, UPLOAD_BYTES // max(row_bytes, 1))
    for start in range(0, n, step):
        buffer.write(np.ascontiguousarray(rows(slice(start, min(n, start + step)))).tobytes(),
                     offset=start * row_bytes)
    return buffer


def _table(ctx, values: np.ndarray, components: int, dtype: str):
    """A texture holding ``values`` (``(N,)`` or ``(N, components)``) POLYGON_ROW_WIDTH texels
    a row, read by texelFetch (nearest, never filtered)."""
    import moderngl

    flat = values.reshape(len(values), -1)
    height = max(1, -(-len(flat) // POLYGON_ROW_WIDTH))
    data = np.zeros((height * POLYGON_ROW_WIDTH, components), flat.dtype)
    data[:len(flat)] = flat
    texture = ctx.texture((POLYGON_ROW_WIDTH, height), components, data.tobytes(), dtype=dtype)
    texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
    return texture

