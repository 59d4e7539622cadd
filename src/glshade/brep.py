"""``glshade.brep`` is :mod:`glshade.geometry.brep` (an explicit re-export, kept for the
import path of earlier releases)."""

from .geometry.brep import *  # noqa: F401,F403
from .geometry.brep import __all__  # noqa: F401
