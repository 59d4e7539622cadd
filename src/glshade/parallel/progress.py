"""Progress of long work, where it is watched: tqdm's bar in a notebook (its widget) or on a
terminal, a plain line now and then in a log, nothing for work that ends soon."""

from __future__ import annotations

import sys
import time
from typing import Any

from ..interrupt import check

__all__ = ["Progress", "as_progress"]

#: a log gets its first line only after this long (short work stays silent), then one each
#: tenth of the work or this often, whichever comes first
LOG_AFTER_S = 5.0
LOG_EVERY_S = 30.0


def in_notebook() -> bool:
    """Whether this runs in a Jupyter kernel (IPython's ZMQ shell): a bar is a widget there."""
    ipython = sys.modules.get("IPython")
    if ipython is None:
        return False
    try:
        shell = ipython.get_ipython()
    except Exception:  # (an IPython too broken to ask)
        return False
    return shell is not None and type(shell).__name__ == "ZMQInteractiveShell"


class Progress:
    """Items done, items/s and time left. ``unit`` names the items ("frames", "meshes",
    "levels"); ``total=None``: work that ends when it converges (the count, rate and a note).

    ``enabled``: None decides by where the output goes -- a notebook or a terminal gets
    tqdm's bar (``tqdm.auto``), a log (a file or pipe) a plain line each tenth of the work
    or every 30 s once it has run 5 s; True always a bar, False nothing.

    Parameters
    ----------
    total : int or None
        Items in all (None: unknown).
    enabled : bool or None
        Show it (None: where output goes decides).
    stream : file or None
        Where it writes (None: standard error).
    unit : str
        What the items are.
    """

    def __init__(self, total: int | None, enabled: bool | None = None, stream=None,
                 unit: str = "frames"):
        self.stream = stream or sys.stderr
        self.total, self.done, self.start = total, 0, time.perf_counter()
        self.unit = unit
        self._bar: Any = None
        self._log = False
        self._last_line, self._last_tenth = self.start, 0
        if enabled is False:
            return
        notebook = stream is None and in_notebook()
        if enabled or notebook or self.stream.isatty():
            self._bar = _tqdm(notebook)(total=total, unit=f" {unit}", file=self.stream,
                                        dynamic_ncols=True, leave=True, smoothing=0.1)
        else:
            self._log = True

    @property
    def enabled(self) -> bool:
        return self._bar is not None or self._log

    def update(self, n: int = 1, note: str | None = None) -> None:
        """``n`` more items done; ``note`` (a residual, an error) shown beside. A Ctrl-C that
        Python dropped on the way (``glshade.interrupt``) is raised here.

        Parameters
        ----------
        n : int
            Items done.
        note : str or None
            Shown beside.
        """
        check()
        self.done += n
        if self._bar is not None:
            if note:
                self._bar.set_postfix_str(note, refresh=False)
            self._bar.update(n)
        elif self._log:
            self._log_line(note)

    def _log_line(self, note: str | None) -> None:
        now = time.perf_counter()
        elapsed = now - self.start
        tenth = 10 * self.done // self.total if self.total else 0
        due = now - self._last_line >= LOG_EVERY_S or (tenth > self._last_tenth)
        if elapsed < LOG_AFTER_S or not due:
            return
        self._last_line, self._last_tenth = now, tenth
        rate = self.done / elapsed
        per = "fps" if self.unit == "frames" else f"{self.unit}/s"
        if self.total:
            left = (self.total - self.done) / rate if rate > 0 else 0.0
            line = (f"{self.done}/{self.total} {self.unit} ({100 * self.done // self.total}%),"
                    f" {rate:.1f} {per}, {left:.0f} s left")
        else:
            line = f"{self.done} {self.unit}, {rate:.1f} {per}, {elapsed:.0f} s"
        self.stream.write(line + (f", {note}" if note else "") + "\n")
        self.stream.flush()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def as_progress(progress, total: int | None, unit: str):
    """``(bar, owned)`` from a ``progress`` argument: an object with ``update`` (the caller's:
    not closed here), True (a bar), None (decided by where output goes: :class:`Progress`)
    or False (none: ``(None, False)``).

    Parameters
    ----------
    progress : bool, object or None
        An object with ``update``, True, None or False.
    total : int or None
        Items in all.
    unit : str
        What the items are.
    """
    if progress is False:
        return None, False
    if progress is None or progress is True:
        return Progress(total, enabled=progress, unit=unit), True
    return progress, False


def _tqdm(notebook: bool):
    """tqdm's notebook bar (an ipywidgets progress bar) in a notebook, else its text bar."""
    if notebook:
        try:
            import ipywidgets  # noqa: F401  (tqdm's notebook bar is one)
            from tqdm.notebook import tqdm
            return tqdm
        except ImportError:
            pass
    from tqdm import tqdm
    return tqdm
