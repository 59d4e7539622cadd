"""Cameras in OpenCV's terms: an intrinsic matrix K and a world-to-camera pose (R, t), read
and written exactly, for the vision code that renders ground truth.

OpenCV's conventions, which these functions keep:

- camera axes x right, y down, z forward; a world point X is at ``x_cam = R @ X + t`` and
  lands at pixel ``(u, v) = (fx x/z + cx, fy y/z + cy)``;
- integer ``(u, v)`` are pixel *centres*: the image's top-left corner is (-0.5, -0.5), so a
  point at ``(u, v)`` lies in column ``floor(u + 0.5)`` and row ``floor(v + 0.5)``.

glshade's camera looks down its -z with y up (OpenGL's axes), so R turns by diag(1, -1, -1)
between the two. A camera made from K keeps K as its *lens*, ``(fx / W, fy / H,
(cx + 0.5) / W, (cy + 0.5) / H)``: the focal lengths and the principal point as fractions
of the image, so the same camera drawn at another size scales K with it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import SceneError, plain

__all__ = ["check_intrinsics", "check_rotation", "lens_of", "intrinsics_of",
           "projection_from_lens", "GL_FROM_CV", "ROTATION_TOLERANCE"]

#: OpenCV's camera axes to OpenGL's (x right, y down, z forward -> x right, y up, z back)
GL_FROM_CV = np.diag([1.0, -1.0, -1.0])
#: how far R may be from a rotation: ``|R^T R - I|`` and ``|det R - 1|`` at most this
ROTATION_TOLERANCE = 1e-6


def _size(size) -> tuple[int, int]:
    try:
        w, h = size
        ok = all(not isinstance(v, bool) and float(v) == int(v) and int(v) >= 1 for v in (w, h))
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise SceneError(f"size must be the image's (width, height) in whole pixels, got "
                         f"{size!r}")
    return int(w), int(h)


def check_intrinsics(K: ArrayLike, size) -> NDArray[np.float64]:
    """``K`` as a float64 ``(3, 3)`` after OpenCV's pinhole rules, or a SceneError naming
    the fault: finite; ``[[fx, 0, cx], [0, fy, cy], [0, 0, 1]]`` with ``fx, fy > 0`` and no
    skew (glshade draws rectangular pixels); the principal point within an image's width or
    height of the image (past that the ``size`` is not K's).

    Parameters
    ----------
    K : array_like
        ``(3, 3)`` the intrinsic matrix, in pixels.
    size : (int, int)
        The image's width and height in pixels.
    """
    w, h = _size(size)
    k = np.asarray(K, dtype=np.float64)
    if k.shape != (3, 3) or not np.isfinite(k).all():
        raise SceneError(f"K must be a 3x3 matrix of finite numbers, got shape {k.shape}")
    if k[0, 1] != 0:
        raise SceneError(f"K has a skew of {plain(k[0, 1])} (K[0][1]); glshade draws "
                         "rectangular pixels: K[0][1] must be 0")
    if k[1, 0] != 0 or k[2, 0] != 0 or k[2, 1] != 0 or k[2, 2] != 1:
        raise SceneError(f"K's last row must be (0, 0, 1) and K[1][0] 0, got rows "
                         f"{plain(k[1])}, {plain(k[2])}")
    fx, fy, cx, cy = k[0, 0], k[1, 1], k[0, 2], k[1, 2]
    if not (fx > 0 and fy > 0):
        raise SceneError(f"K's focal lengths must be positive pixels, got fx {plain(fx)}, "
                         f"fy {plain(fy)}")
    if not (-w <= cx <= 2 * w and -h <= cy <= 2 * h):
        raise SceneError(f"K's principal point ({plain(cx)}, {plain(cy)}) is more than the "
                         f"image away from a {w}x{h} image: is the size K's?")
    return k


def check_rotation(R: ArrayLike) -> NDArray[np.float64]:
    """``R`` as a float64 ``(3, 3)`` rotation (orthonormal with determinant +1 within
    ROTATION_TOLERANCE), or a SceneError saying by how much it is not one.

    Parameters
    ----------
    R : array_like
        ``(3, 3)`` world-to-camera rotation (OpenCV's axes).
    """
    r = np.asarray(R, dtype=np.float64)
    if r.shape != (3, 3) or not np.isfinite(r).all():
        raise SceneError(f"R must be a 3x3 matrix of finite numbers, got shape {r.shape}")
    off = float(np.abs(r.T @ r - np.eye(3)).max())
    det = float(np.linalg.det(r))
    if off > ROTATION_TOLERANCE or abs(det - 1) > ROTATION_TOLERANCE:
        raise SceneError(f"R is not a rotation: |R^T R - I| = {off:.3g}, det R = {det:.6g} "
                         f"(each must be within {ROTATION_TOLERANCE:g} of a rotation's 0 and 1)")
    return r


def lens_of(K: NDArray[np.float64], size) -> tuple[float, float, float, float]:
    """The camera's lens from a checked ``K`` for a ``size`` image: ``(fx / W, fy / H,
    (cx + 0.5) / W, (cy + 0.5) / H)``.

    Parameters
    ----------
    K : ndarray
        ``(3, 3)`` a checked intrinsic matrix (:func:`check_intrinsics`).
    size : (int, int)
        The image's width and height in pixels.
    """
    w, h = _size(size)
    return (float(K[0, 0] / w), float(K[1, 1] / h), float((K[0, 2] + 0.5) / w),
            float((K[1, 2] + 0.5) / h))


def intrinsics_of(lens: tuple[float, float, float, float], size) -> NDArray[np.float64]:
    """K for a ``size`` image from a lens (:func:`lens_of`'s inverse).

    Parameters
    ----------
    lens : (float, float, float, float)
        ``(fx / W, fy / H, (cx + 0.5) / W, (cy + 0.5) / H)``.
    size : (int, int)
        The image's width and height in pixels.
    """
    w, h = _size(size)
    a, b, px, py = lens
    return np.array([[a * w, 0.0, px * w - 0.5], [0.0, b * h, py * h - 0.5], [0.0, 0.0, 1.0]])


def projection_from_lens(lens: tuple[float, float, float, float], near: float,
                         far: float) -> NDArray[np.float64]:
    """View-to-clip ``(4, 4)`` (column vectors, OpenGL's axes and depth range) of a camera
    whose lens is ``lens``: a pixel centre's ray lands on that pixel's centre, OpenCV's
    way -- x_ndc = 2 fx/W x/(-z) + 2 (cx + 0.5)/W - 1, y_ndc its mirror (rows run down).

    Parameters
    ----------
    lens : (float, float, float, float)
        ``(fx / W, fy / H, (cx + 0.5) / W, (cy + 0.5) / H)``.
    near, far : float
        The clip distances along the view axis, 0 < near < far.
    """
    a, b, px, py = lens
    m = np.zeros((4, 4))
    m[0, 0], m[0, 2] = 2 * a, 1 - 2 * px
    m[1, 1], m[1, 2] = 2 * b, 2 * py - 1
    m[2, 2], m[2, 3] = -(far + near) / (far - near), -2 * far * near / (far - near)
    m[3, 2] = -1.0
    return m
