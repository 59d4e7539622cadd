"""Pure-numpy geometry: polygons, meshes, primitives, quaternions, B-Reps. Never imports a
GL module."""

from . import brep, masspoint, primitives, quaternion
from .analytic import AnalyticSphere, AnalyticSurface
from .merge import concatenate
from .mesh import Mesh
from .polygon import newell_normal, polygon_area

__all__ = ["Mesh", "concatenate", "newell_normal", "polygon_area", "primitives", "quaternion",
           "masspoint", "brep", "AnalyticSphere", "AnalyticSurface"]
