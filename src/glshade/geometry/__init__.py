"""Pure-numpy geometry: polygons, meshes, primitives. Never imports a GL module."""

from .mesh import Mesh, concatenate
from .polygon import newell_normal, polygon_area
from . import masspoint, primitives, quaternion

__all__ = ["Mesh", "concatenate", "newell_normal", "polygon_area", "primitives", "quaternion",
           "masspoint"]
