"""``glshade.quaternion`` is :mod:`glshade.geometry.quaternion` (an explicit re-export, kept for the
import path of earlier releases)."""

from .geometry.quaternion import *  # noqa: F401,F403
from .geometry.quaternion import __all__  # noqa: F401
