"""The release idiom every GL-owning object shares.

A :class:`GLResource` is made from a RenderContext, registers with it, keeps the moderngl
objects it creates (``_keep``) and frees them in reverse order on ``release()`` -- once; a
second call does nothing, and use after release raises a clear error (``_check``). The
context releases whatever its children left when it goes. No GL work in ``__del__``.
"""

from __future__ import annotations

from typing import TypeVar

from ..errors import GlshadeError

__all__ = ["GLResource"]

R = TypeVar("R", bound="GLResource")


class GLResource:
    """Base class of objects that own GL objects of one RenderContext.

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    """

    def __init__(self, context):
        self.context = context
        self._objects: list = []
        self.released = False
        context.track(self)

    def _keep(self, obj):
        """Remember a moderngl object to release with this one; return it."""
        self._objects.append(obj)
        return obj

    def _check(self) -> None:
        if self.released:
            raise GlshadeError(f"this {type(self).__name__} was released; make a new one")

    def _release_extra(self) -> None:
        """Free what is not in ``_objects`` (caches); called first by ``release``."""

    def release(self) -> None:
        """Free every GL object this one made (reverse creation order); idempotent."""
        if self.released:
            return
        # (never release the bound framebuffer: moderngl would bind the deleted one again)
        rest = getattr(self.context, "rest", None)
        if rest is not None:
            rest()
        self._release_extra()
        for obj in reversed(self._objects):
            obj.release()
        self._objects.clear()
        self.released = True
        self.context.untrack(self)

    def __enter__(self: R) -> R:
        return self

    def __exit__(self, *exc) -> None:
        self.release()
