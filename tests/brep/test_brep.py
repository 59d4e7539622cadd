"""Winged-edge B-Rep and Euler's formula V - E + F - H = 2(C - G), against known counts
and an independent count (trimesh's Euler number)."""

import numpy as np
import pytest

from glshade import Mesh, TopologyError, concatenate, load_mesh, newell_normal
from glshade.geometry import primitives as P
from glshade.brep import WingedEdge


def counts(w):
    r = w.euler()
    return r.V, r.E, r.F, r.H, r.C, r.G


def plate_with_holes(g):
    """A plate of unit cubes with g square holes through it: genus g, made of quads."""
    occ = np.ones((2 * g + 1, 1, 3), bool)
    for h in range(g):
        occ[2 * h + 1, 0, 1] = False
    return P.voxels(occ)


def test_cube():
    assert counts(WingedEdge.from_mesh(P.cube())) == (8, 12, 6, 0, 1, 0)


def test_tetrahedron():
    tet = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
               [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    assert counts(WingedEdge.from_mesh(tet)) == (4, 6, 4, 0, 1, 0)


@pytest.mark.parametrize("level", [0, 2, 4])
def test_icosphere(level):
    m = P.icosphere(level)
    assert counts(WingedEdge.from_mesh(m)) == (m.n_vertices, m.n_edges, m.n_faces, 0, 1, 0)


def test_torus_has_genus_one():
    r = WingedEdge.from_mesh(P.torus(1, 0.3, 16, 8)).euler()
    assert (r.V - r.E + r.F, r.C, r.G) == (0, 1, 1)
    assert r.holds and r.is_closed and r.is_manifold and r.is_oriented


@pytest.mark.parametrize("genus", [2, 3])
def test_genus_from_quads(genus):
    m = plate_with_holes(genus)
    assert (m.face_sizes == 4).all() and m.signed_volume() > 0
    r = WingedEdge.from_mesh(m).euler()
    assert (r.C, r.G, r.H) == (1, genus, 0)
    assert r.V - r.E + r.F == 2 - 2 * genus


def test_two_disjoint_cubes():
    far = Mesh(P.cube().vertices + [5, 0, 0], P.cube().face_indices.reshape(-1, 4))
    r = WingedEdge.from_mesh(concatenate([P.cube(), far])).euler()
    assert (r.V, r.E, r.F, r.C, r.G) == (16, 24, 12, 2, 0)
    assert r.V - r.E + r.F == 2 * (r.C - r.G)


def oriented(loop, vertices, normal):
    """The loop wound counter-clockwise about ``normal``."""
    n = newell_normal(vertices[loop])
    return list(loop) if n @ normal > 0 else list(loop)[::-1]


def cube_with_tunnel():
    """[0,3]^3 with a square tunnel [1,2]x[1,2] along z, using faces with holes."""
    outer = np.array([[x, y, z] for z in (0, 3) for y in (0, 3) for x in (0, 3)], float)
    inner = np.array([[x, y, z] for z in (0, 3) for y in (1, 2) for x in (1, 2)], float)
    v = np.vstack([outer, inner])

    def idx(pts, off):
        return [off + i for i in pts]

    front_o, back_o = idx([4, 5, 7, 6], 0), idx([0, 1, 3, 2], 0)
    front_i, back_i = idx([4, 5, 7, 6], 8), idx([0, 1, 3, 2], 8)
    z = np.array([0, 0, 1.0])
    faces = [
        [oriented(front_o, v, z), oriented(front_i, v, -z)],     # z = 3, with its hole
        [oriented(back_o, v, -z), oriented(back_i, v, z)],       # z = 0, with its hole
        oriented([0, 2, 6, 4], v, [-1, 0, 0]), oriented([1, 3, 7, 5], v, [1, 0, 0]),
        oriented([0, 1, 5, 4], v, [0, -1, 0]), oriented([2, 3, 7, 6], v, [0, 1, 0]),
        # tunnel walls face into the tunnel (away from the solid)
        oriented([8, 10, 14, 12], v, [1, 0, 0]), oriented([9, 11, 15, 13], v, [-1, 0, 0]),
        oriented([8, 9, 13, 12], v, [0, 1, 0]), oriented([10, 11, 15, 14], v, [0, -1, 0]),
    ]
    return v, faces


def test_cube_with_through_hole_uses_faces_with_holes():
    v, faces = cube_with_tunnel()
    w = WingedEdge.from_faces(v, faces)
    r = w.euler()
    assert (r.V, r.E, r.F, r.H, r.C, r.G) == (16, 24, 10, 2, 1, 1)
    assert r.holds and r.is_closed and r.is_oriented
    assert len(w.face_loops(0)) == 2


def test_open_box_reports_its_boundary():
    box = P.cube()
    top = int(np.argmax(box.face_normals[:, 1]))
    faces = [f for i, f in enumerate(box.faces) if i != top]
    w = WingedEdge.from_mesh(Mesh(box.vertices, faces))
    r = w.euler()
    assert not r.is_closed and r.B == 1
    assert (r.V, r.E, r.F, r.G) == (8, 12, 5, 0)
    assert r.holds and "+ B" in r.formula
    (loop,) = w.boundary_loops()
    assert sorted(loop) == sorted(box.face(top).tolist())


# ---------------------------------------------------------------------- adjacency

@pytest.mark.parametrize("mesh", [P.icosphere(2), P.torus(1, 0.4, 10, 6), P.cylinder(7),
                                  plate_with_holes(2)], ids=["ico", "torus", "cyl", "plate"])
def test_faces_around_every_vertex_close_up(mesh):
    w = WingedEdge.from_mesh(mesh)
    for v in range(w.n_vertices):
        faces = w.vertex_faces(v)
        neighbours = w.vertex_vertices(v)
        assert len(faces) == len(neighbours) == len(w.vertex_edges(v))
        for i, f in enumerate(faces):
            # consecutive faces share the edge from v to a common neighbour
            g = faces[(i + 1) % len(faces)]
            shared = set(w.face_vertices(f)) & set(w.face_vertices(g))
            assert v in shared and len(shared) >= 2
        # the neighbours are exactly the mesh's edge partners
        e = mesh.edges
        expected = set(e[e[:, 0] == v, 1]) | set(e[e[:, 1] == v, 0])
        assert set(neighbours) == expected


def test_wings_agree_with_neighbours():
    w = WingedEdge.from_mesh(P.torus(1, 0.4, 9, 5))
    ev, ef, wings = w.edge_vertices, w.edge_faces, w.edge_wings
    for e in range(w.n_edges):
        p, n = ev[e]
        left, right = ef[e]
        pl, pr, nl, nr = wings[e]
        assert p in ev[pl] and p in ev[pr] and n in ev[nl] and n in ev[nr]
        assert left in ef[pl] and left in ef[nl] and right in ef[pr] and right in ef[nr]
        # the wing at P on the left has e as its N-left (or N-right) wing back
        assert e in wings[pl]
        assert e in wings[nl]


def test_face_queries_follow_loop_order():
    w = WingedEdge.from_mesh(P.cube())
    for f in range(6):
        verts = w.face_vertices(f)
        edges = w.face_edges(f)
        for i, e in enumerate(edges):
            assert set(w.edge_vertices_of(e)) == {verts[i], verts[(i + 1) % 4]}
        assert len(set(w.face_faces(f))) == 4 and f not in w.face_faces(f)
    assert w.edge_faces_of(0)[1] >= 0


# ---------------------------------------------------------------------- bad topology

def test_non_manifold_edge_is_named():
    # three triangles on one edge (0, 1)
    v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]]
    m = Mesh(v, [[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    with pytest.raises(TopologyError,
                       match=r"1 non-manifold edges .*\(0, 1\) in faces \[0, 1, 2\]"):
        WingedEdge.from_mesh(m)
    report = WingedEdge.from_mesh(m, strict=False).report
    assert len(report.non_manifold_edges) == 1 and not report.ok


def test_flipped_face_is_named():
    cube = P.cube()
    faces = [list(f) for f in cube.faces]
    faces[3] = faces[3][::-1]
    with pytest.raises(TopologyError, match=r"4 edges where neighbouring faces disagree"):
        WingedEdge.from_mesh(Mesh(cube.vertices, faces))
    w = WingedEdge.from_mesh(Mesh(cube.vertices, faces), strict=False)
    assert not w.euler().is_oriented
    assert all(3 in fs for _, _, fs in w.report.misoriented_edges)
    # a flip is the one fault named: the ends of its edges are not also called pinched
    # vertices (two triangles whose shared edge runs the same way in both)
    for mesh in (Mesh(cube.vertices, faces),
                 Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], [[0, 1, 2], [1, 2, 3]])):
        with pytest.raises(TopologyError, match="disagree on orientation") as info:
            WingedEdge.from_mesh(mesh)
        assert "non-manifold vertices" not in str(info.value)


def test_isolated_vertex_and_duplicate_face():
    cube = P.cube()
    m = Mesh(np.vstack([cube.vertices, [[9, 9, 9]]]), cube.face_indices.reshape(-1, 4))
    with pytest.raises(TopologyError, match=r"1 isolated vertices \(in no face\): 8"):
        WingedEdge.from_mesh(m)
    tri = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2], [1, 2, 0]])
    with pytest.raises(TopologyError, match=r"duplicate faces: 0 = 1"):
        WingedEdge.from_mesh(tri)


# ---------------------------------------------------------------------- independent count

def test_against_trimesh_euler_number(tmp_path):
    import trimesh

    from glshade import save_mesh

    save_mesh(plate_with_holes(3), tmp_path / "plate.obj")
    meshes = [P.cube(), P.icosphere(3), P.torus(1, 0.3, 20, 10), P.cylinder(9),
              P.uv_sphere(8, 12), load_mesh(tmp_path / "plate.obj"),
              load_mesh("assets/torus.off")]
    for m in meshes:
        tri, _ = m.triangulate()
        theirs = trimesh.Trimesh(m.vertices, tri, process=False).euler_number
        r = WingedEdge.from_mesh(m).euler()
        assert r.V - r.E + r.F - r.H == theirs


def test_pinched_vertex_is_named():
    # two tetrahedra sharing only vertex 0
    v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0], [0, 0, -1]]
    faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2],
             [0, 5, 4], [0, 4, 6], [4, 5, 6], [0, 6, 5]]
    with pytest.raises(TopologyError, match=r"1 non-manifold vertices .*: 0"):
        WingedEdge.from_mesh(Mesh(v, faces))
    r = WingedEdge.from_mesh(Mesh(v, faces), strict=False).euler()
    assert not r.is_manifold


def test_info_cli_shows_topology():
    import json
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-m", "glshade", "info", "assets/torus.off",
                          "--json"], capture_output=True, text=True)
    t = json.loads(out.stdout)["topology"]
    assert (t["V"], t["C"], t["G"], t["closed"], t["euler_holds"]) == (288, 1, 1, True, True)
    text = subprocess.run([sys.executable, "-m", "glshade", "info", "primitive:cube"],
                          capture_output=True, text=True).stdout
    assert "Euler's formula for closed surfaces holds: V - E + F - H = 8 - 12 + 6 - 0 = 2" in text
