"""A CSG solid in the path tracer is the raster pass's solid: random trees (spheres, boxes,
cylinders, tori, their unions, intersections and differences, bores included, under random
rotations) traced with one ray through each pixel centre (Camera.rays) hit exactly the
pixels the raster pass covers, outside the silhouette band (hypothesis, derandomized in
CI). What this caught: a solid alone gave the tracer an empty hierarchy whose root box held
every ray, so its walk ran until the driver stopped the shader and the solid's own cast
was cut short: most pixels missed, bores black."""

import numpy as np
import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import given, settings, strategies as st  # noqa: E402

import glshade  # noqa: E402
from glshade.pathtrace import TraceScene  # noqa: E402
from glshade.render.passes.pathtrace import GpuPathTracer  # noqa: E402
from glshade.solids import Box, Cylinder, Sphere, Torus  # noqa: E402

pytestmark = [pytest.mark.gl, pytest.mark.once]

N = 40
CAMERA = glshade.Camera.look_at((2.6, 1.9, 3.4), (0, 0, 0), fov_y=45)

unit = st.floats(-1.0, 1.0)
leaves = st.one_of(
    st.floats(0.4, 1.2).map(Sphere),
    st.tuples(st.floats(0.4, 1.5), st.floats(0.4, 1.5), st.floats(0.4, 1.5)).map(Box),
    st.tuples(st.floats(0.2, 0.8), st.floats(0.6, 2.5)).map(lambda a: Cylinder(*a)),
    st.tuples(st.floats(0.5, 1.0), st.floats(0.1, 0.45)).map(lambda a: Torus(*a)),
)
placed = st.tuples(leaves, st.tuples(unit, unit, unit, unit), st.tuples(unit, unit, unit)).map(
    lambda a: a[0].rotated(np.asarray(a[1]) + [0, 0, 0, 1.5]).translated(np.asarray(a[2]) * 0.4))
trees = st.recursive(placed, lambda kids: st.tuples(kids, kids, st.sampled_from("|&-")).map(
    lambda a: a[0] | a[1] if a[2] == "|" else a[0] & a[1] if a[2] == "&" else a[0] - a[1]),
    max_leaves=6)


@settings(max_examples=12)
@given(solid=trees)
@pytest.mark.filterwarnings("ignore::glshade.RenderWarning")  # (trees that come out empty)
def test_the_tracer_hits_the_pixels_the_raster_pass_covers(gl_context, solid):
    scene = glshade.Scene(ambient=(0, 0, 0))
    scene.add(solid, glshade.Material(color=(1, 1, 1), kd=0.5, ks=0.0))
    scene.add_light(glshade.DirectionalLight(direction=(-0.3, -1.0, -0.5)))
    with glshade.Renderer(N, N, samples=0, context=gl_context) as renderer:
        covered = renderer.render_frame(scene, CAMERA, "depth").face_id >= 0
    o, d = CAMERA.rays((N, N))
    rays = np.stack([o, d], 2)[::-1]  # (the tracer's rows run bottom-up)
    with GpuPathTracer(gl_context, TraceScene.from_scene(scene), N, N, rays=rays,
                       max_depth=1) as tracer:
        tracer.run(None, 1)
        hits = tracer.read()[2][..., 0] > 0
    pad = np.pad(covered, 1, mode="edge")
    band = np.zeros_like(covered)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            band |= pad[1 + dy:1 + dy + N, 1 + dx:1 + dx + N] != covered
    wrong = (hits != covered) & ~band
    assert not wrong.any(), (int(wrong.sum()), int(covered.sum()), np.argwhere(wrong)[:5])
