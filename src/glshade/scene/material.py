"""A surface's reflection coefficients (the notes' ka, kd, ks, n), and the checked colour
and number values that scene data is made of."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from ..errors import SceneError, plain
from ..modes import LightingModel
from .texture import Texture, texture_field

__all__ = ["Material", "color3", "nonnegative", "check_illum"]


#: the largest colour, intensity or coefficient a scene may hold: shading runs in 32-bit
#: floats (largest 3.4e38), and a light's colour x intensity x a surface's colour stays
#: finite there
MAX_SHADING_VALUE = 1e12


def color3(value, name) -> tuple[float, float, float]:
    """An RGB triple of finite numbers from 0 to MAX_SHADING_VALUE, or a SceneError
    naming ``name``.

    Parameters
    ----------
    value : array_like or float
        Three numbers (r, g, b), or one for all three.
    name : str
        What the colour is, for the message.
    """
    c = np.asarray(value, dtype=np.float64)
    if c.shape == ():
        c = np.repeat(c, 3)
    if c.shape != (3,) or not np.isfinite(c).all() or (c < 0).any():
        raise SceneError(f"{name} must be 3 non-negative numbers (r, g, b), got {value!r}")
    if (c > MAX_SHADING_VALUE).any():
        raise SceneError(f"{name} must be 3 numbers from 0 to {MAX_SHADING_VALUE:g} (shading "
                         f"runs in 32-bit floats), got {plain(c)}")
    return float(c[0]), float(c[1]), float(c[2])


def nonnegative(value, name) -> float:
    """A finite number from 0 to MAX_SHADING_VALUE, or a SceneError naming ``name``.

    Parameters
    ----------
    value : float
        The number given.
    name : str
        What it is, for the message.
    """
    v = float(value)
    if not np.isfinite(v) or v < 0:
        raise SceneError(f"{name} must be a non-negative number, got {value!r}")
    if v > MAX_SHADING_VALUE:
        raise SceneError(f"{name} must be at most {MAX_SHADING_VALUE:g} (shading runs in "
                         f"32-bit floats), got {v:g}")
    return v


def check_illum(illum: object) -> int:
    """The one rule for an illumination model (MTL's ``illum``): 0, 1 or 2, a whole
    number (True is not 1).

    Parameters
    ----------
    illum
        The value given.
    """
    if isinstance(illum, bool) or illum not in (0, 1, 2):
        raise SceneError.must("illum", f"be 0 (no lighting), 1 (no specular) or 2, got "
                                       f"{illum!r}")
    return int(illum)


@dataclass(frozen=True)
class Material:
    """The notes' reflection coefficients: ambient ``ka``, diffuse ``kd``, specular ``ks``
    and the specular exponent ``shininess`` (``n``). Ambient and diffuse multiply
    ``color``; specular takes the light's colour.

    For radiosity (diffuse surfaces only): ``emission`` E, the radiosity a surface gives
    off by itself (RGB, any non-negative size), and ``reflectance`` the notes' rho_d
    (RGB, each in [0, 1]); without it, rho_d = kd * color.

    ``opacity`` in [0, 1]: below 1 the surface is transparent, composited "over" what lies
    behind it (:class:`~glshade.DrawOptions` ``transparency``) after the opaque ones.

    The RGB form (as MTL files give it): ``ambient``, ``diffuse``, ``specular`` colours
    (Ka, Kd, Ks) stand in for ``ka * color``, ``kd * color`` and ``ks`` (white) where
    given. ``illum``: 2 the whole formula, 1 no specular term, 0 no lighting at all (the
    diffuse colour as it is). Textures (:class:`~glshade.Texture`), sampled per pixel at the
    mesh's texture coordinates: ``texture`` multiplies the ambient and diffuse colours (it
    is the notes' surface colour C), ``specular_texture`` the specular one,
    ``opacity_texture`` the opacity.

    Parameters
    ----------
    color : tuple
        Linear RGB, each in [0, 1]: what ambient and diffuse reflection multiply.
    ka, kd, ks : float
        The ambient, diffuse and specular coefficients, each in [0, 1].
    shininess : float
        The specular exponent n, >= 0.
    emission : tuple
        RGB radiosity E the surface gives off by itself, each >= 0.
    reflectance : tuple or None
        RGB rho_d for radiosity, each in [0, 1] (None: ``kd * color``).
    opacity : float
        In [0, 1]; below 1 the surface is transparent.
    ambient, diffuse, specular : tuple or None
        Per-channel colours of each term (MTL's Ka, Kd, Ks), overriding ``color`` x the
        coefficient.
    illum : int
        0 no lighting, 1 no specular term, 2 the whole formula.
    texture, specular_texture, opacity_texture : Texture or None
        Maps of the diffuse colour, the specular colour and the opacity.
    name : str or None
        The material's name (an MTL's ``newmtl``).
    vertex_colors : bool
        Whether the colours a mesh carries (:attr:`Mesh.colors`, :attr:`Mesh.face_colors`)
        are its surface colour C, multiplying ``color`` (and the ambient and diffuse
        colours) and, by their alpha, the opacity; False ignores them.
    """

    color: tuple = (0.8, 0.8, 0.8)
    ka: float = 0.2
    kd: float = 0.7
    ks: float = 0.3
    shininess: float = 32.0
    emission: tuple = (0.0, 0.0, 0.0)
    reflectance: tuple | None = None
    opacity: float = 1.0
    ambient: tuple | None = None
    diffuse: tuple | None = None
    specular: tuple | None = None
    illum: int = 2
    texture: Texture | None = None
    specular_texture: Texture | None = None
    opacity_texture: Texture | None = None
    #: the name it has in its file (an MTL ``newmtl``), for reports
    name: str | None = None
    #: whether a mesh's colours (Mesh.colors, Mesh.face_colors) multiply ``color``
    vertex_colors: bool = True

    #: the lighting model it is written for (the programs it is drawn with)
    lighting = LightingModel.NOTES

    def __post_init__(self):
        for name in ("ambient", "diffuse", "specular"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, color3(getattr(self, name), name))
        if not isinstance(self.vertex_colors, (bool, np.bool_)):
            raise SceneError(f"vertex_colors must be True or False, got {self.vertex_colors!r}")
        object.__setattr__(self, "vertex_colors", bool(self.vertex_colors))
        check_illum(self.illum)
        for name in ("texture", "specular_texture", "opacity_texture"):
            object.__setattr__(self, name, texture_field(getattr(self, name), name))
        object.__setattr__(self, "color", color3(self.color, "color"))
        for name in ("ka", "kd", "ks", "shininess"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))
        object.__setattr__(self, "emission", color3(self.emission, "emission"))
        opacity = nonnegative(self.opacity, "opacity")
        if opacity > 1:
            raise SceneError(f"opacity must be in [0, 1] (1: opaque), got {opacity:g}")
        object.__setattr__(self, "opacity", opacity)
        if self.reflectance is not None:
            rho = color3(self.reflectance, "reflectance")
            if max(rho) > 1:
                raise SceneError(f"reflectance must be 3 numbers in [0, 1] (a surface "
                                    f"reflects at most what it receives), got {rho}")
            object.__setattr__(self, "reflectance", rho)

    def coefficients(self, colors=None) -> tuple[np.ndarray, np.ndarray]:
        """The ambient and diffuse coefficients as colours ``(K, 3)`` each: ``ambient``
        and ``diffuse`` where given, else ``ka`` and ``kd`` times the colour -- this
        material's (K = 1), or each of ``colors`` in its place (instances).

        Parameters
        ----------
        colors : array_like or None
            ``(K, 3)`` linear RGB in place of ``color`` (None: ``color``).
        """
        c = np.asarray(self.color if colors is None else colors, np.float64).reshape(-1, 3)
        ambient = np.broadcast_to(np.asarray(self.ambient, np.float64), c.shape) \
            if self.ambient is not None else self.ka * c
        diffuse = np.broadcast_to(np.asarray(self.diffuse, np.float64), c.shape) \
            if self.diffuse is not None else self.kd * c
        return ambient, diffuse

    @property
    def ambient_rgb(self) -> tuple[float, float, float]:
        """The ambient coefficient as a colour: ``ambient``, else ``ka * color``."""
        if self.ambient is not None:
            return self.ambient
        r, g, b = self.coefficients()[0][0].tolist()
        return r, g, b

    @property
    def diffuse_rgb(self) -> tuple[float, float, float]:
        """The diffuse coefficient as a colour: ``diffuse``, else ``kd * color``."""
        if self.diffuse is not None:
            return self.diffuse
        r, g, b = self.coefficients()[1][0].tolist()
        return r, g, b

    @property
    def specular_rgb(self) -> tuple[float, float, float]:
        """The specular coefficient as a colour: ``specular``, else ``ks`` (white)."""
        if self.specular is not None:
            return self.specular
        return (self.ks, self.ks, self.ks)

    @property
    def textures(self) -> dict[str, Any]:
        """The material's textures by field name."""
        return {name: t for name in ("texture", "specular_texture", "opacity_texture")
                if (t := getattr(self, name)) is not None}

    @property
    def rho(self) -> tuple[float, float, float]:
        """The diffuse reflectance rho_d (RGB) radiosity uses."""
        if self.reflectance is not None:
            return self.reflectance
        return self.diffuse_rgb

    @property
    def transparent(self) -> bool:
        return self.opacity < 1.0 or self.opacity_texture is not None

    @classmethod
    def from_values(cls, values: dict) -> Material:
        """A Material from whichever of its fields ``values`` gives; the rest keep the
        dataclass defaults (the one place material defaults live).

        Parameters
        ----------
        values : dict
            Field names to values.
        """
        names = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in values.items() if k in names and v is not None})

