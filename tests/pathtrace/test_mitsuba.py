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
