"""Image error metrics for comparing shading against a reference (pure numpy).

Images are ``(H, W, C)`` arrays in 8-bit units (uint8, or floats on the 0..255 scale);
an optional boolean ``mask (H, W)`` restricts every metric to the pixels that matter (the
object, not the background).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError

__all__ = ["abs_error", "mae", "max_error", "rmse", "psnr", "ssim", "mach_band_strength",
           "luminance", "edge_mask"]


def _pair(a, b, mask=None):
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    if a.shape != b.shape:
        raise InputError(f"images differ in shape: {a.shape} vs {b.shape}")
    if a.ndim == 2:
        a, b = a[..., None], b[..., None]
    if mask is not None:
        mask = np.asarray(mask, bool)
        if mask.shape != a.shape[:2]:
            raise InputError(f"mask shape {mask.shape} does not match images {a.shape[:2]}")
    return a, b, mask


def luminance(img) -> NDArray[np.float64]:
    """Rec. 709 luma of the RGB channels ``(H, W)``; a 2-D image is returned as is.

    Parameters
    ----------
    img : array_like
        ``(H, W, 3|4)`` RGB(A), or ``(H, W)`` already one channel.
    """
    a = np.asarray(img, dtype=np.float64)
    if a.ndim == 2:
        return a
    return a[..., :3] @ np.array([0.2126, 0.7152, 0.0722]) if a.shape[2] >= 3 else a[..., 0]


def abs_error(a, b) -> NDArray[np.float64]:
    """Per-pixel absolute error ``(H, W)``: the largest over the RGB channels.

    Parameters
    ----------
    a, b : array_like
        ``(H, W, 3|4)`` images, 8-bit units (uint8 or float in [0, 255]).
    """
    a, b, _ = _pair(a, b)
    return np.abs(a[..., :3] - b[..., :3]).max(axis=-1)


def _select(err, mask):
    return err if mask is None else err[mask]


def mae(a, b, mask=None) -> float:
    """Mean absolute error over pixels (and RGB channels).

    Parameters
    ----------
    a, b : array_like
        ``(H, W, 3|4)`` images, 8-bit units (uint8 or float in [0, 255]).
    mask : ndarray or None
        ``(H, W)`` bool: the pixels counted (None: every one).
    """
    a, b, mask = _pair(a, b, mask)
    e = _select(np.abs(a[..., :3] - b[..., :3]), mask)
    return float(e.mean()) if e.size else 0.0


def max_error(a, b, mask=None) -> float:
    """Largest absolute difference (8-bit units) over ``mask`` (every pixel when None).

    Parameters
    ----------
    a, b : array_like
        ``(H, W, 3|4)`` images, 8-bit units (uint8 or float in [0, 255]).
    mask : ndarray or None
        ``(H, W)`` bool: the pixels counted (None: every one).
    """
    a, b, mask = _pair(a, b, mask)
    e = _select(np.abs(a[..., :3] - b[..., :3]), mask)
    return float(e.max()) if e.size else 0.0


def rmse(a, b, mask=None) -> float:
    """Root-mean-square difference (8-bit units) over ``mask`` (every pixel when None).

    Parameters
    ----------
    a, b : array_like
        ``(H, W, 3|4)`` images, 8-bit units (uint8 or float in [0, 255]).
    mask : ndarray or None
        ``(H, W)`` bool: the pixels counted (None: every one).
    """
    a, b, mask = _pair(a, b, mask)
    e = _select((a[..., :3] - b[..., :3]) ** 2, mask)
    return float(np.sqrt(e.mean())) if e.size else 0.0


def psnr(a, b, mask=None, peak: float = 255.0) -> float:
    """Peak signal-to-noise ratio in dB; ``inf`` for identical images.

    Parameters
    ----------
    a, b : array_like
        ``(H, W, 3|4)`` images, 8-bit units (uint8 or float in [0, 255]).
    mask : ndarray or None
        ``(H, W)`` bool: the pixels counted (None: every one).
    peak : float
        The largest value a pixel can have.
    """
    r = rmse(a, b, mask)
    return float("inf") if r == 0 else float(20 * np.log10(peak / r))


def _gaussian_blur(x: NDArray[np.float64], sigma: float = 1.5, radius: int = 5):
    t = np.arange(-radius, radius + 1)
    k = np.exp(-0.5 * (t / sigma) ** 2)
    k /= k.sum()
    pad = np.pad(x, radius, mode="reflect")
    rows = sum(k[i] * pad[i:i + x.shape[0], :] for i in range(len(k)))
    return sum(k[i] * rows[:, i:i + x.shape[1]] for i in range(len(k)))


def ssim(a, b, mask=None, peak: float = 255.0) -> float:
    """Structural similarity (Wang et al. 2004: 11x11 Gaussian window, sigma 1.5,
    K1 = 0.01, K2 = 0.03) of the luminance, averaged over the mask; 1 for identical
    images.

    Parameters
    ----------
    a, b : array_like
        ``(H, W, 3|4)`` images, 8-bit units (uint8 or float in [0, 255]).
    mask : ndarray or None
        ``(H, W)`` bool: the pixels counted (None: every one).
    peak : float
        The largest value a pixel can have.
    """
    a, b, mask = _pair(a, b, mask)
    x, y = luminance(a), luminance(b)
    c1, c2 = (0.01 * peak) ** 2, (0.03 * peak) ** 2
    mx, my = _gaussian_blur(x), _gaussian_blur(y)
    sxx = _gaussian_blur(x * x) - mx * mx
    syy = _gaussian_blur(y * y) - my * my
    sxy = _gaussian_blur(x * y) - mx * my
    s = ((2 * mx * my + c1) * (2 * sxy + c2)) / ((mx * mx + my * my + c1) * (sxx + syy + c2))
    s = _select(s, mask)
    return float(s.mean()) if s.size else 1.0


def mach_band_strength(img, face_id, reference=None) -> float:
    """The visible jump in intensity across polygon edges, in 8-bit units: the mean
    absolute luminance difference between neighbouring pixels that belong to different
    polygons (from a ``face_id`` buffer). With a ``reference`` image, the reference's own
    difference across the same pixel pairs (the true shading's gradient) is subtracted, so
    a shading without Mach bands scores near zero.

    Parameters
    ----------
    img : array_like
        ``(H, W, 3|4)`` the image.
    face_id : ndarray
        ``(H, W)`` its polygon ids (-1: background).
    reference : array_like or None
        The same view's reference image: its own jumps are subtracted (None: none).
    """
    lum = luminance(img)
    ids = np.asarray(face_id)
    ref = luminance(reference) if reference is not None else None
    jumps, base = [], []
    for sl_a, sl_b in (((slice(None), slice(None, -1)), (slice(None), slice(1, None))),
                       ((slice(None, -1), slice(None)), (slice(1, None), slice(None)))):
        ia, ib = ids[sl_a], ids[sl_b]
        edge = (ia != ib) & (ia >= 0) & (ib >= 0)
        jumps.append(np.abs(lum[sl_a] - lum[sl_b])[edge])
        if ref is not None:
            base.append(np.abs(ref[sl_a] - ref[sl_b])[edge])
    j = np.concatenate(jumps)
    if j.size == 0:
        return 0.0
    if ref is None:
        return float(j.mean())
    return float(max(j.mean() - np.concatenate(base).mean(), 0.0))


def edge_mask(face_id: np.ndarray, width: int = 1) -> np.ndarray:
    """``(H, W) bool``: pixels within ``width`` pixels (8-neighbourhood) of a place where the
    polygon id changes -- a polygon's edge, or the silhouette against the background.

    Parameters
    ----------
    face_id : ndarray
        ``(H, W)`` polygon ids.
    width : int
        Pixels either side of an id change.
    """
    ids = np.asarray(face_id)
    if ids.ndim != 2:
        raise ValueError(f"face_id must be (H, W), got {ids.shape}")
    change = np.zeros(ids.shape, bool)
    horizontal = ids[:, 1:] != ids[:, :-1]
    vertical = ids[1:, :] != ids[:-1, :]
    change[:, 1:] |= horizontal
    change[:, :-1] |= horizontal
    change[1:, :] |= vertical
    change[:-1, :] |= vertical
    out = change
    for _ in range(max(int(width) - 1, 0)):  # grow by one pixel (8-neighbourhood) per step
        grown = out.copy()
        grown[1:, :] |= out[:-1, :]
        grown[:-1, :] |= out[1:, :]
        grown[:, 1:] |= out[:, :-1]
        grown[:, :-1] |= out[:, 1:]
        out = grown
    return out
