"""Float tables as GL objects: the one way glshade uploads numpy data a shader reads with
``texelFetch`` (include/data.glsl's ``data_texel``)."""

from __future__ import annotations

import numpy as np

__all__ = ["data_texture", "NEAREST"]

#: GL_NEAREST: a data texel is read whole, never blended with its neighbours
NEAREST = 0x2600


def data_texture(ctx, texels: np.ndarray, width: int):
    """An RGBA32F texture of ``texels (N, 4)`` in rows of ``width`` texels (``N`` a multiple
    of ``width``), filtered NEAREST. The caller owns it (keeps and releases it).

    Parameters
    ----------
    ctx : moderngl.Context
        The context.
    texels : ndarray
        ``(N, 4)`` float32.
    width : int
        Texels a row.
    """
    texels = np.ascontiguousarray(texels, np.float32).reshape(-1, 4)
    if len(texels) % width:
        raise ValueError(f"{len(texels)} texels do not fill rows of {width}")
    tex = ctx.texture((width, len(texels) // width), 4, texels.tobytes(), dtype="f4")
    tex.filter = (NEAREST, NEAREST)
    return tex
