"""The meshes' pass: the one routine that draws a model's triangles.

Every draw of a mesh model goes through :meth:`MeshPass.draw_models` -- the opaque surfaces
(:meth:`MeshPass.draw`, a stage of the pipeline), the shadow pass's G-buffer (the same
stage, drawn into the G-buffer's target) and the transparency pass's capture and blend
(``role``) -- so a model's program, uniforms, culling, winding and textures are chosen in
one place. It owns the GPU copies of the meshes (uploaded once, dropped with their mesh),
the compiled programs of each variant and the per-transform normal matrices, which the
patch and edge passes share.
"""

from __future__ import annotations

import weakref
from typing import Any

import moderngl
import numpy as np

from ...geometry.transforms import gl_bytes, model_matrices
from ...modes import Culling, LightingModel, ShadingMode
from ..base import GLResource
from ..gpu_mesh import GpuMesh
from ..programs import (
    FLAT_CONSTANTS_PIXELS, TEXTURED_MODES, Forward, MaterialUniforms, ProgramKey, Role,
    UniformWriter, Variant, flat_constants_fit, lighting_products,
)
from ..state import DrawState
from ..textures import TextureCache
from ..units import Unit
from . import Stage

__all__ = ["MeshPass", "INSTANCE_ROW_WIDTH", "instance_rows"]

#: texels a row of the instances' texture (instances.glsl's INSTANCE_ROW_WIDTH)
INSTANCE_ROW_WIDTH = 4096


def instance_rows(model_view, normal_view, normal_world, first_ids, ambient, diffuse):
    """The instances' texture rows (instances.glsl): per instance the model-view matrix's
    columns, the two normal matrices' columns, (first polygon id as bits, Ia ka C), then
    Ip kd C per light -- float32, as the uniforms of a separate draw would hold them.

    Parameters
    ----------
    model_view : ndarray
        ``(K, 4, 4)`` float64.
    normal_view, normal_world : ndarray
        ``(K, 3, 3)`` float64.
    first_ids : ndarray
        ``(K,)`` int: each instance's first polygon id.
    ambient : ndarray
        ``(K, 3)`` Ia ka C.
    diffuse : ndarray
        ``(K, L, 3)`` float32 Ip kd C per light.
    """
    k, lights = len(model_view), diffuse.shape[1]
    rows = np.zeros((k, 11 + lights, 4), np.float32)
    rows[:, 0:4] = np.swapaxes(model_view, 1, 2)           # (columns)
    rows[:, 4:7, :3] = np.swapaxes(normal_view, 1, 2)
    rows[:, 7:10, :3] = np.swapaxes(normal_world, 1, 2)
    rows[:, 10, 0] = np.asarray(first_ids, np.int32).view(np.float32)
    rows[:, 10, 1:] = ambient
    rows[:, 11:, :3] = diffuse
    return rows


def _faces(ctx, cull: bool, clockwise: bool) -> None:
    """The winding that faces the camera (clockwise for a mirroring transform, or a target
    drawn upside down, but not both) and whether back faces are culled."""
    ctx.front_face = "cw" if clockwise else "ccw"
    if cull:
        ctx.enable(moderngl.CULL_FACE)
        ctx.cull_face = "back"
    else:
        ctx.disable(moderngl.CULL_FACE)


class MeshPass(GLResource, Stage):
    """A Renderer's meshes on the GPU and the drawing of them.

    Parameters
    ----------
    context
        the RenderContext drawn with.
    shaders
        its :class:`~glshade.render.shaders.ShaderLibrary`.
    uniforms, materials
        the writer and the material cache every pass of the renderer shares (a uniform
        written once is not written again).
    flat_constants
        let Phong programs take the lighting constants as flat varyings for models with
        large triangles (faster on a software rasterizer, the same pictures).
    """

    def __init__(self, context, shaders, uniforms: UniformWriter,
                 materials: MaterialUniforms, flat_constants: bool = False):
        super().__init__(context)
        self.shaders, self.uniforms, self.materials = shaders, uniforms, materials
        self.flat_constants = flat_constants
        self._meshes: dict[int, tuple[weakref.ref, GpuMesh]] = {}
        self._normal_cache: dict[bytes, tuple[np.ndarray, bool]] = {}
        self._programs: dict[tuple, Any] = {}
        self._model_state: dict[int, tuple] = {}  # per program: the model uniforms it holds
        self._textures: TextureCache | None = None  # (made for the first textured draw)
        self._instances: Any = None  # (the instances' rows: made for the first group)
        #: the opaque models and instances the last draw skipped, their boxes wholly
        #: outside the view (``DrawOptions.frustum_cull``)
        self.culled = 0
        #: the spatial chunks of big meshes (GpuMesh.chunks) the last draw skipped
        self.culled_chunks = 0
        #: the vectors of varyings this GL interpolates (flat constants must fit in them)
        self.max_varyings = int(context.ctx.info.get("GL_MAX_VARYING_VECTORS") or 15)

    # ------------------------------------------------------------------ caches
    def gpu_mesh(self, mesh) -> GpuMesh:
        """The GPU copy of ``mesh`` (uploaded on first use, kept while the mesh lives).

        Parameters
        ----------
        mesh : Mesh
            The mesh.
        """
        entry = self._meshes.get(id(mesh))
        if entry is not None and entry[0]() is mesh:
            return entry[1]
        if entry is not None:  # the id was reused by a new object
            entry[1].release()
        gpu = GpuMesh(self.context, mesh)
        self._meshes[id(mesh)] = (weakref.ref(mesh), gpu)
        return gpu

    def sync(self) -> None:
        """Drop GPU copies of meshes that no longer exist (no GL work in finalizers)."""
        dead = [k for k, (ref, _) in self._meshes.items() if ref() is None]
        for k in dead:
            self._meshes.pop(k)[1].release()

    @property
    def cached(self) -> int:
        """How many meshes have a GPU copy."""
        return len(self._meshes)

    def normal_matrix(self, model: np.ndarray, key: bytes) -> tuple[np.ndarray, bool]:
        """Inverse transpose of a model matrix's 3x3 part, and whether it mirrors (its
        faces then wind the other way), cached per transform.

        Parameters
        ----------
        model
            (4, 4) model-to-world matrix.
        key
            its bytes (the cache's key).
        """
        found = self._normal_cache.get(key)
        if found is None:
            if len(self._normal_cache) > 4096:
                self._normal_cache.clear()
            found = self._normal_cache[key] = (np.linalg.inv(model[:3, :3]).T,
                                               bool(np.linalg.det(model[:3, :3]) < 0))
        return found

    def program(self, variant: Variant, two_sided: bool, flat: bool = False,
                role: Role = Role.OPAQUE, textured: bool = False, instanced: bool = False,
                fetch: bool = False, colored: bool = False, emissive: bool = False,
                lighting: LightingModel = LightingModel.NOTES, normal_map: bool = False):
        """The compiled program of a variant, with flat lighting constants if asked for and
        they fit; ``role``: an opaque surface's or a transparent one's; ``textured``: its
        material's maps sampled.

        Parameters
        ----------
        variant : Variant
            What the draw's programs share.
        two_sided : bool
            Light back faces as seen.
        flat : bool
            Phong's lighting constants as flat varyings.
        role : Role
            The transparency pass's role (or opaque).
        textured : bool
            The material has texture maps.
        instanced : bool
            One draw of a group's instances (instances.glsl).
        fetch : bool
            A big mesh's draw over its shared vertices (polygon_fetch.glsl).
        colored : bool
            The mesh's colours multiply the material's (surface_color.glsl).
        emissive : bool
            The material's emission is added to the lit colour.
        lighting : LightingModel
            The material's lighting model (the notes' or glTF's).
        normal_map : bool
            A PBRMaterial's normal map is read.
        """
        found = (variant, two_sided, flat, role, textured, instanced, fetch, colored, emissive,
                 lighting, normal_map)
        program = self._programs.get(found)
        if program is None:
            forwarded = variant.shadows and variant.forward is not Forward.ARRAY
            world = (variant.aux or forwarded) and role is Role.OPAQUE
            flat = flat and flat_constants_fit(variant.mode, world, variant.lights,
                                               self.max_varyings, textured, colored,
                                               normal_map)
            key = ProgramKey.of(variant, two_sided=two_sided, flat_constants=flat, oit=role,
                                textured=textured, instanced=instanced, fetch=fetch,
                                colored=colored, emissive=emissive, lighting=lighting,
                                normal_map=normal_map)
            program = self._programs[found] = self.shaders.program(key)
        return program

    # ------------------------------------------------------------------ the stage
    def draw(self, state: DrawState, id_base: int) -> int:
        """Draw the scene's visible opaque meshes; the polygon id after theirs (transparent
        ones keep their ids: the transparency pass draws them later; a wireframe draw
        leaves the surfaces to the edge pass).

        Parameters
        ----------
        state : DrawState
            The draw.
        id_base : int
            The first polygon id free for the meshes.
        """
        prepared: set[int] = set()
        wireframe = state.options.wireframe
        models = state.scene.models
        self.culled = self.culled_chunks = 0
        outside = state.outside(models)
        skip_to = 0
        for index, model in enumerate(models):
            if index < skip_to:  # (drawn with its group)
                continue
            if not state.drawn(model):
                id_base += model.mesh.n_faces
                continue
            gpu = self.gpu_mesh(model.mesh)
            group = model.group
            if (group is not None and not wireframe and group.models[0] is model
                    and self._instanced(state, group, models, index)):
                self._draw_group(state, group, gpu, id_base, prepared,
                                 ~outside[index:index + len(group)])
                skip_to = index + len(group)
                id_base += gpu.n_polygons * len(group)
                continue
            if not wireframe and not state.transparent(model):
                if outside[index]:
                    self.culled += 1
                else:
                    self._draw_model(state, model, gpu, id_base, prepared)
            id_base += gpu.n_polygons
        return id_base

    @staticmethod
    def _instanced(state: DrawState, group, models, index: int) -> bool:
        """Whether ``group`` (starting at ``models[index]``) is drawn by one instanced call:
        more than one, all shown and opaque, untextured, in the notes' model (an instance's
        row holds its products), where it was added with the mesh and materials it was
        added with, and not in the ``radiosity`` mode (its colours are per model); else
        model by model."""
        first = group.models[0]
        if (len(group) < 2 or state.options.mode is ShadingMode.RADIOSITY
                or state.transparent(first) or first.material.textures
                or first.material.lighting is not LightingModel.NOTES):
            return False
        run = models[index:index + len(group)]
        return len(run) == len(group) and all(
            a is b and a.visible and a.mesh is first.mesh and a.material is material
            for a, b, material in zip(run, group.models, group.materials))

    def _draw_group(self, state: DrawState, group, gpu, id_base: int, prepared: set,
                    inside: np.ndarray) -> None:
        """A group's instances (those ``inside`` the view) in one instanced call for each
        way they are drawn (culled or two-sided, mirrored or not): each instance's
        matrices, first polygon id and colour in its row of a texture (instances.glsl)."""
        ctx, put, options = self.context.ctx, self.uniforms.put, state.options
        near = state.camera.planes()[0]
        first = group.models[0]
        k = len(group)
        model_view, normal_view, normal_world, mirrored = model_matrices(
            state.view, group.transforms)
        ids = id_base + gpu.n_polygons * np.arange(k)
        ambient, diffuse, _ = lighting_products(first.material, state.lights,
                                                state.scene.ambient, group.colors)
        if group.colors is None:  # (one colour for all)
            ambient = np.broadcast_to(ambient, (k, 3))
            diffuse = np.broadcast_to(diffuse, (k,) + diffuse.shape[1:])
        if options.cull is Culling.ON:
            culled = np.ones(k, bool)
        elif options.cull is Culling.AUTO and gpu.closed:
            corners = gpu.corners  # (the mesh's box, model space: beyond the near plane?)
            culled = ((model_view[:, 2] @ corners) < -near).all(1)
        else:
            culled = np.zeros(k, bool)
        self.culled += int(k - inside.sum())
        pixels = state.viewport[2] * state.viewport[3]
        flat = self.flat_constants and gpu.n_triangles * FLAT_CONSTANTS_PIXELS <= pixels
        for cull in (False, True):
            for mirror in (False, True):
                chosen = np.flatnonzero((culled == cull) & (mirrored == mirror) & inside)
                if not len(chosen):
                    continue
                prog = self.program(state.variant, not cull, flat, instanced=True,
                                    colored=gpu.colored and first.material.vertex_colors,
                                    emissive=any(first.material.emission))
                if id(prog) not in prepared:
                    for name, value in state.frame_uniforms:
                        put(prog, name, value)
                    prepared.add(id(prog))
                for name, value in self.materials(first.material, state.lights,
                                                  state.scene.ambient):
                    if name not in ("u_ambient_term", "u_light_diffuse"):
                        put(prog, name, value)
                rows = instance_rows(model_view[chosen], normal_view[chosen],
                                     normal_world[chosen], ids[chosen], ambient[chosen],
                                     diffuse[chosen])
                put(prog, "u_instance_stride", rows.shape[1])
                put(prog, "u_instances", Unit.INSTANCES)
                self._instance_texture(rows).use(location=Unit.INSTANCES)
                _faces(ctx, cull, mirror != state.flip_rows)
                gpu.vertex_array(prog, options.mode).render(moderngl.TRIANGLES,
                                                            instances=len(chosen))

    def _instance_texture(self, rows: np.ndarray):
        """A float texture holding ``rows`` (``(K, S, 4)``), INSTANCE_ROW_WIDTH texels a
        row; kept and grown as needed (rewritten every instanced draw)."""
        texels = rows.reshape(-1, 4)
        height = -(-len(texels) // INSTANCE_ROW_WIDTH)
        data = np.zeros((height * INSTANCE_ROW_WIDTH, 4), np.float32)
        data[:len(texels)] = texels
        found = self._instances
        if found is None or found.size[1] < height:
            if found is not None:
                found.release()
            found = self._instances = self.context.ctx.texture(
                (INSTANCE_ROW_WIDTH, max(height, 1)), 4, dtype="f4")
            found.filter = (moderngl.NEAREST, moderngl.NEAREST)
        found.write(data.tobytes(), viewport=(0, 0, INSTANCE_ROW_WIDTH, height))
        return found

    def draw_models(self, state: DrawState, models, role: Role,
                    extra: dict | None = None) -> None:
        """Draw ``models`` as ``role`` (the transparency pass's capture, fetch or blend),
        with the ``extra`` uniforms its programs take.

        Parameters
        ----------
        state : DrawState
            The draw.
        models : iterable of Model
            What to draw.
        role : Role
            The transparency pass's role.
        extra : dict or None
            Uniforms the role's programs take.
        """
        prepared: set[int] = set()
        for model in models:
            self._draw_model(state, model, self.gpu_mesh(model.mesh), 0, prepared, role,
                             extra)

    def _draw_model(self, state: DrawState, model, gpu, id_base: int, prepared: set,
                    role: Role = Role.OPAQUE, extra: dict | None = None) -> None:
        """One model's draw call, with the uniforms its program does not hold yet."""
        ctx, put = self.context.ctx, self.uniforms.put
        scene, options, view, lights = state.scene, state.options, state.view, state.lights
        near = state.camera.planes()[0]
        pixels = state.viewport[2] * state.viewport[3]
        m = model.transform
        model_view = view @ m
        cull = options.cull is Culling.ON or (
            options.cull is Culling.AUTO and gpu.closed
            and gpu.beyond(model_view, near) and role is Role.OPAQUE)  # (seen from outside)
        flat = self.flat_constants and gpu.n_triangles * FLAT_CONSTANTS_PIXELS <= pixels
        material = model.material
        textured = (gpu.textured and bool(material.textures)
                    and options.mode in TEXTURED_MODES)
        colored = gpu.colored and material.vertex_colors and options.mode in TEXTURED_MODES
        pbr = material.lighting is LightingModel.PBR
        # a big mesh draws its shared vertices in every mode that can (flat lit per
        # triangle, ids per triangle from a table): no copy of them at every corner -- but
        # a coloured one's flat draw, whose polygon colour is the mean of its corners', and
        # a textured PBRMaterial's, whose maps are read at the polygon's centre
        variant = state.variant
        fetch = gpu.chunks is not None and role is Role.OPAQUE and (
            (options.mode is ShadingMode.FLAT and not colored and not (textured and pbr)) or (
                options.mode not in (ShadingMode.RADIOSITY, ShadingMode.FLAT) and (
                    variant.aux or (variant.shadows and variant.forward is Forward.RAYS))))
        prog = self.program(variant, not cull, flat, role, textured, fetch=fetch,
                            colored=colored, emissive=any(material.emission),
                            lighting=material.lighting,
                            normal_map=pbr and getattr(material, "normal_texture", None)
                            is not None)
        if id(prog) not in prepared:  # the frame's uniforms, once per program used
            for name, value in state.frame_uniforms:
                put(prog, name, value)
            for name, value in (extra or {}).items():
                put(prog, name, value)
            prepared.add(id(prog))
        transform = m.tobytes()
        normal_world, mirrored = self.normal_matrix(m, transform)
        # (the view is rigid: its inverse transpose is itself)
        put(prog, "u_normal_view", gl_bytes(view[:3, :3] @ normal_world))
        put(prog, "u_model_view", gl_bytes(model_view))
        held = (transform, id_base, model.material, lights, scene.ambient)
        if self._model_state.get(id(prog)) != held:  # else all of it is in place
            put(prog, "u_normal_world", gl_bytes(normal_world))
            put(prog, "u_face_id_base", id_base)
            put(prog, "u_opacity", float(model.material.opacity))
            for name, value in self.materials(model.material, lights, scene.ambient):
                put(prog, name, value)
            self._model_state[id(prog)] = held
        _faces(ctx, cull, mirrored != state.flip_rows)
        if textured:
            if self._textures is None:
                self._textures = TextureCache(self.context)
            if pbr:
                self._textures.bind_pbr(model.material, put, prog)
            else:
                self._textures.bind(model.material, put, prog)
        if options.mode is ShadingMode.RADIOSITY:
            vao = gpu.color_array(prog, model.display_colors(scene.ambient))
        else:
            vao = gpu.vertex_array(prog, options.mode)
        if fetch:
            polygons, planes = gpu.polygon_tables(options.mode is ShadingMode.FLAT)
            polygons.use(location=Unit.POLYGONS)
            put(prog, "u_polygons", Unit.POLYGONS)
            if planes is not None:
                planes.use(location=Unit.POLYGON_PLANES)
                put(prog, "u_polygon_planes", Unit.POLYGON_PLANES)
        chunks = gpu.chunks
        if chunks is not None and options.frustum_cull:  # (a big mesh: what the view holds)
            ranges, skipped = chunks.in_view(state.view_proj @ m)
            self.culled_chunks += skipped
        else:
            ranges = [(0, gpu.n_triangles)]
        for first, count in ranges:
            put(prog, "u_triangle_base", first)  # (the draw's triangles count from 0)
            vao.render(moderngl.TRIANGLES, vertices=3 * count, first=3 * first)

    def _release_extra(self) -> None:
        for _, gpu in self._meshes.values():
            gpu.release()
        self._meshes.clear()
        if self._textures is not None:
            self._textures.release()
            self._textures = None
        if self._instances is not None:
            self._instances.release()
            self._instances = None
        self._programs.clear()  # (the shader library owns and frees them)
        self._model_state.clear()
