"""Primitives: outward orientation, analytic volumes, Euler characteristics."""

import numpy as np
import pytest

from glshade import GeometryError
from glshade.geometry import primitives as P

CLOSED = {
    "cube": P.cube(), "uv_sphere": P.uv_sphere(12, 24), "icosphere": P.icosphere(2),
    "torus": P.torus(1.0, 0.3, 24, 12), "cylinder": P.cylinder(16),
}


def euler(m):
    return m.n_vertices - m.n_edges + m.n_faces


@pytest.mark.parametrize("name", sorted(CLOSED))
def test_closed_primitives_are_outward(name):
    m = CLOSED[name]
    assert m.signed_volume() > 0
    # every edge is shared by exactly two faces, traversed in opposite directions
    he = m.half_edges
    key = he[:, 0] * m.n_vertices + he[:, 1]
    rev = he[:, 1] * m.n_vertices + he[:, 0]
    assert len(np.unique(key)) == len(key)
    assert np.isin(rev, key).all()
    # face normals point away from the centre for these convex-ish shapes
    if name != "torus":
        assert (np.einsum("ij,ij->i", m.face_normals, m.face_centroids) > 0).all()


def test_cube_volume_exactly_one():
    assert P.cube().signed_volume() == 1.0
    assert P.cube().n_vertices == 8 and P.cube().n_faces == 6


def test_icosphere_volume_increases_to_sphere():
    vols = [P.icosphere(k).signed_volume() for k in range(5)]
    assert all(a < b for a, b in zip(vols, vols[1:]))
    assert vols[-1] < 4 / 3 * np.pi
    assert vols[-1] == pytest.approx(4 / 3 * np.pi, rel=5e-3)
    np.testing.assert_allclose(np.linalg.norm(P.icosphere(3).vertices, axis=1), 1.0,
                               rtol=0, atol=1e-15)
    assert P.icosphere(3).n_faces == 20 * 4**3


def test_cylinder_and_torus_volumes_converge():
    # polygonal prism: n/2 sin(2pi/n) r^2 h exactly
    n = 16
    assert P.cylinder(n).signed_volume() == pytest.approx(n / 2 * np.sin(2 * np.pi / n) * 2)
    t = P.torus(1.0, 0.3, 200, 100).signed_volume()
    assert t == pytest.approx(2 * np.pi**2 * 1.0 * 0.3**2, rel=2e-3)


@pytest.mark.parametrize("name, chi", [("cube", 2), ("uv_sphere", 2), ("icosphere", 2),
                                       ("cylinder", 2), ("torus", 0)])
def test_euler_characteristic(name, chi):
    assert euler(CLOSED[name]) == chi


def test_cornell_box_parts():
    """The published box (mm): walls face into the room, the blocks outward, the light
    down; the parts are the published ones."""
    m = P.cornell_box()
    assert set(m.groups) == {"floor", "ceiling", "back_wall", "green_wall", "red_wall",
                             "light", "short_block", "tall_block"}
    assert (m.face_sizes == 4).all()
    np.testing.assert_allclose(m.face_normals[m.groups["floor"]], [[0, 1, 0]], atol=1e-12)
    np.testing.assert_allclose(m.face_normals[m.groups["back_wall"]], [[0, 0, -1]],
                               atol=1e-3)
    np.testing.assert_allclose(m.face_normals[m.groups["light"]], [[0, -1, 0]], atol=1e-12)
    for box in ("short_block", "tall_block"):
        assert len(m.groups[box]) == 5  # (as published: four sides and a top, no bottom)
    assert m.bounds[1, 1] == pytest.approx(548.8) and m.bounds[0, 1] == 0.0  # mm


def test_teapot():
    t = P.teapot(6)
    assert t.signed_volume() > 0
    assert t.bounds[0, 1] == pytest.approx(0.0) and t.bounds[1, 1] == pytest.approx(3.15)
    assert len(t.degenerate_faces) == 0
    # seams are welded and consistently oriented: no directed edge appears twice
    he = t.half_edges
    key = he[:, 0] * t.n_vertices + he[:, 1]
    assert len(np.unique(key)) == len(key)
    assert P.teapot(8).n_faces > P.teapot(4).n_faces


def test_from_spec():
    assert P.from_spec("primitive:icosphere:1").n_faces == 80
    assert P.from_spec("torus:1,0.5,8,4").n_faces == 32
    with pytest.raises(GeometryError, match="unknown primitive 'sphere'; choose one of"):
        P.from_spec("sphere")
    with pytest.raises(GeometryError, match="not a number"):
        P.from_spec("icosphere:x")
    with pytest.raises(GeometryError, match="subdivisions must be an integer"):
        P.icosphere(-1)
