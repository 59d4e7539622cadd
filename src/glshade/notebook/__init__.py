"""glshade in a notebook: objects that show themselves, :func:`show` for images, frames and
animations, and an interactive viewer widget that needs no display on the kernel's machine.

- :mod:`.display`: :func:`show` and the thumbnails every displayable object's
  ``_repr_html_`` draws (through the hook it installs in ``glshade.display``, the
  layer-free half that the lower layers' reprs call).
- :mod:`.widget`: :func:`view`, the anywidget viewer (``pip install 'glshade[notebook]'``);
  its browser side is ``static/viewer.js``.

    from glshade.notebook import view
    w = view(glshade.geometry.primitives.torus(), compare="phong", pick=True)
"""

from __future__ import annotations

from .display import show, thumbnail
from .widget import camera_from_view, view, view_of

__all__ = ["show", "thumbnail", "view", "view_of", "camera_from_view", "NotebookViewer"]


def __getattr__(name: str):
    """``NotebookViewer``, made on first use (anywidget is imported then)."""
    if name == "NotebookViewer":
        from . import widget

        return widget.NotebookViewer
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
