"""Golden images that explain a mismatch: each golden PNG has a fingerprint of the renderer
that made it beside it (``name.json``), and a comparison gives a verdict, not just a number.

What is promised (measured on Mesa llvmpipe): glshade's images are bit-identical across EGL
and OSMesa, 1 or 2 llvmpipe threads and MSAA 0 or 4 for the same GL driver. So:

* **Same fingerprint** (GL vendor, renderer, version, backend, MSAA samples, glshade
  version): the bytes must be equal. Any difference is a regression.
* **Another fingerprint** (another driver, a GPU, a new glshade): drivers legitimately
  differ where coverage is decided, on polygon edges and silhouettes, so the id buffer of
  the new render (a :class:`~glshade.Frame`'s ``face_id``) splits the pixels. Pixels within
  ``edge_width`` pixels of an edge (where the polygon id changes, background included) may
  differ by any amount; they are counted and shown. Interior pixels -- inside one polygon,
  where every driver evaluates the same formula -- must be within ``max_pixel`` (8-bit
  units), and their mean difference within ``max_mean``. Without an id buffer the
  tolerances apply to every pixel.

RGB and RGBA images are compared by what they hold: an RGB image is RGBA with an opaque
alpha, so an RGBA render with alpha 255 everywhere equals its RGB golden.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..compare.metrics import edge_mask

__all__ = ["fingerprint", "as_rgba", "edge_mask", "Verdict", "judge", "read_golden",
           "write_golden", "FINGERPRINT_KEYS"]

#: what a fingerprint records, in this order
FINGERPRINT_KEYS = ("vendor", "renderer", "version", "backend", "samples", "glshade")


def fingerprint(renderer: Any) -> dict[str, Any]:
    """The facts that decide a render's bytes: the GL driver's vendor, renderer and version,
    the backend, the renderer's MSAA samples and glshade's version.

    Parameters
    ----------
    renderer : Renderer
        The renderer that drew.
    """
    from .._version import __version__

    info = renderer.context.info
    return {"vendor": info.get("vendor"), "renderer": info.get("renderer"),
            "version": info.get("version"), "backend": info.get("backend"),
            "samples": int(renderer.samples), "glshade": __version__}


def as_rgba(image: Any) -> np.ndarray:
    """``(H, W, 4) uint8`` of an image, read as :func:`glshade.testing.levels` reads it
    (integers are levels, floats [0, 1]), rounded.

    Parameters
    ----------
    image : array_like
        Any image :func:`glshade.testing.levels` reads.
    """
    from . import levels

    return np.round(levels(image)).astype(np.uint8)


@dataclass
class Verdict:
    """The outcome of comparing a render with its golden image.

    Parameters
    ----------
    ok : bool
        Whether the render passes.
    reason : str
        Why not, in one line (empty when it passes).
    same_fingerprint : bool
        Whether the golden was made on the same driver and settings.
    mean, worst : float
        The mean and largest absolute difference (8-bit units).
    differing : int
        Pixels that differ at all.
    edge_differing : int
        Of them, those at polygon edges.
    interior_over : int
        Interior pixels over the per-pixel limit.
    diff : ndarray
        ``(H, W)`` the per-pixel difference.
    """

    ok: bool
    reason: str
    same_fingerprint: bool
    mean: float = 0.0            # mean |difference| over the judged pixels (8-bit units)
    worst: float = 0.0           # the largest difference of a judged pixel
    differing: int = 0           # pixels that differ at all
    edge_differing: int = 0      # of them, on polygon edges (another driver's coverage)
    interior_over: int = 0       # interior pixels over max_pixel (a regression)
    diff: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)

    def summary(self) -> str:
        return (f"{self.reason}: {self.differing} pixels differ ({self.edge_differing} on "
                f"polygon edges), {self.interior_over} interior pixels over tolerance, mean "
                f"{self.mean:.3f}, max {self.worst:.1f}")


def judge(actual: Any, expected: Any, *, same_fingerprint: bool,
          face_id: np.ndarray | None = None, max_mean: float = 0.5,
          max_pixel: float = 4.0, edge_width: int = 1) -> Verdict:
    """Compare a render with its golden image (see the module's rules).

    Parameters
    ----------
    actual, expected : array_like
        The images (levels as :func:`levels` reads them).
    same_fingerprint : bool
        Whether the golden was made on the same driver and settings.
    face_id : ndarray or None
        The render's polygon ids (differences at edges tolerated).
    max_mean : float
        The largest mean difference allowed.
    max_pixel : float
        The largest interior difference allowed.
    edge_width : int
        Pixels either side of an id change counted as edge.
    """
    a, e = as_rgba(actual), as_rgba(expected)
    if a.shape != e.shape:
        return Verdict(False, f"sizes differ: the render is {a.shape[1]}x{a.shape[0]}, the "
                       f"golden {e.shape[1]}x{e.shape[0]}", same_fingerprint)
    diff = np.abs(a.astype(np.int16) - e.astype(np.int16)).max(axis=2).astype(np.float64)
    differing = diff > 0
    if same_fingerprint:
        n = int(differing.sum())
        return Verdict(n == 0, "identical bytes, as the same renderer must give" if n == 0
                       else "the same renderer made different bytes (a regression)", True,
                       float(diff.mean()), float(diff.max(initial=0)), n, 0, n, diff)
    if face_id is None:
        judged = np.ones(diff.shape, bool)
        edges = np.zeros(diff.shape, bool)
    else:
        if np.shape(face_id) != diff.shape:
            raise ValueError(f"face_id {np.shape(face_id)} does not match the image "
                             f"{diff.shape}")
        edges = edge_mask(face_id, edge_width)
        judged = ~edges
    values = diff[judged]
    mean = float(values.mean()) if values.size else 0.0
    worst = float(values.max(initial=0))
    over = int(((diff > max_pixel) & judged).sum())
    ok = over == 0 and mean <= max_mean
    where = "interior " if face_id is not None else ""
    reason = (f"another renderer: {where}pixels within tolerance" if ok else
              f"another renderer, but {where}pixels differ beyond tolerance (max_pixel "
              f"{max_pixel:g}, max_mean {max_mean:g}): a regression")
    return Verdict(ok, reason, False, mean, worst, int(differing.sum()),
                   int((differing & edges).sum()), over, diff)


def read_golden(path: Path) -> tuple[np.ndarray, dict[str, Any] | None]:
    """A golden image and its fingerprint (None when it has none: an older golden).

    Parameters
    ----------
    path : Path
        The golden image.
    """
    from PIL import Image

    with Image.open(path) as im:
        image = np.asarray(im)
    meta = path.with_suffix(".json")
    facts = json.loads(meta.read_text(encoding="utf-8")) if meta.exists() else None
    return image, facts


def write_golden(path: Path, image: Any, facts: dict[str, Any]) -> None:
    """Write a golden image and its fingerprint beside it (each atomically).

    Parameters
    ----------
    path : Path
        The golden image.
    image : array_like
        The render.
    facts : dict
        Its fingerprint.
    """
    from ..atomic import atomic_write
    from ..io.images import save_image

    path.parent.mkdir(parents=True, exist_ok=True)
    save_image(as_rgba(image), path)
    with atomic_write(path.with_suffix(".json"), "w") as f:
        json.dump({k: facts.get(k) for k in FINGERPRINT_KEYS}, f, indent=2)
        f.write("\n")
