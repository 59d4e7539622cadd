"""Undirected edges of polygon meshes: the one place that pairs half-edges.

A half-edge ``(a, b)`` and its twin ``(b, a)`` share the undirected key
``min(a, b) * V + max(a, b)``. Sorting by that key groups every edge's half-edges together;
the mesh's edge list, crease splitting, the winged-edge B-Rep, sphere subdivision and the
closed-and-oriented test all read those groups.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["EdgeGroups", "edge_groups", "is_closed_and_oriented", "orientation_flips"]

Int = NDArray[np.int64]


@dataclass(frozen=True)
class EdgeGroups:
    """Half-edges grouped by undirected edge.

    ``order (H,)``: half-edge indices sorted by undirected key (stable: input order within
    a group); ``start (E,)``: position in ``order`` of each edge's first half-edge;
    ``count (E,)``: half-edges of each edge (2 for an interior manifold edge); ``group
    (H,)``: edge of each half-edge; ``lo, hi (E,)``: the edge's end points, lo < hi.

    Parameters
    ----------
    order : ndarray
        ``(H,)`` half-edge indices sorted by undirected key.
    start : ndarray
        ``(E,)`` each edge's first position in ``order``.
    count : ndarray
        ``(E,)`` each edge's half-edges.
    group : ndarray
        ``(H,)`` each half-edge's edge.
    lo, hi : ndarray
        ``(E,)`` each edge's end points, lo < hi.
    """

    order: Int
    start: Int
    count: Int
    group: Int
    lo: Int
    hi: Int

    @property
    def first(self) -> Int:
        """``(E,)`` the first half-edge (in input order) of each edge."""
        return self.order[self.start]

    @property
    def sides(self) -> Int:
        """``(E, 2)`` each edge's first two half-edges, in input order; an edge with one
        (a boundary) names it twice."""
        second = self.start + (self.count > 1)
        return np.stack([self.order[self.start], self.order[second]], axis=1)

    def pairs(self) -> tuple[Int, Int]:
        """The two half-edges ``(h0, h1)`` of every edge that has exactly two."""
        s = self.start[self.count == 2]
        return self.order[s], self.order[s + 1]


def edge_groups(a: Int, b: Int, n_vertices: int) -> EdgeGroups:
    """Group the edges ``(a[i], b[i])`` by their undirected key (vectorized).

    Parameters
    ----------
    a, b : ndarray
        ``(H,)`` int: each half-edge's start and end vertex.
    n_vertices : int
        The vertices (the keys' range).
    """
    a = np.asarray(a, np.int64)
    b = np.asarray(b, np.int64)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    key = lo * max(int(n_vertices), 1) + hi
    order = np.argsort(key, kind="stable")
    ks = key[order]
    start = np.flatnonzero(np.r_[True, ks[1:] != ks[:-1]]) if len(ks) else \
        np.zeros(0, np.int64)
    count = np.diff(np.r_[start, len(ks)])
    group = np.empty(len(key), np.int64)
    group[order] = np.repeat(np.arange(len(start)), count)
    first = order[start]
    return EdgeGroups(order, start, count, group, lo[first], hi[first])


def is_closed_and_oriented(half_edges: Int, n_vertices: int) -> bool:
    """Every edge shared by exactly two faces that traverse it in opposite directions: the
    surface is closed and consistently oriented, so back faces are never visible.

    Parameters
    ----------
    half_edges : ndarray
        ``(H, 2)`` int: each face's edges as (start, end), in its winding.
    n_vertices : int
        The vertices.
    """
    he = np.asarray(half_edges, np.int64)
    if len(he) == 0:
        return False
    g = edge_groups(he[:, 0], he[:, 1], n_vertices)
    if (g.count != 2).any():
        return False
    h0, h1 = g.pairs()
    return bool((he[h0, 0] != he[h1, 0]).all())


def orientation_flips(half_edges: Int, corner_face: Int, n_faces: int,
                      n_vertices: int) -> tuple[NDArray[np.bool_], bool]:
    """Which faces to reverse so that every edge shared by two faces is traversed in
    opposite directions; and whether that is possible everywhere (False on a Moebius strip
    or a Klein bottle). Each connected piece keeps the orientation of its lowest-numbered
    face.

    Solved as connected components of the doubled face graph (vectorized): node ``f`` is
    face f as it is, node ``F + f`` face f reversed; two faces whose shared edge runs the
    same way join each one's reversed node to the other's own, faces that already agree
    join own to own and reversed to reversed.

    Parameters
    ----------
    half_edges : ndarray
        ``(H, 2)`` int: each face's edges as (start, end).
    corner_face : ndarray
        ``(H,)`` the face of each half-edge.
    n_faces, n_vertices : int
        The faces and vertices.
    """
    from .graph import component_labels

    he = np.asarray(half_edges, np.int64)
    g = edge_groups(he[:, 0], he[:, 1], n_vertices)
    h0, h1 = g.pairs()
    f0, f1 = corner_face[h0], corner_face[h1]
    same_way = he[h0, 0] == he[h1, 0]
    other = np.where(same_way, f1 + n_faces, f1)
    a = np.r_[f0, f0 + n_faces]
    b = np.r_[other, np.where(same_way, f1, f1 + n_faces)]
    label = component_labels(2 * n_faces, a, b)
    faces = np.arange(n_faces)
    orientable = not (label[faces] == label[faces + n_faces]).any()
    return label[faces] > label[faces + n_faces], orientable
