"""Writing frames: GIF and animated PNG (Pillow), MP4 (imageio with ffmpeg, the ``video``
extra) or a folder of PNG frames. The output appears only when every frame is written
(temporary name, then rename), so an error or Ctrl-C never leaves a partial file."""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from .._atomic import atomic_write, publish
from ..errors import OutputError, VideoUnavailable

__all__ = ["output_format", "write_animation", "FORMATS"]

FORMATS = ("gif", "png", "apng", "mp4", "dir")


def output_format(output) -> str:
    p = Path(output)
    if str(output).endswith(("/", os.sep)) or p.is_dir() or not p.suffix:
        return "dir"
    ext = p.suffix.lower().lstrip(".")
    if ext in ("gif", "png", "apng", "mp4"):
        return ext
    raise OutputError(f"cannot write {p.name!r}: the output must end in .gif, .png, .apng, "
                       ".mp4, or be a folder (ending in /)")


def write_animation(frames, output, fps: float = 30.0) -> int:
    """Write frames (an iterable of ``(H, W, 4) uint8``) to ``output``; return the count.
    The file (or folder) appears only when every frame is written."""
    fmt = output_format(output)
    out = Path(output)
    if fmt == "dir":
        return _write_dir(frames, out)
    if fmt == "mp4":
        return _write_mp4(frames, out, fps)
    from PIL import Image

    images = [Image.fromarray(np.ascontiguousarray(f[..., :3]), "RGB") for f in frames]
    if not images:
        raise OutputError("no frames to write")
    duration = int(round(1000 / fps))
    with atomic_write(out, "wb") as f:
        if fmt == "gif":
            images[0].save(f, format="GIF", save_all=True, append_images=images[1:],
                           duration=duration, loop=0, optimize=False, disposal=1)
        else:
            images[0].save(f, format="PNG", save_all=True, append_images=images[1:],
                           duration=duration, loop=0)
    return len(images)


def _write_dir(frames, out: Path) -> int:
    from ..io.images import save_image

    if out.exists() and any(out.iterdir()):
        raise OutputError(f"{out}: the folder exists and is not empty")
    parent = out.parent if str(out.parent) else Path(".")
    tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}.", suffix=".part", dir=parent))
    try:
        n = 0
        for n, f in enumerate(frames, start=1):
            save_image(f, tmp / f"frame_{n - 1:05d}.png")
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o777 & ~umask)  # mkdtemp makes 0700
        if out.exists():
            out.rmdir()
        os.replace(tmp, out)
        return n
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise


def _write_mp4(frames, out: Path, fps: float) -> int:
    try:
        import imageio.v2 as imageio
        import imageio_ffmpeg  # noqa: F401
    except ImportError:
        raise VideoUnavailable("MP4 output needs imageio and its ffmpeg plugin: "
                               "pip install 'glshade[video]' (or write .gif or .png)") from None
    fd, tmp = tempfile.mkstemp(prefix=f".{out.name}.", suffix=".part.mp4",
                               dir=out.parent if str(out.parent) else ".")
    os.close(fd)
    n = 0
    try:
        with imageio.get_writer(tmp, fps=fps, codec="libx264", quality=8,
                                macro_block_size=1, ffmpeg_log_level="error") as w:
            for f in frames:
                w.append_data(np.ascontiguousarray(f[..., :3]))
                n += 1
        publish(tmp, out)
        return n
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
