"""Point clouds against float64 closed forms: sphere impostors against the analytic
ray-sphere hit at every pixel centre (which point, its depth, its normal), also where the
spheres cut a mesh (the z-buffer decides per pixel as the oracle does); discs against the
ray-plane hit inside their radius; squares against the square of their size on screen
about the point's projection. Pixels within half a pixel of an outline (where the oracle's
own answer changes across the pixel) are left out of the coverage check and only there."""

import numpy as np
import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import HealthCheck, Phase, assume, example, given, settings, strategies as st  # noqa: E402,E501

import glshade  # noqa: E402
from glshade.geometry import primitives  # noqa: E402
from glshade.geometry.points import PointCloud  # noqa: E402
from glshade.modes import Outputs  # noqa: E402

pytestmark = [pytest.mark.gl, pytest.mark.filterwarnings("ignore::glshade.RenderWarning")]

W, H = 96, 72
#: a pixel's centre and eight points half a pixel (or more) from it
SPREAD = [(0.0, 0.0)] + [(dx, dy) for dx in (-0.5, 0.0, 0.5) for dy in (-0.5, 0.0, 0.5)
                         if dx or dy]


def _sphere_hits(o, d, centres, radii, t_min):
    """``(P, N)`` float64 distances along unit rays to each sphere's first surface past
    ``t_min`` (inf: none) -- the textbook quadratic."""
    oc = o[:, None, :] - centres[None]
    b = (oc * d[:, None, :]).sum(-1)
    c = (oc * oc).sum(-1) - radii[None] ** 2
    disc = b * b - c
    root = np.sqrt(np.maximum(disc, 0))
    near, far = -b - root, -b + root
    t = np.where(near >= t_min[:, None], near, far)
    t[(disc < 0) | (t < t_min[:, None])] = np.inf
    return t


def _plane_hit(o, d, z):
    """Distances along the rays to the plane ``Z = z`` (inf: parallel or behind)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = (z - o[:, 2]) / d[:, 2]
    t[~np.isfinite(t) | (t < 0)] = np.inf
    return t


def _oracle(cam, centres, radii, floor_y, jitter):
    """At one spot of every pixel (``jitter`` pixels from its centre): the id the oracle
    sees (-1 nothing, k point k, N the floor), its view depth, and the sphere normal."""
    o, d = cam.rays((W, H), jitter=jitter)
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    cosf = d @ cam.forward
    t_min = cam.near / cosf
    t = _sphere_hits(o, d, centres, radii, t_min)
    if floor_y is not None:
        tf = _plane_hit(o, d, floor_y)
        with np.errstate(invalid="ignore"):
            off = np.abs((o + tf[:, None] * d)[:, :2]).max(1)
        tf[(tf < t_min) | ~(off <= 2.0)] = np.inf
        t = np.c_[t, tf]
    k = t.argmin(1)
    best = t[np.arange(len(t)), k]
    depth = best * cosf
    ident = np.where(np.isfinite(best) & (depth <= cam.far), k, -1)
    p = o + best[:, None] * d
    n = np.zeros_like(p)
    on_sphere = (ident >= 0) & (ident < len(centres))
    n[on_sphere] = (p[on_sphere] - centres[ident[on_sphere]]) / radii[ident[on_sphere], None]
    # (seen from inside, cut by the near plane: the inside faces the eye)
    inside = on_sphere.copy()
    inside[on_sphere] = (n[on_sphere] * d[on_sphere]).sum(1) > 0
    n[inside] *= -1
    return ident.reshape(H, W), depth.reshape(H, W), n.reshape(H, W, 3), t


def _check(frame, cam, centres, radii, floor_y=None):
    ids, depth, normal, _ = _oracle(cam, centres, radii, floor_y, None)
    agree = np.ones((H, W), bool)
    for jitter in SPREAD[1:]:
        agree &= _oracle(cam, centres, radii, floor_y, jitter)[0] == ids
    n = len(centres)
    floor_faces = 0 if floor_y is None else 1  # (the floor's polygon ids come first)
    got = frame.face_id.copy()
    got_ident = np.where(got < 0, -1, np.where(got >= floor_faces, got - floor_faces, n))
    wrong = agree & (got_ident != ids)
    assert not wrong.any(), (int(wrong.sum()), int(agree.sum()),
                             np.argwhere(wrong)[:3].tolist())
    spheres = agree & (ids >= 0) & (ids < n)
    # relative to the depth, or to the sphere's distance where the hit is much nearer the
    # eye than its centre (an eye at its surface): float32 holds the centre to 6e-8 of that
    scale = np.maximum(depth, np.linalg.norm(centres - cam.position, axis=1)[
        np.where(spheres, ids, 0)])
    rel = np.abs(frame.depth[spheres] - depth[spheres]) / scale[spheres]
    assert rel.max(initial=0) <= 1e-5, (rel.max(), cam.near, cam.far)
    floor = agree & (ids == n)  # (the mesh's depth, interpolated: float32's own rounding)
    rel = np.abs(frame.depth[floor] - depth[floor]) / depth[floor]
    assert rel.max(initial=0) <= 1e-4, rel.max()
    err = np.linalg.norm(frame.normal[spheres] - normal[spheres], axis=-1)
    assert err.max(initial=0) <= 1e-4, err.max()
    return spheres


def _camera(eye_dir, distance, fov, aim, orthographic=False):
    eye = np.asarray(eye_dir, float) / np.linalg.norm(eye_dir) * distance
    forward = np.asarray(aim) - eye
    up = (0, 1, 0) if abs(forward[1]) < 0.95 * np.linalg.norm(forward) else (1, 0, 0)
    if orthographic:
        return glshade.Camera.look_at(eye, aim, up=up, projection="orthographic",
                                      height=2.4)
    return glshade.Camera.look_at(eye, aim, up=up, fov_y=fov)


@settings(max_examples=12, deadline=None, derandomize=True, phases=[Phase.explicit, Phase.generate],
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(seed=st.integers(0, 2**16), radius=st.floats(0.06, 0.5),
       eye_dir=st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.2),
       distance=st.floats(0.5, 8.0), fov=st.floats(20, 100),
       aim=st.tuples(*[st.floats(-0.4, 0.4)] * 3), orthographic=st.booleans(),
       floor=st.booleans(), mode=st.sampled_from(["phong", "flat", "gouraud", "normals"]))
@example(seed=3, radius=0.4, eye_dir=(0.2, 0.3, 1.0), distance=0.6, fov=60,
         aim=(0, 0, 0), orthographic=False, floor=True, mode="phong")   # eye among spheres
@example(seed=5, radius=0.15, eye_dir=(1.0, 0.1, 0.0), distance=3.0, fov=100,
         aim=(0.3, 0, 0.3), orthographic=False, floor=False, mode="flat")  # wide angle
def test_sphere_impostors_are_the_analytic_spheres(
        make_renderer, seed, radius, eye_dir, distance, fov, aim, orthographic, floor, mode):
    rng = np.random.default_rng(seed)
    n = 24
    centres = rng.uniform(-1, 1, (n, 3))
    radii = radius * rng.uniform(0.5, 1.5, n)
    scene = glshade.Scene()
    floor_y = None
    if floor:  # a wall through the spheres (the plane Z = z, 4 x 4): the z-buffer decides
        floor_y = float(centres[:, 2].mean())
        scene.add(primitives.plane(4.0), translation=(0, 0, floor_y))
    scene.add(PointCloud(centres, radii=radii))
    cam = _camera(eye_dir, distance, fov, aim, orthographic).with_planes(scene.bounds)
    renderer = make_renderer(W, H)
    frame = renderer.render_frame(scene, cam, mode, outputs=Outputs.ALL)
    if floor:  # (the oracle's wall: the plane's own square)
        assert primitives.plane(4.0).bounds.tolist() == [[-2, -2, 0], [2, 2, 0]]
    assume(_check(frame, cam, centres, radii, floor_y).sum() > 10)  # (spheres in view)


def test_a_sphere_shaded_by_the_notes_formula(make_renderer):
    """Phong at the pixel's exact point and normal, against the lighting formula in
    float64 (one point light, no specular), away from the silhouette."""
    scene = glshade.Scene(ambient=(0.2, 0.2, 0.2))
    scene.add(PointCloud([[0.0, 0.0, 0.0]], radius=0.8),
              glshade.Material(color=(0.9, 0.5, 0.2), ka=0.5, kd=0.8, ks=0.0))
    light = np.array([2.0, 3.0, 4.0])
    scene.add_light(glshade.PointLight(tuple(light)))
    cam = glshade.Camera.look_at((0, 0, 3.0), (0, 0, 0), fov_y=45).with_planes(scene.bounds)
    frame = make_renderer(W, H).render_frame(scene, cam, "phong", outputs=Outputs.ALL)
    ids, depth, normal, _ = _oracle(cam, np.zeros((1, 3)), np.array([0.8]), None, None)
    o, d = cam.rays((W, H))
    p = o + d * (depth / (d @ cam.forward))[..., None]
    to_light = light - p
    to_light /= np.linalg.norm(to_light, axis=-1, keepdims=True)
    ln = np.maximum((normal * to_light).sum(-1), 0)
    want = 0.2 * 0.5 * np.array([0.9, 0.5, 0.2]) + 0.8 * ln[..., None] * [0.9, 0.5, 0.2]
    inner = ids == 0
    inner &= np.roll(inner, 1, 0) & np.roll(inner, -1, 0) & np.roll(inner, 1, 1) & \
        np.roll(inner, -1, 1)
    got = frame.color[..., :3].astype(np.float64)
    if got.max() > 1.5:
        got /= 255.0
    assert np.abs(got[inner] - np.clip(want[inner], 0, 1)).max() <= 1.5 / 255


@settings(max_examples=6, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(seed=st.integers(0, 2**16),
       eye_dir=st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.2),
       distance=st.floats(2.0, 6.0))
def test_discs_are_the_analytic_discs(make_renderer, seed, eye_dir, distance):
    rng = np.random.default_rng(seed)
    n = 20
    centres = rng.uniform(-1, 1, (n, 3))
    normals = rng.normal(size=(n, 3))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    radius = 0.25
    scene = glshade.Scene()
    scene.add(PointCloud(centres, radius=radius, normals=normals, style="disc"))
    cam = _camera(eye_dir, distance, 50, (0, 0, 0)).with_planes(scene.bounds)
    frame = make_renderer(W, H).render_frame(scene, cam, "phong", outputs=Outputs.ALL)

    def oracle(jitter):
        o, d = cam.rays((W, H), jitter=jitter)
        o, d = o.reshape(-1, 3), d.reshape(-1, 3)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = ((centres[None] - o[:, None]) * normals[None]).sum(-1) / (d @ normals.T)
        p = o[:, None] + t[..., None] * d[:, None]
        inside = (np.linalg.norm(p - centres[None], axis=-1) <= radius) & (t > 0)
        t = np.where(inside, t, np.inf)
        k = t.argmin(1)
        best = t[np.arange(len(t)), k]
        return np.where(np.isfinite(best), k, -1).reshape(H, W), \
            (best * (d @ cam.forward)).reshape(H, W)

    ids, depth = oracle(None)
    agree = np.ones((H, W), bool)
    for jitter in SPREAD[1:]:
        agree &= oracle(jitter)[0] == ids
    assert ((frame.face_id == ids) | ~agree).all()
    drawn = agree & (ids >= 0)
    assert drawn.sum() > 30
    assert (np.abs(frame.depth[drawn] - depth[drawn]) / depth[drawn]).max() <= 1e-5


@pytest.mark.parametrize("pixel_size", [3.0, 8.0])
def test_squares_of_a_pixel_size_cover_their_square_on_screen(make_renderer, pixel_size):
    """A square of ``pixel_size`` pixels about the point's projection (numpy's own:
    the camera's pixel rays inverted), at any depth: pixel centres inside are drawn, those
    outside are not, beyond half a pixel from its edges."""
    rng = np.random.default_rng(4)
    centres = rng.uniform(-1, 1, (12, 3)) * [1.0, 0.8, 1.0]
    scene = glshade.Scene()
    scene.add(PointCloud(centres, style="square", pixel_size=pixel_size))
    cam = glshade.Camera.look_at((0.3, 0.5, 4.0), (0, 0, 0), fov_y=50).with_planes(
        scene.bounds)
    frame = make_renderer(W, H).render_frame(scene, cam, "flat", outputs=Outputs.ALL)
    # the projection in pixels: the point's direction in the camera's frame
    rel = (centres - cam.position) @ cam.rotation
    t = np.tan(np.radians(cam.fov_y) / 2)
    u = (rel[:, 0] / -rel[:, 2] / (t * W / H) + 1) / 2 * W
    v = (1 - rel[:, 1] / -rel[:, 2] / t) / 2 * H
    x, y = np.meshgrid(np.arange(W) + 0.5, np.arange(H) + 0.5)
    half = pixel_size / 2
    dx, dy = np.abs(x[..., None] - u), np.abs(y[..., None] - v)
    inside = (dx < half - 0.5) & (dy < half - 0.5)
    outside = (dx > half + 0.5) | (dy > half + 0.5)
    drawn = frame.face_id >= 0
    assert drawn[inside.any(-1)].all()
    assert not drawn[outside.all(-1)].any()
    # a pixel that only one square can hold shows that square's id
    only = inside.sum(-1) == 1
    assert (frame.face_id[only & (inside & ~outside).any(-1)] ==
            inside.argmax(-1)[only & (inside & ~outside).any(-1)]).sum() > 0


def test_points_take_ids_after_the_polygons_and_their_models_instance(make_renderer):
    scene = glshade.Scene()
    scene.add(primitives.cube(), label="box", translation=(-1.2, 0, 0))
    cloud = PointCloud([[1.0, 0.0, 0.0], [1.5, 0.5, 0.0]], radius=0.3)
    scene.add(cloud, label="dots")
    cam = glshade.Camera.look_at((0, 0, 6.0), (0, 0, 0)).with_planes(scene.bounds)
    frame = make_renderer(W, H).render_frame(scene, cam, "phong", outputs=Outputs.ALL)
    n_faces = primitives.cube().n_faces
    assert set(np.unique(frame.face_id)) >= {-1, n_faces, n_faces + 1}
    assert (frame.instance[frame.face_id >= n_faces] == 2).all()
    assert (frame.semantic[frame.face_id >= n_faces] == scene.labels["dots"]).all()


def test_point_cloud_arguments_are_checked():
    with pytest.raises(glshade.GeometryError, match=r"points must have shape \(N, 3\)"):
        PointCloud(np.zeros((4, 2)))
    with pytest.raises(glshade.GeometryError, match=r"radii\[1\] is -1"):
        PointCloud(np.zeros((2, 3)), radii=[1, -1])
    with pytest.raises(glshade.GeometryError, match="give normals"):
        PointCloud(np.zeros((2, 3)), style="disc")
    with pytest.raises(glshade.GeometryError, match=r"style must be 'sphere', 'disc' or "):
        PointCloud(np.zeros((2, 3)), style="cube")
    with pytest.raises(glshade.GeometryError, match=r"colors\[0\] is"):
        PointCloud(np.zeros((1, 3)), colors=[[2, 0, 0]])
    with pytest.raises(glshade.SceneError, match="shears or scales its axes unequally"):
        glshade.Scene().add(PointCloud(np.zeros((1, 3))), scale=(1, 2, 1))
    with pytest.raises(glshade.SceneError, match="drawn opaque"):
        glshade.Scene().add(PointCloud(np.zeros((1, 3))), glshade.Material(opacity=0.5))


def test_compare_measures_the_modes_of_sphere_impostors(gl_context):
    """``compare`` on a cloud: its analytic reference casts the spheres in numpy (with the
    points' colours); Phong impostors are that picture to the rounding, flat is not."""
    rng = np.random.default_rng(0)
    scene = glshade.Scene()
    scene.add(PointCloud(rng.uniform(-1, 1, (30, 3)), radius=0.25,
                         colors=rng.uniform(0.2, 1, (30, 3))), glshade.Material(ks=0.5))
    scene.add_light(glshade.PointLight((3.0, 4.0, 5.0)))
    cam = glshade.Camera.look_at((0, 0.5, 4), (0, 0, 0))
    with glshade.Renderer(160, 120, samples=0, context=gl_context) as renderer:
        result = glshade.compare(scene, cam, renderer=renderer, size=(160, 120))
    metrics = {m.mode: m for m in result.metrics}
    assert "analytic" in repr(result)
    assert metrics["phong"].max_abs <= 1.0 and metrics["phong"].pixels > 1000
    assert metrics["flat"].mean_abs > 10 * max(metrics["phong"].mean_abs, 0.1)
