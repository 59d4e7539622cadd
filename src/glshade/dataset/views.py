"""The loop every data-set writer runs: each view drawn once (colour, depth, instance ids),
its objects annotated (:meth:`Renderer.annotate`), and handed to the writer -- skipping the
views a run before finished (each view's record is a file of its own, written last and
atomically, so a view is either whole or absent), with a progress bar."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from ..atomic import atomic_write
from ..errors import InputError, OptionError
from ..modes import Outputs
from ..scene import Scene

__all__ = ["DataSetJob", "ViewWorker", "run_views", "view_done", "load_scene_arg",
           "write_json"]


@dataclass(frozen=True)
class DataSetJob:
    """What a writer draws: the scene, its cameras and the images' size.

    Parameters
    ----------
    scene : Scene
        The objects (labelled by ``Scene.add(label=...)``).
    cameras : list of Camera
        One a view, in order: view k is image k.
    size : (int, int)
        The images' width and height in pixels.
    samples : int
        MSAA samples of the colour images (ids, depth and masks are exact whatever).
    options : DrawOptions, ShadingMode, str or None
        How the colour images are drawn.
    images : str
        ``"raster"`` (the colour images drawn with ``options``) or ``"pathtrace"`` (traced
        by :func:`glshade.pathtrace.trace`, ``spp`` samples a pixel or ``until`` a relative
        error; the masks, depth and poses the same exact raster ones of the view).
    spp : int or None
        A traced image's samples a pixel.
    until : float or None
        Or the relative error a traced image is refined to.
    """

    scene: Scene
    cameras: list
    size: tuple[int, int]
    samples: int = 4
    options: object = None
    images: str = "raster"
    spp: int | None = None
    until: float | None = None

    def __post_init__(self):
        if self.images not in ("raster", "pathtrace"):
            raise OptionError(f"images must be 'raster' or 'pathtrace', got {self.images!r}")
        if self.images == "raster" and (self.spp is not None or self.until is not None):
            raise OptionError("spp and until are for images='pathtrace'")
        if self.images == "pathtrace" and self.spp is None and self.until is None:
            object.__setattr__(self, "spp", 64)  # (the tracer's default)


def load_scene_arg(scene, views: int | None, size, cameras=None):
    """``(Scene, cameras, size)`` from a Scene or a scene file's path: the file's [render]
    size unless ``size`` is given, its key-framed path sampled when it has more than one
    key and no ``cameras`` were given, else cameras on a sphere.

    Parameters
    ----------
    scene : Scene, str or Path
        The scene, or its file.
    views : int or None
        How many views (None: 1 for a still, else required).
    size : (int, int) or None
        The images' size (None: the file's, else 640x480).
    cameras : list of Camera or None
        The views' cameras, given.
    """
    from ..options import check_size
    from .cameras import sphere_cameras

    path_cameras = None
    if not isinstance(scene, Scene):
        from ..io.scenefile import load_scene

        made = load_scene(scene)
        scene = made.scene
        if size is None:
            size = (made.settings.width, made.settings.height)
        if len(made.path.keyframes) > 1:
            path_cameras = made.path
    size = check_size(*(size or (640, 480)))
    if cameras is not None:
        cameras = list(cameras)
        if not cameras:
            raise OptionError("cameras must hold at least one camera")
        return scene, cameras, size
    if views is None or isinstance(views, bool) or not isinstance(views, int) or views < 1:
        raise OptionError(f"views must be a whole number >= 1, got {views!r}")
    if not (scene.models or scene.solids or scene.patch_models):
        raise InputError("the scene has nothing to draw: a data set needs objects")
    if path_cameras is not None:
        return scene, path_cameras.sample(views), size
    return scene, sphere_cameras(scene.bounds, views, size), size


def write_json(path: Path, content) -> None:
    """``content`` as JSON, keys sorted, one top-level entry a line (BOP's own layout),
    atomically: the same content, the same bytes.

    Parameters
    ----------
    path : Path
        The file.
    content : dict or list
        What to write.
    """
    if isinstance(content, dict):
        items = [f'  "{k}": {json.dumps(v, sort_keys=True)}' for k, v in content.items()]
        text = "{\n" + ",\n".join(items) + "\n}"
    else:
        text = json.dumps(content, sort_keys=True, indent=1)
    with atomic_write(path, "w", encoding="utf-8") as f:
        f.write(text + "\n")


def renderers(records: list) -> str:
    """The GL renderers that drew a data set's views (each view's record says), joined."""
    return "; ".join(sorted({str(r.get("renderer", "unknown")) for r in records}))


#: a view record's list of the files it wrote, each with its size in bytes
FILES_KEY = "files_written"


def _finish(records_dir: Path, k: int, record: dict, files: list) -> None:
    """Write a view's files, then its record (last), which lists each file with its size:
    a view is done when its record is there and every file it lists is whole
    (:func:`view_done`)."""
    import os

    written = {}
    for fn, *args in files:
        fn(*args)
        for path in (a for a in args if isinstance(a, Path)):
            written[os.path.relpath(path, records_dir)] = path.stat().st_size
    write_json(records_dir / f"{k:06d}.json", {**record, FILES_KEY: written})


def view_done(records_dir: Path, k: int) -> bool:
    """Whether view k need not be drawn again: its record is there, and each file it lists
    exists with the size it was written with (a file deleted or torn since -- cut short by
    a crash, a full disk, a copy -- makes the view be drawn again).

    Parameters
    ----------
    records_dir : Path
        Where the views' records are.
    k : int
        The view.
    """
    path = records_dir / f"{k:06d}.json"
    try:
        record = json.loads(path.read_text(encoding="utf-8"))
        files = record[FILES_KEY]
    except (OSError, ValueError, KeyError, TypeError):  # (none, torn, or from before)
        return False
    for name, size in files.items():
        try:
            if (records_dir / name).stat().st_size != size:
                return False
        except OSError:
            return False
    return True


class ViewWorker:
    """Draws views of one job and writes them: a worker of :mod:`glshade.parallel` (in
    this process, in worker processes or on a Dask cluster), its renderer made on its first
    view and kept for the rest.

    Parameters
    ----------
    job : DataSetJob
        The scene, cameras, size, samples and options.
    writer : callable
        ``(k, frame, notes) -> (record, files)``: what a view writes (picklable).
    records_dir : Path
        Where each view's record goes.
    context : RenderContext or None
        A context to draw in (this process only).
    """

    def __init__(self, job: DataSetJob, writer, records_dir: Path, context=None):
        from ..render.renderer import Renderer

        self.job, self.writer, self.records_dir = job, writer, records_dir
        self.context = context
        self._renderer: Renderer | None = None
        self._trace_scene = None  # (images="pathtrace": the scene as traced, made once)

    def frame(self, k: int):
        """View k drawn, ``(frame, notes)``: ``notes()`` its annotations, drawn if asked.

        Parameters
        ----------
        k : int
            The view.
        """
        return next(self.frames([k]))[1:]

    def frames(self, views: list[int]):
        """``(k, frame, notes)`` for each of ``views`` in turn, drawn a few ahead of the one
        handed out (:meth:`Renderer.render_many`; the annotations' draws between them leave
        the frames drawn ahead as they are); ``notes()`` a view's annotations, drawn if
        asked.

        Parameters
        ----------
        views : list of int
            The views, in order.
        """
        from ..render.renderer import Renderer

        if self._renderer is None:
            self._renderer = Renderer(*self.job.size, samples=self.job.samples,
                                      context=self.context)
        renderer, job = self._renderer, self.job
        drawn = renderer.render_many(job.scene, [job.cameras[k] for k in views], job.options,
                                     outputs=Outputs.COLOR | Outputs.DEPTH | Outputs.INSTANCE)
        for k, frame in zip(views, drawn):
            camera = job.cameras[k]
            if job.images == "pathtrace":
                frame = self._traced(frame, camera)
            yield k, frame, (lambda camera=camera, frame=frame: renderer.annotate(
                job.scene, camera, job.options, view=frame))

    def _traced(self, frame, camera):
        """``frame`` with its colour traced (the job's spp or error), encoded as the
        raster colour is (sRGB where the options say, 8 bits, the raster's alpha)."""
        import dataclasses

        import numpy as np

        from ..options import DrawOptions
        from ..pathtrace import TraceScene, trace

        job = self.job
        assert self._renderer is not None
        scene = self._trace_scene
        if scene is None:
            # (without lights, emitters or a sky, the raster's headlight at the view's
            # eye: made again for each view; else made once, its hierarchy with it)
            scene = TraceScene.from_scene(job.scene, camera=camera)
            if job.scene.lights or job.scene.environment is not None or len(scene.emitters):
                self._trace_scene = scene
        traced = trace(scene, camera, job.size, spp=job.spp, until=job.until,
                       context=self._renderer.context, progress=False)
        color = np.clip(traced.image, 0.0, 1.0)
        if DrawOptions.of(job.options).srgb:
            from .._srgb import linear_to_srgb

            color = linear_to_srgb(color)
        rgba = frame.color.copy()
        rgba[..., :3] = np.round(color * 255).astype(np.uint8)
        return dataclasses.replace(frame, color=rgba)

    def written(self, k: int, frame, notes) -> tuple[dict, list]:
        """The writer's ``(record, files)`` for view k, the record saying what drew it (a
        GPU's name, or llvmpipe where one was lost).

        Parameters
        ----------
        k : int
            The view.
        frame : Frame
            Its frame.
        notes : callable
            Its annotations, drawn if asked.
        """
        record, files = self.writer(k, frame, notes)
        assert self._renderer is not None  # (made by frame)
        return {**record, "renderer": self._renderer.context.detail}, files

    def __call__(self, k: int) -> int:
        frame, notes = self.frame(k)
        record, files = self.written(k, frame, notes)
        _finish(self.records_dir, k, record, files)
        return k

    def close(self) -> None:
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None


def run_views(job: DataSetJob, records_dir: Path, writer, progress=None, context=None, *,
              jobs: int = 1, scheduler: str | None = None) -> list[dict]:
    """Draw each view not yet recorded in ``records_dir`` and hand it to ``writer(k,
    frame, notes) -> (record, files)``: ``notes()`` its objects' annotations (drawn only if
    asked), ``files`` the ``(function, *args)`` that write its files; then its record, last
    (a view with a record is whole). In one process the files are written on a thread of
    their own while the next view is drawn (PNG's zlib lets go of the interpreter); with
    ``jobs`` or a ``scheduler`` the views are shared among worker processes or a Dask
    cluster's workers, each with its renderer. Returns every view's record, in order.

    Parameters
    ----------
    job : DataSetJob
        The scene, cameras, size, samples and options.
    records_dir : Path
        Where each view's record is kept (``{k:06d}.json``, with its files' sizes): a view
        whose record is there and whose files are whole is done (:func:`view_done`).
    writer : callable
        ``(k, frame, notes) -> (record, files)``, picklable for workers.
    progress : bool, tqdm-like or None
        The progress bar (None: one on a terminal).
    context : RenderContext or None
        The context to draw in, in this process (None: the renderer's own).
    jobs : int
        Local worker processes (1: this one).
    scheduler : str or None
        A Dask scheduler's address, or ``"local"`` (the ``distributed`` extra).
    """
    from concurrent.futures import ThreadPoolExecutor

    from ..interrupt import check
    from ..parallel import make_executor
    from ..parallel.progress import as_progress

    records_dir.mkdir(parents=True, exist_ok=True)
    todo = [k for k in range(len(job.cameras)) if not view_done(records_dir, k)]
    bar, owned = as_progress(progress, len(job.cameras), "views")
    try:
        if bar is not None and len(todo) < len(job.cameras):
            bar.update(len(job.cameras) - len(todo), "already written")
        if todo and (jobs > 1 or scheduler is not None):
            executor = make_executor(ViewWorker, (job, writer, records_dir), jobs,
                                     items=len(todo), scheduler=scheduler)
            for _ in executor.map(todo):
                if bar is not None:
                    bar.update(1)
        elif todo:
            worker = ViewWorker(job, writer, records_dir, context)
            pending: list = []
            with ThreadPoolExecutor(max_workers=1) as files:
                try:
                    for k, frame, notes in worker.frames(todo):
                        check()
                        record, to_write = worker.written(k, frame, notes)
                        while pending and pending[0].done():  # (a failed write stops it)
                            pending.pop(0).result()
                        pending.append(files.submit(_finish, records_dir, k, record,
                                                    to_write))
                        if bar is not None:
                            bar.update(1)
                    for future in pending:
                        future.result()
                finally:
                    worker.close()
    finally:
        if owned and bar is not None:
            bar.close()
    return [json.loads((records_dir / f"{k:06d}.json").read_text(encoding="utf-8"))
            for k in range(len(job.cameras))]
