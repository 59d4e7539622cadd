"""Rendering camera paths to files: GIF and animated PNG (Pillow), MP4 (imageio with
ffmpeg, the ``video`` extra) or a folder of PNG frames; in parallel worker processes, each
with its own GL context, frames kept in order. Output is written under a temporary name and
renamed at the end, so an error or Ctrl-C never leaves a partial file."""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import os
import shutil
import signal
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from ._atomic import atomic_write, publish
from .errors import GlshadeError
from .keyframes import CameraPath
from .modes import ShadingMode
from .scene import Scene

__all__ = ["animate", "render_frames", "write_animation", "Progress", "FORMATS"]

FORMATS = ("gif", "png", "apng", "mp4", "dir")


class VideoUnavailable(GlshadeError, RuntimeError):
    """MP4 output needs imageio and imageio-ffmpeg."""


class OutputError(GlshadeError, ValueError):
    """An output name glshade cannot write (bad input: exit status 2)."""


class Progress:
    """A one-line progress bar on a terminal: frames done, frames/s, time left."""

    def __init__(self, total: int, enabled: bool | None = None, stream=None):
        self.stream = stream or sys.stderr
        self.enabled = self.stream.isatty() if enabled is None else enabled
        self.total, self.done, self.start = total, 0, time.perf_counter()

    def update(self, n: int = 1) -> None:
        self.done += n
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.start
        rate = self.done / elapsed if elapsed > 0 else 0.0
        left = (self.total - self.done) / rate if rate > 0 else 0.0
        width = 30
        filled = int(width * self.done / max(self.total, 1))
        self.stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total}"
                          f" frames  {rate:5.1f} fps  {left:5.1f} s left ")
        self.stream.flush()

    def close(self) -> None:
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()


# ------------------------------------------------------------------ frame rendering

def _compose(tiles: dict) -> np.ndarray:
    from .comparison import _label

    if len(tiles) == 1:
        return next(iter(tiles.values()))
    row = np.hstack([_label(t, name) for name, t in tiles.items()])
    return np.dstack([row, np.full(row.shape[:2], 255, np.uint8)])


class _FrameMaker:
    """Renders frame ``i`` of a path (used in the main process and in every worker)."""

    def __init__(self, scene, path, times, modes, size, samples, srgb, backend):
        from .render.renderer import Renderer

        self.scene, self.path, self.times = scene, path, times
        self.modes, self.srgb = modes, srgb
        self.renderer = Renderer(size[0], size[1], samples=samples, backend=backend)

    def __call__(self, i: int) -> bytes:
        camera = self.path.at(self.times[i])
        tiles = {m.value: self.renderer.render(self.scene, camera, m, srgb=self.srgb)
                 for m in self.modes}
        return _compose(tiles).tobytes()

    def close(self):
        self.renderer.close()


_worker: _FrameMaker | None = None
_worker_error: BaseException | None = None


def _init_worker(args, threads):
    global _worker, _worker_error
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C
    # Mesa's software rasterizer starts a thread per core in every process; with one worker
    # per core that oversubscribes the machine. Share the cores out instead (no effect on
    # GPU drivers).
    os.environ.setdefault("LP_NUM_THREADS", str(threads))
    try:
        _worker = _FrameMaker(*args)
    except Exception as exc:  # reported with the first frame, in the parent, as it is;
        _worker_error = exc     # an initializer that raised would be restarted forever


def _work(i: int) -> bytes:
    if _worker_error is not None:
        raise _worker_error
    assert _worker is not None
    return _worker(i)


@contextlib.contextmanager
def _without_main_reimport():
    """Spawned workers normally re-run the user's main script (a script without an
    ``if __name__ == "__main__"`` guard would start pools in its workers). The workers
    need nothing from it -- their code and data come from glshade -- so hide it while they
    start."""
    main = sys.modules.get("__main__")
    saved = {k: getattr(main, k) for k in ("__file__", "__spec__") if hasattr(main, k)}
    try:
        for k in saved:
            if k == "__spec__":
                main.__spec__ = None
            else:
                delattr(main, k)
        yield
    finally:
        for k, v in saved.items():
            setattr(main, k, v)


def render_frames(scene: Scene, path: CameraPath, frames: int, mode="phong", *, modes=None,
                  size=(512, 512), samples: int = 4, srgb: bool = False, jobs: int = 1,
                  backend="auto", progress: Progress | None = None) -> Iterator[np.ndarray]:
    """Yield ``frames`` images ``(H, W', 4) uint8`` evenly spaced along ``path``, in order.
    With ``modes`` several shading modes are laid side by side, labelled. ``jobs > 1``
    renders in worker processes (spawned, each with its own GL context)."""
    modes = [ShadingMode.parse(m) for m in (modes or [mode])]
    if frames < 1:
        raise GlshadeError(f"need at least one frame, got {frames}")
    if jobs < 1:
        raise GlshadeError(f"jobs must be >= 1, got {jobs}")
    times = path.frame_times(frames)
    args = (scene, path, times, modes, tuple(size), samples, srgb, backend)
    shape = None
    jobs = min(jobs, frames)
    if jobs == 1:
        maker = _FrameMaker(*args)
        try:
            for index in range(frames):
                data = maker(index)
                shape = shape or _frame_shape(size, modes)
                if progress:
                    progress.update()
                yield np.frombuffer(data, np.uint8).reshape(shape)
        finally:
            maker.close()
        return
    threads = max(1, (os.cpu_count() or 1) // jobs)
    with _without_main_reimport():  # the pool starts its workers here
        pool = mp.get_context("spawn").Pool(jobs, initializer=_init_worker,
                                            initargs=(args, threads))
    try:
        chunk = max(1, min(8, frames // (4 * jobs)))
        for data in pool.imap(_work, range(frames), chunksize=chunk):
            shape = shape or _frame_shape(size, modes)
            if progress:
                progress.update()
            yield np.frombuffer(data, np.uint8).reshape(shape)
        pool.close()
    except BaseException:
        pool.terminate()  # stop the workers at once (Ctrl-C, an error, a closed generator)
        raise
    finally:
        pool.join()


def _frame_shape(size, modes):
    from .comparison import LABEL_HEIGHT

    w, h = size
    if len(modes) == 1:
        return (h, w, 4)
    return (h + LABEL_HEIGHT, w * len(modes), 4)


# ------------------------------------------------------------------ writing

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
        raise GlshadeError("no frames to write")
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
    from .image import save_image

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


def animate(scene: Scene, path: CameraPath, frames: int, mode="phong", *, modes=None,
            output=None, fps: float = 30.0, size=(512, 512), samples: int = 4,
            srgb: bool = False, jobs: int | None = 1, backend="auto",
            progress: bool | None = False):
    """Render ``frames`` frames along ``path``. Without ``output``, return an iterator of
    images; with it, write the file (GIF, PNG/APNG, MP4 or a folder) and return the number
    of frames. ``jobs=None`` uses every core."""
    jobs = (os.cpu_count() or 1) if jobs is None else jobs
    bar = Progress(frames, enabled=progress) if progress is not False else None
    it = render_frames(scene, path, frames, mode, modes=modes, size=size, samples=samples,
                       srgb=srgb, jobs=jobs, backend=backend, progress=bar)
    if output is None:
        return it
    try:
        return write_animation(it, output, fps)
    finally:
        if bar:
            bar.close()
