"""The mesh kernel, pure numpy: polygons (Newell normals, triangulation), meshes, edges,
merging, primitives, transforms and tolerances. Never imports a GL module."""

from . import primitives
from .analytic import AnalyticSphere, AnalyticSurface
from .merge import concatenate
from .mesh import Mesh
from .polygon import newell_normal, polygon_area

__all__ = ["Mesh", "concatenate", "newell_normal", "polygon_area", "primitives",
           "AnalyticSphere", "AnalyticSurface"]
