"""The path tracer's numpy twin, for small scenes: the same estimator (next-event
estimation, the Phong lobe, Russian roulette) written again with arrays of paths, brute-force
ray-triangle tests and numpy's random numbers. It shares nothing with the GPU tracer but
:class:`~glshade.pathtrace.scene.TraceScene`, so agreeing within noise is evidence for both."""

from __future__ import annotations

import numpy as np

from ..errors import OptionError
from .progressive import PathTraced, _size
from .scene import TraceScene

__all__ = ["trace"]


#: the most a path goes on with under Russian roulette (shaders/pathtrace.frag's RR_CAP)
RR_CAP = 0.99


def _hits(o, d, tri, t_max):
    """Nearest hit of each ray (R, 3) among ``tri`` (T, 3, 3): t (R,) (inf: none) and the
    triangle (R,). Möller-Trumbore over every pair, in blocks of rays."""
    t_best = np.full(len(o), np.inf)
    k_best = np.full(len(o), -1)
    v0, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    step = max(1, 2**22 // max(len(tri), 1) // 8)
    for s in range(0, len(o), step):
        oo, dd = o[s:s + step, None], d[s:s + step, None]
        pv = np.cross(dd, e2)
        det = np.einsum("rtk,tk->rt", pv, e1)
        with np.errstate(divide="ignore", invalid="ignore"):
            f = 1.0 / det
            sv = oo - v0
            u = f * np.einsum("rtk,rtk->rt", sv, pv)
            q = np.cross(sv, e1)
            v = f * np.einsum("rtk,rtk->rt", dd, q)
            t = f * np.einsum("tk,rtk->rt", e2, q)
        ok = (np.abs(det) > 1e-30) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0) & \
            (t < t_max[s:s + step, None])
        t = np.where(ok, t, np.inf)
        k = t.argmin(1)
        t_best[s:s + step] = t[np.arange(len(k)), k]
        k_best[s:s + step] = np.where(np.isfinite(t_best[s:s + step]), k, -1)
    return t_best, k_best


def _frame(n):
    a = np.where(np.abs(n[:, :1]) > 0.5, [[0.0, 1.0, 0.0]], [[1.0, 0.0, 0.0]])
    u = np.cross(a, n)
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    return u, np.cross(n, u)


def _around(n, cos_t, phi):
    u, v = _frame(n)
    sin_t = np.sqrt(np.maximum(0, 1 - cos_t ** 2))[:, None]
    w = u * np.cos(phi)[:, None] * sin_t + v * np.sin(phi)[:, None] * sin_t + n * cos_t[:, None]
    return w / np.linalg.norm(w, axis=1, keepdims=True)


def _brdf_pi(rho, ks, shin, n, wi, wo):
    r = 2 * np.einsum("rk,rk->r", wo, n)[:, None] * n - wo
    ca = np.maximum(np.einsum("rk,rk->r", r, wi), 0)
    return rho + (ks * 0.5 * (shin + 2) * ca ** shin)[:, None]


def radiance(ts: TraceScene, o, d, rng, max_depth: int = 64, hits=None):
    """pi x radiance along each ray (R, 3): one path each (``hits`` (R,), if given, counts
    the rays whose first hit exists)."""
    tri, mats = ts.triangles, ts.materials
    eps = 1e-5 * ts.size
    out = np.zeros((len(o), 3))
    beta = np.ones((len(o), 3))
    alive = np.arange(len(o))
    e_tri = ts.emitters
    for depth in range(max_depth):
        if not len(alive):
            break
        t, k = _hits(o, d, tri, np.full(len(o), np.inf))
        hit = k >= 0
        o, d, t, k, beta, alive = o[hit], d[hit], t[hit], k[hit], beta[hit], alive[hit]
        m = mats[ts.material[k]]
        ng = ts.normals[k]
        front = np.einsum("rk,rk->r", ng, d) < 0
        if depth == 0:
            np.add.at(out, alive, np.where(front[:, None], m[:, 5:8], 0))
            if hits is not None:
                hits[alive] += 1
        n = np.where(front[:, None], ng, -ng)
        x = o + t[:, None] * d + n * eps
        wo = -d
        rho, ks, shin = m[:, :3], m[:, 3], m[:, 4]
        if len(e_tri):
            np.add.at(out, alive, beta * _emitters_seen(ts, x, n, wo, m, rng))
        np.add.at(out, alive, beta * _lights_seen(ts, x, n, wo, m))
        wd = rho.mean(1)
        go = wd + ks > 0
        pd = np.where(go, wd / np.maximum(wd + ks, 1e-300), 1)
        r = d - 2 * np.einsum("rk,rk->r", d, n)[:, None] * n
        diffuse = rng.random(len(x)) < pd
        u1, u2 = rng.random(len(x)), rng.random(len(x))
        cos_t = np.where(diffuse, np.sqrt(u1), u1 ** (1 / (shin + 1)))
        wi = _around(np.where(diffuse[:, None], n, r), cos_t, 2 * np.pi * u2)
        cx = np.einsum("rk,rk->r", wi, n)
        ca = np.maximum(np.einsum("rk,rk->r", wi, r), 0)
        pdf = pd * cx / np.pi + (1 - pd) * (shin + 1) / (2 * np.pi) * ca ** shin
        go &= cx > 0
        with np.errstate(divide="ignore", invalid="ignore"):
            beta = beta * _brdf_pi(rho, ks, shin, n, wi, wo) / np.pi * (cx / pdf)[:, None]
        if depth >= 3:
            q = np.minimum(beta.max(1), RR_CAP)
            go &= rng.random(len(x)) < q
            beta = beta / np.where(go, q, 1)[:, None]
        o, d, beta, alive = x[go], wi[go], beta[go], alive[go]
    return out


def trace(scene, camera=None, size=(32, 32), spp: int = 16, *, seed: int = 0,
          max_depth: int = 64, lights: bool = True) -> PathTraced:
    """Path-trace a small scene in numpy (seconds for a few hundred triangles at 32 x 32);
    the picture and its per-pixel standard errors, as the GPU tracer returns them.

    Parameters
    ----------
    scene : Scene or TraceScene
        A small scene.
    camera : Camera or None
        From where (None: framed).
    size : (int, int)
        Width and height.
    spp : int
        Samples a pixel.
    seed : int
        The random numbers' seed.
    max_depth : int
        Vertices a path may have.
    lights : bool
        Trace the scene's lights.
    """
    import time

    from ..scene.camera import default_camera

    w, h = _size(size)
    ts = scene if isinstance(scene, TraceScene) else TraceScene.from_scene(scene, lights=lights)
    if ts.solids:
        raise OptionError("the numpy twin traces triangles; a CSG solid is the GPU tracer's "
                          "(csg.glsl)")
    if (ts.materials[:, 10] > 0).any():
        raise OptionError("the numpy twin traces the notes' Material; glTF's model "
                          "(PBRMaterial) is traced by the GPU tracer (trace_bsdf.glsl)")
    if ts.shading is not None:
        raise OptionError("the numpy twin shades with the triangles' own normals; make the "
                          "TraceScene with smooth=False")
    if camera is None:
        camera = default_camera(scene.bounds, w / h)
    rng = np.random.default_rng(seed)
    inv = np.linalg.inv(camera.projection_matrix(w / h) @ camera.view_matrix())
    t0 = time.perf_counter()
    ys, xs = np.mgrid[h - 1:-1:-1, 0:w]  # (top row first, as images are)
    total = np.zeros((h * w, 3))
    square = np.zeros((h * w, 3))
    hits = np.zeros(h * w)
    for _ in range(int(spp)):
        px = (xs.ravel() + rng.random(h * w)) / w * 2 - 1
        py = (ys.ravel() + rng.random(h * w)) / h * 2 - 1
        a = np.stack([px, py, -np.ones_like(px), np.ones_like(px)], 1) @ inv.T
        b = np.stack([px, py, np.ones_like(px), np.ones_like(px)], 1) @ inv.T
        o, far = a[:, :3] / a[:, 3:], b[:, :3] / b[:, 3:]
        d = (far - o) / np.linalg.norm(far - o, axis=1, keepdims=True)
        value = radiance(ts, o, d, rng, max_depth, hits)
        total += value
        square += value ** 2
    mean = total / spp
    var = np.maximum(square / spp - mean ** 2, 0) * spp / max(spp - 1, 1)
    se = np.sqrt(var / spp)
    return PathTraced(mean.reshape(h, w, 3), se.reshape(h, w, 3), int(spp),
                      np.zeros((h, w)), time.perf_counter() - t0, method="numpy path tracing",
                      coverage=(hits / spp).reshape(h, w))


def _emitters_seen(ts: TraceScene, x, n, wo, m, rng) -> np.ndarray:
    """Next-event estimation on the emitting triangles (R, 3): a point on one, chosen by
    power, its light through the BRDF where the shaded point ``x`` sees it."""
    tri, mats, e_tri = ts.triangles, ts.materials, ts.emitters
    e_p = np.diff(np.concatenate([[0.0], ts.emitter_cdf]))
    rho, ks, shin = m[:, :3], m[:, 3], m[:, 4]
    j = np.searchsorted(ts.emitter_cdf, rng.random(len(x)), side="right")
    j = np.minimum(j, len(e_tri) - 1)
    et = tri[e_tri[j]]
    a, b = rng.random(len(x)), rng.random(len(x))
    flip = a + b > 1
    a, b = np.where(flip, 1 - a, a), np.where(flip, 1 - b, b)
    y = et[:, 0] + a[:, None] * (et[:, 1] - et[:, 0]) + b[:, None] * (et[:, 2] - et[:, 0])
    to = y - x
    dist = np.linalg.norm(to, axis=1)
    wi = to / dist[:, None]
    cx = np.einsum("rk,rk->r", n, wi)
    cy = -np.einsum("rk,rk->r", ts.normals[e_tri[j]], wi)
    ok = (cx > 0) & (cy > 0)
    th, _ = _hits(x[ok], wi[ok], tri, dist[ok] * (1 - 1e-4))
    seen = np.zeros(len(x), bool)
    seen[np.flatnonzero(ok)[~np.isfinite(th)]] = True
    e = mats[ts.material[e_tri[j]], 5:8]
    w = np.where(seen, cx * cy / dist ** 2 * ts.areas[e_tri[j]] / e_p[j], 0)
    f = _brdf_pi(rho, ks, shin, n, wi, wo) / np.pi
    return f * e * w[:, None]


def _lights_seen(ts: TraceScene, x, n, wo, m) -> np.ndarray:
    """The point and directional lights' contribution (R, 3) where ``x`` sees them."""
    rho, ks, shin = m[:, :3], m[:, 3], m[:, 4]
    out = np.zeros((len(x), 3))
    for light in ts.lights:
        if light[0] > 0.5:
            to = light[1:4] - x
            dist = np.linalg.norm(to, axis=1)
            wi = to / dist[:, None]
            c = light[7:10]
            att = 1 / np.maximum(c[0] + c[1] * dist + c[2] * dist ** 2, 1e-30)
            window = np.clip(1 - (dist * light[14]) ** 4, 0.0, 1.0)
            att = att * window * window
            if light[0] > 1.5:  # (a spot light's cone)
                cone = np.clip(-wi @ light[10:13] + light[13], 0.0, 1.0)
                att = att * cone * cone
        else:
            wi = np.broadcast_to(light[1:4], x.shape)
            dist, att = np.full(len(x), np.inf), np.ones(len(x))
        cx = np.einsum("rk,rk->r", n, wi)
        ok = cx > 0
        th, _ = _hits(x[ok], wi[ok], ts.triangles, dist[ok])
        seen = np.zeros(len(x), bool)
        seen[np.flatnonzero(ok)[~np.isfinite(th)]] = True
        w = np.where(seen, cx * att, 0)
        out += _brdf_pi(rho, ks, shin, n, wi, wo) * light[4:7] * w[:, None]
    return out
