"""The numpy twin of ``shaders/include/lighting.glsl``: the notes' lighting model evaluated
on arrays, term for term as the GLSL evaluates it, for CPU reference images.

    I = Ia ka C + sum over lights  k Ip (kd max(L.N, 0) C + ks max(R.V, 0)^n),
    R = 2 (L.N) N - L,  no term at all from a light behind the surface (L.N <= 0),

with ``k = 1 / (c + l d + q d^2)`` for an attenuated point light (1 otherwise). Lighting is
invariant under the rigid view transform, so the twin works in world space while the GLSL
works in view space. Tested pixel by pixel against the small independent oracle in
``tests/oracle/``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .._srgb import linear_to_srgb
from ..scene.lights import DirectionalLight

__all__ = ["light_intensity", "pbr_radiance", "view_dir", "face_viewer", "encode_srgb",
           "final_color"]

F = NDArray[np.float64]


def _dot(a, b) -> F:
    return np.einsum("...i,...i", a, b)


def view_dir(p: F, camera) -> F:
    """Unit vector from each point towards the eye ``(..., 3)``: the view axis reversed for
    an orthographic camera (lighting.glsl's ``view_dir``).

    Parameters
    ----------
    p : ndarray
        ``(..., 3)`` view-space points.
    camera : Camera
        The view (perspective or orthographic).
    """
    p = np.asarray(p, np.float64)
    if camera.projection == "orthographic":
        return np.broadcast_to(-camera.forward, p.shape)
    v = camera.position - p
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-300)


def face_viewer(n: F, facing_away) -> F:
    """Two-sided lighting: the normal negated where the surface faces away from the viewer
    (surface.glsl's ``face_viewer``; the GPU knows this from ``gl_FrontFacing``).

    Parameters
    ----------
    n : ndarray
        ``(..., 3)`` normals.
    facing_away : ndarray
        ``(...)`` bool: where the surface faces away from the viewer.
    """
    return np.where(np.asarray(facing_away)[..., None], -n, n)


def light_intensity(p: F, n: F, v: F, material, lights, ambient) -> F:
    """Colour ``(..., 3)``, unclamped, at points ``p`` with unit normals ``n`` and unit view
    vectors ``v``, for a Material (or a PBRMaterial: :func:`pbr_radiance`) with its
    emission added, a list of lights (use ``Scene.lights_for(camera)``, so an
    empty scene gets the default headlight) and the ambient intensity ``Ia``.

    Parameters
    ----------
    p : ndarray
        ``(..., 3)`` view-space points.
    n : ndarray
        ``(..., 3)`` unit normals.
    v : ndarray
        ``(..., 3)`` unit vectors towards the eye.
    material : Material
        The surface.
    lights : list
        The lights, their vectors in view space.
    ambient : array_like
        ``(3,)`` the ambient intensity.
    """
    p = np.asarray(p, np.float64)
    n = np.asarray(n, np.float64)
    if material.lighting.value == "pbr":
        return pbr_radiance(p, n, v, material, lights, ambient)
    kd = np.asarray(material.diffuse_rgb, np.float64)
    ks = np.asarray(material.specular_rgb, np.float64) * (material.illum == 2)
    if material.illum == 0:  # (the diffuse colour, unlit)
        return np.broadcast_to(kd, p.shape) + np.asarray(material.emission, np.float64)
    color = np.broadcast_to(np.asarray(ambient) * np.asarray(material.ambient_rgb),
                            p.shape).copy()
    for light in lights:
        ip = np.asarray(light.color) * light.intensity
        if isinstance(light, DirectionalLight):
            to_light = np.broadcast_to(-np.asarray(light.direction), p.shape)
            dist = np.linalg.norm(to_light, axis=-1)
            k = np.ones(p.shape[:-1])
        else:
            to_light = np.asarray(light.position) - p
            dist = np.linalg.norm(to_light, axis=-1)
            c0, c1, c2 = light.attenuation
            k = light.window(dist) / np.maximum(c0 + c1 * dist + c2 * dist * dist, 1e-30)
            if hasattr(light, "spot_vector"):  # (a spot light's cone, in view space)
                s = light.spot_vector(np.eye(4))
                cone = np.clip(_dot(-to_light / np.maximum(dist, 1e-30)[..., None], s[:3])
                               + s[3], 0.0, 1.0)
                k = k * cone * cone
        l_vec = to_light / np.maximum(dist, 1e-30)[..., None]
        ln = _dot(l_vec, n)
        lit = ln > 0
        r = 2 * ln[..., None] * n - l_vec
        rv = np.maximum(_dot(r, v), 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            spec = np.where(rv > 0, rv ** material.shininess, 0.0)
        term = kd * ln[..., None] + ks * spec[..., None]
        color += np.where(lit[..., None], (k[..., None] * ip) * term, 0.0)
    return color + np.asarray(material.emission, np.float64)  # (outputs.glsl: EMISSIVE)


def _cone(light, to_light: F, dist: F) -> F:
    """A spot light's cone factor at the points (1 for other lights)."""
    if not hasattr(light, "spot_vector"):
        return np.ones(dist.shape)
    s = light.spot_vector(np.eye(4))
    c = np.clip(_dot(-to_light / np.maximum(dist, 1e-30)[..., None], s[:3]) + s[3], 0.0, 1.0)
    return c * c


def pbr_radiance(p: F, n: F, v: F, material, lights, ambient) -> F:
    """glTF's metallic-roughness model (pbr.glsl's twin): outgoing radiance ``(..., 3)`` at
    points ``p`` with unit normals ``n`` and unit view vectors ``v``, for a PBRMaterial --
    Appendix B's BRDF times each light's colour x intensity (over d^2 for point and spot
    lights, times a spot's cone) x N.L, plus ``ambient x ka x base_color``.

    Parameters
    ----------
    p : ndarray
        ``(..., 3)`` points.
    n : ndarray
        ``(..., 3)`` unit normals.
    v : ndarray
        ``(..., 3)`` unit vectors towards the eye.
    material : PBRMaterial
        The surface.
    lights : list
        The lights.
    ambient : array_like
        ``(3,)`` the ambient light.
    """
    base = np.asarray(material.base_color, np.float64)
    metallic, alpha = material.metallic, material.roughness ** 2
    a2 = alpha * alpha
    f0 = 0.04 * (1 - metallic) + base * metallic
    nv = np.maximum(_dot(n, v), 1e-4)
    color = np.broadcast_to(np.asarray(ambient) * material.ka * base, p.shape).copy()
    for light in lights:
        ip = np.asarray(light.color) * light.intensity
        if isinstance(light, DirectionalLight):
            to_light = np.broadcast_to(-np.asarray(light.direction), p.shape)
            dist = np.ones(p.shape[:-1])
            k = np.ones(p.shape[:-1])
        else:
            to_light = np.asarray(light.position) - p
            dist = np.linalg.norm(to_light, axis=-1)
            k = _cone(light, to_light, dist) * light.window(dist) / np.maximum(dist * dist,
                                                                               1e-30)
        l_vec = to_light / np.maximum(dist, 1e-30)[..., None]
        nl = _dot(n, l_vec)
        h = l_vec + v
        h = h / np.maximum(np.linalg.norm(h, axis=-1, keepdims=True), 1e-30)
        nh = np.maximum(_dot(n, h), 0.0)
        vh = np.maximum(_dot(v, h), 0.0)
        fresnel = f0 + (1 - f0) * ((1 - vh) ** 5)[..., None]
        denom = np.pi * (nh * nh * (a2 - 1) + 1) ** 2
        d = np.where(denom > 0, a2 / np.maximum(denom, 1e-300), 0.0)
        nlc = np.maximum(nl, 0.0)
        vis = 0.5 / np.maximum(nlc * np.sqrt(nv * nv * (1 - a2) + a2) +
                               nv * np.sqrt(nlc * nlc * (1 - a2) + a2), 1e-30)
        f = (1 - fresnel) * (1 - metallic) * base / np.pi + fresnel * (d * vis)[..., None]
        color += np.where((nl > 0)[..., None], f * (nl * k)[..., None] * ip, 0.0)
    return color + np.asarray(material.emission, np.float64)


def encode_srgb(c: F) -> F:
    """Linear [0, 1] to sRGB (outputs.glsl's ``encode_srgb``).

    Parameters
    ----------
    c : ndarray
        Linear values in [0, 1].
    """
    return linear_to_srgb(c)


def final_color(color: F, srgb: bool = False) -> F:
    """What a program writes: clamped to [0, 1], sRGB-encoded when asked.

    Parameters
    ----------
    color : ndarray
        ``(..., 3)`` linear colour.
    srgb : bool
        Encode as sRGB.
    """
    color = np.clip(color, 0.0, 1.0)
    return encode_srgb(color) if srgb else color
