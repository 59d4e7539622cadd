"""Per-surface radiosity by path tracing: the area mean of each model's radiosity B,
estimated from points uniform over its area, each point's B by paths leaving it. This is
what radiosity solvers report per surface, so the two can be compared number for number."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..options import check_whole
from .scene import TraceScene

__all__ = ["SurfaceRadiosity", "surface_radiosity"]


@dataclass(frozen=True)
class SurfaceRadiosity:
    """``names`` of the models; ``mean`` (M, 3) area-mean radiosity of each; ``se`` (M, 3)
    its standard error (of the points' spread and the paths' noise together); ``points``
    a model and ``spp`` paths a point.

    Parameters
    ----------
    names : tuple
        The models.
    mean : ndarray
        ``(M, 3)`` each model's area-mean radiosity.
    se : ndarray
        ``(M, 3)`` its standard error.
    points : int
        Points a model.
    spp : int
        Paths a point.
    """

    names: tuple
    mean: np.ndarray
    se: np.ndarray
    points: int
    spp: int

    def __getitem__(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        k = self.names.index(name)
        return self.mean[k], self.se[k]


def probe_rays(scene: TraceScene, points: int, seed: int) -> np.ndarray:
    """(M, points, 2, 3): for each model, points uniform over its area (a triangle by area,
    then a point uniform in it), each as a ray arriving at it along its normal from just
    in front (a path's first hit is then the point itself, seen from its front side)."""
    rng = np.random.default_rng(seed)
    rays = np.zeros((len(scene.names), points, 2, 3))
    h = 1e-4 * scene.size
    for k in range(len(scene.names)):  # (a loop per model, not per point)
        tri = np.flatnonzero(scene.model == k)
        if not len(tri):
            continue
        pick = tri[rng.choice(len(tri), points, p=scene.areas[tri] / scene.areas[tri].sum())]
        a, b = rng.random(points), rng.random(points)
        flip = a + b > 1
        a, b = np.where(flip, 1 - a, a), np.where(flip, 1 - b, b)
        t = scene.triangles[pick]
        x = t[:, 0] + a[:, None] * (t[:, 1] - t[:, 0]) + b[:, None] * (t[:, 2] - t[:, 0])
        n = scene.normals[pick]
        rays[k, :, 0], rays[k, :, 1] = x + h * n, -n
    return rays


def surface_radiosity(scene, points: int = 2048, spp: int = 64, *, seed: int = 0,
                      lights: bool = False, max_depth: int | None = None,
                      backend: str = "auto",
                      context=None) -> SurfaceRadiosity:
    """Each model's area-mean radiosity (front side) by path tracing ``spp`` paths from
    each of ``points`` points. ``lights=False``: emitting surfaces only, as radiosity
    sees the scene.

    Parameters
    ----------
    scene : Scene or TraceScene
        The scene.
    points : int
        Points a model.
    spp : int
        Paths a point.
    seed : int
        The random streams' seed.
    lights : bool
        Trace the scene's lights too (else emitters only).
    max_depth : int or None
        Vertices a path may have.
    backend : str
        The backend of a context made here.
    context : RenderContext or None
        A context to trace in.
    """
    from ..render.context import create_context
    from ..render.passes.pathtrace import GpuPathTracer

    points, spp = check_whole("points", points, 2), check_whole("spp", spp, 2)
    ts = scene if isinstance(scene, TraceScene) else TraceScene.from_scene(scene, lights=lights)
    rays = probe_rays(ts, int(points), seed)
    own = context is None
    ctx = create_context(backend) if own else context
    try:
        with GpuPathTracer(ctx, ts, int(points), len(ts.names), max_depth=max_depth,
                           rays=rays[::-1]) as gpu:
            gpu.run(None, int(spp), seed)
            total, _, _ = gpu.read()
    finally:
        if own:
            ctx.release()
    per_point = total[..., :3] / total[..., 3:4]
    mean = per_point.mean(1)
    se = per_point.std(1, ddof=1) / np.sqrt(points)
    return SurfaceRadiosity(ts.names, mean, se, int(points), int(total[0, 0, 3]))
