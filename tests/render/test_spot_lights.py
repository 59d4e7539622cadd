"""A spot light's cone against its closed form (KHR_lights_punctual: full within the inner
angle, none beyond the outer, clamp((cos a - cos outer) / (cos inner - cos outer))^2
between), written out here in float64: a white floor under a spot light pointing straight
down, every pixel's camera ray met with the floor by hand; and its shadows."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from glshade import Camera, Material, Mesh, Scene, SpotLight
from glshade.errors import SceneError

pytestmark = pytest.mark.gl

W = H = 96
CAMERA = Camera.look_at(eye=(0.3, -0.2, 6.0), target=(0.0, 0.0, 0.0), fov_y=50.0)
FLOOR = Mesh([[-4, -4, 0], [4, -4, 0], [4, 4, 0], [-4, 4, 0]], [[0, 1, 2, 3]])
WHITE = Material(color=(1, 1, 1), ka=0.0, kd=1.0, ks=0.0)


def closed_form(spot_at, inner, outer, attenuation=(1.0, 0.0, 0.0)):
    """``(H, W)`` the floor's diffuse intensity under the spot, at each pixel centre."""
    o, d = CAMERA.rays((W, H))
    t = -o[..., 2] / d[..., 2]
    p = o + t[..., None] * d
    to = np.asarray(spot_at) - p
    dist = np.linalg.norm(to, axis=-1)
    cos_n = to[..., 2] / dist                       # L.N, N = +z
    cos_axis = to[..., 2] / dist                    # the angle from the axis (straight down)
    s = np.clip((cos_axis - np.cos(outer)) / (np.cos(inner) - np.cos(outer)), 0, 1)
    c, lin, q = attenuation
    return cos_n * s * s / (c + lin * dist + q * dist * dist)


@settings(max_examples=12, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(inner=st.floats(0.0, 0.9), width=st.floats(0.05, 0.6), height=st.floats(1.0, 3.0),
       mode=st.sampled_from(["phong", "gouraud"]))
def test_the_cone_is_its_closed_form(make_renderer, inner, width, height, mode):
    outer = min(inner + width, np.pi / 2)
    spot_at = (0.2, -0.1, height)
    scene = Scene(ambient=(0, 0, 0), background=(0, 0, 0))
    scene.add(FLOOR if mode == "phong" else _fine_floor(), WHITE)
    scene.add_light(SpotLight(position=spot_at, direction=(0, 0, -1), inner_angle=inner,
                              outer_angle=outer))
    r = make_renderer(W, H, samples=0)
    got = r.render_frame(scene, CAMERA, mode, color_dtype="f4").color[..., 0]
    want = closed_form(spot_at, inner, outer)
    if mode == "gouraud":  # (the vertices' values interpolated: a fine floor, a mean bound)
        assert np.abs(got - want).mean() <= 0.02
        return
    assert np.abs(got - want).max() <= 2e-4, np.abs(got - want).max()
    # the line through both edges: dark beyond the outer one, the closed form between
    row, line = got[H // 2], want[H // 2]
    assert (row[line == 0] <= 1e-6).all()


def _fine_floor(n=48):
    x = np.linspace(-4, 4, n + 1)
    xx, yy = np.meshgrid(x, x)
    v = np.column_stack([xx.ravel(), yy.ravel(), np.zeros(xx.size)])
    i = np.arange(n)
    a = (i[:, None] * (n + 1) + i[None, :]).ravel()
    return Mesh(v, np.column_stack([a, a + 1, a + n + 2, a + n + 1]))


def test_attenuation_and_colour_multiply_the_cone(make_renderer):
    spot_at = (0.0, 0.0, 2.0)
    light = SpotLight(position=spot_at, direction=(0, 0, -1), color=(1.0, 0.5, 0.25),
                      intensity=2.0, inner_angle=0.3, outer_angle=0.7,
                      attenuation=(1.0, 0.2, 0.1))
    scene = Scene(ambient=(0, 0, 0), background=(0, 0, 0))
    scene.add(FLOOR, WHITE)
    scene.add_light(light)
    got = make_renderer(W, H, samples=0).render_frame(scene, CAMERA, "phong",
                                                      color_dtype="f4").color[..., :3]
    want = closed_form(spot_at, 0.3, 0.7, (1.0, 0.2, 0.1))[..., None] * \
        2.0 * np.array([1.0, 0.5, 0.25])
    assert np.abs(got - np.clip(want, 0, 1)).max() <= 3e-4


@pytest.mark.parametrize("method", ["exact", "map"])
def test_a_spot_light_casts_shadows(make_renderer, method):
    """A small square between the spot and the floor: the pixels whose floor point cannot
    see the light (the ray to it meets the square) are dark -- every one with exact
    shadows; with a (cube) shadow map, every one more than 2 pixels from the shadow's
    edge."""
    from scipy import ndimage

    spot_at = np.array([0.0, 0.0, 3.0])
    blocker = Mesh([[-0.4, -0.4, 1.5], [0.4, -0.4, 1.5], [0.4, 0.4, 1.5], [-0.4, 0.4, 1.5]],
                   [[0, 1, 2, 3]])
    scene = Scene(ambient=(0, 0, 0), background=(0, 0, 0))
    scene.add(FLOOR, WHITE)
    scene.add(blocker, Material(color=(0, 0, 0), ka=0, kd=0, ks=0))
    scene.add_light(SpotLight(position=tuple(spot_at), direction=(0, 0, -1), inner_angle=0.6,
                              outer_angle=1.0))
    frame = make_renderer(W, H, samples=0).render_frame(scene, CAMERA, "phong",
                                                        shadows=method, color_dtype="f4")
    o, d = CAMERA.rays((W, H))
    p = o + (-o[..., 2] / d[..., 2])[..., None] * d
    # where the segment floor -> light crosses z = 1.5 (inside the square: in shadow)
    k = 1.5 / 3.0
    cross = p + k * (spot_at - p)
    shade = (np.abs(cross[..., 0]) < 0.4) & (np.abs(cross[..., 1]) < 0.4)
    floor = frame.face_id == 0
    if method == "map":  # (the map's band: 2 pixels either side of the shadow's edge)
        band = ndimage.binary_dilation(shade, iterations=2) & \
            ~ndimage.binary_erosion(shade, iterations=2)
        floor &= ~band
    clear = floor & ~shade & (closed_form(tuple(spot_at), 0.6, 1.0) > 0.05)
    assert (frame.color[..., 0][floor & shade] <= 1e-6).sum() >= 0.97 * (floor & shade).sum()
    assert (floor & shade).sum() > 50 and (frame.color[..., 0][clear] > 0.04).all()


def test_bad_cones_are_refused_naming_the_field():
    with pytest.raises(SceneError, match="outer_angle must be in"):
        SpotLight(outer_angle=2.0)
    with pytest.raises(SceneError, match="inner_angle must be in"):
        SpotLight(inner_angle=0.8, outer_angle=0.5)
    with pytest.raises(SceneError, match="direction must be a non-zero"):
        SpotLight(direction=(0, 0, 0))


def test_the_path_tracer_takes_the_cone(gl_context):
    """A diffuse floor under a spot light, traced: one bounce (nothing else to hit), so each
    pixel is rho x the closed form averaged over the pixel; dark beyond the cone."""
    from glshade.pathtrace.progressive import trace

    spot_at = (0.0, 0.0, 2.0)
    scene = Scene(ambient=(0, 0, 0), background=(0, 0, 0))
    scene.add(FLOOR, Material(color=(0.5, 0.5, 0.5), ka=0.0, kd=1.0, ks=0.0))
    scene.add_light(SpotLight(position=spot_at, direction=(0, 0, -1), inner_angle=0.2,
                              outer_angle=0.6))
    traced = trace(scene, CAMERA, (W, H), spp=16, context=gl_context, progress=False)
    got = np.asarray(traced.image)[..., 0]
    want = 0.5 * closed_form(spot_at, 0.2, 0.6)
    # (a pixel's samples spread over it: the closed form's slope across a pixel is the bound)
    slope = np.maximum(np.abs(np.gradient(want, axis=0)), np.abs(np.gradient(want, axis=1)))
    assert (np.abs(got - want) <= slope + 2e-3).mean() >= 0.99
    assert np.abs(got - want).mean() <= 2e-3


def test_a_scene_file_spot_light_is_the_api_s(tmp_path):
    from glshade import load_scene
    from glshade.errors import SceneFormatError

    (tmp_path / "spot.toml").write_text(
        '[[mesh]]\nsource = "primitive:plane"\nka = 0.0\n\n[[light]]\ntype = "spot"\n'
        'position = [0.1, 0.0, 2.0]\ndirection = [0, 0, -1]\ninner_angle = 0.2\n'
        'outer_angle = 0.45\n')
    loaded = load_scene(tmp_path / "spot.toml")
    (light,) = loaded.scene.lights
    assert light == SpotLight(position=(0.1, 0.0, 2.0), direction=(0, 0, -1),
                              inner_angle=0.2, outer_angle=0.45)
    (tmp_path / "bad.toml").write_text(
        '[[mesh]]\nsource = "primitive:plane"\n\n[[light]]\nposition = [0, 0, 2]\n'
        'outer_angle = 0.45\n')
    with pytest.raises(SceneFormatError, match=r"bad.toml:4: \[\[light\]\] 1: 'outer_angle' "
                                               r"is a spot light's"):
        load_scene(tmp_path / "bad.toml")


@pytest.mark.parametrize("model", ["notes", "pbr"])
def test_a_lights_range_is_glTFs_window(make_renderer, model):
    """KHR_lights_punctual's range: the light times clamp(1 - (d / range)^4, 0, 1)^2, in
    either lighting model, against the closed form along the floor."""
    from glshade import PBRMaterial, PointLight

    light_at = np.array([0.0, 0.0, 1.5])
    scene = Scene(ambient=(0, 0, 0), background=(0, 0, 0))
    material = WHITE if model == "notes" else PBRMaterial(base_color=(1, 1, 1), metallic=0.0,
                                                          roughness=1.0, ka=0.0)
    scene.add(FLOOR, material)
    scene.add_light(PointLight(position=tuple(light_at), range=2.5))
    got = make_renderer(W, H, samples=0).render_frame(scene, CAMERA, "phong",
                                                      color_dtype="f4").color[..., 0]
    o, d = CAMERA.rays((W, H))
    p = o + (-o[..., 2] / d[..., 2])[..., None] * d
    to = light_at - p
    dist = np.linalg.norm(to, axis=-1)
    cos = to[..., 2] / dist
    window = np.clip(1 - (dist / 2.5) ** 4, 0, 1) ** 2
    if model == "notes":
        want = cos * window
        assert np.abs(got - want).max() <= 2e-4
    else:  # (a white, rough dielectric: Appendix B over the inverse square)
        from tests.render.test_pbr import appendix_b

        eye = np.asarray(CAMERA.position, np.float64)
        v = eye - p
        v /= np.linalg.norm(v, axis=-1, keepdims=True)
        n = np.broadcast_to([0.0, 0.0, 1.0], p.shape).reshape(-1, 3)
        brdf = appendix_b(n, (to / dist[..., None]).reshape(-1, 3), v.reshape(-1, 3),
                          np.ones(3), 0.0, 1.0)[:, 0].reshape(H, W)
        want = np.clip(brdf * window / dist ** 2, 0, 1)
        assert np.abs(got - want).max() <= 2e-4
    assert (window == 0).any() and (window > 0.5).any()
