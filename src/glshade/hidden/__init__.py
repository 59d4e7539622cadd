"""The hidden-surface lab: the classic algorithms of the notes, in numpy, each producing
the GPU renderer's outputs (polygon ids and view depth per pixel) so that they check each
other. Image space: :func:`zbuffer`, :func:`scanline`, :func:`raycast`; object space:
:func:`depth_sort` (Newell, Newell and Sancha) and :func:`bsp`.
"""

from ._bsp import bsp
from .common import HiddenResult, Prepared, edge_pixels, prepare
from ._depth_sort import DepthSortCycle, depth_sort
from ._raycast import raycast
from ._scanline import scanline
from ._zbuffer import zbuffer

__all__ = ["prepare", "Prepared", "HiddenResult", "edge_pixels", "zbuffer", "scanline",
           "raycast", "depth_sort", "bsp", "DepthSortCycle", "ALGORITHMS", "run"]

#: name -> function(prepared) -> HiddenResult
ALGORITHMS = {"zbuffer": zbuffer, "scanline": scanline, "depth-sort": depth_sort,
              "bsp": bsp, "raycast": raycast}


def run(name: str, scene_or_mesh, camera, size=(256, 256)) -> HiddenResult:
    """Run the algorithm ``name`` on a Scene or Mesh seen by ``camera``."""
    from ..errors import InputError

    if name not in ALGORITHMS:
        raise InputError(f"unknown hidden-surface algorithm {name!r}; choose from "
                         f"{', '.join(ALGORITHMS)}")
    return ALGORITHMS[name](prepare(scene_or_mesh, camera, size))
