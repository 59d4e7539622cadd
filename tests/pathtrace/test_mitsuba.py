"""The path tracer against Mitsuba 3 (a test extra: installed by the README's test command)
on the Cornell box: the image's mean and 4 x 4 block means, off the light."""

import numpy as np
import pytest

from glshade.pathtrace import TraceScene, trace
from glshade.radiosity.control import radiosity_control
from glshade.radiosity.cornell import CORNELL_CAMERA, cornell_scene

from ..conftest import require
from ..oracle import mitsuba_scene

pytestmark = [pytest.mark.gl, pytest.mark.once]


@pytest.fixture(scope="module")
def mitsubas(tmp_path_factory):
    """Mitsuba's Cornell box, 64 x 64 x 256 samples (rendered once for every variant)."""
    require("mitsuba", "Mitsuba 3 is part of the test extra")
    scene, _ = cornell_scene()
    return mitsuba_scene.render(TraceScene.from_scene(scene), CORNELL_CAMERA, 64, 256,
                                tmp_path_factory.mktemp("mitsuba"), seed=3)


@pytest.mark.parametrize("accel, sampler, coherent, control, adaptive", [
    ("auto", "pcg", False, False, False), ("bvh", "sobol", False, False, False),
    ("auto", "sobol", True, False, False), ("auto", "sobol", False, True, False),
    ("auto", "sobol", False, False, True)])
def test_the_cornell_box_agrees_with_mitsuba(gl_context, mitsubas, accel, sampler, coherent,
                                             control, adaptive):
    """The default tracer, the hierarchy with Sobol points, blocks of pixels sharing their
    numbers, the radiosity control variate, and adaptive sampling (a mean of 256)."""
    scene, camera = cornell_scene()
    values = radiosity_control(scene, context=gl_context) if control else None
    ours = trace(scene, camera, (64, 64), spp=256, seed=3, context=gl_context, progress=False,
                 accel=accel, sampler=sampler, coherent=coherent, control=values,
                 adaptive=adaptive)
    theirs = mitsubas
    # (pixels that see the light are left out: a pixel half on the light is E = 17 or 0 by
    # where its sample lands, and those few pixels would decide the means)
    lit = (ours.emitting == 0)[..., None]
    assert (theirs * lit).mean() == pytest.approx((ours.image * lit).mean(), rel=0.01)

    def blocks(a):
        return (a * lit).reshape(4, 16, 4, 16, 3).sum((1, 3)) / \
            np.maximum(lit.reshape(4, 16, 4, 16, 1).sum((1, 3)), 1)

    np.testing.assert_allclose(blocks(ours.image), blocks(theirs), rtol=0.05, atol=2e-3)


def test_a_sky_lighting_a_ball_on_a_floor_agrees_with_mitsuba(gl_context, tmp_path):
    """Light from a constant sky (glshade's Environment, Mitsuba's constant emitter) on a
    diffuse ball over a diffuse floor: next-event estimation of the sky, its MIS with the
    bounce, the ball's shadow and the light between the two -- the image's mean and 4 x 4
    block means."""
    require("mitsuba", "Mitsuba 3 is part of the test extra")
    from glshade import Environment, Material, Mesh, Scene
    from glshade.geometry import primitives

    scene = Scene(environment=Environment((0.6, 0.7, 0.9)))
    scene.add(Mesh([[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]], [[0, 1, 2, 3]]),
              Material(color=(0.8, 0.8, 0.7), kd=0.9, ks=0.0))
    scene.add(primitives.icosphere(2), Material(color=(0.9, 0.5, 0.2), kd=0.9, ks=0.0),
              translation=(0, 1.1, 0))
    camera = {"eye": (0.0, 2.5, 6.0), "target": (0.0, 0.8, 0.0), "up": (0.0, 1.0, 0.0),
              "fov_y": 40.0}
    ts = TraceScene.from_scene(scene)
    theirs = mitsuba_scene.render(ts, camera, 48, 256, tmp_path, seed=5)
    from glshade import Camera

    ours = trace(ts, Camera.look_at(camera["eye"], camera["target"], camera["up"],
                                     fov_y=camera["fov_y"]), (48, 48), spp=256, seed=5,
                 context=gl_context, progress=False)
    assert theirs.mean() == pytest.approx(ours.image.mean(), rel=0.01)

    def blocks(a):
        return a.reshape(4, 12, 4, 12, 3).mean((1, 3))

    np.testing.assert_allclose(blocks(ours.image), blocks(theirs), rtol=0.03, atol=2e-3)


def _separable_albedo(mu, alpha, k=192):
    """Mitsuba's ``roughconductor`` of reflectance 1 (``material`` none: its Fresnel term
    is 1): GGX with the separable Smith term G1(l) G1(v) -- its directional albedo at view
    cosines ``mu`` by the same quadrature as the glTF model's (Gauss-Legendre in cos theta,
    the trapezoid in phi)."""
    x, wx = np.polynomial.legendre.leggauss(k)
    ct, wt = 0.5 * (x + 1), 0.5 * wx
    phi = 2 * np.pi * np.arange(2 * k) / (2 * k)
    c, p = np.meshgrid(ct, phi, indexing="ij")
    s = np.sqrt(1 - c * c)
    light = np.stack([s * np.cos(p), s * np.sin(p), c], -1).reshape(-1, 3)
    weight = (wt[:, None] * np.full(2 * k, np.pi / k)).reshape(-1)
    a2 = alpha * alpha

    def g1(x):
        return 2 * x / (x + np.sqrt(a2 + (1 - a2) * x * x))

    out = []
    for m in mu:
        v = np.array([np.sqrt(1 - m * m), 0.0, m])
        h = light + v
        h /= np.linalg.norm(h, axis=1, keepdims=True)
        d = a2 / (np.pi * (h[:, 2] ** 2 * (a2 - 1) + 1) ** 2)
        f_cos = d * g1(light[:, 2]) * g1(m) / (4 * m)
        out.append((f_cos * weight).sum())
    return np.array(out)


@pytest.mark.parametrize("roughness", [0.3, 0.9])
def test_a_ggx_metal_ball_under_a_sky_agrees_with_mitsubas_roughconductor(gl_context,
                                                                          roughness):
    """A white metal ball (glTF: base colour 1, metallic 1; Schlick's Fresnel is then 1)
    under a constant sky against Mitsuba's analytic sphere of ``roughconductor``, GGX of
    alpha = roughness^2 and no Fresnel loss: the same lobe but for the Smith term (glTF's
    height-correlated, Mitsuba's separable). Each ball's mean over the pixels wholly on it,
    divided by its model's directional albedo integrated by quadrature at each of those
    pixels' views, is the sky's radiance: the two quotients agree within their errors
    (at roughness 0.9 the Smith terms differ by 3.5% over the ball; the quotients by 0.2%).
    (A dielectric maps to no Mitsuba BSDF exactly -- ``roughplastic`` scatters inside its
    coat -- so it meets the glTF model's quadrature alone: test_environment's furnace.)"""
    require("mitsuba", "Mitsuba 3 is part of the test extra")
    from glshade import Environment, PBRMaterial

    from .test_environment import CAMERA, EYE, SUB, H, W, ball_scene, ball_views, \
        directional_albedo

    sky, alpha = 0.8, roughness ** 2
    mus = np.linspace(1e-4, 1.0, 65)
    ours_table = directional_albedo(mus, np.ones(3), 1.0, roughness)[:, 0]
    theirs_table = _separable_albedo(mus, alpha)
    inside = np.ones((H, W), bool)
    ours_albedo, theirs_albedo = np.zeros((H, W)), np.zeros((H, W))
    for n, v in ball_views():
        mu = np.einsum("...k,...k", n, v)
        inside &= np.isfinite(mu) & (np.nan_to_num(mu) > 0.2)
        ours_albedo += np.interp(np.nan_to_num(mu), mus, ours_table) / SUB ** 2
        theirs_albedo += np.interp(np.nan_to_num(mu), mus, theirs_table) / SUB ** 2
    traced = trace(ball_scene(PBRMaterial(base_color=(1, 1, 1), metallic=1.0,
                                          roughness=roughness), Environment((sky,) * 3)),
                   CAMERA, (W, H), spp=128, seed=2, context=gl_context, progress=False)
    camera = {"eye": tuple(EYE), "target": (0, 0, 0), "up": (0, 1, 0), "fov_y": 45.0}
    bsdf = {"type": "roughconductor", "distribution": "ggx", "alpha": alpha,
            "material": "none"}
    # (four seeds: Mitsuba's error from their spread)
    theirs = [mitsuba_scene.render_ball(bsdf, sky, camera, W, 64, seed=s).mean(-1)[inside]
              for s in range(4)]
    ours_q = traced.image.mean(-1)[inside].sum() / ours_albedo[inside].sum()
    ours_se = np.sqrt((traced.se.mean(-1)[inside] ** 2).sum()) / ours_albedo[inside].sum()
    quotients = [t.sum() / theirs_albedo[inside].sum() for t in theirs]
    theirs_q = np.mean(quotients)
    theirs_se = np.std(quotients, ddof=1) / 2
    slack = 3e-3 * theirs_q  # (our ball's facets: a uv sphere of 96 x 192)
    assert abs(ours_q - theirs_q) <= 4 * np.hypot(ours_se, theirs_se) + slack, \
        (ours_q, theirs_q, ours_se, theirs_se)
    assert ours_q == pytest.approx(np.pi * sky, rel=0.01)
    # (the Smith terms differ, and the quadrature says by how much: the quotients need it)
    if roughness > 0.5:  # (3.5% at 0.9)
        assert abs(ours_albedo[inside].sum() / theirs_albedo[inside].sum() - 1) > 0.005
