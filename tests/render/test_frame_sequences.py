"""A frame is a function of (scene, camera, options) alone: any sequence of frames drawn on
one renderer gives, frame by frame, the bytes a fresh renderer gives (hypothesis,
derandomized in CI). What this caught: the CSG pass drew its screen polygon with every
vertex its buffer had room for, so corners left from an earlier frame's polygon drew
pixels twice, from slightly different interpolated rays."""

import numpy as np
import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import given, settings, strategies as st  # noqa: E402

import glshade  # noqa: E402
from glshade.geometry import primitives  # noqa: E402
from glshade.solids import Box, Cylinder, Sphere, Torus  # noqa: E402

pytestmark = [pytest.mark.gl, pytest.mark.once,
              pytest.mark.filterwarnings("ignore::glshade.RenderWarning")]

SIZE = 48


def _scenes():
    part = glshade.Scene()
    part.add((Box(2) - Sphere(1.2)) | Torus(1.5, 0.3))
    mixed = glshade.Scene()
    mixed.add(primitives.icosphere(2), transform=np.diag([0.6, 0.6, 0.6, 1.0]))
    turn = glshade.quaternion.from_axis_angle((1, 0, 0), np.pi / 2)
    mixed.add(Box(1.5) - Cylinder(0.4, 3).rotated(turn))
    big = glshade.Scene()  # (a tree past the one-step cast's 14 leaves: the walk)
    tree = Box(3.0)
    for k in range(15):
        tree = tree - Sphere(0.25).translated((-1.2 + 0.17 * k, 0.5 * np.sin(k), 1.5))
    big.add(tree)
    return [part, mixed, big]


SCENES = _scenes()
cameras = st.builds(
    lambda r, az, el, tx: glshade.Camera.look_at(
        (r * np.cos(el) * np.sin(az), r * np.sin(el), r * np.cos(el) * np.cos(az)),
        (tx, 0.1, -tx), near=0.01 if r < 2 else None),
    r=st.floats(0.3, 7.0), az=st.floats(0, 2 * np.pi), el=st.floats(-1.2, 1.2),
    tx=st.floats(-0.5, 0.5))
frames = st.tuples(st.integers(0, len(SCENES) - 1), cameras,
                   st.sampled_from(["flat", "gouraud", "phong", "normals", "depth"]))


@settings(max_examples=10)
@given(sequence=st.lists(frames, min_size=2, max_size=4))
def test_every_frame_is_the_frame_a_fresh_renderer_draws(gl_context, sequence):
    with glshade.Renderer(SIZE, SIZE, samples=0, context=gl_context) as shared:
        drawn = [shared.render_frame(SCENES[s], cam, mode) for s, cam, mode in sequence]
    for (s, cam, mode), got in zip(sequence, drawn):
        with glshade.Renderer(SIZE, SIZE, samples=0, context=gl_context) as fresh:
            want = fresh.render_frame(SCENES[s], cam, mode)
        assert np.array_equal(got.color, want.color), (s, mode)
        assert np.array_equal(got.depth, want.depth, equal_nan=True), (s, mode)
        assert np.array_equal(got.face_id, want.face_id), (s, mode)
