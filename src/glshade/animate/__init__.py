"""Animation: frames along camera paths (frames), the executors that render them in order
(executors), the files they go to (writers) and the progress bar (progress)."""

import sys as _sys
import types as _types

from .executors import make_executor
from .frames import animate, render_frames
from .progress import Progress
from .writers import FORMATS, output_format, write_animation

__all__ = ["animate", "render_frames", "write_animation", "output_format", "Progress",
           "FORMATS", "make_executor"]


class _Callable(_types.ModuleType):
    """``glshade.animate(...)`` is the function (the README's API) even after this package,
    which shares its name, has been imported and bound in its place: calling the package
    calls :func:`animate`."""

    def __call__(self, *args, **kwargs):
        return animate(*args, **kwargs)


_sys.modules[__name__].__class__ = _Callable
