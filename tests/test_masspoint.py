"""Mass-points: the notes' sum rule, vectors of mass zero, quaternion form, and centres of
mass of meshes against hand-computed values."""

import numpy as np
import pytest

from glshade import GeometryError, MassPoint, Mesh, centroid
from glshade.geometry import primitives as P


def test_sum_is_at_the_centre_of_mass():
    a = MassPoint([0.0, 0, 0], 1.0)
    b = MassPoint([4.0, 0, 0], 3.0)
    s = a + b
    assert float(s.mass) == 4.0
    np.testing.assert_allclose(s.point, [3, 0, 0])
    np.testing.assert_allclose(s.weighted, [12, 0, 0])  # m1 P1 + m2 P2


def test_vectors_have_mass_zero_and_translate_points():
    v = MassPoint.vector([1.0, 2, 3])
    assert v.is_vector
    with pytest.raises(GeometryError, match="no point"):
        _ = v.point
    p = MassPoint([1.0, 1, 1], 2.0)
    # adding the vector (v, 0) to (2P, 2) moves the point by v / 2
    np.testing.assert_allclose((p + v).point, [1.5, 2, 2.5])
    # the difference of two points of equal mass is a vector
    d = MassPoint([3.0, 0, 0], 1) - MassPoint([1.0, 0, 0], 1)
    assert d.is_vector and np.allclose(d.weighted, [2, 0, 0])


def test_scalar_multiplication_keeps_the_point():
    p = MassPoint([1.0, 2, 3], 2.0) * 5
    assert float(p.mass) == 10
    np.testing.assert_allclose(p.point, [1, 2, 3])
    with pytest.raises(GeometryError, match="non-zero mass"):
        MassPoint([0, 0, 0], 0)


def test_quaternion_form():
    p = MassPoint([1.0, 2, 3], 2.0)
    q = p.to_quaternion()
    np.testing.assert_allclose(q, [2, 4, 6, 2])  # m O + m P
    back = MassPoint.from_quaternion(q)
    np.testing.assert_allclose(back.point, [1, 2, 3])
    # the sum of mass-points is the sum of their quaternions
    a, b = MassPoint([0.0, 1, 0], 1), MassPoint([2.0, 0, 0], 3)
    np.testing.assert_allclose((a + b).to_quaternion(), a.to_quaternion() + b.to_quaternion())


def test_arrays_and_centroid(rng):
    pts = rng.normal(size=(100, 3))
    m = rng.uniform(0.5, 2, 100)
    arr = MassPoint(pts, m)
    np.testing.assert_allclose(arr.sum().point, (pts * m[:, None]).sum(0) / m.sum())
    np.testing.assert_allclose(centroid(pts, m), arr.sum().point)
    np.testing.assert_allclose(centroid(pts), pts.mean(0))
    with pytest.raises(GeometryError, match="sum to zero"):
        centroid([[0, 0, 0], [1, 0, 0]], [1, -1])


def test_center_of_mass_cube_and_torus():
    cube = P.cube().transformed(np.diag([2.0, 1, 1, 1]) @ np.eye(4))
    shifted = cube.transformed(np.array([[1, 0, 0, 3], [0, 1, 0, -1], [0, 0, 1, 2],
                                         [0, 0, 0, 1.0]]))
    np.testing.assert_allclose(shifted.center_of_mass(), [3, -1, 2], atol=1e-12)
    np.testing.assert_allclose(shifted.center_of_mass("surface"), [3, -1, 2], atol=1e-12)
    torus = P.torus(1.0, 0.3, 32, 16).transformed(np.array(
        [[1, 0, 0, 0.5], [0, 1, 0, 0.25], [0, 0, 1, 0], [0, 0, 0, 1.0]]))
    np.testing.assert_allclose(torus.center_of_mass(), [0.5, 0.25, 0], atol=1e-12)


def test_center_of_mass_l_prism_by_hand():
    # L of unit squares at (0..2, 0..1) and (0..1, 1..2) in xz, extruded 1 in y:
    # solid centroid: areas 2 and 1 at x=(1, .5), z=(.5, 1.5) -> (5/6, 1/2, 5/6)
    outline = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    n = 6
    bottom = np.c_[outline[:, 0], np.zeros(n), outline[:, 1]]
    v = np.vstack([bottom, bottom + [0, 1, 0]])
    sides = [[i, n + i, n + (i + 1) % n, (i + 1) % n] for i in range(n)]
    m = Mesh(v, [list(range(n)), [n + i for i in reversed(range(n))], *sides])
    assert m.signed_volume() == pytest.approx(3.0)
    np.testing.assert_allclose(m.center_of_mass(), [5 / 6, 0.5, 5 / 6], atol=1e-12)


def test_center_of_mass_of_a_mesh_object():
    """A Mesh is taken as it is (its triangles); anything else of the wrong shape is named."""
    from glshade.geometry import primitives
    from glshade.masspoint import mesh_center_of_mass

    shifted = primitives.cube().transformed(np.array([[1, 0, 0, 2.0], [0, 1, 0, -1.0],
                                                      [0, 0, 1, 0.5], [0, 0, 0, 1.0]]))
    np.testing.assert_allclose(mesh_center_of_mass(shifted), [2.0, -1.0, 0.5], atol=1e-12)
    np.testing.assert_allclose(mesh_center_of_mass(shifted, "surface"), [2.0, -1.0, 0.5],
                               atol=1e-12)
    with pytest.raises(GeometryError, match=r"triangles of shape \(T, 3, 3\), got \(4, 3\)"):
        mesh_center_of_mass(np.zeros((4, 3)))
