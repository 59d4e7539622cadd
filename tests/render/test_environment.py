"""The rasterizer under a sky (glshade.Environment): the background is the map's texel each
pixel centre's view ray meets (the camera's rays and the map's convention, written here);
glTF's model lit by it by the split-sum approximation, against the BRDF's directional
albedo by quadrature under a constant sky (exact there but for the tables' resolution), and
against the path tracer under a sky and a ground (the approximation's error, stated in the
guide); the notes' model keeps its ambient term, and a sky without lights has no headlight."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from glshade import Camera, Environment, Material, PBRMaterial, Scene
from glshade.geometry import primitives as P
from glshade.pathtrace import TraceScene, trace
from tests.pathtrace.test_environment import directional_albedo

pytestmark = pytest.mark.gl

W = H = 48
CAMERA = Camera.look_at((0.0, 0.0, 3.2), (0, 0, 0), fov_y=45.0)


def ball_hits(camera=CAMERA, size=(W, H)):
    """Pixel-centre rays against the unit ball: their directions, and N.V (NaN: a miss)."""
    o, d = camera.rays(size)
    b = np.einsum("...k,...k", o, d)
    disc = b * b - (np.einsum("...k,...k", o, o) - 1)
    t = -b - np.sqrt(np.where(disc > 0, disc, np.nan))
    n = o + t[..., None] * d
    return d, np.einsum("...k,...k", n, -d)


def texel_of(d, shape, rotation=0.0):
    """The map's texel a world direction meets (scene/environment.py's convention)."""
    c, s = np.cos(rotation), np.sin(rotation)
    x, z = c * d[..., 0] - s * d[..., 2], s * d[..., 0] + c * d[..., 2]
    u = (0.5 + np.arctan2(x, -z) / (2 * np.pi)) % 1.0
    v = np.arccos(np.clip(d[..., 1], -1, 1)) / np.pi
    h, w = shape[:2]
    return np.minimum((v * h).astype(int), h - 1), np.minimum((u * w).astype(int), w - 1)


def test_the_background_is_the_maps_texel_at_each_pixel_centre(make_renderer):
    rng = np.random.default_rng(7)
    image = rng.random((8, 16, 3))
    scene = Scene(environment=Environment(image, intensity=0.8, rotation=0.7))
    scene.add(P.icosphere(2, 0.3), Material())
    camera = Camera.look_at((0.0, 0.5, 3.0), (1.0, 0.6, 0.0), fov_y=70.0)
    r = make_renderer(64, 40, samples=0)
    got = r.render_frame(scene, camera, "phong", color_dtype="f4").color[..., :3]
    _, d = camera.rays((64, 40))
    # (pixels whose neighbours' rays meet the same texel: clear of the texels' edges)
    rows, cols = texel_of(d, image.shape, 0.7)
    clear = np.ones(rows.shape, bool)
    for axis in (0, 1):
        for step in (1, -1):
            clear &= (np.roll(rows, step, axis) == rows) & (np.roll(cols, step, axis) == cols)
    frame = r.render_frame(scene, camera, "phong", color_dtype="f4")
    sky = frame.instance == 0
    want = 0.8 * image[rows, cols]
    assert (clear & sky).sum() > 500
    assert np.abs(got[clear & sky] - want[clear & sky]).max() < 1e-5
    srgb = r.render_frame(scene, camera, "phong", srgb=True, color_dtype="f4").color[..., :3]
    encoded = np.where(want <= 0.0031308, 12.92 * want, 1.055 * want ** (1 / 2.4) - 0.055)
    assert np.abs(srgb[clear & sky] - encoded[clear & sky]).max() < 1e-5


@settings(max_examples=6, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(metallic=st.sampled_from([0.0, 0.5, 1.0]), roughness=st.floats(0.3, 1.0),
       mode=st.sampled_from(["phong", "gouraud"]))
def test_a_constant_sky_lights_gltfs_model_by_its_directional_albedo(make_renderer, metallic,
                                                                      roughness, mode):
    base = np.array([0.9, 0.6, 0.3])
    sky = 0.5
    scene = Scene(ambient=(0, 0, 0), environment=Environment((sky, sky, sky)))
    scene.add(P.uv_sphere(96, 192), PBRMaterial(base_color=tuple(base), metallic=metallic,
                                                 roughness=roughness))
    got = make_renderer(W, H, samples=0).render_frame(scene, CAMERA, mode,
                                                       color_dtype="f4").color[..., :3]
    _, mu = ball_hits()
    inside = np.nan_to_num(mu) > 0.25
    mus = np.linspace(0.0, 1.0, 65)
    table = directional_albedo(np.maximum(mus, 1e-4), base, metallic, roughness)
    want = sky * np.stack([np.interp(mu[inside], mus, table[:, c]) for c in range(3)], -1)
    # (the split sum is exact under a constant sky; its 32 x 32 table, bilinear, is not)
    assert np.abs(got[inside] - want).max() <= 0.015 * want.max() + 1e-4, (
        np.abs(got[inside] - want).max(), metallic, roughness, mode)


def test_the_split_sum_is_within_its_stated_error_of_the_path_tracer(make_renderer):
    """A rough gold ball under a sky, a bright patch and a ground: the rasterizer's
    picture within 8% (mean absolute over mean) of the tracer's (pi x radiance), the
    tracer's own noise included (docs/guide/materials.md states the measurement)."""
    image = np.zeros((32, 64, 3))
    image[:16], image[16:] = (0.54, 0.48, 0.36), (0.1, 0.2, 0.05)
    image[4:10, 20:30] = (1.0, 0.95, 0.9)
    scene = Scene(ambient=(0, 0, 0), environment=Environment(image))
    scene.add(P.uv_sphere(96, 192), PBRMaterial(base_color=(0.9, 0.6, 0.3), metallic=1.0,
                                                 roughness=0.3))
    r = make_renderer(W, H, samples=0)
    got = r.render_frame(scene, CAMERA, "phong", color_dtype="f4").color[..., :3]
    traced = trace(TraceScene.from_scene(scene, smooth=True), CAMERA, (W, H), spp=256,
                   context=r.context)
    _, mu = ball_hits()
    inside = np.nan_to_num(mu) > 0.3
    want = traced.image[inside] / np.pi
    error = np.abs(got[inside] - want).mean(0) / want.mean(0)
    assert (error < 0.08).all(), error


def test_without_lights_a_sky_has_no_headlight_and_the_notes_model_its_ambient(
        make_renderer):
    scene = Scene(ambient=(0.2, 0.2, 0.2), environment=Environment((0.0, 0.0, 0.0)))
    scene.add(P.uv_sphere(32, 64), Material(color=(1, 1, 1), ka=0.5, kd=0.8))
    got = make_renderer(W, H, samples=0).render_frame(scene, CAMERA, "phong",
                                                       color_dtype="f4").color[..., :3]
    _, mu = ball_hits()
    inside = np.nan_to_num(mu) > 0.25
    assert np.allclose(got[inside], 0.5 * 0.2, atol=1e-5)  # (ka Ia: no light, no sky)
