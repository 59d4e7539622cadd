"""The hidden-surface lab: the classic algorithms of the notes, in numpy, each producing
the GPU renderer's outputs (polygon ids and view depth per pixel) so that they check each
other. Image space: :func:`zbuffer`, :func:`scanline`, :func:`raycast`; object space:
:func:`depth_sort` (Newell, Newell and Sancha) and :func:`bsp`.
"""

from .bsp import bsp
from .common import HiddenResult, Prepared, edge_pixels, prepare
from .raycast import raycast
from .zbuffer import zbuffer

__all__ = ["prepare", "Prepared", "HiddenResult", "edge_pixels", "zbuffer", "raycast", "bsp"]
