"""The notebook viewer's kernel side, without a browser: gestures as the browser sends them
(from another thread, as a kernel delivers widget messages) change the view as the window's
controls do, and every frame is glshade's own render of the view it reports."""

import io
import threading

import numpy as np
import pytest
from PIL import Image

from glshade import Camera, Scene
from glshade.geometry import primitives
from glshade.notebook import camera_from_view, view, view_of
from tests.conftest import BACKEND

pytestmark = pytest.mark.gl
SIZE = (96, 72)


@pytest.fixture
def widget():
    scene = Scene()
    scene.add(primitives.torus())
    w = view(scene, size=SIZE, backend=BACKEND)
    yield w
    w.close()


def send(w, **content):
    """A message from the browser, delivered on a thread that is not the one that made the
    widget (as a kernel does)."""
    errors = []

    def deliver():
        try:
            w._on_message(w, content, [])
        except Exception as exc:  # (re-raised in the test's thread)
            errors.append(exc)

    t = threading.Thread(target=deliver)
    t.start()
    t.join()
    if errors:
        raise errors[0]


def shown(w) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(w.png)).convert("RGB"))


def expected(w, mode, gl_renderer) -> np.ndarray:
    return gl_renderer.render(w.scene, camera_from_view(w.view), mode)[..., :3]


def test_a_view_round_trips():
    camera = Camera.look_at((1, 2, 3), (0, 0, 0), fov_y=30, projection="orthographic",
                            height=3.0)
    again = camera_from_view(view_of(camera))
    assert np.allclose(again.view_matrix(), camera.view_matrix())
    assert (again.projection, again.height, again.fov_y) == (camera.projection, 3.0, 30.0)


def test_gestures_change_the_view_and_every_frame_is_glshades_render(widget, make_renderer):
    r = make_renderer(*SIZE, samples=4)
    first = widget.revision
    assert (shown(widget) == expected(widget, "phong", r)).all()
    start = dict(widget.view)
    send(widget, event="down", x=30, y=30, button="left", shift=False)
    send(widget, event="move", x=60, y=40)
    send(widget, event="up")
    assert widget.revision == first + 3  # (every gesture answered by a frame)
    assert not np.allclose(widget.view["orientation"], start["orientation"])
    assert (shown(widget) == expected(widget, "phong", r)).all()
    distance = np.linalg.norm(widget.view["position"])
    send(widget, event="wheel", dy=1)
    assert np.linalg.norm(widget.view["position"]) < distance  # dollied in
    send(widget, event="key", key="2")
    assert widget.mode == "gouraud" and (shown(widget) == expected(widget, "gouraud", r)).all()
    send(widget, event="compare", mode="normals")
    half = SIZE[0] // 2
    image = shown(widget)
    assert (image[:, half:] == expected(widget, "normals", r)[:, half:]).all()
    assert (image[:, :half] == expected(widget, "gouraud", r)[:, :half]).all()
    send(widget, event="key", key="r")
    assert np.allclose(widget.view["position"], start["position"])


def test_a_mode_that_does_not_exist_is_said_in_the_status_line(widget):
    before = widget.mode
    send(widget, event="mode", mode="toon")  # (no exception: a kernel would only log it)
    assert widget.status.startswith("error: ") and "toon" in widget.status
    assert widget.mode == before


def test_a_gltf_files_materials_lights_and_camera_in_the_widget(make_renderer):
    """The widget on a glTF file as read whole (PBR maps, the file's spot light, its
    camera): every frame is glshade's render of the view, in each scheme, and the gold
    ball is lit (an unlit PBR scene would be the ambient term alone)."""
    from glshade import examples, load_gltf

    asset = load_gltf(examples.path("spotlit.glb"))
    w = view(asset.scene(), asset.cameras[0].camera, size=SIZE, backend=BACKEND)
    try:
        r = make_renderer(*SIZE, samples=4)
        assert np.allclose(w.view["position"], asset.cameras[0].camera.position)
        for key, mode in (("1", "flat"), ("2", "gouraud"), ("3", "phong")):
            send(w, event="key", key=key)
            image = shown(w)
            assert (image == expected(w, mode, r)).all(), mode
            assert image[..., 0].max() > 200, mode  # (the spot's highlight on the gold)
    finally:
        w.close()


def _until(w, text, timeout=120):
    import time

    deadline = time.time() + timeout
    while text not in w.status:
        assert time.time() < deadline, w.status
        time.sleep(0.05)


def test_t_path_traces_gltfs_materials_in_the_widget_and_rests_at_its_samples():
    """Key t in the widget: the picture refines a sample a pixel a frame up to
    trace_samples, then rests -- what pathtrace.trace gives the same view for as many
    samples (glTF's gold ball, its spot light and a sky), at the exposure of the view's
    first sample; a gesture starts it over from the new view; a mode key ends it."""
    from glshade import Environment, examples, load_gltf, pathtrace

    scene = load_gltf(examples.path("spotlit.glb")).scene()
    scene.environment = Environment((0.2, 0.25, 0.3))
    camera = Camera.look_at((0.0, 1.5, 4.0), (0.0, 0.3, 0.0), fov_y=40.0)
    w = view(scene, camera, size=SIZE, backend=BACKEND, trace_samples=6)
    try:
        send(w, event="key", key="t")
        _until(w, "path tracing, 6 samples a pixel (done")
        smooth = pathtrace.TraceScene.from_scene(scene, smooth=True)
        first = pathtrace.trace(smooth, camera, SIZE, spp=1, progress=False, backend=BACKEND)
        ref = pathtrace.trace(smooth, camera, SIZE, spp=6, samples_per_pass=1, progress=False,
                              backend=BACKEND)
        want = ref.rgba8(first.auto_exposure())[..., :3].astype(int)
        got = shown(w).astype(int)
        assert np.abs(got - want).max() <= 1
        assert (got[..., 0] > got[..., 2] + 30).mean() > 0.02  # (the gold is there)
        send(w, event="wheel", dy=1.0)
        assert w.status.startswith("path tracing") and camera_from_view(w.view) != camera
        _until(w, "6 samples a pixel (done")  # (the new view, refined again)
        send(w, event="key", key="3")
        assert not w.status.startswith("path tracing") and w.tracer is None
    finally:
        w.close()


def test_t_on_a_scene_the_tracer_cannot_take_says_why_in_the_status_line():
    """kd + ks past 1 (light from nothing): the tracer refuses it, and the widget says so
    in its status line and keeps drawing the mode."""
    from glshade import Material
    from glshade.geometry import primitives as P

    scene = Scene()
    scene.add(P.cube(), Material(kd=0.9, ks=0.5, color=(1, 1, 1)), name="cube")
    w = view(scene, size=SIZE, backend=BACKEND)
    try:
        send(w, event="key", key="t")
        assert w.tracer is None and w.status.startswith("cannot path-trace this scene")
        assert "rho_d + k_s" in w.status
    finally:
        w.close()
    from glshade.errors import OptionError

    with pytest.raises(OptionError, match="trace_samples must be a whole number >= 1, got 0"):
        view(scene, size=SIZE, backend=BACKEND, trace_samples=0)
