"""CSG solids against closed forms: membership, volumes, and Roth's ray casting against
membership along the rays and against the analytic sphere."""

import numpy as np
import pytest

from glshade.errors import GeometryError
from glshade.solids import Box, Cone, Cylinder, HalfSpace, Sphere, Torus

SHEAR = np.array([[1.0, 0.4, 0.0, 0.3], [0.0, 1.0, 0.2, -0.1], [0.0, 0.0, 1.5, 0.2],
                  [0.0, 0.0, 0.0, 1.0]])
QUARTER_X = [np.sin(np.pi / 4), 0.0, 0.0, np.cos(np.pi / 4)]  # 90 degrees about x


def every_kind():
    """A tree with every leaf and node kind, a rotation and a sheared transform."""
    block = Box((2.0, 1.0, 2.0)) - Cylinder(0.4, 3.0).rotated(QUARTER_X)
    return ((block | Sphere(0.6).translated((0, 0.8, 0))) & HalfSpace((0, 0, 1), 0.7)
            | Torus(1.0, 0.25).transformed(SHEAR) | Cone(0.5, 1.0).scaled((1, 2, 1))
            .translated((1.6, 0, 0)))


def closed_form(p):
    x, y, z = p.T
    block = (np.abs(x) <= 1) & (np.abs(y) <= 0.5) & (np.abs(z) <= 1) & \
        ~((x ** 2 + y ** 2 <= 0.16) & (np.abs(z) <= 1.5))  # the cylinder turned onto z
    ball = x ** 2 + (y - 0.8) ** 2 + z ** 2 <= 0.36
    first = (block | ball) & (z <= 0.7)
    q = (p - SHEAR[:3, 3]) @ np.linalg.inv(SHEAR[:3, :3]).T
    ring = (np.hypot(q[:, 0], q[:, 2]) - 1.0) ** 2 + q[:, 1] ** 2 <= 0.0625
    c = (p - [1.6, 0, 0]) / [1, 2, 1]
    cone = (np.hypot(c[:, 0], c[:, 2]) <= 0.5 * (0.5 - c[:, 1])) & (np.abs(c[:, 1]) <= 0.5)
    return first | ring | cone


def test_contains_matches_the_closed_form():
    rng = np.random.default_rng(7)
    p = rng.uniform(-2.5, 2.5, (200_000, 3))
    got = every_kind().contains(p)
    assert got.mean() > 0.03  # (a test of something: 4% of the cube is inside)
    assert np.array_equal(got, closed_form(p))


def test_volumes_of_known_solids():
    for r in (0.3, 0.6):
        part = Box(2.0) - Cylinder(r, 3.0)  # a 2x2x2 block minus a through hole
        v, err = part.volume(400_000, seed=1)
        assert abs(v - (8 - 2 * np.pi * r * r)) < 4 * err
    v, err = Torus(1.0, 0.3).volume(400_000, seed=2)
    assert abs(v - 2 * np.pi ** 2 * 1.0 * 0.09) < 4 * err
    v, err = Sphere(1.0).transformed(SHEAR).volume(400_000, seed=3)
    assert abs(v - 4 / 3 * np.pi * np.linalg.det(SHEAR[:3, :3])) < 4 * err


def test_ray_events_agree_with_membership_along_every_ray():
    rng = np.random.default_rng(11)
    tree = every_kind()
    o = rng.uniform(-3, 3, (3000, 3))
    d = rng.normal(size=(3000, 3))
    ev = tree.events(o, d)
    assert ev.t.shape[1] == 2 + 2 + 2 + 2 + 4 + 2  # sized from the leaves
    ts = rng.uniform(-5, 5, (3000, 40))
    inside = (ev.kind[:, None, :] * (ev.t[:, None, :] <= ts[:, :, None])).sum(2) > 0
    points = (o[:, None, :] + ts[..., None] * d[:, None, :]).reshape(-1, 3)
    assert np.array_equal(inside.ravel(), closed_form(points))


def test_first_hit_on_a_sphere_and_normals_of_a_hole():
    rng = np.random.default_rng(5)
    o = rng.uniform(-3, 3, (500, 3)) * [1, 1, 0] + [0, 0, 5]
    d = np.tile([0.0, 0.0, -1.0], (500, 1))
    t, n, leaf = Sphere(2.0).translated((0.5, 0, 0)).intersect(o, d)
    c = o - [0.5, 0, 0]
    disc = 4.0 - c[:, 0] ** 2 - c[:, 1] ** 2
    expected = np.where(disc >= 0, c[:, 2] - np.sqrt(np.maximum(disc, 0)), np.inf)
    assert np.allclose(t[np.isfinite(t)], expected[np.isfinite(t)], rtol=1e-12)
    assert np.array_equal(np.isfinite(t), disc > 0)
    hit = np.isfinite(t)
    p = o + np.where(hit, t, 0.0)[:, None] * d
    assert np.allclose(n[hit], (p[hit] - [0.5, 0, 0]) / 2.0, atol=1e-9)
    assert set(leaf[hit]) == {0} and set(leaf[~hit]) == {-1}
    # a block with a spherical pocket cut into its top: normals face into the pocket
    part = Box(2.0) - Sphere(0.5).translated((0, 1, 0))
    t, n, leaf = part.intersect([[0.0, 5.0, 0.0]], [[0.0, -1.0, 0.0]])
    assert np.isclose(t[0], 5 - 0.5) and leaf[0] == 1
    assert np.allclose(n[0], [0, 1, 0])  # at the pocket's bottom, facing up into it


def test_bad_solids_say_what_is_wrong():
    with pytest.raises(GeometryError, match="singular"):
        Sphere().transformed(np.diag([1.0, 0.0, 1.0, 1.0]))
    with pytest.raises(GeometryError, match="non-finite"):
        Box().transformed(np.diag([1.0, np.nan, 1.0, 1.0]))
    with pytest.raises(GeometryError, match="r < R"):
        Torus(1.0, 1.5)
    with pytest.raises(GeometryError, match="radius must be a positive"):
        Cylinder(-1.0)
    with pytest.raises(GeometryError, match="must be solids"):
        Sphere() | 3
    with pytest.raises(GeometryError, match="unbounded"):
        HalfSpace().volume()
    assert (Box(2.0) & HalfSpace()).bounds.tolist() == [[-1, -1, -1], [1, 1, 1]]


def test_a_pickled_tree_loads_in_a_fresh_process():
    """Worker processes unpickle solids before anything else imports them: the leaves'
    module (what a pickle names) must load first as well as second."""
    import pickle
    import subprocess
    import sys

    tree = (Box((2, 1, 2)) - Cylinder(0.4, 3)).translated((0.5, 0, 0)) | Sphere(0.6)
    code = ("import pickle, sys, numpy as np; _, s = pickle.loads(sys.stdin.buffer.read()); "
            "print(int(s.contains(np.array([[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], "
            "[1.4, 0.0, 0.9]])).sum()))")
    payload = pickle.dumps((Sphere(1.0), tree))  # (a leaf's class is the first looked up)
    done = subprocess.run([sys.executable, "-c", code], input=payload,
                          capture_output=True, timeout=60)
    assert done.returncode == 0, done.stderr.decode()
    expected = tree.contains(np.array([[0.0, 0, 0], [0.5, 0, 0], [1.4, 0, 0.9]])).sum()
    assert int(done.stdout) == expected
