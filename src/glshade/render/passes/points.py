"""Point clouds on the GPU (:class:`~glshade.geometry.points.PointCloud`): the stage that
draws them after the opaque surfaces' other stages, into the same z-buffer.

One draw call a cloud, ``GL_POINTS``: the geometry stage (``points.geom``) turns each point
into the quad that holds it on screen -- a sphere's exact screen box (in perspective the
projected sphere is an ellipse off the projected centre, so a square about the centre would
cut it), a square's own corners -- and the fragment stage (``points.frag``) casts the
pixel's ray against the sphere or disc, writing the hit's depth: an impostor, exact to
float32 at every pixel centre, that meets meshes where the surfaces really cross. Squares
write no depth of their own (early depth test: the cheap style for millions).

A cloud's arrays are uploaded once while it lives (float32 positions, radii, colours and
normals where it has them: 12 to 40 bytes a point) and dropped with it.
"""

from __future__ import annotations

import numpy as np

from ...geometry.points import PointCloud
from ...geometry.transforms import gl_bytes
from ...octree import CHUNK_SIZE, CHUNKED_FROM, point_chunks
from ..gpu_mesh import Chunks
from ...modes import ShadingMode
from ..arrays import GpuArrays, PerObject
from ..base import GLResource
from ..programs import ProgramKey, UniformWriter, lighting_products
from ..state import DrawState
from . import Stage

__all__ = ["PointPass", "point_defines", "cloud_gpu_bytes"]

#: the defines of each shading mode's point program (the lit modes light per pixel)
_MODE_DEFINES = {ShadingMode.NORMALS: ("SHOW_NORMALS",), ShadingMode.DEPTH: ("SHOW_DEPTH",),
                 ShadingMode.RADIOSITY: ("SHOW_DISPLAY",), ShadingMode.FLAT: ("FLAT_FACES",)}


def point_defines(cloud: PointCloud) -> tuple[str, ...]:
    """The ``#define``s of the program that draws clouds like ``cloud``: its style and the
    arrays it has.

    Parameters
    ----------
    cloud : PointCloud
        The cloud.
    """
    flags = ((f"STYLE_{cloud.style.name}", True), ("POINT_RADII", cloud.radii is not None),
             ("POINT_COLORS", cloud.colors is not None),
             ("POINT_NORMALS", cloud.normals is not None),
             ("PIXEL_SIZE", cloud.pixel_size is not None))
    return tuple(name for name, on in flags if on)


def cloud_gpu_bytes(cloud: PointCloud) -> int:
    """The bytes a cloud's GPU copy takes: 12 a point for positions, plus 4 for radii, 12
    for colours and 12 for normals where it has them, and 4 for the chunk order of a big
    cloud sized in the world (``glshade.octree.CHUNKED_FROM`` points or more).

    Parameters
    ----------
    cloud : PointCloud
        The cloud.
    """
    return sum(a.nbytes for _, a in cloud.arrays()) + 4 * len(cloud) * _chunked(cloud)


def _chunked(cloud: PointCloud) -> bool:
    """Whether a cloud is drawn by octree chunks (big, and sized in the world)."""
    return len(cloud) >= CHUNKED_FROM and cloud.pixel_size is None


def _gpu_cloud(ctx, cloud: PointCloud) -> GpuArrays:
    """A cloud's GPU copy. A big cloud (CHUNKED_FROM points or more, sized in the world) is
    drawn by octree chunks like a big mesh: an index buffer lists its points chunk by chunk,
    so a draw skips the chunks out of view while each point keeps its number (an indexed
    draw's gl_VertexID is the index)."""
    chunks = order = None
    if _chunked(cloud):
        order, starts = point_chunks(cloud.points, CHUNK_SIZE)
        grow = cloud.world_radii()[order, None]
        p = cloud.points[order]
        chunks = Chunks.of(starts, p - grow, p + grow)
    return GpuArrays(ctx, cloud.arrays(), order, chunks)


class PointPass(GLResource, Stage):
    """The point clouds' programs (per shading variant, style and arrays), their buffers
    and their draws, for one Renderer.

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    shaders : ShaderLibrary
        Where its programs are compiled.
    uniforms : UniformWriter
        The one uniform writer.
    """

    def __init__(self, context, shaders, uniforms: UniformWriter):
        super().__init__(context)
        self.shaders, self.uniforms = shaders, uniforms
        self._programs: dict = {}
        self._clouds = PerObject(lambda cloud: _gpu_cloud(context.ctx, cloud))
        #: clouds skipped by the last draw's frustum test
        self.culled = 0
        #: a big cloud's octree chunks skipped by the last draw (as a big mesh's)
        self.culled_chunks = 0

    def gpu_cloud(self, cloud: PointCloud) -> GpuArrays:
        """A cloud's GPU copy (its arrays, and a big one's chunk order and ``chunks``),
        uploaded once while it lives.

        Parameters
        ----------
        cloud : PointCloud
            The cloud.
        """
        self._check()
        return self._clouds(cloud)

    def program(self, key: ProgramKey, cloud: PointCloud):
        """The program of a variant for clouds like ``cloud`` (style, arrays).

        Parameters
        ----------
        key : ProgramKey
            The variant.
        cloud : PointCloud
            A cloud of the style and arrays wanted.
        """
        self._check()
        wanted = point_defines(cloud)
        found = self._programs.get((key, wanted))
        if found is None:
            defines = (*key.defines(), *wanted, *_MODE_DEFINES.get(key.mode, ()))
            found = self._programs[(key, wanted)] = self.shaders.compile(
                "points.vert", "points.frag", defines=defines, geom="points.geom")
        return found

    def wanted(self, state: DrawState) -> bool:
        return bool(state.scene.clouds)

    def draw(self, state: DrawState, id_base: int) -> int:
        """Draw the scene's visible clouds (their ids, a point each, follow from
        ``id_base``); the id base after them.

        Parameters
        ----------
        state : DrawState
            The draw.
        id_base : int
            The first polygon id free for this stage.
        """
        import moderngl

        self._check()
        ctx, put = self.context.ctx, self.uniforms.put
        clouds = state.scene.clouds
        self.culled = self.culled_chunks = 0
        outside = state.outside(clouds)
        view = state.view
        common = {**state.screen_uniforms(), "u_near": float(state.camera.planes()[0])}
        ctx.disable(moderngl.CULL_FACE)
        for index, model in enumerate(clouds):
            if not model.visible or outside[index]:
                self.culled += bool(model.visible)
                id_base += model.n_polygons
                continue
            cloud = model.cloud
            prog = self.program(ProgramKey.of(state.variant, two_sided=False), cloud)
            for name, value in state.frame_uniforms:
                put(prog, name, value)
            for name, value in common.items():
                put(prog, name, value)
            m = model.transform
            scale = model.scale
            values = {"u_model_view": gl_bytes(view @ m),
                      "u_normal_view": gl_bytes(view[:3, :3] @ m[:3, :3] / scale),
                      "u_radius": float(cloud.radius), "u_scale": scale,
                      "u_face_id_base": id_base,
                      "u_pixel_size": float(cloud.pixel_size or 0.0)}
            values.update(_material(model.material, state, cloud.colors is not None))
            for name, value in values.items():
                put(prog, name, value)
            gpu = self.gpu_cloud(cloud)
            vao = gpu.vertex_array(ctx, prog)
            chunks = gpu.chunks
            if chunks is not None and state.options.frustum_cull:
                ranges, skipped = chunks.in_view(state.view_proj @ m)
                self.culled_chunks += skipped
                for first, count in ranges:
                    vao.render(moderngl.POINTS, vertices=count, first=first)
            else:
                vao.render(moderngl.POINTS, vertices=cloud.n_points)
            id_base += model.n_polygons
        return id_base

    def _release_extra(self) -> None:
        self._clouds.release()
        self._programs.clear()  # (the shader library owns and frees them)


def _material(material, state: DrawState, per_point: bool) -> dict:
    """A cloud material's products: its own (as a mesh's), or with per-point colours each
    colour-borne product for a colour of 1, weighed by the point's colour in the shader
    (``u_color_weight``: 1 where the product is the colour's, 0 where the material gives
    it outright)."""
    colors = np.ones((1, 3)) if per_point else None
    ambient_term, diffuse, specular = lighting_products(material, state.lights,
                                                        state.scene.ambient, colors)
    ambient_from_color = material.ambient is None
    if material.illum == 0:  # (the diffuse colour is the whole term)
        ambient_from_color = material.diffuse is None
    return {"u_ambient_term": tuple(float(x) for x in ambient_term[0]),
            "u_light_diffuse": diffuse[0].tobytes(), "u_light_specular": specular.tobytes(),
            "u_shininess": float(material.shininess),
            "u_color_weight": (float(ambient_from_color), float(material.diffuse is None)),
            "u_emission": tuple(float(x) for x in np.asarray(material.emission, np.float64))}
