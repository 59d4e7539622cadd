"""Wide lines against the exact shapes of their width, built here in float64 from the
camera's own axes (not glshade's projection): a segment's rectangle (butt caps), its
capsule (round caps), the trapezoid of a band of world width under perspective, and a
mitered polyline's outline from the intersections of its offset lines (another
construction than the shader's bisector cuts). Pixel centres inside are drawn, those
outside are not; only centres within half a pixel of the outline are left out."""

import numpy as np
import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import HealthCheck, assume, example, given, settings, strategies as st  # noqa: E402

import glshade  # noqa: E402
from glshade.modes import Outputs  # noqa: E402

pytestmark = [pytest.mark.gl, pytest.mark.filterwarnings("ignore::glshade.RenderWarning")]

W, H = 120, 90
SWEEP = settings(max_examples=10, deadline=None, derandomize=True,
                 suppress_health_check=[HealthCheck.function_scoped_fixture])


def _project(cam, points, size=(W, H)):
    """Pixels (x right, y down from the top-left corner) of a ``size`` image and view
    depths of world points, from the camera's position, axes and field of view."""
    w, h = size
    rel = (np.asarray(points, float) - cam.position) @ cam.rotation
    depth = -rel[:, 2]
    t = np.tan(np.radians(cam.fov_y) / 2)
    x = (rel[:, 0] / depth / (t * w / h) + 1) / 2 * w
    y = (1 - rel[:, 1] / depth / t) / 2 * h
    return np.c_[x, y], depth


def _centres(size=(W, H)):
    x, y = np.meshgrid(np.arange(size[0]) + 0.5, np.arange(size[1]) + 0.5)
    return np.stack([x, y], -1)


def _segment_distance(p, a, b):
    """(distance to the segment a-b, parameter along it, signed distance across it)."""
    ab = b - a
    s = ((p - a) @ ab) / (ab @ ab)
    closest = a + np.clip(s, 0, 1)[..., None] * ab
    n = np.array([-ab[1], ab[0]]) / np.linalg.norm(ab)
    return np.linalg.norm(p - closest, axis=-1), s, (p - a) @ n


def _assert_shape(drawn, inside_far, outside_far):
    assert inside_far.sum() > 20, "the shape has pixels well inside it"
    missing, stray = inside_far & ~drawn, outside_far & drawn
    assert not missing.any(), (int(missing.sum()), np.argwhere(missing)[:3].tolist())
    assert not stray.any(), (int(stray.sum()), np.argwhere(stray)[:3].tolist())


def _camera(eye):
    return glshade.Camera.look_at(eye, (0, 0, 0), fov_y=50, near=0.1, far=50.0)


@SWEEP
@given(angle=st.floats(0, 180), width=st.floats(3.0, 12.0), caps=st.sampled_from(["butt", "round"]),
       tilt=st.floats(-0.8, 0.8), eye_z=st.floats(2.5, 8.0))
def test_a_segment_is_its_rectangle_or_capsule(make_renderer, angle, width, caps, tilt, eye_z):
    """Any direction on screen (0-180 degrees), ends at different depths."""
    r = np.radians(angle)
    a = np.array([-np.cos(r), -np.sin(r), -tilt])
    b = np.array([np.cos(r), np.sin(r), tilt])
    scene = glshade.Scene()
    scene.add(glshade.Polyline([a, b], width=width, caps=caps))
    cam = _camera((0.2, 0.1, eye_z))
    frame = make_renderer(W, H).render_frame(scene, cam, "flat", outputs=Outputs.ALL)
    (pa, pb), _ = _project(cam, [a, b])
    dist, s, across = _segment_distance(_centres(), pa, pb)
    h = width / 2
    if caps == "round":
        inside, outside = dist < h - 0.5, dist > h + 0.5
    else:
        length = np.linalg.norm(pb - pa)
        along = s * length
        inside = (np.abs(across) < h - 0.5) & (along > 0.5) & (along < length - 0.5)
        outside = (np.abs(across) > h + 0.5) | (along < -0.5) | (along > length + 0.5)
    _assert_shape(frame.face_id == 0, inside, outside)


@SWEEP
@given(angle=st.floats(0, 180), width=st.floats(0.05, 0.4), tilt=st.floats(-1.5, 1.5))
def test_a_world_width_is_a_band_narrowing_with_depth(make_renderer, angle, width, tilt):
    """``units="world"``: the band of ``width`` scene units facing the eye: on screen the
    trapezoid whose half widths at the ends are half the width over each end's depth."""
    r = np.radians(angle)
    a = np.array([-np.cos(r), -np.sin(r), -tilt])
    b = np.array([np.cos(r), np.sin(r), tilt])
    scene = glshade.Scene()
    scene.add(glshade.Polyline([a, b], width=width, units="world"))
    cam = _camera((0.0, 0.0, 4.0))
    frame = make_renderer(W, H).render_frame(scene, cam, "flat", outputs=Outputs.ALL)
    (pa, pb), (da, db) = _project(cam, [a, b])
    focal = H / 2 / np.tan(np.radians(cam.fov_y) / 2)   # pixels a unit at depth 1
    ha, hb = width / 2 * focal / da, width / 2 * focal / db
    _, s, across = _segment_distance(_centres(), pa, pb)
    length = np.linalg.norm(pb - pa)
    h = ha + (hb - ha) * s
    # (the slanted sides: a pixel's distance to them is |across| - h over the slope's
    # secant, at most 1.02 here; half a pixel's band covers it)
    inside = (np.abs(across) < h - 0.55) & (s * length > 0.5) & (s * length < length - 0.5)
    outside = (np.abs(across) > h + 0.55) | (s * length < -0.5) | (s * length > length + 0.5)
    assume(inside.sum() > 20)
    _assert_shape(frame.face_id == 0, inside, outside)


def _inside_polygon(p, poly):
    """Even-odd rule: whether points ``p`` (..., 2) lie inside polygon ``poly`` (M, 2)."""
    inside = np.zeros(p.shape[:-1], bool)
    x, y = p[..., 0], p[..., 1]
    for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, 0)):
        crosses = (y0 > y) != (y1 > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            at = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
        inside ^= crosses & (x < at)
    return inside


def _line_intersection(p, d, q, e):
    t = np.linalg.solve(np.c_[d, -e], q - p)[0]
    return p + t * d


def _polygon_distance(p, poly):
    d = np.full(p.shape[:-1], np.inf)
    for a, b in zip(poly, np.roll(poly, -1, 0)):
        d = np.minimum(d, _segment_distance(p, a, b)[0])
    return d


@SWEEP
@given(turn=st.floats(-172, 172).filter(lambda t: abs(t) > 5), width=st.floats(3.0, 24.0),
       start=st.floats(0, 360))
@example(turn=155.0, width=24.0, start=20.0)   # past the miter limit: a bevel
@example(turn=-100.0, width=14.0, start=200.0)  # a long miter tip
def test_a_mitered_joint_is_where_the_offset_lines_meet(make_renderer, turn, width, start):
    """Two segments meeting at any angle up to the miter limit: the outline whose corners
    are the offset lines' intersections (the miter tip outside, the inner corner inside);
    past the limit, the bevel: the outer corners joined by a straight edge."""
    r0 = np.radians(start)
    r1 = r0 + np.radians(turn)
    j = np.zeros(3)
    a = j - 2.2 * np.array([np.cos(r0), np.sin(r0), 0])
    c = j + 2.2 * np.array([np.cos(r1), np.sin(r1), 0])
    scene = glshade.Scene()
    scene.add(glshade.Polyline([a, j, c], width=width))
    cam = glshade.Camera.look_at((0, 0, 5.0), (0, 0, 0), fov_y=50, near=0.1, far=50.0)
    frame = make_renderer(2 * W, 2 * H).render_frame(scene, cam, "flat", outputs=Outputs.ALL)
    (pa, pj, pc), _ = _project(cam, [a, j, c], (2 * W, 2 * H))
    h = width / 2
    d1, d2 = (pj - pa) / np.linalg.norm(pj - pa), (pc - pj) / np.linalg.norm(pc - pj)
    n1, n2 = np.array([-d1[1], d1[0]]), np.array([-d2[1], d2[0]])
    left = _line_intersection(pa + h * n1, d1, pc + h * n2, d2)
    right = _line_intersection(pa - h * n1, d1, pc - h * n2, d2)
    turn_left = d1[0] * d2[1] - d1[1] * d2[0] > 0     # (image y down: the sign is the view's)
    outer, outer_n1, outer_n2 = (right, -n1, -n2) if turn_left else (left, n1, n2)
    if np.linalg.norm(outer - pj) > glshade.geometry.lines.MITER_LIMIT * h:  # a bevel
        outer_corners = [pj + h * outer_n1, pj + h * outer_n2]
    else:
        outer_corners = [outer]
    inner = left if turn_left else right
    side = -1 if turn_left else 1
    poly = np.array([pa + side * h * (-n1), *[inner], pc + side * h * (-n2),
                     pc + side * h * n2, *outer_corners[::-1], pa + side * h * n1])
    # (the inner corner may pass the segments' ends at sharp turns: keep to clear joints)
    assume(np.linalg.norm(inner - pj) < 0.9 * min(np.linalg.norm(pj - pa),
                                                     np.linalg.norm(pc - pj)))
    p = _centres((2 * W, 2 * H))
    inside_poly = _inside_polygon(p, poly)
    far = _polygon_distance(p, poly) > 0.5
    _assert_shape(frame.face_id >= 0, inside_poly & far, ~inside_poly & far)


def test_lines_are_depth_tested_and_take_ids_after_the_points(make_renderer):
    """A line through a cube shows outside it and is hidden inside; its segments follow
    the cube's faces and a cloud's points in the ids, with their model's instance."""
    scene = glshade.Scene()
    scene.add(glshade.geometry.primitives.cube())
    scene.add(glshade.PointCloud([[3.0, 3.0, 0.0]], radius=0.1))
    scene.add(glshade.Polyline([[-3, 0, 0], [0, 0, 0], [3, 0, 0]], width=5),
              glshade.Material(color=(1, 0, 0)), label="path")
    cam = _camera((0.0, 0.0, 8.0))
    frame = make_renderer(W, H).render_frame(scene, cam, "flat", outputs=Outputs.ALL)
    n_faces = glshade.geometry.primitives.cube().n_faces
    (pa, pj, pc), _ = _project(cam, [[-3, 0, 0], [0, 0, 0], [3, 0, 0]])
    row = int(pj[1])
    ids = frame.face_id[row]
    (lo, hi) = glshade.geometry.primitives.cube().bounds
    cube_x = _project(cam, [[lo[0], 0, hi[2]], [hi[0], 0, hi[2]]])[0][:, 0]
    left = (np.arange(W) + 0.5 > pa[0] + 1) & (np.arange(W) + 0.5 < cube_x[0] - 1)
    right = (np.arange(W) + 0.5 > cube_x[1] + 1) & (np.arange(W) + 0.5 < pc[0] - 1)
    middle = (np.arange(W) + 0.5 > cube_x[0] + 1) & (np.arange(W) + 0.5 < cube_x[1] - 1)
    assert (ids[left] == n_faces + 1).all() and (ids[right] == n_faces + 2).all()
    assert (ids[middle] < n_faces).all()   # (the cube's front face hides the line)
    assert (frame.instance[row][left | right] == 3).all()
    assert (frame.semantic[row][left] == scene.labels["path"]).all()


def test_polyline_arguments_are_checked():
    with pytest.raises(glshade.GeometryError, match=r"N >= 2 \(a line needs two points\)"):
        glshade.Polyline([[0, 0, 0]])
    with pytest.raises(glshade.GeometryError, match=r"points\[1\] must have shape"):
        glshade.Polyline([np.zeros((3, 3)), np.zeros((2, 2))])
    with pytest.raises(glshade.GeometryError, match="width must be a finite number > 0"):
        glshade.Polyline(np.zeros((2, 3)), width=0)
    with pytest.raises(glshade.GeometryError, match=r"joins must be 'miter' or 'round'"):
        glshade.Polyline(np.zeros((2, 3)), joins="bevel")
    with pytest.raises(glshade.GeometryError, match=r"colors must have shape \(5, 3\)"):
        glshade.Polyline([np.zeros((2, 3)), np.ones((3, 3))], colors=np.zeros((4, 3)))
    lines = glshade.Polyline([np.zeros((2, 3)), np.ones((3, 3))])
    assert lines.n_segments == 3
    assert lines.segments.tolist() == [[0, 0, 1, 1], [2, 2, 3, 4], [2, 3, 4, 4]]
