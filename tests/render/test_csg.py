"""CSG solids on the GPU against the numpy reference (Roth's ray casting in float64):
ids, depth and normals per pixel; solids and meshes in one z-buffer; the camera inside;
empty and coincident cases."""

import numpy as np
import pytest

from glshade import Camera, Material, Scene
from glshade.cpu.csg import render_solids
from glshade.errors import RenderWarning
from glshade.geometry import primitives
from glshade.solids import Box, Cone, Cylinder, HalfSpace, Sphere, Torus

SIZE = (160, 120)
QUARTER_X = [np.sin(np.pi / 4), 0.0, 0.0, np.cos(np.pi / 4)]
SHEAR = [[1, 0.3, 0, 0], [0, 1, 0, 0], [0, 0, 1.4, 0], [0, 0, 0, 1]]
TREES = {
    "block, hole, ball": (Box((2, 1, 2)) - Cylinder(0.4, 3).rotated(QUARTER_X))
    | Sphere(0.6).translated((0, 0.8, 0)),
    "sheared torus minus a box": Torus(1.0, 0.3).transformed(SHEAR)
    - Box(0.8).translated((1, 0, 0)),
    "cut cone and ball": (Cone(0.8, 1.6) & HalfSpace((1, 1, 0), 0.2))
    | Sphere(0.3).translated((0, -0.8, 0)),
    "ball less a half-space": Sphere(1.0) - HalfSpace((-0.3, -1, -0.2), -0.3),
}
OUTSIDE = Camera.look_at((3, 2.5, 4), (0, 0, 0))


def away_from_silhouettes(ids):
    """Pixels whose 3x3 neighbourhood shows one id (silhouettes excluded)."""
    h, w = ids.shape
    pad = np.pad(ids, 1, mode="edge")
    same = np.ones_like(ids, bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            same &= pad[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] == ids
    return same


def check_against_reference(frame, scene, camera):
    depth, normal, ids = render_solids(scene, camera, SIZE)
    ok = away_from_silhouettes(ids)
    assert (frame.face_id[ok] == ids[ok]).all()
    hit = ok & (ids >= 0)
    assert hit.sum() > 300
    assert (np.abs(frame.depth[hit] - depth[hit]) / depth[hit]).max() < 1e-4
    assert np.abs(frame.normal[hit] - normal[hit]).max() < 1e-3
    return ids


@pytest.mark.parametrize("name", list(TREES))
def test_gpu_equals_the_numpy_reference(name, make_renderer):
    scene = Scene()
    scene.add(TREES[name], Material(color=(0.8, 0.5, 0.3)))
    frame = make_renderer(*SIZE).render_frame(scene, OUTSIDE, "phong")
    ids = check_against_reference(frame, scene, OUTSIDE)
    assert len(np.unique(ids[ids >= 0])) >= 2  # several leaves show


BORED = ((Box((3, 1, 2)) - Cylinder(0.35, 3.0).rotated(QUARTER_X).translated((-0.75, 0, 0))
          - Cylinder(0.35, 3.0).rotated(QUARTER_X).translated((0.75, 0, 0))
          | Sphere(0.7).translated((0, 0.6, 0)) | Cone(0.3, 0.8).translated((1.2, 0.9, 0)))
         - Cylinder(0.15, 3.0).translated((0, 0.6, 0)) - Box(0.3).translated((-1.5, 0.5, 1)))


@pytest.mark.parametrize("name", [*TREES, "bored block"])
def test_the_screen_polygon_cuts_no_pixel(name, make_renderer):
    """The solid is drawn as a polygon about its positive leaves (solids/proxy.py): every
    pixel the reference hits -- silhouettes too -- is drawn (up to the few a float32 ray
    misses at a grazing edge)."""
    from glshade.solids.encoding import tree_data
    from glshade.solids.proxy import screen_polygon

    solid = BORED if name == "bored block" else TREES[name]
    scene = Scene()
    scene.add(solid)
    camera = OUTSIDE.with_planes(scene.bounds)
    view_proj = camera.projection_matrix(SIZE[0] / SIZE[1]) @ camera.view_matrix()
    polygon = screen_polygon(view_proj, solid.bounds, tree_data(solid).hull, SIZE)
    assert np.abs(polygon).max() < 1  # (the whole polygon in view: it is what is drawn)
    frame = make_renderer(*SIZE).render_frame(scene, OUTSIDE, "phong")
    _, _, ids = render_solids(scene, OUTSIDE, SIZE)
    missed = (ids >= 0) & (frame.face_id < 0)
    assert (ids >= 0).sum() > 1000
    assert missed.sum() <= 0.002 * (ids >= 0).sum(), f"{missed.sum()} pixels not drawn"


def test_a_mesh_through_a_solid_meets_it_in_one_z_buffer(make_renderer):
    r = make_renderer(*SIZE)
    plane = primitives.plane(3.0)  # z = 0, through the sphere's centre
    both, alone_solid, alone_mesh = Scene(), Scene(), Scene()
    for s in (both, alone_mesh):
        s.add(plane, rotation=[np.sin(0.3), 0, 0, np.cos(0.3)])
    for s in (both, alone_solid):
        s.add(Sphere(1.0))
    # (one camera, with the clip planes of the whole scene: the same projection each time)
    camera = Camera.look_at((0.5, 1.5, 4), (0, 0, 0)).with_planes(both.bounds)
    d_both = r.render_frame(both, camera, "flat").depth
    d_solid = r.render_frame(alone_solid, camera, "flat").depth
    d_mesh = r.render_frame(alone_mesh, camera, "flat").depth
    expected = np.minimum(d_solid, d_mesh)
    seen = np.isfinite(expected)
    assert np.allclose(d_both[seen], expected[seen], rtol=1e-6)
    # the intersection curve: where the two depths cross, both surfaces show
    ids = r.render_frame(both, camera, "flat").face_id
    assert {0, 1} <= set(np.unique(ids).tolist())  # the plane's polygon, the sphere (1)


@pytest.mark.parametrize("eye", [(0.0, 0.3, 1.5), (0.1, 0.1, 0.2)],
                         ids=["inside the box, outside the solid", "inside the solid"])
def test_the_camera_inside(eye, make_renderer):
    scene = Scene()
    scene.add(Box(4.0) - Sphere(1.8), Material(color=(0.6, 0.7, 0.8)))
    scene.add(Sphere(0.5).translated((0.8, 0, -0.5)))
    camera = Camera.look_at(eye, (1, 0, -1), near=0.01)
    frame = make_renderer(*SIZE).render_frame(scene, camera, "phong")
    check_against_reference(frame, scene, camera)


def test_an_empty_intersection_draws_nothing_and_says_so(make_renderer):
    scene = Scene()
    scene.add(Sphere(1.0) & Sphere(1.0).translated((3, 0, 0)), name="apart")
    with pytest.warns(RenderWarning, match=r"solid \(apart\) is empty"):
        image = make_renderer(*SIZE).render(scene, OUTSIDE)
    assert (image[..., :3] == 0).all()


def test_coincident_faces_go_to_the_left_operand(make_renderer):
    """Tie rule: where two leaves' surfaces coincide, the left operand's shows -- so
    swapping the operands swaps nothing but which leaf is first (no z-fighting)."""
    r = make_renderer(*SIZE)
    a, b = Box(2.0), Box(2.0).translated((0.8, 0, 0))
    top = Camera.look_at((0.4, 5, 0.01), (0.4, 0, 0))
    ids = []
    for tree in (a | b, b | a):
        s = Scene()
        s.add(tree)
        ids.append(r.render_frame(s, top, "flat").face_id)
    both = (ids[0] >= 0) & (ids[1] >= 0)
    assert both.sum() > 1000
    # each render: left leaf (0) over the shared part, leaf 1 only beyond it
    frac0 = [(i[both] == 0).mean() for i in ids]
    assert np.isclose(frac0[0], frac0[1], atol=0.02)
    # the shared top face, seen from above: ids form two clean blocks, no speckle
    for i in ids:
        row = i[SIZE[1] // 2]
        changes = np.count_nonzero(np.diff(row[row >= 0]))
        assert changes == 1


def test_editing_a_tree_reuses_its_program(make_renderer):
    """A small tree's program is keyed by how many leaves of each kind it has: sizes,
    places and operators are data. A larger tree's walk has one program per size class."""
    r = make_renderer(*SIZE)
    for radius, op in ((0.5, "-"), (0.7, "|"), (0.9, "&")):
        ball = Sphere(radius).translated((0, radius, 0.2))
        s = Scene()
        s.add(Box(2.0) - ball if op == "-" else Box(2.0) | ball if op == "|" else
              Box(2.0) & ball)
        r.render(s, OUTSIDE)
    assert len(r.csg.compiled) == 1
    s = Scene()
    s.add(Box(2.0) - Sphere(0.5) - Sphere(0.3).translated((1, 1, 1)))  # one more ball
    r.render(s, OUTSIDE)
    assert len(r.csg.compiled) == 2
    for n in (20, 31):  # (over the 14 leaves a truth table serves: the walk)
        s = Scene()
        s.add(random_union(n))
        r.render(s, OUTSIDE)
    assert len(r.csg.compiled) == 3


def random_union(n):
    rng = np.random.default_rng(n)
    solid = Sphere(0.3)
    for _ in range(n - 1):
        solid = solid | Sphere(rng.uniform(0.1, 0.3)).translated(rng.uniform(-1, 1, 3))
    return solid


def test_unbounded_solids_are_refused():
    from glshade.errors import SceneError

    with pytest.raises(SceneError, match="bounded"):
        Scene().add(HalfSpace())
    with pytest.raises(SceneError, match="bounded"):
        Scene().add(Sphere() | HalfSpace())


def test_flat_lights_each_planar_face_once_at_its_centre(make_renderer):
    """Oracle: the numpy twin of the lighting formula at the face's centre."""
    from glshade import PointLight
    from glshade.cpu.lighting import light_intensity, view_dir

    scene = Scene()
    material = Material(color=(0.8, 0.6, 0.4), ks=0.4, shininess=20)
    scene.add(Box((2, 1, 2)) | Sphere(0.5).translated((0, 0.8, 0)), material)
    scene.add_light(PointLight((1.5, 2.0, 2.5)))
    frame = make_renderer(*SIZE).render_frame(scene, OUTSIDE, "flat", color_dtype="f4")
    box = frame.face_id == 0
    faces = {(1, 0, 0): (1, 0, 0), (0, 1, 0): (0, 0.5, 0), (0, 0, 1): (0, 0, 1)}
    for normal, centre in faces.items():
        on = box & (np.abs(frame.normal - normal).max(-1) < 1e-4)
        assert on.sum() > 100
        c = np.array(centre, float)
        expected = light_intensity(c, np.array(normal, float), view_dir(c, OUTSIDE), material,
                                   scene.lights_for(OUTSIDE), scene.ambient)
        got = frame.color[on][:, :3]
        assert np.abs(got - np.clip(expected, 0, 1)).max() < 1e-4
    ball = frame.color[frame.face_id == 1][:, :3]
    assert ball.std(0).max() > 0.01  # a curved face stays lit per pixel


# Cones and cylinders from every side: along the axis (rays parallel to it: the quadratic
# degenerates), along a generator (the cone's quadratic loses its square term), from inside,
# from below the base, from beyond the apex; each against the numpy reference.
CONE = Cone(0.8, 1.2)  # apex at y = 0.6, base radius 0.8 at y = -0.6
SIDES = {
    "cone from the side": (CONE, (3.0, 0.2, 2.0), (0, 0, 0)),
    "cone down the axis": (CONE, (0.0, 4.0, 0.001), (0, 0, 0)),
    "cone up the axis": (CONE, (0.001, -4.0, 0.0), (0, 0, 0)),
    # the slope of a generator is 0.8 / 1.2: an eye on the generator's line, looking along it
    "cone along a generator": (CONE, (0.8 * 2.5, 0.6 - 1.2 * 2.5, 0.0), (0, 0.6, 0)),
    "cone from inside": (CONE, (0.1, -0.4, 0.1), (1, 0.3, 0.5)),
    "cone beyond the apex": (CONE | Sphere(0.2).translated((0.5, -0.5, 0)),
                             (0.3, 2.5, 0.4), (0, -0.5, 0)),
    "cylinder down the axis": (Cylinder(0.6, 1.0) - Cylinder(0.3, 2.0), (0.0, 3.0, 0.0005),
                               (0, 0, 0)),
    "cylinder from inside": (Cylinder(0.8, 1.0) - Sphere(0.3).translated((0.4, 0, 0)),
                             (-0.2, 0.1, 0.1), (1, 0, 0.2)),
}


@pytest.mark.parametrize("name", [*SIDES, "orthographic, down the axes"])
def test_cones_and_cylinders_from_every_side(name, make_renderer):
    if name in SIDES:
        solid, eye, target = SIDES[name]
        camera = Camera.look_at(eye, target, near=0.01)
    else:  # every ray parallel to the axes, some outside the cylinder, some in the bore
        solid = ((Cylinder(0.6, 1.0) - Cylinder(0.3, 2.0)).translated((-0.7, 0, 0))
                 | Cone(0.5, 1.0).translated((0.7, 0, 0)))
        camera = Camera.look_at((0, 4, 0), (0, 0, 0), up=(0, 0, -1),
                                projection="orthographic", height=2.5)
    scene = Scene()
    scene.add(solid)
    frame = make_renderer(*SIZE).render_frame(scene, camera, "phong")
    check_against_reference(frame, scene, camera)
