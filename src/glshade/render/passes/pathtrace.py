"""The GPU half of the path tracer: the scene's tables (:mod:`glshade.pathtrace.pack`) in one
float texture, the program (``shaders/pathtrace.frag``) and the accumulation targets it adds
to pass after pass."""

from __future__ import annotations

import numpy as np

from ...geometry.transforms import gl_bytes
from ...solids.encoding import ROW, tree_data
from ..base import GLResource
from ..data import data_texture
from ..shaders import ShaderLibrary
from .csg import csg_defines

__all__ = ["GpuPathTracer"]

class GpuPathTracer(GLResource):
    """Path-trace ``scene`` (a :class:`glshade.pathtrace.TraceScene`, whose ``tables()``
    give the texels) at ``width x height``: each
    :meth:`run` adds passes of ``samples`` paths per pixel; :meth:`read` returns the sums.
    The pass number seeds each sample, so a pixel's k-th sample is the same whatever the
    passes are grouped into."""

    def __init__(self, context, scene, width: int, height: int, *,
                 samples: int = 1, max_depth: int = 64, shaders: ShaderLibrary | None = None,
                 rays: np.ndarray | None = None):
        super().__init__(context)
        ctx = context.ctx
        self.scene, self.width, self.height = scene, int(width), int(height)
        self.samples, self.max_depth = int(samples), int(max_depth)
        self._shaders = shaders or self._keep(ShaderLibrary(context))
        data, self.layout = scene.tables()
        width = self.layout["width"]
        defines: tuple[str, ...] = (f"SAMPLES {self.samples}", f"DATA_WIDTH {width}")
        if scene.shading is not None:
            defines += ("SMOOTH_NORMALS",)
        self._csg = None
        if scene.solids:
            solid, material = scene.solids[0]
            tree = tree_data(solid)
            defines += ("CSG_SOLID", *csg_defines(tree, blocks=False))
            self._csg = self._keep(data_texture(ctx, tree.texels, ROW))
            self._csg_values = {
                "u_csg": 2, "u_csg_material": material, **tree.offsets(),
                "u_csg_start": tree.nodes,  # (a path's rays start anywhere: always look)
                "u_csg_kind_start": np.array(tree.kind_start, "i4")}
        self._rays = None
        if rays is not None:  # (H, W, 2, 3): each pixel's ray origin and unit direction
            texels = np.zeros((self.height, 2, self.width, 4), np.float32)
            texels[:, :, :, :3] = np.asarray(rays, np.float32).transpose(0, 2, 1, 3)
            self._rays = self._keep(data_texture(ctx, texels, self.width))
            defines += ("PROBES",)
        self.program = self._keep(self._shaders.compile("pathtrace.vert", "pathtrace.frag",
                                                        defines=defines))
        self._write(self._static_uniforms())  # (the program is this tracer's: they stay)
        self.texture = self._keep(data_texture(ctx, data, width))
        self._sum = self._keep(ctx.texture((self.width, self.height), 4, dtype="f4"))
        self._square = self._keep(ctx.texture((self.width, self.height), 4, dtype="f4"))
        self._hit = self._keep(ctx.texture((self.width, self.height), 4, dtype="f4"))
        self.fbo = self._keep(ctx.framebuffer([self._sum, self._square, self._hit]))
        self.vao = self._keep(ctx.vertex_array(self.program, []))
        self.passes = 0
        self.reset()

    def _write(self, values: dict) -> None:
        prog = self.program
        for name, value in values.items():
            if name in prog:  # (the compiler drops what a variant does not use)
                if isinstance(value, np.ndarray):  # (an int array; the compiler may trim it)
                    prog[name].write(value[:prog[name].array_length].tobytes())
                elif isinstance(value, bytes):
                    prog[name].write(value)
                else:
                    prog[name].value = value

    def _static_uniforms(self) -> dict:
        """The uniforms that stay for this tracer's life: sizes, tables, lights, the solid."""
        values: dict = {"u_size": (float(self.width), float(self.height)),
                        "u_max_depth": self.max_depth, "u_eps": 1e-5 * self.scene.size,
                        "u_data": 0, "u_rays": 1, "u_n_lights": len(self.scene.lights)}
        values.update((k, v) for k, v in self.layout.items() if k.startswith("u_"))
        if self._csg is not None:
            values.update(self._csg_values)
        lights = self.scene.lights
        if len(lights):
            pos = np.zeros((8, 4), np.float32)
            pos[:len(lights), :3], pos[:len(lights), 3] = lights[:, 1:4], lights[:, 0]
            irr = np.zeros((8, 3), np.float32)
            irr[:len(lights)] = lights[:, 4:7]
            att = np.zeros((8, 3), np.float32)
            att[:len(lights)] = lights[:, 7:10]
            values.update(u_light_pos=pos.tobytes(), u_light_irr=irr.tobytes(),
                          u_light_att=att.tobytes())
        return values

    def reset(self) -> None:
        """Forget every sample (a new camera)."""
        self._check()
        self.fbo.clear(0.0, 0.0, 0.0, 0.0)
        self.passes = 0

    def run(self, camera, passes: int = 1, seed: int = 0) -> None:
        """Add ``passes`` passes of samples seen from ``camera`` (None for given rays)."""
        import moderngl

        self._check()
        ctx = self.context.ctx
        prog = self.program
        aspect = self.width / self.height
        values: dict = {"u_seed": int(seed) & 0xFFFFFFFF}
        if camera is not None:
            vp = camera.projection_matrix(aspect) @ camera.view_matrix()
            values["u_inverse_view_proj"] = gl_bytes(np.linalg.inv(vp))
        self._write(values)
        if self._csg is not None:
            self._csg.use(location=2)
        self.texture.use(location=0)
        if self._rays is not None:
            self._rays.use(location=1)
        self.fbo.use()
        ctx.viewport = (0, 0, self.width, self.height)
        ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        ctx.enable(moderngl.BLEND)
        ctx.blend_func = moderngl.ONE, moderngl.ONE
        try:
            for _ in range(int(passes)):
                prog["u_pass"].value = self.passes
                self.vao.render(moderngl.TRIANGLES, vertices=3)
                self.passes += 1
        finally:
            ctx.disable(moderngl.BLEND)
            ctx.blend_func = moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA

    def show(self, fbo, exposure: float, srgb: bool = False) -> None:
        """Draw the picture so far (mean times ``exposure``, clipped) into ``fbo``, a
        framebuffer of this size (a window's): what the viewer's progressive mode shows."""
        import moderngl

        self._check()
        if getattr(self, "_show", None) is None:
            self._show = self._keep(self._shaders.compile("pathtrace.vert",
                                                          "pathtrace_show.frag"))
            self._show_vao = self._keep(self.context.ctx.vertex_array(self._show, []))
        fbo.use()
        ctx = self.context.ctx
        ctx.viewport = (0, 0, self.width, self.height)
        ctx.disable(moderngl.DEPTH_TEST | moderngl.BLEND)
        self._sum.use(location=0)
        self._show["u_sum"].value = 0
        self._show["u_exposure"].value = float(exposure)
        self._show["u_srgb"].value = bool(srgb)
        self._show_vao.render(moderngl.TRIANGLES, vertices=3)

    def _release_extra(self) -> None:
        self.context.rest()  # (never release the bound framebuffer)

    def read(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(sum, square, hits): ``(H, W, 4)`` float64, top row first: the samples' sum
        (RGB) and count (A); the sum of their squares (RGB) and of first hits on an
        emitter (A); the count of camera rays that hit anything (R)."""
        self._check()
        out = []
        for tex in (self._sum, self._square, self._hit):
            a = np.frombuffer(tex.read(), np.float32).reshape(self.height, self.width, 4)
            out.append(a[::-1].astype(np.float64))
        return out[0], out[1], out[2]
