"""``glshade.hidden`` is :mod:`glshade.cpu.hidden`: the hidden-surface lab (z-buffer,
scan line, depth sort, BSP tree, ray casting in numpy, checked against the GPU)."""

from .cpu.hidden import *  # noqa: F401,F403
from .cpu.hidden import __all__  # noqa: F401
