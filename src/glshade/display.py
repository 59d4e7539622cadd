"""The layer-free half of notebook display: HTML of a picture and facts, PNG encoding,
colour maps of a frame's buffers, and the hook through which a picture is rendered.

Why split: every layer's objects (a Mesh, a Scene, a radiosity Solution) display
themselves, but a thumbnail needs the renderer, which the lower layers must not import. So
they ask :func:`picture`, which calls the hook :mod:`glshade.notebook.display` installs when it is
imported (``import glshade`` imports it when IPython is running); with no hook, or no GL,
the facts are shown alone.
"""

from __future__ import annotations

import base64
import html
import io
from typing import Callable

import numpy as np

__all__ = ["facts_html", "png_bytes", "buffers_image", "bounds_fact",
           "picture", "THUMBNAIL"]

#: thumbnails' size in pixels (width, height)
THUMBNAIL = (256, 192)
#: (a Scene, Mesh or solid, mode, choose) -> (H, W, 4) uint8 or None; installed by
#: glshade.notebook.display
thumbnail_hook: Callable | None = None


def picture(drawable, mode: str = "phong", choose: bool = False, polygons=None):
    """A thumbnail of ``drawable`` (a Scene, a Mesh or a solid) through the installed
    hook, or None; an image ``(H, W, 4)`` uint8 is its own picture.

    Parameters
    ----------
    drawable
        What is drawn.
    mode
        The shading mode.
    choose
        From the view that shows most (a closed room is dark from outside).
    polygons
        ``(labels (F,) int, emits (L,) bool)``: the part each polygon of the scene belongs
        to and which parts emit, for ``choose`` to judge views by (default: the scene's
        models and their materials' emission).
    """
    if isinstance(drawable, np.ndarray):
        return drawable
    return None if thumbnail_hook is None else thumbnail_hook(drawable, mode=mode,
                                                              choose=choose,
                                                              polygons=polygons)


def png_bytes(image: np.ndarray) -> bytes:
    """PNG of an ``(H, W)``, ``(H, W, 3)`` or ``(H, W, 4)`` uint8 image.

    Parameters
    ----------
    image : ndarray
        ``(H, W)``, ``(H, W, 3)`` or ``(H, W, 4)`` uint8.
    """
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(image)).save(buf, format="PNG")
    return buf.getvalue()


def buffers_image(frame) -> np.ndarray:
    """A frame's buffers as one ``(H, k W, 3)`` uint8 image: colour, then depth (near
    white, far dark), world normals (0.5 n + 0.5) and polygon ids, those the frame has.

    Parameters
    ----------
    frame : Frame
        A frame with any of its buffers.
    """
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
        from .colormaps import id_colors

        tiles.append(id_colors(np.asarray(frame.face_id)))
    return np.concatenate(tiles, axis=1)


def facts_html(title: str, facts: list[str], image: np.ndarray | None = None) -> str:
    """HTML of a picture (inline PNG) beside a title and a list of facts.

    Parameters
    ----------
    title : str
        The heading.
    facts : list of str
        The facts listed.
    image : ndarray or None
        A picture shown beside them.
    """
    rows = "".join(f"<li>{html.escape(f)}</li>" for f in facts)
    picture = ""
    if image is not None:
        data = base64.b64encode(png_bytes(image)).decode("ascii")
        h, w = image.shape[:2]
        picture = (f'<img src="data:image/png;base64,{data}" width="{w}" height="{h}" '
                   'style="margin-right:1em"/>')
    return (f'<div style="display:flex;align-items:flex-start">{picture}<div>'
            f"<b>{html.escape(title)}</b><ul>{rows}</ul></div></div>")


def bounds_fact(bounds) -> str:
    """One line of a notebook card: an object's box.

    Parameters
    ----------
    bounds
        (2, 3) lowest and highest corner in world units, or None (unbounded).
    """
    if bounds is None:
        return "unbounded"
    lo, hi = np.asarray(bounds)
    return ("bounds [" + ", ".join(f"{x:.4g}" for x in lo) + "] .. [" +
            ", ".join(f"{x:.4g}" for x in hi) + "]")
