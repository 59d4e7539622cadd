"""Newell's formula against independent oracles: the shoelace area, cross products,
rotations."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from glshade import GeometryError, newell_normal, polygon_area
from glshade.geometry.polygon import ear_clip


def shoelace(xy):
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * (np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def embed(xy, rotation, offset):
    """Put a 2-D polygon into 3-D: the plane z=0 rotated and moved."""
    p = np.c_[xy, np.zeros(len(xy))]
    return rotation.apply(p) + offset


@pytest.mark.parametrize("k", [3, 4, 5, 7, 12])
def test_planar_polygons_area_matches_shoelace(rng, k):
    for _ in range(20):
        # a star-shaped (possibly concave) polygon: angles jittered about a regular
        # polygon's (every gap < pi, so the origin sees all of it), random radii
        angles = 2 * np.pi * (np.arange(k) + rng.uniform(0.4, 0.6, k)) / k
        radii = rng.uniform(0.3, 2.0, k)
        xy = np.c_[radii * np.cos(angles), radii * np.sin(angles)]
        rot = Rotation.random(random_state=rng.integers(1 << 31))
        p = embed(xy, rot, rng.normal(size=3) * 10)
        n = newell_normal(p)
        assert np.linalg.norm(n) == pytest.approx(2 * shoelace(xy), rel=1e-9)
        # direction: the rotated +z (counter-clockwise in the xy plane)
        np.testing.assert_allclose(n / np.linalg.norm(n), rot.apply([0, 0, 1]), atol=1e-9)
        assert polygon_area(p) == pytest.approx(shoelace(xy), rel=1e-9)


def test_triangle_equals_cross_product(rng):
    p = rng.normal(size=(1000, 3, 3))
    expected = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 1])
    np.testing.assert_allclose(newell_normal(p), expected, atol=1e-12)
    # and equals the general sum (the fast path is not a different formula)
    general = np.cross(p, np.roll(p, -1, axis=1)).sum(axis=1)
    np.testing.assert_allclose(newell_normal(p), general, atol=1e-12)


def test_quad_fast_path_equals_general_sum(rng):
    p = rng.normal(size=(1000, 4, 3))
    general = np.cross(p, np.roll(p, -1, axis=1)).sum(axis=1)
    np.testing.assert_allclose(newell_normal(p), general, atol=1e-12)


def test_first_three_vertices_collinear():
    # the square with an extra vertex on its first edge
    p = np.array([[0, 0, 0], [0.5, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    naive = np.cross(p[1] - p[0], p[2] - p[1])
    assert np.allclose(naive, 0)  # the two-edge cross product fails here
    np.testing.assert_allclose(newell_normal(p), [0, 0, 2])  # Newell does not


def test_concave_polygon():
    # an L shape of area 3 in the plane y = 2, counter-clockwise seen from +y
    xz = np.array([[0, 0], [0, 2], [1, 2], [1, 1], [2, 1], [2, 0]], float)
    p = np.c_[xz[:, 0], np.full(6, 2.0), xz[:, 1]]
    np.testing.assert_allclose(newell_normal(p), [0, 6, 0], atol=1e-12)


def test_non_planar_quad_best_fit():
    # a saddle quad symmetric about z: the best-fit normal is +z, with the projected area
    p = np.array([[1, 0, 0.3], [0, 1, -0.3], [-1, 0, 0.3], [0, -1, -0.3]], float)
    n = newell_normal(p)
    np.testing.assert_allclose(n[:2], 0, atol=1e-12)
    assert n[2] == pytest.approx(2 * 2.0)  # projected square of area 2


def test_rotation_rotates_normal(rng):
    p = rng.normal(size=(50, 6, 3))
    rots = Rotation.random(50, random_state=7)
    rotated = np.stack([r.apply(q) for r, q in zip(rots, p)])
    np.testing.assert_allclose(newell_normal(rotated), rots.apply(newell_normal(p)), atol=1e-9)


def test_bad_shape_is_reported():
    with pytest.raises(GeometryError, match=r"\(\.\.\., K, 3\).*\(4, 2\)"):
        newell_normal(np.zeros((4, 2)))


def test_ear_clip_concave_area_preserved():
    xz = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    p = np.c_[xz[:, 0], np.zeros(6), xz[:, 1]]
    n = newell_normal(p)
    tri = ear_clip(p, n)
    assert tri.shape == (4, 3)
    normals = newell_normal(p[tri])
    assert (normals @ n > 0).all()  # every triangle wound like the polygon
    assert np.linalg.norm(normals, axis=1).sum() / 2 == pytest.approx(3.0)
