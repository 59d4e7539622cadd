"""Running the same work on many items, results in item order: in this process, in a pool of
local worker processes (``jobs``), or on a Dask cluster (``scheduler``); each worker builds
its renderer (one GL context) once. Behind ``animate``, ``compare --sweep`` and ``batch``."""

from .executors import Executor, ProcessExecutor, SerialExecutor, make_executor
from .progress import Progress

__all__ = ["Executor", "SerialExecutor", "ProcessExecutor", "make_executor", "Progress",
           "DaskExecutor"]


def __getattr__(name):  # the Dask executor imports dask only when asked for
    if name == "DaskExecutor":
        from .dask import DaskExecutor

        return DaskExecutor
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
