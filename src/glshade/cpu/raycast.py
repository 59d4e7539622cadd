"""Analytic reference images: per-pixel ray casting of the exact surfaces that meshes
approximate (sphere primitives, and the ellipsoids transforms make of them) and of point
clouds' spheres, lit by the numpy lighting twin. The truth that flat, Gouraud and Phong
shading are measured against."""

from __future__ import annotations

import dataclasses

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
    from ..modes import PointStyle

    visible = [m for m in scene.models if m.visible]
    clouds = [c for c in scene.clouds if c.visible]
    return bool(visible or clouds) and all(m.mesh.analytic is not None for m in visible) \
        and all(c.cloud.style is PointStyle.SPHERE and c.cloud.pixel_size is None and
                (c.cloud.colors is None or (c.material.ambient is None and
                                            c.material.diffuse is None))
                for c in clouds) and not any(m.visible for m in scene.lines) \
        and not any(s.visible for s in scene.solids) \
        and not any(p.visible for p in scene.patch_models)


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
                              "surface (primitive:icosphere, primitive:uv_sphere) or clouds "
                              "of spheres; use reference='phong-fine' (or --reference "
                              "phong-fine) for other meshes")
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
    for cloud in scene.clouds:
        if cloud.visible:
            best_t, color = _cloud(cloud, camera, o, d, best_t, color, lights, scene.ambient)
    return np.clip(color, 0, 1), np.isfinite(best_t)


#: the points one pass of a cloud's cast takes (its (pixels, points) table's width)
CLOUD_BATCH = 64


def _cloud(model, camera, o, d, best_t, color, lights, ambient):
    """A cloud's spheres cast into ``best_t``/``color``: the textbook quadratic against
    CLOUD_BATCH points at a time; a point's colour scales the colour-borne terms of the
    formula (ambient and diffuse), as the GPU's products do."""
    cloud = model.cloud
    m = model.transform
    centres = cloud.points @ m[:3, :3].T + m[:3, 3]
    radii = cloud.world_radii() * model.scale
    o2, d2 = o.reshape(-1, 3), d.reshape(-1, 3)
    near = np.full(len(o2), np.inf)
    which = np.full(len(o2), -1)
    for start in range(0, len(centres), CLOUD_BATCH):
        c, r = centres[start:start + CLOUD_BATCH], radii[start:start + CLOUD_BATCH]
        oc = o2[:, None, :] - c[None]
        b = np.einsum("pki,pi->pk", oc, d2)
        disc = b * b - (np.einsum("pki,pki->pk", oc, oc) - r[None] ** 2)
        root = np.sqrt(np.maximum(disc, 0))
        t = np.where(-b - root > 0, -b - root, -b + root)
        t[(disc < 0) | (t <= 0)] = np.inf
        k = t.argmin(1)
        tk = t[np.arange(len(t)), k]
        closer = tk < near
        near, which = np.where(closer, tk, near), np.where(closer, start + k, which)
    near = near.reshape(best_t.shape)
    hit = near < best_t
    if not hit.any():
        return best_t, color
    idx = np.where(hit.ravel(), which, 0).reshape(best_t.shape)
    p = o + np.where(hit, near, 0)[..., None] * d
    n = (p - centres[idx]) / radii[idx][..., None]
    n = face_viewer(n, np.einsum("...i,...i", n, -d) < 0)
    v = view_dir(p, camera)
    if cloud.colors is None:
        shaded = light_intensity(p, n, v, model.material, lights, ambient)
    else:  # (ambient and diffuse for a white surface, times the point's colour; specular)
        white = dataclasses.replace(model.material, color=(1.0, 1.0, 1.0), ks=0.0,
                                    specular=None)
        shine = dataclasses.replace(model.material, ka=0.0, kd=0.0)
        shaded = cloud.colors[idx] * light_intensity(p, n, v, white, lights, ambient) + \
            light_intensity(p, n, v, shine, lights, ambient)
    return np.where(hit, near, best_t), np.where(hit[..., None], shaded, color)
