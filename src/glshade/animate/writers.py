"""Writing frames: GIF and animated PNG (Pillow), MP4 (ffmpeg from imageio-ffmpeg, the
``video`` extra) or a folder of PNG frames. The output appears only when every frame is written
(temporary name, then rename), so an error or Ctrl-C never leaves a partial file."""

from __future__ import annotations

import contextlib
import os
from typing import Any
from pathlib import Path

import numpy as np

from ..atomic import atomic_write, held_interrupts, part, publish, writing
from ..errors import OutputError, OutputWriteError, VideoUnavailable

__all__ = ["output_format", "write_animation", "check_fps", "FORMATS", "MIN_FPS", "MAX_FPS"]

FORMATS = ("gif", "png", "apng", "mp4", "dir")
#: the frame rates an animation may have: a GIF frame lasts at most 655.35 s (a 16-bit count
#: of 1/100 s), and a frame shorter than 1 ms is no frame a player shows
MIN_FPS, MAX_FPS = 0.01, 1000.0


def check_fps(fps: float, name: str = "fps") -> float:
    """``fps`` as a float in [MIN_FPS, MAX_FPS], or an OptionError naming ``name``.

    Parameters
    ----------
    fps : float
        The value given.
    name : str
        Its name, for the message.
    """
    from ..errors import OptionError

    try:
        value = float(fps)
    except (TypeError, ValueError):
        raise OptionError(f"{name} must be a number, got {fps!r}") from None
    if not MIN_FPS <= value <= MAX_FPS:
        raise OptionError(f"{name} must be from {MIN_FPS:g} to {MAX_FPS:g} frames a second, "
                          f"got {value:g}")
    return value


def output_format(output) -> str:
    """The writer an output path asks for: "gif", "png" (APNG), "apng", "mp4", or "dir" (a
    folder of PNG frames); an OutputError for any other suffix.

    Parameters
    ----------
    output : str or Path
        The file or folder to write.
    """
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
    The file (or folder) appears only when every frame is written.

    Parameters
    ----------
    frames : iterable of ndarray
        ``(H, W, 4)`` uint8 images.
    output : str or Path
        The file or folder.
    fps : float
        Frames a second.
    """
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
    with writing(out), part(out, folder=True) as name:
        tmp = Path(name)
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


def _write_mp4(frames, out: Path, fps: float) -> int:
    try:
        import imageio_ffmpeg
    except ImportError:
        raise VideoUnavailable("MP4 output needs imageio-ffmpeg (it ships ffmpeg): "
                               "pip install 'glshade[video]' (or write .gif or .png)") from None
    n = 0
    with writing(out), part(out, suffix=".mp4") as tmp:
        encoder = None
        try:
            for f in frames:
                rgb = np.ascontiguousarray(f[..., :3])
                if encoder is None:
                    encoder = _Encoder(tmp, rgb.shape, fps, out)
                    encoder.start(imageio_ffmpeg)
                encoder.write(rgb)
                n += 1
            if encoder is None:
                raise OutputError("no frames to write")
            encoder.finish()
        except BaseException:
            # A Ctrl-C or a failure: kill ffmpeg and reap it before the temporary file goes
            # (asked to finish, it would encode what it has; alive, it could write it again)
            if encoder is not None:
                encoder.kill()
            raise
        if not _mp4_complete(tmp):  # ffmpeg can exit 0 after a failed write
            raise OutputWriteError(out, "the video encoder wrote an incomplete file (is the "
                                   "disk full?)")
        publish(tmp, out)
    return n


class _Encoder:
    """ffmpeg reading raw RGB frames ``(H, W, 3) uint8`` on a pipe and writing H.264
    (yuv420p, CRF 10) to ``path``. Started with interrupts held, so a Ctrl-C leaves either
    no process or one this object holds; in its own session, so a terminal's Ctrl-C does
    not reach it: it is killed and reaped here, never left behind."""

    def __init__(self, path: str, shape, fps: float, out: Path):
        self.path, self.shape, self.fps, self.out = path, tuple(shape), fps, out
        self.proc: Any = None

    def start(self, imageio_ffmpeg) -> None:
        """Find ffmpeg (it runs ``ffmpeg -version`` once) and start it, interrupts held:
        afterwards either no process runs or ``self.proc`` holds it."""
        import subprocess
        import tempfile
        from fractions import Fraction

        h, w = self.shape[:2]
        rate = Fraction(self.fps).limit_denominator(1001)
        self.log = tempfile.TemporaryFile()
        with held_interrupts():
            cmd = [imageio_ffmpeg.get_ffmpeg_exe(), "-nostdin", "-y", "-loglevel", "error",
                   "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", f"{w}x{h}", "-r", str(rate),
                   "-i", "pipe:0", "-an", "-c:v", "libx264", "-pix_fmt", "yuv420p",
                   "-crf", "10", "-f", "mp4", self.path]
            self.proc = subprocess.Popen(cmd, stdin=subprocess.PIPE,
                                         stdout=subprocess.DEVNULL, stderr=self.log,
                                         start_new_session=True)

    def write(self, rgb: np.ndarray) -> None:
        """Send one frame; a frame of another size, or an encoder gone, is an error."""
        if rgb.shape != self.shape:
            raise OutputError(f"{self.out}: frame of {rgb.shape[1]}x{rgb.shape[0]} in a video "
                              f"of {self.shape[1]}x{self.shape[0]}")
        try:
            self.proc.stdin.write(rgb.tobytes())
        except OSError:
            self.proc.wait()
            raise self._failure() from None

    def finish(self) -> None:
        """Close the pipe, let ffmpeg write the index, and check that it succeeded."""
        try:
            self.proc.stdin.close()
        except OSError:
            pass
        if self.proc.wait() != 0:
            raise self._failure()
        self.log.close()

    def kill(self) -> None:
        """End ffmpeg at once and reap it (interrupts held: a second Ctrl-C cannot leave
        it running)."""
        if self.proc is None:
            return
        with held_interrupts():
            with contextlib.suppress(OSError):
                self.proc.kill()
            with contextlib.suppress(OSError, ValueError):
                self.proc.stdin.close()
            self.proc.wait()
            self.log.close()

    def _failure(self) -> OutputWriteError:
        self.log.seek(0)
        lines = [x.strip() for x in self.log.read().decode(errors="replace").splitlines()
                 if x.strip()]
        reason = lines[-1] if lines else f"ffmpeg exited with status {self.proc.returncode}"
        return OutputWriteError(self.out, f"the video encoder failed: {reason}")


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
