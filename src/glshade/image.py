"""Saving images: PNG through Pillow, written to a temporary file and renamed."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._atomic import atomic_write
from .errors import GlshadeError

__all__ = ["save_image"]


def save_image(array, path, format: str | None = None) -> None:
    """Write an ``(H, W, 3|4)`` uint8 (or float in [0, 1]) image. The format comes from the
    extension (PNG by default); nothing is left behind if writing fails."""
    from PIL import Image

    a = np.asarray(array)
    if a.ndim == 2:
        a = a[..., None].repeat(3, -1)
    if a.ndim != 3 or a.shape[2] not in (3, 4):
        raise GlshadeError(f"an image must have shape (H, W, 3) or (H, W, 4), got {a.shape}")
    if a.dtype != np.uint8:
        if not np.issubdtype(a.dtype, np.floating):
            raise GlshadeError(f"image dtype must be uint8 or float, got {a.dtype}")
        a = (np.clip(a, 0, 1) * 255 + 0.5).astype(np.uint8)
    path = Path(path)
    fmt = format or {".jpg": "JPEG", ".jpeg": "JPEG", ".bmp": "BMP", ".tif": "TIFF",
                     ".tiff": "TIFF", ".webp": "WEBP"}.get(path.suffix.lower(), "PNG")
    img = Image.fromarray(a, "RGBA" if a.shape[2] == 4 else "RGB")
    if fmt == "JPEG":
        img = img.convert("RGB")
    with atomic_write(path, "wb") as f:
        img.save(f, format=fmt)
