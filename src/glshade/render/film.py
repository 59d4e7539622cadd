"""The path tracer's film: where each image pixel lives in the GPU pass's targets.

The targets hold the image in 8x8 blocks, ``LAYOUT_BLOCKS`` a row, so that every tile of a
software rasterizer (a thread's unit of work) holds parts of the whole image (measured:
docs/guide/speed.md's table of tuning constants). Pure numpy (the
GL pass, ``render/passes/pathtrace.py``, uploads and reads through it; no GL here), so
the layout is testable without a GL.
"""

from __future__ import annotations

import numpy as np

__all__ = ["LAYOUT_BLOCKS", "MAX_BLOCK_ROWS", "film_layout", "film_places"]

#: 8x8 blocks a target row (more where the target would pass MAX_BLOCK_ROWS rows of blocks)
LAYOUT_BLOCKS = 64
#: the most rows of blocks a target has (8,192 pixel rows)
MAX_BLOCK_ROWS = 1024


def film_layout(width: int, height: int, per_row: int = LAYOUT_BLOCKS,
                max_side: int | None = None) -> tuple[tuple[int, int], tuple[int, int]]:
    """The targets' size for an image laid out in 8x8 blocks, and the shaders' ``u_blocks``.

    Parameters
    ----------
    width, height
        the image's size in pixels (at least 1 each).
    per_row
        8x8 blocks a target row (raised where the target would pass ``MAX_BLOCK_ROWS`` rows
        of blocks; lowered to the image's blocks when it has fewer).
    max_side
        The GL's largest framebuffer side in pixels, where known: a row never wider (the
        rows then pass MAX_BLOCK_ROWS rather than the target the GL's width).

    Returns
    -------
    (target width, target height), (the image's blocks a row, the target's blocks a row)
    """
    nbx = -(-int(width) // 8)
    n = nbx * -(-int(height) // 8)
    per_row = max(int(per_row), -(-n // MAX_BLOCK_ROWS))
    if max_side is not None:
        per_row = min(per_row, max(int(max_side) // 8, 1))
    per_row = min(per_row, n)
    return (8 * per_row, 8 * -(-n // per_row)), (nbx, per_row)


def film_places(width: int, height: int,
                blocks: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """Each image pixel's row and column in the targets (GL's rows, bottom first; the
    shaders' ``target_of``).

    Parameters
    ----------
    width, height
        the image's size in pixels.
    blocks
        :func:`film_layout`'s ``u_blocks``.

    Returns
    -------
    rows, columns
        (H, W) int arrays.
    """
    y, x = np.mgrid[0:int(height), 0:int(width)]
    nbx, per_row = blocks
    b = (y // 8) * nbx + x // 8
    return (b // per_row) * 8 + y % 8, (b % per_row) * 8 + x % 8
