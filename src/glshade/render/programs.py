"""Specialised programs: what a draw needs is compiled into its program as ``#define`` lines --
the number and kinds of lights, sRGB encoding, an orthographic view, two-sided lighting,
auxiliary outputs -- so no shader pays at every pixel for a branch on a uniform (which a
software rasterizer evaluates on both sides). Programs are compiled lazily and cached by
:class:`ProgramKey`; uniforms are written only when their value changed."""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..modes import LightingModel, ShadingMode
from ..scene.lights import DirectionalLight

__all__ = ["ProgramKey", "Variant", "Forward", "Role", "light_kind", "UniformWriter",
           "material_uniforms",
           "MaterialUniforms", "flat_constants_fit", "FLAT_CONSTANTS_PIXELS"]


class Forward(enum.Enum):
    """Where a shadowed draw's fragments find each light's visibility: in the shadow pass's
    visibility array (``ARRAY``, drawn from a G-buffer first) or themselves, at their own
    point, as they shade: ``MAPS`` looked up (SHADOW_MAPS_FORWARD), ``RAYS`` traced
    (SHADOW_RAYS_FORWARD)."""

    ARRAY = "array"
    MAPS = "maps"
    RAYS = "rays"


class Role(enum.Enum):
    """What a model's draw is for: an opaque surface's, or a transparent one's --
    ``CAPTURE`` (into per-pixel fragment lists through storage-buffer atomics), ``FETCH``
    (the same, counted through framebuffer fetch, OIT_FETCH), ``PEEL_DEPTH`` and ``PEEL`` (a
    layer's depth, then its colour, in depth peeling where the GL has no storage buffers:
    OIT_PEEL) or ``BLEND`` (its opacity as
    alpha, blended in drawing order)."""

    OPAQUE = "opaque"
    CAPTURE = "capture"
    FETCH = "fetch"
    PEEL = "peel"
    PEEL_DEPTH = "peel-depth"
    BLEND = "blend"


def light_kind(light) -> str:
    """The GLSL kind of a light: DIRECTIONAL, POINT, ATTENUATED (a point light whose
    intensity falls off with distance, or ends at its range) or SPOT (a cone, with its
    attenuation and range).

    Parameters
    ----------
    light : PointLight, SpotLight or DirectionalLight
        The light.
    """
    if isinstance(light, DirectionalLight):
        return "DIRECTIONAL"
    if hasattr(light, "spot_vector"):
        return "SPOT"
    plain = tuple(light.attenuation) == (1.0, 0.0, 0.0) and light.range is None
    return "POINT" if plain else "ATTENUATED"


def lighting_products(material, lights, ambient, colors=None):
    """The lighting formula's per-draw products: ``(Ia ka C (K, 3), Ip kd C (K, L, 3)
    float32, Ip ks (L, 3) float32)`` for the material (K = 1) or for each of ``colors`` in
    place of its colour (an instanced draw's rows: the same products, so the same bits).
    ``illum`` 1 drops the specular products; 0 makes the diffuse colour the whole
    (ambient) term, unlit.

    Parameters
    ----------
    material : Material
        The surface.
    lights : sequence
        The draw's lights.
    ambient : array_like
        ``(3,)`` the scene's ambient intensity.
    colors : array_like or None
        ``(K, 3)`` colours in place of the material's (None: its own).
    """
    ip = np.array([np.asarray(x.color) * x.intensity for x in lights], np.float64)
    ka, kd = material.coefficients(colors)
    diffuse = (ip[None] * kd[:, None]).astype("f4")
    specular = (ip * np.asarray(material.specular_rgb, np.float64)).astype("f4")
    ambient_term = np.asarray(ambient, np.float64) * ka
    if material.illum < 2:
        specular[:] = 0
    if material.illum == 0:
        ambient_term, diffuse[:] = kd, 0
    return ambient_term, diffuse, specular


def material_uniforms(material, lights, ambient) -> list:
    """The lighting formula's per-draw products for one material: Ia ka C, and per light
    Ip kd C and Ip ks (lighting.glsl multiplies them by the per-pixel terms) -- with the
    RGB coefficients where the material has them. ``illum`` 1 drops the specular
    products; 0 makes the diffuse colour the whole (ambient) term, unlit.

    Parameters
    ----------
    material : Material
        The surface.
    lights : sequence
        The draw's lights.
    ambient : array_like
        ``(3,)`` the ambient intensity.
    """
    if material.lighting is LightingModel.PBR:  # (pbr.glsl: the light's colour x intensity
        # in the specular slot, Ia ka x the base colour the ambient term)
        ip = np.array([np.asarray(x.color) * x.intensity for x in lights], "f4")
        base = np.asarray(material.base_color, np.float64)
        return [("u_ambient_term", tuple(float(x) for x in np.asarray(ambient) *
                                         material.ka * base)),
                ("u_light_diffuse", np.zeros_like(ip).tobytes()),
                ("u_light_specular", ip.tobytes()), ("u_shininess", 0.0),
                ("u_emission", tuple(float(x) for x in material.emission)),
                ("u_pbr_base", (*(float(x) for x in base), float(material.metallic))),
                ("u_pbr_roughness", float(material.roughness))]
    ambient_term, diffuse, specular = lighting_products(material, lights, ambient)
    return [("u_ambient_term", tuple(float(x) for x in ambient_term[0])),
            ("u_light_diffuse", diffuse[0].tobytes()), ("u_light_specular", specular.tobytes()),
            ("u_shininess", float(material.shininess)),
            # (what the surface gives off by itself: added to the lit colour, unshadowed;
            # read only by the programs compiled EMISSIVE)
            ("u_emission", tuple(float(x) for x in material.emission))]


class MaterialUniforms:
    """:func:`material_uniforms`, cached per (material, lights, ambient): shared by the
    passes of one Renderer, so a material lit the same way is computed once.

    Parameters
    ----------
    limit : int
        The most entries kept.
    """

    def __init__(self, limit: int = 1024):
        self._cache: dict[tuple, list] = {}
        self.limit = limit

    def __call__(self, material, lights: tuple, ambient) -> list:
        key = (material, lights, ambient)
        found = self._cache.get(key)
        if found is None:
            if len(self._cache) > self.limit:
                self._cache.clear()
            found = self._cache[key] = material_uniforms(material, lights, ambient)
        return found

    def clear(self) -> None:
        self._cache.clear()


#: viewport pixels per triangle from which a model's Phong program takes its lighting
#: constants as flat varyings (on a software rasterizer). Below it the triangle setup they
#: add costs more than the uniform loads they save (measured: docs/guide/speed.md).
FLAT_CONSTANTS_PIXELS = 128


def flat_constants_fit(mode: ShadingMode, aux: bool, lights: tuple, max_vectors: int,
                       textured: bool = False, colored: bool = False,
                       normal_map: bool = False) -> bool:
    """Whether a Phong program's lighting constants fit the driver's varyings alongside its
    own (position, normal and, with aux outputs, the world normal): one vector for ambient
    and n, then per light its position, diffuse and specular (and attenuation).

    Parameters
    ----------
    mode : ShadingMode
        The shading mode (only Phong's fit).
    aux : bool
        The program writes the auxiliary outputs.
    lights : tuple of str
        The lights' kinds.
    max_vectors : int
        The driver's varying vectors.
    textured : bool
        The program reads texture coordinates.
    colored : bool
        The program reads vertex colours.
    normal_map : bool
        The program interpolates a tangent frame (a PBRMaterial's normal map).
    """
    if mode is not ShadingMode.PHONG:
        return False
    per_light = 3 + ("ATTENUATED" in lights or "SPOT" in lights) + ("SPOT" in lights)
    own = 2 + bool(aux) + bool(textured) + bool(colored) + bool(normal_map)
    return own + 1 + per_light * len(lights) <= max_vectors


#: the shading modes that show a material's textures (the others show geometry)
TEXTURED_MODES = (ShadingMode.FLAT, ShadingMode.GOURAUD, ShadingMode.PHONG)

#: a pixel's own slots for its first transparent fragments (the rest: a shared pool)
OIT_SLOTS = 8


class Variant(NamedTuple):
    """What every program of one draw shares (the rest of a ProgramKey is per model).

    Parameters
    ----------
    mode : ShadingMode
        The shading mode.
    aux : bool
        Whether the draw writes the auxiliary outputs (normals, ids, depth).
    lights : tuple of str
        Each light's GLSL kind (:func:`light_kind`).
    srgb : bool
        Encode the output as sRGB.
    orthographic : bool
        An orthographic camera (the view direction is constant).
    shadows : bool
        The draw casts shadows.
    forward : Forward
        Where shadows are found (array, maps, rays).
    environment : bool
        The scene has an environment: glTF's model is lit by it too (image-based light).
    """

    mode: ShadingMode
    aux: bool
    lights: tuple
    srgb: bool
    orthographic: bool
    #: each light's term is weighed by its visibility at the pixel (a shadow pass's)
    shadows: bool = False
    #: ... found where (:class:`Forward`; ARRAY when the draw has no shadows)
    forward: Forward = Forward.ARRAY
    #: the scene's sky lights glTF's model (environment_light.glsl)
    environment: bool = False


@dataclass(frozen=True)
class ProgramKey:
    """Everything that selects a compiled program variant.

    Parameters
    ----------
    mode : ShadingMode
        The shading mode.
    aux : bool
        Whether the draw writes the auxiliary outputs (normals, ids, depth).
    lights : tuple of str
        Each light's GLSL kind (:func:`light_kind`).
    srgb : bool
        Encode the output as sRGB.
    orthographic : bool
        An orthographic camera (the view direction is constant).
    two_sided : bool
        Light back faces as seen (else cull them).
    flat_constants : bool
        Phong's lighting constants as flat varyings.
    shadows : bool
        The draw casts shadows.
    oit : Role
        The transparency pass's role of the program (or opaque).
    textured : bool
        The material has texture maps.
    forward : Forward
        Where shadows are found (array, maps, rays).
    instanced : bool
        One draw of many instances, each its own row of transforms and colour
        (instances.glsl).
    fetch : bool
        A big mesh's draw over shared vertices: its polygon ids found per triangle in a
        table (polygon_fetch.glsl), flat's polygon lit once a triangle by flat.geom.
    colored : bool
        The mesh's colours are the notes' C (surface_color.glsl): per vertex, or a
        polygon's mean in flat shading.
    emissive : bool
        The material gives off light of its own, added to the lit colour.
    lighting : LightingModel
        The lighting model the schemes evaluate (the material's).
    normal_map : bool
        A PBRMaterial's normal map is read (with its other maps).
    environment : bool
        glTF's model is lit by the scene's sky too (environment_light.glsl).
    """

    mode: ShadingMode
    aux: bool = False
    lights: tuple = ("POINT",)
    srgb: bool = False
    orthographic: bool = False
    two_sided: bool = True
    #: Phong's lighting constants reach the fragment stage as flat varyings (constants.glsl)
    flat_constants: bool = False
    shadows: bool = False
    #: an opaque surface's draw or a transparent one's (:class:`Role`)
    oit: Role = Role.OPAQUE
    #: the surface has texture coordinates and its material's maps are sampled (textures.glsl)
    textured: bool = False
    #: where the fragment stage finds its lights' visibility (:class:`Forward`)
    forward: Forward = Forward.ARRAY
    #: an instanced draw: each instance's matrices, first id and colour from its row
    instanced: bool = False
    #: a big mesh's draw: polygons per triangle from a table, no per-corner copies
    fetch: bool = False
    #: the mesh's colours multiply the material's (surface_color.glsl)
    colored: bool = False
    #: the material's emission is added to the lit colour (outputs.glsl)
    emissive: bool = False
    #: the lighting model evaluated (the notes' or glTF's: pbr.glsl)
    lighting: LightingModel = LightingModel.NOTES
    #: a PBRMaterial's tangent-space normal map bends the normal where the scheme lights
    normal_map: bool = False
    #: glTF's model lit by the scene's sky (image-based light by the split sum)
    environment: bool = False

    @classmethod
    def of(cls, variant: Variant, *, two_sided: bool = True,
           flat_constants: bool = False, oit: Role = Role.OPAQUE,
           textured: bool = False, instanced: bool = False,
           fetch: bool = False, colored: bool = False, emissive: bool = False,
           lighting: LightingModel = LightingModel.NOTES,
           normal_map: bool = False) -> ProgramKey:
        """The key of a draw's variant for one model.

        Parameters
        ----------
        variant : Variant
            What the draw's programs share.
        two_sided : bool
            Light back faces as seen.
        flat_constants : bool
            Phong's lighting constants as flat varyings.
        oit : Role
            The transparency pass's role.
        textured : bool
            The material has texture maps.
        instanced : bool
            One draw of many instances.
        fetch : bool
            A big mesh's draw: polygons found per triangle (opaque draws only).
        colored : bool
            The mesh's colours multiply the material's.
        emissive : bool
            The material's emission is added.
        lighting : LightingModel
            The material's lighting model.
        normal_map : bool
            A PBRMaterial's normal map is read.
        """
        # (a transparent surface neither casts nor receives shadows: its light is unshadowed)
        opaque = oit is Role.OPAQUE
        return cls(variant.mode, variant.aux and opaque, variant.lights, variant.srgb,
                   variant.orthographic, two_sided, flat_constants,
                   variant.shadows and opaque, oit, textured and variant.mode in TEXTURED_MODES,
                   variant.forward if variant.shadows and opaque else Forward.ARRAY,
                   instanced, fetch and opaque, colored and variant.mode in TEXTURED_MODES,
                   # (a textured PBRMaterial's emission is its map's: pbr.glsl adds it)
                   emissive and variant.mode in TEXTURED_MODES and not (
                       textured and lighting is LightingModel.PBR),
                   lighting if variant.mode in TEXTURED_MODES else LightingModel.NOTES,
                   normal_map and textured and variant.mode in TEXTURED_MODES
                   and lighting is LightingModel.PBR,
                   variant.environment and variant.mode in TEXTURED_MODES
                   and lighting is LightingModel.PBR)

    def defines(self) -> tuple[str, ...]:
        forward = self.forward is not Forward.ARRAY
        world = self.aux or self.mode is ShadingMode.NORMALS or forward
        flat = self.flat_constants and self.mode is ShadingMode.PHONG
        capture = self.oit in (Role.CAPTURE, Role.FETCH)
        flags = (("GLSHADE_AUX_OUTPUTS", self.aux), ("WORLD_NORMALS", world), ("SRGB", self.srgb),
                 ("ORTHOGRAPHIC", self.orthographic), ("TWO_SIDED", self.two_sided),
                 ("FLAT_CONSTANTS", flat),
                 ("ANY_ATTENUATED", "ATTENUATED" in self.lights or "SPOT" in self.lights),
                 ("ANY_SPOT", "SPOT" in self.lights),
                 ("SHADOW_MASK", self.shadows), ("OIT_CAPTURE", capture),
                 ("OIT_FETCH", self.oit is Role.FETCH),
                 ("GLSL_430", capture or self.forward is Forward.RAYS),
                 # (a sampler array indexed in a loop: GLSL 4.00, what every Mac has)
                 ("GLSL_410", self.forward is Forward.MAPS and not capture),
                 ("OIT_BLEND", self.oit is Role.BLEND),
                 ("OIT_PEEL", self.oit in (Role.PEEL, Role.PEEL_DEPTH)),
                 ("OIT_PEEL_DEPTH", self.oit is Role.PEEL_DEPTH),
                 ("TEXTURED", self.textured),
                 ("NOTES_TEXTURED", self.textured and self.lighting is LightingModel.NOTES),
                 ("PBR_TEXTURED", self.textured and self.lighting is LightingModel.PBR),
                 ("PBR_NORMAL_MAP", self.normal_map),
                 ("VERTEX_COLORS", self.colored), ("EMISSIVE", self.emissive),
                 ("PBR", self.lighting is LightingModel.PBR),
                 ("ENVIRONMENT_LIGHT", self.environment),
                 ("SHADOW_MAPS_FORWARD", self.forward is Forward.MAPS),
                 ("SHADOW_RAYS_FORWARD", self.forward is Forward.RAYS),
                 ("INSTANCED", self.instanced),
                 ("POLYGON_FETCH", self.fetch and self.mode is not ShadingMode.FLAT),
                 ("FLAT_FETCH", self.fetch and self.mode is ShadingMode.FLAT))
        out = [name for name, on in flags if on]
        if capture:
            out.append(f"OIT_SLOTS {OIT_SLOTS}")
        if self.fetch:
            from .gpu_mesh import POLYGON_ROW_WIDTH

            out.append(f"POLYGON_ROW_WIDTH {POLYGON_ROW_WIDTH}")
        out.append(f"LIGHT_COUNT {len(self.lights)}")
        out.append(f"LIGHT_KINDS {', '.join(self.lights)}")
        return tuple(out)


class UniformWriter:
    """Writes uniforms, skipping any whose value is the one last written to that program
    (a camera move changes a few matrices; materials and lights mostly stay)."""

    _ABSENT = (None, 0)

    def __init__(self):
        self._last: dict[tuple[int, str], object] = {}
        # (program, name) -> (member, bytes it holds) or _ABSENT: optimised away
        self._members: dict[tuple[int, str], tuple] = {}

    def put(self, prog, name: str, value) -> None:
        """Write ``value`` to ``prog``'s uniform ``name`` unless it holds it already (a name the

        Parameters
        ----------
        compiler dropped is skipped; an array is fitted to the member's size).
        prog : moderngl.Program
            The program.
        name : str
            The uniform.
        value : object
            A number, a tuple, bytes or an ndarray.
        """
        key = (id(prog), name)
        found = self._members.get(key)
        if found is None:  # (moderngl's `in` walks every member: look each up once)
            names = set(prog)
            if name in names:
                member = prog[name]
                found = (member, member.array_length * member.dimension * 4)
            else:
                found = self._ABSENT
            self._members[key] = found
        member, size = found
        if member is None:
            return
        if isinstance(value, np.ndarray):
            value = value.tobytes()
        if isinstance(value, bytes):
            # an array the program uses only in part (2 of 8 lights) is shortened to it; one
            # the driver kept whole is padded with zeros
            value = value[:size] if len(value) >= size else value.ljust(size, b"\0")
            if self._last.get(key) != value:
                member.write(value)
                self._last[key] = value
        elif self._last.get(key) != value:
            member.value = value
            self._last[key] = value

    def forget(self) -> None:
        """Drop what was remembered (programs were released; their ids may be reused)."""
        self._last.clear()
        self._members.clear()
