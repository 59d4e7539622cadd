"""The BSP tree (object space): each node holds a polygon's plane and the polygons in it;
the polygons in front of the plane go to one subtree, those behind to the other, and a
polygon that straddles the plane is split in two. Drawn back to front from the eye --
for each node, the subtree on the far side of its plane, the node's own polygons, then the
near subtree -- by a painter that overwrites, the nearest surface is painted last.

The tree is built and walked with explicit stacks (no recursion limit); each node's
classification of its polygons is one vectorised step. Polygons are triangles (the
mesh's own triangulation: pieces of a split triangle are triangles again)."""

from __future__ import annotations

import numpy as np

from .raster import fragments, resolve_last
from .result import HiddenResult
from .view import Prepared, split_by_plane, takes_scene, timed

__all__ = ["bsp", "build_bsp", "back_to_front", "paint", "Pieces"]


class Pieces:
    """Triangles and the pieces they are split into: view-space ``tris``, the ``src``
    triangle of the Prepared view each comes from, and ``cut`` flags of its edges. Grows
    (capacity doubling) as pieces are added; indices stay valid."""

    def __init__(self, tris, src, cut=None):
        self.size = len(tris)
        cap = max(16, 2 * self.size)
        self._t = np.empty((cap, 3, 3))
        self._s = np.empty(cap, np.int64)
        self._c = np.zeros((cap, 3), bool)
        self._n = np.zeros((cap, 4))  # unit normal, offset (zeros: no plane)
        self._a = np.zeros(cap)       # area
        self._t[:self.size], self._s[:self.size] = tris, src
        if cut is not None:
            self._c[:self.size] = cut
        self._planes(0, self.size)

    def _planes(self, start, stop):
        t = self._t[start:stop]
        cross = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        area = np.linalg.norm(cross, axis=1)
        n = np.divide(cross, area[:, None], out=np.zeros_like(cross), where=area[:, None] > 0)
        self._n[start:stop, :3] = n
        self._n[start:stop, 3] = np.einsum("nd,nd->n", n, t[:, 0])
        self._a[start:stop] = area

    def arrays(self):
        return self._t[:self.size], self._s[:self.size], self._c[:self.size]

    def plane(self, k):
        return self._n[k, :3], self._n[k, 3], self._a[k]

    def add(self, tris, src, cut, plane=None) -> np.ndarray:
        """Append pieces; ``plane`` (4,): the plane they all lie in (pieces of one split
        triangle inherit its plane, exact where their own cross product is a sliver's)."""
        need = self.size + len(tris)
        if need > len(self._t):
            cap = max(need, 2 * len(self._t))
            for name in ("_t", "_s", "_c", "_n", "_a"):
                old = getattr(self, name)
                new = np.zeros((cap, *old.shape[1:]), old.dtype)
                new[:self.size] = old[:self.size]
                setattr(self, name, new)
        self._t[self.size:need], self._s[self.size:need], self._c[self.size:need] = \
            tris, src, cut
        start, self.size = self.size, need
        if plane is None:
            self._planes(start, need)
        else:
            self._n[start:need] = plane
            self._a[start:need] = [_twice_area(t) for t in np.asarray(tris).tolist()]
        return np.arange(start, need)


def _twice_area(t: list) -> float:
    """|(b - a) x (c - a)| of one triangle, in plain floats (a split adds two or three)."""
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    ux, uy, uz, vx, vy, vz = bx - ax, by - ay, bz - az, cx - ax, cy - ay, cz - az
    return ((uy * vz - uz * vy) ** 2 + (uz * vx - ux * vz) ** 2 +
            (ux * vy - uy * vx) ** 2) ** 0.5


def build_bsp(pieces: Pieces, eps: float):
    """Nodes ``[normal, offset, own pieces, front child, back child]`` (children: node
    indices or -1) over ``pieces`` (split ones are added to it), and counters."""
    nodes: list[list] = []
    counters = {"nodes": 0, "splits": 0, "classifications": 0}
    if not pieces.size:
        return nodes, counters
    tiny = (eps * 1e3) ** 2
    stack = [(-1, False, np.arange(pieces.size))]  # (parent, in front of it, members)
    while stack:
        parent, side, members = stack.pop()
        t_all, s_all, c_all = pieces.arrays()
        # the splitter: the first member with an area to speak of (slivers of splits and
        # degenerate triangles have no reliable plane; they cover no pixel either)
        usable = np.flatnonzero(pieces._a[members] > tiny)
        if len(members) == 1 or not len(usable):  # a leaf
            n, d, _ = pieces.plane(members[0])
            nodes.append([n, d, members, -1, -1])
            if parent >= 0:
                nodes[parent][3 if side else 4] = len(nodes) - 1
            continue
        if usable[0]:
            members = np.r_[members[usable[0]], np.delete(members, usable[0])]
        n, d, _ = pieces.plane(members[0])
        rest = members[1:]
        dist = np.einsum("nkd,d->nk", t_all[rest], n) - d
        counters["classifications"] += len(rest)
        on = np.abs(dist) <= eps
        coplanar = on.all(1)
        front = ((dist >= 0) | on).all(1) & ~coplanar
        back = ((dist <= 0) | on).all(1) & ~coplanar & ~front
        straddle = ~(coplanar | front | back)
        own = np.r_[members[:1], rest[coplanar]]
        f_members, b_members = rest[front], rest[back]
        if straddle.any():
            sp = rest[straddle]
            counters["splits"] += len(sp)
            ft, fs, fc, bt, bs, bc = split_by_plane(t_all[sp], n, np.full(len(sp), d), eps,
                                                    c_all[sp])
            f_members = np.r_[f_members, pieces.add(ft, s_all[sp][fs], fc)]
            b_members = np.r_[b_members, pieces.add(bt, s_all[sp][bs], bc)]
        index = len(nodes)
        nodes.append([n, d, own, -1, -1])
        if parent >= 0:
            nodes[parent][3 if side else 4] = index
        if len(b_members):
            stack.append((index, False, b_members))
        if len(f_members):
            stack.append((index, True, f_members))
    counters["nodes"] = len(nodes)
    return nodes, counters


def back_to_front(nodes, eye=(0.0, 0.0, 0.0, 1.0)) -> np.ndarray:
    """Piece indices in painting order (far to near) for an eye at ``eye`` (view space,
    homogeneous: ``w = 0`` is an orthographic camera's eye, at infinity)."""
    eye = np.asarray(eye, np.float64)
    if not nodes:
        return np.zeros(0, np.int64)
    out = []
    stack = [("node", 0)]
    while stack:
        kind, k = stack.pop()
        if kind == "own":
            out.append(k)
            continue
        normal, offset, own, front, back = nodes[k]
        # coplanar polygons: the first drawn painted last (it wins a tie, as GL_LESS)
        own = own[::-1]
        if normal @ eye[:3] - offset * eye[3] >= 0:  # the eye is in front: back, own, front
            first, second = back, front
        else:
            first, second = front, back
        if second >= 0:
            stack.append(("node", second))
        stack.append(("own", own))
        if first >= 0:
            stack.append(("node", first))
    return np.concatenate(out) if out else np.zeros(0, np.int64)


def paint(p: Prepared, result: HiddenResult, pieces: Pieces, sequence, counters=None):
    """Paint ``pieces`` in ``sequence`` (later over earlier); each pixel of a piece's source
    triangle goes to the one piece that holds it."""
    if not len(sequence):
        return
    tris, src, cut = pieces.arrays()
    tris, src, cut = tris[sequence], src[sequence], cut[sequence]
    sub = p.subset(tris, p.ids[src], np.arange(len(sequence)))
    sub.src, sub.cut = src, cut  # (kept: the steps of a painter repaint prefixes of it)
    for pix, k, depth in fragments(p, p.screen[src], p.tris[src], None, sub.screen, cut):
        if counters is not None:
            counters["pixels painted"] = counters.get("pixels painted", 0) + len(pix)
        resolve_last(sub, result, pix, k, depth, k)
    return sub


@takes_scene
def bsp(p: Prepared) -> HiddenResult:
    """A BSP tree of the polygons (split where a plane cuts them), walked back to front from
    the eye and painted. Same inputs and result as :func:`zbuffer`, counting nodes and
    splits."""
    extent = float(np.abs(p.tris).max()) if len(p.tris) else 1.0
    counters = {"polygons": p.n_polygons, "triangles": len(p.tris)}

    def run(result: HiddenResult):
        pieces = Pieces(p.tris, np.arange(len(p.tris)))
        nodes, c = build_bsp(pieces, 1e-9 * extent)
        counters.update(c)
        sequence = back_to_front(nodes, p.eye)
        counters["pieces painted"] = len(sequence)
        result.painted = paint(p, result, pieces, sequence, counters)

    result = timed("bsp", p, run)
    result.counters = counters
    return result
