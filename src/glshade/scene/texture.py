"""Images on surfaces: a :class:`Texture` is an image and how it is sampled (filter, wrap).

Colour images (a diffuse or specular map) are stored as their 8-bit sRGB bytes and decoded
to linear light when sampled -- by the GPU's sRGB texture format, before filtering, as the
lighting formula wants linear values; a scalar map (opacity) is used as stored. Texture
coordinates follow OBJ: (0, 0) is the image's bottom-left corner, u to the right, v up;
outside [0, 1] the ``wrap`` rule applies.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .._srgb import srgb_to_linear
from ..errors import SceneError

__all__ = ["Texture", "FILTERS", "WRAPS", "srgb_to_linear", "texture_field",
           "check_texture_filter", "check_texture_wrap"]

#: how a texel is chosen: the nearest texel's value, bilinear between the four nearest,
#: or trilinear between mipmap levels (minified images without shimmer)
FILTERS = ("nearest", "linear", "mipmap")
#: what lies outside [0, 1]: the image again, or its edge texels (MTL's -clamp on)
WRAPS = ("repeat", "clamp")


def _one_of(value: object, names: tuple, what: str) -> str:
    if value not in names:
        raise SceneError.must(what, f"be one of {', '.join(names)}, got {value!r}")
    return str(value)


def check_texture_filter(value: object, what: str = "texture filter") -> str:
    """The one rule for a texture's filter: one of FILTERS.

    Parameters
    ----------
    value
        The filter's name.
    what
        Its name in the message.
    """
    return _one_of(value, FILTERS, what)


def check_texture_wrap(value: object, what: str = "texture wrap") -> str:
    """The one rule for a texture's wrap: one of WRAPS.

    Parameters
    ----------
    value
        The wrap's name.
    what
        Its name in the message.
    """
    return _one_of(value, WRAPS, what)


@dataclass(eq=False, frozen=True)
class Texture:
    """An image for a material's diffuse colour, specular colour or opacity.

    ``pixels`` is the image as ``(H, W, 4)`` uint8, row 0 at the top (alpha 255 where the
    image has none); ``path`` the file it came from, if any.

    Parameters
    ----------
    source : path, PIL image or array
        An array is ``(H, W)``, ``(H, W, 3)`` or ``(H, W, 4)``, uint8 or floats in [0, 1],
        row 0 at the top, as images are stored.
    filter : str
        ``"nearest"``, ``"linear"`` (bilinear) or ``"mipmap"`` (trilinear).
    wrap : str
        ``"repeat"`` or ``"clamp"`` (to the edge texels).
    scale : (u, v)
        Multiplies the texture coordinates (MTL's -s option).
    offset : (u, v)
        Is added to them after the scale (MTL's -o option).
    """

    source: object
    filter: str = "linear"
    wrap: str = "repeat"
    scale: tuple = (1.0, 1.0)
    offset: tuple = (0.0, 0.0)
    pixels: np.ndarray = field(init=False, repr=False)
    path: Path | None = field(init=False, default=None)

    def __post_init__(self):
        check_texture_filter(self.filter)
        check_texture_wrap(self.wrap)
        for name in ("scale", "offset"):
            v = np.asarray(getattr(self, name), np.float64)
            if v.shape != (2,) or not np.isfinite(v).all() or (abs(v) > 1e15).any():
                raise SceneError(f"texture {name} must be 2 finite numbers (u, v), got "
                                 f"{getattr(self, name)!r}")
            object.__setattr__(self, name, (float(v[0]), float(v[1])))
        path, pixels = _pixels(self.source)
        pixels.setflags(write=False)
        object.__setattr__(self, "pixels", pixels)
        object.__setattr__(self, "path", path)

    @property
    def size(self) -> tuple[int, int]:
        """``(width, height)`` in texels."""
        return int(self.pixels.shape[1]), int(self.pixels.shape[0])

    def replace(self, **changes) -> Texture:
        """The same image with another ``filter`` or ``wrap`` (the pixels are shared).

        Parameters
        ----------
        **changes
            ``filter`` and/or ``wrap``.
        """
        t = Texture.__new__(Texture)
        for name in ("source", "filter", "wrap", "scale", "offset", "pixels", "path"):
            object.__setattr__(t, name, changes.get(name, getattr(self, name)))
        if t.filter not in FILTERS or t.wrap not in WRAPS:
            Texture(self.pixels, t.filter, t.wrap)  # (the same checks, the same errors)
        return t

    def linear(self) -> np.ndarray:
        """The image decoded to linear light, ``(H, W, 4)`` float64 (alpha as stored): what
        a colour map's texels are when sampled."""
        out = self.pixels / 255.0
        out[..., :3] = srgb_to_linear(out[..., :3])
        return out

    def __repr__(self) -> str:
        what = str(self.path) if self.path is not None else "an image"
        w, h = self.size
        return f"<Texture {what}: {w}x{h}, {self.filter}, {self.wrap}>"


def _pixels(source) -> tuple[Path | None, np.ndarray]:
    """``(path or None, (H, W, 4) uint8)`` from a path, a PIL image or an array."""
    from PIL import Image, UnidentifiedImageError

    path = None
    if isinstance(source, (str, Path)):
        path = Path(source)
        if not path.is_file():
            raise SceneError(f"{path}: no such image file" if not path.exists() else
                             f"{path}: not a file")
        try:
            with Image.open(path) as im:
                im.load()
                source = im.copy()
        except (UnidentifiedImageError, OSError, Image.DecompressionBombError) as exc:
            raise SceneError(f"{path}: not an image Pillow can read "
                             f"({type(exc).__name__}: {exc})") from None
    if isinstance(source, Image.Image):
        source = np.asarray(source.convert("RGBA"))
    a = np.asarray(source)
    if a.ndim == 2:
        a = a[..., None]
    if a.ndim != 3 or a.shape[2] not in (1, 3, 4) or a.shape[0] < 1 or a.shape[1] < 1:
        raise SceneError(f"a texture image must have shape (H, W), (H, W, 3) or (H, W, 4), "
                         f"got {a.shape}")
    if a.dtype != np.uint8:
        f = a.astype(np.float64)
        if not np.isfinite(f).all() or f.min() < 0 or f.max() > 1:
            raise SceneError("a float texture image must hold numbers in [0, 1]")
        a = np.round(f * 255).astype(np.uint8)
    if a.shape[2] == 1:
        a = np.repeat(a, 3, axis=2)
    if a.shape[2] == 3:
        a = np.concatenate([a, np.full(a.shape[:2] + (1,), 255, np.uint8)], axis=2)
    return path, np.ascontiguousarray(a)


def texture_field(value, name: str):
    """A material's map as given: a Texture, an image path made one, or None; anything else
    a SceneError naming the field (the one rule for every material's maps).

    Parameters
    ----------
    value : Texture, str, Path or None
        What the field was given.
    name : str
        The field, for the message.
    """
    if isinstance(value, (str, Path)):
        return Texture(value)
    if value is not None and not isinstance(value, Texture):
        raise SceneError(f"{name} must be a glshade.Texture or an image path, got "
                         f"{type(value).__name__}")
    return value
