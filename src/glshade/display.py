"""Notebook display: glshade's objects show themselves as a small picture and a few facts.

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
import html
import io
import sys
from pathlib import Path

import numpy as np

__all__ = ["show", "png_bytes", "buffers_image", "thumbnail", "facts_html", "THUMBNAIL"]

#: thumbnails' size in pixels (width, height)
THUMBNAIL = (256, 192)


def png_bytes(image: np.ndarray) -> bytes:
    """PNG of an ``(H, W)``, ``(H, W, 3)`` or ``(H, W, 4)`` uint8 image."""
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(image)).save(buf, format="PNG")
    return buf.getvalue()


def _id_colours(ids: np.ndarray) -> np.ndarray:
    """(H, W, 3) uint8: a distinct colour per polygon id (a hash), black background."""
    h = (ids.astype(np.int64) + 1) * 2654435761 % (2 ** 32)
    rgb = np.stack([(h >> s) & 255 for s in (0, 8, 16)], -1).astype(np.uint8) // 2 + 96
    return np.where((ids >= 0)[..., None], rgb, 0).astype(np.uint8)


def buffers_image(frame) -> np.ndarray:
    """A frame's buffers as one ``(H, k W, 3)`` uint8 image: colour, then depth (near
    white, far dark), world normals (0.5 n + 0.5) and polygon ids, those the frame has."""
    color = np.asarray(frame.color)
    if color.dtype != np.uint8:
        color = (np.clip(color, 0, 1) * 255 + 0.5).astype(np.uint8)
    tiles = [color[..., :3]]
    if frame.depth is not None:
        d = np.asarray(frame.depth, np.float64)
        seen = np.isfinite(d)
        grey = np.zeros(d.shape)
        if seen.any():
            lo, hi = d[seen].min(), d[seen].max()
            grey[seen] = 1.0 - 0.8 * (d[seen] - lo) / max(hi - lo, 1e-30)
        tiles.append(np.repeat((grey * 255 + 0.5).astype(np.uint8)[..., None], 3, -1))
    if frame.normal is not None:
        n = np.asarray(frame.normal, np.float64)
        shown = np.linalg.norm(n, axis=-1) > 0
        rgb = ((0.5 * n + 0.5) * 255 + 0.5).astype(np.uint8)
        tiles.append(np.where(shown[..., None], rgb, 0).astype(np.uint8))
    if frame.face_id is not None:
        tiles.append(_id_colours(np.asarray(frame.face_id)))
    return np.concatenate(tiles, axis=1)


def thumbnail(scene, camera=None, size: tuple[int, int] = THUMBNAIL, mode: str = "phong"):
    """A ``(H, W, 4)`` uint8 render of ``scene`` (framed from the iso view unless a camera
    is given), or None where no GL context can be made or there is nothing to draw."""
    import warnings

    from .errors import EnvironmentFailure
    from .scene.camera import Camera

    bounds = scene.bounds
    if bounds is None:
        return None
    cam = camera or Camera.named("iso", bounds, aspect=size[0] / size[1])
    try:
        from .render.renderer import Renderer

        with warnings.catch_warnings(), Renderer(*size, samples=0) as r:
            warnings.simplefilter("ignore")
            return r.render(scene, cam, mode)
    except EnvironmentFailure:
        return None


def facts_html(title: str, facts: list[str], image: np.ndarray | None = None) -> str:
    """HTML of a picture (inline PNG) beside a title and a list of facts."""
    rows = "".join(f"<li>{html.escape(f)}</li>" for f in facts)
    picture = ""
    if image is not None:
        data = base64.b64encode(png_bytes(image)).decode("ascii")
        h, w = image.shape[:2]
        picture = (f'<img src="data:image/png;base64,{data}" width="{w}" height="{h}" '
                   'style="margin-right:1em"/>')
    return (f'<div style="display:flex;align-items:flex-start">{picture}<div>'
            f"<b>{html.escape(title)}</b><ul>{rows}</ul></div></div>")


def _bounds_fact(bounds) -> str:
    if bounds is None:
        return "unbounded"
    lo, hi = np.asarray(bounds)
    return ("bounds [" + ", ".join(f"{x:.4g}" for x in lo) + "] .. [" +
            ", ".join(f"{x:.4g}" for x in hi) + "]")


def show(x, **kwargs) -> None:
    """Display ``x`` in a notebook: an image array, a Frame (its buffers side by side), an
    animation file (.gif, .png, .mp4) or anything with ``_repr_html_``. Outside IPython
    nothing is displayed and a ValueError says so only for what cannot be shown at all."""
    from .render.renderer import Frame

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
