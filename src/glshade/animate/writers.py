"""Writing frames: GIF and animated PNG (Pillow), MP4 (imageio with ffmpeg, the ``video``
extra) or a folder of PNG frames. The output appears only when every frame is written
(temporary name, then rename), so an error or Ctrl-C never leaves a partial file."""

from __future__ import annotations

import contextlib
import os
import shutil
from pathlib import Path

import numpy as np

from .._atomic import atomic_write, publish, temporary, writing
from ..errors import OutputError, OutputWriteError, VideoUnavailable

__all__ = ["output_format", "write_animation", "FORMATS"]

FORMATS = ("gif", "png", "apng", "mp4", "dir")


def output_format(output) -> str:
    """The writer an output path asks for: "gif", "png" (APNG), "apng", "mp4", or "dir" (a
    folder of PNG frames); an OutputError for any other suffix."""
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
    # (Pillow merges a frame identical to the one before into it, lengthening its
    # duration: N frames asked would be fewer written. So no two neighbours are the same
    # bytes to it: in a GIF a repeated frame names one colour by a spare palette entry, in
    # an APNG neighbours alternate their blend operation -- the same pictures either way.)
    with atomic_write(out, "wb") as f:
        if fmt == "gif":
            frames_p = _gif_frames(images)
            frames_p[0].save(f, format="GIF", save_all=True, append_images=frames_p[1:],
                             duration=duration, loop=0, optimize=False, disposal=1)
        else:
            images[0].save(f, format="PNG", save_all=True, append_images=images[1:],
                           duration=duration, loop=0,
                           blend=[k % 2 for k in range(len(images))])
    return len(images)


def _gif_frames(images):
    """Palette frames, each palette with a spare copy of the first pixel's colour; a frame
    identical to the one before draws that colour with the copy, so the GIF writer keeps it
    as a frame of its own (its pixels are the same colours)."""
    from PIL import Image

    out, prev, flip = [], None, False
    for im in images:
        raw = np.asarray(im)
        flip = (not flip) if prev is not None and np.array_equal(raw, prev) else False
        prev = raw
        p = im.quantize(255, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        idx = np.asarray(p)
        palette = p.getpalette()[: 3 * (int(idx.max()) + 1)]
        first = int(idx.flat[0])
        spare = len(palette) // 3
        palette += palette[3 * first: 3 * first + 3]
        if flip:
            idx = np.where(idx == first, spare, idx).astype(np.uint8)
        frame = Image.fromarray(idx, "P")
        frame.putpalette(palette)
        out.append(frame)
    return out


def _write_dir(frames, out: Path) -> int:
    from ..io.images import save_image

    if out.exists() and any(out.iterdir()):
        raise OutputError(f"{out}: the folder exists and is not empty")
    with writing(out):
        tmp = Path(temporary(out, folder=True))
    try:
        n = 0
        for n, f in enumerate(frames, start=1):
            with writing(out):
                save_image(f, tmp / f"frame_{n - 1:05d}.png")
        with writing(out):
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
    with writing(out):
        tmp = temporary(out, suffix=".mp4")
    n = 0
    try:
        writer = imageio.get_writer(tmp, fps=fps, codec="libx264", quality=8,
                                    macro_block_size=1, ffmpeg_log_level="error")
        try:
            for f in frames:
                with _encoder_errors(out):
                    writer.append_data(np.ascontiguousarray(f[..., :3]))
                n += 1
        except BaseException as exc:
            # Ctrl-C: kill ffmpeg now. Closed gracefully, the writer waits without a bound
            # for ffmpeg to finish, and an interrupt landing in that wait could hang the run.
            if not isinstance(exc, Exception):
                _kill_encoder(writer)
            raise
        finally:
            with _encoder_errors(out):
                writer.close()
        if not _mp4_complete(tmp):  # ffmpeg can exit 0 after a failed write
            raise OutputWriteError(out, "the video encoder wrote an incomplete file (is the "
                                   "disk full?)")
        with writing(out):
            publish(tmp, out)
        return n
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _kill_encoder(writer) -> None:
    """End the ffmpeg process behind an imageio writer at once (an interrupt: its output
    is thrown away anyway), so that closing the writer cannot wait on it."""
    gen = getattr(writer, "_write_gen", None)
    if gen is not None:
        with contextlib.suppress(BaseException):
            gen.throw(KeyboardInterrupt)  # (imageio-ffmpeg kills ffmpeg on this)


@contextlib.contextmanager
def _encoder_errors(out: Path):
    """ffmpeg's failures (a broken pipe, a full disk) as one line naming the output."""
    try:
        yield
    except (OSError, RuntimeError, ValueError) as exc:
        lines = [x.strip() for x in str(exc).splitlines() if x.strip()]
        reason = getattr(exc, "strerror", None) or (lines[-1] if lines else type(exc).__name__)
        raise OutputWriteError(out, f"the video encoder failed: {reason}") from None


def _mp4_complete(path) -> bool:
    """Whether an MP4's top-level boxes run exactly to the end of the file and include the
    index ('moov'): a truncated file fails one or the other."""
    import struct

    with open(path, "rb") as f:
        data = f.read()
    pos, kinds = 0, set()
    while pos + 8 <= len(data):
        size, kind = struct.unpack(">I4s", data[pos:pos + 8])
        if size == 1 and pos + 16 <= len(data):
            size = struct.unpack(">Q", data[pos + 8:pos + 16])[0]
        elif size == 0:
            size = len(data) - pos
        if size < 8:
            return False
        kinds.add(kind)
        pos += size
    return pos == len(data) and b"moov" in kinds
