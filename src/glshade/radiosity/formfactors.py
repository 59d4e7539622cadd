"""Form factors ``F[i, j]`` -- the fraction of the energy leaving patch i that arrives at
patch j -- by GPU hemicubes, one row per shooting patch.

A hemicube at a patch's centre gives the factor from that *point* to each patch; for a
patch that is large next to its distance from others, that is not the patch-to-patch
factor. So each shooter is integrated over by Gauss quadrature with about ``s^2``
points (``s`` from the patch's size against the distance to its nearest non-coplanar
neighbour: ``s = ceil(FACTOR diameter / d)``, at most 8; one point is the centre) and the
rows averaged with the quadrature weights.
Each hemicube is turned about the normal by a random angle (seeded), so that aliasing
against the pixel grid does not repeat from one patch to the next.

The near field. Those few points integrate a receiver's factor over the shooter well only
where it varies slowly across the shooter: where the receiver's distance ``g`` from it (the
gap of their bounding spheres, or the receiver's height above the shooter's plane, the
larger) is at least ``NEAR`` times the spacing of the points, ``D / s``. A receiver nearer
than that -- a small patch close over a large emitter, rectangles sharing an edge, the
Cornell box's light just under its ceiling -- gets its factor again from the exact
point-to-polygon factor (:mod:`.contour`) at ``m^2`` Gauss points, ``m = ceil(NEAR D /
max(g, D / MAX_NEAR_POINTS))`` in ``[2 s, MAX_NEAR_POINTS]``, times the share of it the
hemicubes saw unoccluded (their value over the contour factor at their own points: the
hemicubes keep the visibility, the contour integral the geometry). Measured against closed
forms (tests/radiosity: the near-field family), that leaves under 0.3% where the hemicubes
alone were off by up to 85% (a 0.05-high square over an emitter 40 times its size); the
bound of an ``m``-point Gauss rule on a factor whose width is ``g`` over a shooter ``D``
across is about ``rho^(-2m)``, ``rho = (g + sqrt(D^2/4 + g^2)) / (D / 2)``. A shooter with
covered points keeps its hemicube values (its open part is not known finely enough).

Both the nearest receiver (for ``s``) and the near receivers are sought only among the
patches whose grid cells could hold them (:mod:`glshade.geometry.cells`): a 20,480-patch
sphere under a light set up in 1.3 s where comparing every pair took 81 s.
"""

from __future__ import annotations

from collections import OrderedDict

import numpy as np

from ..errors import InputError, OptionError
from ..geometry.cells import near_blocks
from ..modes import Backend
from ..options import HEMICUBE_RESOLUTION
from .contour import clip_to_plane, point_polygon_factors
from .problem import PatchScene

__all__ = ["FormFactors", "quadrature_counts", "near_pairs", "delta_form_factors",
           "HEMICUBE_RESOLUTION"]

MAX_QUADRATURE = 8
#: the set-up shows its progress (where output is watched) for more patches than this
SETUP_PROGRESS = 20_000


FACTOR = 1.5
def delta_form_factors(n: int) -> np.ndarray:
    """The atlas of delta form factors ``(N, 3N)``, row 0 at the bottom (GL's order): the
    top face in columns ``0..N``, the side faces as ``N x N/2`` halves stacked two by two in
    columns ``N..2N`` and ``2N..3N``. They sum to 1 as N grows.

    Parameters
    ----------
    n : int
        The hemicube's top face, pixels a side.
    """
    d = 2.0 / n
    c = -1 + (np.arange(n) + 0.5) * d
    x, y = np.meshgrid(c, c)  # (row, column)
    top = d * d / (np.pi * (x * x + y * y + 1) ** 2)
    z = (np.arange(n // 2) + 0.5) * d
    xs, zs = np.meshgrid(c, z)
    side = zs * d * d / (np.pi * (xs * xs + zs * zs + 1) ** 2)
    atlas = np.zeros((n, 3 * n))
    atlas[:, :n] = top
    for k in range(4):
        col, row = n + (k // 2) * n, (k % 2) * (n // 2)
        atlas[row:row + n // 2, col:col + n] = side
    return atlas



#: a quadrature point whose hemicube meets back faces over more than this share is covered
COVERED = 0.5
#: a receiver nearer than NEAR point spacings of a shooter's quadrature is near
NEAR = 1.5
#: Gauss points a side at most for a near pair
MAX_NEAR_POINTS = 64
#: Gauss points a side at least where the receiver touches the shooter's plane (the factor's
#: slope is unbounded at the line where they meet)
TOUCHING_POINTS = 8


def _extents(p) -> tuple[np.ndarray, np.ndarray]:
    """Each patch's diameter D and circumradius about its centre R, (P,) each."""
    corners = polygons(p)  # (P, 4, 3)
    extent = np.linalg.norm(corners[:, :, None] - corners[:, None, :], axis=3).max((1, 2))
    radius = np.linalg.norm(corners - p.centers[:, None], axis=2).max(1)
    return extent, radius


def polygons(p) -> np.ndarray:
    """Each patch's corners (P, 4, 3), a triangle's last one repeated (an edge of length 0)."""
    c = np.where(p.corners >= 0, p.corners, p.corners[:, 2:3])
    return p.vertices[c]


def near_pairs(problem: PatchScene, counts: np.ndarray, progress=None
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The receivers too near each shooter for its ``counts`` (P,) quadrature points (see
    the module's docstring): (first (P+1,), receiver (N,), points a side (N,)), the
    receivers of shooter i at ``receiver[first[i]:first[i+1]]``. Receivers wholly behind
    or in the shooter's plane get nothing and are not listed.

    Parameters
    ----------
    problem : PatchScene
        The patches.
    counts : ndarray
        ``(P,)`` quadrature points a side of each shooter.
    progress : object with ``update`` or None
        Told of each shooter done.
    """
    p = problem.patches
    c, n = p.centers, p.normals
    extent, radius = _extents(p)
    corners = polygons(p)
    spacing = extent / counts
    rows, cols, widths = [], [], []
    # (a near pair's gap is under NEAR spacings: its centres are within that and both radii)
    for si, rj in near_blocks(c, NEAR * spacing + radius, radius):
        gap = np.linalg.norm(c[None, rj] - c[si, None], axis=2) - radius[si, None] - \
            radius[rj]
        # heights of every receiver's corners above each shooter's plane: (rows, cols, 4)
        height = np.einsum("jkd,id->ijk", corners[rj], n[si]) - \
            np.einsum("id,id->i", c[si], n[si])[:, None, None]
        tol = 1e-9 * extent[si, None]
        above = height.max(axis=2) > tol
        low = height.min(axis=2)
        width = np.maximum(gap, low)
        near = above & (width < NEAR * spacing[si, None]) & (si[:, None] != rj[None, :])
        width[low <= tol] = -1.0  # (touching the shooter's plane: marked for the rule below)
        i, j = np.nonzero(near)
        rows.append(si[i])
        cols.append(rj[j])
        widths.append(width[i, j])
        if progress:
            progress.update(len(si))
    i, j, w = np.concatenate(rows), np.concatenate(cols), np.concatenate(widths)
    by = np.lexsort((j, i))
    i, j, w = i[by], j[by], w[by]
    d = extent[i]
    m = np.ceil(NEAR * d / np.maximum(w, d / MAX_NEAR_POINTS))
    m = np.where(w < 0, TOUCHING_POINTS, m)
    m = np.maximum(m, 2 * counts[i])
    m = np.clip(m, 1, MAX_NEAR_POINTS).astype(np.int64)
    first = np.searchsorted(i, np.arange(p.n_patches + 1))
    return first, j, m


def quadrature_counts(problem: PatchScene, factor: float = FACTOR, progress=None
                      ) -> np.ndarray:
    """Quadrature points a side for each shooter: ``ceil(factor D / d)`` in [1,
    MAX_QUADRATURE], D the patch's diameter, d the distance to the nearest patch centre not
    in its plane (a long thin patch needs points along its length, whatever its area).

    Parameters
    ----------
    problem : PatchScene
        The patches.
    factor : float
        Points a side per (patch size / distance to the nearest receiver).
    progress : object with ``update`` or None
        Told of each patch done.
    """
    p = problem.patches
    c, n = p.centers, p.normals
    extent = _extents(p)[0]
    nearest = np.full(p.n_patches, np.inf)
    # (a receiver further than factor D gives one point a side: only nearer ones are sought)
    for rows, cols in near_blocks(c, factor * extent, np.zeros(p.n_patches)):
        d = c[None, cols, :] - c[rows, None, :]
        dist = np.linalg.norm(d, axis=2)
        off_plane = np.abs(np.einsum("ijk,ik->ij", d, n[rows]))
        coplanar = (off_plane <= 1e-6 * (dist + 1e-300)) | (dist == 0)
        dist[coplanar] = np.inf
        nearest[rows] = dist.min(axis=1)
        if progress:
            progress.update(len(rows))
    s = np.ceil(factor * extent / nearest)
    return np.clip(np.nan_to_num(s, nan=1.0, posinf=1.0), 1, MAX_QUADRATURE).astype(np.int64)


class FormFactors:
    """Rows of the form-factor matrix of ``problem`` from GPU hemicubes of ``resolution``
    (the top face's pixels a side). ``quadrature``: Gauss points per shooter triangle
    side, "auto" (:func:`quadrature_counts`) or a whole number for every patch (not MSAA
    ``samples``: hemicubes are never multisampled). Rows are cached (up to
    ``cache_mb``); ``close()`` releases the GL objects (and the context, if made here).

    Parameters
    ----------
    problem : PatchScene
        The patches.
    resolution : int
        The hemicube's top face, pixels a side.
    quadrature : int or str
        Gauss points a shooter triangle's side, or ``"auto"`` (:func:`quadrature_counts`).
    seed : int
        The hemicubes' random turns.
    context : RenderContext or None
        A context to draw in (None: one made here).
    backend : Backend or str
        The backend of a context made here.
    cache_mb : float
        The rows kept in memory, in MiB.
    progress : bool, object with ``update``, or None
        The set-up's progress (each patch's quadrature and near receivers, found among the
        patches near it: seconds for tens of thousands): None a bar where output is watched
        for more than ``SETUP_PROGRESS`` patches, True always, False never.
    """

    def __init__(self, problem: PatchScene, resolution: int = HEMICUBE_RESOLUTION,
                 quadrature: int | str = "auto",
                 seed: int = 0, context=None, backend: Backend | str = "auto",
                 cache_mb: float = 512, progress=None):
        from ..parallel.progress import as_progress
        from ..render.context import create_context
        from ..render.passes.hemicube import Hemicube

        self.problem = problem
        p = problem.patches
        if quadrature != "auto" and (isinstance(quadrature, str) or
                                     int(quadrature) != quadrature or quadrature < 1):
            raise OptionError(f"quadrature must be 'auto' or a whole number >= 1, got "
                              f"{quadrature!r}")
        if progress is None and p.n_patches <= SETUP_PROGRESS:
            progress = False
        bar, owned = as_progress(progress, 2 * p.n_patches if quadrature == "auto"
                                 else p.n_patches, "patches set up")
        try:
            self._set_up(problem, quadrature, bar)
        finally:
            if owned:
                bar.close()
        self.near_corrected = 0
        self._rng = np.random.default_rng(seed)
        self._owns = context is None
        self.context = context or create_context(backend)
        try:
            self.hemicube = Hemicube(self.context, resolution, delta_form_factors)
            self.hemicube.upload(p.vertices, p.triangles, p.triangle_patch, p.n_patches)
        except BaseException:
            self.close()
            raise
        self._cache: OrderedDict[int, np.ndarray] = OrderedDict()
        self._cache_rows = max(1, int(cache_mb * 2**20 // (8 * max(p.n_patches, 1))))
        self.hemicubes_drawn = 0

    def _set_up(self, problem: PatchScene, quadrature, bar) -> None:
        """Each shooter's quadrature points and near receivers."""
        p = problem.patches
        if quadrature == "auto":
            self.quadrature = quadrature_counts(problem, progress=bar)
        else:  # (a whole number: checked before the bar)
            self.quadrature = np.full(p.n_patches, int(quadrature))
        points, owner, weight = p.sample_points(self.quadrature)
        self._points, self._weights = points, weight
        self._first = np.searchsorted(owner, np.arange(p.n_patches + 1))
        self._near = near_pairs(problem, self.quadrature, progress=bar)
        self._polygons = polygons(p)

    @property
    def resolution(self) -> int:
        return self.hemicube.resolution

    def _tangents(self, normal: np.ndarray, count: int) -> np.ndarray:
        """(count, 3) unit tangents of ``normal``, each turned by its own random angle."""
        a = np.array([1.0, 0.0, 0.0]) if abs(normal[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        t = np.cross(normal, a)
        t /= np.linalg.norm(t)
        b = np.cross(normal, t)
        angle = self._rng.uniform(0, 2 * np.pi, count)[:, None]
        return np.cos(angle) * t + np.sin(angle) * b

    def row(self, i: int) -> np.ndarray:
        """``F[i, :]`` (P,): from patch i to every patch (``F[i, i] = 0``).

        Parameters
        ----------
        i : int
            The shooting patch.
        """
        found = self._cache.get(i)
        if found is not None:
            self._cache.move_to_end(i)
            return found
        n = self.problem.patches.normals[i]
        a, b = self._first[i], self._first[i + 1]
        turns = self._tangents(n, b - a)  # (one random turn per cube)
        back = np.zeros(b - a)
        rows = self.hemicube.rows(self._points[a:b], n, turns, back)
        # a point of the patch that sees mostly back faces is covered (under a block that
        # stands on the floor, above a light hung under the ceiling): light neither reaches
        # nor leaves it, so the patch's energy leaves from its other points
        weights = np.where(back > COVERED, 0.0, self._weights[a:b])
        total = weights.sum()
        weights = weights / total if total > 0 else self._weights[a:b]
        out = weights @ rows
        if not (back > COVERED).any():
            self._near_field(i, out, weights)
        self.hemicubes_drawn += b - a
        out[i] = 0.0
        self._cache[i] = out
        if len(self._cache) > self._cache_rows:
            self._cache.popitem(last=False)
        return out

    def _near_field(self, i: int, out: np.ndarray, weights: np.ndarray) -> None:
        """Replace ``out[j]`` for shooter i's near receivers j by the contour factor over
        finely spaced points times the visible share the hemicubes saw (in place)."""
        first, receiver, m = self._near
        lo, hi = first[i], first[i + 1]
        if lo == hi:
            return
        p = self.problem.patches
        js, ms = receiver[lo:hi], m[lo:hi]
        n = p.normals[i]
        clipped = clip_to_plane(self._polygons[js], np.broadcast_to(p.centers[i], (len(js), 3)),
                                np.broadcast_to(n, (len(js), 3)))
        coarse_pts = self._points[self._first[i]:self._first[i + 1]]
        coarse = point_polygon_factors(coarse_pts, n, clipped, p.normals[js]) @ weights
        seen = out[js]
        fine = np.zeros(len(js))
        for size in np.unique(ms):  # (a handful of distinct point counts)
            pts, _, w = p.sample_points(np.array([size]), only=np.array([i]))
            k = ms == size
            fine[k] = point_polygon_factors(pts, n, clipped[k], p.normals[js[k]]) @ w
        ok = (coarse > 0) & (seen > 0)
        out[js[ok]] = fine[ok] * (seen[ok] / coarse[ok])
        self.near_corrected += int(ok.sum())

    def matrix(self, progress=None) -> np.ndarray:
        """The whole ``(P, P)`` matrix (small scenes: P^2 numbers).

        Parameters
        ----------
        progress : bool, tqdm-like or None
            The progress bar.
        """
        n = self.problem.n_patches
        if n > 20_000:
            raise InputError(f"a full form-factor matrix of {n:,} patches needs "
                             f"{n * n * 8 / 2**30:.1f} GiB; use progressive refinement, "
                             "or larger patches")
        out = np.empty((n, n))
        for i in range(n):
            out[i] = self.row(i)
            if progress:
                progress.update()
        return out

    def close(self) -> None:
        hemicube = getattr(self, "hemicube", None)
        if hemicube is not None:
            hemicube.release()
        if self._owns and self.context is not None:
            self.context.release()
            self.context = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
