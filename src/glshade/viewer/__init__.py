"""The interactive viewer: a glfw window drawn by the same Renderer as headless renders.
Importing this package opens nothing; :class:`Viewer` does."""

from .arcball import Arcball, drag_rotation, sphere_point

__all__ = ["Arcball", "drag_rotation", "sphere_point", "Viewer"]


def __getattr__(name):
    if name == "Viewer":
        from . import window

        return getattr(window, name)
    raise AttributeError(name)
