"""A scene's sky in the rasterizer (:class:`~glshade.Environment`): drawn where nothing
else is (``background.frag``, each pixel's view direction looked up in the map), and the
image-based light of glTF's model -- the sky prefiltered by roughness, its irradiance and
the split-sum table (:mod:`glshade.scene.environment` makes them; environment_light.glsl
reads them) -- bound for the draw's programs. The first stage of a frame's pipeline."""

from __future__ import annotations

from typing import Any

import moderngl
import numpy as np

from ...geometry.transforms import gl_bytes
from ...modes import Outputs
from ..base import GLResource
from ..programs import TEXTURED_MODES
from ..state import DrawState
from ..units import Unit
from . import Stage

__all__ = ["EnvironmentPass"]


class EnvironmentPass(GLResource, Stage):
    """The sky's textures (one environment's at a time, made again when the scene's
    changes) and the background program, for one Renderer.

    Parameters
    ----------
    context
        the RenderContext drawn with.
    shaders
        its shader library.
    uniforms
        the Renderer's uniform writer.
    """

    def __init__(self, context, shaders, uniforms):
        super().__init__(context)
        self.shaders, self.uniforms = shaders, uniforms
        self._made: tuple[Any, list] | None = None  # (the environment, its textures)
        self._programs: dict[bool, Any] = {}

    def wanted(self, state: DrawState) -> bool:
        return state.scene.environment is not None and state.options.mode in TEXTURED_MODES

    def _texture(self, image: np.ndarray, *, repeat_x: bool, nearest: bool = False):
        h, w, c = image.shape
        tex = (self.context.ctx.texture(
            (w, h), c, np.ascontiguousarray(image, "f4").tobytes(), dtype="f4"))
        f = moderngl.NEAREST if nearest else moderngl.LINEAR
        tex.filter = (f, f)
        tex.repeat_x, tex.repeat_y = repeat_x, False
        return tex

    def _textures(self, environment) -> list:
        """The environment's four textures (made once for it): the map, its levels, its
        irradiance, the split-sum table."""
        if self._made is not None and self._made[0] is environment:
            return self._made[1]
        from ...scene.environment import IBL_LEVELS, irradiance, prefiltered

        self._release_extra()  # (the last environment's)
        levels = prefiltered(environment)
        specular = self._texture(levels[0], repeat_x=True)
        specular.build_mipmaps(0, IBL_LEVELS - 1)
        for k, level in enumerate(levels[1:], 1):
            specular.write(np.ascontiguousarray(level, "f4").tobytes(), level=k)
        specular.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
        made = [self._texture(np.asarray(environment.image), repeat_x=True, nearest=True),
                specular, self._texture(irradiance(environment), repeat_x=True),
                self._texture(_split_sum(), repeat_x=False)]
        self._made = (environment, made)
        return made

    def _release_extra(self) -> None:
        if self._made is not None:
            for tex in self._made[1]:
                tex.release()
            self._made = None

    def prepare(self, state: DrawState) -> DrawState:
        """Bind the sky's textures; the draw's programs read their units.

        Parameters
        ----------
        state : DrawState
            The draw.
        """
        from ...scene.environment import IBL_LEVELS

        self._check()
        background, specular, irr, split = self._textures(state.scene.environment)
        background.use(location=Unit.ENV_BACKGROUND)
        specular.use(location=Unit.ENV_SPECULAR)
        irr.use(location=Unit.ENV_IRRADIANCE)
        split.use(location=Unit.ENV_SPLIT_SUM)
        return state.with_uniforms({"u_env_specular": Unit.ENV_SPECULAR,
                                    "u_env_irradiance": Unit.ENV_IRRADIANCE,
                                    "u_env_split_sum": Unit.ENV_SPLIT_SUM,
                                    "u_env_levels": float(IBL_LEVELS)})

    def draw(self, state: DrawState, id_base: int) -> int:
        """The sky where nothing is drawn: a triangle over the viewport, before every
        surface, into the colour alone (ids, depth and normals stay the background's).

        Parameters
        ----------
        state : DrawState
            The draw.
        id_base : int
            The first polygon id free for this stage.
        """
        if not state.clear:
            return id_base
        srgb = bool(state.options.srgb)
        found = self._programs.get(srgb)
        if found is None:
            compiled = self._keep(self.shaders.compile(
                "fullscreen.vert", "background.frag", defines=("SRGB",) if srgb else ()))
            found = self._programs[srgb] = (compiled, self._keep(
                self.context.ctx.vertex_array(compiled, [])))
        prog, vao = found
        environment = state.scene.environment
        x, y, w, h = state.viewport
        put = self.uniforms.put
        put(prog, "u_env_background", Unit.ENV_BACKGROUND)
        put(prog, "u_inverse_view_proj", gl_bytes(np.linalg.inv(state.view_proj)))
        put(prog, "u_viewport_origin", (float(x), float(y)))
        put(prog, "u_viewport_size", (float(w), float(h)))
        put(prog, "u_env_rotation", float(environment.rotation))
        put(prog, "u_env_intensity", float(environment.intensity))
        ctx = self.context.ctx
        state.target.bind(Outputs.COLOR)
        ctx.disable(moderngl.DEPTH_TEST)
        vao.render(moderngl.TRIANGLES, vertices=3)
        if state.options.depth_test:
            ctx.enable(moderngl.DEPTH_TEST)
        state.target.bind(state.options.outputs)
        return id_base


_SPLIT_SUM: list = []


def _split_sum() -> np.ndarray:
    """The split-sum table, computed once a process (0.2 s)."""
    if not _SPLIT_SUM:
        from ...scene.environment import split_sum_table

        _SPLIT_SUM.append(split_sum_table())
    return _SPLIT_SUM[0]
