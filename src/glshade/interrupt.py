"""A Ctrl-C is never lost. Python raises KeyboardInterrupt wherever the interpreter happens
to be; one raised inside a weakref callback or a ``__del__`` (the import machinery's locks,
garbage collection) is printed as "Exception ignored" and dropped, and the run would go on
to the end. The command line notes such a drop (:func:`catch_dropped`) and the long loops
raise it again between items (:func:`check`, called by the progress bar)."""

from __future__ import annotations

import contextlib
import sys
from typing import Any

__all__ = ["catch_dropped", "check", "held", "caused_by_interrupt"]

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


def caused_by_interrupt(exc: BaseException) -> bool:
    """Whether ``exc`` is a Ctrl-C in disguise: a KeyboardInterrupt, or an error Python made
    of one -- a class being built while a module imports wraps an interrupt that lands in
    a descriptor's ``__set_name__`` in a RuntimeError, an extension's import may turn it
    into an ImportError -- found along the exception's causes and contexts.

    Parameters
    ----------
    exc : BaseException
        The exception that ended the work.
    """
    seen: set[int] = set()
    found: BaseException | None = exc
    while found is not None and id(found) not in seen:
        if isinstance(found, KeyboardInterrupt):
            return True
        seen.add(id(found))
        found = found.__cause__ or found.__context__
    return False


def check() -> None:
    """Raise KeyboardInterrupt if one was dropped since the last check."""
    global _dropped
    if _dropped:
        _dropped = False
        raise KeyboardInterrupt


@contextlib.contextmanager
def held():
    """Hold a Ctrl-C until the block ends, then deliver it (to the handler that was there:
    Python's raises KeyboardInterrupt): for the driver's work that must not be cut short (a
    GL context being made, a program compiled and linked -- a KeyboardInterrupt in the
    middle of them can leave the driver's state half-made, and the interpreter crash at
    exit). In the main thread, under a Python handler; elsewhere the block simply runs."""
    import signal
    import threading

    previous = signal.getsignal(signal.SIGINT)
    if threading.current_thread() is not threading.main_thread() or not callable(previous):
        yield
        return
    caught: list[int] = []
    signal.signal(signal.SIGINT, lambda *_: caught.append(1))
    # (and the system calls the driver is in restart rather than fail with EINTR: a Ctrl-C
    # landing in Mesa's compile of a compute program crashed the process, SIGSEGV)
    signal.siginterrupt(signal.SIGINT, False)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if caught:
            previous(signal.SIGINT, None)
