"""Exact surfaces and file normals follow the mesh through transforms, flips, welds and
crease splits (the oracle: the ellipsoid's closed-form normal)."""

import numpy as np
import pytest

from glshade import GeometryError, Mesh
from glshade.geometry import AnalyticSphere
from glshade.geometry import primitives as P

SHEAR = np.array([[1.5, 0.4, 0.0, 0.3], [0.0, 0.8, 0.2, -0.5], [0.1, 0.0, 1.1, 0.2],
                  [0, 0, 0, 1.0]])


def ellipsoid_normal(points, m):
    """Unit normal of the sphere |x| = r mapped by m, at world points (closed form: the
    gradient of |M^-1 (p - t)|^2)."""
    inv = np.linalg.inv(m[:3, :3])
    q = (points - m[:3, 3]) @ inv.T
    n = q @ inv
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def test_transformed_sphere_keeps_its_exact_surface():
    sphere = P.icosphere(2, radius=0.8)
    moved = sphere.transformed(SHEAR)
    assert isinstance(moved.analytic, AnalyticSphere)
    np.testing.assert_allclose(moved.analytic.matrix, SHEAR)
    # rays from outside towards the mesh vertices meet the exact surface at those vertices
    target = moved.vertices[:50]
    origin = target + 5 * ellipsoid_normal(target, SHEAR)
    t, n = moved.analytic.intersect(origin, target - origin)
    np.testing.assert_allclose(origin + t[:, None] * (target - origin), target, atol=1e-9)
    np.testing.assert_allclose(n, ellipsoid_normal(target, SHEAR), atol=1e-9)


def test_flip_weld_and_creases_keep_the_surface():
    sphere = P.icosphere(1)
    flipped = sphere.flipped()
    p = np.array([[0.0, 0.0, 3.0]])
    d = np.array([[0.0, 0.0, -1.0]])
    t0, n0 = sphere.analytic.intersect(p, d)
    t1, n1 = flipped.analytic.intersect(p, d)
    assert t0 == t1 == pytest.approx(2.0)
    np.testing.assert_allclose(n1, -n0)
    assert sphere.weld().analytic is sphere.analytic
    assert sphere.split_creases(10).analytic is sphere.analytic


def test_file_normals_follow_by_the_inverse_transpose():
    sphere = P.icosphere(2)
    with_normals = Mesh(sphere.vertices, sphere.face_indices.reshape(-1, 3),
                        normals=sphere.vertices)
    moved = with_normals.transformed(SHEAR)
    np.testing.assert_allclose(moved.normals_from_file, ellipsoid_normal(moved.vertices, SHEAR),
                               atol=1e-12)
    np.testing.assert_allclose(with_normals.flipped().normals_from_file,
                               -with_normals.normals_from_file)
    mirror = np.diag([-1.0, 1, 1, 1])
    mirrored = with_normals.transformed(mirror)
    np.testing.assert_allclose(mirrored.normals_from_file, mirrored.vertices, atol=1e-12)
    assert mirrored.signed_volume() > 0  # faces reversed: still outward
    creased = with_normals.split_creases(0)
    np.testing.assert_allclose(creased.normals_from_file, creased.vertices, atol=1e-12)


def test_weld_keeps_normals_and_renumbers_groups():
    quad = Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 0], [1, 1, 0]],
                [[0, 1, 2, 3], [4, 5, 2]], normals=[[0, 0, 1]] * 6, groups={"b": [1]})
    welded = quad.weld()
    assert welded.n_vertices == 4 and welded.n_faces == 1  # the sliver collapsed
    np.testing.assert_allclose(welded.normals_from_file, [[0, 0, 1]] * 4)
    assert welded.groups["b"].tolist() == []


@pytest.mark.parametrize("matrix, message", [
    (np.zeros((4, 4)), "must be affine"),
    (np.diag([1.0, 0, 1, 1]), "singular"),
    (np.full((4, 4), np.nan), "non-finite"),
    (np.eye(2), "shape"),
])
def test_bad_transforms_are_clear_errors(matrix, message):
    with pytest.raises(GeometryError, match=message):
        P.cube().transformed(matrix)
