"""Notebook display: glshade's objects show themselves as a small picture and a few facts
(this module renders the pictures; the HTML and colour maps are in ``glshade.display``).

Why: a course runs in notebooks, where a render printed as a numpy array, or a radiosity
solution as 126,661 characters, teaches nothing. Each displayable object has a short
``repr`` and a ``_repr_html_`` (a thumbnail rendered headless by glshade itself, and its
facts); :func:`show` displays an image array, a :class:`~glshade.Frame`'s buffers side by
side (colour, depth, normals, polygon ids in readable colour maps) or an animation file.
IPython is imported only when it is already loaded (inside a notebook or a shell); where no
GL context can be made, the facts are shown without the picture -- a repr never raises.
"""

from __future__ import annotations

import base64
import sys
from pathlib import Path

import numpy as np

from .. import display as _display
from ..display import THUMBNAIL, buffers_image, png_bytes

__all__ = ["show", "thumbnail", "telling_view", "png_bytes", "buffers_image", "THUMBNAIL"]


def thumbnail(scene, camera=None, size: tuple[int, int] = THUMBNAIL, mode: str = "phong",
              choose: bool = False, polygons=None):
    """A ``(H, W, 4)`` uint8 render of ``scene`` (a Scene, or a Mesh or solid put in one;
    framed from the iso view unless a camera is given, or, ``choose``, from the view that
    shows most: see :func:`telling_view`), or None where no GL context can be made or there
    is nothing to draw; ``polygons``: :func:`telling_view`'s.

    Parameters
    ----------
    scene : Scene, Mesh or Solid
        What to show.
    camera : Camera or None
        From where (None: framed from the iso view).
    size : (int, int)
        Width and height.
    mode : str
        The shading mode.
    choose : bool
        Choose the most telling of several views.
    polygons : ndarray or None
        Each display polygon's role, for judging views (a radiosity solution's).
    """
    import warnings

    from ..errors import EnvironmentFailure
    from ..scene import Scene
    from ..scene.camera import Camera

    if not isinstance(scene, Scene):
        alone = Scene()
        alone.add(scene)
        scene = alone

    bounds = scene.bounds
    if bounds is None:
        return None
    try:
        from ..render.renderer import Renderer

        with warnings.catch_warnings(), Renderer(*size, samples=0) as r:
            warnings.simplefilter("ignore")
            if camera is None and choose:
                camera = telling_view(r, scene, bounds, size[0] / size[1], mode, polygons)
            cam = camera or Camera.named("iso", bounds, aspect=size[0] / size[1])
            return r.render(scene, cam, mode)
    except EnvironmentFailure:
        return None


def telling_view(renderer, scene, bounds, aspect: float, mode: str, polygons=None):
    """The camera whose picture tells most of ``scene``, among the iso view, the six axis
    views from outside and six wide views from inside, near each wall, across the middle (a
    closed room is dark from every outside view).

    A view is judged by its small render's polygon ids and colours, in order: whether it
    shows an emitter (a radiosity solution's picture shows what was solved: the light and
    the walls it lights), how many of the scene's models it shows, then how bright it is.

    Parameters
    ----------
    renderer
        The Renderer whose context the small renders share.
    scene
        What is shown.
    bounds
        ``(2, 3)`` the scene's box, world units.
    aspect
        The thumbnail's width over its height.
    mode
        The shading mode it is drawn in.
    polygons
        ``(labels (F,) int, emits (L,) bool)``: the part each polygon id belongs to and
        which parts emit (default: the scene's models, and whether each one's material
        emits). A radiosity solution's one display mesh says its models this way.
    """
    from ..modes import Outputs
    from ..scene.camera import Camera

    lo, hi = np.asarray(bounds, np.float64)
    centre, reach = (lo + hi) / 2, float(np.linalg.norm(hi - lo)) / 2 or 1.0
    cameras = [Camera.named("iso", bounds, aspect=aspect)]
    for axis in range(3):
        for sign in (-1.0, 1.0):
            look = np.zeros(3)
            look[axis] = sign
            up = (0, 0, 1) if axis == 1 else (0, 1, 0)
            cameras.append(Camera.look_at(centre + 2.5 * reach * look, centre, up=up,
                                          fov_y=40))
            inside = centre + 0.45 * (hi - lo)[axis] * look
            cameras.append(Camera.look_at(inside, centre - 0.45 * (hi - lo)[axis] * look,
                                          up=up, fov_y=75))
    if polygons is None:  # each polygon id's model, and whether that model emits
        faces = np.array([m.mesh.n_faces for m in scene.models], np.int64)
        polygons = (np.repeat(np.arange(len(faces)), faces),
                    np.array([max(m.material.emission) > 0 for m in scene.models], bool))
    model_of, emits = (np.asarray(a) for a in polygons)
    small = renderer.__class__(48, max(1, int(48 / aspect)), samples=0,
                               context=renderer.context)
    scores = []
    with small:
        for cam in cameras:
            frame = small.render_frame(scene, cam, mode, outputs=Outputs.FACE_ID)
            ids = frame.face_id[(frame.face_id >= 0) & (frame.face_id < len(model_of))]
            seen = np.unique(model_of[ids]) if len(ids) else np.zeros(0, np.int64)
            scores.append((bool(emits[seen].any()), len(seen),
                           float(frame.color[..., :3].mean())))
    return cameras[max(range(len(cameras)), key=scores.__getitem__)]


def show(x) -> None:
    """Display ``x`` in a notebook: an image array, a Frame (its buffers side by side), an
    animation file (.gif, .png, .mp4) or anything with ``_repr_html_``. Outside IPython
    nothing is displayed and a ValueError says so only for what cannot be shown at all.

    Parameters
    ----------
    x : object
        What to show.
    """
    from ..render.renderer import Frame

    if isinstance(x, (str, Path)):
        path = Path(x)
        if not path.is_file():
            raise ValueError(f"show: no file {str(path)!r}")
        if path.suffix.lower() == ".mp4":
            data = base64.b64encode(path.read_bytes()).decode("ascii")
            _display_html(f'<video controls loop autoplay muted src="data:video/mp4;base64,'
                          f'{data}"></video>')
        elif path.suffix.lower() in (".gif", ".png", ".apng"):
            _display_png(path.read_bytes(), path.suffix.lower())
        else:
            raise ValueError(f"show: {path.name}: shows .gif, .png and .mp4 files")
        return
    if isinstance(x, Frame):
        _display_png(png_bytes(buffers_image(x)), ".png")
        return
    if isinstance(x, np.ndarray):
        image = x
        if image.dtype != np.uint8:
            image = (np.clip(image, 0, 1) * 255 + 0.5).astype(np.uint8)
        if image.ndim not in (2, 3) or (image.ndim == 3 and image.shape[2] not in (3, 4)):
            raise ValueError(f"show: an image is (H, W), (H, W, 3) or (H, W, 4), got "
                             f"{x.shape}")
        _display_png(png_bytes(image), ".png")
        return
    if hasattr(x, "_repr_html_"):
        _display_html(x._repr_html_())
        return
    raise ValueError(f"show: cannot show a {type(x).__name__}")


def _ipython_display():
    """IPython's display module, only if IPython is already running."""
    if "IPython" not in sys.modules:
        return None
    from IPython import display  # (already imported by the running shell)

    return display


def _display_png(data: bytes, suffix: str) -> None:
    d = _ipython_display()
    if d is not None:
        mime = "gif" if suffix == ".gif" else "png"
        d.display(d.HTML(f'<img src="data:image/{mime};base64,'
                         f'{base64.b64encode(data).decode("ascii")}"/>'))


def _display_html(text: str) -> None:
    d = _ipython_display()
    if d is not None:
        d.display(d.HTML(text))


_display.thumbnail_hook = thumbnail  # (the lower layers' reprs draw through it)
