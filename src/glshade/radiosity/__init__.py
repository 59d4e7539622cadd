"""Radiosity for diffuse scenes: patches (``PatchScene``), form factors by GPU hemicubes
(``FormFactors``), progressive refinement and Gauss-Seidel solvers, and the display of a
solution in the renderer's ``radiosity`` mode (vertex radiosities, Gouraud-interpolated).

    from glshade.radiosity import cornell_scene, solve
    scene, camera = cornell_scene()
    solution = solve(scene, patch_size=40, until=0.01)
    image = renderer.render(solution.scene(), camera, "radiosity")
"""

from __future__ import annotations

import enum

import numpy as np

from ..modes import Backend, parse_enum
from .cornell import CORNELL_CAMERA, CORNELL_MATERIALS, cornell_parts, cornell_scene
from ..options import HEMICUBE_RESOLUTION
from .formfactors import FormFactors, quadrature_counts
from .problem import PatchScene
from .solvers import Solution, gauss_seidel, progressive

__all__ = ["PatchScene", "FormFactors", "Solution", "Method", "progressive", "gauss_seidel",
           "solve", "quadrature_counts", "cornell_scene", "cornell_parts", "CORNELL_CAMERA",
           "CORNELL_MATERIALS"]


class Method(str, enum.Enum):
    """How the radiosity equation is solved."""

    PROGRESSIVE = "progressive"    # shoot the most unshot energy first (Cohen et al. 1988)
    GAUSS_SEIDEL = "gauss-seidel"  # gather over the full matrix (small scenes)
    MONTE_CARLO = "monte-carlo"    # light tracing, no form factors (montecarlo.py)

    @classmethod
    def parse(cls, value: object) -> Method:
        """A Method or its name; a bad name lists the choices.

        Parameters
        ----------
        value : Method or str
            A member or its name.
        """
        return parse_enum(cls, value, "radiosity method")


def solve(scene, patch_size: float | None = None, *, method: Method | str = Method.PROGRESSIVE,
          until: float = 0.01, max_shots: int | None = None, hemicube: int = HEMICUBE_RESOLUTION,
          quadrature: int | str = "auto", seed: int = 0, context=None,
          backend: Backend | str = Backend.AUTO, progress=None, on_shot=None,
          particles: int | None = None) -> Solution:
    """Patch ``scene``, compute form factors on the GPU and solve: ``method`` is
    PROGRESSIVE (until the unshot fraction is below ``until``, or ``max_shots``) or
    GAUSS_SEIDEL (the full matrix; small scenes). ``quadrature``: Gauss points a side per
    shooter (:func:`quadrature_counts`). MONTE_CARLO traces ``particles`` light particles
    (default 200,000) instead, sharing no form-factor code with the others; its
    ``Solution.se`` is each patch's standard error. ``progress``: a bar (a notebook's
    widget, a terminal's line), None to decide by where output goes, False for none, or an
    object with ``update(n, note)``.

    Parameters
    ----------
    scene : Scene
        The models (emission and reflectance from their materials).
    patch_size : float or None
        About how long a patch's edge is.
    method : Method or str
        ``"progressive"``, ``"gauss-seidel"`` or ``"monte-carlo"``.
    until : float
        Progressive: stop below this unshot fraction.
    max_shots : int or None
        Progressive: the most shots (iterations for Gauss-Seidel).
    hemicube : int
        The hemicube's top face, pixels a side.
    quadrature : int or str
        Gauss points a shooter's side, or ``"auto"``.
    seed : int
        The hemicubes' turns (and Monte Carlo's particles).
    context : RenderContext or None
        A context to draw in.
    backend : Backend or str
        The backend of a context made here.
    progress : bool, tqdm-like or None
        The progress bar.
    on_shot : callable or None
        ``on_shot(solution, shots)`` after each shot.
    particles : int or None
        Monte Carlo's light particles (default 200,000).
    """
    from ..parallel.progress import as_progress

    from .solvers import check_converges

    chosen = Method.parse(method)
    problem = PatchScene.from_scene(scene, patch_size)
    if chosen is not Method.MONTE_CARLO:  # (particles end by count: it always ends)
        check_converges(problem)
    unit = "batches" if chosen is Method.MONTE_CARLO else "shots" \
        if chosen is Method.PROGRESSIVE else "shooters"
    bar, owned = as_progress(progress, None, unit)
    try:
        return _solve(problem, chosen, until, max_shots, hemicube, quadrature, seed, context,
                      backend, bar, on_shot, particles)
    finally:
        if owned:
            bar.close()


def _solve(problem, chosen, until, max_shots, hemicube, quadrature, seed, context, backend,
           progress, on_shot, particles) -> Solution:
    if chosen is Method.MONTE_CARLO:  # (no GL, no form factors: the independent solution)
        from .montecarlo import light_trace

        mc = light_trace(problem, particles or 200_000, seed=seed, progress=progress)
        solution = Solution(problem, mc.radiosity, np.zeros_like(mc.radiosity),
                            "Monte Carlo light tracing")
        solution.history.append((0.0, mc.particles, 0.0))
        solution.se = mc.se
        solution.converged = mc.converged  # (False: particles stopped at MAX_BOUNCES)
        return solution
    with FormFactors(problem, hemicube, quadrature, seed, context, backend,
                     progress=False if progress is None else None) as ff:
        if chosen is Method.PROGRESSIVE:
            return progressive(ff, until, max_shots, progress, on_shot)
        return gauss_seidel(ff, progress=progress)
