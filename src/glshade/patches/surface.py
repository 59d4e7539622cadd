"""Patches as a B-Rep: faces point to patches, edges to their boundary curves, vertices to
the patches' corners. Adjacency is found by matching boundary control nets (a curve shared
by two patches has the same control points and weights, in one direction or the other), so
Euler's formula is reported on a patch model as on a mesh.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..brep.topology import EulerReport
from .bezier import PatchSet

__all__ = ["PatchSurface", "SIDES"]

#: the four sides of a patch: (name, which index is fixed, at which end)
SIDES = (("u0", 1, 0), ("u1", 1, -1), ("v0", 2, 0), ("v1", 2, -1))
#: control points within this fraction of the model's size are the same point
MATCH = 1e-9


@dataclass(frozen=True)
class Edges:
    """The boundary curves: ``side_edge (P, 4)`` edge of each patch side (-1: a collapsed
    side, a point), ``side_reversed (P, 4)`` whether the side runs against its edge's
    canonical direction, ``uses (E,)`` patch sides on each edge, ``control`` the edges'
    canonical control nets ``(E, k, 4)`` (homogeneous), ``corner_vertex (P, 4)``."""

    side_edge: np.ndarray
    side_reversed: np.ndarray
    uses: np.ndarray
    control: list
    corner_vertex: np.ndarray
    n_vertices: int
    edge_vertices: np.ndarray = field(repr=False)


def side_net(h: np.ndarray, side: int) -> np.ndarray:
    """The homogeneous control net of one side of every patch: ``(P, k, 4)``, in the
    direction of increasing parameter along it."""
    _, axis, end = SIDES[side]
    return np.take(h, end, axis=axis)


class PatchSurface:
    """A model made of patches (a :class:`PatchSet`): the B-Rep of faces, edges and vertices
    found from them, and its Euler characteristic. ``name`` for messages.

    Parameters
    ----------
    patches : PatchSet
        The patches.
    name : str
        Its name, for messages.
    """

    def __init__(self, patches: PatchSet, name: str = "patches"):
        self.patches = patches
        self.name = name

    def __repr__(self) -> str:
        m, n = self.patches.degree
        return (f"<PatchSurface {self.name!r}: {len(self.patches)} patches of degree "
                f"{m}x{n}{' (rational)' if self.patches.rational else ''}>")

    def _repr_html_(self) -> str:
        """In a notebook: a thumbnail of a tessellation (exact normals) and the B-Rep's
        counts."""
        from ..display import bounds_fact, facts_html, picture

        e = self.euler()
        b = self.patches.bounds()
        lo, hi = b[:, 0].min(0), b[:, 1].max(0)
        facts = [f"V {e.V}, E {e.E} boundary curves, F {e.F} patches",
                 e.formula, ("closed" if e.is_closed else f"{e.B} boundary loops") +
                 f", {e.C} component{'s' if e.C != 1 else ''}",
                 bounds_fact(np.stack([lo, hi]))]
        return facts_html(repr(self), facts, picture(self))  # (a scene tessellates it)

    def _key(self, pts: np.ndarray) -> np.ndarray:
        """Points (x, y, z[, w]) rounded to whole steps of MATCH times the patches' size
        (a weight, a pure number, to steps of MATCH: divided by a tiny patch's size it
        would pass int64's range)."""
        scale = float(np.ptp(self.patches.points.reshape(-1, 3), 0).max()) or 1.0
        steps = np.full(pts.shape[-1], MATCH * scale)
        steps[3:] = MATCH
        return np.round(pts / steps).astype(np.int64)

    @cached_property
    def edges(self) -> Edges:
        h = self.patches.homogeneous
        P = len(h)
        nets = [side_net(h, s) for s in range(4)]  # each (P, k, 4): k = n+1 or m+1
        width = max(x.shape[1] for x in nets) * 4
        rows, fwd_all, canon_nets = [], [], []
        for net in nets:
            proj = np.concatenate([net[..., :3] / net[..., 3:], net[..., 3:]], -1)
            key = self._key(proj)  # (P, k, 4)
            fwd = key.reshape(P, -1)
            rev = key[:, ::-1].reshape(P, -1)
            differ = fwd != rev
            first = differ.argmax(1)
            reverse = differ.any(1) & (rev[np.arange(P), first] < fwd[np.arange(P), first])
            canon = np.where(reverse[:, None], rev, fwd)
            pad = np.full((P, width - canon.shape[1]), np.iinfo(np.int64).min)
            rows.append(np.hstack([canon, pad]))
            fwd_all.append(reverse)
            canon_nets.append(np.where(reverse[:, None, None], net[:, ::-1], net))
            # a side whose control points all coincide is a collapsed edge: a point
            rows[-1][(key[:, :, :3] == key[:, :1, :3]).all((1, 2))] = np.iinfo(np.int64).max
        keys = np.stack(rows, 1).reshape(P * 4, width)  # (side-major within a patch)
        side_rev = np.stack(fwd_all, 1)
        degenerate = (keys == np.iinfo(np.int64).max).all(1)
        flat_edge = np.full(P * 4, -1)
        uniq, first_use, inverse = np.unique(keys[~degenerate], axis=0, return_index=True,
                                             return_inverse=True)
        flat_edge[~degenerate] = inverse.ravel()
        side_edge = flat_edge.reshape(P, 4)
        uses = np.bincount(inverse.ravel(), minlength=len(uniq))
        owners = np.flatnonzero(~degenerate)[first_use]  # (E,) patch side defining each
        control = [canon_nets[o % 4][o // 4] for o in owners]
        corners = np.stack([h[:, 0, 0], h[:, -1, 0], h[:, -1, -1], h[:, 0, -1]], 1)
        cpts = self._key(corners[..., :3] / corners[..., 3:]).reshape(-1, 3)
        _, vertex = np.unique(cpts, axis=0, return_inverse=True)
        vertex = vertex.reshape(P, 4)
        # an edge's end vertices, from its defining side: u0 runs corner 0 -> 3, u1 1 -> 2,
        # v0 0 -> 1, v1 3 -> 2 (reversed when the side runs against the edge)
        ends = np.array([(0, 3), (1, 2), (0, 1), (3, 2)])
        op, os_ = owners // 4, owners % 4
        ev = np.stack([vertex[op, ends[os_, 0]], vertex[op, ends[os_, 1]]], 1)
        ev = np.where(side_rev[op, os_][:, None], ev[:, ::-1], ev)
        return Edges(side_edge, side_rev, uses, control, vertex,
                     int(vertex.max()) + 1 if P else 0, ev)

    @cached_property
    def _neighbours(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The patches meeting at each shared edge ``(a, b)`` and whether they run it in the
        same direction around their boundaries (v0 and u1 forward, v1 and u0 backward, times
        each side's own reversal): then one of them is turned against the other."""
        e = self.edges
        P = len(self.patches)
        loop = np.array([-1, 1, 1, -1])  # u0, u1, v0, v1
        d = np.where(e.side_reversed, -1, 1) * loop  # (P, 4)
        sides = e.side_edge.ravel()
        has = sides >= 0
        patch_of = np.repeat(np.arange(P), 4)[has]
        edge_of, dir_of = sides[has], d.ravel()[has]
        order = np.argsort(edge_of, kind="stable")
        edge_of, patch_of, dir_of = edge_of[order], patch_of[order], dir_of[order]
        pair = np.flatnonzero(edge_of[1:] == edge_of[:-1])  # (consecutive uses of an edge)
        return patch_of[pair], patch_of[pair + 1], dir_of[pair] == dir_of[pair + 1]

    def _components(self) -> np.ndarray:
        """``(P,)`` component label of each patch: patches joined by shared edges."""
        a, b, _ = self._neighbours
        return _labels(len(self.patches), np.stack([a, b], 1))

    def oriented(self) -> PatchSurface:
        """The same surface with every patch turned (v reversed where needed) so that
        neighbours run their shared edges in opposite directions and each component's
        normals point outward. Data sets wind patches either way (the teapot's body one way,
        the rest the other)."""
        P = len(self.patches)
        a, b, must_differ = self._neighbours
        flip = np.zeros(P, bool)
        known = np.zeros(P, bool)
        component = np.unique(self._components(), return_inverse=True)[1].ravel()
        for label in range(component.max() + 1):
            seed = np.flatnonzero(component == label)[0]
            known[seed] = True
            while True:
                step_a = known[a] & ~known[b]
                step_b = known[b] & ~known[a]
                if not (step_a.any() or step_b.any()):
                    break
                flip[b[step_a]] = flip[a[step_a]] ^ must_differ[step_a]
                known[b[step_a]] = True
                flip[a[step_b]] = flip[b[step_b]] ^ must_differ[step_b]
                known[a[step_b]] = True
        # then each component turned to face outward: the flux of (p - c) through it, c the
        # centre of its box, is 3 V > 0 for a closed surface (divergence theorem) whatever c,
        # and for an open one (a lid, a spout) tells outward from inward all the same
        t = (np.arange(6) + 0.5) / 6
        u, v = [x.ravel() for x in np.meshgrid(t, t, indexing="ij")]
        d = self.patches.derivatives(u, v)
        area = np.linalg.norm(np.cross(d["Su"], d["Sv"]), axis=-1)  # (P, 36)
        n = self.patches.normals(u, v)
        lo = np.full((component.max() + 1, 3), np.inf)
        hi = np.full((component.max() + 1, 3), -np.inf)
        bounds = self.patches.bounds()
        np.minimum.at(lo, component, bounds[:, 0])
        np.maximum.at(hi, component, bounds[:, 1])
        mid = (lo + hi) / 2
        sign = np.where(flip, -1.0, 1.0)
        flux = np.einsum("pki,pki,pk->p", n, d["S"] - mid[component][:, None], area) * sign
        total = np.zeros(len(mid))
        np.add.at(total, component, flux)
        flip ^= total[component] < 0
        # (turned over by running v backwards: the degrees stay as they are)
        pts = np.where(flip[:, None, None, None], self.patches.points[:, :, ::-1],
                       self.patches.points)
        w = np.where(flip[:, None, None], self.patches.weights[:, :, ::-1],
                     self.patches.weights)
        return PatchSurface(PatchSet(pts, w), self.name)

    def euler(self) -> EulerReport:
        """V, E, F (patches), C, G and boundary loops B, as for a mesh: ``V - E + F + B =
        2 (C - G)``. An edge used by one patch is on the boundary; by more than two, the
        surface is not a manifold."""
        e = self.edges
        P = len(self.patches)
        E, F = len(e.uses), P
        label = self._components()
        labels = np.unique(label)
        # (components touching at a point -- the teapot's spout and handle on its body --
        # keep a vertex each there, as they would apart)
        V = sum(len(np.unique(e.corner_vertex[label == lab])) for lab in labels)
        boundary = e.uses == 1
        B = _loops(e.edge_vertices[boundary])
        genus: list[int | None] = []
        for lab in labels:
            mine = label == lab
            edges_here = np.unique(e.side_edge[mine][e.side_edge[mine] >= 0])
            chi = len(np.unique(e.corner_vertex[mine])) - len(edges_here) + int(mine.sum())
            g2 = 2 - _loops(e.edge_vertices[edges_here[boundary[edges_here]]]) - chi
            genus.append(g2 // 2 if g2 >= 0 and g2 % 2 == 0 else None)
        G = None if any(g is None for g in genus) else sum(g or 0 for g in genus)
        return EulerReport(V, E, F, 0, len(labels), G, B, not boundary.any(),
                           bool((e.uses <= 2).all()), True, genus)


def _labels(n: int, pairs: np.ndarray) -> np.ndarray:
    """``(n,)`` connected-component labels of a graph given by its edges ``pairs (k, 2)``:
    each node's label is spread along the edges until nothing changes (the smallest wins)."""
    label = np.arange(n)
    while len(pairs):
        low = np.minimum(label[pairs[:, 0]], label[pairs[:, 1]])
        new = label.copy()
        np.minimum.at(new, pairs[:, 0], low)
        np.minimum.at(new, pairs[:, 1], low)
        if (new == label).all():
            break
        label = new
    return label


def _loops(edges: np.ndarray) -> int:
    """Loops formed by boundary edges ``(k, 2)``: the components of their graph."""
    if len(edges) == 0:
        return 0
    nodes, idx = np.unique(edges, return_inverse=True)
    return len(np.unique(_labels(len(nodes), idx.reshape(-1, 2))))
