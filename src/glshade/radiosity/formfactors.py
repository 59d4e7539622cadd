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
"""

from __future__ import annotations

from collections import OrderedDict

import numpy as np

from ..errors import InputError, OptionError
from ..modes import Backend
from .problem import PatchScene

__all__ = ["FormFactors", "quadrature_counts"]

MAX_QUADRATURE = 8


FACTOR = 1.5
#: a quadrature point whose hemicube meets back faces over more than this share is covered
COVERED = 0.5


def quadrature_counts(problem: PatchScene, factor: float = FACTOR) -> np.ndarray:
    """Quadrature points a side for each shooter: ``ceil(factor D / d)`` in [1,
    MAX_QUADRATURE], D the patch's diameter, d the distance to the nearest patch centre not
    in its plane (a long thin patch needs points along its length, whatever its area)."""
    p = problem.patches
    c, n = p.centers, p.normals
    nearest = np.full(p.n_patches, np.inf)
    step = max(1, 4_000_000 // max(p.n_patches, 1))
    for a in range(0, p.n_patches, step):  # (chunks of rows: memory, not speed)
        d = c[None, :, :] - c[a:a + step, None, :]
        dist = np.linalg.norm(d, axis=2)
        off_plane = np.abs(np.einsum("ijk,ik->ij", d, n[a:a + step]))
        coplanar = (off_plane <= 1e-6 * (dist + 1e-300)) | (dist == 0)
        dist[coplanar] = np.inf
        nearest[a:a + step] = dist.min(axis=1)
    corners = p.vertices[p.corners]  # (P, 4, 3); a triangle's -1 picks some vertex: masked
    corners = np.where((p.corners >= 0)[..., None], corners, corners[:, :1])
    extent = np.linalg.norm(corners[:, :, None] - corners[:, None, :], axis=3).max((1, 2))
    s = np.ceil(factor * extent / nearest)
    return np.clip(np.nan_to_num(s, nan=1.0, posinf=1.0), 1, MAX_QUADRATURE).astype(np.int64)


class FormFactors:
    """Rows of the form-factor matrix of ``problem`` from GPU hemicubes of ``resolution``
    (the top face's pixels a side). ``quadrature``: Gauss points per shooter triangle
    side, "auto" (:func:`quadrature_counts`) or a whole number for every patch (not MSAA
    ``samples``: hemicubes are never multisampled). Rows are cached (up to
    ``cache_mb``); ``close()`` releases the GL objects (and the context, if made here)."""

    def __init__(self, problem: PatchScene, resolution: int = 128,
                 quadrature: int | str = "auto",
                 seed: int = 0, context=None, backend: Backend | str = "auto",
                 cache_mb: float = 512):
        from ..render.context import create_context
        from ..render.hemicube import Hemicube

        self.problem = problem
        p = problem.patches
        if quadrature == "auto":
            self.quadrature = quadrature_counts(problem)
        else:
            if isinstance(quadrature, str) or int(quadrature) != quadrature or quadrature < 1:
                raise OptionError(f"quadrature must be 'auto' or a whole number >= 1, got "
                                  f"{quadrature!r}")
            self.quadrature = np.full(p.n_patches, int(quadrature))
        points, owner, weight = p.sample_points(self.quadrature)
        self._points, self._weights = points, weight
        self._first = np.searchsorted(owner, np.arange(p.n_patches + 1))
        self._rng = np.random.default_rng(seed)
        self._owns = context is None
        self.context = context or create_context(backend)
        try:
            self.hemicube = Hemicube(self.context, resolution)
            self.hemicube.upload(p.vertices, p.triangles, p.triangle_patch, p.n_patches)
        except BaseException:
            self.close()
            raise
        self._cache: OrderedDict[int, np.ndarray] = OrderedDict()
        self._cache_rows = max(1, int(cache_mb * 2**20 // (8 * max(p.n_patches, 1))))
        self.hemicubes_drawn = 0

    @property
    def resolution(self) -> int:
        return self.hemicube.resolution

    def _tangent(self, normal: np.ndarray) -> np.ndarray:
        a = np.array([1.0, 0.0, 0.0]) if abs(normal[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        t = np.cross(normal, a)
        t /= np.linalg.norm(t)
        b = np.cross(normal, t)
        angle = self._rng.uniform(0, 2 * np.pi)
        return np.cos(angle) * t + np.sin(angle) * b

    def row(self, i: int) -> np.ndarray:
        """``F[i, :]`` (P,): from patch i to every patch (``F[i, i] = 0``)."""
        found = self._cache.get(i)
        if found is not None:
            self._cache.move_to_end(i)
            return found
        n = self.problem.patches.normals[i]
        a, b = self._first[i], self._first[i + 1]
        turns = [self._tangent(n) for _ in range(a, b)]  # (one random turn per cube)
        back = np.zeros(b - a)
        rows = self.hemicube.rows(self._points[a:b], n, turns, back)
        # a point of the patch that sees mostly back faces is covered (under a block that
        # stands on the floor, above a light hung under the ceiling): light neither reaches
        # nor leaves it, so the patch's energy leaves from its other points
        weights = np.where(back > COVERED, 0.0, self._weights[a:b])
        total = weights.sum()
        out = (weights / total if total > 0 else self._weights[a:b]) @ rows
        self.hemicubes_drawn += b - a
        out[i] = 0.0
        self._cache[i] = out
        if len(self._cache) > self._cache_rows:
            self._cache.popitem(last=False)
        return out

    def matrix(self, progress=None) -> np.ndarray:
        """The whole ``(P, P)`` matrix (small scenes: P^2 numbers)."""
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
