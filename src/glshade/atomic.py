"""Write files atomically: to a temporary name in the same folder, renamed at the end, so
that an error or an interrupt never leaves a half-written output behind.

A temporary name says who writes it: ``.NAME.HOST-PID.RANDOM.part``. A process killed
outright (SIGKILL, a lost machine) cannot remove its own; the next writer of the same
output, or :func:`remove_stale` over a folder, removes those whose process is gone (on this
host; another host's are left alone, they may be in use).

A Ctrl-C can land between any two steps, so a temporary's creation and its removal never
have a gap between them: :func:`part` creates it with interrupts held and removes it on any
exception, and :func:`held_interrupts` does the same for a child process (the encoder)
that must be started and reaped as one step."""

from __future__ import annotations

import contextlib
import os
import re
import shutil
import signal
import socket
import tempfile
import threading
from pathlib import Path

from .errors import OutputWriteError

__all__ = ["atomic_write", "publish", "writing", "temporary", "part", "held_interrupts",
           "remove_stale", "is_whole", "HOST"]

HOST = re.sub(r"[^A-Za-z0-9_-]", "_", socket.gethostname()) or "host"
_PART = re.compile(r"^\.(?P<name>.+)\.(?P<host>[A-Za-z0-9_-]+)-(?P<pid>\d+)\.[^.]+\.part"
                   r"(?:\.[A-Za-z0-9]+)?$")


def _tag(path: Path) -> str:
    return f".{path.name}.{HOST}-{os.getpid()}."


def temporary(path, *, folder: bool = False, suffix: str = "") -> str:
    """Make a temporary file (or folder) beside ``path``, named for this process; return
    its name. Stale ones of the same output are removed first (those this process found in
    the folder at its first write there).

    Parameters
    ----------
    path : str or Path
        The output it stands in for.
    folder : bool
        Make a folder (else a file).
    suffix : str
        The temporary name's ending (an encoder may need the output's extension).
    """
    path = Path(path)
    parent = path.parent if str(path.parent) else Path(".")
    _remove_stale_once(parent, path.name)
    if folder:
        return tempfile.mkdtemp(prefix=_tag(path), suffix=".part" + suffix, dir=parent)
    fd, tmp = tempfile.mkstemp(prefix=_tag(path), suffix=".part" + suffix, dir=parent)
    os.close(fd)
    return tmp


@contextlib.contextmanager
def held_interrupts():
    """Hold Ctrl-C for the block: a SIGINT arriving waits and is raised as
    KeyboardInterrupt at its end, so a step like "create a file and keep its name" or "start
    a process and keep its handle" is never cut in half. A Python-level handler, not a
    signal mask: the kernel hands a process's signal to any thread that does not block it,
    and Python raises it in the main thread at once. (Only the main thread ever gets a
    KeyboardInterrupt, so elsewhere there is nothing to hold.)"""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list = []
    old = signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)
    if caught:
        if callable(old):
            old(signal.SIGINT, None)  # (the default handler raises KeyboardInterrupt)
        elif old != signal.SIG_IGN:
            raise KeyboardInterrupt


def _remove(path) -> None:
    with contextlib.suppress(OSError):
        shutil.rmtree(path) if os.path.isdir(path) else os.unlink(path)


@contextlib.contextmanager
def part(path, *, folder: bool = False, suffix: str = ""):
    """Yield a new temporary file (or folder) beside ``path``, removed if the block raises
    anything, a Ctrl-C included, at whatever moment it lands; the block publishes it. An
    OSError creating it is an OutputWriteError naming ``path``.

    Parameters
    ----------
    path : str or Path
        The output it stands in for.
    folder : bool
        A folder (else a file).
    suffix : str
        The temporary name's ending.
    """
    tmp = None
    try:
        with writing(path), held_interrupts():
            tmp = temporary(path, folder=folder, suffix=suffix)
        yield tmp
    except BaseException:
        if tmp is not None:
            _remove(tmp)
        raise


#: each folder's stale temporaries by output name, found on this process's first write
#: there (one scan a folder: a data set writes tens of thousands of files into one, and a
#: scan a file made writing it quadratic in its size)
_STALE: dict[str, dict[str, list[Path]]] = {}
_STALE_LOCK = threading.Lock()


def _remove_stale_once(folder: Path, name: str) -> None:
    """Remove output ``name``'s stale temporaries in ``folder``, as found by this process's
    first look there (a writer that dies while this process runs leaves its temporary for
    the next process to remove)."""
    key = os.path.abspath(folder)
    with _STALE_LOCK:
        found = _STALE.get(key)
        if found is None:
            found = _STALE[key] = {}
            for p, output in _stale(folder, recursive=False):
                found.setdefault(output, []).append(p)
        stale = found.pop(name, [])
    for p in stale:
        with contextlib.suppress(OSError):
            shutil.rmtree(p) if p.is_dir() else p.unlink()


def _stale(folder: Path, recursive: bool) -> list[tuple[Path, str]]:
    """The temporaries in ``folder`` of processes of this host that no longer run, each
    with the name of the output it stood in for."""
    if not folder.is_dir():
        return []
    found = folder.rglob(".*.part*") if recursive else folder.glob(".*.part*")
    out = []
    for p in found:
        m = _PART.match(p.name)
        if not m or m["host"] != HOST:
            continue
        if int(m["pid"]) == os.getpid() or _alive(int(m["pid"])):
            continue
        out.append((p, m["name"]))
    return out


def _alive(pid: int) -> bool:
    """Whether process ``pid`` of this host runs. (On Windows ``os.kill(pid, 0)`` would end
    it -- any signal but the console's two is TerminateProcess there --: asked of the
    kernel instead.)"""
    if os.name == "nt":
        return _alive_windows(pid)
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # someone else's process
        return True
    return True


def _alive_windows(pid: int) -> bool:
    import ctypes

    kernel = ctypes.windll.kernel32  # type: ignore[attr-defined]
    handle = kernel.OpenProcess(0x1000, False, int(pid))  # PROCESS_QUERY_LIMITED_INFORMATION
    if not handle:
        return kernel.GetLastError() == 5  # (ERROR_ACCESS_DENIED: it runs, someone else's)
    try:
        code = ctypes.c_ulong()
        return bool(kernel.GetExitCodeProcess(handle, ctypes.byref(code))) and \
            code.value == 259  # STILL_ACTIVE
    finally:
        kernel.CloseHandle(handle)


def remove_stale(folder, *, name: str | None = None, recursive: bool = False) -> int:
    """Remove the temporary files and folders in ``folder`` (of output ``name`` only, if
    given) left by processes of this host that no longer run. Returns how many.

    Parameters
    ----------
    folder : str or Path
        Where to look.
    name : str or None
        Only the temporaries of this output (None: every one).
    recursive : bool
        Look in sub-folders too.
    """
    removed = 0
    for p, output in _stale(Path(folder), recursive):
        if name is not None and output != name:
            continue
        with contextlib.suppress(OSError):
            shutil.rmtree(p) if p.is_dir() else p.unlink()
            removed += 1
    return removed


def publish(tmp, path) -> None:
    """Give a finished temporary file the usual permissions and move it into place.

    Parameters
    ----------
    tmp : str or Path
        The finished temporary file.
    path : str or Path
        Its place.
    """
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600
    os.replace(tmp, path)


@contextlib.contextmanager
def writing(path):
    """Report a failure to write ``path`` -- an OSError, or a broken encoder's error --
    as an OutputWriteError naming ``path``, whatever temporary file was being written.

    Parameters
    ----------
    path : str or Path
        The output a failure is reported for.
    """
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
def atomic_write(path, mode: str = "wb", **text):
    """Yield a file object; on success it replaces ``path``, on failure it is deleted.
    ``text``: ``encoding`` and ``errors`` of a text file.

    Parameters
    ----------
    path : str or Path
        The file to write.
    mode : str
        ``open``'s mode (``"wb"``, ``"w"``).
    **text
        ``encoding`` and ``errors`` of a text file.
    """
    path = Path(path)
    with writing(path), part(path) as tmp:
        with open(tmp, mode, **text) as f:
            yield f
        publish(tmp, path)


#: the chunk a PNG ends with (its length 0, its type, its CRC)
_PNG_END = b"\x00\x00\x00\x00IEND\xaeB`\x82"


def is_whole(path) -> bool:
    """Whether an output file is there and whole: a PNG ends with its IEND chunk, a .npz's
    zip directory (at its end) is there; another kind exists. What this package writes is
    whole or absent (atomic); this finds one torn since -- a copy cut short, a disk that
    filled, a hand -- so that a resumed run makes it again rather than keep it.

    Parameters
    ----------
    path : str or Path
        The file.
    """
    import zipfile

    path = Path(path)
    try:
        size = path.stat().st_size
        if path.suffix.lower() == ".png":
            with open(path, "rb") as f:
                f.seek(max(size - len(_PNG_END), 0))
                return size > len(_PNG_END) and f.read() == _PNG_END
        if path.suffix.lower() == ".npz":
            return zipfile.is_zipfile(path)
        return path.is_file()
    except OSError:
        return False
