"""Colour maps glshade draws buffers with, written once: polygon ids (the id buffer of a
frame, the hidden-surface lab's results, notebook thumbnails) get one palette everywhere,
so a polygon has the same colour in every picture of it."""

from __future__ import annotations

import numpy as np

__all__ = ["id_colors", "BACKGROUND_ID_COLOR"]

#: the colour of pixels no polygon covers (id -1)
BACKGROUND_ID_COLOR = (18, 18, 22)


def id_colors(face_id: np.ndarray) -> np.ndarray:
    """``(H, W, 3) uint8`` of an id buffer ``(H, W)``: each polygon id a colour of its own
    (golden-ratio hues, so neighbouring ids differ), the background (-1) dark.

    Parameters
    ----------
    face_id : ndarray
        ``(H, W)`` int polygon ids, -1 for background.
    """
    ids = np.asarray(face_id).astype(np.int64)
    h = (ids * 0.6180339887) % 1.0
    s = 0.55 + 0.35 * ((ids * 0.37) % 1.0)
    v = 0.95 - 0.25 * ((ids * 0.71) % 1.0)
    i = np.floor(h * 6).astype(int) % 6
    f = h * 6 - np.floor(h * 6)
    p, q, t = v * (1 - s), v * (1 - f * s), v * (1 - (1 - f) * s)
    r = np.choose(i, [v, q, p, p, t, v])
    g = np.choose(i, [t, v, v, q, p, p])
    b = np.choose(i, [p, p, t, v, v, q])
    rgb = (np.stack([r, g, b], -1) * 255).astype(np.uint8)
    rgb[ids < 0] = BACKGROUND_ID_COLOR
    return rgb
