"""Boundary representation: the winged-edge structure and Euler's formula.

Every edge stores its two vertices ``P`` (previous) and ``N`` (next), its two faces
(``left``: the face whose loop runs P -> N, counter-clockwise seen from outside; ``right``:
the face whose loop runs N -> P) and its four wings (notes, Figure 20.5)::

    P_L: the edge before it in the left face's loop (meets it at P)
    N_L: the edge after it in the left face's loop (meets it at N)
    P_R: the edge after it in the right face's loop (meets it at P)
    N_R: the edge before it in the right face's loop (meets it at N)

Vertices and faces each point to one incident edge. A face may have inner loops (holes),
wound the other way so that the face stays on their left. The structure is built with
array operations (sorting edge keys); queries walk it.

Euler's formula for solids bounded by 2-manifolds: ``V - E + F - H = 2 (C - G)`` with H
the inner loops of faces, C the connected components and G the genus; an open surface with
B boundary loops satisfies ``V - E + F - H + B = 2 (C - G)``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import GeometryError, TopologyError
from ..geometry.edges import edge_groups
from ..geometry.graph import component_labels as _components
from ..geometry.graph import cycle_labels as _cycle_labels
from ..geometry.mesh import Mesh
from .topology import EulerReport, TopologyReport

__all__ = ["WingedEdge"]

Int = NDArray[np.int64]


class WingedEdge:
    """A winged-edge B-Rep of a polygonal solid or surface.

    Build with :meth:`from_mesh` or :meth:`from_faces` (faces with holes). Arrays (all
    int64, -1 for "none"):

    ``edge_vertices (E, 2)`` P and N; ``edge_faces (E, 2)`` left and right; ``edge_wings
    (E, 4)`` P_L, P_R, N_L, N_R; ``vertex_edge (V,)``; ``face_edge (F,)`` (an edge of the
    outer loop); ``loop_face (L,)``, ``face_loops`` (outer loop first).

    Parameters
    ----------
    vertices : array_like
        ``(V, 3)`` positions.
    loops : sequence of sequence of int or None
        Each loop's vertices in order (outer loops counter-clockwise, holes clockwise).
    loop_face : array_like
        ``(L,)`` the face of each loop.
    n_faces : int
        The faces.
    strict : bool
        Raise on a non-manifold or inconsistent input (else collect the problems).
    """

    def __init__(self, vertices, loops: Sequence[Sequence[int]] | None, loop_face,
                 n_faces: int, *, strict: bool = True, _csr=None):
        self.vertices = np.asarray(vertices, dtype=np.float64)
        nv = len(self.vertices)
        if _csr is not None:
            idx, off = _csr
        elif loops is None:
            raise TopologyError("a WingedEdge needs loops (or the CSR arrays)")
        else:
            sizes = np.fromiter((len(lp) for lp in loops), np.int64, len(loops))
            off = np.zeros(len(loops) + 1, np.int64)
            np.cumsum(sizes, out=off[1:])
            idx = np.fromiter((i for lp in loops for i in lp), np.int64, int(off[-1]))
        sizes = np.diff(off)
        if (sizes < 3).any():
            raise GeometryError(f"loop {int(np.flatnonzero(sizes < 3)[0])} has fewer than 3 "
                                "vertices")
        if len(idx) and (idx.min() < 0 or idx.max() >= nv):
            raise GeometryError("a loop refers to a vertex that does not exist")
        self.loop_face = np.asarray(loop_face, np.int64)
        self.n_faces = int(n_faces)
        n_loops = len(sizes)
        # half-edges, one per loop corner
        h_loop = np.repeat(np.arange(n_loops), sizes)
        nxt = np.arange(1, len(idx) + 1)
        nxt[off[1:] - 1] = off[:-1]
        prv = np.arange(-1, len(idx) - 1)
        prv[off[:-1]] = off[1:] - 1
        h_from, h_to = idx, idx[nxt]
        h_face = self.loop_face[h_loop]
        self._h = {"from": h_from, "to": h_to, "next": nxt, "prev": prv, "face": h_face,
                   "loop": h_loop}
        self.loop_offsets = off

        # pair half-edges through the undirected key
        groups = edge_groups(h_from, h_to, nv)
        h0, h1 = groups.pairs()
        same = h_from[h0] == h_from[h1]
        self.report = report = self._report(groups, idx, off, h0, h1, same)
        self._edges(groups, h0, h1, same, n_loops)
        # (a mis-oriented edge breaks the fans at its ends: those are reported with it)
        on_misoriented = {v for a, b, _ in report.misoriented_edges for v in (a, b)}
        report.non_manifold_vertices = [v for v in self._pinched_vertices()
                                        if v not in on_misoriented]
        if strict and not report.ok:
            raise TopologyError(report.message())

    def _report(self, groups, idx, off, h0, h1, same) -> TopologyReport:
        """What is wrong with the surface, but for pinched vertices (found once the edges
        are linked): edges of more than two faces, mis-oriented pairs, isolated vertices,
        duplicate faces."""
        h_from, h_to, h_face = self._h["from"], self._h["to"], self._h["face"]
        order, start, count = groups.order, groups.start, groups.count
        report = TopologyReport()
        for e in np.flatnonzero(count > 2).tolist():
            hs = order[start[e]:start[e] + count[e]]
            report.non_manifold_edges.append((int(groups.lo[e]), int(groups.hi[e]),
                                              sorted(set(h_face[hs].tolist()))))
        for a, b in zip(h0[same].tolist(), h1[same].tolist()):
            report.misoriented_edges.append((int(h_from[a]), int(h_to[a]),
                                             [int(h_face[a]), int(h_face[b])]))
        used = np.zeros(len(self.vertices), bool)
        used[idx] = True
        report.isolated_vertices = np.flatnonzero(~used).tolist()
        report.duplicate_faces = self._duplicates(idx, off)
        return report

    def _edges(self, groups, h0, h1, same, n_loops: int) -> None:
        """The winged-edge records: one edge per undirected key, its first half-edge
        P -> N with the left face; wings, vertex and face edges, boundary half-edges."""
        h_from, h_to, h_face = self._h["from"], self._h["to"], self._h["face"]
        nxt, prv, off, nh = self._h["next"], self._h["prev"], self.loop_offsets, len(h_from)
        h_edge = groups.group
        first = groups.first
        twin = np.full(nh, -1, np.int64)
        ok_pair = ~same
        twin[h0[ok_pair]] = h1[ok_pair]
        twin[h1[ok_pair]] = h0[ok_pair]
        self._h["edge"], self._h["twin"] = h_edge, twin
        self.edge_half = first                       # the P -> N half-edge of each edge
        second = twin[first]
        self.edge_vertices = np.stack([h_from[first], h_to[first]], 1)
        self.edge_faces = np.stack([h_face[first], np.where(second >= 0, h_face[second], -1)], 1)
        h_e = np.where(second >= 0, second, 0)
        self.edge_wings = np.stack([
            h_edge[prv[first]],                                    # P_L
            np.where(second >= 0, h_edge[nxt[h_e]], -1),           # P_R
            h_edge[nxt[first]],                                    # N_L
            np.where(second >= 0, h_edge[prv[h_e]], -1),           # N_R
        ], 1)
        self.vertex_edge = np.full(len(self.vertices), -1, np.int64)
        self.vertex_edge[h_from[::-1]] = h_edge[::-1]  # any incident edge; the first wins
        self._vertex_half = np.full(len(self.vertices), -1, np.int64)
        self._vertex_half[h_from[::-1]] = np.arange(nh)[::-1]
        outer = np.full(self.n_faces, -1, np.int64)
        outer[self.loop_face[::-1]] = np.arange(n_loops)[::-1]  # the first loop of a face
        self.face_outer_loop = outer
        self.face_edge = np.where(outer >= 0, h_edge[off[np.maximum(outer, 0)]], -1)
        # boundary half-edges (no twin), and boundary loops through them
        self._boundary = np.flatnonzero(twin < 0)

    def _pinched_vertices(self) -> list:
        """Vertices where more than one fan of faces meets (the surface is pinched there):
        the rotation around them has several cycles, or several boundary gaps."""
        h = self._h
        if len(h["from"]) == 0:
            return []
        t = h["twin"]
        rot = np.where(t[h["prev"]] >= 0, t[h["prev"]], -1)  # next outgoing half-edge, CCW
        # close boundary fans onto themselves so that rot is a permutation: the fan's last
        # half-edge points back to its first (found by walking clockwise from boundaries)
        last = np.flatnonzero(rot < 0)
        starts = np.flatnonzero(t < 0)  # no clockwise neighbour: a fan starts here
        start_of_vertex = np.full(self.n_vertices, -1, np.int64)
        start_of_vertex[h["from"][starts]] = starts
        rot = rot.copy()
        rot[last] = start_of_vertex[h["from"][last]]
        rot = np.where(rot < 0, np.arange(len(rot)), rot)
        label = _cycle_labels(rot)
        pairs = np.unique(h["from"] * len(label) + label)  # (vertex, fan) pairs
        fans = np.bincount(pairs // len(label), minlength=self.n_vertices)
        gaps = np.bincount(h["from"][starts], minlength=self.n_vertices)
        return np.flatnonzero((fans > 1) | (gaps > 1)).tolist()

    # ------------------------------------------------------------------ builders
    @staticmethod
    def _duplicates(idx: Int, off: Int) -> list:
        sizes = np.diff(off)
        out = []
        for k in np.unique(sizes).tolist():
            ids = np.flatnonzero(sizes == k)
            rows = np.ascontiguousarray(np.sort(idx[off[ids][:, None] + np.arange(k)], axis=1))
            keys = rows.view(np.dtype((np.void, 8 * k))).ravel()
            _, first, inverse, counts = np.unique(keys, return_index=True,
                                                  return_inverse=True, return_counts=True)
            dup = counts[inverse.ravel()] > 1
            for i in np.flatnonzero(dup & (np.arange(len(ids)) != first[inverse.ravel()])):
                out.append((int(ids[first[inverse.ravel()[i]]]), int(ids[i])))
        return out

    @classmethod
    def from_mesh(cls, mesh: Mesh, *, strict: bool = True) -> WingedEdge:
        """The winged-edge structure of a polygon mesh (one loop per face). With
        ``strict=False`` problems are collected in ``.report`` instead of raised; a surface
        whose faces are merely wound inconsistently is then built from
        :meth:`Mesh.oriented` (its topology -- closed, manifold, boundary loops -- is the
        same) and reported as not oriented.

        Parameters
        ----------
        mesh : Mesh
            The polygons.
        strict : bool
            Raise on a problem (else collect them in ``problems``).
        """
        w = cls(mesh.vertices, None, np.arange(mesh.n_faces), mesh.n_faces, strict=strict,
                _csr=(mesh.face_indices, mesh.face_offsets))
        if strict or not w.report.misoriented_edges or w.report.non_manifold_edges:
            return w
        try:
            fixed = mesh.oriented()
        except TopologyError:
            return w  # one-sided: no consistent winding exists
        out = cls(fixed.vertices, None, np.arange(fixed.n_faces), fixed.n_faces,
                  strict=False, _csr=(fixed.face_indices, fixed.face_offsets))
        out.report.misoriented_edges = w.report.misoriented_edges
        out.report.fixable_orientation = True
        return out

    @classmethod
    def from_faces(cls, vertices: ArrayLike, faces: Sequence, *, strict: bool = True
                   ) -> WingedEdge:
        """Faces with holes: each face is a list of loops, the outer loop first
        (counter-clockwise seen from outside), then its inner loops (clockwise).

        Parameters
        ----------
        vertices : array_like
            ``(V, 3)`` positions.
        faces : sequence
            Each face a list of loops (vertex lists), the outer loop first.
        strict : bool
            Raise on a problem (else collect them).
        """
        loops, owner = [], []
        for f, face in enumerate(faces):
            if len(face) == 0:
                raise GeometryError(f"face {f} has no loops")
            if np.ndim(face[0]) == 0:  # a plain polygon
                face = [face]
            for loop in face:
                loops.append(list(loop))
                owner.append(f)
        return cls(vertices, loops, owner, len(faces), strict=strict)

    # ------------------------------------------------------------------ counts
    @property
    def n_vertices(self) -> int:
        return len(self.vertices)

    @property
    def n_edges(self) -> int:
        return len(self.edge_vertices)

    @property
    def n_loops(self) -> int:
        return len(self.loop_face)

    @property
    def is_closed(self) -> bool:
        return len(self._boundary) == 0

    @property
    def is_manifold(self) -> bool:
        return not (self.report.non_manifold_edges or self.report.non_manifold_vertices)

    @property
    def is_oriented(self) -> bool:
        return not self.report.misoriented_edges

    def boundary_loops(self) -> list[list[int]]:
        """Boundary loops as vertex lists, each running around the hole in the surface."""
        b = self._boundary
        if len(b) == 0:
            return []
        h = self._h
        # the boundary continues from a half-edge's start vertex, reversed: b -> a -> ...
        start_at = np.full(self.n_vertices, -1, np.int64)
        start_at[h["to"][b]] = np.arange(len(b))
        nxt = start_at[h["from"][b]]
        if (nxt < 0).any():
            nxt = np.where(nxt < 0, np.arange(len(b)), nxt)
        label = _cycle_labels(nxt)
        loops = []
        for lab in np.unique(label).tolist():
            members = np.flatnonzero(label == lab)
            cur, seen = int(members[0]), []
            for _ in range(len(members)):
                seen.append(int(h["to"][b[cur]]))
                cur = int(nxt[cur])
            loops.append(seen)
        return loops

    def components(self) -> Int:
        """Component label of each vertex (isolated vertices are components of their own).
        Vertices are connected through edges, and through faces: a hole's loop belongs to
        the same component as its face's outer loop."""
        ev = self.edge_vertices
        loop_vertex = self._h["from"][self.loop_offsets[:-1]]
        outer_vertex = loop_vertex[self.face_outer_loop[self.loop_face]]
        return _components(self.n_vertices, np.r_[ev[:, 0], loop_vertex],
                           np.r_[ev[:, 1], outer_vertex])

    def euler(self) -> EulerReport:
        """V, E, F, H, C, G (per component from the formula, checked to be a non-negative
        integer), boundary loops B, and whether the surface is closed, manifold, oriented."""
        comp = self.components()
        used = np.zeros(self.n_vertices, bool)
        used[self._h["from"]] = True
        labels, inverse = np.unique(comp[used], return_inverse=True)
        c = len(labels)
        vert_c = np.bincount(inverse, minlength=c)
        edge_c = np.bincount(np.searchsorted(labels, comp[self.edge_vertices[:, 0]]),
                             minlength=c)
        face_vertex = self._h["from"][self.loop_offsets[:-1]]
        loop_c = np.searchsorted(labels, comp[face_vertex])
        outer = np.zeros(self.n_loops, bool)
        outer[self.face_outer_loop[self.face_outer_loop >= 0]] = True
        face_c = np.bincount(loop_c[outer], minlength=c)
        hole_c = np.bincount(loop_c[~outer], minlength=c)
        loops = self.boundary_loops()
        bnd_c = np.bincount([int(np.searchsorted(labels, comp[lp[0]])) for lp in loops],
                            minlength=c).astype(np.int64)
        chi = vert_c - edge_c + face_c - hole_c + bnd_c
        twice_g = 2 - chi
        genus = [int(g) // 2 if g % 2 == 0 and g >= 0 else None for g in twice_g.tolist()]
        g_total = None if any(g is None for g in genus) else sum(g or 0 for g in genus)
        return EulerReport(
            V=int(used.sum()), E=self.n_edges, F=int(outer.sum()), H=int((~outer).sum()),
            C=c, G=g_total, B=len(loops), is_closed=self.is_closed,
            is_manifold=self.is_manifold, is_oriented=self.is_oriented,
            genus_per_component=genus)

    # ------------------------------------------------------------------ queries
    def _check(self, kind: str, i: int, n: int) -> int:
        i = int(i)
        if not 0 <= i < n:
            raise GeometryError(f"{kind} {i} does not exist (0..{n - 1})")
        return i

    def _loop_halves(self, loop: int) -> list[int]:
        a, b = int(self.loop_offsets[loop]), int(self.loop_offsets[loop + 1])
        return list(range(a, b))

    def face_edges(self, f: int) -> list[int]:
        """Edges around face ``f`` in loop order (outer loop; see :meth:`face_loops`).

        Parameters
        ----------
        f : int
            The face's index.
        """
        f = self._check("face", f, self.n_faces)
        return [int(self._h["edge"][h]) for h in self._loop_halves(int(self.face_outer_loop[f]))]

    def face_vertices(self, f: int) -> list[int]:
        """Vertices of face ``f`` counter-clockwise (outer loop).

        Parameters
        ----------
        f : int
            The face's index.
        """
        f = self._check("face", f, self.n_faces)
        return [int(self._h["from"][h]) for h in self._loop_halves(int(self.face_outer_loop[f]))]

    def face_faces(self, f: int) -> list[int]:
        """Faces across each edge of face ``f``, in loop order (-1 across a boundary).

        Parameters
        ----------
        f : int
            The face's index.
        """
        f = self._check("face", f, self.n_faces)
        t = self._h["twin"]
        return [int(self._h["face"][t[h]]) if t[h] >= 0 else -1
                for h in self._loop_halves(int(self.face_outer_loop[f]))]

    def face_loops(self, f: int) -> list[list[int]]:
        """Every loop of face ``f`` as vertex lists: outer first, then the holes.

        Parameters
        ----------
        f : int
            The face's index.
        """
        f = self._check("face", f, self.n_faces)
        return [[int(self._h["from"][h]) for h in self._loop_halves(lp)]
                for lp in np.flatnonzero(self.loop_face == f).tolist()]

    def edge_vertices_of(self, e: int) -> tuple[int, int]:
        """The (P, N) vertices of edge ``e``.

        Parameters
        ----------
        e : int
            The edge's index.
        """
        e = self._check("edge", e, self.n_edges)
        return int(self.edge_vertices[e, 0]), int(self.edge_vertices[e, 1])

    def edge_faces_of(self, e: int) -> tuple[int, int]:
        """(left, right) faces of edge ``e``; -1 on a boundary.

        Parameters
        ----------
        e : int
            The edge's index.
        """
        e = self._check("edge", e, self.n_edges)
        return int(self.edge_faces[e, 0]), int(self.edge_faces[e, 1])

    def edge_edges(self, e: int) -> tuple[int, int, int, int]:
        """The four wings (P_L, P_R, N_L, N_R) of edge ``e``; -1 where absent.

        Parameters
        ----------
        e : int
            The edge's index.
        """
        e = self._check("edge", e, self.n_edges)
        return tuple(int(x) for x in self.edge_wings[e])  # type: ignore[return-value]

    def _vertex_fan(self, v: int) -> list[int]:
        """Outgoing half-edges around vertex ``v`` in counter-clockwise order (seen from
        outside); on a boundary the fan starts at the boundary."""
        h0 = int(self._vertex_half[v])
        if h0 < 0:
            return []
        t, prv = self._h["twin"], self._h["prev"]
        # walk clockwise to the start of the fan (or all the way round)
        start, h = h0, h0
        for _ in range(len(t)):
            back = t[h]
            if back < 0:
                start = h
                break
            h = int(self._h["next"][back])
            if h == h0:
                start = h0
                break
            start = h
        fan, h = [start], start
        for _ in range(len(t)):
            p = int(prv[h])
            if t[p] < 0:
                break
            h = int(t[p])
            if h == start:
                break
            fan.append(h)
        return fan

    def vertex_edges(self, v: int) -> list[int]:
        """Edges at vertex ``v`` in cyclic order (counter-clockwise seen from outside).

        Parameters
        ----------
        v : int
            The vertex's index.
        """
        v = self._check("vertex", v, self.n_vertices)
        fan = self._vertex_fan(v)
        out = [int(self._h["edge"][h]) for h in fan]
        if fan and self._h["twin"][self._h["prev"][fan[-1]]] < 0:
            out.append(int(self._h["edge"][self._h["prev"][fan[-1]]]))  # the last boundary edge
        return out

    def vertex_faces(self, v: int) -> list[int]:
        """Faces around vertex ``v`` in cyclic order.

        Parameters
        ----------
        v : int
            The vertex's index.
        """
        v = self._check("vertex", v, self.n_vertices)
        return [int(self._h["face"][h]) for h in self._vertex_fan(v)]

    def vertex_vertices(self, v: int) -> list[int]:
        """Neighbours of vertex ``v`` in cyclic order.

        Parameters
        ----------
        v : int
            The vertex's index.
        """
        v = self._check("vertex", v, self.n_vertices)
        out = []
        for e in self.vertex_edges(v):
            a, b = self.edge_vertices[e]
            out.append(int(b if a == v else a))
        return out
