"""Undirected edge groups against a plain dictionary, and the closed-and-oriented test
against hand-built cases."""

import numpy as np

from glshade import Mesh
from glshade.geometry import primitives as P
from glshade.geometry.edges import edge_groups, is_closed_and_oriented


def test_groups_equal_a_dictionary_of_edges(rng):
    a = rng.integers(0, 30, 500)
    b = rng.integers(0, 30, 500)
    g = edge_groups(a, b, 30)
    expected = {}
    for i, (x, y) in enumerate(zip(a.tolist(), b.tolist())):
        expected.setdefault((min(x, y), max(x, y)), []).append(i)
    assert sorted(zip(g.lo.tolist(), g.hi.tolist())) == sorted(expected)
    for e, (lo, hi) in enumerate(zip(g.lo.tolist(), g.hi.tolist())):
        members = g.order[g.start[e]:g.start[e] + g.count[e]].tolist()
        assert members == expected[(lo, hi)]  # input order kept within a group
        assert (g.group[members] == e).all()
    h0, h1 = g.pairs()
    assert len(h0) == sum(len(v) == 2 for v in expected.values())


def test_closed_and_oriented_cases():
    cube = P.cube()
    assert cube.closed_and_oriented
    assert P.icosphere(2).closed_and_oriented
    faces = [f.tolist() for f in cube.faces]
    faces[0] = faces[0][::-1]  # one face wound the wrong way
    assert not Mesh(cube.vertices, faces).closed_and_oriented
    assert not Mesh(cube.vertices, faces[1:]).closed_and_oriented  # a hole
    assert not P.plane().closed_and_oriented
    assert not is_closed_and_oriented(np.zeros((0, 2), np.int64), 0)


def test_mesh_edges_and_euler_of_a_torus():
    torus = P.torus(1.0, 0.3, 12, 8)
    assert torus.n_edges == 2 * 12 * 8  # a quad torus: E = 2F
    assert torus.n_vertices - torus.n_edges + torus.n_faces == 0


def test_each_edge_sides_triangle_holds_the_edge_in_its_face():
    """``Mesh.edge_side_triangles`` against a plain search: for each edge and side, the
    triangle of that side's face whose corners hold both of the edge's ends (-1 where the
    face drew none) -- on meshes of triangles, quads, non-planar quads (the teapot's
    patches), a pentagon (a fan of three) and a collinear triangle."""
    pentagon = Mesh(np.c_[np.cos(np.arange(5) * 1.2566), np.sin(np.arange(5) * 1.2566),
                          np.zeros(5)], [[0, 1, 2, 3, 4]])
    degenerate = Mesh(np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0.0]]),
                      [[0, 1, 2], [0, 1, 3]])
    for mesh in (P.icosphere(1), P.cube(), P.teapot(2), P.torus(1.0, 0.3, 8, 5), pentagon,
                 degenerate):
        tri, owner = mesh.triangles
        got = mesh.edge_side_triangles
        for e, (lo, hi) in enumerate(mesh.edges.tolist()):
            for side, face in enumerate(mesh.edge_faces[e].tolist()):
                holding = [t for t in range(len(tri)) if owner[t] == face
                           and {lo, hi} <= set(tri[t].tolist())]
                assert got[e, side] == (holding[0] if holding else -1), (e, side, holding)


def test_each_edge_sides_normal_is_the_plane_drawn_beside_it():
    """``Mesh.edge_side_normals``: on planar polygons the faces' Newell normals; on the
    teapot's non-planar quads a unit normal perpendicular to the edge and to the far corner
    of the triangle drawn beside it, on the face's side (its dot with the face's normal
    positive)."""
    for mesh in (P.cube(), P.icosphere(1), P.torus(1.0, 0.3, 8, 5)):
        np.testing.assert_allclose(mesh.edge_side_normals,
                                   mesh.face_normals[mesh.edge_faces], atol=1e-9)
    teapot = P.teapot(2)
    tri, _ = teapot.triangles
    n = teapot.edge_side_normals
    v = teapot.vertices
    lo, hi = v[teapot.edges[:, 0]], v[teapot.edges[:, 1]]
    side = teapot.edge_side_triangles
    drawn = side >= 0
    far = v[tri[side.clip(min=0)]].mean(axis=2) - lo[:, None]     # (E, 2, 3)
    np.testing.assert_allclose(np.linalg.norm(n, axis=-1), 1.0, atol=1e-9)
    assert np.abs(np.einsum("esk,ek->es", n, hi - lo))[drawn].max() < 1e-9
    assert np.abs(np.einsum("esk,esk->es", n, far))[drawn].max() < 1e-9
    assert (np.einsum("esk,esk->es", n, teapot.face_normals[teapot.edge_faces])[drawn] > 0).all()
    assert not np.allclose(n, teapot.face_normals[teapot.edge_faces])  # (not planar)
