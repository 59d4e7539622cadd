"""The path tracer's sky (glshade.Environment), against closed forms and quadrature:

- the white furnace: a ball of glTF's model under a constant sky shows, at each pixel, the
  sky's radiance times the BRDF's directional albedo at that view -- the albedo integrated
  here in float64 by Gauss-Legendre quadrature of the Appendix B BRDF (GGX's single
  scattering loses energy at high roughness: the quadrature says how much);
- a diffuse ball under a sky that is one radiance above the horizon and another below:
  irradiance pi (L_sky (1 + n_y) + L_ground (1 - n_y)) / 2, the classic closed form;
- a rotated map rotates the picture: the sky turned a quarter about +y, seen looking down
  -z, is the unturned sky seen looking down +x.
Pictures are in radiosity units (pi x radiance)."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from glshade import Camera, Environment, Material, PBRMaterial, Scene
from glshade.errors import SceneError
from glshade.geometry import primitives as P
from glshade.pathtrace import TraceScene, trace
from tests.render.test_pbr import appendix_b

pytestmark = pytest.mark.gl

W = H = 32
EYE = np.array([0.0, 0.0, 3.2])
CAMERA = Camera.look_at(tuple(EYE), (0, 0, 0), fov_y=45.0)
SUB = 4  # (sub-pixel samples a side: the oracle's mean over each pixel, as jitter averages)


def ball_views():
    """For SUB x SUB points in each pixel: the unit ball's normal where the camera ray
    meets it (NaN where it misses), and the view direction."""
    offsets = (np.arange(SUB) + 0.5) / SUB - 0.5
    out = []
    for dx in offsets:
        for dy in offsets:
            o, d = CAMERA.rays((W, H), jitter=(dx, dy))
            b = np.einsum("...k,...k", o, d)
            disc = b * b - (np.einsum("...k,...k", o, o) - 1)
            t = -b - np.sqrt(np.where(disc > 0, disc, np.nan))
            n = o + t[..., None] * d
            out.append((n, -d))
    return out


def directional_albedo(mu, base, metallic, roughness, k=192):
    """The Appendix B BRDF's directional albedo ``(len(mu), 3)`` at view cosines ``mu``:
    the integral of f cos over the hemisphere, Gauss-Legendre in cos(theta) x the
    trapezoid (exact for periodic functions) in phi."""
    x, wx = np.polynomial.legendre.leggauss(k)
    cos_t, w_t = 0.5 * (x + 1), 0.5 * wx
    phi = 2 * np.pi * np.arange(2 * k) / (2 * k)
    ct, ph = np.meshgrid(cos_t, phi, indexing="ij")
    st_ = np.sqrt(1 - ct ** 2)
    light = np.stack([st_ * np.cos(ph), st_ * np.sin(ph), ct], -1).reshape(-1, 3)
    weight = (w_t[:, None] * np.full(2 * k, 2 * np.pi / (2 * k))).reshape(-1)
    out = []
    for m in mu:
        v = np.broadcast_to([np.sqrt(1 - m * m), 0.0, m], light.shape)
        n = np.broadcast_to([0.0, 0.0, 1.0], light.shape)
        f_cos = appendix_b(n, light, np.ascontiguousarray(v), base, metallic, roughness)
        out.append((f_cos * weight[:, None]).sum(0))
    return np.array(out)


def ball_scene(material, environment):
    scene = Scene(environment=environment)
    scene.add(P.uv_sphere(96, 192), material)
    return TraceScene.from_scene(scene, smooth=True)  # (the ball's normals, not facets')


def compare(traced, want, inside):
    """Each pixel within its error (a few of ~1,000 past 4 se by chance, none past 7), and
    the picture's sum within the sum's error."""
    got, se = traced.image[inside], traced.se[inside]
    slack = 3e-3 * want[inside] + 1e-4  # (the ball's facets)
    z = np.abs(got - want[inside]) / (se + slack)
    assert (z > 4).mean() < 0.01 and z.max() < 7, z.max()
    bias = np.abs((got - want[inside]).sum(0))
    assert (bias <= 4 * np.sqrt((se ** 2).sum(0)) + slack.sum(0)).all(), bias


@settings(max_examples=4, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(metallic=st.sampled_from([0.0, 1.0]), roughness=st.floats(0.3, 1.0))
def test_the_white_furnace_is_the_brdfs_directional_albedo(gl_context, metallic, roughness):
    sky = 0.8
    base = np.array([1.0, 1.0, 1.0])
    material = PBRMaterial(base_color=(1.0, 1.0, 1.0), metallic=metallic, roughness=roughness)
    traced = trace(ball_scene(material, Environment((sky, sky, sky))), CAMERA, (W, H),
                   spp=96, context=gl_context)
    mus = np.linspace(0.0, 1.0, 65)
    table = directional_albedo(np.maximum(mus, 1e-4), base, metallic, roughness)
    want = np.zeros((H, W, 3))
    inside = np.ones((H, W), bool)
    for n, v in ball_views():
        mu = np.einsum("...k,...k", n, v)
        inside &= np.isfinite(mu) & (np.nan_to_num(mu) > 0.3)
        albedo = np.stack([np.interp(np.nan_to_num(mu), mus, table[:, c]) for c in range(3)],
                          -1)
        want += np.pi * sky * albedo
    want /= SUB ** 2
    compare(traced, want, inside)
    assert inside.sum() > 0.3 * W * H
    # (GGX single scattering: a rough metal reflects less than all of a white sky)
    if metallic == 1.0 and roughness > 0.8:
        assert table[-1].mean() < 0.97


def test_a_sky_and_a_ground_light_a_diffuse_ball_in_closed_form(gl_context):
    sky, ground = np.array([0.9, 0.8, 0.6]), np.array([0.1, 0.2, 0.05])
    image = np.zeros((8, 16, 3))
    image[:4], image[4:] = sky, ground  # (rows 0-3 above the horizon)
    rho = 0.7
    material = Material(color=(1, 1, 1), kd=rho, ks=0.0)
    traced = trace(ball_scene(material, Environment(image)), CAMERA, (W, H), spp=128,
                   context=gl_context)
    want = np.zeros((H, W, 3))
    inside = np.ones((H, W), bool)
    for n, v in ball_views():
        mu = np.einsum("...k,...k", n, v)
        inside &= np.isfinite(mu) & (np.nan_to_num(mu) > 0.2)
        ny = np.nan_to_num(n[..., 1])[..., None]
        want += rho * np.pi * (sky * (1 + ny) + ground * (1 - ny)) / 2
    want /= SUB ** 2
    compare(traced, want, inside)
    # (the sky itself where camera rays miss: pi x its radiance, above the horizon here)
    corner = traced.image[0, 0]
    assert np.allclose(corner, np.pi * sky, rtol=1e-5)


def test_a_rotated_map_rotates_the_picture(gl_context):
    rng = np.random.default_rng(3)
    image = rng.random((16, 32, 3))
    speck = Scene(environment=Environment(image, rotation=np.pi / 2))
    speck.add(P.icosphere(1, 0.01), Material())  # (something to trace, far from the views)
    ahead = Camera.look_at((0, 0, 0.5), (0, 0, -1), fov_y=60)
    turned = trace(speck, ahead, (24, 16), spp=16, context=gl_context)
    speck.environment = Environment(image)
    right = Camera.look_at((0, 0, 0.5), (1, 0, 0.5), fov_y=60)
    plain = trace(speck, right, (24, 16), spp=16, context=gl_context)
    # (the same texels, but for pixels whose rays pass within a rounding of a texel's edge)
    same = np.abs(turned.image - plain.image).max(-1) < 1e-4
    assert same.mean() > 0.97, same.mean()
    assert np.abs(turned.image - trace(speck, ahead, (24, 16), spp=16,
                                       context=gl_context).image).max() > 0.1


def test_bad_environments_are_one_line():
    with pytest.raises(SceneError, match=r"an environment is \(r, g, b\) or an \(H, W, 3\)"):
        Environment(np.ones((4, 4)))
    with pytest.raises(SceneError, match="finite and >= 0"):
        Environment((1.0, -1.0, 0.0))
    with pytest.raises(SceneError, match="intensity must be >= 0"):
        Environment((1.0, 1.0, 1.0), intensity=-2)
    with pytest.raises(SceneError, match="environment must be a glshade.Environment"):
        Scene(environment=(1, 1, 1))


def test_an_hdr_file_is_read_as_linear_rgb(tmp_path):
    """A Radiance .hdr written by OpenCV (BGR; RGBE: 8-bit mantissas, one exponent)
    reads back as the RGB radiance it holds, within RGBE's rounding; a .npy as it is; a
    bad path or kind is one line."""
    from glshade.errors import InputError

    cv2 = pytest.importorskip("cv2")
    rng = np.random.default_rng(2)
    image = (rng.random((8, 16, 3)) * 5).astype(np.float32)
    cv2.imwrite(str(tmp_path / "sky.hdr"), image[..., ::-1])
    sky = Environment.from_file(tmp_path / "sky.hdr", intensity=2.0)
    assert sky.image.shape == (8, 16, 3) and sky.intensity == 2.0
    # (RGBE: the three channels share the exponent of the largest)
    assert (np.abs(sky.image - image) <= image.max(-1, keepdims=True) * 2 / 256).all()
    np.save(tmp_path / "sky.npy", image)
    assert np.array_equal(Environment.from_file(tmp_path / "sky.npy").image, image)
    with pytest.raises(InputError, match="no such environment image"):
        Environment.from_file(tmp_path / "none.hdr")
    (tmp_path / "sky.png").write_bytes(b"")
    with pytest.raises(InputError, match=r"sky.png: an environment image is .hdr, .exr or"):
        Environment.from_file(tmp_path / "sky.png")
