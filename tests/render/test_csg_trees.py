"""CSG trees of any size on the GPU, one program for all: random trees of 1 to 256 leaves
and thin tori against the numpy reference; a rebalanced 1,000-long union against the closed
form of its first hit; the reference itself against bisection on ``contains``, which shares
nothing with its event lists."""

import numpy as np
import pytest

from glshade import Camera, Scene
from glshade.cpu.csg import render_solids
from glshade.solids.encoding import flatten, postorder, truth_table
from glshade.solids.tree import Difference, Intersection, Transformed, Union
from glshade.solids import Box, Cone, Cylinder, Sphere, Torus

from .test_csg import away_from_silhouettes


def random_tree(n: int, seed: int):
    """``n`` leaves of every kind, placed at random in a 4-unit cube, combined pairwise in a
    random order by union (mostly), difference and intersection with a large ball."""
    rng = np.random.default_rng(seed)
    makers = [lambda s: Sphere(0.3 + 0.5 * s), lambda s: Box(0.4 + 0.8 * s),
              lambda s: Cylinder(0.2 + 0.3 * s, 0.5 + s), lambda s: Cone(0.3 + 0.4 * s, 1 + s),
              lambda s: Torus(0.5 + 0.3 * s, 0.08 + 0.1 * s)]
    pool = []
    for k in range(n):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        angle = rng.uniform(0, np.pi)
        q = [*(np.sin(angle / 2) * axis), np.cos(angle / 2)]
        leaf = makers[k % len(makers)](rng.uniform()).rotated(q)
        pool.append(leaf.translated(rng.uniform(-2, 2, 3) * (n > 1)))
    while len(pool) > 1:
        i, j = sorted(rng.choice(len(pool), 2, replace=False))
        a, b = pool[i], pool.pop(j)
        r = rng.uniform()
        pool[i] = a - b if r < 0.25 else (a & Sphere(3.5)) | b if r < 0.3 else a | b
    return pool[0]


def compare(frame, scene, camera, size, mismatch=0.0):
    depth, normal, ids = render_solids(scene, camera, size)
    ok = away_from_silhouettes(ids) & away_from_silhouettes(frame.face_id)
    wrong = frame.face_id[ok] != ids[ok]
    assert wrong.mean() <= mismatch, f"{wrong.sum()} of {ok.sum()} pixels show another leaf"
    hit = ok & (ids >= 0) & (frame.face_id == ids)
    assert hit.sum() > 40
    assert np.median(np.abs(frame.depth[hit] - depth[hit]) / depth[hit]) < 1e-5
    assert (np.abs(frame.depth[hit] - depth[hit]) / depth[hit]).max() < 1e-3
    assert np.quantile(np.abs(frame.normal[hit] - normal[hit]).max(-1), 0.99) < 1e-3
    return ids


# 1, 8, 14: cast in one step (4, 8, 16 slots); 24: a small tree's walk, run as its program;
# 64, 256: the walk through the hierarchy
@pytest.mark.parametrize("leaves", [1, 8, 14, 24, 64, 256])
def test_random_trees_match_the_numpy_reference(leaves, make_renderer):
    size = (96, 72) if leaves <= 64 else (64, 48)
    scene = Scene()
    solid = random_tree(leaves, seed=leaves)
    scene.add(solid)
    lo, hi = solid.bounds
    centre, reach = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    camera = Camera.look_at(centre + 2.6 * reach * np.array([0.55, 0.45, 0.7]), centre,
                            fov_y=45)
    frame = make_renderer(*size).render_frame(scene, camera, "phong")
    ids = compare(frame, scene, camera, size, mismatch=0.002)
    assert len(np.unique(ids[ids >= 0])) >= min(leaves, 4)


def test_few_varyings_make_a_small_tree_walk(make_renderer):
    """Where the driver interpolates too few floats for 16 slots (GL 3.3 promises 60), a
    tree of 9-14 leaves walks instead -- and still matches the reference."""
    size = (96, 72)
    scene = Scene()
    solid = random_tree(12, seed=12)
    scene.add(solid)
    lo, hi = solid.bounds
    centre, reach = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    camera = Camera.look_at(centre + 2.6 * reach * np.array([0.55, 0.45, 0.7]), centre)
    r = make_renderer(*size)
    r.csg.max_slots = 8
    frame = r.render_frame(scene, camera, "phong")
    assert all(not key[3] for key in r.csg.compiled)  # (no slots: the walk)
    compare(frame, scene, camera, size, mismatch=0.002)


def test_a_thousand_long_union_is_rebalanced_and_exact(make_renderer):
    """1,000 balls joined one by one: 14 deep at most, rebalanced; on the GPU every pixel's
    depth is the nearest ray-sphere entry, computed here in closed form."""
    rng = np.random.default_rng(5)
    centres, radii = rng.uniform(-3, 3, (1000, 3)), rng.uniform(0.15, 0.35, 1000)
    solid = Sphere(radii[0]).translated(centres[0])
    for c, r in zip(centres[1:], radii[1:]):
        solid = solid | Sphere(r).translated(c)
    assert solid.depth <= 14 and solid.n_leaves == 1000  # (log2 1,000 + 4)
    scene = Scene()
    scene.add(solid)
    size = (160, 120)
    camera = Camera.look_at((7, 6, 9), (0, 0, 0), fov_y=45).with_planes(scene.bounds)
    frame = make_renderer(*size).render_frame(scene, camera, "flat")
    # the rays of the pixel centres, as the reference renderer makes them
    from glshade.hidden.view import prepare

    p = prepare(Scene(), camera, size)
    inv = np.linalg.inv(camera.view_matrix())
    o = p.ray_origin @ inv[:3, :3].T + inv[:3, 3]
    d = p.ray_dir @ inv[:3, :3].T
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    first, leaf = np.full(len(o), np.inf), np.zeros(len(o), np.int64)
    for a in range(0, len(o), 1024):  # (chunks of rays: memory)
        oc = o[a:a + 1024, None, :] - centres[None]
        b = np.einsum("nkd,nd->nk", oc, d[a:a + 1024])
        disc = b * b - (np.einsum("nkd,nkd->nk", oc, oc) - radii ** 2)
        t = np.where(disc > 0, -b - np.sqrt(np.maximum(disc, 0)), np.inf)
        t = np.where(t > 0, t, np.inf)
        first[a:a + 1024], leaf[a:a + 1024] = t.min(1), t.argmin(1)
    point = o + np.where(np.isfinite(first), first, 0)[:, None] * d
    depth = np.where(np.isfinite(first), -(point @ camera.view_matrix()[2, :3]
                                           + camera.view_matrix()[2, 3]), np.inf)
    ids = np.where(np.isfinite(first), leaf, -1).reshape(size[::-1])
    ok = away_from_silhouettes(ids)
    assert (frame.face_id[ok] == ids[ok]).all()
    hit = ok & (ids >= 0)
    assert hit.sum() > 500
    assert (np.abs(frame.depth[hit] - depth.reshape(size[::-1])[hit]) /
            depth.reshape(size[::-1])[hit]).max() < 1e-4


TORI = {
    "thin ring edge-on": (Torus(2.0, 0.02), Camera.look_at((0, 0.0, 8), (0, 0, 0), fov_y=40)),
    "r/R = 0.01 from above the plane": (Torus(2.0, 0.02),
                                        Camera.look_at((0, 0.4, 8), (0, 0, 0), fov_y=40)),
    "through the hole": (Torus(1.0, 0.3), Camera.look_at((0, 4, 0.01), (0, 0, 0), fov_y=50)),
    "from inside the tube": (Torus(1.0, 0.3), Camera.look_at((1.0, 0.0, 0.0), (0, 0, -1),
                                                             fov_y=90, near=0.01)),
    "sheared, grazing the outer equator": (
        Torus(1.0, 0.25).transformed([[1, 0.4, 0, 0], [0, 1, 0, 0], [0, 0, 0.7, 0],
                                      [0, 0, 0, 1]]),
        Camera.look_at((0, 0.2, 6), (0, 0.2, 0), fov_y=30)),
}


@pytest.mark.parametrize("case", TORI.values(), ids=TORI.keys())
def test_tori_match_the_numpy_reference(case, make_renderer):
    solid, camera = case
    size = (160, 120)
    scene = Scene()
    scene.add(solid)
    frame = make_renderer(*size).render_frame(scene, camera, "phong")
    depth, normal, ids = render_solids(scene, camera, size)
    # every pixel: the same pixels are hit (a thin ring is mostly silhouette)
    differ = (frame.face_id >= 0) != (ids >= 0)
    assert differ.sum() <= 0.01 * max((ids >= 0).sum(), 1) + 2, differ.sum()
    hit = (frame.face_id >= 0) & (ids >= 0)
    assert hit.sum() > 50
    assert (np.abs(frame.depth[hit] - depth[hit]) / depth[hit]).max() < 1e-3
    # the normal faces the eye (never the back of the tube)
    assert np.quantile(np.abs(frame.normal[hit] - normal[hit]).max(-1), 0.98) < 1e-2


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_reference_agrees_with_bisection_on_contains(seed):
    """The first surface of random trees along random rays: the reference's event lists
    against sampling ``contains`` along each ray and bisecting the first change (only the
    inside test is shared: a different algorithm)."""
    solid = random_tree(12, seed)
    rng = np.random.default_rng(seed)
    n = 300
    o = rng.normal(size=(n, 3))
    o = 9 * o / np.linalg.norm(o, axis=1, keepdims=True)
    target = rng.uniform(-1.5, 1.5, (n, 3))
    d = target - o
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    t_ref = solid.intersect(o, d)[0]
    steps = np.linspace(0, 18, 3601)
    inside = solid.contains((o[:, None] + steps[None, :, None] * d[:, None]).reshape(-1, 3))
    inside = inside.reshape(n, -1)
    starts_in = inside[:, 0]
    change = inside != starts_in[:, None]
    has = change.any(1)
    k = np.argmax(change, axis=1)
    lo, hi = steps[np.maximum(k - 1, 0)], steps[k]
    for _ in range(40):
        mid = (lo + hi) / 2
        m_in = solid.contains(o + mid[:, None] * d)
        same = m_in == starts_in
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
    found = np.where(has, (lo + hi) / 2, np.inf)
    # a sliver thinner than the sampling step can hide from it: allow a few
    agree = np.isclose(found, t_ref, rtol=0, atol=1e-7) | (np.isinf(found) & np.isinf(t_ref))
    assert agree.mean() >= 0.98, (found[~agree][:5], t_ref[~agree][:5])
    assert has.sum() > 50


def walk_tree(solid, bits, leaves):
    """The tree's value for leaf inside-bits, by walking the solid's own nodes (a stack of
    (node, children done) -- the test's own evaluator, sharing nothing with the program)."""
    values: list = []
    stack: list = [(solid, False)]
    ops = {Union: np.logical_or, Intersection: np.logical_and,
           Difference: lambda a, b: a & ~b}
    while stack:
        node, done = stack.pop()
        while isinstance(node, Transformed):
            node = node.child
        if type(node) in ops:
            if done:
                b, a = values.pop(), values.pop()
                values.append(ops[type(node)](a, b))
            else:
                stack += [(node, True), (node.b, False), (node.a, False)]
        else:
            values.append(((bits >> next(leaves)) & 1).astype(bool))
    return values[0]


@pytest.mark.parametrize("seed", range(6))
def test_the_truth_table_is_the_tree(seed):
    solid = random_tree([1, 3, 6, 8, 10, 12][seed], seed=100 + seed)
    n = len(solid.leaves())  # (with the balls some intersections add)
    assert n <= 14
    _, booleans, root = flatten(solid)
    program, _, _ = postorder(booleans, root)
    bits = np.arange(2 ** n)
    expected = walk_tree(solid, bits, iter(range(n)))
    assert (truth_table(program, n) == expected).all()
    assert 0 < expected.sum() < 2 ** n or n == 1
