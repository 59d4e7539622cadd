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
