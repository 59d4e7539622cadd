"""Which kernel the path tracer runs where ``kernel="auto"``: the one a short measurement
found faster on this GL, kept by the renderer and version strings -- in this process, and
between processes in a small JSON file (``$XDG_CACHE_HOME/glshade/kernels.json``, else
``~/.cache/glshade/kernels.json``), so a node measures once per device and driver, not once
per run. A new driver has a new version string, so it is measured again; a file that cannot
be read or written (a read-only home in a container) only means measuring again."""

from __future__ import annotations

import json
import os
from pathlib import Path

from ..modes import Kernel

__all__ = ["cache_file", "chosen", "keep"]

#: the kernel each GL ran faster, by (renderer string, GL version): this process's copy
_KEPT: dict[tuple[str, str], Kernel] = {}


def cache_file() -> Path:
    """The file the measured choices are kept in between processes (the XDG cache folder,
    where Mesa keeps its shader cache too)."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "glshade" / "kernels.json"


def _driver(context) -> tuple[str, str]:
    """What a choice is kept by: the GL's renderer and version strings."""
    info = context.ctx.info
    return str(info.get("GL_RENDERER", "")), str(info.get("GL_VERSION", ""))


def _key(driver: tuple[str, str]) -> str:
    return " | ".join(driver)


def _stored() -> dict:
    """The file's choices (``{"renderer | version": "fragment"}``), {} where it is missing
    or unreadable."""
    try:
        found = json.loads(cache_file().read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return found if isinstance(found, dict) else {}


def chosen(context) -> Kernel:
    """The kernel measured faster on ``context``'s GL before (in this process, else in the
    file), or ``Kernel.AUTO``: not measured yet.

    Parameters
    ----------
    context : GLContext
        The context whose renderer and version the choice is kept by.
    """
    driver = _driver(context)
    if driver not in _KEPT:
        name = _stored().get(_key(driver))
        if name in (Kernel.FRAGMENT.value, Kernel.COMPUTE.value):
            _KEPT[driver] = Kernel(name)
    return _KEPT.get(driver, Kernel.AUTO)


def keep(context, kernel: Kernel) -> None:
    """Keep ``kernel`` as the measured choice for ``context``'s GL, here and in the file
    (written whole to a temporary name and renamed: two processes writing at once leave
    one's choices, never a broken file).

    Parameters
    ----------
    context : GLContext
        The context it was measured on.
    kernel : Kernel
        ``Kernel.FRAGMENT`` or ``Kernel.COMPUTE``.
    """
    from ..atomic import atomic_write
    from ..errors import OutputWriteError

    driver = _driver(context)
    _KEPT[driver] = kernel
    choices = _stored()
    choices[_key(driver)] = kernel.value
    try:
        cache_file().parent.mkdir(parents=True, exist_ok=True)
        with atomic_write(cache_file(), "w", encoding="utf-8") as f:
            json.dump(choices, f, indent=1, sort_keys=True)
    except (OSError, OutputWriteError):
        pass  # (not kept between processes: the next one measures again)
