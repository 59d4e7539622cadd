"""The numpy twin of lighting.glsl against the independent oracle, point by point; and the
analytic ray caster against the oracle's ellipsoid."""

import numpy as np
import pytest

from glshade import Camera, DirectionalLight, Material, PointLight, Scene
from glshade.cpu.lighting import encode_srgb, face_viewer, light_intensity, view_dir
from glshade.cpu.raycast import raycast_scene
from glshade.geometry import primitives as P
from tests.oracle.raycast import render_ellipsoid, shade_any


def unit(a):
    return a / np.linalg.norm(a, axis=-1, keepdims=True)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_twin_equals_oracle_on_random_points_and_lights(seed):
    rng = np.random.default_rng(seed)
    n_pts = 2000
    p = rng.normal(size=(n_pts, 3))
    n = unit(rng.normal(size=(n_pts, 3)))
    v = unit(rng.normal(size=(n_pts, 3)))
    mat = Material(color=rng.uniform(0, 1, 3), ka=rng.uniform(), kd=rng.uniform(),
                   ks=rng.uniform(), shininess=rng.uniform(1, 80))
    pos = rng.normal(size=3) * 4
    att = (1.0, rng.uniform(0, 0.3), rng.uniform(0, 0.1))
    direction = rng.normal(size=3)
    lights = [PointLight(pos, color=(1, 0.5, 0.2), intensity=1.5, attenuation=att),
              DirectionalLight(direction, color=(0.3, 0.9, 1.0), intensity=0.7)]
    ambient = rng.uniform(0, 1, 3)
    got = light_intensity(p, n, v, mat, lights, ambient)
    oracle = shade_any(p, n, v, [("point", pos, np.array([1, 0.5, 0.2]) * 1.5, att),
                                 ("directional", direction, np.array([0.3, 0.9, 1.0]) * 0.7)],
                       mat, ambient)
    np.testing.assert_allclose(got, oracle, rtol=1e-12, atol=1e-12)
    lit = (got > ambient * mat.ka * np.asarray(mat.color) + 1e-9).any(-1)
    assert 0.2 < lit.mean() < 0.9  # both lit and unlit points were tested


def test_view_dir_and_two_sided_flip():
    cam = Camera.look_at([0, 0, 5], [0, 0, 0])
    p = np.array([[0.0, 0, 0], [1, 0, 1]])
    np.testing.assert_allclose(view_dir(p, cam), unit(np.array([[0, 0, 5.0], [-1, 0, 4]])))
    ortho = cam.replace(projection="orthographic")
    np.testing.assert_allclose(view_dir(p, ortho), [[0, 0, 1], [0, 0, 1]], atol=1e-12)
    n = np.array([[0, 0, 1.0], [0, 1, 0]])
    np.testing.assert_array_equal(face_viewer(n, [False, True]), [[0, 0, 1], [0, -1, 0]])


def test_srgb_twin_matches_the_standard_curve():
    c = np.linspace(0, 1, 101)
    expected = np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)
    np.testing.assert_allclose(encode_srgb(c), expected)


def test_raycast_of_a_scaled_sphere_equals_the_oracle_ellipsoid():
    mat = Material(color=(0.9, 0.6, 0.3), ks=0.6, shininess=20)
    scene = Scene()
    radii = np.array([1.2, 0.7, 0.9])
    scene.add(P.icosphere(1), mat, scale=radii)
    scene.add_light(PointLight((2.0, 3.0, 4.0)))
    cam = Camera.look_at([0.5, 0.8, 4.0], [0, 0, 0], fov_y=40)
    color, mask = raycast_scene(scene, cam, 48, 40)
    ref, hit = render_ellipsoid(cam, 48, 40, radii, [((2.0, 3.0, 4.0), (1, 1, 1))], mat)
    np.testing.assert_array_equal(mask, hit)
    assert 0.1 < mask.mean() < 0.9
    np.testing.assert_allclose(color[mask], ref[mask], atol=1e-9)


def test_raycast_without_lights_uses_the_headlight():
    mat = Material(color=(1, 1, 1), ka=0.0, kd=1.0, ks=0.0)
    scene = Scene()
    scene.add(P.icosphere(1), mat)
    cam = Camera.look_at([0, 0, 4.0], [0, 0, 0], fov_y=40)
    color, mask = raycast_scene(scene, cam, 33, 33)
    assert mask[16, 16]
    np.testing.assert_allclose(color[16, 16], 1.0, atol=1e-12)  # L = V = N at the centre
