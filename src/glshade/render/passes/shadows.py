"""Cast shadows: how much of each light reaches each pixel's surface point.

``exact``: one ray from the point to the light through a BVH of the scene's triangles
(shaders/include/shadow_trace.glsl). A plain draw traces them in its fragment stage, each
fragment its own point's rays as it shades (SHADOW_RAYS_FORWARD: no G-buffer, no second
pass); a draw whose visibility is read back (``render_frame``) or where a CSG solid casts
first draws the scene into a G-buffer of its own (view depth, polygon ids, normals) and
traces its points in a compute pass (shaders/shadow_rays.comp, one invocation a ray; a
solid's rays after the triangles'), leaving a texture array (a layer a light) that the
shading programs read (shaders/include/shadow_mask.glsl). Either way a ray's work is
bounded, and the rays that ran out are counted and reported.

Where the GL has no compute shaders or storage buffers (OpenGL 4.1: every Mac; the
context's :class:`~glshade.render.features.Features` say), the same hierarchy lies in
textures and the visibility array is filled by fragment programs drawn over the viewport,
a light a draw (shaders/shadow_rays.frag: the same rays through the same walk, so the same
visibility bit for bit; each draw's picture is copied into its layer through a pixel
buffer, and its rays that ran out are flagged in a second target and counted); a plain
draw goes through the G-buffer too (its fragments could not count their rays).

``map``: the light's depth map (2D for a directional light, six faces of a cube for a point
light) with percentage-closer filtering, looked up the same two ways
(shaders/include/shadow_lookup.glsl, shaders/shadow_maps.comp; without compute shaders
shaders/shadow_maps.frag).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import RenderWarning, warn_user
from ...geometry.transforms import gl_bytes
from ...modes import Outputs, ShadingMode, Shadows
from ..base import GLResource
from ..data import NEAREST
from ..programs import Forward, UniformWriter
from ..shaders import LOOP_BUDGET
from ..units import Binding, Unit
from ..state import DrawState
from . import Stage, run
from .gbuffer import GBuffer, bind_gbuffer
from .shadow_maps import LayerScratch, ShadowMaps, fill_layers, shadow_lights

__all__ = ["ShadowPass", "UNIT", "MAP_FORWARD_UNIT", "SHADOW_EPS", "RAY_BUDGET"]

#: texture unit of the visibility array in the shading programs
UNIT = Unit.SHADOW_VISIBILITY
#: the first texture unit of a forward map-shadowed draw's maps (a light each, up to 8)
MAP_FORWARD_UNIT = Unit.LIGHT_MAPS
#: a shadow ray starts this far from its point, relative to the point's depth plus the
#: scene's largest coordinate (the point is rebuilt from a float32 depth, ~1e-7 of those)
SHADOW_EPS = 2e-5
#: loop iterations one shadow ray may take (llvmpipe stops a shader at 65,535); a ray that
#: runs out shows its light as seen, and is counted and reported
RAY_BUDGET = LOOP_BUDGET
#: texels a row of the hierarchy's textures where the GL has no storage buffers
#: (shadow_trace.glsl's SHADOW_TEXEL_ROW): 16,384 rows of it (every GL 4.1's largest
#: texture) hold 22 million triangles
TEXEL_ROW = 4096
#: triangles wider than this fraction of the scene's diagonal are tested by every ray in a
#: list of their own (at most MAX_BIG of them), the rest through the hierarchy
BIG_TRIANGLE, MAX_BIG = 0.25, 64


@dataclass
class _Occluding:
    """The scene's occluders on the GPU: the BVH's ``nodes``, the ``tris`` (the ``big``
    ones first, tested by every ray), each mesh polygon's world ``normals`` (storage
    buffers; textures of :data:`TEXEL_ROW` texels a row without them), the triangles as
    ``found`` on the CPU (the maps draw them), the scene's largest coordinate ``scale``, and
    the ``key`` of the geometry they were built for."""

    key: tuple
    nodes: Any
    tris: Any
    normals: Any
    found: Any
    big: int
    scale: float
    root: dict  # (the hierarchy's root and its boxes' quantum, as uniforms)

    def release(self) -> None:
        for buf in (self.nodes, self.tris, self.normals):
            buf.release()


def _geometry_key(scene) -> tuple:
    """What the occluders depend on: each mesh and patch model, its transform, whether it
    is shown and whether it is opaque (transparent surfaces cast no shadows)."""
    return tuple((id(m.mesh), m.transform.tobytes(), m.visible, not m.transparent)
                 for m in scene.models) + \
        tuple((id(p.patches), p.level, p.transform.tobytes(), p.visible)
              for p in scene.patch_models)


def _texels(ctx, words: np.ndarray):
    """``(N, 4)`` words (uint32 or float32) as a texture of :data:`TEXEL_ROW` texels a row,
    read whole (NEAREST): a storage buffer's words where the GL has none."""
    words = np.ascontiguousarray(words).reshape(-1, 4)
    width = min(TEXEL_ROW, max(len(words), 1))
    rows = -(-max(len(words), 1) // width)
    data = np.zeros((rows * width, 4), words.dtype)
    data[:len(words)] = words
    dtype = "f4" if words.dtype == np.float32 else "u4"
    tex = ctx.texture((width, rows), 4, data.tobytes(), dtype=dtype)
    tex.filter = (NEAREST, NEAREST)
    return tex


def _hidden(model):
    out = copy.copy(model)
    out.visible = False
    return out


class ShadowPass(GLResource, Stage):
    """The shadow work of one Renderer: its G-buffer, BVH buffers, shadow maps and the
    visibility array, made for the first draw that asks and kept (per size, per scene
    geometry) for the next ones.

    Parameters
    ----------
    context
        the RenderContext drawn with.
    shaders
        its shader library.
    opaque
        the stages that draw the opaque surfaces (meshes, patches, solids): the G-buffer of
        a draw whose visibility is read back is drawn with them.
    """

    def __init__(self, context, shaders, opaque: Sequence[Stage]):
        super().__init__(context)
        self.shaders = shaders
        #: the stages that draw the opaque surfaces, which the G-buffer is drawn with
        self.opaque = tuple(opaque)
        self._array: Any = None  # (the visibility array a draw's programs read, or None)
        self.drawn = False  # (some draw cast shadows)
        self._gbuffer: tuple | None = None
        self._visibility: tuple | None = None
        self._occluding: _Occluding | None = None
        self._soup: tuple | None = None  # (key, triangles) for the maps alone
        self._programs: dict = {}
        self._counts = self._keep(context.ctx.buffer(reserve=4))
        self.undecided = 0
        self.maps: Any = None  # (a ShadowMaps, for the map method)
        self._solid_data: dict = {}  # id(solid) -> (solid, its tree data, its texture)
        self._put = UniformWriter().put
        self._lights_drawn = 0
        self._scratch = LayerScratch(context.ctx)  # (the fragment fills' targets)

    # ---------------------------------------------------------------- resources
    def _gbuffer_for(self, width: int, height: int, rows_top_down: bool) -> GBuffer:
        key = (width, height, rows_top_down)
        if self._gbuffer is None or self._gbuffer[0] != key:
            if self._gbuffer is not None:
                for obj in self._gbuffer[2]:
                    obj.release()
            made: list = []

            def keep(obj):
                made.append(obj)
                return obj

            self._gbuffer = (key, GBuffer(self.context.ctx, width, height, rows_top_down,
                                           keep), made)
        return self._gbuffer[1]

    def visibility(self, width: int, height: int, layers: int):
        """The ``(W, H, layers)`` R8 array the shading programs read (made once a size).

        Parameters
        ----------
        width, height : int
            The draw's size in pixels.
        layers : int
            Its lights.
        """
        key = (width, height, layers)
        if self._visibility is None or self._visibility[0] != key:
            if self._visibility is not None:
                self._visibility[1].release()
            tex = self.context.ctx.texture_array((width, height, layers), 1, dtype="f1")
            tex.filter = (NEAREST, NEAREST)
            self._visibility = (key, tex)
        return self._visibility[1]

    def occluder_triangles(self, scene) -> tuple[tuple, np.ndarray]:
        """``(key, (T, 3, 3) world triangles)`` of the scene's occluders: what the maps draw
        -- the exact method's BVH's when it has one for this geometry, else gathered (and
        kept) without building a hierarchy the maps do not use.

        Parameters
        ----------
        scene : Scene
            The scene.
        """
        from ...scene.occluders import occluders

        key = _geometry_key(scene)
        if self._occluding is not None and self._occluding.key == key:
            return key, self._occluding.found.triangles
        if self._soup is None or self._soup[0] != key:
            self._soup = (key, occluders(scene).triangles)
        return self._soup

    def occluding(self, scene) -> _Occluding:
        """The scene's occluders on the GPU (a BVH in storage buffers), built again only
        when the geometry changed (meshes, patches, transforms, visibility, opacity).

        Parameters
        ----------
        scene : Scene
            The scene.
        """
        from ...geometry.bvh import NO_CHILDREN, build, packed_children
        from ...scene.occluders import occluders

        key = _geometry_key(scene)
        if self._occluding is not None and self._occluding.key == key:
            return self._occluding
        if self._occluding is not None:
            self._occluding.release()
            self._occluding = None
        found = occluders(scene)
        ctx = self.context.ctx
        big = np.zeros(0, np.int64)
        packed = NO_CHILDREN
        tris = np.zeros((2, 4), np.float32)
        if len(found):
            # the largest triangles (a floor's, a wall's) go in a list every ray tests first:
            # in the hierarchy their boxes would widen every node they share to the scene's
            extent = np.linalg.norm(np.ptp(found.triangles, axis=1), axis=1)
            size = float(np.linalg.norm(np.ptp(found.bounds, axis=0))) or 1.0
            big = np.flatnonzero(extent > BIG_TRIANGLE * size)
            big = big[np.argsort(-extent[big], kind="stable")][:MAX_BIG]
            rest = np.setdiff1d(np.arange(len(found)), big)
            order = big
            if len(rest):
                bvh = build(found.triangles[rest])
                order = np.concatenate([big, rest[bvh.order]])
                packed = packed_children(bvh, len(big))
            tri = found.triangles[order]
            tris = np.zeros((3 * len(tri), 4), np.float32)
            tris[0::3, :3] = tri[:, 0]
            tris[0::3, 3] = np.asarray(found.polygon[order], np.int32).view(np.float32)
            tris[1::3, :3] = tri[:, 1] - tri[:, 0]
            tris[2::3, :3] = tri[:, 2] - tri[:, 0]
        normals = np.zeros((max(len(found.normals), 1), 4), np.float32)
        normals[:len(found.normals), :3] = found.normals
        if self.context.features.storage:
            made = [ctx.buffer(a.tobytes()) for a in (packed.entries, tris, normals)]
        else:
            made = [_texels(ctx, a) for a in (packed.entries, tris, normals)]
        nodes, tris_data, normals_data = made
        self._occluding = _Occluding(
            key, nodes, tris_data, normals_data, found, len(big),
            float(np.abs(found.bounds).max()) if len(found) else 1.0, packed.uniforms())
        return self._occluding

    def _program(self, defines: tuple):
        """The exact method's program for ``defines`` (compiled once): the compute pass, or
        without compute shaders the fragment program drawn over the viewport."""
        prog = self._programs.get(defines)
        if prog is None:
            if self.context.features.storage:
                from ..shaders import assemble, compile_compute

                source, _ = assemble("shadow_rays.comp", defines=defines)
                prog = compile_compute(self.context, source)
            else:
                prog = self.shaders.compile(
                    "fullscreen.vert", "shadow_rays.frag",
                    defines=("SHADOW_TEXELS", f"SHADOW_TEXEL_ROW {TEXEL_ROW}") + defines)
            self._programs[defines] = prog
        return prog

    # ---------------------------------------------------------------- the stage
    def wanted(self, state) -> bool:
        return bool(state.variant.shadows)

    def prepare(self, state):
        """Find each light's visibility for ``state``'s draw: for a draw whose programs find
        it themselves as they shade (``variant.forward`` MAPS or RAYS), bind what they read
        and add the uniforms they take; else draw the G-buffer with the opaque stages,
        fill the visibility array at its points and add its unit.

        Parameters
        ----------
        state : DrawState
            The draw.
        """
        self._check()
        self.drawn = True
        if state.options.shadows is Shadows.MAP:  # (its lookups index sampler arrays)
            self.context.require(400, "shadows='map' needs", "use shadows='exact'")
        self._array = None
        if state.variant.forward is not Forward.ARRAY:
            return state.with_uniforms(self._forward(state))
        target = state.target
        width, height = int(target.width), int(target.height)
        gbuf = self._gbuffer_for(width, height, bool(state.flip_rows))
        options = state.options.replace(shadows=Shadows.OFF, mode=ShadingMode.NORMALS,
                                        outputs=Outputs.ALL, edges=False, srgb=False)
        scene = state.scene
        if any(m.transparent for m in scene.models):
            # the opaque surfaces' points (transparent ones receive no shadows), hidden
            # copies keeping the polygon ids of the transparent ones
            scene = copy.copy(scene)
            scene.models = [m if not m.transparent else _hidden(m)
                            for m in scene.models]
        points = DrawState.of(gbuf, scene, state.camera, options, state.viewport)
        run(self.context.ctx, self.opaque, points)
        lights = state.lights
        vis = self.visibility(width, height, max(len(lights), 1))
        self._lights_drawn = len(lights)
        if state.options.shadows is Shadows.MAP:
            # (the draw's own scene: the G-buffer's hidden copies would key the maps anew)
            self._maps().fill(state, self.occluder_triangles(state.scene), gbuf, vis,
                              self._put)
            self.undecided = 0
        else:
            self._trace(state, gbuf, vis)
        self._array = vis
        return state.with_uniforms({"u_visibility": UNIT})

    def draw(self, state, id_base: int) -> int:
        """Bind the visibility array (a draw through a G-buffer) for the shading programs.

        Parameters
        ----------
        state : DrawState
            The draw.
        id_base : int
            The first polygon id free for this stage.
        """
        if self._array is not None:
            self._array.use(UNIT)
        return id_base

    def finish(self, state) -> None:
        """After a draw whose fragments traced their own rays: count those that ran out.

        Parameters
        ----------
        state : DrawState
            The draw.
        """
        if state.variant.forward is Forward.RAYS:
            self.forward_done()

    def _maps(self) -> ShadowMaps:
        if self.maps is None:
            self.maps = ShadowMaps(self.context, self.shaders, self._scratch)
        return self.maps

    def _forward(self, state) -> dict:
        """A shadowed draw that needs no visibility array, no G-buffer: the draw's programs
        find each light's visibility as they shade, at their own point -- tracing its ray
        (SHADOW_RAYS_FORWARD: the BVH's buffers bound) or looking the maps up
        (SHADOW_MAPS_FORWARD: the maps drawn when changed and bound from
        :data:`MAP_FORWARD_UNIT`). The uniforms they take."""
        self._lights_drawn = 0
        if state.variant.forward is Forward.RAYS:
            occ = self.occluding(state.scene)
            self._counts.write(np.zeros(1, np.uint32).tobytes())
            self._bind_occluding(occ)
            # (one fragment traces every light: they share its loop budget)
            return {**self._ray_uniforms(state, occ, len(state.lights)),
                    "u_camera_to_world": gl_bytes(np.linalg.inv(state.view))}
        return self._maps().forward(state, self.occluder_triangles(state.scene),
                                    MAP_FORWARD_UNIT)

    def forward_done(self) -> None:
        """After a draw that traced its own rays: count those that ran out (a warning)."""
        self.context.ctx.memory_barrier()  # (the fragments' counts, before they are read)
        undecided = int(np.frombuffer(self._counts.read(), np.uint32)[0])
        self.undecided = undecided
        if undecided:
            self._warn_undecided(undecided)

    @staticmethod
    def _warn_undecided(count: int) -> None:
        warn_user(f"{count:,} shadow rays ran past their share of {RAY_BUDGET:,} steps "
                  "(the GL's loop limit) and show their light as seen", RenderWarning)

    def read(self) -> np.ndarray:
        """The last draw's visibility ``(H, W, L)`` float32 in [0, 1] (row 0 at the top of
        an offscreen target's image)."""
        assert self._visibility is not None, "no shadowed draw yet"
        (w, h, layers), tex = self._visibility
        data = np.frombuffer(tex.read(), np.uint8).reshape(layers, h, w)
        n = self._lights_drawn
        return np.ascontiguousarray(data[:n].transpose(1, 2, 0), np.float32) / 255.0

    def _ray_uniforms(self, state, occ: _Occluding, rays_a_pixel: int) -> dict:
        """What shadow_trace.glsl takes: the hierarchy's facts, its lights, and the loop
        budget of one ray (an invocation that traces ``rays_a_pixel`` rays shares one)."""
        return {"u_scale": occ.scale, "u_eps": SHADOW_EPS,
                "u_budget": RAY_BUDGET // max(rays_a_pixel, 1),
                "u_has_triangles": int(len(occ.found) > occ.big), "u_big": occ.big,
                "u_polygons": len(occ.found.normals), **occ.root,
                "u_shadow_lights": shadow_lights(state.lights).astype("f4")}

    def _bind_occluding(self, occ: _Occluding, prog=None) -> None:
        """Bind the hierarchy's buffers, or (no storage buffers) its textures for ``prog``."""
        if not self.context.features.storage:
            for name, tex, unit in (("u_walk_nodes", occ.nodes, Unit.WALK_NODES),
                                    ("u_walk_tris", occ.tris, Unit.WALK_TRIANGLES),
                                    ("u_polygon_normals", occ.normals, Unit.WALK_NORMALS)):
                tex.use(unit)
                self._put(prog, name, unit)
            return
        occ.nodes.bind_to_storage_buffer(Binding.WALK_NODES)
        occ.tris.bind_to_storage_buffer(Binding.WALK_TRIANGLES)
        self._counts.bind_to_storage_buffer(Binding.RAY_COUNTS)
        occ.normals.bind_to_storage_buffer(Binding.POLYGON_NORMALS)

    def _trace(self, state, gbuf: GBuffer, vis) -> None:
        """The exact method: a ray a pixel and light (shaders/shadow_rays.comp)."""
        from ...scene.camera import Projection

        occ = self.occluding(state.scene)
        ortho = state.camera.projection is Projection.ORTHOGRAPHIC
        prog = self._program(("ORTHOGRAPHIC",) if ortho else ())
        bind_gbuffer(self._put, prog, state, gbuf)
        values = self._ray_uniforms(state, occ, 1)
        for name, value in values.items():
            self._put(prog, name, value)
        self._bind_occluding(occ, prog)
        self.dispatch(prog, state, vis)
        for model in state.scene.solids:  # (each hides more of what the triangles left)
            if model.visible:
                self._trace_solid(model.solid, state, gbuf, vis, ortho, values)

    def _trace_solid(self, solid, state, gbuf: GBuffer, vis, ortho: bool, values) -> None:
        """One CSG solid's shadows over the triangles': the raster pass's exact cast."""
        from ...solids.encoding import ROW, tree_data
        from ...solids.tree import TIE
        from ..data import data_texture
        from .csg import csg_defines

        found = self._solid_data.get(id(solid))
        if found is None or found[0] is not solid:
            if found is not None:
                found[2].release()
            tree = tree_data(solid)
            texture = data_texture(self.context.ctx, tree.texels, ROW)
            found = self._solid_data[id(solid)] = (solid, tree, texture)
        _, tree, texture = found
        defines = ("CSG_SOLID", *csg_defines(tree, blocks=False)) + \
            (("ORTHOGRAPHIC",) if ortho else ())
        prog = self._program(defines)
        bind_gbuffer(self._put, prog, state, gbuf)
        texture.use(Unit.CAST_TREE)
        bounds = np.asarray(solid.bounds, np.float64)
        size = float(np.linalg.norm(bounds[1] - bounds[0])) or 1.0
        extra = {"u_csg": Unit.CAST_TREE, **tree.offsets(), "u_csg_start": tree.nodes,
                 "u_csg_tie": TIE * size, "u_scale": max(values["u_scale"],
                                                         float(np.abs(bounds).max()))}
        extra["u_csg_kind_start"] = np.array(tree.kind_start, "i4")
        for name, value in {**values, **extra}.items():
            self._put(prog, name, value)
        if not self.context.features.storage:  # (the triangles' answers, read)
            self._bind_occluding(self.occluding(state.scene), prog)
            vis.use(Unit.CAST_PREVIOUS)
            self._put(prog, "u_previous", Unit.CAST_PREVIOUS)
        self.dispatch(prog, state, vis, keep_count=True)

    def dispatch(self, prog, state, vis, keep_count: bool = False) -> None:
        """Run ``prog`` over the viewport's pixels x the lights; count the rays that ran out
        of their budget (a warning, never silent).

        Parameters
        ----------
        prog : moderngl.ComputeShader
            The compute program.
        state : DrawState
            The draw.
        vis : moderngl.Texture
            The visibility array.
        keep_count : bool
            Add to the count of rays out of budget (else start it anew).
        """
        ctx = self.context.ctx
        if not self.context.features.storage:
            undecided = self._fill_layers(prog, state, vis, range(len(state.lights)))
            undecided += self.undecided if keep_count else 0
        else:
            if not keep_count:
                self._counts.write(np.zeros(1, np.uint32).tobytes())
            vis.bind_to_image(Binding.VISIBILITY_IMAGE, read=True, write=True)
            _, _, w, h = (int(v) for v in state.viewport)
            prog.run(math.ceil(w / 8), math.ceil(h / 8), max(len(state.lights), 1))
            ctx.memory_barrier()
            undecided = int(np.frombuffer(self._counts.read(), np.uint32)[0])
        self.undecided, new = undecided, undecided - (self.undecided if keep_count else 0)
        if new:
            self._warn_undecided(new)

    def _fill_layers(self, prog, state, vis, layers, uniform: str = "u_light",
                     flagged: bool = True) -> int:
        """Without compute shaders: draw ``prog`` over the viewport once for each of
        ``layers`` (its ``uniform`` set to it), each picture copied into that layer of
        ``vis`` through a pixel buffer (on the GPU); the pixels it flagged in its second
        target counted (``flagged``). Returns their count.

        Parameters
        ----------
        prog : moderngl.Program
            A fragment program over shaders/fullscreen.vert.
        state : DrawState
            The draw (its viewport).
        vis : moderngl.TextureArray
            The visibility array.
        layers : iterable of int
            The layers to fill.
        uniform : str
            The uniform that says which.
        flagged : bool
            Count the second target's flags (rays that ran out).
        """
        return fill_layers(self.context, self._scratch, prog, state.viewport, vis, layers,
                           self._put, uniform, flagged)

    def _release_extra(self) -> None:
        for p in self._programs.values():
            p.release()
        self._programs.clear()
        self._scratch.release()
        if self._gbuffer is not None:
            for obj in self._gbuffer[2]:
                obj.release()
            self._gbuffer = None
        if self._visibility is not None:
            self._visibility[1].release()
            self._visibility = None
        if self._occluding is not None:
            self._occluding.release()
            self._occluding = None
        if self.maps is not None:
            self.maps.release()
            self.maps = None
        for _, _, texture in self._solid_data.values():
            texture.release()
        self._solid_data.clear()
