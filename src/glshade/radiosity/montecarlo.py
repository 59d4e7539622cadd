"""The radiosity equation solved a second, independent way: light tracing (a random walk of
light particles) over the same patches, in numpy, sharing no form-factor code with the
hemicube path -- the oracle the hemicube solution is held to, and ``method="monte-carlo"``.

Particles leave the emitting patches with the emitted power shared out among them (patch
chosen by its power, point uniform on it, direction by the cosine law); each flies to the
nearest polygon of the scene's meshes, where its power arriving is tallied on the patch it
lands on, and goes on reflected by the cosine law with its power times the patch's
reflectance; Russian roulette (survival by the mean reflectance) ends walks without bias.
A patch's radiosity is then ``B = E + rho H / A`` with ``H`` the power arriving on it. The
particles run in batches; the standard error of each patch's (and each model's) radiosity
is the spread of the batch means. Patches are found within the polygon a particle hits by
the nearest patch centre (exact for the grids quads are cut into; per model the tallies
are exact whatever the patches).
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError

__all__ = ["MonteCarlo", "light_trace", "MAX_BOUNCES"]

#: the most surfaces a particle reaches: Russian roulette ends a path with the mean
#: reflectance's odds, so in a room that loses no light (every reflectance 1) nothing would;
#: particles still going at the cap are counted (``MonteCarlo.cut``) and their light past it
#: left out -- a solution that stopped at its cap says so, never silently
MAX_BOUNCES = 1_000


class MonteCarlo:
    """What :func:`light_trace` estimates: radiosity ``B (P, 3)``, its standard error
    ``se (P, 3)``, and per model the area-weighted mean radiosity and its error; ``cut``:
    the particles still going after MAX_BOUNCES surfaces (their later light left out:
    ``converged`` is False).

    Parameters
    ----------
    problem : PatchScene
        The patches.
    b : ndarray
        ``(P, 3)`` radiosity.
    se : ndarray
        ``(P, 3)`` its standard error.
    model_b, model_se : ndarray
        ``(M, 3)`` each model's area-weighted mean radiosity and its error.
    particles : int
        The particles traced.
    cut : int
        Particles still going after MAX_BOUNCES surfaces (their later light left out).
    """

    def __init__(self, problem, b, se, model_b, model_se, particles: int, cut: int = 0):
        self.problem, self.radiosity, self.se = problem, b, se
        self.model_radiosity, self.model_se, self.particles = model_b, model_se, particles
        self.cut = int(cut)

    @property
    def converged(self) -> bool:
        """Whether every particle's path ended by roulette or by leaving the scene."""
        return self.cut == 0


def _triangles(meshes):
    tris, owner = [], []
    for k, mesh in enumerate(meshes):
        if mesh.n_faces == 0:
            continue
        t, face = mesh.triangles
        tris.append(mesh.vertices[t])
        owner.append(np.stack([np.full(len(t), k), face], 1))
    return np.concatenate(tris), np.concatenate(owner)


def _hit(o, d, tris, eps):
    """Nearest triangle along each ray (Moller-Trumbore over all triangles): (t, index)."""
    a, e1, e2 = tris[:, 0], tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
    best_t = np.full(len(o), np.inf)
    best = np.full(len(o), -1)
    for start in range(0, len(tris), 256):
        sl = slice(start, start + 256)
        p = np.cross(d[:, None, :], e2[None, sl])
        det = np.einsum("rtk,tk->rt", p, e1[sl])
        ok = np.abs(det) > 1e-300
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        s = o[:, None, :] - a[None, sl]
        u = np.einsum("rtk,rtk->rt", s, p) * inv
        q = np.cross(s, e1[None, sl])
        v = np.einsum("rk,rtk->rt", d, q) * inv
        t = np.einsum("rtk,tk->rt", q, e2[sl]) * inv
        good = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > eps)
        t = np.where(good, t, np.inf)
        k = np.argmin(t, axis=1)
        tk = t[np.arange(len(o)), k]
        closer = tk < best_t
        best_t[closer], best[closer] = tk[closer], start + k[closer]
    return best_t, best


def _cosine(normals, rng):
    """Directions by the cosine law about each unit normal ``(N, 3)``."""
    n = len(normals)
    r1, r2 = rng.random(n), rng.random(n)
    phi, r = 2 * np.pi * r1, np.sqrt(r2)
    local = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(1 - r2)], 1)
    helper = np.where(np.abs(normals[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]])
    t1 = np.cross(normals, helper)
    t1 /= np.linalg.norm(t1, axis=1, keepdims=True)
    t2 = np.cross(normals, t1)
    return local[:, :1] * t1 + local[:, 1:2] * t2 + local[:, 2:] * normals


def light_trace(problem, particles: int = 200_000, batches: int = 16, seed: int = 0,
                chunk: int = 4096, progress=None) -> MonteCarlo:
    """Estimate the radiosity of ``problem`` (a :class:`~glshade.radiosity.PatchScene`)
    from ``particles`` light particles in ``batches`` (see the module).

    Parameters
    ----------
    problem : PatchScene
        The patches.
    particles : int
        Light particles in all.
    batches : int
        Independent batches (the standard error's samples).
    seed : int
        The random numbers' seed.
    chunk : int
        Particles traced at once.
    progress : bool, tqdm-like or None
        The progress bar.
    """
    if int(particles) != particles or particles < batches or batches < 2:
        raise InputError(f"particles must be a whole number >= batches >= 2, got {particles!r}")
    if not problem.meshes:
        raise InputError("the problem has no meshes to trace (make it with "
                         "PatchScene.from_scene)")
    rng = np.random.default_rng(seed)
    p = problem.patches
    tris, owner = _triangles(problem.meshes)
    scale = float(np.abs(tris).max()) or 1.0
    eps = 1e-9 * scale
    first_polygon, table, counts = _polygon_patches(problem)
    lum = (problem.emission * p.areas[:, None]).sum(1)
    if not lum.sum() > 0:
        raise InputError("the scene has no emitter")
    pick = lum / lum.sum()
    tri_area = 0.5 * np.linalg.norm(np.cross(
        p.vertices[p.triangles[:, 1]] - p.vertices[p.triangles[:, 0]],
        p.vertices[p.triangles[:, 2]] - p.vertices[p.triangles[:, 0]]), axis=1)
    # the emitting patches' triangles, and each one's share of its patch's area
    emitters = np.flatnonzero(lum > 0)
    etri = np.flatnonzero(np.isin(p.triangle_patch, emitters))
    share = tri_area[etri] / np.bincount(p.triangle_patch[etri], weights=tri_area[etri],
                                         minlength=p.n_patches)[p.triangle_patch[etri]]
    n_batch = int(particles) // batches
    arrived = np.zeros((batches, p.n_patches, 3))
    cut = 0
    for batch in range(batches):
        for start in range(0, n_batch, chunk):
            n = min(chunk, n_batch - start)
            # a patch by its power, then one of its triangles by area (together: a triangle
            # by patch power times area share), then a point uniform in it
            choice = etri[rng.choice(len(etri), n, p=pick[p.triangle_patch[etri]] * share)]
            src = p.triangle_patch[choice]
            c = p.vertices[p.triangles[choice]]
            r1, r2 = rng.random(n), rng.random(n)
            flip = r1 + r2 > 1
            r1, r2 = np.where(flip, 1 - r1, r1), np.where(flip, 1 - r2, r2)
            o = c[:, 0] + r1[:, None] * (c[:, 1] - c[:, 0]) + r2[:, None] * (c[:, 2] - c[:, 0])
            normal = p.normals[src]
            d = _cosine(normal, rng)
            power = problem.emission[src] * p.areas[src, None] / (pick[src, None] * n_batch)
            o = o + normal * eps * 10
            scene = (problem, tris, owner, first_polygon, table, counts, eps)
            cut += _follow(scene, o, d, power, arrived[batch], rng)
        if progress is not None:
            progress.update(1)
    per_batch = problem.emission[None] + problem.rho[None] * arrived / p.areas[None, :, None]
    b = per_batch.mean(0)
    se = per_batch.std(0, ddof=1) / np.sqrt(batches)
    models = int(problem.model.max()) + 1
    area = np.bincount(problem.model, weights=p.areas, minlength=models)
    means = np.stack([np.stack([np.bincount(problem.model, weights=per_batch[j, :, c] *
                                            p.areas, minlength=models) / area
                                for c in range(3)], 1) for j in range(batches)])
    return MonteCarlo(problem, b, se, means.mean(0),
                      means.std(0, ddof=1) / np.sqrt(batches), n_batch * batches, cut)


_GATHERED = 32  # a polygon of more patches finds a hit's patch on its own (_patch_of)


def _patch_of(x, polygon, table, counts, centers):
    """The patch of each hit point: the nearest patch centre among its polygon's patches
    (row ``polygon`` of ``table``, ``counts`` long). The hits of polygons with as many
    patches, up to ``_GATHERED``, at once (a loop over the few patch counts, not over
    polygons); a polygon of more patches on its own, its distances one matrix product
    (such polygons are at most patches / ``_GATHERED``: a Cornell box's floor is 800)."""
    out = np.empty(len(x), np.int64)
    n = counts[polygon]
    small = n <= _GATHERED
    for k in np.unique(n[small]):
        sel = np.flatnonzero(n == k)
        cand = table[polygon[sel], :k]
        gap = centers[cand] - x[sel, None]
        out[sel] = cand[np.arange(len(sel)), np.argmin(np.einsum("nkd,nkd->nk", gap, gap), 1)]
    big = np.flatnonzero(~small)
    order = big[np.argsort(polygon[big], kind="stable")]
    ids, starts = np.unique(polygon[order], return_index=True)
    for poly, sel in zip(ids.tolist(), np.split(order, starts[1:])):
        cand = table[poly, :counts[poly]]
        c = centers[cand]
        # |x - c|^2 = |x|^2 - 2 x.c + |c|^2: the nearest maximises x.c - |c|^2 / 2
        score = x[sel] @ c.T - 0.5 * np.einsum("kd,kd->k", c, c)
        out[sel] = cand[np.argmax(score, 1)]
    return out


def _polygon_patches(problem):
    """For finding a hit's patch: each model's first polygon number (M + 1,), a table
    (polygon, k) -> patch, each polygon's row padded with its first patch (a pad repeats a
    candidate: harmless), and each polygon's count of patches."""
    p = problem.patches
    first_polygon = np.cumsum([0] + [mesh.n_faces for mesh in problem.meshes])
    key = first_polygon[problem.model] + p.source
    order = np.argsort(key, kind="stable")
    counts = np.bincount(key, minlength=first_polygon[-1])
    starts = np.concatenate([[0], np.cumsum(counts)])
    slot = np.arange(len(order)) - starts[key[order]]
    table = np.repeat(order[starts[:-1].clip(max=len(order) - 1)][:, None],
                      max(int(counts.max()), 1), axis=1)
    table[key[order], slot] = order
    return first_polygon, table, counts


def _follow(scene, o, d, power, arrived, rng) -> int:
    """Follow particles from ``o`` along ``d`` carrying ``power`` (N, 3) until they leave
    the scene or are absorbed (Russian roulette by the mean reflectance), adding the power
    each brings to a patch into ``arrived`` (P, 3); the number still going after
    MAX_BOUNCES surfaces (then left)."""
    problem, tris, owner, first_polygon, table, counts, eps = scene
    p = problem.patches
    for _ in range(MAX_BOUNCES):
        if not len(o):
            return 0
        t, k = _hit(o, d, tris, eps)
        going = np.isfinite(t)
        o, d, power, t, k = o[going], d[going], power[going], t[going], k[going]
        if not len(o):
            return 0
        x = o + t[:, None] * d
        model, face = owner[k, 0], owner[k, 1]
        patch = _patch_of(x, first_polygon[model] + face, table, counts, p.centers)
        np.add.at(arrived, patch, power)
        rho = problem.rho[patch]
        survive = rho.mean(axis=1)
        alive = rng.random(len(o)) < survive
        keep = alive & (survive > 0)
        n_hit = p.normals[patch][keep]
        facing = np.einsum("nk,nk->n", n_hit, d[keep]) > 0
        n_hit[facing] *= -1  # (reflected to the side the particle came from)
        power = power[keep] * rho[keep] / survive[keep, None]
        o = x[keep] + n_hit * eps * 10
        d = _cosine(n_hit, rng)
    return len(o)
