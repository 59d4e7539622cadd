"""render_many draws frames ahead into targets of its own and reads them back as groups:
swept with hypothesis over image sizes (down to 1x1), MSAA, outputs, modes, transparency
(a float colour target), run lengths across the group size and eyes among and inside the
objects -- every frame the bytes render_frame gives for its camera, and the renderer's GL
objects as they were after the run."""

import warnings

import numpy as np

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402

import glshade  # noqa: E402
from glshade import Camera, Material, Outputs, Scene  # noqa: E402
from glshade.geometry import primitives as P  # noqa: E402

NAMES = ("color", "depth", "normal", "face_id", "instance", "semantic", "visibility")
OUTPUTS = [Outputs.DEPTH, Outputs.NORMAL, Outputs.FACE_ID, Outputs.INSTANCE,
           Outputs.SEMANTIC]


def _scene(glass: bool) -> Scene:
    s = Scene(ambient=(0.2, 0.2, 0.25))
    s.add(P.icosphere(2), Material(color=(0.9, 0.4, 0.2)), label="ball")
    s.add(P.cube(), Material(color=(0.2, 0.6, 0.9)), translation=(1.5, 0.2, -0.5),
          scale=0.7, label="box")
    s.add(P.torus(0.8, 0.12, 24, 12), Material(color=(0.3, 0.8, 0.3),
                                                opacity=0.45 if glass else 1.0),
          translation=(-1.2, -0.3, 0.4), label="ring")
    s.add_light(glshade.PointLight((3.0, 4.0, 5.0)))
    return s


@settings(max_examples=25, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(size=st.tuples(st.integers(1, 48), st.integers(1, 40)),
       samples=st.sampled_from([0, 2, 4]),
       outputs=st.lists(st.sampled_from(OUTPUTS), max_size=3),
       mode=st.sampled_from(["phong", "flat", "gouraud", "normals"]),
       glass=st.booleans(),
       eyes=st.lists(st.tuples(st.floats(-4, 4), st.floats(-3, 3), st.floats(-4, 4)),
                     max_size=19))
def test_every_frame_is_render_frame_s(make_renderer, size, samples, outputs, mode, glass,
                                       eyes):
    scene = _scene(glass)
    want = Outputs.COLOR
    for o in outputs:
        want |= o
    cameras = []
    for k, eye in enumerate(eyes):
        eye = np.asarray(eye, float)
        target = np.array([0.1 * k, 0.0, 0.0]) if np.linalg.norm(eye) > 0.2 else \
            eye + [0.0, 0.0, -1.0]  # (the eye inside the ball: it looks out)
        if np.linalg.norm(target - eye) < 1e-3:
            target = eye + [0.0, 0.0, -1.0]
        up = (0, 0, 1) if abs(np.dot((target - eye) / np.linalg.norm(target - eye),
                                     (0, 1, 0))) > 0.99 else (0, 1, 0)
        cameras.append(Camera.look_at(eye, target, up=up, fov_y=55.0))
    r = make_renderer(*size, samples)
    with warnings.catch_warnings():  # (an eye looking away from everything: a blank view
        warnings.simplefilter("ignore")  # warns, either way alike)
        r.render_frame(scene, Camera.look_at((0, 0, 6), (0, 0, 0)), mode, outputs=want)
        children = len(r.context._children)
        many = list(r.render_many(scene, cameras, mode, outputs=want))
        one = [r.render_frame(scene, c, mode, outputs=want) for c in cameras]
    assert len(many) == len(cameras)
    for k, (a, b) in enumerate(zip(many, one)):
        for name in NAMES:
            x, y = getattr(a, name), getattr(b, name)
            assert (x is None) == (y is None), (k, name)
            if x is not None:
                assert x.dtype == y.dtype and np.array_equal(x, y, equal_nan=True), \
                    (k, name, int((x != y).sum()))
        assert a.camera == b.camera
    assert len(r.context._children) == children
