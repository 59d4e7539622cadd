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

__all__ = ["DataSetJob", "run_views", "load_scene_arg", "write_json"]


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
    """

    scene: Scene
    cameras: list
    size: tuple[int, int]
    samples: int = 4
    options: object = None


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
    atomically: the same content, the same bytes."""
    if isinstance(content, dict):
        items = [f'  "{k}": {json.dumps(v, sort_keys=True)}' for k, v in content.items()]
        text = "{\n" + ",\n".join(items) + "\n}"
    else:
        text = json.dumps(content, sort_keys=True, indent=1)
    with atomic_write(path, "w", encoding="utf-8") as f:
        f.write(text + "\n")


def run_views(job: DataSetJob, records_dir: Path, write_view, progress=None,
              context=None) -> list[dict]:
    """Draw each view not yet recorded in ``records_dir`` and hand it to ``write_view(k,
    frame, notes) -> (record, files)``: ``notes()`` its objects' annotations (drawn only if
    asked), ``files`` the ``(function, *args)`` that write its files. The files are written
    on a thread of their own while the next view is drawn (PNG's zlib lets go of the
    interpreter), then the record, last: a view with a record is whole. Returns every
    view's record, in order.

    Parameters
    ----------
    job : DataSetJob
        The scene, cameras, size, samples and options.
    records_dir : Path
        Where each view's record is kept (``{k:06d}.json``): a view with one is done.
    write_view : callable
        ``(k, frame, notes) -> (record, files)``.
    progress : bool, tqdm-like or None
        The progress bar (None: one on a terminal).
    context : RenderContext or None
        The context to draw in (None: the renderer's own).
    """
    from concurrent.futures import ThreadPoolExecutor

    from ..interrupt import check
    from ..parallel.progress import as_progress
    from ..render.renderer import Renderer

    records_dir.mkdir(parents=True, exist_ok=True)
    todo = [k for k in range(len(job.cameras)) if not (records_dir / f"{k:06d}.json").exists()]
    bar, owned = as_progress(progress, len(job.cameras), "views")

    def finish(k: int, record: dict, files: list) -> None:
        for fn, *args in files:
            fn(*args)
        write_json(records_dir / f"{k:06d}.json", record)

    pending: list = []
    try:
        if bar is not None and len(todo) < len(job.cameras):
            bar.update(len(job.cameras) - len(todo), "already written")
        if todo:
            with Renderer(*job.size, samples=job.samples, context=context) as renderer, \
                    ThreadPoolExecutor(max_workers=1) as writer:
                for k in todo:
                    check()
                    camera = job.cameras[k]
                    frame = renderer.render_frame(
                        job.scene, camera, job.options,
                        outputs=Outputs.COLOR | Outputs.DEPTH | Outputs.INSTANCE)

                    def notes(camera=camera, frame=frame):
                        return renderer.annotate(job.scene, camera, job.options, view=frame)

                    record, files = write_view(k, frame, notes)
                    while pending and pending[0].done():  # (a failed write stops the run)
                        pending.pop(0).result()
                    pending.append(writer.submit(finish, k, record, files))
                    if bar is not None:
                        bar.update(1)
                for future in pending:
                    future.result()
    finally:
        if owned and bar is not None:
            bar.close()
    return [json.loads((records_dir / f"{k:06d}.json").read_text(encoding="utf-8"))
            for k in range(len(job.cameras))]
