"""glTF 2.0's metallic-roughness material: the lighting model modern assets are authored for,
beside the notes' (:class:`~glshade.Material`). The same three schemes -- flat, Gouraud,
Phong -- evaluate either; ``shaders/include/pbr.glsl`` holds its BRDF, the specification's
Appendix B, and ``cpu/lighting.py`` its numpy twin."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import SceneError
from ..modes import LightingModel
from .material import color3, nonnegative
from .texture import Texture, texture_field

__all__ = ["PBRMaterial"]

#: glTF's maps, the fields that hold them
_MAPS = ("base_color_texture", "metallic_roughness_texture", "occlusion_texture",
         "emissive_texture", "normal_texture")


def _unit(value, name: str) -> float:
    v = nonnegative(value, name)
    if v > 1:
        raise SceneError(f"{name} must be in [0, 1], got {v:g}")
    return v


@dataclass(frozen=True)
class PBRMaterial:
    """glTF 2.0's metallic-roughness material, lit by the BRDF of the glTF 2.0
    specification's Appendix B: Fresnel by Schlick with ``F0 = mix(0.04, base_color,
    metallic)``, the Trowbridge-Reitz (GGX) distribution with ``alpha = roughness^2``, the
    height-correlated Smith visibility term, and the diffuse lobe ``(1 - F)(1 - metallic)
    base_color / pi``. Lights act as glTF defines: outgoing radiance = BRDF x colour x
    intensity x cos(theta), the intensity in lux for a directional light and candela / d^2
    for point and spot lights (their ``attenuation`` is the notes' model's, not used here).
    glTF's model has no ambient term; the scene's ambient light ``Ia`` adds
    ``ka x Ia x base_color``, with the notes' coefficient ``ka`` (0.2, as for a Material, so
    that a scene's default ambient light lights both models alike; ``ka=1`` is pyrender's
    ``ambient_light x base colour``). ``emissive`` adds as it is.

    A mesh's colours (:attr:`Mesh.colors`) multiply ``base_color`` (glTF's ``COLOR_0``), and
    their alpha the opacity, unless ``vertex_colors=False``.

    Parameters
    ----------
    base_color : tuple
        Linear RGB, each in [0, 1] (glTF's baseColorFactor).
    metallic : float
        In [0, 1]: 0 a dielectric, 1 a metal.
    roughness : float
        Perceptual roughness in [0, 1] (alpha = roughness^2).
    emissive : tuple
        Linear RGB radiance the surface gives off, each >= 0 (glTF's emissiveFactor).
    opacity : float
        In [0, 1] (glTF's base colour alpha); below 1 the surface is transparent.
    ka : float
        In [0, 1]: how much of the scene's ambient light it reflects, times its base colour.
    vertex_colors : bool
        Whether the colours a mesh carries multiply ``base_color``.
    name : str or None
        Its name in its file.
    base_color_texture, metallic_roughness_texture, occlusion_texture, emissive_texture, \
normal_texture : Texture or None
        glTF's maps (a Texture or an image path), at the mesh's texture coordinates: the
        base colour (sRGB; multiplies ``base_color``, its alpha the opacity), roughness in
        the green channel and metallic in the blue (linear; multiplying ``roughness`` and
        ``metallic``), occlusion in the red (multiplying the ambient light), the emissive
        colour (sRGB; multiplying ``emissive``), and a tangent-space normal map (linear,
        ``2 x texel - 1`` in the frame of increasing u, increasing v and the normal, the
        tangents from the texture coordinates). Read where the scheme lights: at every pixel
        (Phong), at the vertices (Gouraud), once at a polygon's centre (flat).
    """

    base_color: tuple = (1.0, 1.0, 1.0)
    metallic: float = 1.0
    roughness: float = 1.0
    emissive: tuple = (0.0, 0.0, 0.0)
    opacity: float = 1.0
    ka: float = 0.2
    vertex_colors: bool = True
    name: str | None = None
    base_color_texture: Texture | None = None
    metallic_roughness_texture: Texture | None = None
    occlusion_texture: Texture | None = None
    emissive_texture: Texture | None = None
    normal_texture: Texture | None = None

    #: the lighting model it is written for (the programs it is drawn with)
    lighting = LightingModel.PBR

    def __post_init__(self):
        base = color3(self.base_color, "base_color")
        if max(base) > 1:
            raise SceneError(f"base_color must be 3 numbers in [0, 1] (a surface reflects at "
                             f"most what arrives), got {base}")
        object.__setattr__(self, "base_color", base)
        object.__setattr__(self, "metallic", _unit(self.metallic, "metallic"))
        object.__setattr__(self, "roughness", _unit(self.roughness, "roughness"))
        object.__setattr__(self, "emissive", color3(self.emissive, "emissive"))
        object.__setattr__(self, "opacity", _unit(self.opacity, "opacity"))
        object.__setattr__(self, "ka", _unit(self.ka, "ka"))
        if not isinstance(self.vertex_colors, (bool, np.bool_)):
            raise SceneError(f"vertex_colors must be True or False, got {self.vertex_colors!r}")
        object.__setattr__(self, "vertex_colors", bool(self.vertex_colors))
        for name in _MAPS:
            object.__setattr__(self, name, texture_field(getattr(self, name), name))

    @classmethod
    def like(cls, material) -> PBRMaterial:
        """The nearest glTF material to a notes' :class:`~glshade.Material`, to compare the
        two lighting models on one scene (``compare(..., modes=["phong", "pbr-phong"])``):
        its colour C as the base colour, a dielectric (metallic 0: the notes' highlight is
        the light's colour), roughness from the specular exponent n by ``alpha^2 = 2 / (n +
        2)`` (the Phong-to-microfacet correspondence of Walter et al. 2007, alpha =
        roughness^2), its ka, emission, opacity and diffuse map. A PBRMaterial is returned
        as it is.

        Parameters
        ----------
        material : Material or PBRMaterial
            The material.
        """
        if isinstance(material, cls):
            return material
        alpha = float(np.sqrt(2.0 / (material.shininess + 2.0)))
        base = np.clip(np.asarray(material.color, np.float64), 0.0, 1.0)
        return cls(base_color=tuple(base.tolist()), metallic=0.0,
                   roughness=float(np.sqrt(min(alpha, 1.0))), emissive=material.emission,
                   opacity=material.opacity, ka=min(float(material.ka), 1.0),
                   vertex_colors=material.vertex_colors, name=material.name,
                   base_color_texture=material.texture)

    # ------------------------------------------------------------ what every pass asks
    @property
    def emission(self) -> tuple[float, float, float]:
        """``emissive``: what every pass adds to the lit colour (the name Material uses)."""
        return self.emissive

    @property
    def color(self) -> tuple[float, float, float]:
        """``base_color``: the surface's colour where a pass takes one colour (a wireframe's
        lines)."""
        return self.base_color

    @property
    def ambient_rgb(self) -> tuple[float, float, float]:
        """What the scene's ambient light is multiplied by: ``ka x base_color``."""
        r, g, b = (self.ka * np.asarray(self.base_color)).tolist()
        return r, g, b

    @property
    def textures(self) -> dict:
        """Its texture maps by field name."""
        return {name: t for name in _MAPS if (t := getattr(self, name)) is not None}

    @property
    def transparent(self) -> bool:
        return self.opacity < 1.0

    @property
    def diffuse_rgb(self) -> tuple[float, float, float]:
        """The diffuse albedo ``base_color x (1 - metallic)`` (what a diffuse-only reader,
        radiosity, takes)."""
        r, g, b = (np.asarray(self.base_color) * (1.0 - self.metallic)).tolist()
        return r, g, b

    @property
    def rho(self) -> tuple[float, float, float]:
        """The diffuse reflectance radiosity uses: the diffuse albedo."""
        return self.diffuse_rgb
