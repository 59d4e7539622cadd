"""Analytic reference images: per-pixel ray casting of exact quadrics, lit with the notes'
formula in numpy. Independent of every line of the GL code."""

from __future__ import annotations

import numpy as np


def pixel_rays(camera, width, height):
    """World-space ray origins and unit directions through pixel centres, row 0 at top."""
    j, i = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    x_ndc = 2 * j / width - 1
    y_ndc = 1 - 2 * i / height
    t = np.tan(np.radians(camera.fov_y) / 2)
    d_view = np.stack([x_ndc * t * width / height, y_ndc * t, -np.ones_like(x_ndc)], -1)
    r = camera.rotation
    d = d_view @ r.T
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    return np.broadcast_to(camera.position, d.shape), d


def hit_ellipsoid(origin, direction, radii, center=(0, 0, 0)):
    """Nearest hit with the ellipsoid ``sum((p - c)^2 / r^2) = 1``: points, unit normals,
    mask."""
    radii = np.asarray(radii, float)
    o = (origin - center) / radii
    d = direction / radii
    a = np.einsum("...i,...i", d, d)
    b = 2 * np.einsum("...i,...i", o, d)
    c = np.einsum("...i,...i", o, o) - 1
    disc = b * b - 4 * a * c
    hit = disc >= 0
    t = (-b - np.sqrt(np.where(hit, disc, 0))) / (2 * a)
    hit &= t > 0
    p = origin + t[..., None] * direction
    n = (p - center) / radii**2
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return p, n, hit


def shade(p, n, eye, lights, material, ambient=(1, 1, 1)):
    """The notes' lighting: I = Ia ka C + sum Ip (kd max(L.N, 0) C + ks max(R.V, 0)^n),
    no specular where L.N <= 0. ``lights``: list of (position, rgb intensity)."""
    color = np.asarray(material.color)
    out = np.asarray(ambient) * material.ka * color * np.ones(p.shape)
    v = eye - p
    v /= np.linalg.norm(v, axis=-1, keepdims=True)
    for pos, ip in lights:
        l_vec = np.asarray(pos) - p
        l_vec /= np.linalg.norm(l_vec, axis=-1, keepdims=True)
        ln = np.einsum("...i,...i", l_vec, n)
        r = 2 * ln[..., None] * n - l_vec
        rv = np.maximum(np.einsum("...i,...i", r, v), 0)
        lit = ln > 0
        diffuse = material.kd * np.maximum(ln, 0)[..., None] * color
        spec = material.ks * np.where(lit, rv ** material.shininess, 0)[..., None]
        out = out + np.asarray(ip) * (diffuse + spec) * lit[..., None]
    return np.clip(out, 0, 1)


def render_ellipsoid(camera, width, height, radii, lights, material, transform=None):
    """Reference image (H, W, 3) float in [0, 1] and coverage mask."""
    o, d = pixel_rays(camera, width, height)
    p, n, hit = hit_ellipsoid(o, d, radii)
    img = shade(p, n, camera.position, lights, material)
    return np.where(hit[..., None], img, 0.0), hit


def shade_any(p, n, v, lights, material, ambient=(1, 1, 1)):
    """The notes' lighting for point lights with attenuation and directional lights,
    unclamped, with the view vector given: ``lights`` are ``("point", position, ip,
    (c, l, q))`` or ``("directional", travel_direction, ip)``. Written from the notes."""
    color = np.asarray(material.color, float)
    total = np.zeros(np.shape(p)) + np.asarray(ambient) * material.ka * color
    for light in lights:
        if light[0] == "point":
            _, pos, ip, (c, lin, q) = light
            d = np.asarray(pos, float) - p
            dist = np.sqrt((d * d).sum(-1, keepdims=True))
            to_light = d / dist
            factor = 1.0 / (c + lin * dist + q * dist * dist)
        else:
            _, direction, ip = light
            direction = np.asarray(direction, float)
            to_light = np.zeros(np.shape(p)) - direction / np.linalg.norm(direction)
            factor = 1.0
        cos_i = (to_light * n).sum(-1, keepdims=True)
        reflected = 2 * cos_i * n - to_light
        cos_r = np.clip((reflected * v).sum(-1, keepdims=True), 0, None)
        contribution = material.kd * cos_i * color + material.ks * cos_r ** material.shininess
        total = total + np.where(cos_i > 0, factor * np.asarray(ip) * contribution, 0.0)
    return total
