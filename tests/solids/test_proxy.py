"""A solid's screen proxy must hold every pixel the solid covers. Oracles that share nothing
with solids/proxy.py: points sampled inside a leaf or a tree by its ``contains`` (support
functions compared in many directions), and the numpy reference ray caster's pixels."""

import numpy as np
import pytest

from glshade import Camera, Scene
from glshade.cpu.csg import render_solids
from glshade.solids.encoding import flatten
from glshade.solids import Box, Cone, Cylinder, HalfSpace, Sphere, Torus
from glshade.solids.proxy import hull_points, leaf_points, screen_polygon

from ..render.test_csg_trees import random_tree

LEAVES = {
    "sphere": Sphere(0.7),
    "box": Box((1.0, 0.4, 2.2)),
    "cylinder": Cylinder(0.3, 2.0),
    "cone": Cone(0.5, 1.2),
    "torus": Torus(1.0, 0.2),
    "thin torus": Torus(2.0, 0.02),
}


def inside_points(solid, n=200_000, seed=0):
    """Points of ``solid`` (M, 3), sampled uniformly in its bounds and kept by contains."""
    lo, hi = solid.bounds
    p = np.random.default_rng(seed).uniform(lo, hi, (n, 3))
    return p[solid.contains(p)]


def directions(n=400, seed=1):
    d = np.random.default_rng(seed).normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


@pytest.mark.parametrize("name", list(LEAVES))
def test_a_leafs_points_hold_it_and_hug_it(name):
    leaf = LEAVES[name]
    pts, hull = inside_points(leaf), leaf_points(leaf)
    assert len(pts) > 1000
    u = directions()
    reach = (pts @ u.T).max(0)  # the leaf's support each way (sampled: a little short)
    cover = (hull @ u.T).max(0)
    assert (cover >= reach).all()  # holds it
    size = np.linalg.norm(leaf.bounds[1] - leaf.bounds[0])
    assert (cover - reach).max() < 0.06 * size  # and no box around a round leaf


def test_a_half_space_has_no_points():
    assert leaf_points(HalfSpace((0, 1, 0), 0.5)) is None
    solid = Sphere(1.0) - HalfSpace((0, 1, 0), 0.5)  # (subtracted: the hull is the ball's)
    leaves, _, _ = flatten(solid)
    assert hull_points(leaves) is not None
    leaves, _, _ = flatten(Sphere(1.0) & HalfSpace((0, 1, 0), 0.5))
    assert hull_points(leaves) is None


@pytest.mark.parametrize("seed", [3, 4, 5])
def test_the_hull_of_the_positive_leaves_holds_a_random_tree(seed):
    solid = random_tree(9, seed)
    leaves, _, _ = flatten(solid)
    hull = hull_points(leaves)
    pts = inside_points(solid, seed=seed)
    assert len(pts) > 500
    u = directions(seed=seed)
    assert ((hull @ u.T).max(0) >= (pts @ u.T).max(0)).all()


def pixel_ndc(size):
    w, h = size
    x, y = np.meshgrid((np.arange(w) + 0.5) / w * 2 - 1, 1 - (np.arange(h) + 0.5) / h * 2)
    return np.stack([x, y], -1)  # (H, W, 2): row 0 at the top


def in_polygon(p, corners):
    """(N,) whether points (N, 2) lie in the counter-clockwise convex polygon (K, 2)."""
    a, b = corners, np.roll(corners, -1, 0)
    cross = ((b - a)[None, :, 0] * (p[:, None, 1] - a[None, :, 1])
             - (b - a)[None, :, 1] * (p[:, None, 0] - a[None, :, 0]))
    return (cross >= 0).all(1)


CAMERAS = {
    "three quarters": ((0.55, 0.45, 0.7), 2.6),
    "from below, near": ((-0.3, -0.8, 0.5), 1.6),
    "down an axis": ((0.0, 0.0, 1.0), 2.2),
}


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("view", list(CAMERAS))
def test_the_screen_polygon_holds_every_pixel_the_reference_hits(seed, view):
    size = (96, 72)
    solid = random_tree(7, seed)
    scene = Scene()
    scene.add(solid)
    lo, hi = solid.bounds
    centre, reach = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    way, far = CAMERAS[view]
    camera = Camera.look_at(centre + far * reach * np.asarray(way), centre, fov_y=45)
    _, _, ids = render_solids(scene, camera, size)
    assert (ids >= 0).sum() > 100
    fitted = camera.with_planes(scene.bounds)
    view_proj = fitted.projection_matrix(size[0] / size[1]) @ fitted.view_matrix()
    leaves, _, _ = flatten(solid)
    corners = screen_polygon(view_proj, solid.bounds, hull_points(leaves), size)
    covered = in_polygon(pixel_ndc(size)[ids >= 0], corners)
    assert covered.all(), f"{(~covered).sum()} hit pixels outside the polygon"


def test_the_polygon_is_the_smaller_of_box_and_hull():
    """A ball seen whole: its hull's polygon (a 16-gon about its disc) is well under its
    box's; a box's own corners give the same polygon either way."""
    camera = Camera.look_at((0, 0, 6), (0, 0, 0), fov_y=40)
    view_proj = camera.with_planes(np.array([[-1.0] * 3, [1.0] * 3])).projection_matrix(1.0) \
        @ camera.view_matrix()
    ball = Sphere(1.0)
    leaves, _, _ = flatten(ball)
    poly = screen_polygon(view_proj, ball.bounds, hull_points(leaves), (256, 256))
    box_only = screen_polygon(view_proj, ball.bounds, None, (256, 256))
    area = lambda c: 0.5 * abs(np.dot(c[:, 0], np.roll(c[:, 1], -1))  # noqa: E731
                               - np.dot(c[:, 1], np.roll(c[:, 0], -1)))
    disc = np.pi * np.tan(np.arcsin(1 / 6)) ** 2 / np.tan(np.radians(20)) ** 2  # (NDC units)
    assert disc < area(poly) < 1.2 * disc  # (16 sides, circumscribed rings, 2 pixels)
    assert area(box_only) > 1.2 * area(poly)


def test_behind_the_eye_and_inside():
    """A solid behind the camera has no polygon; with the camera inside it, its box cut by
    the near plane fills the screen; half in view, the polygon stops at the screen's edge."""
    ball = Sphere(1.0)
    leaves, _, _ = flatten(ball)
    hull = hull_points(leaves)
    behind = Camera.look_at((0, 0, 3), (0, 0, 6), fov_y=60)
    view_proj = behind.projection_matrix(1.0) @ behind.view_matrix()
    assert len(screen_polygon(view_proj, ball.bounds, hull, (64, 64))) == 0
    inside = Camera.look_at((0, 0, 0.5), (0, 0, -1), fov_y=60, near=0.01)
    view_proj = inside.projection_matrix(1.0) @ inside.view_matrix()
    corners = screen_polygon(view_proj, ball.bounds, hull, (64, 64))
    assert in_polygon(pixel_ndc((64, 64)).reshape(-1, 2), corners).all()
    aside = Camera.look_at((0, 0, 4), (1.2, 0, 0), fov_y=40)
    view_proj = aside.projection_matrix(1.0) @ aside.view_matrix()
    corners = screen_polygon(view_proj, ball.bounds, hull, (64, 64))
    assert np.abs(corners).max() <= 1 + 4 / 64 + 1e-9 and corners[:, 0].min() < -0.99
