"""Helpers for testing rendered images in other projects' test suites.

``assert_images_close`` compares two images with explicit thresholds and, when they differ,
saves the actual image, the expected one and a difference heat map in a results folder
outside the source tree (:func:`failure_dir`), and says where they differ. RGB and RGBA
images are compared by what they hold (RGB is RGBA with an opaque alpha). The pytest plugin
(``glshade.pytest_plugin``, registered as an entry point) adds a ``glshade_renderer``
fixture and golden-image checks (:mod:`glshade.golden`).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

__all__ = ["assert_images_close", "failure_dir"]


def failure_dir() -> Path:
    """Where failure images go: ``<results>/<test name>/``, the results folder being
    ``GLSHADE_RESULTS`` (the pytest plugin sets it to its results folder) or this machine's
    temporary folder -- never beside the test, in the source tree."""
    import tempfile

    current = os.environ.get("PYTEST_CURRENT_TEST", "")
    node = current.split(" ")[0]
    name = node.partition("::")[2]
    safe = re.sub(r"[^A-Za-z0-9_.\-\[\]]+", "_", name or "images")
    base = os.environ.get("GLSHADE_RESULTS") or os.path.join(tempfile.gettempdir(),
                                                             "glshade-results")
    return Path(base) / safe


def _as_float(img, name) -> np.ndarray:
    a = np.asarray(img)
    if a.ndim == 2:
        a = a[..., None]
    if a.ndim != 3:
        raise AssertionError(f"{name} must be an (H, W[, C]) image, got shape {a.shape}")
    a = a.astype(np.float64)
    if np.asarray(img).dtype != np.uint8 and a.max(initial=0) <= 1.0:
        a = a * 255.0  # floats in [0, 1]
    return a


def assert_images_close(actual, expected, max_mean: float = 0.5, max_pixel: float = 4.0,
                        *, save_to: str | Path | None = None) -> None:
    """Fail unless the mean absolute difference (8-bit units, over pixels and channels) is
    at most ``max_mean`` and no pixel differs by more than ``max_pixel``.

    On failure the actual and expected images and a heat map of the difference are saved
    (``save_to`` or :func:`failure_dir`) and the message gives both numbers, how many
    pixels are over, their bounding box and the worst pixel.
    """
    a, e = _as_float(actual, "actual"), _as_float(expected, "expected")
    if a.shape[:2] == e.shape[:2] and {a.shape[2], e.shape[2]} == {3, 4}:
        a, e = (x if x.shape[2] == 4 else np.concatenate([x, np.full(x.shape[:2] + (1,), 255.0)],
                                                         axis=2) for x in (a, e))
    if a.shape != e.shape:
        raise AssertionError(f"image shapes differ: actual {a.shape}, expected {e.shape}")
    diff = np.abs(a - e).max(axis=-1)
    mean = float(np.abs(a - e).mean())
    worst = float(diff.max(initial=0))
    if mean <= max_mean and worst <= max_pixel:
        return
    from .io.images import heatmap, save_image

    out = Path(save_to) if save_to is not None else failure_dir()
    out.mkdir(parents=True, exist_ok=True)
    save_image(np.clip(a, 0, 255).astype(np.uint8)[..., :4] if a.shape[2] in (3, 4)
               else np.clip(a[..., 0], 0, 255).astype(np.uint8), out / "actual.png")
    save_image(np.clip(e, 0, 255).astype(np.uint8)[..., :4] if e.shape[2] in (3, 4)
               else np.clip(e[..., 0], 0, 255).astype(np.uint8), out / "expected.png")
    save_image(heatmap(diff, max(worst, 1.0)), out / "diff.png")
    over = diff > max_pixel
    y, x = np.unravel_index(int(np.argmax(diff)), diff.shape)
    where = ""
    if over.any():
        ys, xs = np.nonzero(over)
        where = (f"; {int(over.sum())} pixels differ by more than {max_pixel:g}, within rows "
                 f"{ys.min()}..{ys.max()}, columns {xs.min()}..{xs.max()}")
    raise AssertionError(
        f"images differ: mean |difference| {mean:.3f} (allowed {max_mean:g}), max {worst:.1f} "
        f"(allowed {max_pixel:g}) at row {y}, column {x}{where}. Saved actual.png, "
        f"expected.png and diff.png in {out}")
