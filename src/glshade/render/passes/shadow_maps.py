"""Shadow maps, the fast method of :mod:`glshade.render.passes.shadows`: each light's depth
map drawn from the scene's triangles (kept while the geometry and the light stay: a moving
camera draws none),
then looked up per pixel with percentage-closer filtering (shaders/shadow_maps.comp).

A directional light's map is orthographic, fitted to the scene's box; a point light's is a
cube (six square faces of 90 degrees, tiles of one depth texture). The bias is the texel's
footprint on the surface times its slope against the light (in the shader). CSG solids
receive map shadows but cast none (they are ray cast, not triangles): ``exact`` casts theirs.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...errors import RenderWarning, warn_user
from ...geometry.transforms import gl_bytes, look_at, orthographic, perspective
from ..base import GLResource
from ..programs import UniformWriter
from ..units import Binding, Unit

__all__ = ["ShadowMaps", "LayerScratch", "fill_layers", "MAP_SIZE", "CUBE_SIZE", "PCF_RADIUS",
           "shadow_lights"]

#: texels a side of a directional light's map
MAP_SIZE = 2048
#: texels a side of each of a point light's six cube faces
CUBE_SIZE = 1024
#: percentage-closer filtering over (2 R + 1)^2 texels (the shader's PCF_RADIUS)
PCF_RADIUS = 1

#: a cube's faces: the direction each looks along and its up (GL's cube-map order)
_FACES = (((1, 0, 0), (0, -1, 0)), ((-1, 0, 0), (0, -1, 0)), ((0, 1, 0), (0, 0, 1)),
          ((0, -1, 0), (0, 0, -1)), ((0, 0, 1), (0, -1, 0)), ((0, 0, -1), (0, -1, 0)))


def light_frames(light_row: np.ndarray, bounds: np.ndarray):
    """The views and projections of one light's map over a scene box ``bounds (2, 3)``:
    ``(views [(4, 4)], proj (4, 4), facts)``; facts: "faces", "size", "planes" (a point
    light's near and far) or "ortho" (half width, half height, near, far)."""
    lo, hi = np.asarray(bounds, np.float64)
    centre = (lo + hi) / 2
    radius = max(float(np.linalg.norm(hi - lo)) / 2, 1e-12)
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                        for z in (lo[2], hi[2])])
    if light_row[3] < 0.5:  # directional: orthographic along the light's direction
        to = light_row[:3] / np.linalg.norm(light_row[:3])
        up = (0.0, 1.0, 0.0) if abs(to[1]) < 0.9 else (1.0, 0.0, 0.0)
        view = look_at(centre + to * 2 * radius, centre, up)
        q = corners @ view[:3, :3].T + view[:3, 3]
        half = max(float(np.abs(q[:, :2]).max()), 1e-12) * 1.01
        near, far = float(-q[:, 2].max()), float(-q[:, 2].min())
        pad = 0.01 * (far - near) + 1e-9 * radius
        near, far = near - pad, far + pad
        proj = orthographic(2 * half, 1.0, near, far)
        return [view], proj, {"faces": 1, "size": MAP_SIZE, "ortho": (half, half, near, far)}
    p = light_row[:3].astype(np.float64)
    gap = np.maximum(np.maximum(lo - p, p - hi), 0.0)
    far = float(np.linalg.norm(corners - p, axis=1).max()) * 1.01
    near = max(float(np.linalg.norm(gap)) * 0.5, 1e-3 * radius, 1e-6 * far)
    views = [look_at(p, p + np.asarray(d, float), up) for d, up in _FACES]
    proj = perspective(90.0, 1.0, near, far)
    return views, proj, {"faces": 6, "size": CUBE_SIZE, "planes": (near, far)}


def shadow_lights(lights) -> np.ndarray:
    """``(L, 4)`` float32 rows the compute programs read: a point light's world position
    with w = 1, a directional light's unit vector towards it with w = 0; w = 2 for a light
    that casts no shadows.

    Parameters
    ----------
    lights : sequence
        The draw's lights.
    """
    rows = np.zeros((max(len(lights), 1), 4), np.float32)
    for i, light in enumerate(lights):
        if hasattr(light, "position"):
            rows[i] = (*light.position, 1.0)
        else:
            rows[i] = (*(-np.asarray(light.direction)), 0.0)
        if not getattr(light, "shadows", True):
            rows[i, 3] = 2.0
    return rows


class LayerScratch:
    """The targets of a fragment pass that fills the layers of a visibility array where
    the GL has no compute shaders: an R8 picture, an R8 target of flags, and the pixel
    buffer that carries the picture into a layer -- made once a size.

    Parameters
    ----------
    ctx : moderngl.Context
        The context.
    """

    def __init__(self, ctx):
        self.ctx = ctx
        self._made: tuple | None = None  # (size, fbo, picture, flags, pixel buffer)

    def at(self, width: int, height: int) -> tuple:
        """``(framebuffer, picture, flags, pixel buffer)`` of ``width x height``.

        Parameters
        ----------
        width, height : int
            The visibility array's size in pixels.
        """
        if self._made is None or self._made[0] != (width, height):
            self.release()
            from ..data import NEAREST

            ctx = self.ctx
            picture = ctx.texture((width, height), 1, dtype="f1")
            flags = ctx.texture((width, height), 1, dtype="f1")
            for tex in (picture, flags):
                tex.filter = (NEAREST, NEAREST)
            self._made = ((width, height), ctx.framebuffer([picture, flags]), picture, flags,
                          ctx.buffer(reserve=width * height))
        return self._made[1:]

    def release(self) -> None:
        if self._made is not None:
            for obj in self._made[:0:-1]:
                obj.release()
            self._made = None


def fill_layers(context, scratch: LayerScratch, prog, viewport, vis, layers, put,
                uniform: str, flagged: bool) -> int:
    """Draw the fragment program ``prog`` (over shaders/fullscreen.vert) in ``viewport``
    once for each of ``layers``, its ``uniform`` set to the layer; copy each picture into
    that layer of the array ``vis`` (a pixel buffer: it never leaves the GPU); count the
    pixels its second output flagged (``flagged``). Returns the count.

    Parameters
    ----------
    context : RenderContext
        The context.
    scratch : LayerScratch
        The pass's targets.
    prog : moderngl.Program
        The fragment program.
    viewport : tuple of int
        ``(x, y, w, h)`` in the array's pixels.
    vis : moderngl.TextureArray
        The R8 array filled.
    layers : iterable of int
        Its layers to fill.
    put : callable
        Writes ``prog``'s uniforms.
    uniform : str
        The uniform that says which layer.
    flagged : bool
        Count the flags.
    """
    import moderngl

    ctx = context.ctx
    width, height, _ = vis.size
    fbo, _, flags, pixels = scratch.at(width, height)
    x, y, w, h = (int(v) for v in viewport)
    vao = ctx.vertex_array(prog, [])
    count = 0
    fbo.use()
    ctx.viewport = (x, y, w, h)
    ctx.disable(moderngl.DEPTH_TEST | moderngl.BLEND | moderngl.CULL_FACE)
    try:
        for layer in layers:
            put(prog, uniform, int(layer))
            vao.render(moderngl.TRIANGLES, vertices=3)
            fbo.read_into(pixels, (x, y, w, h), components=1, attachment=0, alignment=1)
            vis.write(pixels, (x, y, int(layer), w, h, 1), alignment=1)
            if flagged:
                seen = np.frombuffer(fbo.read((x, y, w, h), components=1, attachment=1,
                                              alignment=1), np.uint8)
                count += int(np.count_nonzero(seen))
    finally:
        vao.release()
        context.rest()
    return count


class ShadowMaps(GLResource):
    """The depth maps of a Renderer's lights and the program that draws them.

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    shaders : ShaderLibrary
        Where its programs are compiled.
    scratch : LayerScratch or None
        The targets its fragment lookups draw into (None: its own).
    """

    def __init__(self, context, shaders, scratch: LayerScratch | None = None):
        super().__init__(context)
        self.shaders = shaders
        self._maps: dict[int, tuple] = {}    # light index -> (key, texture, framebuffer)
        self._soup: tuple | None = None      # (key, buffer, vertex array)
        self._program = None
        self._put = UniformWriter().put
        self._lookup: dict[bool, Any] = {}
        #: per light of the last draw: (faces, texels a side, texel footprint in pixels)
        self.facts: list[tuple[int, int, float]] = []
        self._warned_solids = False
        # (the fragment lookups' targets: the shadow pass's own, shared, where it has them)
        self._owns_scratch = scratch is None
        self._scratch = LayerScratch(context.ctx) if scratch is None else scratch

    def _soup_for(self, key, triangles: np.ndarray):
        if self._soup is None or self._soup[0] != key:
            if self._soup is not None:
                self._soup[2].release()
                self._soup[1].release()
            ctx = self.context.ctx
            if self._program is None:
                self._program = self._keep(self.shaders.compile("shadow_depth.vert",
                                                                "shadow_depth.frag"))
            data = np.ascontiguousarray(triangles.reshape(-1, 3), np.float32)
            buf = ctx.buffer(data.tobytes() if len(data) else np.zeros(9, "f4").tobytes())
            vao = ctx.vertex_array(self._program, [(buf, "3f", "in_position")])
            self._soup = (key, buf, vao, len(data))
        return self._soup

    def _draw_map(self, index: int, key, soup, views, proj, facts) -> Any:
        """The light's depth texture, drawn anew only when its key changed."""
        import moderngl

        found = self._maps.get(index)
        if found is not None and found[0] == key:
            return found[1]
        if found is not None:
            found[2].release()
            found[1].release()
        ctx = self.context.ctx
        size, faces = facts["size"], facts["faces"]
        shape = (3 * size, 2 * size) if faces == 6 else (size, size)
        tex = ctx.depth_texture(shape)
        tex.compare_func = ""
        tex.filter = (moderngl.NEAREST, moderngl.NEAREST)
        fbo = ctx.framebuffer(depth_attachment=tex)
        fbo.use()
        fbo.clear(depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.CULL_FACE)
        for f, view in enumerate(views):
            ctx.viewport = ((f % 3) * size, (f // 3) * size, size, size) if faces == 6 else \
                (0, 0, size, size)
            self._put(self._program, "u_mvp", gl_bytes(proj @ view))
            if soup[3]:
                soup[2].render(moderngl.TRIANGLES)
        self._maps[index] = (key, tex, fbo)
        return tex

    def draw_maps(self, state, occluders: tuple[tuple, np.ndarray]) -> list[tuple]:
        """Each light's map, drawn when its geometry or light changed: ``[(texture, light
        row, face views, facts)]``; :attr:`facts` keeps each one's size and footprint.

        Parameters
        ----------
        state
            the draw's facts (its scene, lights, camera).
        occluders
            ``(key, (T, 3, 3) world triangles)``: what casts, and the key of the geometry it
            was gathered for (a map is drawn again when it changes).
        """
        if state.scene.solids and not self._warned_solids:
            self._warned_solids = True
            warn_user("CSG solids receive map shadows but cast none (they are ray cast, "
                          "not drawn into the maps): shadows='exact' casts theirs",
                          RenderWarning)
        geometry, triangles = occluders
        soup = self._soup_for(geometry, triangles)
        bounds = np.asarray(state.scene.bounds, np.float64)
        out = []
        self.facts = []
        for i, row in enumerate(shadow_lights(state.lights)[:len(state.lights)]):
            views, proj, facts = light_frames(row.astype(np.float64), bounds)
            key = (geometry, row.tobytes(), bounds.tobytes())
            out.append((self._draw_map(i, key, soup, views, proj, facts), row, views, facts))
            self.facts.append((facts["faces"], facts["size"],
                               self._footprint(state, views, facts, bounds)))
        return out

    @staticmethod
    def lookup_uniforms(maps: list[tuple], units: list[int]) -> dict:
        """shadow_lookup.glsl's arrays for ``maps`` (from :meth:`draw_maps`), their
        textures on ``units``.

        Parameters
        ----------
        maps : list of tuple
            The maps (:meth:`draw_maps`).
        units : list of int
            Their texture units.
        """
        views = []
        for _, _, v, _ in maps:
            views += [gl_bytes(m) for m in v] + [gl_bytes(np.eye(4))] * (6 - len(v))
        return {"u_maps": np.array(units, "i4"),
                "u_map_light": np.array([row for _, row, _, _ in maps], "f4"),
                "u_map_shape": np.array([(f["faces"], f["size"]) for *_, f in maps], "i4"),
                "u_face_view": b"".join(views),
                "u_face_planes": np.array([f.get("planes", (1.0, 2.0)) for *_, f in maps],
                                          "f4"),
                "u_ortho": np.array([f.get("ortho", (1.0, 1.0, 0.0, 1.0)) for *_, f in maps],
                                    "f4")}

    def forward(self, state, occluders: tuple[tuple, np.ndarray], first_unit: int) -> dict:
        """For a draw that looks its maps up as it shades (SHADOW_MAPS_FORWARD): the maps
        bound from ``first_unit`` on, and the uniforms every program of the draw takes.

        Parameters
        ----------
        state : DrawState
            The draw.
        occluders : (tuple, ndarray)
            ``(key, (T, 3, 3) world triangles)``: what casts shadows.
        first_unit : int
            The first texture unit for the maps.
        """
        maps = self.draw_maps(state, occluders)
        units = [first_unit + i for i in range(len(maps))]
        for (tex, *_), unit in zip(maps, units):
            tex.use(unit)
        values = self.lookup_uniforms(maps, units)
        values["u_camera_to_world"] = gl_bytes(np.linalg.inv(state.view))
        return values

    def fill(self, state, occluders: tuple[tuple, np.ndarray], gbuf, vis, put) -> None:
        """Each light's map (:meth:`draw_maps`), then its layer of ``vis`` by PCF lookups
        at the G-buffer ``gbuf``'s points (the visibility a frame reads back); ``put``
        writes the lookup program's uniforms.

        Parameters
        ----------
        state : DrawState
            The draw.
        occluders : (tuple, ndarray)
            ``(key, (T, 3, 3) world triangles)``: what casts shadows.
        gbuf : GBuffer
            The draw's surface points.
        vis : moderngl.Texture
            The visibility array.
        put : callable
            Writes the lookup program's uniforms.
        """
        from ...scene.camera import Projection
        from .gbuffer import bind_gbuffer

        maps = self.draw_maps(state, occluders)
        ortho = state.camera.projection is Projection.ORTHOGRAPHIC
        storage = self.context.features.storage
        prog = self._lookup.get(ortho)
        if prog is None:
            defines = ("ORTHOGRAPHIC",) if ortho else ()
            if storage:
                from ..shaders import assemble, compile_compute

                source, _ = assemble("shadow_maps.comp", defines=defines)
                prog = compile_compute(self.context, source)
            else:  # (no compute shaders: a fragment program drawn over the viewport)
                prog = self.shaders.compile("fullscreen.vert", "shadow_maps.frag",
                                            defines=defines)
            self._lookup[ortho] = prog
        bind_gbuffer(put, prog, state, gbuf)
        for i, one in enumerate(maps):
            one[0].use(Unit.LOOKUP_MAP)
            values = self.lookup_uniforms([one], [Unit.LOOKUP_MAP])
            for name, value in values.items():
                put(prog, name, value)
            if not storage:
                fill_layers(self.context, self._scratch, prog, state.viewport, vis, [i], put,
                            "u_layer", flagged=False)
                continue
            put(prog, "u_layer", i)
            vis.bind_to_image(Binding.VISIBILITY_IMAGE, read=False, write=True)
            _, _, w, h = (int(v) for v in state.viewport)
            prog.run(math.ceil(w / 8), math.ceil(h / 8), 1)
        if storage:
            self.context.ctx.memory_barrier()

    @staticmethod
    def _footprint(state, views, facts, bounds) -> float:
        """A map texel's width over a pixel's, at the scene's centre (how coarse the map is
        on screen: above 1, its texels show as steps along a shadow's edge)."""
        from ...scene.camera import Projection

        centre = np.asarray(bounds, np.float64).mean(0)
        if facts["faces"] == 6:
            light = np.linalg.inv(views[0])[:3, 3]
            texel = 2 * float(np.linalg.norm(centre - light)) / facts["size"]
        else:
            texel = 2 * facts["ortho"][0] / facts["size"]
        cam = state.camera
        height = state.viewport[3]
        if cam.projection is Projection.ORTHOGRAPHIC:
            pixel = cam.height / height
        else:
            depth = max(-(state.view[:3, :3] @ centre + state.view[:3, 3])[2], 1e-12)
            pixel = 2 * depth * math.tan(math.radians(cam.fov_y) / 2) / height
        return texel / pixel

    def summary(self) -> str:
        """One line: each light's map size and its texel footprint in pixels."""
        parts = [f"{'6x' if faces == 6 else ''}{size}x{size} ({'cube' if faces == 6 else '2D'}"
                 f", a texel {fp:.2g} px)" for faces, size, fp in self.facts]
        return "shadow maps: " + "; ".join(parts) + f", PCF {2 * PCF_RADIUS + 1}x" \
            f"{2 * PCF_RADIUS + 1}"

    def _release_extra(self) -> None:
        for _, tex, fbo in self._maps.values():
            fbo.release()
            tex.release()
        self._maps.clear()
        if self._soup is not None:
            self._soup[2].release()
            self._soup[1].release()
            self._soup = None
        for p in self._lookup.values():
            p.release()
        self._lookup.clear()
        if self._owns_scratch:
            self._scratch.release()
