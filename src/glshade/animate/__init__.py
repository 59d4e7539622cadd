"""Animation: frames along camera paths (frames) and the files they go to (writers). The
executors that render them in order and the progress bar live in :mod:`glshade.parallel`."""

from .._callable import callable_package
from ..parallel import Progress, make_executor
from .frames import animate, render_frames
from .writers import FORMATS, output_format, write_animation

__all__ = ["animate", "render_frames", "write_animation", "output_format", "Progress",
           "FORMATS", "make_executor"]

callable_package(__name__, animate)  # glshade.animate(...) calls the function, whatever is bound
