"""Running the same work on many items, in order: in this process, or in a pool of spawned
worker processes that each build their worker once (one GL context per process).

A *worker factory* is a picklable callable; ``factory(*args)`` returns a worker, a callable
``worker(item) -> result`` with a ``close()``. Executors yield results in item order.
"""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import os
import pickle
import queue
import signal
import sys
import threading
from collections.abc import Generator, Iterable

from ..atomic import held_interrupts
from ..interrupt import check

__all__ = ["Executor", "SerialExecutor", "ProcessExecutor", "terminate"]


class Executor:
    """``map(items)`` yields ``worker(item)`` for each item, in order.

    Parameters
    ----------
    factory : callable
        ``factory(*args)`` makes a worker: ``worker(item)``, ``worker.close()``.
    args : tuple
        Its arguments (picklable for other processes).
    """

    def __init__(self, factory, args: tuple):
        self.factory, self.args = factory, args

    def map(self, items: Iterable) -> Generator:
        """``worker(item)`` for each item, in order.

        Parameters
        ----------
        items : iterable
            The work, in order.
        """
        raise NotImplementedError


class SerialExecutor(Executor):
    """One worker in this process.

    Parameters
    ----------
    factory : callable
        ``factory(*args)`` makes a worker: ``worker(item)``, ``worker.close()``.
    args : tuple
        Its arguments (picklable for other processes).
    """

    def map(self, items):
        """``worker(item)`` for each item, in order, in this process.

        Parameters
        ----------
        items : iterable
            The work, in order.
        """
        worker = self.factory(*self.args)
        try:
            for item in items:
                check()
                yield worker(item)
        finally:
            worker.close()


_worker = None
_worker_error: BaseException | None = None


def _init_worker(payload: bytes, threads: int, ranks):
    global _worker, _worker_error
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C
    try:  # (a number a worker: its turn of the devices, where there are several)
        os.environ["GLSHADE_WORKER_RANK"] = str(ranks.get(timeout=10))
    except queue.Empty:  # (a worker started in the place of one that died: the default)
        pass
    # Mesa's software rasterizer starts a thread per core in every process; with one worker
    # per core that oversubscribes the machine. Share the cores out instead (no effect on
    # GPU drivers).
    os.environ.setdefault("LP_NUM_THREADS", str(threads))
    # a warning from a worker (a blank frame) is one line on stderr, as in the parent's CLI
    import warnings

    warnings.formatwarning = lambda message, *_, **__: f"glshade: warning: {message}\n"
    try:  # (the factory comes pickled: a worker that cannot load it reports why)
        factory, args = pickle.loads(payload)
        _worker = factory(*args)
    except Exception as exc:  # reported with the first item, in the parent, as it is; a
        _worker_error = exc     # worker that died while starting would be restarted forever


def _work(item):
    if _worker_error is not None:
        raise _worker_error
    assert _worker is not None
    return _worker(item)


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


class _WorkerProcess(mp.context.SpawnProcess):
    """A spawned worker that starts with Ctrl-C blocked. A terminal's Ctrl-C reaches every
    process of the group, and a worker still importing would print its own traceback; a
    blocked signal stays blocked through fork and exec, so the worker's Python never turns
    it into KeyboardInterrupt. Only the starting thread blocks it, and only while the child
    is launched; the parent's own Ctrl-C is held back meanwhile
    (:func:`~glshade.atomic.held_interrupts`), not
    lost."""

    @staticmethod
    def _Popen(process_obj):
        if not hasattr(signal, "pthread_sigmask"):  # (not POSIX: nothing to block)
            return mp.context.SpawnProcess._Popen(process_obj)
        old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        try:
            return mp.context.SpawnProcess._Popen(process_obj)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)


def terminate(pool, timeout: float = 10.0) -> bool:
    """``pool.terminate()``, bounded: whether it finished. (CPython's result handler can
    wait forever on a message a worker was killed in the middle of writing -- seen about
    once in a hundred Ctrl-Cs -- and terminate waits for that thread.) On a timeout the
    workers are killed outright.

    Parameters
    ----------
    pool : multiprocessing.pool.Pool
        The pool.
    timeout : float
        Seconds to wait.
    """
    t = threading.Thread(target=pool.terminate, daemon=True, name="glshade-pool-stop")
    t.start()
    t.join(timeout)
    if not t.is_alive():
        return True
    for worker in list(getattr(pool, "_pool", ())):
        with contextlib.suppress(Exception):
            worker.kill()
    return False


class _WorkerContext(mp.context.SpawnContext):
    Process = _WorkerProcess


class ProcessExecutor(Executor):
    """``jobs`` spawned worker processes sharing the cores; stopped at once on an error,
    Ctrl-C or a closed generator.

    Parameters
    ----------
    factory : callable
        ``factory(*args)`` makes a worker: ``worker(item)``, ``worker.close()``.
    args : tuple
        Its arguments (picklable for other processes).
    jobs : int
        Worker processes.
    """

    def __init__(self, factory, args: tuple, jobs: int):
        super().__init__(factory, args)
        self.jobs = int(jobs)

    def map(self, items):
        """``worker(item)`` for each item, in order, from the worker processes.

        Parameters
        ----------
        items : iterable
            The work, in order.
        """
        items = list(items)
        threads = max(1, (os.cpu_count() or 1) // self.jobs)
        pool = None
        try:
            payload = pickle.dumps((self.factory, self.args))
            context = _WorkerContext()
            ranks = context.Queue()  # (not a shared Value: its memory is a file, which a
            for rank in range(self.jobs):  # full disk refuses before any work)
                ranks.put(rank)
            with _without_main_reimport(), held_interrupts():  # the pool starts its workers
                pool = context.Pool(self.jobs, initializer=_init_worker,
                                    initargs=(payload, threads, ranks))
            chunk = max(1, min(8, len(items) // (4 * self.jobs)))
            for result in pool.imap(_work, items, chunksize=chunk):
                check()
                yield result
            pool.close()
        except BaseException:
            if pool is not None and not terminate(pool):
                pool = None  # (its threads are daemons, left behind; its workers are gone)
            raise
        finally:
            if pool is not None:
                pool.join()
