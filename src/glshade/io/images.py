"""Images out: saving (PNG through Pillow, written to a temporary file and renamed), and the
pieces pictures are composed of -- labelled tiles, grids, heat maps with a colour bar."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import InputError
from ..atomic import atomic_write

__all__ = ["save_image", "save_gray", "image_format", "IMAGE_FORMATS", "heatmap", "label",
           "labelled_row", "colour_bar", "opaque", "font", "label_image", "LABEL_HEIGHT",
           "BACKGROUND"]

LABEL_HEIGHT = 22
BACKGROUND = (24, 24, 28)


#: image file extensions and their Pillow formats
IMAGE_FORMATS = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG", ".bmp": "BMP", ".tif": "TIFF",
                 ".tiff": "TIFF", ".webp": "WEBP"}


def image_format(path) -> str:
    """The format an image written to ``path`` gets: its extension's, PNG for a path with
    none; an extension that is not an image's is refused (a typo, or a file of another
    kind), naming the path.

    Parameters
    ----------
    path : str or Path
        The file to be written.
    """
    suffix = Path(path).suffix.lower()
    if not suffix:
        return "PNG"
    if suffix not in IMAGE_FORMATS:
        raise InputError(f"{path}: {suffix!r} is not an image extension; use one of "
                         f"{', '.join(IMAGE_FORMATS)}")
    return IMAGE_FORMATS[suffix]


def save_image(array, path, format: str | None = None,
               compress_level: int | None = None) -> None:
    """Write an ``(H, W, 3|4)`` uint8 (or float in [0, 1]) image. The format comes from the
    extension (:func:`image_format`); nothing is left behind if writing fails.

    Parameters
    ----------
    array : ndarray
        ``(H, W, 3|4)`` uint8, or float in [0, 1], row 0 at the top.
    path : str or Path
        Where (PNG, JPEG, PPM ...).
    format : str or None
        The format (None: from the extension).
    compress_level : int or None
        PNG's zlib level, 0-9 (None: Pillow's 6; a data set's thousands of frames take 1:
        a third of the time for a few percent more bytes).
    """
    from PIL import Image

    path = Path(path)
    fmt = format or image_format(path)
    a = np.asarray(array)
    if a.ndim == 2:
        a = a[..., None].repeat(3, -1)
    if a.ndim != 3 or a.shape[2] not in (3, 4):
        raise InputError(f"an image must have shape (H, W, 3) or (H, W, 4), got {a.shape}")
    if a.dtype != np.uint8:
        if not np.issubdtype(a.dtype, np.floating):
            raise InputError(f"image dtype must be uint8 or float, got {a.dtype}")
        a = (np.clip(a, 0, 1) * 255 + 0.5).astype(np.uint8)
    img = Image.fromarray(np.ascontiguousarray(a), "RGBA" if a.shape[2] == 4 else "RGB")
    if fmt == "JPEG":
        img = img.convert("RGB")
    with atomic_write(path, "wb") as f:
        if fmt == "PNG" and compress_level is not None:
            img.save(f, format=fmt, compress_level=compress_level)
        else:
            img.save(f, format=fmt)


def save_gray(array, path) -> None:
    """Write a one-channel ``(H, W)`` image as PNG, 8-bit (uint8: masks) or 16-bit
    (uint16: depth), atomically; the same array gives the same bytes.

    Parameters
    ----------
    array : ndarray
        ``(H, W)`` uint8 or uint16.
    path : str or Path
        Where (a .png).
    """
    a = np.asarray(array)
    if a.ndim != 2 or a.dtype not in (np.uint8, np.uint16):
        raise InputError(f"a gray image must be (H, W) uint8 or uint16, got {a.shape} "
                         f"{a.dtype}")
    from PIL import Image

    img = Image.fromarray(np.ascontiguousarray(a))  # ("L" for uint8, "I;16" for uint16)
    with atomic_write(Path(path), "wb") as f:
        # (zlib's fastest level: masks and depth are long runs, which it packs nearly as
        # tight as level 6 at a third of the time -- a data set writes dozens a view; 8-bit
        # images, masks, with zlib's run-length strategy (Z_RLE, 3): a 640x480 mask in 0.76
        # ms and 1.1 kB against 1.32 ms and 2.5 kB -- depth's gradients pack worse so)
        strategy = {"compress_type": 3} if a.dtype == np.uint8 else {}
        img.save(f, format="PNG", compress_level=1, **strategy)


# a perceptually ordered ramp (dark blue -> purple -> orange -> pale yellow)
_RAMP = np.array([[0, 0, 4], [40, 11, 84], [101, 21, 110], [159, 42, 99], [212, 72, 66],
                  [245, 125, 21], [250, 193, 39], [252, 255, 164]], float)


def heatmap(values, vmax: float) -> np.ndarray:
    """Map ``(H, W)`` values in ``[0, vmax]`` to RGB uint8 through the ramp.

    Parameters
    ----------
    values : array_like
        ``(H, W)`` values.
    vmax : float
        The value shown at the ramp's top (> 0).
    """
    t = np.clip(np.asarray(values, float) / max(vmax, 1e-12), 0, 1) * (len(_RAMP) - 1)
    i = np.minimum(t.astype(int), len(_RAMP) - 2)
    f = (t - i)[..., None]
    return ((1 - f) * _RAMP[i] + f * _RAMP[i + 1] + 0.5).astype(np.uint8)


def font(size: int = 14):
    """Pillow's built-in font at ``size`` pixels (a fixed size on Pillow < 10.1).

    Parameters
    ----------
    size : int
        Its height in pixels.
    """
    from PIL import ImageFont

    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow < 10.1
        return ImageFont.load_default()


def fitted(draw, text: str, width: float, size: int = 14):
    """``(font, text)`` that fit ``width`` pixels: the font shrunk down to 8 pixels, then
    the text cut short with an ellipsis (a label never runs past its tile)."""
    room = max(width - 4, 1)
    for px in range(size, 7, -1):
        face = font(px)
        if draw.textlength(text, font=face) <= room:
            return face, text
    face = font(8)
    while len(text) > 1 and draw.textlength(text + "\u2026", font=face) > room:
        text = text[:-1]
    return face, (text + "\u2026" if draw.textlength(text, font=face) <= room else "")


def label(tile: np.ndarray, text: str, background=BACKGROUND) -> np.ndarray:
    """``tile`` (RGB) under a band of LABEL_HEIGHT pixels with ``text`` centred in it
    (shrunk or cut to fit the tile: :func:`fitted`).

    Parameters
    ----------
    tile : ndarray
        ``(H, W, 3)`` uint8.
    text : str
        The label.
    background : (int, int, int)
        The band's RGB.
    """
    from PIL import Image, ImageDraw

    h, w = tile.shape[:2]
    band = Image.new("RGB", (w, LABEL_HEIGHT), background)
    draw = ImageDraw.Draw(band)
    face, text = fitted(draw, text, w)
    width = draw.textlength(text, font=face)
    draw.text(((w - width) / 2, 3), text, fill=(235, 235, 235), font=face)
    return np.vstack([np.asarray(band), tile[..., :3]])


def colour_bar(height: int, vmax: float) -> np.ndarray:
    """A vertical key of :func:`heatmap`'s ramp from ``vmax`` (top) to 0, labelled.

    Parameters
    ----------
    height : int
        The key's height in pixels.
    vmax : float
        The value at its top.
    """
    from PIL import Image, ImageDraw

    width = 64
    ramp = heatmap(np.linspace(vmax, 0, height)[:, None].repeat(14, 1), vmax)
    img = Image.new("RGB", (width, height), BACKGROUND)
    img.paste(Image.fromarray(ramp), (4, 0))
    draw = ImageDraw.Draw(img)
    face = font(11)
    draw.text((21, 0), f"{vmax:.3g}", fill=(235, 235, 235), font=face)
    draw.text((21, height // 2 - 6), f"{vmax / 2:.3g}", fill=(235, 235, 235), font=face)
    draw.text((21, height - 13), "0", fill=(235, 235, 235), font=face)
    draw.text((21, height - 28), "|err|", fill=(180, 180, 180), font=face)
    return np.asarray(img)


def opaque(rgb: np.ndarray) -> np.ndarray:
    """``(H, W, 3)`` uint8 with an opaque alpha channel added: ``(H, W, 4)``.

    Parameters
    ----------
    rgb : ndarray
        ``(H, W, 3)`` uint8.
    """
    return np.dstack([rgb, np.full(rgb.shape[:2], 255, np.uint8)])


def labelled_row(tiles: dict) -> np.ndarray:
    """Tiles ``{label: (H, W, 3|4) uint8}`` side by side, each under its label: RGBA.

    Parameters
    ----------
    tiles : dict
        ``{label: (H, W, 3|4) uint8}``, in order.
    """
    return opaque(np.hstack([label(t, name) for name, t in tiles.items()]))


def label_image(text: str, width: int) -> np.ndarray:
    """``(LABEL_HEIGHT, width, 4) uint8``: the text centred on a dark band (opaque).

    Parameters
    ----------
    text : str
        The label.
    width : int
        The band's width in pixels.
    """
    from PIL import Image, ImageDraw

    band = Image.new("RGBA", (width, LABEL_HEIGHT), (*BACKGROUND, 255))
    draw = ImageDraw.Draw(band)
    face, text = fitted(draw, text, width)
    draw.text(((width - draw.textlength(text, font=face)) / 2, 3), text,
              fill=(235, 235, 235, 255), font=face)
    return np.asarray(band)
