"""Write files atomically: to a temporary name in the same folder, renamed at the end, so
that an error or an interrupt never leaves a half-written output behind."""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

from .errors import OutputWriteError


def publish(tmp, path) -> None:
    """Give a finished temporary file the usual permissions and move it into place."""
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600
    os.replace(tmp, path)


@contextlib.contextmanager
def writing(path):
    """Report a failure to write ``path`` -- an OSError, or a broken encoder's error --
    as an OutputWriteError naming ``path``, whatever temporary file was being written."""
    try:
        yield
    except OutputWriteError as exc:
        if exc.path == str(path):
            raise
        raise OutputWriteError(path, exc.reason) from None
    except OSError as exc:
        lines = str(exc).strip().splitlines()
        reason = exc.strerror or (lines[-1] if lines else type(exc).__name__)
        raise OutputWriteError(path, reason) from None


@contextlib.contextmanager
def atomic_write(path, mode: str = "wb"):
    """Yield a file object; on success it replaces ``path``, on failure it is deleted."""
    path = Path(path)
    with writing(path):
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part",
                                   dir=path.parent or ".")
        try:
            with os.fdopen(fd, mode) as f:
                yield f
            publish(tmp, path)
        except BaseException:  # interrupted or failed: remove the partial file, re-raise
            with contextlib.suppress(OSError):
                os.unlink(tmp)
            raise
