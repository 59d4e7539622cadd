"""Camera and key-frame paths."""

import numpy as np
import pyrr
import pytest

from glshade import Camera, CameraPath, GeometryError, Keyframe, OptionError, SceneError
from glshade import quaternion as Q
from glshade.errors import PathFormatError


def test_look_at_puts_target_on_minus_z(rng):
    for _ in range(20):
        eye, target = rng.normal(size=(2, 3)) * 5
        cam = Camera.look_at(eye, target)
        p = cam.view_matrix() @ np.append(target, 1)
        np.testing.assert_allclose(p[:2], 0, atol=1e-12)
        assert p[2] == pytest.approx(-np.linalg.norm(target - eye))
        # camera's up lies in the plane of world up and the view direction
        assert abs(np.dot(np.cross(cam.forward, [0, 1, 0]), cam.up)) < 1e-12
        assert cam.up[1] > 0


def test_view_matrix_agrees_with_pyrr_look_at(rng):
    eye, target = np.array([3.0, 2, 5]), np.array([0.0, 0.5, 0])
    ours = Camera.look_at(eye, target).view_matrix()
    theirs = pyrr.matrix44.create_look_at(eye, target, [0, 1, 0], dtype=np.float64)
    np.testing.assert_allclose(ours, theirs.T, atol=1e-12)  # pyrr is row-vector layout


def test_projection_layout_column_vectors():
    cam = Camera(fov_y=60.0, near=0.5, far=50.0)
    p = cam.projection_matrix(2.0)
    for z, ndc_z in ((-0.5, -1.0), (-50.0, 1.0)):
        clip = p @ [0, 0, z, 1]
        assert clip[2] / clip[3] == pytest.approx(ndc_z)
    # a point at the top edge of the field of view maps to ndc y = 1
    y = np.tan(np.radians(30)) * 10
    clip = p @ [0, y, -10, 1]
    assert clip[1] / clip[3] == pytest.approx(1.0)
    x = y * 2.0
    assert (p @ [x, 0, -10, 1])[0] / 10 == pytest.approx(1.0)
    ortho = Camera(projection="orthographic", height=4.0).projection_matrix(1.0)
    np.testing.assert_allclose(ortho @ [0, 2, -1, 1], [0, 1, ortho[2] @ [0, 2, -1, 1], 1])


def test_orbit_keeps_center_on_axis():
    cam = Camera.look_at([0, 0, 5], [0, 0, 0])
    moved = cam.orbit(Q.from_axis_angle([0, 1, 0], np.pi / 2))
    np.testing.assert_allclose(moved.position, [5, 0, 0], atol=1e-12)
    p = moved.view_matrix() @ [0, 0, 0, 1]
    np.testing.assert_allclose(p[:3], [0, 0, -5], atol=1e-12)


def test_frame_fits_bounding_sphere():
    from glshade.geometry import primitives as P

    m = P.icosphere(2).transformed(np.diag([1, 1, 1, 1.0]))
    cam = Camera.look_at([0, 0, 1], [0, 0, 0]).frame(m, aspect=1.0, margin=1.0)
    radius = np.linalg.norm(m.bounds[1] - m.bounds[0]) / 2
    d = np.linalg.norm(cam.position)
    assert np.sin(np.radians(cam.fov_y / 2)) * d == pytest.approx(radius)
    near, far = cam.planes(m.bounds)  # (fitted to the box around the sphere)
    assert cam.near is None and cam.far is None
    view = cam.view_matrix()
    depth = -(m.vertices @ view[2, :3] + view[2, 3])  # every vertex lies between the planes
    assert near < depth.min() and far > depth.max()


def test_camera_validation():
    with pytest.raises(SceneError, match="fov_y"):
        Camera(fov_y=0)
    with pytest.raises(SceneError, match="near < far"):
        Camera(near=2, far=1)
    with pytest.raises(OptionError, match="projection"):
        Camera(projection="fisheye")
    with pytest.raises(GeometryError, match="parallel"):
        Camera.look_at([0, 5, 0], [0, 0, 0])


def make_path(**kw):
    return CameraPath([
        Keyframe.look_at(0.0, [0, 0, 5], [0, 0, 0]),
        Keyframe.look_at(1.0, [5, 0, 0], [0, 0, 0], fov_y=30.0),
        Keyframe.look_at(3.0, [0, 2, -5], [0, 0, 0]),
    ], **kw)


@pytest.mark.parametrize("orient", ["slerp", "spline"])
@pytest.mark.parametrize("pos", ["linear", "catmull-rom"])
def test_path_at_key_time_equals_key(orient, pos):
    path = make_path(orientation_interp=orient, position_interp=pos)
    for key in path.keyframes:
        cam = path.at(key.time)
        np.testing.assert_allclose(cam.position, key.position, atol=1e-12)
        assert Q.angle_between(cam.orientation, key.orientation) < 1e-7
    assert path.at(1.0).fov_y == 30.0


def test_path_slerp_equal_angles_per_frame():
    a = Q.from_axis_angle([0, 1, 0], 0.0)
    b = Q.from_axis_angle([0, 1, 0], np.pi / 2)
    path = CameraPath([Keyframe(0, [0, 0, 0], a), Keyframe(2, [0, 0, 0], b)])
    cams = path.sample(9)
    steps = [Q.angle_between(c0.orientation, c1.orientation) for c0, c1 in
             zip(cams, cams[1:])]
    np.testing.assert_allclose(steps, np.pi / 2 / 8, atol=1e-12)


@pytest.mark.parametrize("degrees", [360.0, 90.0, -135.0])
def test_turntable_circles_the_centre_at_constant_speed(degrees):
    """Against the exact orbit: the start camera turned about the up axis (scipy-free:
    Rodrigues by hand), looking at the centre all the way."""
    centre = np.array([1.0, 0.5, -2.0])
    start = Camera.look_at([4.0, 2.5, 3.0], centre, fov_y=35.0)
    path = CameraPath.turntable(start, centre, 3.0, degrees)
    cams = path.sample(61)
    rel0 = start.position - centre
    for i, cam in enumerate(cams):
        a = np.radians(degrees) * i / 60
        c, s_ = np.cos(a), np.sin(a)
        exact = centre + [c * rel0[0] + s_ * rel0[2], rel0[1], -s_ * rel0[0] + c * rel0[2]]
        assert np.linalg.norm(cam.position - exact) < 1e-3 * np.linalg.norm(rel0)
        to_centre = (centre - cam.position) / np.linalg.norm(centre - cam.position)
        assert np.degrees(np.arccos(min(1.0, cam.forward @ to_centre))) < 0.05
        assert cam.fov_y == 35.0
    steps = [Q.angle_between(c0.orientation, c1.orientation) for c0, c1 in zip(cams, cams[1:])]
    np.testing.assert_allclose(steps, abs(np.radians(degrees)) / 60, atol=1e-9)
    assert path.duration == 3.0
    with pytest.raises(SceneError, match="duration"):
        CameraPath.turntable(start, centre, 0.0)


def test_path_times_must_increase():
    with pytest.raises(SceneError, match="times must increase: key 2 has time 1 after 1"):
        CameraPath([Keyframe.look_at(1, [0, 0, 5], [0, 0, 0]),
                    Keyframe.look_at(1, [5, 0, 0], [0, 0, 0])])


def test_toml_round_trip(tmp_path):
    path = make_path()
    path.save(tmp_path / "p.toml")
    back = CameraPath.load(tmp_path / "p.toml")
    for t in np.linspace(0, 3, 7):
        a, b = path.at(t), back.at(t)
        np.testing.assert_allclose(a.position, b.position, atol=1e-12)
        assert Q.angle_between(a.orientation, b.orientation) < 1e-7


def test_toml_hand_written_and_errors(tmp_path):
    f = tmp_path / "hand.toml"
    f.write_text("[[keyframe]]\ntime = 0\neye = [0, 0, 5]\ntarget = [0, 0, 0]\n\n"
                 "[[keyframe]]\ntime = 2\nposition = [5, 0, 0]\n"
                 "orientation = [0, 0.7071067811865476, 0, 0.7071067811865476]\n")
    path = CameraPath.load(f)
    np.testing.assert_allclose(path.at(2).forward, [-1, 0, 0], atol=1e-12)
    f.write_text("[[keyframe]]\ntime = 0\neye = [0, 0, 5]\n")
    with pytest.raises(PathFormatError, match="keyframe 1: give both 'eye' and 'target'"):
        CameraPath.load(f)
    f.write_text("[[keyframe]]\ntime = 0\neye = [0, 0, 5]\ntarget = [0,0,0]\nzoom = 2\n")
    with pytest.raises(PathFormatError, match=r"unknown key\(s\) \['zoom'\]"):
        CameraPath.load(f)
    f.write_text("[[keyframe]\n")
    with pytest.raises(PathFormatError, match="hand.toml"):
        CameraPath.load(f)
