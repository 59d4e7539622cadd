"""The camera that just works: clip planes fitted to the scene at every draw (a dolly into
and through a model never loses what is in front of the near plane), named views at the
eyes computed by hand, picking against the test's own ray-polygon intersection, and the
polygon-edge overlay (no triangulation diagonals)."""

import numpy as np
import pytest

from glshade import Camera, Material, Scene, View
from glshade.geometry import primitives

pytestmark = pytest.mark.gl

SIZE = (64, 48)


def _sphere_scene(radius=1.0):
    s = Scene()
    s.add(primitives.icosphere(4, radius=radius), Material(color=(0.7, 0.7, 0.7)))
    return s


def _ray_sphere_coverage(camera, size, radius):
    """Which pixel centres' rays meet the sphere |p| = radius (the test's own math): the
    exact answer for a camera outside it; every pixel for one inside it."""
    w, h = size
    j, i = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    x, y = 2 * j / w - 1, 1 - 2 * i / h
    t = np.tan(np.radians(camera.fov_y) / 2)
    d = np.stack([x * t * w / h, y * t, -np.ones_like(x)], -1) @ camera.rotation.T
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    o = camera.position
    b = d @ o
    disc = b * b - (o @ o - radius ** 2)
    far_root = -b + np.sqrt(np.maximum(disc, 0))
    return (disc > 0) & (far_root > 0)


def test_a_dolly_into_and_through_a_sphere_never_clips_it(make_renderer):
    """From outside, closer and closer, past the bounding sphere's surface and into the
    sphere itself: the id buffer covers exactly the pixels whose rays meet the sphere (away
    from the silhouette, where the tessellation differs from the sphere)."""
    r = make_renderer(*SIZE)
    scene = _sphere_scene()
    start = Camera.named(View.FRONT, scene.bounds, SIZE[0] / SIZE[1])
    distance = float(np.linalg.norm(start.position))
    for travelled in np.linspace(0, distance + 0.6, 9):  # ends 0.6 past the centre
        camera = start.dolly(travelled)
        ids = r.render_frame(scene, camera, "flat", cull="auto").face_id
        exact = _ray_sphere_coverage(camera, SIZE, 1.0)
        inner = _ray_sphere_coverage(camera, SIZE, 0.99)
        outer = _ray_sphere_coverage(camera, SIZE, 1.0 / np.cos(np.pi / 80))
        inside = np.linalg.norm(camera.position) < 0.99
        if inside:
            assert (ids >= 0).all(), travelled  # every pixel sees the inside
        else:
            covered = ids >= 0
            assert covered[inner].all() and not covered[~outer].any(), travelled
            assert exact.any()


def test_named_views_at_the_eyes_computed_by_hand():
    b = np.array([[-1.0, 0.0, -2.0], [3.0, 2.0, 0.0]])
    center = np.array([1.0, 1.0, -1.0])
    radius = np.linalg.norm(b[1] - b[0]) / 2 * 1.1
    distance = radius / np.sin(np.radians(45.0) / 2)  # fov 45, aspect 1
    expected = {"front": (0, 0, 1), "back": (0, 0, -1), "left": (-1, 0, 0),
                "right": (1, 0, 0), "top": (0, 1, 0), "bottom": (0, -1, 0),
                "iso": np.array([1, 1, 1]) / np.sqrt(3)}
    for name, direction in expected.items():
        cam = Camera.named(name, b)
        np.testing.assert_allclose(cam.position, center + distance * np.asarray(direction),
                                   atol=1e-9, err_msg=name)
        np.testing.assert_allclose(cam.forward, -np.asarray(direction, float) /
                                   np.linalg.norm(direction), atol=1e-9)
    np.testing.assert_allclose(Camera.named("top", b).up, [0, 0, -1], atol=1e-9)
    with pytest.raises(ValueError, match="unknown view 'sideways'; choose one of front"):
        Camera.named("sideways", b)


def test_orbit_moves_keep_the_centre_and_zoom_narrows():
    cam = Camera.named("front", np.array([[-1, -1, -1], [1, 1, 1.0]]))
    east = cam.azimuth(90)
    np.testing.assert_allclose(east.position, [cam.position[2], 0, 0], atol=1e-9)
    np.testing.assert_allclose(east.forward, [-1, 0, 0], atol=1e-9)
    up = cam.elevation(90)
    np.testing.assert_allclose(up.position, [0, cam.position[2], 0], atol=1e-9)
    np.testing.assert_allclose(cam.roll(90).up, [-1, 0, 0], atol=1e-9)
    z = cam.zoom(2.0)
    assert np.tan(np.radians(z.fov_y) / 2) == pytest.approx(np.tan(np.radians(45) / 2) / 2)
    np.testing.assert_allclose(cam.dolly(1.0).position, cam.position - [0, 0, 1.0])


def _pick_by_rays(mesh, camera, size, x, y):
    """The nearest polygon that the pixel centre's ray meets: plane intersection, then a
    point-in-convex-polygon test (the test's own math, no renderer code)."""
    w, h = size
    t = np.tan(np.radians(camera.fov_y) / 2)
    nx, ny = 2 * (x + 0.5) / w - 1, 1 - 2 * (y + 0.5) / h
    d = camera.rotation @ np.array([nx * t * w / h, ny * t, -1.0])
    d /= np.linalg.norm(d)
    o = camera.position
    best = (np.inf, -1, None)
    for f in range(mesh.n_faces):
        poly = mesh.vertices[mesh.face(f)]
        n = np.cross(poly[1] - poly[0], poly[2] - poly[0])
        n /= np.linalg.norm(n)
        denom = n @ d
        if abs(denom) < 1e-12:
            continue
        s = n @ (poly[0] - o) / denom
        if s <= 0 or s >= best[0]:
            continue
        p = o + s * d
        edges = np.roll(poly, -1, axis=0) - poly
        if all(np.cross(e, p - q) @ n >= 0 for e, q in zip(edges, poly)):
            best = (s, f, p)
    return best[1], best[2]


def test_pick_names_the_polygon_the_ray_meets(make_renderer):
    r = make_renderer(96, 72)
    mesh = primitives.cube()
    scene = Scene()
    scene.add(mesh)
    camera = Camera.look_at((2.1, 1.7, 2.6), (0, 0, 0))
    rng = np.random.default_rng(3)
    checked = 0
    for x, y in rng.uniform((0, 0), (96, 72), (300, 2)).astype(int):
        face, point = _pick_by_rays(mesh, camera, (96, 72), x, y)
        got = r.pick(scene, camera, x, y)
        if face < 0:
            assert got is None
            continue
        if got is None or got.face_id != face:  # only on an edge, within a pixel
            continue
        checked += 1
        np.testing.assert_allclose(got.point, point,
                                   atol=2e-3 * np.linalg.norm(point - camera.position))
        np.testing.assert_allclose(got.normal, mesh.face_normals[face], atol=1e-5)
    assert checked >= 25
    # away from edges every pick agrees (the pixel centres of the middle of each face)
    ids = r.render_frame(scene, camera, "flat").face_id
    for f in np.unique(ids[ids >= 0]):
        ys, xs = np.nonzero(ids == f)
        k = np.argmin(np.hypot(xs - xs.mean(), ys - ys.mean()))
        assert _pick_by_rays(mesh, camera, (96, 72), xs[k], ys[k])[0] == f
        assert r.pick(scene, camera, xs[k], ys[k]).face_id == f
    with pytest.raises(ValueError, match="outside the 96x72 image"):
        r.pick(scene, camera, 96, 0)


def _diagonal_pixels(size, corners_px, margin):
    """Pixels along the segment between two image points, ``margin`` pixels from its ends."""
    (x0, y0), (x1, y1) = corners_px
    n = int(np.hypot(x1 - x0, y1 - y0))
    t = np.linspace(0, 1, 4 * n)
    keep = (t * n > margin) & ((1 - t) * n > margin)
    xs, ys = (x0 + t * (x1 - x0))[keep], (y0 + t * (y1 - y0))[keep]
    return ys.astype(int), xs.astype(int)


def test_the_edge_overlay_draws_polygon_edges_not_diagonals(make_renderer):
    """A unit quad seen head on, edges only: its four sides are drawn, its diagonal (where
    its two triangles meet) has no lit pixel; and over a filled cube the same."""
    w, h = 128, 128
    r = make_renderer(w, h)
    scene = Scene()
    scene.add(primitives.plane(2.0), Material(color=(1, 1, 1)))  # z = 0, x, y in [-1, 1]
    camera = Camera.look_at((0, 0, 4), (0, 0, 0))
    img = r.render(scene, camera, "flat", wireframe=True)
    lit = img[..., :3].max(axis=2) > 40
    t = np.tan(np.radians(45) / 2) * 4  # half the view at the quad's depth
    to_px = lambda p: ((p[0] / t + 1) * w / 2, (1 - p[1] / t) * h / 2)  # noqa: E731
    corners = [to_px(c) for c in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    for a, b in ((0, 2), (1, 3)):  # both diagonals: nothing
        ys, xs = _diagonal_pixels((w, h), (corners[a], corners[b]), 4)
        assert lit[ys, xs].sum() == 0
    for a in range(4):  # the sides: lit all along
        ys, xs = _diagonal_pixels((w, h), (corners[a], corners[(a + 1) % 4]), 2)
        assert lit[np.clip(ys, 0, h - 1), np.clip(xs, 0, w - 1)].mean() > 0.9
    # over the filled picture, in the dark edge colour, with no diagonal either
    filled = r.render(scene, camera, "flat")
    over = r.render(scene, camera, "flat", edges=True)
    dark = (filled[..., :3].astype(int) - over[..., :3].astype(int)).max(axis=2) > 60
    for a, b in ((0, 2), (1, 3)):
        ys, xs = _diagonal_pixels((w, h), (corners[a], corners[b]), 4)
        assert dark[ys, xs].sum() == 0
    assert dark.sum() > 4 * 60


def test_the_radiosity_mode_on_an_unsolved_scene_says_how_to_solve_it(make_renderer):
    r = make_renderer(16, 16)
    scene = _sphere_scene()
    with pytest.warns(UserWarning, match="solve it first: glshade radiosity SCENE.toml"):
        r.render(scene, Camera.named("front", scene.bounds), "radiosity")
    import warnings

    with warnings.catch_warnings():  # (once per scene: a viewer draws every frame)
        warnings.simplefilter("error")
        r.render(scene, Camera.named("front", scene.bounds), "radiosity")


@pytest.mark.parametrize("x, y, words", [
    (float("nan"), 3.0, "finite"), (2.0, float("inf"), "finite"), (-1.0, 3.0, "outside"),
    (96.0, 3.0, "outside"), ("left", 3.0, "two numbers"), (None, 1.0, "two numbers")])
def test_a_pick_outside_the_image_or_not_a_number_is_refused_in_words(make_renderer, x, y,
                                                                      words):
    from glshade.errors import OptionError

    scene = Scene()
    scene.add(primitives.cube())
    r = make_renderer(96, 72)
    with pytest.raises(OptionError, match=words):
        r.pick(scene, Camera.look_at((3, 2, 4), (0, 0, 0)), x, y)


@pytest.mark.parametrize("mode", ["radiosity", "phong", "flat", "gouraud"])
def test_polygon_ids_in_every_mode_are_the_faces_that_face_the_eye(make_renderer, mode):
    """Each mode's id output (per-corner polygon ids: the radiosity mode's colour array has
    its own) against the convex solid's rule: exactly the faces whose normals point at the
    eye are seen, each over a region of its own, and the background has none."""
    import warnings

    cube = primitives.cube()
    scene = Scene()
    scene.add(cube)
    eye = np.array([2.5, 2.0, 3.0])
    camera = Camera.look_at(eye, (0.0, 0.0, 0.0), fov_y=40)
    centres = cube.face_centroids
    facing = {i for i, n in enumerate(cube.face_normals) if n @ (eye - centres[i]) > 1e-9}
    r = make_renderer(64, 64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (the radiosity mode on an unsolved scene)
        frame = r.render_frame(scene, camera, mode)
    seen, counts = np.unique(frame.face_id[frame.face_id >= 0], return_counts=True)
    assert set(seen.tolist()) == facing and counts.min() > 50
    assert (frame.face_id[0, 0], frame.face_id[-1, -1]) == (-1, -1)
