"""Degenerate meshes through the API's drawing entry points (hypothesis, derandomized in
CI): polygons whose corners are collinear or coincide, at any scale from 1e-30 to 1e17 and
any direction. The renderer draws nothing of them and says why (a RenderWarning, every
pixel background), the path tracer refuses them in one line -- where both once ended in a
numpy reduction over nothing."""

import numpy as np
import pytest

from tests.conftest import require

from glshade import Camera, Mesh, Renderer, Scene
from glshade.errors import RenderWarning, SceneError
from glshade.pathtrace import TraceScene

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402

pytestmark = pytest.mark.gl


@st.composite
def degenerate(draw):
    """Faces of 3-5 corners on one line (or at one point), ``exponent`` its scale."""
    exponent = draw(st.integers(-30, 17))  # (Scene.add refuses past 1e18: its own rule)
    direction = np.array(draw(st.tuples(*[st.floats(-1, 1)] * 3)))
    if not np.linalg.norm(direction) > 1e-3:
        direction = np.array([1.0, 0.0, 0.0])
    point = draw(st.booleans())
    n = draw(st.integers(3, 8))
    along = np.zeros(n) if point else np.sort(np.array(draw(
        st.lists(st.floats(-1, 1), min_size=n, max_size=n))))
    vertices = (np.asarray(along)[:, None] * direction + 0.25) * 10.0 ** exponent
    faces = [list(range(k, k + 3)) for k in range(n - 2)]
    return Mesh(vertices, faces), exponent


@settings(max_examples=25, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=degenerate())
def test_a_degenerate_mesh_draws_nothing_and_says_why(gl_context, case):
    mesh, exponent = case
    scene = Scene()
    scene.add(mesh)
    scale = 10.0 ** exponent
    camera = Camera.look_at(np.array([0.25, 0.25, 3.0]) * scale, np.full(3, 0.25 * scale))
    with Renderer(24, 24, samples=0, context=gl_context) as r, \
            pytest.warns(RenderWarning, match="blank"):
        frame = r.render_frame(scene, camera, "flat")
    assert (frame.face_id == -1).all()
    with pytest.raises(SceneError, match="zero area"):
        TraceScene.from_scene(scene, camera=camera)
