"""``glshade.octree`` is :mod:`glshade.geometry.octree`: octrees of CSG solids and closed
meshes, built level by level."""

from .geometry.octree import *  # noqa: F401,F403
from .geometry.octree import __all__  # noqa: F401
