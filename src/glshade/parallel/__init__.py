"""Running the same work on many items, results in item order: in this process, in a pool of
local worker processes (``jobs``), or on a Dask cluster (``scheduler``); each worker builds
its renderer (one GL context) once. Behind ``animate``, ``compare --sweep`` and ``batch``."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..errors import InputError
from .executors import Executor, ProcessExecutor, SerialExecutor
from .progress import Progress, as_progress

if TYPE_CHECKING:
    from .dask import DaskExecutor

__all__ = ["Executor", "SerialExecutor", "ProcessExecutor", "make_executor", "Progress",
           "as_progress", "DaskExecutor"]


def __getattr__(name: str) -> Any:  # the Dask executor imports dask only when asked for
    if name == "DaskExecutor":
        from .dask import DaskExecutor

        return DaskExecutor
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def make_executor(factory, args: tuple, jobs: int = 1, items: int | None = None,
                  scheduler: str | None = None) -> Executor:
    """Where the work runs: on a Dask cluster if ``scheduler`` is given (an address, or
    ``"local"`` for a LocalCluster of ``jobs`` workers), else in this process for one job
    (or one item), else in ``jobs`` local worker processes.

    Parameters
    ----------
    factory : callable
        ``factory(*args)`` makes a worker: ``worker(item)``, ``worker.close()``.
    args : tuple
        Its arguments (picklable for other processes).
    jobs : int
        Local processes (1: this one).
    items : int or None
        How many items (no more processes than items).
    scheduler : str or None
        A Dask scheduler's address, or ``"local"``.
    """
    if int(jobs) != jobs or jobs < 1:
        raise InputError(f"jobs must be a whole number >= 1, got {jobs!r}")
    if scheduler is not None:
        from .dask import DaskExecutor

        return DaskExecutor(factory, args, scheduler, workers=int(jobs))
    if items is not None:
        jobs = min(jobs, max(items, 1))
    return SerialExecutor(factory, args) if jobs == 1 else ProcessExecutor(factory, args, jobs)
