"""Shading modes against an analytic image: a ray-cast unit sphere lit by the same formula
with the exact normal."""

import numpy as np
import pytest

from glshade import Camera
from glshade.geometry import primitives as P
from glshade.scene import Material, PointLight, Scene
from tests.oracle.raycast import render_ellipsoid

SIZE = 256
LIGHT = (3.0, 4.0, 5.0)
MAT = Material(color=(0.9, 0.7, 0.5), ka=0.15, kd=0.6, ks=0.4, shininess=20)
CAMERA = Camera.look_at([0.5, 0.8, 3.2], [0, 0, 0], fov_y=40.0)


def sphere_scene(level):
    s = Scene()
    s.add(P.icosphere(level), MAT)
    s.add_light(PointLight(LIGHT))
    return s


@pytest.fixture(scope="module")
def reference():
    img, hit = render_ellipsoid(CAMERA, SIZE, SIZE, (1, 1, 1), [(LIGHT, (1, 1, 1))], MAT)
    return img * 255, hit


def errors(make_renderer, reference, mode, level):
    r = make_renderer(SIZE, SIZE, samples=0)
    frame = r.render_frame(sphere_scene(level), CAMERA, mode, color_dtype="f4")
    ref, hit = reference
    both = hit & (frame.face_id >= 0)
    diff = np.abs(frame.color[..., :3] * 255 - ref)[both]
    return diff.mean(), diff.max(), both.sum()


def test_phong_on_icosphere_5_matches_analytic(make_renderer, reference):
    mean, worst, n = errors(make_renderer, reference, "phong", 5)
    assert n > 0.2 * SIZE * SIZE
    assert mean <= 0.25, mean
    assert worst <= 4, worst


def test_error_order_and_convergence(make_renderer, reference):
    table = {m: [errors(make_renderer, reference, m, k)[0] for k in (3, 4, 5)]
             for m in ("flat", "gouraud", "phong")}
    for k in range(3):
        assert table["flat"][k] > table["gouraud"][k] > table["phong"][k], table
    for m, errs in table.items():
        assert errs[0] > errs[1] > errs[2], (m, errs)


def test_8bit_output_rounds_the_float_image(make_renderer):
    r = make_renderer(64, 64)
    scene = sphere_scene(3)
    f = r.render_frame(scene, CAMERA, "phong", color_dtype="f4").color
    u = r.render(scene, CAMERA, "phong")
    assert np.abs(u.astype(float) - f * 255).max() <= 0.5 + 1e-3
