"""The arcball's rotations (pure numpy, no window)."""

import numpy as np
import pytest

from glshade import quaternion as Q
from glshade.viewer.arcball import Arcball, drag_rotation, sphere_point


def test_centre_to_rim_is_90_degrees_about_the_perpendicular_axis():
    ball = Arcball(400, 300)
    ball.begin(200, 150)
    for dx, dy, axis in ((150, 0, [0, 1, 0]), (-150, 0, [0, -1, 0]), (0, -150, [-1, 0, 0]),
                         (0, 150, [1, 0, 0])):
        q = ball.drag(200 + dx, 150 + dy)
        a, angle = Q.to_axis_angle(q)
        assert np.degrees(angle) == pytest.approx(90)
        np.testing.assert_allclose(a, axis, atol=1e-12)
    # a diagonal drag to the rim: the axis is perpendicular to the drag, in the screen plane
    q = ball.drag(200 + 150 / np.sqrt(2), 150 - 150 / np.sqrt(2))
    a, angle = Q.to_axis_angle(q)
    assert np.degrees(angle) == pytest.approx(90)
    np.testing.assert_allclose(a, [-1 / np.sqrt(2), 1 / np.sqrt(2), 0], atol=1e-12)


def test_rotation_maps_start_point_to_end_point_and_is_unit(rng):
    for _ in range(500):
        x0, x1 = rng.uniform(-100, 500, 2)
        y0, y1 = rng.uniform(-100, 400, 2)
        p0, p1 = sphere_point(x0, y0, 400, 300), sphere_point(x1, y1, 400, 300)
        q = drag_rotation(p0, p1)
        assert Q.norm(q) == pytest.approx(1.0, abs=1e-15)
        np.testing.assert_allclose(Q.rotate(q, p0), p1, atol=1e-12)
    # opposite rim points: a half turn, still unit
    q = drag_rotation(np.array([1.0, 0, 0]), np.array([-1.0, 0, 0]))
    assert Q.norm(q) == pytest.approx(1.0)
    np.testing.assert_allclose(Q.rotate(q, [1.0, 0, 0]), [-1, 0, 0], atol=1e-12)


def test_points_outside_the_ball_go_to_its_rim():
    p = sphere_point(1000, 150, 400, 300)
    np.testing.assert_allclose(p, [1, 0, 0])
    assert np.linalg.norm(sphere_point(123, 45, 400, 300)) == pytest.approx(1.0)
