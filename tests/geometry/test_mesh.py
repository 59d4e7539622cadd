"""Mesh construction, validation, normals, triangulation and creases."""

import numpy as np
import pytest

from glshade import GeometryError, Mesh, newell_normal
from glshade.geometry import primitives


def test_accepts_list_of_lists_and_array():
    v = np.eye(3)
    a = Mesh(v, [[0, 1, 2]])
    b = Mesh(v, np.array([[0, 1, 2]]))
    np.testing.assert_array_equal(a.face_indices, b.face_indices)
    np.testing.assert_array_equal(a.face_offsets, [0, 3])


def test_mixed_sizes_stored_flat():
    v = np.random.default_rng(1).normal(size=(6, 3))
    m = Mesh(v, [[0, 1, 2], [0, 1, 2, 3], [1, 2, 3, 4, 5]])
    np.testing.assert_array_equal(m.face_offsets, [0, 3, 7, 12])
    np.testing.assert_array_equal(m.face(2), [1, 2, 3, 4, 5])


@pytest.mark.parametrize("faces, message", [
    ([[0, 1]], r"face 0 has 2 vertices"),
    ([[0, 1, 2], [0, 1, 9]], r"face 1 refers to vertex 9, but there are 3 vertices"),
    ([[0, 1, -1]], r"face 0 refers to vertex -1"),
])
def test_bad_faces_are_named(faces, message):
    with pytest.raises(GeometryError, match=message):
        Mesh(np.eye(3), faces)


def test_non_finite_vertex_is_named():
    v = np.eye(3)
    v[1, 2] = np.nan
    with pytest.raises(ValueError, match=r"vertex 1 has a non-finite"):
        Mesh(v, [[0, 1, 2]])


def test_bad_vertex_shape():
    with pytest.raises(GeometryError, match=r"shape \(n, 3\), got \(4, 2\)"):
        Mesh(np.zeros((4, 2)), [[0, 1, 2]])


def test_face_normals_mixed_sizes_match_a_fan_of_cross_products(rng):
    """Each face's normal against an oracle that shares nothing with Newell's sum the
    mesh uses: the vector area of the face's fan of triangles from its first corner."""
    m = primitives.cylinder(9)  # quads and 9-gons
    fans = []
    for f in m.faces:
        p = m.vertices[f]
        fans.append(sum(np.cross(p[i] - p[0], p[i + 1] - p[0]) for i in range(1, len(p) - 1)))
    expected = np.array(fans) / np.linalg.norm(fans, axis=1, keepdims=True)
    np.testing.assert_allclose(m.face_normals, expected, atol=1e-12)
    # caps point along +-y, sides horizontally
    assert np.allclose(m.face_normals[-2], [0, 1, 0]) and np.allclose(m.face_normals[-1],
                                                                       [0, -1, 0])


def test_degenerate_face_gets_zero_normal_and_is_reported():
    v = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]], float)
    m = Mesh(v, [[0, 1, 2], [0, 1, 3]])
    assert np.isfinite(m.face_normals).all()
    np.testing.assert_array_equal(m.face_normals[0], 0)
    np.testing.assert_array_equal(m.degenerate_faces, [0])
    np.testing.assert_allclose(m.face_normals[1], [0, 0, 1])


def test_face_areas_and_centroids():
    m = primitives.cube()
    np.testing.assert_allclose(m.face_areas, 1.0)
    np.testing.assert_allclose(np.abs(m.face_centroids).max(axis=1), 0.5)
    assert m.total_area == pytest.approx(6.0)


def test_icosphere_vertex_normals_equal_positions():
    m = primitives.icosphere(4)
    angle = np.arccos(np.clip(np.einsum("ij,ij->i", m.vertex_normals, m.vertices), -1, 1))
    assert angle.max() < 1e-2


def test_vertex_normal_is_normalised_sum_of_unit_face_normals():
    # the corner of a cube: the sum of three unit axis normals
    m = primitives.cube()
    corner = int(np.argmax(m.vertices.sum(axis=1)))  # (+.5, +.5, +.5)
    np.testing.assert_allclose(m.vertex_normals[corner], np.ones(3) / np.sqrt(3))


def test_weighted_vertex_normals():
    # a vertex shared by a big and a small face: area weighting leans to the big one
    v = np.array([[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 1], [1, 0, 0]], float)
    m = Mesh(v, [[0, 1, 2], [0, 4, 3]])  # normals +z (area 50) and -y (area 0.5)
    unit = m.vertex_normals[0]
    area = m.vertex_normals_weighted("area")[0]
    angle = m.vertex_normals_weighted("angle")[0]
    np.testing.assert_allclose(unit, np.array([0, -1, 1]) / np.sqrt(2))
    np.testing.assert_allclose(area, np.array([0, -0.5, 50]) / np.hypot(0.5, 50))
    np.testing.assert_allclose(angle, unit)  # both corners are right angles
    with pytest.raises(GeometryError, match="'area', 'angle'"):
        m.vertex_normals_weighted("volume")


def test_triangulate_concave_and_convex(rng):
    outline = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    cap = np.c_[outline[:, 0], outline[:, 1], np.zeros(6)]
    m = Mesh(np.vstack([cap, [[3, 0, 0], [4, 0, 0], [4, 1, 0], [3, 1, 0]]]),
             [list(range(6)), [6, 7, 8, 9]])
    tri, owner = m.triangulate()
    assert len(tri) == 4 + 2
    np.testing.assert_array_equal(np.bincount(owner), [4, 2])
    n = newell_normal(m.vertices[tri])
    assert (n[:, 2] > 0).all()  # wound like the polygons, no flipped triangle
    per_face = np.bincount(owner, np.linalg.norm(n, axis=1) / 2)
    np.testing.assert_allclose(per_face, m.face_areas)


def test_split_creases_cube_and_sphere():
    cube = primitives.cube().split_creases(30)
    assert cube.n_vertices == 24  # every corner split into its three faces
    np.testing.assert_allclose(cube.vertex_normals[cube.face_indices],
                               cube.face_normals[cube.corner_face], atol=1e-12)
    sphere = primitives.icosphere(2)
    assert sphere.split_creases(30).n_vertices == sphere.n_vertices  # smooth: nothing split
    assert sphere.split_creases(0).n_vertices == 3 * sphere.n_faces  # everything split


def test_flipped_and_transformed_keep_orientation_meaningful():
    m = primitives.cube()
    assert m.flipped().signed_volume() == pytest.approx(-1.0)
    mirror = np.diag([-1.0, 1, 1])
    assert m.transformed(mirror).signed_volume() == pytest.approx(1.0)
    scale = np.diag([2.0, 3, 4, 1])
    assert m.transformed(scale).signed_volume() == pytest.approx(24.0)


def test_weld_collapses_duplicates():
    m = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 0], [1, 0, 0], [0, 0, 1]],
             [[0, 1, 2], [3, 5, 4]])
    w = m.weld()
    assert w.n_vertices == 4 and w.n_edges == 5
