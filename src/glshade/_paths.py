"""What every input file must be before it is read (one rule for meshes, scene files and
patch files)."""

from __future__ import annotations

__all__ = ["file_fault"]


def file_fault(path) -> str | None:
    """What keeps ``path`` from being read as an input file, or None: it must exist and be
    a regular file (after links) -- a directory, a device such as /dev/zero, a FIFO or a
    socket is refused before reading (reading one would hang or never end)."""
    import os
    import stat

    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return "no such file"
    except OSError as exc:
        return f"cannot read: {exc.strerror or exc}"
    if stat.S_ISDIR(mode):
        return "is a directory, not a file"
    if not stat.S_ISREG(mode):
        return "is not a regular file (a device, a FIFO or a socket)"
    return None
