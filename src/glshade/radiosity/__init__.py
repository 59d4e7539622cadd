"""Radiosity for diffuse scenes: patches (``PatchScene``), form factors by GPU hemicubes
(``FormFactors``), progressive refinement and Gauss-Seidel solvers, and the display of a
solution in the renderer's ``radiosity`` mode (vertex radiosities, Gouraud-interpolated).

    from glshade.radiosity import cornell_scene, solve
    scene, camera = cornell_scene()
    solution = solve(scene, patch_size=40, until=0.01)
    image = renderer.render(solution.scene(), camera, "radiosity")
"""

from __future__ import annotations

from .cornell import CORNELL_CAMERA, CORNELL_MATERIALS, cornell_parts, cornell_scene
from .formfactors import FormFactors, sample_counts
from .problem import PatchScene
from .solvers import Solution, gauss_seidel, progressive

__all__ = ["PatchScene", "FormFactors", "Solution", "progressive", "gauss_seidel", "solve",
           "sample_counts", "cornell_scene", "cornell_parts", "CORNELL_CAMERA",
           "CORNELL_MATERIALS"]


def solve(scene, patch_size: float | None = None, *, method: str = "progressive",
          until: float = 0.01, max_shots: int | None = None, hemicube: int = 128,
          samples="auto", seed: int = 0, context=None, backend: str = "auto",
          progress=None, on_shot=None) -> Solution:
    """Patch ``scene``, compute form factors on the GPU and solve: ``method`` is
    "progressive" (until the unshot fraction is below ``until``, or ``max_shots``) or
    "gauss-seidel" (the full matrix; small scenes)."""
    from ..errors import InputError

    if method not in ("progressive", "gauss-seidel"):
        raise InputError(f"method must be 'progressive' or 'gauss-seidel', got {method!r}")
    problem = PatchScene.from_scene(scene, patch_size)
    with FormFactors(problem, hemicube, samples, seed, context, backend) as ff:
        if method == "progressive":
            return progressive(ff, until, max_shots, progress, on_shot)
        return gauss_seidel(ff, progress=progress)
