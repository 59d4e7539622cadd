"""The path tracer's two programs -- a fragment program a pass, or a compute kernel (what a
GPU with few graphics units wants) -- run the same pass (trace_integrator.glsl) on the same
sample stream: the same pictures to rounding on the Cornell box, a CSG solid's scene and a
patch surface's, and the compute kernel meets the furnace's closed form on its own. Two
tracers used in turn in one process each keep their own context."""

import numpy as np
import pytest

from glshade import patches
from glshade.geometry import primitives
from glshade.pathtrace import PathTracer, trace
from glshade.radiosity import cornell_scene
from glshade.scene import Camera, Material, Scene
from glshade.solids import Box, Sphere

pytestmark = pytest.mark.gl


def _lamp(scene):
    scene.add(primitives.plane(1.0), Material(color=(1, 1, 1), kd=0.0, ka=0.0, ks=0.0,
                                              emission=(20.0, 20.0, 20.0)),
              rotation=(0.7071068, 0.0, 0.0, 0.7071068), translation=(0.0, 2.5, 0.0))


def _scene(name):
    if name == "cornell":
        return cornell_scene()
    scene = Scene(ambient=(0, 0, 0))
    scene.add(primitives.plane(8.0), Material(color=(0.7, 0.7, 0.7), ks=0.0),
              rotation=(-0.7071068, 0.0, 0.0, 0.7071068), translation=(0.0, -1.0, 0.0))
    if name == "csg":
        scene.add(Box((1.6, 1.6, 1.6)) - Sphere(1.0), Material(color=(0.8, 0.4, 0.3),
                                                                 ks=0.2, shininess=20))
    else:
        scene.add(patches.named("teapot"), Material(color=(0.3, 0.6, 0.8), ks=0.3),
                  scale=0.5, level=4)
    _lamp(scene)
    return scene, Camera.look_at((0.0, 1.5, 5.0), (0.0, 0.0, 0.0), fov_y=45)


@pytest.mark.parametrize("name", ["cornell", "csg", "patches"])
def test_the_compute_kernel_traces_what_the_fragment_program_traces(gl_context, name):
    scene, camera = _scene(name)
    images = {kernel: trace(scene, camera, (40, 32), spp=8, seed=3, kernel=kernel,
                            context=gl_context, progress=False).image
              for kernel in ("fragment", "compute")}
    a, b = images["fragment"], images["compute"]
    assert a.mean() > 0.01   # (the scene is lit)
    assert (np.abs(a - b) <= 1e-5 * np.maximum(np.abs(a), 1e-3)).all(), np.abs(a - b).max()


def test_the_compute_kernel_meets_the_furnace(gl_context):
    """Inside a closed room of emission 1 and reflectance 0.5 every pixel is 1 / (1 - 0.5)."""
    scene = Scene(ambient=(0, 0, 0))
    scene.add(primitives.cube().flipped(), Material(color=(1.0, 1.0, 1.0), kd=0.5, ka=0.0,
                                                    ks=0.0, emission=(1.0, 1.0, 1.0)))
    camera = Camera.look_at((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), fov_y=60, near=0.01, far=10.0)
    r = trace(scene, camera, (16, 16), spp=256, kernel="compute", context=gl_context,
              progress=False)
    pixels = r.image.mean(-1).ravel()
    bar = pixels.std(ddof=1) / np.sqrt(pixels.size)
    assert abs(pixels.mean() - 2.0) < 4 * bar and bar < 0.01, (pixels.mean(), bar)


def test_auto_measures_once_and_keeps_its_choice(gl_context):
    """``kernel="auto"`` times both on first use and keeps the faster for this GL: a second
    tracer takes it without measuring; either way the picture is the same."""
    scene, camera = _scene("cornell")
    first = PathTracer(scene, (24, 24), kernel="auto", context=gl_context)
    first.add(camera, 4)
    chosen = first.gpu.kernel
    assert chosen.value in ("fragment", "compute")
    second = PathTracer(scene, (24, 24), kernel="auto", context=gl_context)
    assert second.gpu.kernel is chosen   # (kept: no measurement)
    second.add(camera, 4)
    np.testing.assert_array_equal(first.result().image, second.result().image)


def test_two_tracers_used_in_turn_keep_their_own_contexts():
    """Each tracer made its own context; adding to one after the other was used must draw
    in its own (GL calls go to the current context): the same pictures as each alone."""
    scene, camera = _scene("cornell")
    alone = trace(scene, camera, (24, 24), spp=8, progress=False).image
    a, b = PathTracer(scene, (24, 24)), PathTracer(scene, (24, 24))
    try:
        for _ in range(4):
            a.add(camera, 2)
            b.add(camera, 2)
        np.testing.assert_array_equal(a.result().image, alone)
        np.testing.assert_array_equal(b.result().image, alone)
    finally:
        a.close()
        b.close()


def test_a_tracer_on_a_given_context_draws_there_whatever_was_current(gl_context):
    """A tracer made on the shared context just after another context was made (and so
    became current) makes its targets and programs in its own, and finishes: its picture is
    the one traced before."""
    from glshade.render.context import create_context

    scene, camera = _scene("cornell")
    before = trace(scene, camera, (16, 16), spp=4, context=gl_context, progress=False).image
    other = create_context("egl")
    try:
        after = trace(scene, camera, (16, 16), spp=4, context=gl_context,
                      progress=False).image
    finally:
        other.release()
    np.testing.assert_array_equal(after, before)
