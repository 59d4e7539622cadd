"""The work of one batch item, in whichever process or cluster worker runs it: load the
mesh, frame it from ``views`` directions around it, render every mode, write the images and
arrays atomically, and return one manifest row. Bad input becomes the row's error; only a
failure of the machine (no GL context, a disk that cannot be written) stops the run."""

from __future__ import annotations

import dataclasses
import io
import os
import time
import warnings
import zipfile

import numpy as np

from ..atomic import atomic_write, writing
from ..errors import EnvironmentFailure, GlshadeError, UsageError
from ..modes import Backend, Outputs
from ..options import DrawOptions, RenderConfig
from ._plan import Task

__all__ = ["BatchSpec", "BatchWorker", "Row", "view_directions", "write_npz"]


@dataclasses.dataclass(frozen=True)
class BatchSpec:
    """How every mesh of a batch is drawn (the same for all of them).

    Parameters
    ----------
    modes : tuple of str
        The shading modes drawn.
    outputs : Outputs
        What is written besides colour.
    size : (int, int)
        The images' size.
    samples : int
        MSAA samples.
    views : int
        Views a mesh, turned about the up axis.
    options : DrawOptions
        How each is drawn.
    material : Material or None
        The meshes' material (None: the default).
    background : tuple or None
        The background colour.
    lights : tuple
        Lights (none: the headlight).
    crease : float or None
        Degrees past which edges stay sharp.
    fov : float or None
        The camera's vertical field of view.
    backend : Backend or str
        The headless backend.
    """

    modes: tuple[str, ...] = ("phong",)
    outputs: Outputs = Outputs.COLOR
    size: tuple[int, int] = (256, 256)
    samples: int = 4
    views: int = 1
    options: DrawOptions = DrawOptions()
    material: dict = dataclasses.field(default_factory=dict)  # Material fields given
    background: tuple | None = None
    lights: tuple = ()  # point-light positions; none: the headlight
    crease: float | None = None
    fov: float | None = None
    backend: Backend | str = "auto"

    @property
    def config(self) -> RenderConfig:
        """What each worker's Renderer is built with (checked there, by RenderConfig)."""
        return RenderConfig(*self.size, samples=self.samples, backend=Backend.parse(self.backend))


@dataclasses.dataclass
class Row:
    """One line of ``manifest.csv``.

    Parameters
    ----------
    input : str
        The mesh's path or spec.
    status : str
        ``"ok"``, ``"exists"``, ``"error"`` or ``"not run"``.
    polygons : int or None
        Its polygons.
    seconds : float or None
        Its render's time.
    outputs : tuple of str
        The files written.
    message : str
        An error's line.
    renderer : str
        The GL renderer that drew it (a GPU's name, or llvmpipe where a GPU was lost).
    """

    input: str
    status: str  # ok, error, exists (kept from an earlier run), not run (interrupted)
    polygons: int | None = None
    seconds: float | None = None
    outputs: tuple[str, ...] = ()
    message: str = ""
    renderer: str = ""


def view_directions(views: int) -> np.ndarray:
    """``(views, 3)`` directions from the target to the eye: the default view turned about
    the up axis in equal steps (view 0 is the default camera's).

    Parameters
    ----------
    views : int
        How many.
    """
    from ..scene.camera import DEFAULT_VIEW_FROM

    x, y, z = DEFAULT_VIEW_FROM
    a = 2 * np.pi * np.arange(views) / views
    c, s = np.cos(a), np.sin(a)
    return np.stack([c * x + s * z, np.full(views, y), -s * x + c * z], axis=1)


def write_npz(path, arrays: dict) -> None:
    """``np.savez_compressed``, but byte-for-byte reproducible (numpy stamps each member
    with the current time) and atomic.

    Parameters
    ----------
    path : str or Path
        The file.
    arrays : dict
        Arrays by name.
    """
    with atomic_write(path, "wb") as f, zipfile.ZipFile(f, "w", zipfile.ZIP_DEFLATED) as z:
        for name, a in arrays.items():
            buf = io.BytesIO()
            np.lib.format.write_array(buf, np.ascontiguousarray(a), allow_pickle=False)
            info = zipfile.ZipInfo(f"{name}.npy", date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, buf.getvalue())


class BatchWorker:
    """``worker(task) -> Row``; one renderer (one GL context) for every task it is given.

    Parameters
    ----------
    spec : BatchSpec
        How every mesh is drawn.
    """

    def __init__(self, spec: BatchSpec):
        from ..render.renderer import Renderer

        self.spec = spec
        self.renderer = Renderer(config=spec.config)

    def __call__(self, task: Task) -> Row:
        start = time.perf_counter()
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                polygons = self._render(task)
            except EnvironmentFailure:
                raise  # the machine, not the file: stop the run
            except GlshadeError as exc:
                return Row(task.input, "error", message=str(exc))
            except (MemoryError, RecursionError) as exc:
                return Row(task.input, "error", message=f"{type(exc).__name__}: {exc}")
        notes = "; ".join(dict.fromkeys(str(w.message) for w in caught))
        return Row(task.input, "ok", polygons, round(time.perf_counter() - start, 4),
                   task.outputs, notes, self.renderer.context.detail)

    def _render(self, task: Task) -> int:
        from ..io.images import save_image
        from ..io.meshes import load_source
        from ..scene import Camera, Material, PointLight, Scene

        s = self.spec
        mesh = load_source(str(task.input))  # (a mesh file, or a .bpt file of patches)
        scene = Scene(**({"background": s.background} if s.background is not None else {}))
        model = scene.add(mesh, Material.from_values(s.material), crease=s.crease)
        for position in s.lights:
            scene.add_light(PointLight(position))
        fault = task.fault()  # (checked again where the files are made: links can change)
        if fault is not None:
            raise UsageError(f"{task.input}: {fault}")
        for p in task.outputs:
            with writing(p):
                os.makedirs(os.path.dirname(p), exist_ok=True)
        b = scene.bounds
        centre = b.mean(axis=0)
        lens = {"fov_y": s.fov} if s.fov is not None else {}
        images = iter(task.images)
        arrays = iter(task.arrays)
        for direction in view_directions(s.views):
            camera = Camera.look_at(centre + direction, centre, **lens)
            camera = camera.frame(b, aspect=s.size[0] / s.size[1], margin=1.0)
            for mode in s.modes:
                options = s.options.replace(mode=DrawOptions.of(mode).mode)
                save_image(self.renderer.render(scene, camera, options), next(images))
            if s.outputs.auxiliary:  # (a pass of its own: colour keeps its MSAA)
                frame = self.renderer.render_frame(scene, camera, s.options,
                                                   outputs=s.outputs)
                write_npz(next(arrays), {name: getattr(frame, name) for name in
                                         ("depth", "normal", "face_id")
                                         if getattr(frame, name) is not None})
        # (patches: their tessellation's polygons; a point cloud or polylines: none)
        mesh = getattr(model, "mesh", None)
        return mesh.n_faces if mesh is not None else 0

    def close(self):
        self.renderer.close()
