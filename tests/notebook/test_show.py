"""Notebook display: every displayable object has a short repr and an HTML view whose
inline picture decodes to an image of the stated size; show() refuses what it cannot show.
(The pictures are glshade's own renders; here they are checked to be real images of the
object -- not blank, the right size -- not compared to themselves.)"""

import base64
import io
import re
import sys
import types

import numpy as np
import pytest
from PIL import Image

import glshade
from glshade import Camera, CameraPath, Keyframe, Scene
from glshade.notebook.display import THUMBNAIL, buffers_image, png_bytes, show
from glshade.geometry import primitives
from glshade.octree import Octree
from glshade.solids import Box, Sphere

SHORT = 160  # characters a repr may take


def pictures(text: str) -> list[np.ndarray]:
    """The inline PNGs of an HTML view, decoded, each checked against its stated size."""
    out = []
    for data, w, h in re.findall(r'src="data:image/png;base64,([^"]+)" width="(\d+)" '
                                 r'height="(\d+)"', text):
        image = np.asarray(Image.open(io.BytesIO(base64.b64decode(data))))
        assert image.shape[1] == int(w) and image.shape[0] == int(h)
        out.append(image)
    return out


def objects(renderer):
    cube = primitives.cube()
    scene = Scene()
    scene.add(cube)
    frame = renderer.render_frame(scene, Camera.look_at((3, 2, 4), (0, 0, 0)))
    from glshade.hidden import zbuffer

    hidden = zbuffer(scene, Camera.look_at((3, 2, 4), (0, 0, 0)), (64, 48))
    path = CameraPath([Keyframe.look_at(0, (4, 1, 0), (0, 0, 0)),
                       Keyframe.look_at(2, (0, 1, 4), (0, 0, 0)),
                       Keyframe.look_at(3, (-4, 2, 0), (0, 0, 0))])
    from glshade.radiosity import cornell_scene, solve

    box, box_camera = cornell_scene()
    solution = solve(box, patch_size=250, until=0.2, context=renderer.context)
    from glshade import patches
    from glshade.pathtrace import trace

    traced = trace(box, box_camera, size=(32, 24), spp=4, context=renderer.context)

    return {"mesh": cube, "scene": scene, "solid": Box(2) - Sphere(1.2),
            "patches": patches.named("teapot"),
            "octree": Octree.from_solid(Box(2) - Sphere(1.2), 4), "frame": frame,
            "hidden": hidden, "path": path, "solution": solution, "traced": traced}


def test_every_object_has_a_short_repr_and_a_picture(make_renderer):
    r = make_renderer(64, 48)
    for name, obj in objects(r).items():
        text = repr(obj)
        assert len(text) <= SHORT and "array(" not in text, (name, text)
        view = obj._repr_html_()
        images = pictures(view)
        assert len(images) == 1, name
        image = images[0]
        # a real picture: more than one colour
        flat = image.reshape(-1, image.shape[-1] if image.ndim == 3 else 1)
        assert len(np.unique(flat, axis=0)) > 2, name


def test_a_closed_rooms_thumbnail_is_chosen_to_show_it(gl_context):
    """A radiosity solution of the Cornell box is seen from a view that shows what was
    solved: its light (white pixels) and both coloured walls it lights (pixels twice as red
    as green, and twice as green as red) -- the iso view sees the room's outside, dark, and
    the brightest view (what was chosen before) looked down past the light."""
    from glshade.radiosity import cornell_scene, solve

    box, _ = cornell_scene()
    solution = solve(box, patch_size=250, until=0.2, context=gl_context)
    (image,) = pictures(solution._repr_html_())
    rgb = image[..., :3].astype(int)
    r, g = rgb[..., 0], rgb[..., 1]
    assert (rgb.min(-1) >= 240).sum() >= 20  # the light
    assert ((r > 2 * g) & (r > 20)).sum() >= 500 and ((g > 2 * r) & (g > 20)).sum() >= 500


def test_thumbnails_have_the_thumbnail_size_and_show_the_object(gl_context):
    view = primitives.cube()._repr_html_()
    (image,) = pictures(view)
    assert image.shape[:2] == (THUMBNAIL[1], THUMBNAIL[0])
    # the cube covers the middle of the picture, the corners are background
    h, w = image.shape[:2]
    assert image[h // 2, w // 2, :3].max() > 0 and image[0, 0, :3].max() == 0


def test_a_frames_buffers_side_by_side(make_renderer):
    scene = Scene()
    scene.add(primitives.uv_sphere(16, 32))
    frame = make_renderer(40, 30).render_frame(scene, Camera.look_at((0, 0, 4), (0, 0, 0)))
    tiles = buffers_image(frame)
    assert tiles.shape == (30, 4 * 40, 3)
    # the normal tile at the sphere's centre faces the eye: (0.5, 0.5, 1) * 255
    assert np.abs(tiles[15, 2 * 40 + 20].astype(int) - [128, 128, 255]).max() <= 12
    # the depth tile: nearest is brightest
    depth_tile = tiles[:, 40:80, 0]
    assert depth_tile[15, 20] == depth_tile.max()


def test_show_refuses_what_it_cannot_show(tmp_path):
    with pytest.raises(ValueError, match=r"\(H, W\)"):
        show(np.zeros((2, 3, 5)))
    with pytest.raises(ValueError, match="no file"):
        show(tmp_path / "missing.gif")
    with pytest.raises(ValueError, match="cannot show"):
        show(object())
    show(np.zeros((4, 4, 3)))  # (outside IPython: nothing shown, nothing raised)


def test_png_bytes_round_trip():
    image = (np.arange(48, dtype=np.uint8).reshape(4, 4, 3) * 5)
    back = np.asarray(Image.open(io.BytesIO(png_bytes(image))))
    assert (back == image).all()


def test_without_the_display_module_the_facts_show_alone():
    """In a script (no IPython, glshade.notebook.display never imported) a repr draws nothing: the
    lower layers cannot reach the renderer except through the hook display installs."""
    import subprocess
    import sys

    code = ("import sys; from glshade.geometry import primitives; "
            "h = primitives.cube()._repr_html_(); "
            "print('<img' in h, 'glshade.notebook.display' in sys.modules, "
            "'moderngl' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.split() == ["False", "False", "False"], out.stderr


def test_nothing_imports_ipython():
    import subprocess
    import sys

    code = ("import sys, glshade, glshade.notebook.display; "
            "glshade.notebook.display.show(__import__('numpy').zeros((2, 2, 3))); "
            "print('IPython' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.strip() == "False", out.stderr


assert glshade  # (the package, as users import it)


@pytest.mark.parametrize("side", [96, 24], ids=["tiles", "tiles narrower than the key"])
def test_a_comparison_shows_its_grid_and_has_a_short_repr(side, make_renderer):
    import glshade

    scene = Scene()
    scene.add(primitives.icosphere(1))
    result = glshade.compare(scene, Camera.look_at((0, 0, 3), (0, 0, 0)), size=(side, side),
                             renderer=make_renderer(side, side))
    text = repr(result)
    assert len(text) <= SHORT and "array(" not in text and "analytic" in text, text
    image = np.asarray(Image.open(io.BytesIO(result._repr_png_())))
    assert image.shape[:2] == result.image.shape[:2] and len(np.unique(image)) > 2
    view = result._repr_html_()
    (shown,) = pictures(view)
    assert shown.shape[:2] == result.image.shape[:2] and "phong: mean" in view


def _captured_display(monkeypatch) -> list:
    """A stand-in for a running IPython's display module: what show() displays, as HTML."""
    shown: list = []
    fake = types.ModuleType("IPython")
    fake.display = types.SimpleNamespace(HTML=lambda text: text, display=shown.append)
    monkeypatch.setitem(sys.modules, "IPython", fake)
    return shown


def _payload(html: str, tag: str) -> bytes:
    found = re.search(rf'<{tag}[^>]* src="data:[a-z]+/([a-z0-9]+);base64,([^"]+)"', html)
    assert found, html[:200]
    return base64.b64decode(found.group(2))


@pytest.mark.parametrize("suffix", [".gif", ".png", ".mp4"])
def test_show_plays_an_animation_inline_with_every_frame(suffix, tmp_path, monkeypatch):
    """An animation file shows inline as the animated image or the video itself: the
    payload decodes to the frames written (counted by Pillow / imageio, not glshade)."""
    from glshade.animate.writers import write_animation

    frames = [np.full((24, 32, 3), 40 * k, np.uint8) for k in range(5)]
    path = tmp_path / f"clip{suffix}"
    assert write_animation(frames, path, fps=10) == 5
    shown = _captured_display(monkeypatch)
    show(path)
    assert len(shown) == 1
    if suffix == ".mp4":
        import imageio.v3 as iio

        data = _payload(shown[0], "video")
        decoded = iio.imread(data, extension=".mp4", index=None)
        assert decoded.shape[0] == 5 and decoded.shape[1:3] == (24, 32)
        assert decoded[-1].mean() > decoded[0].mean() + 100  # (the frames in order)
    else:
        image = Image.open(io.BytesIO(_payload(shown[0], "img")))
        assert getattr(image, "n_frames", 1) == 5 and image.size == (32, 24)


def test_show_displays_an_array_and_a_frames_buffers(make_renderer, monkeypatch):
    shown = _captured_display(monkeypatch)
    show(np.linspace(0, 1, 12 * 16).reshape(12, 16))  # (floats 0..1: grey levels)
    grey = np.asarray(Image.open(io.BytesIO(_payload(shown[0], "img"))))
    assert grey.shape[:2] == (12, 16) and grey[0, 0] == 0 and grey[-1, -1] == 255
    scene = Scene()
    scene.add(primitives.icosphere(2))
    frame = make_renderer(40, 30).render_frame(scene, Camera.look_at((0, 0, 4), (0, 0, 0)))
    show(frame)
    tiles = Image.open(io.BytesIO(_payload(shown[1], "img")))
    assert tiles.size == buffers_image(frame).shape[1::-1]
