"""Constructive solid geometry: the notes' binary trees whose leaves are primitive solids
and whose interior nodes are boolean operations or nonsingular transformations, with
Roth's ray casting as the numpy reference.

Leaves (unit-size defaults, centred at the origin, axis along y): :class:`Sphere`,
:class:`Box`, :class:`Cylinder`, :class:`Cone` (apex up), :class:`Torus` (around y),
:class:`HalfSpace` (``normal . p <= offset``). Nodes: ``a | b`` (union), ``a & b``
(intersection), ``a - b`` (difference) and ``a.transformed(m)`` for any nonsingular affine
``m`` (shear and non-uniform scale included), with ``translated``, ``rotated``, ``scaled``.

Roth: along every ray each leaf gives its intervals of inside (as boundary *events*: a
parameter t, entering or leaving, the surface's outward normal, the leaf), and the
boolean operators combine the event lists up the tree -- sort the two lists together,
follow inside-A and inside-B through them, keep the events where the result changes.
The lists are fixed-width arrays sized from the tree (the sum of its leaves' widths), so
no interval is ever dropped; everything is vectorised over rays.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..errors import GeometryError
from ..geometry.analytic import affine_matrix
from ..geometry.transforms import box_corners

__all__ = ["Solid", "Union", "Intersection", "Difference", "Transformed", "Events",
           "MAX_DEPTH", "SIZE_RANGE", "TIE", "tie_length"]

#: sizes, offsets and translations within (1 / SIZE_RANGE, SIZE_RANGE) in magnitude: their
#: squares stay finite and normal in float32 (the GPU's numbers)
SIZE_RANGE = 1e15
#: the deepest a tree may be after rebalancing (its runs of one operator rebuilt balanced;
#: a move folds into the transform below it): well inside Python's recursion limit, which
#: the numpy reference's walk down the tree uses
MAX_DEPTH = 200
#: the tie rule: leaf boundaries closer along a ray than TIE times the cast's scale (the
#: solid's reach plus the ray origin's distance from its centre) are one place -- the
#: tree's answer is taken past all of them, and the surface there, if any, is the
#: lowest-numbered (leftmost) leaf among them. Coincident faces computed through
#: different transforms differ by rounding (float32 on the GPU), so without it their order
#: is noise: a box minus a box that shares a face speckles, a union shows either leaf.
#: 2^-16: some 100 times float32's rounding; thinner features than this vanish. Between
#: two planes at the same angle to the ray (one plane, or parallel ones), the GPU's one-step
#: cast widens the length by the inverse of their cosine with the ray (at most 64 times,
#: shaders/include/csg/onestep.glsl): a crossing's rounding grows so along the ray.
TIE = 2.0 ** -16


def tie_length(bounds, origin) -> float:
    """The tie rule's length (world units) for a solid with ``bounds (2, 3)`` cast from
    ``origin (3,)``: TIE times its reach plus the origin's distance from its centre.

    Parameters
    ----------
    bounds : array_like
        ``(2, 3)`` the solid's box.
    origin : array_like
        ``(3,)`` where the rays start.
    """
    lo, hi = np.asarray(bounds, np.float64)
    centre = (lo + hi) / 2
    reach = np.linalg.norm(hi - lo) / 2
    return float(TIE * (reach + np.linalg.norm(np.asarray(origin, np.float64) - centre)))


class Events:
    """Boundary events along each of N rays, ``(N, K)``: ``t`` (sorted; +inf pads),
    ``kind`` (+1 enter, -1 leave, 0 pad), ``normal (N, K, 3)`` outward from the solid,
    ``leaf`` (the leaf's index in the tree).

    Parameters
    ----------
    t : ndarray
        ``(N, K)`` event distances along each ray, sorted; +inf pads.
    kind : ndarray
        ``(N, K)`` +1 enter, -1 leave, 0 pad.
    normal : ndarray
        ``(N, K, 3)`` outward unit normals at the events.
    leaf : ndarray
        ``(N, K)`` the leaf of each event.
    """

    def __init__(self, t, kind, normal, leaf):
        self.t, self.kind, self.normal, self.leaf = t, kind, normal, leaf

    @classmethod
    def empty(cls, n: int, k: int) -> Events:
        """No events: N rays of K padding slots.

        Parameters
        ----------
        n : int
            Rays.
        k : int
            Slots a ray.
        """
        return cls(np.full((n, k), np.inf), np.zeros((n, k), np.int8), np.zeros((n, k, 3)),
                   np.full((n, k), -1, np.int64))

    def sorted(self) -> Events:
        order = np.argsort(self.t, axis=1, kind="stable")
        take = lambda a: np.take_along_axis(a, order if a.ndim == 2 else order[..., None], 1)  # noqa: E731
        return Events(take(self.t), take(self.kind), take(self.normal), take(self.leaf))


class Solid:
    """A node of a CSG tree."""

    width = 2  # events per ray (a leaf with one interval)
    depth = 1  # levels, the node's own included
    n_leaves = 1

    def __or__(self, other):
        return Union(self, _solid(other))

    def __and__(self, other):
        return Intersection(self, _solid(other))

    def __sub__(self, other):
        return Difference(self, _solid(other))

    def transformed(self, matrix: ArrayLike) -> Solid:
        """This solid moved by an affine map.

        Parameters
        ----------
        matrix : array_like
            ``(4, 4)`` affine (or ``(3, 3)`` linear) matrix for column vectors, nonsingular.
        """
        return Transformed(self, affine_matrix(matrix, "CSG transform"))

    def translated(self, offset: ArrayLike) -> Solid:
        """This solid moved by ``offset``.

        Parameters
        ----------
        offset : array_like
            ``(3,)`` scene units.
        """
        m = np.eye(4)
        m[:3, 3] = _vec(offset, "translation")
        return self.transformed(m)

    def scaled(self, factor) -> Solid:
        """This solid scaled about the origin.

        Parameters
        ----------
        factor : float or array_like
            One factor, or ``(3,)`` per axis, none zero.
        """
        f = np.broadcast_to(np.asarray(factor, np.float64), (3,))
        return self.transformed(np.diag([*f, 1.0]))

    def rotated(self, q: ArrayLike) -> Solid:
        """This solid turned about the origin.

        Parameters
        ----------
        q : array_like
            ``(4,)`` a unit quaternion ``(x, y, z, w)``.
        """
        from ..quaternion import to_matrix

        m = np.eye(4)
        m[:3, :3] = to_matrix(q)[:3, :3]
        return self.transformed(m)

    # the tree
    def leaves(self) -> list:
        """The leaves, left to right (iterative: any depth)."""
        out, stack = [], [self]
        while stack:
            node = stack.pop()
            if isinstance(node, Transformed):
                stack.append(node.child)
            elif isinstance(node, _Boolean):
                stack += [node.b, node.a]
            else:
                out.append(node)
        return out

    def contains(self, points: ArrayLike) -> np.ndarray:
        """``(N,) bool``: which points lie in the solid (its boundary included).

        Parameters
        ----------
        points : array_like
            ``(N, 3)`` world positions.
        """
        return self._contains(_points(points))

    @property
    def bounds(self) -> np.ndarray | None:
        """``(2, 3)`` box around the solid, or None where it is unbounded."""
        return self._bounds()

    def events(self, origins, directions) -> Events:
        """Roth's boundary events along the rays ``origins + t directions``, every t, with
        the tie rule (:data:`TIE`): ``kind`` 0 marks a boundary the solid's surface is not
        on (kept for the rule; t = inf marks padding).

        Parameters
        ----------
        origins : array_like
            ``(N, 3)`` the rays' starts.
        directions : array_like
            ``(N, 3)`` their directions (not necessarily unit: t is in their units).
        """
        o, d = np.asarray(origins, np.float64), np.asarray(directions, np.float64)
        bounds = self.bounds
        if bounds is None:
            tie = np.zeros((len(o), 1))
        else:
            centre = bounds.mean(0)
            reach = np.linalg.norm(bounds[1] - bounds[0]) / 2
            with np.errstate(divide="ignore", invalid="ignore"):
                tie = TIE * (reach + np.linalg.norm(o - centre, axis=1)) \
                    / np.linalg.norm(d, axis=1)
            tie = np.nan_to_num(tie, posinf=0.0)[:, None]
        leaves = {id(leaf): i for i, leaf in enumerate(self.leaves())}
        return self._events(o, d, _Cast(leaves, tie))

    def intersect(self, origins: ArrayLike, directions: ArrayLike, t_min: float = 0.0):
        """First surface along each ray beyond ``t_min``: ``(t (N,), normal (N, 3), leaf
        (N,))``; t = inf and leaf = -1 where the ray misses. Normals are unit, outward
        from the solid (so flipped on surfaces a difference subtracted).

        Parameters
        ----------
        origins : array_like
            ``(N, 3)`` the rays' starts.
        directions : array_like
            ``(N, 3)`` their directions.
        t_min : float
            Hits at or before this t are not counted.
        """
        o, d = _points(origins), _points(directions)
        if o.shape != d.shape:
            raise GeometryError(f"origins {o.shape} and directions {d.shape} differ")
        ev = self.events(o, d)
        hit = (ev.t > t_min) & (ev.kind != 0)
        first = np.where(hit.any(1), np.argmax(hit, axis=1), -1)
        rows = np.arange(len(o))
        t = np.where(first >= 0, ev.t[rows, first], np.inf)
        normal = np.where((first >= 0)[:, None], ev.normal[rows, first], 0.0)
        length = np.linalg.norm(normal, axis=1, keepdims=True)
        normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
        return t, normal, np.where(first >= 0, ev.leaf[rows, first], -1)

    def classify_boxes(self, lo: ArrayLike, hi: ArrayLike) -> np.ndarray:
        """For axis-aligned boxes ``lo``, ``hi`` (N, 3): 1 if wholly inside the solid, 0 if
        wholly outside, 2 if the boundary may cross it -- conservative (never 0 or 1 by
        mistake), from each leaf's distance bound and the booleans' three-valued logic.

        Parameters
        ----------
        lo, hi : array_like
            ``(N, 3)`` the boxes' min and max corners.
        """
        return self._classify(np.asarray(lo, np.float64), np.asarray(hi, np.float64))

    def volume(self, samples: int = 200_000, seed: int = 0) -> tuple[float, float]:
        """Monte Carlo volume over the bounds: (estimate, standard error).

        Parameters
        ----------
        samples : int
            Random points in the bounds.
        seed : int
            Their generator's seed.
        """
        b = self.bounds
        if b is None:
            raise GeometryError("an unbounded solid (a half-space not cut by anything) has "
                                "no volume")
        rng = np.random.default_rng(seed)
        p = rng.uniform(b[0], b[1], (int(samples), 3))
        frac = self.contains(p).mean()
        box = float(np.prod(b[1] - b[0]))
        return box * frac, box * np.sqrt(frac * (1 - frac) / samples)

    def __repr__(self) -> str:
        return f"<{type(self).__name__}: {self.n_leaves:,} leaves, {self.depth} levels>"

    def _repr_html_(self) -> str:
        """In a notebook: a thumbnail (ray cast on the GPU) and the tree's counts."""
        from ..display import bounds_fact, facts_html, picture

        image = picture(self) if self.bounds is not None else None
        return facts_html(repr(self), [bounds_fact(self.bounds)], image)

    # what every node implements (points, rays and boxes already as float64 arrays)
    def _contains(self, p: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def _bounds(self) -> np.ndarray | None:
        raise NotImplementedError

    def _events(self, o: np.ndarray, d: np.ndarray, cast: _Cast) -> Events:
        raise NotImplementedError

    def _classify(self, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        raise NotImplementedError


# ----------------------------------------------------------------------------- helpers

class _Cast:
    """What a cast passes down the tree: each leaf's number (by ``id``) and the tie
    rule's length per ray, ``(N, 1)`` in units of t."""

    def __init__(self, leaves: dict[int, int], tie: np.ndarray):
        self.leaves, self.tie = leaves, tie


def _solid(x) -> Solid:
    if not isinstance(x, Solid):
        raise GeometryError(f"CSG operands must be solids, got {type(x).__name__}")
    return x


def _vec(v, what) -> np.ndarray:
    try:
        a = np.asarray(v, np.float64)
    except (TypeError, ValueError):
        raise GeometryError(f"{what} must be 3 finite numbers, got {v!r}") from None
    if a.shape != (3,) or not np.isfinite(a).all():
        raise GeometryError(f"{what} must be 3 finite numbers, got {v!r}")
    if np.abs(a).max() >= SIZE_RANGE:
        raise GeometryError(f"{what} {_plain(a)} is too large: keep it under "
                            f"{SIZE_RANGE:g}")
    return a


def _plain(a) -> str:
    return "(" + ", ".join(f"{float(x):g}" for x in np.ravel(a)) + ")"


def _finite(value, what) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise GeometryError(f"{what} must be a number, got {value!r}") from None
    if not np.isfinite(v) or abs(v) >= SIZE_RANGE:
        raise GeometryError(f"{what} must be a finite number under {SIZE_RANGE:g}, got "
                            f"{v:g}")
    return v


def _points(p) -> np.ndarray:
    a = np.asarray(p, np.float64)
    if a.ndim != 2 or a.shape[1] != 3:
        raise GeometryError(f"points must have shape (N, 3), got {a.shape}")
    return a


def _positive(value, what) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise GeometryError(f"{what} must be a positive number, got {value!r}") from None
    if not np.isfinite(v) or v <= 0:
        raise GeometryError(f"{what} must be a positive number, got {v:g}")
    if not 1 / SIZE_RANGE < v < SIZE_RANGE:
        raise GeometryError(f"{what} {v:g} is out of range: sizes lie between "
                            f"{1 / SIZE_RANGE:g} and {SIZE_RANGE:g}")
    return v


def _interval(n, t0, t1, n0, n1, leaf) -> Events:
    """Events of one interval [t0, t1] per ray (NaN t0: no interval)."""
    ev = Events.empty(n, 2)
    ok = ~np.isnan(t0)
    ev.t[ok, 0], ev.t[ok, 1] = t0[ok], t1[ok]
    ev.kind[ok, 0], ev.kind[ok, 1] = 1, -1
    ev.normal[ok, 0], ev.normal[ok, 1] = n0[ok], n1[ok]
    ev.leaf[ok] = leaf
    return ev


def _convex(o, d, candidates, inside, gradient, leaf) -> Events:
    """A convex leaf's interval from candidate boundary parameters (N, C): the segment
    between consecutive candidates whose midpoints are inside, first to last."""
    n = len(o)
    t = np.sort(np.c_[np.full(n, -np.inf), candidates, np.full(n, np.inf)], axis=1)
    a, b = t[:, :-1], t[:, 1:]
    mid = np.where(np.isinf(a), b - 1.0, np.where(np.isinf(b), a + 1.0, (a + b) / 2))
    mid = np.where(np.isinf(a) & np.isinf(b), 0.0, mid)
    p = o[:, None, :] + mid[..., None] * d[:, None, :]
    ins = inside(p.reshape(-1, 3)).reshape(mid.shape) & np.isfinite(mid)
    has = ins.any(1)
    first = np.argmax(ins, axis=1)
    last = ins.shape[1] - 1 - np.argmax(ins[:, ::-1], axis=1)
    rows = np.arange(n)
    t0 = np.where(has, a[rows, first], np.nan)
    t1 = np.where(has, b[rows, last], np.nan)
    p0 = o + np.nan_to_num(t0, posinf=0, neginf=0)[:, None] * d
    p1 = o + np.nan_to_num(t1, posinf=0, neginf=0)[:, None] * d
    return _interval(n, t0, t1, gradient(p0), gradient(p1), leaf)


def _by_distance(distance, lo, hi) -> np.ndarray:
    """Classify boxes by a leaf's signed distance bound at their centres (|d| never more
    than the true distance to the surface): beyond the half-diagonal, wholly out or in."""
    centre, half = (lo + hi) / 2, np.linalg.norm(hi - lo, axis=1) / 2
    d = distance(centre)
    return np.where(d > half, 0, np.where(d < -half, 1, 2)).astype(np.int8)


def _quadratic(a, b, c):
    """Real roots (NaN where none) of a t^2 + b t + c, stable."""
    disc = b * b - 4 * a * c
    ok = (disc >= 0) & (a != 0)
    s = np.sqrt(np.where(ok, disc, 0.0))
    q = -0.5 * (b + np.copysign(s, b))
    with np.errstate(divide="ignore", invalid="ignore"):
        r1, r2 = q / a, c / q
    r1 = np.where(ok, r1, np.nan)
    r2 = np.where(ok & (q != 0), r2, r1)
    return np.fmin(r1, r2), np.fmax(r1, r2)


# ----------------------------------------------------------------------------- nodes

class _Boolean(Solid):
    #: inside the result, from inside A and inside B (elementwise on bool arrays)
    op: Any

    def __init__(self, a: Solid, b: Solid):
        self._link(_solid(a), _solid(b))
        if self.depth > int(self.n_leaves).bit_length() + 4:
            self._rebalance()
        if self.depth > MAX_DEPTH:
            raise GeometryError(f"this CSG tree is {self.depth} levels deep even rebalanced "
                                f"(its {self.n_leaves:,} leaves alternate operators); the "
                                f"limit is {MAX_DEPTH}: group them, e.g. (a | b) & (c | d)")

    def _link(self, a: Solid, b: Solid) -> None:
        """Make a and b this node's operands (and its counts follow)."""
        self.a, self.b = a, b
        self.width = a.width + b.width
        self.n_leaves = a.n_leaves + b.n_leaves
        self.depth = 1 + max(a.depth, b.depth)

    def _run(self) -> list[Solid]:
        """The operands of the run of this operator below (and including) this node, left
        to right; for a difference, the left spine's base and then its subtracted operands
        (``((a - b) - c)`` is ``a - (b | c)``)."""
        kind = type(self)
        if kind is Difference:
            spine: Solid = self
            rights: list[Solid] = []
            while type(spine) is Difference:
                rights.append(spine.b)
                spine = spine.a
            return [spine, *reversed(rights)]
        out: list[Solid] = []
        stack: list[Solid] = [self]
        while stack:
            node = stack.pop()
            if type(node) is kind:
                stack += [node.b, node.a]
            else:
                out.append(node)
        return out

    def _rebalance(self) -> None:
        """Rebuild this node's run of one operator as a balanced tree, in place, keeping
        the leaves' order (and so their ids and the tie rule)."""
        operands = self._run()
        if isinstance(self, Difference):
            base = operands[0]
            cut = [x for op in operands[1:]
                   for x in (op._run() if isinstance(op, Union) else [op])]
            if len(cut) < 2:
                return
            a, b = base, _balanced(Union, cut)
        else:
            half = len(operands) // 2
            a, b = _balanced(type(self), operands[:half]), _balanced(type(self), operands[half:])
        self._link(a, b)

    def leaves(self) -> list:
        return [*self.a.leaves(), *self.b.leaves()]

    def _contains(self, p):
        return self.op(self.a._contains(p), self.b._contains(p))

    def _events(self, o, d, cast) -> Events:
        ea, eb = self.a._events(o, d, cast), self.b._events(o, d, cast)
        sign = -1.0 if isinstance(self, Difference) else 1.0  # B's surfaces face the other way
        ev = Events(np.c_[ea.t, eb.t], np.c_[ea.kind, eb.kind],
                    np.concatenate([ea.normal, sign * eb.normal], 1), np.c_[ea.leaf, eb.leaf])
        from_a = np.c_[np.ones_like(ea.kind, bool), np.zeros_like(eb.kind, bool)]
        order = np.argsort(ev.t, axis=1, kind="stable")
        ev = Events(*(np.take_along_axis(x, order if x.ndim == 2 else order[..., None], 1)
                      for x in (ev.t, ev.kind, ev.normal, ev.leaf)))
        from_a = np.take_along_axis(from_a, order, 1)
        k = ev.kind.astype(np.int64)
        in_a = np.cumsum(np.where(from_a, k, 0), axis=1) > 0
        in_b = np.cumsum(np.where(from_a, 0, k), axis=1) > 0
        inside = self.op(in_a, in_b)
        before = np.c_[self.op(np.zeros((len(o), 1), bool), np.zeros((len(o), 1), bool)),
                       inside[:, :-1]]
        return _tied(ev, before, inside, cast.tie)


def _tied(ev: Events, before: np.ndarray, after: np.ndarray, tie: np.ndarray) -> Events:
    """A node's events from its operands' merged, sorted ones and its answer before and
    after each: boundaries within ``tie`` of the previous one are one group (the tie
    rule); a group where the answer changes is one event at its first t, of its
    lowest-numbered leaf; every other boundary is kept silent (kind 0)."""
    n, width = ev.t.shape
    with np.errstate(invalid="ignore"):
        gap = np.diff(ev.t, axis=1) > tie  # (inf - inf: NaN, no gap: padding is one group)
    start = np.c_[np.ones((n, 1), bool), gap]
    end = np.c_[gap, np.ones((n, 1), bool)]
    col = np.broadcast_to(np.arange(width), (n, width))
    first = np.maximum.accumulate(np.where(start, col, 0), axis=1)
    last = np.minimum.accumulate(np.where(end, col, width)[:, ::-1], axis=1)[:, ::-1]
    change = start & (np.take_along_axis(before, first, 1) != np.take_along_axis(after, last, 1))
    # each group's lowest leaf and where it is: the least (leaf, column) key over the group
    key = np.where(ev.leaf >= 0, ev.leaf, 1 << 40) * width + col
    starts = (np.flatnonzero(start.ravel()))
    least = np.minimum.reduceat(key.ravel(), starts)
    group_least = np.repeat(least, np.diff(np.r_[starts, key.size]))
    rep = (group_least % width).reshape(n, width)
    rows = np.arange(n)[:, None]
    leaf = np.where(change, ev.leaf[rows, rep], ev.leaf)
    normal = np.where(change[..., None], ev.normal[rows, rep], ev.normal)
    kind = np.where(change, np.take_along_axis(after, last, 1) * 2 - 1, 0).astype(np.int8)
    return Events(ev.t, kind, normal, leaf)


def _balanced(kind, operands: list[Solid]) -> Solid:
    """``operands[0] op operands[1] op ...`` as a balanced tree (log2 levels)."""
    if len(operands) == 1:
        return operands[0]
    half = len(operands) // 2
    node = kind.__new__(kind)  # (not __init__: the halves are balanced already)
    node._link(_balanced(kind, operands[:half]), _balanced(kind, operands[half:]))
    return node


OUT, IN, MAYBE = 0, 1, 2


class Union(_Boolean):
    """``a | b``: inside either.

    Parameters
    ----------
    a, b : Solid
        The operands.
    """

    op = staticmethod(np.logical_or)

    def _classify(self, lo, hi):
        a, b = self.a._classify(lo, hi), self.b._classify(lo, hi)
        return np.where((a == IN) | (b == IN), IN, np.where((a == OUT) & (b == OUT), OUT,
                                                            MAYBE))

    def _bounds(self):
        a, b = self.a._bounds(), self.b._bounds()
        if a is None or b is None:
            return None
        return np.array([np.minimum(a[0], b[0]), np.maximum(a[1], b[1])])


class Intersection(_Boolean):
    """``a & b``: inside both.

    Parameters
    ----------
    a, b : Solid
        The operands.
    """

    op = staticmethod(np.logical_and)

    def _classify(self, lo, hi):
        a, b = self.a._classify(lo, hi), self.b._classify(lo, hi)
        return np.where((a == OUT) | (b == OUT), OUT, np.where((a == IN) & (b == IN), IN,
                                                               MAYBE))

    def _bounds(self):
        a, b = self.a._bounds(), self.b._bounds()
        if a is None or b is None:
            return a if b is None else b
        lo, hi = np.maximum(a[0], b[0]), np.minimum(a[1], b[1])
        return np.array([lo, np.maximum(hi, lo)])  # (empty: a flat box)


class Difference(_Boolean):
    """``a - b``: inside a and not b (b's surfaces face the other way).

    Parameters
    ----------
    a, b : Solid
        What is kept, and what is cut away.
    """

    @staticmethod
    def op(a, b):
        """The difference of inside-flags: ``a and not b``.

        Parameters
        ----------
        a, b : ndarray
            Bool inside-flags of the operands.
        """
        return a & ~b

    def _classify(self, lo, hi):
        a, b = self.a._classify(lo, hi), self.b._classify(lo, hi)
        return np.where((a == OUT) | (b == IN), OUT, np.where((a == IN) & (b == OUT), IN,
                                                              MAYBE))

    def _bounds(self):
        return self.a._bounds()


class Transformed(Solid):
    """A solid moved by a nonsingular affine matrix (column vectors).

    Parameters
    ----------
    child : Solid
        The solid moved.
    matrix : array_like
        ``(4, 4)`` nonsingular affine matrix, column vectors.
    """

    child: Solid
    matrix: np.ndarray

    def __init__(self, child: Solid, matrix):
        child = _solid(child)
        m = affine_matrix(matrix, "CSG transform")
        if isinstance(child, Transformed):  # (a chain of moves is one move: no depth)
            m = affine_matrix(m @ child.matrix, "CSG transform (composed)")
            child = child.child
        if np.abs(m[:3, 3]).max() >= SIZE_RANGE:
            raise GeometryError(f"CSG translation {_plain(m[:3, 3])} is too large: keep it "
                                f"under {SIZE_RANGE:g}")
        # (its stretch, as sizes are held: volumes cube it, so a scale of 1e150 overflowed
        # float64 in a volume rather than being refused here)
        stretch = np.linalg.svd(m[:3, :3], compute_uv=False)
        if not (stretch.max() < SIZE_RANGE and stretch.min() > 1 / SIZE_RANGE):
            raise GeometryError(f"CSG transform scales by {_plain(stretch)}: keep its scale "
                                f"factors between {1 / SIZE_RANGE:g} and {SIZE_RANGE:g}")
        self.child, self.matrix = child, m
        self.inverse = np.linalg.inv(self.matrix)
        self.width = child.width
        self.n_leaves = child.n_leaves
        self.depth = child.depth + 1

    def leaves(self) -> list:
        return self.child.leaves()

    def _contains(self, p):
        return self.child._contains(p @ self.inverse[:3, :3].T + self.inverse[:3, 3])

    def _classify(self, lo, hi):
        """(the child sees the box's image as the box around it: conservative)"""
        c = box_corners(np.stack([lo, hi], 1)) @ self.inverse[:3, :3].T + self.inverse[:3, 3]
        return self.child._classify(c.min(1), c.max(1))

    def _bounds(self):
        b = self.child._bounds()
        if b is None:
            return None
        c = box_corners(b) @ self.matrix[:3, :3].T + self.matrix[:3, 3]
        return np.array([c.min(0), c.max(0)])

    def _events(self, o, d, cast) -> Events:
        m = self.inverse
        ev = self.child._events(o @ m[:3, :3].T + m[:3, 3], d @ m[:3, :3].T, cast)
        # normals follow by the inverse transpose (t is unchanged: rays are not rescaled)
        ev.normal = ev.normal @ m[:3, :3]
        return ev
