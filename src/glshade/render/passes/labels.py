"""Text labels over the viewer's panes ("flat", "gouraud", "phong" in the split view), as
the compare grid labels its tiles: Pillow draws the text (:func:`glshade.io.images.label_image`),
one textured quad shows it."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...io.images import LABEL_HEIGHT, label_image
from ..base import GLResource
from ..programs import UniformWriter
from ..units import Unit

__all__ = ["LabelOverlay"]


class LabelOverlay(GLResource):
    """Draws text bands at the top of viewports; textures are made once per text and
    width, and freed with the overlay.

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    shaders : ShaderLibrary
        Where its programs are compiled.
    """

    def __init__(self, context, shaders):
        super().__init__(context)
        self.program = shaders.compile("overlay.vert", "overlay.frag")
        self._keep(self.program)
        UniformWriter().put(self.program, "u_image", Unit.LABEL)  # (the one unit it reads)
        quad = np.array([[-1, -1, 0, 0], [1, -1, 1, 0], [-1, 1, 0, 1], [1, 1, 1, 1]], "f4")
        self.vbo = self._keep(context.ctx.buffer(quad.tobytes()))
        self.vao = self._keep(context.ctx.vertex_array(
            self.program, [(self.vbo, "2f 2f", "in_ndc", "in_uv")]))
        self._textures: dict[tuple[str, int], Any] = {}

    def _texture(self, text: str, width: int):
        key = (text, width)
        if key not in self._textures:
            img = label_image(text, width)[::-1]  # GL's rows run bottom-up
            tex = self.context.ctx.texture((width, LABEL_HEIGHT), 4, np.ascontiguousarray(img))
            self._textures[key] = tex
        return self._textures[key]

    def draw(self, text: str, viewport: tuple[int, int, int, int]) -> None:
        """The label band across the top of ``viewport`` (x, y, w, h; GL's origin).

        Parameters
        ----------
        text : str
            The label.
        viewport : (int, int, int, int)
            ``(x, y, w, h)``, GL's origin.
        """
        self._check()
        x, y, w, h = viewport
        ctx = self.context.ctx
        band = min(LABEL_HEIGHT, h)
        ctx.viewport = (x, y + h - band, w, band)
        self._texture(text, w).use(Unit.LABEL)
        ctx.disable(ctx.DEPTH_TEST)
        self.vao.render(mode=ctx.TRIANGLE_STRIP)
        ctx.viewport = viewport

    def _release_extra(self) -> None:
        for tex in self._textures.values():
            tex.release()
        self._textures.clear()
