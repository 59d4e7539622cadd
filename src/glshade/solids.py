"""``glshade.solids`` is :mod:`glshade.geometry.solids`: CSG trees of primitive solids,
booleans and affine transforms, with Roth's ray casting."""

from .geometry.solids import *  # noqa: F401,F403
from .geometry.solids import __all__  # noqa: F401
