"""A solid's screen proxy: the convex polygon a ray-cast solid is drawn as, so that only
pixels whose rays can meet the solid run the ray cast.

Why: on a software rasteriser every pixel of the proxy pays the whole ray cast (a
fragment program cannot skip work for a group of pixels), and a solid's bounding box covers
far more pixels than the solid (the benchmark's 7-leaf part at 512x512: its box 95,000,
the solid 69,600, this polygon 79,600).

Two facts make the polygon conservative and cheap:

- a solid lies inside the union of the leaves it counts *positively* (under an even number
  of right operands of differences): a point in none of them is in none of the booleans'
  left sides of differences, of any union or intersection of them -- so inside the convex
  hull of points whose hulls hold those leaves (:func:`hull_points`: a box's corners,
  circumscribed polygons for round leaves);
- the projection of a convex set lying wholly in front of the eye is the convex hull of
  its projected points, which their k-DOP contains (the polygon of K half-planes
  ``d_k . x <= max_p d_k . p``; every one touches the hull, so its corners are the
  crossings of neighbouring lines). The smaller of the hull's and the box's is drawn
  (:func:`screen_polygon`), cut to the screen; the box is first cut by the near plane
  (where the rays start: nothing before it shows), so a camera inside the solid still
  gets a polygon -- the whole screen.

Why 16 sides: a tiled rasteriser shades the pixel blocks along a triangle's inner edges
once for each triangle, so a finer polygon's thinner fan costs more than its few pixels
saved (measured: 16 sides faster than 8, 12 and 32; scissored bands slower still).

Pure numpy; shapes in each docstring.
"""

from __future__ import annotations

import numpy as np

from ..geometry.transforms import box_corners
from . import leaves as L

__all__ = ["hull_points", "screen_polygon", "DIRECTIONS"]

#: directions of the screen polygon (its corners); the polygon is at most 1/cos(pi/K) - 1
#: (2% at 16) wider than the points' hull
DIRECTIONS = 16
_SIDES = 24  # sides of a round leaf's circumscribed polygons
#: more points than this (many positive leaves) and the solid's box alone is the proxy
MAX_POINTS = 20_000


def _ring(radius: float, y: float) -> np.ndarray:
    """(S, 3) corners of a polygon circumscribing the circle of ``radius`` at height y."""
    a = np.arange(_SIDES) * (2 * np.pi / _SIDES)
    r = radius / np.cos(np.pi / _SIDES)
    return np.c_[r * np.cos(a), np.full(_SIDES, y), r * np.sin(a)]


def leaf_points(leaf) -> np.ndarray | None:
    """(N, 3) points in the leaf's own frame whose convex hull holds the leaf; None for an
    unbounded leaf (a half-space). A sphere: the circumscribed rings of a circumscribed
    profile (the hull of the rings holds the solid of revolution of the profile, which
    holds the ball)."""
    if isinstance(leaf, L.Box):
        return box_corners([-leaf.half, leaf.half])
    if isinstance(leaf, L.Sphere):
        n = 8  # profile sides from pole to pole
        phi = np.linspace(-np.pi / 2, np.pi / 2, n + 1)
        rho = leaf.radius / np.cos(np.pi / (2 * n))
        return np.concatenate([_ring(rho * np.cos(p), rho * np.sin(p)) for p in phi])
    if isinstance(leaf, L.Cylinder):
        return np.concatenate([_ring(leaf.radius, -leaf.h), _ring(leaf.radius, leaf.h)])
    if isinstance(leaf, L.Cone):
        return np.concatenate([_ring(leaf.radius, -leaf.apex), [[0.0, leaf.apex, 0.0]]])
    if isinstance(leaf, L.Torus):
        outer = leaf.R + leaf.r
        return np.concatenate([_ring(outer, -leaf.r), _ring(outer, leaf.r)])
    return None


def hull_points(leaves: list) -> np.ndarray | None:
    """(N, 3) world points whose convex hull holds a solid, from its leaves ``[(leaf,
    leaf -> world matrix (4, 4), sign)]`` (sign > 0: counted positively); None where a
    positive leaf is unbounded or the points would be too many to project each frame.

    Parameters
    ----------
    leaves : list
        ``[(leaf, leaf -> world matrix (4, 4), sign)]``.
    """
    parts = []
    for leaf, matrix, sign in leaves:
        if sign <= 0:
            continue
        p = leaf_points(leaf)
        if p is None:
            return None
        parts.append(p @ matrix[:3, :3].T + matrix[:3, 3])
        if sum(len(x) for x in parts) > MAX_POINTS:
            return None
    return np.concatenate(parts) if parts else None


def _in_front(clip: np.ndarray, edges: np.ndarray | None) -> np.ndarray | None:
    """Clip coordinates (N, 4) of a convex set's points, cut to the part in front of the
    near plane (z >= -w: where the rays start, so nothing before it shows): the points in
    front and, given the set's ``edges`` (E, 2) point indices, where edges cross the plane;
    None where a point is behind it and no edges are given."""
    ahead = clip[:, 2] + clip[:, 3]
    front = ahead >= 0
    if front.all():
        return clip
    if edges is None:
        return None
    i, j = edges[:, 0], edges[:, 1]
    cross = front[i] != front[j]
    f = ahead[i[cross]] / (ahead[i[cross]] - ahead[j[cross]])
    return np.concatenate([clip[front], clip[i[cross]]
                           + f[:, None] * (clip[j[cross]] - clip[i[cross]])])


def _polygon(clip: np.ndarray, directions: np.ndarray, grow: float) -> np.ndarray:
    """The k-DOP corners (K, 2) of points' projections (clip coordinates (N, 4), all at or
    beyond the near plane, so w > 0), grown by ``grow``."""
    ndc = clip[:, :2] / clip[:, 3:]
    s = (ndc @ directions.T).max(0) + grow  # (K,) supports
    # every line touches the points' hull (at the point giving its support), so the
    # corners are the crossings of neighbouring lines
    nxt = np.roll(np.arange(len(s)), -1)
    a = np.stack([directions, directions[nxt]], 1)  # (K, 2, 2)
    return np.linalg.solve(a, np.stack([s, s[nxt]], 1)[..., None])[..., 0]


def _clip_to(corners: np.ndarray, reach: float) -> np.ndarray:
    """A convex counter-clockwise polygon (K, 2) cut to the square |x|, |y| <= reach
    (Sutherland-Hodgman: four cuts, each over every edge at once); (0, 2) if none is
    left."""
    for axis, sign in ((0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)):
        if len(corners) == 0:
            break
        inside = sign * corners[:, axis] <= reach
        if inside.all():
            continue
        nxt = np.roll(corners, -1, 0)
        nxt_inside = np.roll(inside, -1)
        with np.errstate(divide="ignore", invalid="ignore"):  # (parallel edges: unused)
            f = (reach - sign * corners[:, axis]) / (sign * (nxt[:, axis] - corners[:, axis]))
            crossing = corners + f[:, None] * (nxt - corners)
        # each edge a -> b gives a where a is inside, then the crossing if it changes side
        keep = np.stack([inside, inside != nxt_inside], 1)  # (K, 2)
        corners = np.stack([corners, crossing], 1)[keep]
    return corners


def _area(corners: np.ndarray) -> float:
    if len(corners) < 3:
        return 0.0
    x, y = corners[:, 0], corners[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


_BOX_EDGES = np.array([[i, i ^ b] for i in range(8) for b in (1, 2, 4) if i < i ^ b])
_SCREEN = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])


def screen_polygon(view_proj: np.ndarray, box: np.ndarray, points: np.ndarray | None,
                   viewport: tuple[int, int]) -> np.ndarray:
    """The proxy's corners (M, 2) in NDC, counter-clockwise, within the screen (grown by
    its margin): the smaller of the k-DOPs of the solid's box (cut by the near plane) and
    of its hull points (where all are in front of it); (0, 2) where the solid is off
    screen. ``view_proj (4, 4)`` world -> clip, ``box (2, 3)`` the solid's bounds,
    ``points (N, 3)`` from :func:`hull_points` or None, ``viewport`` (width, height) in
    pixels: the polygon is grown by two pixels against rounding.

    Parameters
    ----------
    view_proj : ndarray
        ``(4, 4)`` world to clip.
    box : ndarray
        ``(2, 3)`` the solid's world box.
    points : ndarray or None
        ``(N, 3)`` hull points (None: the box's corners).
    viewport : (int, int)
        The viewport's width and height.
    """
    angles = np.arange(DIRECTIONS) * (2 * np.pi / DIRECTIONS)
    d = np.c_[np.cos(angles), np.sin(angles)]  # (K, 2)
    corners = box_corners(box)  # (index bits: x 4, y 2, z 1: _BOX_EDGES)
    grow = 4.0 / min(viewport)
    found = []
    for pts, edges in ((corners, _BOX_EDGES), (points, None)):
        if pts is None:
            continue
        clip = _in_front(pts @ view_proj[:, :3].T + view_proj[:, 3], edges)
        if clip is None:
            continue
        if len(clip) == 0:
            return np.zeros((0, 2))  # wholly behind the near plane
        found.append(_clip_to(_polygon(clip, d, grow), 1.0 + grow))
    best = min(found, key=_area)
    return best if len(best) >= 3 and _area(best) > 0 else np.zeros((0, 2))
