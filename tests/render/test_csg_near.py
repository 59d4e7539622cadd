"""CSG solids seen through any clip planes: the ray of a pixel is unprojected in view space
and then moved to the world (shaders/include/rays.glsl), so a tiny near plane -- the eye
inside the scene's box fits one at 1e-4 of the far plane -- leaves the cast surface where
it is. Through the whole inverse view-projection, the rounding of the far point's w moved
it about the world's origin, off the pixel's ray: a sphere's depth was off by 0.75% at a
near plane of 1e-4 (0.028 at 3.7 units). Swept (hypothesis, derandomized in CI) over
near planes 0.5..1e-5 of the eye's distance and far planes 2..1000 times it (far / near
up to 1e5, the depth buffer's own range), eyes anywhere outside and inside, spheres and
boxes in any pose, against float64 closed forms."""

import numpy as np
import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import example, given, settings, strategies as st  # noqa: E402

import glshade  # noqa: E402
from glshade.modes import Outputs  # noqa: E402
from glshade.solids import Box, Sphere  # noqa: E402

pytestmark = [pytest.mark.gl, pytest.mark.once,
              pytest.mark.filterwarnings("ignore::glshade.RenderWarning")]

N = 40


def _first_hit(kind, size, centre, rot, o, d, t_min):
    """float64 distance along unit rays ``d`` from ``o`` to the first surface of a sphere
    (radius ``size``) or a box (half sizes ``size``) past ``t_min`` (inf: none)."""
    o = (o - centre) @ rot          # into the solid's frame (rigid)
    d = d @ rot
    if kind == "sphere":
        b = (o * d).sum(-1)
        disc = b * b - ((o * o).sum(-1) - size * size)
        root = np.sqrt(np.maximum(disc, 0))
        ts = np.stack([-b - root, -b + root], -1)
        ts[disc < 0] = np.inf
    else:
        with np.errstate(divide="ignore", invalid="ignore"):
            a, b = (-size - o) / d, (size - o) / d
        lo, hi = np.nanmax(np.minimum(a, b), -1), np.nanmin(np.maximum(a, b), -1)
        ts = np.stack([lo, hi], -1)
        ts[lo > hi] = np.inf
    ts[ts < t_min[:, None]] = np.inf
    return ts.min(-1)


@settings(max_examples=40, deadline=None)
@given(kind=st.sampled_from(["sphere", "box"]), size=st.floats(0.05, 5.0),
       q=st.tuples(*[st.floats(-1, 1)] * 4).filter(lambda q: np.linalg.norm(q) > 0.1),
       eye_dir=st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.1),
       eye_at=st.floats(0.3, 30.0), nearer=st.floats(0.3, 5.0), far=st.floats(0.3, 3.0),
       aim=st.tuples(*[st.floats(-0.3, 0.3)] * 3))
@example(kind="sphere", size=1.0, q=(1, 0, 0, 0), eye_dir=(0.3, 0.4, 4.0), eye_at=4.0,
         nearer=2.6, far=1.4, aim=(0.2, 0.1, 0.0))
def test_a_csg_surface_is_where_it_is_whatever_the_clip_planes(
        gl_context, kind, size, q, eye_dir, eye_at, nearer, far, aim):
    nearer = min(nearer, 5.0 - far)   # (far / near at most 1e5)
    q = np.asarray(q, float) / np.linalg.norm(q)
    rot = glshade.quaternion.to_matrix(q)
    centre = np.array([0.4, -0.2, 0.1]) * size
    solid = (Sphere(size) if kind == "sphere" else Box(2 * np.array([size, 0.7 * size,
                                                                     0.4 * size])))
    half = size if kind == "sphere" else np.array([size, 0.7 * size, 0.4 * size])
    solid = solid.rotated(q).translated(centre)
    eye = centre + np.asarray(eye_dir) / np.linalg.norm(eye_dir) * eye_at * size
    distance = float(np.linalg.norm(eye - centre))
    scene = glshade.Scene()
    scene.add(solid)
    target = centre + np.asarray(aim) * size
    if np.linalg.norm(target - eye) < 0.05 * size:  # (the eye on its target: look at the centre)
        target = centre
    forward = target - eye
    up = (0, 1, 0) if abs(forward[1]) < 0.9 * np.linalg.norm(forward) else (1, 0, 0)
    cam = glshade.Camera.look_at(eye, target, up=up, fov_y=50,
                                 near=10 ** -nearer * distance, far=10 ** far * distance)
    with glshade.Renderer(N, N, samples=0, context=gl_context) as renderer:
        frame = renderer.render_frame(scene, cam, "phong", outputs=Outputs.DEPTH)
    o, d = cam.rays((N, N))
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    cosf = d @ cam.forward
    t = _first_hit(kind, half, centre, rot, o, d, cam.near / cosf)   # (rays from the eye)
    want = (t * cosf).reshape(N, N)
    want[want > cam.far] = np.inf
    hit = np.isfinite(want)
    pad = np.pad(hit, 1, mode="edge")
    band = np.zeros_like(hit)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            band |= pad[1 + dy:N + 1 + dy, 1 + dx:N + 1 + dx] != hit
    inner = hit & ~band
    got = frame.depth
    wrong = (np.isfinite(got) != hit) & ~band
    assert not wrong.any(), (wrong.sum(), got[wrong][:4], want[wrong][:4], cam.near, cam.far)
    err = np.abs(got[inner] - want[inner])
    if len(err):
        assert err.max() <= 2e-4 * want[inner].max() + 1e-6 * distance, (
            err.max(), cam.near, cam.far)


def test_clip_planes_past_the_depth_buffers_range_are_named(gl_context):
    """A sphere seen from inside through far / near = 1e7 loses most of its pixels in the
    depth buffer (meshes and solids alike: float32 window depth is 1 there): the draw warns,
    naming both planes; at 1e4 (what a camera inside its scene gets) nothing is said and
    every pixel is drawn."""
    import warnings

    from glshade.geometry import primitives

    scene = glshade.Scene()
    scene.add(primitives.icosphere())
    eye = (0.0, 0.0, 0.5)
    with glshade.Renderer(32, 32, samples=0, context=gl_context) as renderer:
        with pytest.warns(glshade.RenderWarning, match=r"near plane \(2e-07\).*far plane"):
            renderer.render_frame(scene, glshade.Camera.look_at(eye, (0, 0, 0), near=2e-7,
                                                                far=2.0))
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            frame = renderer.render_frame(scene, glshade.Camera.look_at(
                eye, (0, 0, 0), near=2e-4, far=2.0), outputs=Outputs.DEPTH)
    assert np.isfinite(frame.depth).all()
