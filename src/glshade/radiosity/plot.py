"""A solver's convergence as a picture: the unshot (or still arriving) fraction of the
emitted energy against time, on a log scale, drawn with Pillow."""

from __future__ import annotations

import numpy as np

from ..io.images import font

__all__ = ["convergence_plot"]


def convergence_plot(history, title: str = "", size=(520, 360), target: float | None = None):
    """``history``: rows of (seconds, step, fraction); returns an (H, W, 3) uint8 image.

    Parameters
    ----------
    history : list
        Rows of (seconds, step, fraction).
    title : str
        The plot's title.
    size : (int, int)
        Width and height in pixels.
    target : float or None
        The fraction aimed at, drawn as a line.
    """
    from PIL import Image, ImageDraw

    w, h = size
    left, right, top, bottom = 64, 16, 36, 46
    img = Image.new("RGB", (w, h), (250, 250, 250))
    d = ImageDraw.Draw(img)
    face, small = font(13), font(11)
    t = np.array([r[0] for r in history], np.float64)
    f = np.maximum(np.array([r[2] for r in history], np.float64), 1e-6)
    lo = np.floor(np.log10(min(f.min(), target or 1.0)))
    hi = max(0.0, np.ceil(np.log10(f.max())))
    t1 = max(float(t.max()), 1e-3)

    def px(ti, fi):
        x = left + ti / t1 * (w - left - right)
        y = top + (hi - np.log10(fi)) / max(hi - lo, 1) * (h - top - bottom)
        return float(x), float(y)

    d.rectangle([left, top, w - right, h - bottom], outline=(120, 120, 120))
    for e in range(int(lo), int(hi) + 1):
        _, y = px(0, 10.0 ** e)
        d.line([left, y, w - right, y], fill=(225, 225, 225))
        d.text((8, y - 7), f"1e{e}", fill=(60, 60, 60), font=small)
    for k in range(5):
        x, _ = px(t1 * k / 4, 1.0)
        d.text((x - 10, h - bottom + 6), f"{t1 * k / 4:.3g}", fill=(60, 60, 60), font=small)
    d.text((w / 2 - 30, h - 22), "seconds", fill=(30, 30, 30), font=face)
    d.text((left, 10), title or "unshot energy fraction (log)", fill=(30, 30, 30), font=face)
    if target:
        _, y = px(0, target)
        d.line([left, y, w - right, y], fill=(230, 120, 60), width=1)
        d.text((w - right - 70, y - 14), f"goal {target:g}", fill=(230, 120, 60), font=small)
    d.line([px(a, b) for a, b in zip(t, f)], fill=(60, 110, 200), width=2)
    return np.asarray(img)
