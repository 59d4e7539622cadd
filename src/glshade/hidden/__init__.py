"""The hidden-surface lab: the classic algorithms of the notes, in numpy, each producing
the GPU renderer's outputs (polygon ids and view depth per pixel) so that they check each
other. Image space: :func:`zbuffer`, :func:`scanline`, :func:`raycast`; object space:
:func:`depth_sort` (Newell, Newell and Sancha) and :func:`bsp`.
"""

from __future__ import annotations

import enum

from ..modes import parse_enum
from ._bsp import bsp
from .raster import edge_pixels
from .result import HiddenResult
from .view import Prepared, prepare
from .painter import DepthSortCycle, depth_sort
from ._raycast import raycast
from ._scanline import scanline
from ._zbuffer import zbuffer

__all__ = ["prepare", "Prepared", "HiddenResult", "edge_pixels", "zbuffer", "scanline",
           "raycast", "depth_sort", "bsp", "DepthSortCycle", "Algorithm", "ALGORITHMS", "run"]


class Algorithm(str, enum.Enum):
    """The lab's hidden-surface algorithms (the GPU's z-buffer is the reference)."""

    ZBUFFER = "zbuffer"
    SCANLINE = "scanline"
    DEPTH_SORT = "depth-sort"
    BSP = "bsp"
    RAYCAST = "raycast"

    @classmethod
    def parse(cls, value: object) -> Algorithm:
        """An Algorithm or its name; a bad name lists the choices.

        Parameters
        ----------
        value : Algorithm or str
            A member or its name.
        """
        return parse_enum(cls, value, "hidden-surface algorithm")


#: an algorithm's name -> function(prepared) -> HiddenResult
ALGORITHMS = {Algorithm.ZBUFFER.value: zbuffer, Algorithm.SCANLINE.value: scanline,
              Algorithm.DEPTH_SORT.value: depth_sort, Algorithm.BSP.value: bsp,
              Algorithm.RAYCAST.value: raycast}


def run(algorithm: Algorithm | str, scene_or_mesh, camera, size=(256, 256)) -> HiddenResult:
    """Run ``algorithm`` on a Scene or Mesh seen by ``camera``.

    Parameters
    ----------
    algorithm : Algorithm or str
        The hidden-surface algorithm.
    scene_or_mesh : Scene or Mesh
        What to view.
    camera : Camera
        From where.
    size : (int, int)
        Width and height in pixels.
    """
    return ALGORITHMS[Algorithm.parse(algorithm).value](prepare(scene_or_mesh, camera, size))
