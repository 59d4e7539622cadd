"""Light from every direction at infinity: a constant colour, or an equirectangular
(latitude-longitude) image of radiance -- what modern assets are lit by, and what the path
tracer samples by importance. No GL.

The map's convention (one home; the tracer's GLSL, ``trace_environment.glsl``, reads it
so): a world direction ``d = (x, y, z)``, +y up, is the image's column ``u W`` and row
``v H`` with ``u = 0.5 + atan2(x, -z) / (2 pi)`` -- the middle column straight ahead of
the default camera, which looks down -z -- and ``v = acos(y) / pi``, row 0 the zenith.
``rotation`` turns the map about +y by that many radians (counter-clockwise seen from
above): a direction is looked up turned back by it."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import SceneError

__all__ = ["Environment"]

#: the image a constant colour is sampled as (the tracer's choice of direction is by this
#: grid's rows, each weighted by its solid angle: coarse is enough for one colour)
CONSTANT_GRID = (32, 16)


@dataclass(frozen=True, eq=False)
class Environment:
    """Radiance arriving from infinitely far away, in every direction: the sky.

    Parameters
    ----------
    image : array_like
        ``(3,)`` a constant linear RGB radiance, or ``(H, W, 3)`` an equirectangular image
        of linear radiance (W = 2 H is usual; the module's header gives the mapping).
    intensity : float
        A factor on it, >= 0.
    rotation : float
        Radians the map turns about +y.

    Examples
    --------
    >>> sky = Environment((0.6, 0.7, 0.9), intensity=1.5)
    >>> sky.radiance.shape
    (16, 32, 3)
    """

    image: ArrayLike
    intensity: float = 1.0
    rotation: float = 0.0
    #: whether it is one colour (``image`` was ``(3,)``)
    constant: bool = field(init=False, default=False)

    def __post_init__(self):
        a = np.asarray(self.image, dtype=np.float64)
        constant = a.shape == (3,)
        if constant:
            a = np.broadcast_to(a, (*CONSTANT_GRID[::-1], 3)).copy()
        if a.ndim != 3 or a.shape[2] != 3 or a.shape[0] < 1 or a.shape[1] < 1:
            raise SceneError(f"an environment is (r, g, b) or an (H, W, 3) image, got shape "
                             f"{np.shape(self.image)}")
        if not np.isfinite(a).all() or (a < 0).any():
            raise SceneError("an environment's radiance must be finite and >= 0")
        intensity = float(self.intensity)
        if not (math.isfinite(intensity) and intensity >= 0):
            raise SceneError(f"environment intensity must be >= 0, got {self.intensity!r}")
        rotation = float(self.rotation)
        if not math.isfinite(rotation):
            raise SceneError(f"environment rotation must be a finite angle, got "
                             f"{self.rotation!r}")
        a.setflags(write=False)
        object.__setattr__(self, "image", a)
        object.__setattr__(self, "intensity", intensity)
        object.__setattr__(self, "rotation", rotation)
        object.__setattr__(self, "constant", constant)

    @classmethod
    def from_file(cls, path, intensity: float = 1.0, rotation: float = 0.0) -> Environment:
        """An environment from an equirectangular image file: ``.npy`` (an ``(H, W, 3)``
        array of linear radiance), or Radiance ``.hdr`` and OpenEXR ``.exr`` through OpenCV
        (``pip install opencv-python-headless``; its channels are BGR, turned to RGB here).

        Parameters
        ----------
        path : str or Path
            The image.
        intensity : float
            A factor on it, >= 0.
        rotation : float
            Radians the map turns about +y.
        """
        from pathlib import Path

        from ..errors import InputError

        path = Path(path)
        if not path.is_file():
            raise InputError(f"{path}: no such environment image")
        suffix = path.suffix.lower()
        if suffix == ".npy":
            image = np.load(path, allow_pickle=False)
        elif suffix in (".hdr", ".exr"):
            image = _read_hdr(path)
        else:
            raise InputError(f"{path}: an environment image is .hdr, .exr or .npy, got "
                             f"{suffix or 'no extension'}")
        try:
            return cls(image, intensity, rotation)
        except SceneError as exc:
            raise InputError(f"{path}: {exc}") from None

    @property
    def radiance(self) -> NDArray[np.float64]:
        """``(H, W, 3)`` the map's radiance, intensity applied."""
        return np.asarray(self.image) * self.intensity

    def __repr__(self) -> str:
        image = np.asarray(self.image)
        h, w, _ = image.shape
        what = (f"({', '.join(f'{x:g}' for x in image[0, 0])})" if self.constant
                else f"{w}x{h} image")
        return (f"Environment({what}, intensity={self.intensity:g}"
                f"{f', rotation={self.rotation:g}' if self.rotation else ''})")


def _read_hdr(path) -> np.ndarray:
    """A Radiance or OpenEXR image as ``(H, W, 3)`` float linear RGB, through OpenCV (the
    maintained reader of both; OpenEXR switched on for it by its environment variable)."""
    import os

    from ..errors import InputError

    os.environ.setdefault("OPENCV_IO_ENABLE_OPENEXR", "1")
    try:
        import cv2
    except ImportError:
        raise InputError(f"{path}: reading .hdr and .exr needs OpenCV (pip install "
                         "opencv-python-headless), or give the image as an array") from None
    image = cv2.imread(str(path), cv2.IMREAD_UNCHANGED | cv2.IMREAD_ANYDEPTH)
    if image is None or image.ndim != 3 or image.shape[2] < 3:
        raise InputError(f"{path}: OpenCV could not read it as an RGB image")
    return np.ascontiguousarray(image[..., 2::-1], np.float64)


# ---------------------------------------------------------------- image-based lighting
# The rasterizer lights glTF's model with an environment by the split-sum approximation
# (Karis 2013, as glTF's sample viewer and every real-time engine): the light reflected is
#   (F0 A + B) x the sky prefiltered by the GGX lobe about the mirror direction
#   + (1 - metallic) base (1 - (F0 A_d + B_d)) x the irradiance's mean radiance,
# with A, B the specular lobe's directional albedo split by Schlick's Fresnel and A_d, B_d
# the diffuse lobe's (1 - F) the same way (exact for a constant sky). These are the tables,
# in the map's frame (rotation is the shader's); render/passes/environment.py uploads them,
# shaders/include/environment_light.glsl reads them.

#: the prefiltered sky's largest level (W x H; each rougher level half the last, roughness
#: k / (IBL_LEVELS - 1) at level k) and its levels
IBL_SIZE, IBL_LEVELS = (128, 64), 6
#: the irradiance map's size and the split-sum table's (view cosine x roughness)
IRRADIANCE_SIZE, SPLIT_SUM_SIZE = (32, 16), 32


def map_frame(rotation: float) -> np.ndarray:
    """``(3, 3)`` the rotation taking world directions to the map's frame (the map turned
    by ``rotation`` radians about +y: a direction turned back by it).

    Parameters
    ----------
    rotation : float
        The map's turn about +y, radians.
    """
    c, s = np.cos(rotation), np.sin(rotation)
    return np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])


def map_directions(width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """``(H, W, 3)`` the map-frame directions of an equirectangular grid's texel centres
    (the module's convention) and ``(H, W)`` each texel's solid angle (steradians).

    Parameters
    ----------
    width, height : int
        The grid's size.
    """
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    phi, theta = np.meshgrid((u - 0.5) * 2 * np.pi, v * np.pi)
    d = np.stack([np.sin(theta) * np.sin(phi), np.cos(theta), -np.sin(theta) * np.cos(phi)], -1)
    return d, (2 * np.pi / width) * (np.pi / height) * np.sin(theta)


def _resampled(image: np.ndarray, width: int, height: int) -> np.ndarray:
    """``image`` (H, W, 3) at ``width x height``: block means where it divides, else the
    nearest texels."""
    h, w, _ = image.shape
    if h % height == 0 and w % width == 0 and h >= height:
        return image.reshape(height, h // height, width, w // width, 3).mean((1, 3))
    rows = np.minimum(((np.arange(height) + 0.5) * h / height).astype(int), h - 1)
    cols = np.minimum(((np.arange(width) + 0.5) * w / width).astype(int), w - 1)
    return image[rows][:, cols]


def prefiltered(environment: Environment) -> list[np.ndarray]:
    """The sky prefiltered for each roughness level: level k ``(H0 / 2^k, W0 / 2^k, 3)``
    is the radiance averaged about each direction R with the GGX lobe of roughness
    ``k / (IBL_LEVELS - 1)`` (n = v = R, weighted by D(h) max(R.l, 0) over solid angle);
    level 0 the sky itself (a mirror).

    Parameters
    ----------
    environment : Environment
        The sky.
    """
    w0, h0 = IBL_SIZE
    source = _resampled(environment.radiance, w0, h0)
    d_in, omega = map_directions(w0, h0)
    d_in, radiance = d_in.reshape(-1, 3), source.reshape(-1, 3) * omega.reshape(-1, 1)
    weight_in = omega.reshape(-1)
    levels = [source]
    for k in range(1, IBL_LEVELS):
        alpha = max((k / (IBL_LEVELS - 1)) ** 2, 1e-3)
        w, h = max(w0 >> k, 2), max(h0 >> k, 1)
        d_out, _ = map_directions(w, h)
        d_out = d_out.reshape(-1, 3)
        out = np.empty((len(d_out), 3))
        for start in range(0, len(d_out), 256):  # (blocks of outputs: bounded memory)
            r = d_out[start:start + 256]
            c = r @ d_in.T  # (R.l)
            cos_h = np.sqrt(np.clip((1 + c) / 2, 0, 1))  # (R.h: h halfway to R)
            den = cos_h ** 2 * (alpha ** 2 - 1) + 1
            lobe = alpha ** 2 / (np.pi * den ** 2) * np.maximum(c, 0)
            out[start:start + 256] = (lobe @ radiance) / np.maximum(lobe @ weight_in,
                                                                   1e-300)[:, None]
        levels.append(out.reshape(h, w, 3))
    return levels


def irradiance(environment: Environment) -> np.ndarray:
    """``(H, W, 3)`` the irradiance about each direction n over pi (the mean radiance a
    Lambertian surface facing n receives, weighted by the cosine), on IRRADIANCE_SIZE.

    Parameters
    ----------
    environment : Environment
        The sky.
    """
    w0, h0 = IBL_SIZE
    d_in, omega = map_directions(w0, h0)
    radiance = (_resampled(environment.radiance, w0, h0) * omega[..., None]).reshape(-1, 3)
    d_out, _ = map_directions(*IRRADIANCE_SIZE)
    cos = np.maximum(d_out.reshape(-1, 3) @ d_in.reshape(-1, 3).T, 0)
    return (cos @ radiance / np.pi).reshape(IRRADIANCE_SIZE[1], IRRADIANCE_SIZE[0], 3)


def split_sum_table(n: int = SPLIT_SUM_SIZE, k: int = 64) -> np.ndarray:
    """``(n, n, 4)`` float32: at view cosine ``i / (n - 1)`` (column i) and roughness
    ``j / (n - 1)`` (row j) -- both ends in the table, read by the shader at texel centres
    -- the specular lobe's directional albedo split by Schlick's
    Fresnel, ``A`` (times F0) and ``B``, and the diffuse lobe's (1 - F), ``A_d`` and
    ``B_d`` (albedo = 1 - (F0 A_d + B_d)) -- Appendix B's D and height-correlated V,
    integrated by a stratified k x k grid drawn from GGX's half-vector density (each
    roughness's lobe resolved) and, for the diffuse lobe, by the cosine's.

    Parameters
    ----------
    n : int
        The table's side.
    k : int
        The quadrature's strata a side.
    """
    xi = (np.arange(k) + 0.5) / k
    grid = np.meshgrid(xi, xi, indexing="ij")
    x1, x2 = grid[0].reshape(-1), grid[1].reshape(-1)
    phi = 2 * np.pi * x2
    out = np.zeros((n, n, 4))
    for i, mu in enumerate(np.maximum(np.arange(n) / (n - 1), 1e-4)):
        v = np.array([np.sqrt(1 - mu * mu), 0.0, mu])
        # the diffuse lobe: l by the cosine, (1 - F(v.h)) split
        st, ct = np.sqrt(x1), np.sqrt(1 - x1)
        lv = np.stack([st * np.cos(phi), st * np.sin(phi), ct], -1)
        hv = lv + v
        hv /= np.linalg.norm(hv, axis=1, keepdims=True)
        s5 = (1 - np.clip(hv @ v, 0, 1)) ** 5
        out[i, :, 2], out[i, :, 3] = (1 - s5).mean(), s5.mean()
        for j, rough in enumerate(np.arange(n) / (n - 1)):
            a2 = max(rough ** 2, 1e-3) ** 2
            cos_h = np.sqrt((1 - x1) / (1 + (a2 - 1) * x1))  # (GGX's half-vector draw)
            sin_h = np.sqrt(1 - cos_h ** 2)
            h = np.stack([sin_h * np.cos(phi), sin_h * np.sin(phi), cos_h], -1)
            vh = h @ v
            l_ = 2 * vh[:, None] * h - v
            nl = l_[:, 2]
            ok = (nl > 0) & (vh > 0)
            nlc = np.maximum(nl, 0)
            vis = 0.5 / (nlc * np.sqrt(mu * mu * (1 - a2) + a2) +
                         mu * np.sqrt(nlc * nlc * (1 - a2) + a2))
            # f cos / pdf(l) with F = 1: D V cos_l / (D cos_h / (4 v.h)) = 4 V cos_l v.h / cos_h
            g = np.where(ok, 4 * vis * nlc * vh / cos_h, 0.0)
            s5 = (1 - np.clip(vh, 0, 1)) ** 5
            out[i, j, 0], out[i, j, 1] = (g * (1 - s5)).mean(), (g * s5).mean()
    return out.transpose(1, 0, 2).astype(np.float32)  # (rows: roughness; columns: mu)
