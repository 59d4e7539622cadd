"""``glshade.masspoint`` is :mod:`glshade.geometry.masspoint` (an explicit re-export, kept for the
import path of earlier releases)."""

from .geometry.masspoint import *  # noqa: F401,F403
from .geometry.masspoint import __all__  # noqa: F401
