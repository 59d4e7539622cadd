"""A scene as a path tracer sees it: world-space triangles, a material per triangle, the
emitting triangles to sample and the scene's lights. Pure numpy, shared by the GPU tracer
and its numpy twin (and nothing else is: each traces rays its own way).

Units: the tracer works in *radiosity units*, pi times radiance, so that a diffuse surface's
pixel is its radiosity B and an emitter's is its ``Material.emission`` E. Reflection follows
the notes' lighting model made energy-conserving: the BRDF is ``rho_d / pi + k_s (n + 2) /
(2 pi) cos^n(alpha)`` (alpha between the mirror direction and the outgoing one), with
``rho_d = Material.rho`` (``kd * color`` unless a reflectance is given). A scene light adds
what the raster formula's diffuse and specular terms take from it: its ``color *
intensity`` is the irradiance it gives a surface facing it (times its attenuation), so the
direct diffuse term equals the renderer's ``kd Ip C (N.L)`` exactly. Ambient light is
ignored: interreflection replaces it. Emission is one-sided (along the polygon's normal, as
radiosity's patches emit); reflection is two-sided."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..errors import SceneError, plain
from ..scene.lights import DirectionalLight

__all__ = ["TraceScene", "MAX_LIGHTS"]

#: scene lights a trace takes (directional and point, each a uniform of the program)
MAX_LIGHTS = 8


@dataclass(frozen=True)
class TraceScene:
    """A scene as the path tracer reads it: world triangles, their materials, emitters
    and lights (made by :meth:`from_scene`, which checks that it can be traced).

    Parameters
    ----------
    triangles : ndarray
        ``(T, 3, 3)`` world positions (float64).
    normals : ndarray
        ``(T, 3)`` unit normals, by the winding.
    areas : ndarray
        ``(T,)`` areas (scene units squared).
    material : ndarray
        ``(T,)`` each triangle's row of ``materials``.
    materials : ndarray
        ``(M, 12)`` rows of rho_d (RGB; glTF's base colour), k_s, n, E (RGB, radiosity
        units), metallic, roughness, 1 for glTF's model (0: the notes'), opacity.
    emitters : ndarray
        ``(K,)`` the emitting triangles' indices.
    emitter_cdf : ndarray
        ``(K,)`` their cumulative chances, by emitted power.
    lights : ndarray
        ``(L, 15)`` rows of kind (0 directional, 1 point, 2 spot), position or direction
        to the light (3), irradiance RGB (3), attenuation (3), a spot's cone (4: its axis
        times the cone's scale, the cone's offset; zero for the others), 1 / range (0:
        none).
    model : ndarray
        ``(T,)`` each triangle's model.
    names : tuple
        The models' names.
    shading : ndarray or None
        ``(T, 3, 3)`` unit normals at the corners (smooth shading, the renderer's vertex
        normals), or None (flat: the triangles' own).
    solids : tuple
        ``(solid, material row)`` pairs: CSG solids ray cast exactly (at most one).
    environment : Environment or None
        The sky (:class:`~glshade.Environment`): seen where rays leave the scene, sampled
        by importance (its radiance x the rows' solid angle) as next-event estimation's
        third kind of light.
    colors : ndarray or None
        ``(T, 3, 3)`` linear RGB at each triangle's corners: colours on geometry, the
        surface colour C multiplying the material's reflectance (rho_d, or glTF's base
        colour), interpolated across the triangle; None: none.
    uvs : ndarray or None
        ``(T, 3, 2)`` texture coordinates at each triangle's corners (None: no map read).
    textures : tuple
        The maps' texels, ``(H, W, 4)`` float32 each (:func:`texture_texels`).
    maps : ndarray or None
        ``(M, 5, 6)`` each material's colour map, glTF's metallic-roughness, emissive and
        normal maps and its opacity map: index
        into ``textures`` (-1: none), sampling (1 if clamped, else repeated, + 2 if the
        nearest texel, else bilinear), the coordinates' scale and offset (u, v).
    tangents : ndarray or None
        ``(T, 4)`` each triangle's dP/du (world) and in w the handedness of (N, dP/du,
        dP/dv): the frame a normal map bends the normal in; None: no normal map.
    """

    triangles: np.ndarray
    normals: np.ndarray
    areas: np.ndarray
    material: np.ndarray
    materials: np.ndarray
    emitters: np.ndarray
    emitter_cdf: np.ndarray
    lights: np.ndarray
    model: np.ndarray
    names: tuple
    shading: np.ndarray | None = None
    #: ((solid, material index),): a CSG solid ray cast exactly (at most one: union them)
    solids: tuple = ()
    environment: object = None
    colors: np.ndarray | None = None
    uvs: np.ndarray | None = None
    textures: tuple = ()
    maps: np.ndarray | None = None
    tangents: np.ndarray | None = None

    @property
    def n_triangles(self) -> int:
        return len(self.triangles)

    @property
    def bounds(self) -> np.ndarray:
        """``(2, 3)`` box of the triangles and the solid (a camera frames it)."""
        t = np.concatenate([self.triangles.reshape(-1, 3)] + [s.bounds for s, _ in self.solids])
        return np.stack([t.min(0), t.max(0)])

    @property
    def size(self) -> float:
        """The diagonal of :attr:`bounds` (for offsets and epsilons)."""
        return float(np.linalg.norm(np.ptp(self.bounds, 0))) or 1.0

    def tables(self, compiled: np.ndarray | None = None) -> tuple[np.ndarray, dict]:
        """The texels ``(rows * width, 4) float32`` the GPU program reads, and where each
        table starts (:func:`glshade.pathtrace.pack.pack`; ``compiled``: ``(T,)`` bool, the
        triangles a tracer compiles into its program, kept out of the hierarchy). Built
        once a scene and choice (the hierarchy of 82k triangles takes 0.4 s) and kept,
        read-only: a tracer made again for the same scene starts at once.

        Parameters
        ----------
        compiled : ndarray or None
            ``(T,)`` bool: triangles kept out of the hierarchy (compiled into the program).
        """
        from .pack import pack

        key = None if compiled is None else np.packbits(compiled).tobytes()
        if key not in self._tables:
            data, layout = pack(self, compiled)
            for a in (data, layout["hierarchy"]):
                a.setflags(write=False)
            self._tables[key] = data, layout
        data, layout = self._tables[key]
        return data, dict(layout)

    @cached_property
    def _tables(self) -> dict:
        return {}

    def small_models(self, limit: int) -> np.ndarray:
        """``(T,)`` bool: the triangles of the scene's smallest models, whole models, at most
        ``limit`` triangles in all (walls, floors, boxes: what a tracer tests cheaply in
        straight-line code beside a hierarchy of the large meshes); none when that would
        leave no model for the hierarchy.

        Parameters
        ----------
        limit : int
            The most triangles in all.
        """
        counts = np.bincount(self.model, minlength=len(self.names))
        chosen = np.zeros(len(counts), bool)
        order = np.argsort(counts, kind="stable")
        total = np.cumsum(counts[order])
        chosen[order[total <= limit]] = True
        chosen &= counts > 0
        if chosen.sum() == (counts > 0).sum():
            chosen[:] = False
        return chosen[self.model]

    @classmethod
    def from_scene(cls, scene, *, lights: bool = True, camera=None,
                   smooth: bool = False) -> TraceScene:
        """Flatten ``scene``'s visible meshes into world triangles and check that they can
        be traced: something emits (an emitting material or a light), every reflectance
        is at most 1 and ``max(rho_d) + k_s <= 1`` (a surface reflects at most what
        arrives). Patch models are taken as their tessellation; a CSG solid (one: union
        several) is ray cast exactly, as its raster pass does, and may not emit.
        ``lights=False`` leaves out the scene's lights (emitting surfaces only, as
        radiosity sees it); given a ``camera``, a scene with neither lights nor emitters
        gets the renderer's headlight (a light at the eye), as ``glshade render`` does.
        ``smooth``: shade with the vertex normals the renderer's Gouraud and Phong modes
        interpolate (what a comparison with them wants), not the flat triangles'.

        Parameters
        ----------
        scene : Scene
            What to trace.
        lights : bool
            Whether the scene's point and directional lights are traced.
        camera : Camera or None
            The headlight's place for a scene with neither lights nor emitters.
        smooth : bool
            Shade with the renderer's vertex normals (else the triangles' own).
        """
        solid_models = [m for m in scene.solids if m.visible]
        if len(solid_models) > 1:
            raise SceneError(f"the path tracer takes one CSG solid, the scene has "
                             f"{len(solid_models)}: make them one (a | b)")
        names: list = []
        rows: list = []
        maps: list = []
        textures: list = []
        tris, corner_normals, mats, models, colors, uvs, tangents = _world_triangles(
            scene, smooth, names, rows, maps, textures)
        solids = []
        for k, model in enumerate(solid_models):
            name = model.name or f"solid {k}"
            _refuse_unlit_parts(model.material, name)
            if max(model.material.emission) > 0:
                raise SceneError(f"{name}: a CSG solid cannot emit here (its surface is not "
                                 "sampled for light); give the emission to a mesh")
            solids.append((model.solid, len(rows)))
            rows.append(_material_row(model.material, name))
            maps.append(_material_maps(model.material, None, textures))
        if not tris and not solids:
            raise SceneError("the scene has nothing to trace (no visible meshes or solids)")
        triangles = (np.concatenate(tris) if tris else np.zeros((0, 3, 3))).astype(np.float64)
        if not np.isfinite(triangles).all():  # (a solid's numbers are checked when made)
            raise SceneError("the scene has vertices that are not finite numbers")
        cross = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
        length = np.linalg.norm(cross, axis=1)
        keep = length > 1e-12 * max(float(np.abs(triangles).max(initial=0)), 1e-300) ** 2
        triangles, cross, length = triangles[keep], cross[keep], length[keep]
        if not len(triangles) and not solids:
            raise SceneError(f"the scene's {int(keep.size):,} triangles all have zero area "
                             "(collinear or coincident corners): nothing to trace")
        material = np.concatenate(mats)[keep] if mats else np.zeros(0, np.int64)
        model = np.concatenate(models)[keep] if models else np.zeros(0, np.int64)
        materials = np.array(rows, np.float64)
        areas = 0.5 * length
        power = areas * materials[material, 5:8].mean(1)
        emitters = np.flatnonzero(power > 0)
        cdf = np.cumsum(power[emitters])
        cdf = cdf / cdf[-1] if len(cdf) else cdf
        chosen = list(scene.lights) if lights else []
        if lights and not chosen and not len(emitters) and camera is not None and \
                scene.environment is None:
            chosen = scene.lights_for(camera)
        light_rows = np.array([_light_row(x) for x in chosen], np.float64).reshape(-1, 15)
        if len(light_rows) > MAX_LIGHTS:
            raise SceneError(f"the path tracer takes at most {MAX_LIGHTS} lights, the scene "
                             f"has {len(light_rows)}")
        environment = scene.environment if lights else None
        if environment is not None and not environment.radiance.any():
            environment = None  # (a black sky: nothing to sample)
        if not len(emitters) and not len(light_rows) and environment is None:
            raise SceneError("the scene has no emitter: give a material an emission (or add "
                             "a light or an environment); nothing would be lit")
        corner_colors = np.concatenate(colors)[keep] if colors else None
        corner_uvs = np.concatenate(uvs)[keep] if uvs else None
        shading = None
        if smooth and corner_normals:
            shading = np.concatenate(corner_normals)[keep]
            shading /= np.maximum(np.linalg.norm(shading, axis=2, keepdims=True), 1e-300)
        return cls(triangles, cross / length[:, None], areas, material, materials, emitters,
                   cdf, light_rows, model, tuple(names), shading, tuple(solids), environment,
                   corner_colors, corner_uvs,
                   tuple(texture_texels(t, kind) for t, kind in textures),
                   np.array(maps, np.float64).reshape(len(rows), 5, 6),
                   np.concatenate(tangents)[keep] if tangents else None)


#: the maps the tracer reads, by lighting model: a colour map (the notes' diffuse map,
#: glTF's base colour) and glTF's metallic-roughness map; glTF's occlusion map is the
#: rasterizer's stand-in for what the paths find themselves (left to them)
TRACED_MAPS = {"notes": ("texture", "opacity_texture"),
               "pbr": ("base_color_texture", "metallic_roughness_texture",
                       "emissive_texture", "normal_texture", "occlusion_texture")}


def _refuse_unlit_parts(material, name: str, mesh=None) -> None:
    """The path tracer traces either lighting model (the notes' Material, glTF's
    PBRMaterial), opacity as a thin surface a path passes through with the chance 1 -
    opacity, colours on geometry and the colour and metallic-roughness maps multiplying
    the material's: the other maps, or colours' alpha, would be left out of the picture, so
    the trace refuses them by name (a CSG solid's surface has no texture coordinates: no
    maps)."""
    if mesh is not None and material.vertex_colors and mesh.colored and any(
            c is not None and (c[:, 3] < 1).any() for c in (mesh.colors, mesh.face_colors)):
        raise SceneError(f"{name}: its colours' alpha below 1 is not traced (the path "
                         "tracer's surfaces are opaque): give the colours alpha 1, or draw it "
                         "with glshade render")
    traced = TRACED_MAPS[material.lighting.value] if mesh is not None else ()
    untraced = sorted(k.removesuffix("_texture") for k in material.textures
                      if k not in traced)
    if untraced:
        raise SceneError(f"{name}: its texture maps ({', '.join(untraced)}) are not traced "
                         f"(the path tracer reads {_traced_names(mesh)}): drop them, or draw "
                         "it with glshade render")


def _traced_names(mesh) -> str:
    if mesh is None:
        return "no maps on a CSG solid"
    return "a colour map and glTF's metallic-roughness, emissive and normal maps"


def _material_maps(material, mesh, textures: list) -> list:
    """A material's five map slots (its colour map; glTF's metallic-roughness, emissive
    and normal maps; its opacity map), each
    (texture index or -1, sampling: 1 if clamped + 2 if nearest, scale u, scale v, offset
    u, offset v);
    ``textures`` ((Texture, "colour", "data" or "opacity") pairs, each once) is appended
    to. A mesh
    without texture coordinates reads none (the Scene warned when it was added)."""
    pbr = material.lighting.value == "pbr"
    # (the opacity slot: the notes' opacity map; glTF's base colour's alpha where the
    # material is drawn see-through, as the rasterizer's SURFACE_OPACITY takes it)
    see_through = "base_color_texture" if material.opacity < 1 else None
    slots = (("base_color_texture", "metallic_roughness_texture", "emissive_texture",
              "normal_texture", see_through) if pbr else
             ("texture", None, None, None, "opacity_texture"))
    out = []
    for kind, slot in zip(("colour", "data", "colour", "data", "opacity"), slots):
        texture = getattr(material, slot) if slot is not None else None
        if texture is None or mesh is None or mesh.uv is None:
            out.append([-1.0, 0.0, 1.0, 1.0, 0.0, 0.0])
            continue
        if kind == "opacity" and pbr:
            kind = "colour"  # (the base colour's own texels: their alpha as stored)
        found = [i for i, (t, c) in enumerate(textures) if t is texture and c == kind]
        if not found:
            textures.append((texture, kind))
        index = found[0] if found else len(textures) - 1
        out.append([float(index), float(texture.wrap == "clamp") +
                    2.0 * float(texture.filter == "nearest"), *texture.scale, *texture.offset])
    return out


def texture_texels(texture, kind: str) -> np.ndarray:
    """``(H, W, 4)`` float32: a texture's texels as the tracer samples them -- row 0 the
    image's bottom (v = 0, as GL's upload has it), a colour map decoded from sRGB to linear
    (alpha as stored), a data map (metallic-roughness, normal) as stored, an opacity map its
    opacity channel (alpha where it has one, else red, as the rasterizer reads it) in all
    four, each over 255.

    Parameters
    ----------
    texture : Texture
        The map.
    kind : str
        ``"colour"``, ``"data"`` or ``"opacity"``.
    """
    if kind == "colour":
        texels = texture.linear()
    elif kind == "opacity":
        from ..render.textures import opacity_channel

        texels = np.repeat(opacity_channel(texture.pixels)[..., None] / 255.0, 4, -1)
    else:
        texels = texture.pixels / 255.0
    return np.ascontiguousarray(texels[::-1], np.float32)


def _world_triangles(scene, smooth: bool, names: list, rows: list, maps: list,
                     textures: list):
    """The visible meshes' (and tessellated patches') world triangles, their corner normals
    where ``smooth``, each triangle's material row and model number, their corner colours
    and texture coordinates (None where no mesh has them), as lists of arrays; ``names``,
    ``rows`` (material rows), ``maps`` (their map slots) and ``textures`` are appended
    to."""
    tris: list = []
    corner_normals: list = []
    corner_colors: list = []
    corner_uvs: list = []
    tangents: list = []
    mats: list = []
    models: list = []
    visible = [m for m in scene.models if m.visible]
    if scene.patch_models:  # (GPU-tessellated there: the same grid here)
        from ..patches import tessellate
        from ..scene.scene import Model

        visible += [Model(tessellate(p.patches, level=p.level).mesh, p.material,
                          p.transform, p.name) for p in scene.patch_models if p.visible]
    for k, model in enumerate(visible):
        mesh = model.mesh
        name = model.name or f"model {k}"
        _refuse_unlit_parts(model.material, name, mesh)
        t, _ = mesh.triangles
        if not len(t):
            continue
        v = mesh.vertices @ model.transform[:3, :3].T + model.transform[:3, 3]
        tris.append(v[t])
        corner_colors.append(_corner_colors(mesh, model.material, mesh.corner_triangles))
        slots = _material_maps(model.material, mesh, textures)
        corner_uvs.append(mesh.uv[mesh.corner_triangles] if any(
            slot[0] >= 0 for slot in slots) else None)
        tangents.append(_tangents(v[t], corner_uvs[-1]) if slots[3][0] >= 0 else None)
        if smooth:
            from ..render.gpu_mesh import drawable_normals

            inverse_t = np.linalg.inv(model.transform[:3, :3]).T
            n = drawable_normals(mesh) @ inverse_t.T
            corner_normals.append(n[t])
        mats.append(np.full(len(t), len(rows)))
        models.append(np.full(len(t), len(names)))
        names.append(name)
        rows.append(_material_row(model.material, name))
        maps.append(slots)
    colors = uvs = None
    if any(c is not None for c in corner_colors):  # (white where a mesh has none)
        colors = [np.ones((len(x), 3, 3)) if c is None else c
                  for x, c in zip(tris, corner_colors)]
    if any(c is not None for c in corner_uvs):
        uvs = [np.zeros((len(x), 3, 2)) if c is None else c for x, c in zip(tris, corner_uvs)]
    frames = None
    if any(c is not None for c in tangents):
        frames = [np.zeros((len(x), 4)) if c is None else c for x, c in zip(tris, tangents)]
    return tris, corner_normals, mats, models, colors, uvs, frames


def _tangents(corners: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """``(T, 4)`` each triangle's dP/du and the handedness of (N, dP/du, dP/dv), N its
    winding's normal: the frame a tangent-space normal map bends the normal in (the
    tracer makes dP/du perpendicular to the shading normal where it is read)."""
    from ..render.gpu_mesh import triangle_frames

    du, dv = triangle_frames(corners, uv)
    n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    hand = np.where(np.einsum("ij,ij->i", np.cross(n, du), dv) < 0, -1.0, 1.0)
    return np.concatenate([du, hand[:, None]], 1)


def _corner_colors(mesh, material, corners: np.ndarray) -> np.ndarray | None:
    """``(T, 3, 3)`` the surface colour C at each triangle's corners (the mesh's corner
    colours: its vertex's times its polygon's), or None: the mesh has none or its material
    ignores them."""
    if not (mesh.colored and material.vertex_colors):
        return None
    return mesh.corner_colors[corners, :3]


def _material_row(material, name: str) -> list:
    """A material's row of the table (TraceScene.materials): the notes' rho_d, k_s and n,
    or glTF's base colour, metallic and roughness; the emission in radiosity units (a
    PBRMaterial's emissive is radiance: pi times it)."""
    if material.lighting.value == "pbr":
        return [*np.asarray(material.base_color, np.float64), 0.0, 0.0,
                *(np.pi * np.asarray(material.emissive, np.float64)),
                float(material.metallic), float(material.roughness), 1.0,
                float(material.opacity)]
    rho = np.asarray(material.rho, np.float64)
    # (the tracer's Phong lobe is grey: a coloured Ks gives its largest component)
    ks = float(max(material.specular_rgb)) if material.illum == 2 else 0.0
    n = float(material.shininess)
    if rho.max() > 1:
        raise SceneError(f"{name}: diffuse reflectance rho_d = {plain(rho)} is above "
                         "1 (it would reflect more light than arrives)")
    if rho.max() + ks > 1 + 1e-9:
        raise SceneError(f"{name}: rho_d + k_s = {rho.max():.4g} + {ks:.4g} > 1: the Phong "
                         "lobe would not conserve energy (lower kd, ks or the colour)")
    return [*rho, ks, n, *np.asarray(material.emission, np.float64), 0.0, 0.0, 0.0,
            float(material.opacity)]


def _light_row(light) -> list:
    """A light's row: kind (0 directional, 1 point, 2 spot), position or direction to it,
    irradiance, attenuation (c, l, q), a spot's cone (its axis times the cone's scale,
    and its offset: trace_lights.glsl; zero for the others), and 1 / its range (0: none)."""
    irradiance = np.asarray(light.color, np.float64) * light.intensity
    if isinstance(light, DirectionalLight):
        d = -np.asarray(light.direction, np.float64)
        return [0.0, *(d / np.linalg.norm(d)), *irradiance, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
                0.0]
    spot = light.spot_vector(np.eye(4)).tolist() if hasattr(light, "spot_vector") else [0.0] * 4
    return [2.0 if hasattr(light, "spot_vector") else 1.0,
            *np.asarray(light.position, np.float64), *irradiance,
            *np.asarray(light.attenuation, np.float64), *spot,
            1.0 / light.range if light.range else 0.0]
