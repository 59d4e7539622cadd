"""Batch rendering of mesh collections: every mesh file under the inputs to images (and
depth, normal and id arrays), in local worker processes or on a Dask cluster; resumable
(outputs that exist whole are kept) and accounted for in ``manifest.csv``::

    from glshade.batch import batch, BatchSpec
    result = batch(["meshes/"], "thumbs/", BatchSpec(modes=("flat", "phong"), views=4),
                   jobs=2)
"""

from __future__ import annotations

import contextlib
import dataclasses
import time
from pathlib import Path

from ..atomic import remove_stale, writing
from ..parallel import Progress, make_executor
from .manifest import kept, read_manifest, write_manifest
from ._plan import Task, find_inputs, plan
from .worker import BatchSpec, BatchWorker, Row

__all__ = ["batch", "BatchSpec", "BatchResult", "Row", "Task", "find_inputs", "plan"]

MANIFEST = "manifest.csv"


@dataclasses.dataclass
class BatchResult:
    """The rows of the manifest, in input order, and what the run did.

    Parameters
    ----------
    rows : list of Row
        The manifest's rows, in input order.
    manifest : Path
        The manifest written.
    seconds : float
        The run's time.
    """

    rows: list[Row]
    manifest: Path
    seconds: float

    def count(self, status: str) -> int:
        """How many rows have ``status``.

        Parameters
        ----------
        status : str
            ``"ok"``, ``"exists"``, ``"error"`` or ``"not run"``.
        """
        return sum(r.status == status for r in self.rows)

    def summary(self) -> str:
        return (f"{len(self.rows)} meshes: {self.count('ok')} rendered, {self.count('exists')} "
                f"kept, {self.count('error')} failed"
                + (f", {self.count('not run')} not run" if self.count("not run") else "")
                + f" in {self.seconds:.1f} s; manifest: {self.manifest}")


def batch(inputs, outdir, spec: BatchSpec | None = None, *, jobs: int = 1,
          scheduler: str | None = None, overwrite: bool = False,
          progress: bool | None = None) -> BatchResult:
    """Render every mesh named by ``inputs`` (files, folders, globs) into ``outdir``.

    An input whose outputs all exist is kept (``overwrite=True`` renders it again); a
    malformed one gets a row with its error and the run goes on. ``jobs`` local worker
    processes, or ``scheduler`` (a Dask address, or "local"). Ctrl-C stops the run with
    the manifest of what was done written and no partial file left. ``progress`` (default
    None): tqdm's bar in a notebook (its widget) or on a terminal, a line now and then in
    a log, False nothing.

    Parameters
    ----------
    inputs : str, Path or sequence
        Mesh files, folders or globs.
    outdir : str or Path
        Where the pictures and the manifest go.
    spec : BatchSpec or None
        How every mesh is drawn (None: the defaults).
    jobs : int
        Local worker processes.
    scheduler : str or None
        A Dask scheduler's address, or ``"local"``.
    overwrite : bool
        Render a mesh again though its outputs exist.
    progress : bool or None
        The progress bar (None: where output goes decides).
    """
    start = time.perf_counter()
    spec = spec or BatchSpec()
    _ = spec.config  # (a setting the renderer refuses -- MSAA samples -- fails first)
    tasks = plan(find_inputs(inputs), outdir, spec.modes, spec.outputs, spec.views)
    outdir = Path(outdir)
    manifest = outdir / MANIFEST
    earlier = read_manifest(manifest)
    rows: dict[int, Row] = {}
    todo: list[int] = []
    for i, t in enumerate(tasks):
        fault = t.fault()  # (a name too long, a link out of OUTDIR: that input's error)
        if fault is not None:
            rows[i] = Row(t.input, "error", message=f"{t.input}: {fault}")
        elif not overwrite and t.done():
            rows[i] = kept(t, earlier)
        else:
            todo.append(i)
    # where the work runs is settled before anything is written (a missing extra, an
    # unknown scheduler: no folder, no manifest)
    executor = make_executor(BatchWorker, (spec,), jobs, items=len(todo),
                             scheduler=scheduler) if todo else None
    with writing(outdir):
        outdir.mkdir(parents=True, exist_ok=True)
    remove_stale(outdir, recursive=True)  # left by a run that was killed
    bar = Progress(len(todo), enabled=progress, unit="meshes") if progress is not False \
        else None
    try:
        if executor is not None:
            with contextlib.closing(executor.map([tasks[i] for i in todo])) as results:
                for i, row in zip(todo, results):
                    rows[i] = row
                    if bar:
                        bar.update()
    finally:
        if bar:
            bar.close()
        ordered = [rows.get(i) or _unreported(t) for i, t in enumerate(tasks)]
        write_manifest(ordered, manifest)
        remove_stale(outdir, recursive=True)  # a worker stopped mid-write
    return BatchResult(ordered, manifest, time.perf_counter() - start)


def _unreported(task: Task) -> Row:
    """The row of a task the run stopped before hearing from: a worker may have finished
    it (its outputs all exist) or not."""
    if task.done():
        return Row(task.input, "ok", outputs=task.outputs,
                   message="rendered; its report was cut off by the interrupt")
    return Row(task.input, "not run")
