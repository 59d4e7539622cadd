"""Helpers for testing rendered images in other projects' test suites.

``assert_images_close`` compares two images with explicit thresholds and, when they differ,
saves the actual image, the expected one and a difference heat map in a results folder
outside the source tree (:func:`failure_dir`), and says where they differ. RGB and RGBA
images are compared by what they hold (RGB is RGBA with an opaque alpha). The pytest plugin
(:mod:`glshade.testing.pytest_plugin`, registered as an entry point) adds a
``glshade_renderer`` fixture and golden-image checks (:mod:`glshade.testing.golden`). Both
read an image's values one way (:func:`levels`).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

__all__ = ["assert_images_close", "failure_dir", "node_folder", "safe_name", "levels"]


def safe_name(text: str) -> str:
    """``text`` as a file name: runs of anything but letters, digits, ``_.-[]`` become
    ``_``.

    Parameters
    ----------
    text : str
        Any text.
    """
    return re.sub(r"[^A-Za-z0-9_.\-\[\]]+", "_", text)


def node_folder(nodeid: str) -> str:
    """A test's own results folder name, from its whole node id (its file's path
    included: tests of one name in two folders do not share one).

    Parameters
    ----------
    nodeid : str
        A pytest node id.
    """
    return safe_name(nodeid.replace("::", "."))


def failure_dir() -> Path:
    """Where failure images go: ``<results>/<test node id>/``, the results folder being
    ``GLSHADE_RESULTS`` (the pytest plugin sets it to its results folder) or this machine's
    temporary folder -- never beside the test, in the source tree."""
    import tempfile

    current = os.environ.get("PYTEST_CURRENT_TEST", "")
    node = current.split(" ")[0]
    safe = node_folder(node) if node else "images"
    base = os.environ.get("GLSHADE_RESULTS") or os.path.join(tempfile.gettempdir(),
                                                             "glshade-results")
    return Path(base) / safe


def levels(image, name: str = "image") -> np.ndarray:
    """An image's values as ``(H, W, 4) float64`` in 8-bit units, the one reading every
    comparison makes: grey ``(H, W)`` or ``(H, W, 1)``, RGB (alpha 255) or RGBA; integers
    (any integer type) are 8-bit levels 0..255 as they are, floats are [0, 1] (times 255).
    Anything else -- levels out of range, floats beyond [0, 1] or not finite -- is refused
    (a ValueError naming ``name``), never rescaled by a guess.

    Parameters
    ----------
    image : array_like
        Grey, RGB or RGBA; integers are levels, floats [0, 1].
    name : str
        What it is, for errors.
    """
    a = np.asarray(image)
    if a.ndim == 2:
        a = a[..., None]
    if a.ndim != 3 or a.shape[2] not in (1, 3, 4):
        raise ValueError(f"{name} must be an (H, W), (H, W, 1), (H, W, 3) or (H, W, 4) "
                         f"image, got shape {a.shape}")
    if a.dtype == bool or not (np.issubdtype(a.dtype, np.integer)
                               or np.issubdtype(a.dtype, np.floating)):
        raise ValueError(f"{name} must hold integers (levels 0..255) or floats in [0, 1], "
                         f"got {a.dtype}")
    values = a.astype(np.float64)
    if np.issubdtype(a.dtype, np.integer):
        if values.size and (values.min() < 0 or values.max() > 255):
            raise ValueError(f"{name}: integer levels must be 0..255, got "
                             f"{values.min():g}..{values.max():g}")
    else:
        if not np.isfinite(values).all():
            raise ValueError(f"{name}: floats must be finite")
        if values.size and (values.min() < 0 or values.max() > 1):
            raise ValueError(f"{name}: floats are read as [0, 1], got "
                             f"{values.min():g}..{values.max():g} (scale them, or pass uint8)")
        values = values * 255.0
    if values.shape[2] == 1:
        values = np.repeat(values, 3, axis=2)
    if values.shape[2] == 3:
        values = np.concatenate([values, np.full(values.shape[:2] + (1,), 255.0)], axis=2)
    return values


def _as_float(image, name: str) -> np.ndarray:
    try:
        return levels(image, name)
    except ValueError as exc:
        raise AssertionError(str(exc)) from None


def assert_images_close(actual, expected, max_mean: float = 0.5, max_pixel: float = 4.0,
                        *, save_to: str | Path | None = None) -> None:
    """Fail unless the mean absolute difference (8-bit units, over pixels and channels) is
    at most ``max_mean`` and no pixel differs by more than ``max_pixel``.

    On failure the actual and expected images and a heat map of the difference are saved
    (``save_to`` or :func:`failure_dir`) and the message gives both numbers, how many
    pixels are over, their bounding box and the worst pixel.

    Parameters
    ----------
    actual, expected : array_like
        The images (levels as :func:`levels` reads them).
    max_mean : float
        The largest mean absolute difference allowed (8-bit units).
    max_pixel : float
        The largest single difference allowed.
    save_to : str or Path or None
        Where to save the images and their difference on failure.
    """
    a, e = _as_float(actual, "actual"), _as_float(expected, "expected")
    if a.shape != e.shape:
        raise AssertionError(f"image shapes differ: actual {a.shape}, expected {e.shape}")
    diff = np.abs(a - e).max(axis=-1)
    mean = float(np.abs(a - e).mean())
    worst = float(diff.max(initial=0))
    if mean <= max_mean and worst <= max_pixel:
        return
    from ..io.images import heatmap, save_image

    out = Path(save_to) if save_to is not None else failure_dir()
    out.mkdir(parents=True, exist_ok=True)
    save_image(np.round(a).astype(np.uint8), out / "actual.png")
    save_image(np.round(e).astype(np.uint8), out / "expected.png")
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
