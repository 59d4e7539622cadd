"""Animation: frames along camera paths (frames), the executors that render them in order
(executors), the files they go to (writers) and the progress bar (progress)."""

from .._callable import callable_package
from .executors import make_executor
from .frames import animate, render_frames
from .progress import Progress
from .writers import FORMATS, output_format, write_animation

__all__ = ["animate", "render_frames", "write_animation", "output_format", "Progress",
           "FORMATS", "make_executor"]

callable_package(__name__, animate)  # glshade.animate(...) calls the function, whatever is bound
