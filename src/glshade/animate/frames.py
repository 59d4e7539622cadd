"""Rendering camera paths: the frames of a key-frame path, one or several shading modes side
by side, in this process or in worker processes (each with its own GL context), in order;
and :func:`animate`, which writes them to a file."""

from __future__ import annotations

import os
from collections.abc import Iterator

import numpy as np

from ..errors import InputError, OutputError
from .writers import check_fps
from ..io.images import LABEL_HEIGHT, labelled_row
from ..io.scenefile import SceneFile
from ..options import DrawOptions, RenderConfig
from ..scene import CameraPath, Scene
from ..parallel import make_executor
from ..parallel import Progress
from .writers import write_animation

__all__ = ["animate", "render_frames", "FrameMaker"]


class FrameMaker:
    """A worker that renders frame ``i`` of a path to RGBA bytes (in the main process or in
    a worker process). ``options`` are drawn unchanged, once per mode in ``modes``. With a
    ``spool`` folder (a cluster's workers) it writes the frame there as a PNG and returns
    the file's path instead: pixels do not travel through the scheduler.

    Parameters
    ----------
    scene : Scene
        What to draw.
    path : CameraPath
        The camera's key frames.
    times : ndarray
        Each frame's time.
    options : DrawOptions
        How.
    modes : sequence of str or None
        Several modes side by side.
    config : RenderConfig
        What the worker's renderer is built with.
    spool : str or Path or None
        Where frames go as PNG files (a cluster's workers), or None (returned as bytes).
    """

    def __init__(self, scene, path, times, options, modes, config: RenderConfig,
                 spool=None):
        from ..render.renderer import Renderer

        self.scene, self.path, self.times = scene, path, times
        self.options, self.modes, self.spool = options, modes, spool
        self.renderer = Renderer(config=config)

    def __call__(self, i: int) -> bytes | str:
        camera = self.path.at(self.times[i])
        tiles = {m.value: self.renderer.render(self.scene, camera, self.options.replace(mode=m))
                 for m in self.modes}
        image = next(iter(tiles.values())) if len(tiles) == 1 else labelled_row(tiles)
        if self.spool is None:
            return image.tobytes()
        from ..io.images import save_image

        path = os.path.join(self.spool, f"frame_{i:06d}.png")
        save_image(image, path)
        return path

    def close(self):
        self.renderer.close()


def frame_shape(size, n_modes: int) -> tuple[int, int, int]:
    """``(H, W, 4)`` of a frame: one tile, or ``n_modes`` labelled tiles side by side."""
    w, h = size
    return (h, w, 4) if n_modes == 1 else (h + LABEL_HEIGHT, w * n_modes, 4)


def render_frames(scene: Scene, path: CameraPath, frames: int, options=None, *, modes=None,
                  config: RenderConfig | None = None, size=None, samples: int | None = None,
                  jobs: int = 1, backend=None, progress: Progress | None = None,
                  scheduler: str | None = None, spool=None,
                  **changes) -> Iterator[np.ndarray]:
    """Yield ``frames`` images ``(H, W', 4) uint8`` evenly spaced along ``path``, in order.

    ``options``: DrawOptions or a mode's name (``changes`` override single options). With
    ``modes`` several shading modes are laid side by side, labelled. ``jobs > 1`` renders
    in spawned worker processes, each with its own GL context; ``scheduler`` (a Dask
    address, or "local") on a Dask cluster, whose workers pass frames as PNG files through
    a temporary folder beside ``spool`` (a path every worker can reach; default: this
    machine's temporary folder). ``config`` (or ``size``, ``samples``, ``backend``): what
    each worker's Renderer is built with (default 512x512, 4 samples).

    Parameters
    ----------
    scene : Scene
        What to draw.
    path : CameraPath
        The camera's key frames.
    frames : int
        How many, evenly spaced.
    options : DrawOptions, ShadingMode, str or None
        How.
    modes : sequence of str or None
        Several modes side by side.
    config : RenderConfig or None
        What each renderer is built with (or the next keywords).
    size : (int, int) or None
        Width and height in pixels.
    samples : int or None
        MSAA samples.
    jobs : int
        Worker processes.
    backend : str or None
        The headless backend.
    progress : Progress or None
        The bar to update.
    scheduler : str or None
        A Dask scheduler's address, or ``"local"``.
    spool : str or Path or None
        Where workers on a cluster leave their frames (a folder every worker reaches).
    **changes
        Single draw options replaced, by name.
    """
    config = RenderConfig.of(config, size=size, samples=samples, backend=backend)
    options = DrawOptions.of(options, **changes)
    modes = [DrawOptions.of(m).mode for m in (modes or [options.mode])]
    if int(frames) != frames or frames < 1:
        raise InputError(f"need at least one frame, got {frames!r}")
    times = path.frame_times(int(frames))
    if scheduler is None:
        args = (scene, path, times, options, modes, config)
        executor = make_executor(FrameMaker, args, jobs, items=int(frames))
        shape = frame_shape(config.size, len(modes))
        for data in executor.map(range(int(frames))):
            if progress:
                progress.update()
            yield np.frombuffer(data, np.uint8).reshape(shape)
        return
    yield from _spooled(scene, path, times, options, modes, config, jobs, scheduler, spool,
                        progress)


def _spooled(scene, path, times, options, modes, config, jobs, scheduler, spool, progress):
    import shutil
    import tempfile

    from PIL import Image

    from ..atomic import held_interrupts, temporary

    folder = None
    try:
        with held_interrupts():  # (a Ctrl-C cannot land between making it and keeping its name)
            folder = (temporary(spool, folder=True) if spool
                      else tempfile.mkdtemp(prefix="glshade-"))
        args = (scene, path, times, options, modes, config, folder)
        executor = make_executor(FrameMaker, args, jobs, scheduler=scheduler)
        for file in executor.map(range(len(times))):
            with Image.open(file) as im:
                frame = np.asarray(im.convert("RGBA"))
            os.unlink(file)
            if progress:
                progress.update()
            yield frame
    finally:
        if folder is not None:
            shutil.rmtree(folder, ignore_errors=True)


def _check_output(output, shape) -> None:
    """Refuse, before any frame is drawn, what the output's format cannot hold: H.264 (MP4,
    yuv420p) stores colour at half resolution, so it needs an even width and height."""
    from .writers import output_format

    if output_format(output) == "mp4" and (shape[0] % 2 or shape[1] % 2):
        h, w = shape[:2]
        raise OutputError(f"{output}: MP4 (H.264) needs an even width and height, and the "
                          f"frames would be {w}x{h}; make the size even (e.g. --size "
                          f"{w + w % 2}x{h + h % 2}, or a .gif / .png output)")


def animate(scene, path: CameraPath | None = None, frames: int | None = None, options=None,
            *, modes=None, output=None, fps: float | None = None,
            config: RenderConfig | None = None, size=None, samples: int | None = None,
            jobs: int | None = 1, backend=None, progress: bool | None = None,
            scheduler: str | None = None, **changes):
    """Render ``frames`` frames along ``path``. Without ``output``, return an iterator of
    images; with it, write the file (GIF, PNG/APNG, MP4 or a folder) and return the number
    of frames. ``jobs=None`` uses every core; ``progress`` (default None) shows tqdm's bar in a
    notebook (its widget) or on a terminal, a line now and then in a log, False nothing;
    ``scheduler`` renders on a Dask cluster (see :func:`render_frames`); ``config`` (or
    ``size``, ``samples``, ``backend``) is what each Renderer is built with.

    ``scene`` may be a loaded scene file (:func:`glshade.load_scene`): then its camera path,
    its ``[render]`` size, samples, fps, duration and draw options are used wherever the
    call does not give its own (``frames`` defaults to duration x fps, else the path's).

    Parameters
    ----------
    scene : Scene or SceneFile
        What to draw (a loaded scene file brings its path and settings).
    path : CameraPath or None
        The camera's key frames (None: the scene file's).
    frames : int or None
        How many (None: duration x fps, else the path's keys).
    options : DrawOptions, ShadingMode, str or None
        How (None: the defaults or the file's).
    modes : sequence of str or None
        Several modes side by side, labelled.
    output : str or Path or None
        A GIF, PNG/APNG, MP4 or folder to write (None: return an iterator of images).
    fps : float or None
        Frames a second of the file.
    config : RenderConfig or None
        What each renderer is built with (or the next keywords).
    size : (int, int) or None
        Width and height in pixels.
    samples : int or None
        MSAA samples.
    jobs : int or None
        Worker processes (None: every core).
    backend : str or None
        The headless backend.
    progress : bool, tqdm-like or None
        The progress bar (None: where output goes decides; False: none).
    scheduler : str or None
        A Dask scheduler's address, or ``"local"``.
    **changes
        Single draw options replaced, by name.
    """
    if isinstance(scene, SceneFile):
        st = scene.settings
        path = scene.path if path is None else path
        options = st.options if options is None else options
        fps = check_fps(st.fps if fps is None else fps)
        if config is None:
            config = RenderConfig.of(size=size or st.size,
                                     samples=st.samples if samples is None else samples,
                                     backend=backend)
        if frames is None:
            seconds = st.duration if st.duration is not None else path.duration
            frames = max(1, int(round(seconds * fps)))
        scene = scene.scene
    if path is None or frames is None:
        raise InputError("animate needs a camera path and a number of frames (or a loaded "
                         "scene file, which has both)")
    fps = 30.0 if fps is None else check_fps(fps)
    config = RenderConfig.of(config, size=size, samples=samples, backend=backend)
    if output is not None:
        _check_output(output, frame_shape(config.size, len(modes or [None])))
    jobs = (os.cpu_count() or 1) if jobs is None else jobs
    bar = Progress(frames, enabled=progress) if progress is not False else None
    spool = None
    if output is not None and scheduler is not None and scheduler != "local":
        spool = os.path.join(os.path.dirname(os.path.abspath(output)), "frames")
    config = RenderConfig.of(config, size=size, samples=samples, backend=backend)
    it = render_frames(scene, path, frames, options, modes=modes, config=config, jobs=jobs,
                       progress=bar, scheduler=scheduler, spool=spool, **changes)
    if output is None:
        return it
    try:
        return write_animation(it, output, fps)
    finally:
        if bar:
            bar.close()
