"""GPU copies of textures (scene/texture.py), made on first use and kept while their
Texture lives: colour maps as sRGB textures (the sampler decodes to linear light before it
filters), opacity maps as plain 8-bit ones, and a 1x1 white texture standing in for a map
a material lacks (textures.glsl samples all three maps, without a branch)."""

from __future__ import annotations

import weakref

import moderngl
import numpy as np

from ..errors import SceneError
from .base import GLResource
from .units import Unit

__all__ = ["TextureCache", "MAP_UNITS"]

#: the texture units of the three maps (diffuse, specular, opacity): render/units.py's
MAP_UNITS = {"texture": Unit.MAP_DIFFUSE, "specular_texture": Unit.MAP_SPECULAR,
             "opacity_texture": Unit.MAP_OPACITY}
_UNIFORMS = {"texture": "u_map_diffuse", "specular_texture": "u_map_specular",
             "opacity_texture": "u_map_opacity"}
#: a PBRMaterial's maps: unit, sampler and how the image is read (colour: sRGB decoded;
#: data: linear, as glTF packs roughness, metallic and occlusion)
PBR_MAPS = {"base_color_texture": (Unit.MAP_BASE, "u_pbr_base_map", "colour"),
            "metallic_roughness_texture": (Unit.MAP_METALLIC_ROUGHNESS, "u_pbr_mr_map", "data"),
            "occlusion_texture": (Unit.MAP_OCCLUSION, "u_pbr_occlusion_map", "data"),
            "emissive_texture": (Unit.MAP_EMISSIVE, "u_pbr_emissive_map", "colour"),
            "normal_texture": (Unit.MAP_NORMAL, "u_pbr_normal_map", "data")}
_SRGB8_ALPHA8 = 0x8C43
_FILTERS = {"nearest": (moderngl.NEAREST, moderngl.NEAREST),
            "linear": (moderngl.LINEAR, moderngl.LINEAR),
            "mipmap": (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)}


def opacity_channel(pixels: np.ndarray) -> np.ndarray:
    """An opacity map's values ``(H, W)`` uint8: the image's alpha where it has one (any
    texel below 255), else its red channel (a grey image)."""
    alpha = pixels[..., 3]
    return alpha if (alpha < 255).any() else pixels[..., 0]


class TextureCache(GLResource):
    """The GL textures of one context, by Texture and use (colour or opacity).

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    """

    def __init__(self, context):
        super().__init__(context)
        self._found: dict[tuple, tuple] = {}
        ctx = context.ctx
        self.white = self._keep(ctx.texture((1, 1), 4, bytes([255] * 4)))
        self.max_size = int(ctx.info.get("GL_MAX_TEXTURE_SIZE", 4096))

    def get(self, texture, opacity: bool = False, data: bool = False):
        """The moderngl texture of ``texture`` (made now if need be).

        Parameters
        ----------
        texture : Texture
            The image.
        opacity : bool
            Its use as an opacity map (one channel).
        data : bool
            Its use as data (glTF's roughness, metallic and occlusion): RGBA, linear.
        """
        self._check()
        key = (id(texture), opacity, data)
        found = self._found.get(key)
        if found is not None and found[0]() is texture:
            return found[1]
        if found is not None:  # (an id reused by another Texture: the old one is gone)
            found[1].release()
        w, h = texture.size
        if max(w, h) > self.max_size:
            raise SceneError(f"{texture!r} is {w}x{h} texels; this GL takes at most "
                             f"{self.max_size}x{self.max_size}: scale the image down")
        # rows bottom first: texture coordinate v = 0 is the image's bottom row
        pixels = np.ascontiguousarray(texture.pixels[::-1])
        ctx = self.context.ctx
        if opacity:
            tex = ctx.texture((w, h), 1, np.ascontiguousarray(opacity_channel(pixels)))
        elif data:
            tex = ctx.texture((w, h), 4, pixels.tobytes())
        else:
            tex = ctx.texture((w, h), 4, pixels.tobytes(), internal_format=_SRGB8_ALPHA8)
        tex.filter = _FILTERS[texture.filter]
        if texture.filter == "mipmap":
            tex.build_mipmaps()
        tex.repeat_x = tex.repeat_y = texture.wrap == "repeat"
        self._found[key] = (weakref.ref(texture), tex)
        if len(self._found) > 256:  # (textures no longer alive)
            for k, (ref, t) in list(self._found.items()):
                if ref() is None:
                    t.release()
                    del self._found[k]
        return tex

    def bind(self, material, put, prog) -> None:
        """Bind ``material``'s maps (white where it has none) and point ``prog``'s samplers
        at them.

        Parameters
        ----------
        material : Material
            The surface.
        put : callable
            The uniform writer's ``put``.
        prog : moderngl.Program
            The program.
        """
        textures = self._bind(material, {name: (unit, _UNIFORMS[name], "opacity" if
                                                name == "opacity_texture" else "colour")
                                         for name, unit in MAP_UNITS.items()}, put, prog)
        st = [v for t in textures for v in ((*t.scale, *t.offset) if t is not None else
                                             (1, 1, 0, 0))]
        put(prog, "u_map_st", np.array(st, "f4").tobytes())

    def bind_pbr(self, material, put, prog) -> None:
        """Bind a PBRMaterial's maps (white where it has none) and point ``prog``'s samplers
        at them.

        Parameters
        ----------
        material : PBRMaterial
            The surface.
        put : callable
            The uniform writer's ``put``.
        prog : moderngl.Program
            The program.
        """
        self._bind(material, PBR_MAPS, put, prog)

    def _bind(self, material, maps: dict, put, prog) -> list:
        """Bind each of ``maps`` (field -> (unit, sampler, "colour", "opacity" or "data"))
        of ``material`` (white where it has none); its Textures (None: none), in order."""
        textures = []
        for name, (unit, uniform, use) in maps.items():
            texture = getattr(material, name)
            gl = self.white if texture is None else self.get(
                texture, opacity=use == "opacity", data=use == "data")
            gl.use(location=unit)
            put(prog, uniform, unit)
            textures.append(texture)
        return textures

    def _release_extra(self) -> None:
        for _, tex in self._found.values():
            tex.release()
        self._found.clear()
