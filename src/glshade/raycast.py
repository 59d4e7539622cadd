"""Analytic reference images: per-pixel ray casting of exact spheres (and the ellipsoids
that transforms make of them), lit with the same formula as the GLSL programs. Pure numpy:
the truth that flat, Gouraud and Phong shading are measured against."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .camera import Camera
from .errors import ComparisonError
from .scene import DirectionalLight, PointLight, Scene

__all__ = ["pixel_rays", "raycast_scene", "has_analytic_surfaces"]


def pixel_rays(camera: Camera, width: int, height: int):
    """World-space ray origins and unit directions through pixel centres ``(H, W, 3)``,
    row 0 at the top."""
    j, i = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    x = 2 * j / width - 1
    y = 1 - 2 * i / height
    r = camera.rotation
    if camera.projection == "perspective":
        t = np.tan(np.radians(camera.fov_y) / 2)
        d = np.stack([x * t * width / height, y * t, -np.ones_like(x)], -1) @ r.T
        d /= np.linalg.norm(d, axis=-1, keepdims=True)
        o = np.broadcast_to(camera.position, d.shape)
    else:
        half_h = camera.height / 2
        offset = np.stack([x * half_h * width / height, y * half_h, np.zeros_like(x)], -1)
        o = camera.position + offset @ r.T
        d = np.broadcast_to(camera.forward, o.shape)
    return o, d


def has_analytic_surfaces(scene: Scene) -> bool:
    return bool(scene.models) and all(
        m.mesh.analytic is not None and m.mesh.analytic.get("kind") == "sphere"
        for m in scene.models if m.visible)


def raycast_scene(scene: Scene, camera: Camera, width: int, height: int
                  ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Colour ``(H, W, 3)`` in [0, 1] (linear) and coverage ``(H, W)`` of the exact
    surfaces of a scene whose models are all sphere primitives (any transforms)."""
    if not has_analytic_surfaces(scene):
        raise ComparisonError("the analytic reference needs sphere primitives "
                              "(primitive:icosphere, primitive:uv_sphere); use "
                              "reference='phong-fine' (or --reference phong-fine) for other "
                              "meshes")
    o, d = pixel_rays(camera, width, height)
    best_t = np.full((height, width), np.inf)
    color = np.zeros((height, width, 3))
    for model in scene.models:
        if not model.visible:
            continue
        m = model.transform
        inv = np.linalg.inv(m)
        radius = model.mesh.analytic["radius"]
        # the ray in the sphere's object space: o' + t d' (t is the same parameter)
        oo = o @ inv[:3, :3].T + inv[:3, 3]
        dd = d @ inv[:3, :3].T
        a = np.einsum("...i,...i", dd, dd)
        b = 2 * np.einsum("...i,...i", oo, dd)
        c = np.einsum("...i,...i", oo, oo) - radius**2
        disc = b * b - 4 * a * c
        hit = disc >= 0
        t = (-b - np.sqrt(np.where(hit, disc, 0))) / (2 * a)
        hit &= (t > 0) & (t < best_t)
        if not hit.any():
            continue
        p = o + t[..., None] * d
        n_obj = (oo + t[..., None] * dd) / radius
        n = n_obj @ np.linalg.inv(m[:3, :3])  # inverse transpose applied to the normal
        n /= np.linalg.norm(n, axis=-1, keepdims=True)
        shaded = _shade(p, n, camera, scene, model.material)
        best_t = np.where(hit, t, best_t)
        color = np.where(hit[..., None], shaded, color)
    return np.clip(color, 0, 1), np.isfinite(best_t)


def _shade(p, n, camera, scene, mat):
    base = np.asarray(mat.color)
    out = np.asarray(scene.ambient) * mat.ka * base * np.ones(p.shape)
    if camera.projection == "perspective":
        v = camera.position - p
        v /= np.linalg.norm(v, axis=-1, keepdims=True)
    else:
        v = np.broadcast_to(-camera.forward, p.shape)
    lights = scene.lights or [PointLight(tuple(camera.position))]  # the default headlight
    for light in lights:
        if isinstance(light, DirectionalLight):
            l_vec = np.broadcast_to(-np.asarray(light.direction), p.shape)
            k = 1.0
        else:
            to = np.asarray(light.position) - p
            dist = np.linalg.norm(to, axis=-1, keepdims=True)
            l_vec = to / dist
            c0, c1, c2 = light.attenuation
            k = 1.0 / (c0 + c1 * dist + c2 * dist**2)
        ln = np.einsum("...i,...i", l_vec, n)
        r = 2 * ln[..., None] * n - l_vec
        rv = np.maximum(np.einsum("...i,...i", r, v), 0)
        lit = (ln > 0)[..., None]
        ip = np.asarray(light.color) * light.intensity
        term = mat.kd * np.maximum(ln, 0)[..., None] * base + mat.ks * (rv ** mat.shininess)[
            ..., None]
        out = out + lit * k * ip * term
    return out
