"""Analytic reference images: per-pixel ray casting of the exact surfaces that meshes
approximate (sphere primitives, and the ellipsoids transforms make of them), lit by the
numpy lighting twin. The truth that flat, Gouraud and Phong shading are measured against."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..errors import ComparisonError
from ..scene import Camera, Scene
from .lighting import face_viewer, light_intensity, view_dir

__all__ = ["pixel_rays", "raycast_scene", "has_analytic_surfaces"]


def pixel_rays(camera: Camera, width: int, height: int):
    """World-space ray origins and unit directions through pixel centres ``(H, W, 3)``,
    row 0 at the top: :meth:`Camera.rays`, kept under the name the CPU twins use.

    Parameters
    ----------
    camera : Camera
        The view.
    width, height : int
        The image's size in pixels.
    """
    return camera.rays((width, height))


def has_analytic_surfaces(scene: Scene) -> bool:
    """Whether every visible model knows the exact surface it approximates.

    Parameters
    ----------
    scene : Scene
        The scene.
    """
    visible = [m for m in scene.models if m.visible]
    return bool(visible) and all(m.mesh.analytic is not None for m in visible)


def raycast_scene(scene: Scene, camera: Camera, width: int, height: int
                  ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Colour ``(H, W, 3)`` in [0, 1] (linear) and coverage ``(H, W)`` of the exact
    surfaces of a scene whose models all carry one (``Mesh.analytic``).

    Parameters
    ----------
    scene : Scene
        Models that know their exact surfaces (``Mesh.analytic``).
    camera : Camera
        The view.
    width, height : int
        The image's size in pixels.
    """
    if not has_analytic_surfaces(scene):
        raise ComparisonError("the analytic reference needs meshes that know their exact "
                              "surface (primitive:icosphere, primitive:uv_sphere); use "
                              "reference='phong-fine' (or --reference phong-fine) for other "
                              "meshes")
    o, d = pixel_rays(camera, width, height)
    best_t = np.full((height, width), np.inf)
    color = np.zeros((height, width, 3))
    lights = scene.lights_for(camera)
    for model in scene.models:
        if not model.visible:
            continue
        surface = model.mesh.analytic
        assert surface is not None  # (has_analytic_surfaces was checked)
        t, n = surface.transformed(model.transform).intersect(o, d)
        hit = t < best_t
        if not hit.any():
            continue
        p = o + np.where(hit, t, 0)[..., None] * d
        v = view_dir(p, camera)
        n = face_viewer(n, np.einsum("...i,...i", n, -d) < 0)
        shaded = light_intensity(p, n, v, model.material, lights, scene.ambient)
        best_t = np.where(hit, t, best_t)
        color = np.where(hit[..., None], shaded, color)
    return np.clip(color, 0, 1), np.isfinite(best_t)
