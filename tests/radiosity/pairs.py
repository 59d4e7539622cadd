"""Two-polygon radiosity problems and the form factor between them."""

import numpy as np

from glshade import Mesh
from glshade.radiosity import PatchScene
from glshade.scene import Material, Scene

LIGHT = Material(emission=(1.0, 1.0, 1.0), reflectance=(0.0, 0.0, 0.0))
BLACK = Material(reflectance=(0.0, 0.0, 0.0))


def pair(first, second, patch_size=100.0) -> PatchScene:
    scene = Scene()
    scene.add(Mesh(first, [list(range(len(first)))]), LIGHT, name="a")
    scene.add(Mesh(second, [list(range(len(second)))]), BLACK, name="b")
    return PatchScene.from_scene(scene, patch_size)


def group_factor(problem, ff) -> float:
    """F from model 0 to model 1: the area-weighted sum over their patches."""
    a = problem.patches.areas
    src, dst = np.flatnonzero(problem.model == 0), np.flatnonzero(problem.model == 1)
    return sum(a[i] * ff.row(i)[dst].sum() for i in src) / a[src].sum()
