"""A one-line progress bar on a terminal, silent elsewhere."""

from __future__ import annotations

import sys
import time

from .._interrupt import check

__all__ = ["Progress"]


class Progress:
    """A one-line progress bar on a terminal: items done, items/s, time left. ``unit`` names
    the items ("frames", "meshes", "levels")."""

    def __init__(self, total: int | None, enabled: bool | None = None, stream=None,
                 unit: str = "frames"):
        self.stream = stream or sys.stderr
        self.enabled = self.stream.isatty() if enabled is None else enabled
        self.total, self.done, self.start = total, 0, time.perf_counter()
        self.unit = unit

    def update(self, n: int = 1, note: str | None = None) -> None:
        """``n`` more items done. With no total (``total=None``: work that ends when it
        converges) the bar shows the count, the rate and ``note`` instead. A Ctrl-C that
        Python dropped on the way (``glshade._interrupt``) is raised here."""
        check()
        self.done += n
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.start
        rate = self.done / elapsed if elapsed > 0 else 0.0
        if self.total is None:
            self.stream.write(f"\r{self.done} {self.unit}  {rate:6.1f} {self.unit}/s  "
                              f"{elapsed:6.1f} s  {note or ''} ")
            self.stream.flush()
            return
        left = (self.total - self.done) / rate if rate > 0 else 0.0
        width = 30
        filled = int(width * self.done / max(self.total, 1))
        per = "fps" if self.unit == "frames" else f"{self.unit}/s"
        self.stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total}"
                          f" {self.unit}  {rate:5.1f} {per}  {left:5.1f} s left ")
        self.stream.flush()

    def close(self) -> None:
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
