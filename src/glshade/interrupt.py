"""A Ctrl-C is never lost. Python raises KeyboardInterrupt wherever the interpreter happens
to be; one raised inside a weakref callback or a ``__del__`` (the import machinery's locks,
garbage collection) is printed as "Exception ignored" and dropped, and the run would go on
to the end. The command line notes such a drop (:func:`catch_dropped`) and the long loops
raise it again between items (:func:`check`, called by the progress bar)."""

from __future__ import annotations

from typing import Any

import sys

__all__ = ["catch_dropped", "check"]

_dropped = False
_previous_hook: Any = None


def _hook(unraisable) -> None:
    global _dropped
    if unraisable.exc_type is not None and issubclass(unraisable.exc_type, KeyboardInterrupt):
        _dropped = True  # (and nothing printed: the interrupt is not over)
        return
    _previous_hook(unraisable)


def catch_dropped() -> None:
    """Note KeyboardInterrupts that Python would drop, from now on in this process."""
    global _previous_hook
    if sys.unraisablehook is not _hook:
        _previous_hook = sys.unraisablehook
        sys.unraisablehook = _hook


def check() -> None:
    """Raise KeyboardInterrupt if one was dropped since the last check."""
    global _dropped
    if _dropped:
        _dropped = False
        raise KeyboardInterrupt
