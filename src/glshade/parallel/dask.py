"""The same work on a Dask cluster (the ``distributed`` extra): a scheduler's address, or
``"local"`` for a :class:`distributed.LocalCluster` on this machine.

Each Dask worker thread builds the job's worker (its renderer, one GL context) on its first
task and keeps it for the job's other tasks, so a context is made once per worker, not per
task; a worker plugin sets Mesa's thread count before any context exists, sharing each
host's cores among the workers on it. The factory and its arguments travel once per worker
(scattered), the items one per task, and each task returns what the worker returns -- file
paths and small records, never pixels. Results come back in item order. A task on a worker
that dies is run again elsewhere (Dask's ``allowed-failures``); an error raised by a task
is raised here, as it was raised there.
"""

from __future__ import annotations

import contextlib
import logging
import os
import threading
import uuid

from ..interrupt import check
from ..errors import ClusterError, InputError
from .executors import Executor

try:
    from distributed import WorkerPlugin
except ImportError:  # the extra is missing: DaskExecutor says how to install it
    WorkerPlugin = object  # type: ignore[misc,assignment]

__all__ = ["DaskExecutor", "connect", "host_of", "INSTALL_HINT"]

INSTALL_HINT = "pip install 'glshade[distributed]'"

_slot = threading.local()  # (job id, worker or the error its factory raised)


def _import_distributed():
    try:
        import distributed
    except ImportError:
        raise ClusterError(f"running on a Dask cluster needs Dask distributed: "
                           f"{INSTALL_HINT} (or use --jobs N for local processes)") from None
    return distributed


@contextlib.contextmanager
def connect(scheduler: str, workers: int | None = None):
    """Yield a Client of the scheduler at ``scheduler`` (``tcp://HOST:PORT``), or of a new
    LocalCluster of ``workers`` single-threaded worker processes for ``"local"``.

    Parameters
    ----------
    scheduler : str
        ``tcp://HOST:PORT`` or ``"local"``.
    workers : int or None
        A local cluster's worker processes.
    """
    distributed = _import_distributed()
    cluster = None
    try:
        if scheduler == "local":
            cluster = distributed.LocalCluster(
                n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                processes=True, dashboard_address=None, silence_logs=logging.ERROR)
            client = distributed.Client(cluster)
        else:
            if "://" not in scheduler:
                raise InputError(f"--scheduler: expected tcp://HOST:PORT or 'local', got "
                                 f"{scheduler!r}")
            client = _client_within(distributed, scheduler, _deadline())
        try:
            yield client
        finally:
            client.close()
    finally:
        if cluster is not None:
            cluster.close()


#: seconds a scheduler has to answer (GLSHADE_SCHEDULER_TIMEOUT overrides)
SCHEDULER_TIMEOUT = 20.0


def _deadline() -> float:
    text = os.environ.get("GLSHADE_SCHEDULER_TIMEOUT", "")
    try:
        value = float(text) if text else SCHEDULER_TIMEOUT
    except ValueError:
        raise InputError(f"GLSHADE_SCHEDULER_TIMEOUT must be a number of seconds, got "
                         f"{text!r}") from None
    if not value > 0:
        raise InputError(f"GLSHADE_SCHEDULER_TIMEOUT must be > 0, got {text!r}")
    return value


def _listening(scheduler: str, seconds: float) -> None:
    """A TCP scheduler's port refused or unreachable is said at once (Dask's Client retries
    a refused connection until its timeout: 20 s for an address where nothing listens);
    other protocols are left to the Client."""
    import socket
    from urllib.parse import urlsplit

    if not scheduler.startswith("tcp://"):
        return
    try:
        place = urlsplit(scheduler)
        host, port = place.hostname, place.port
    except ValueError:
        return  # (the Client says what is wrong with the address)
    if host is None or port is None:
        return
    try:
        socket.create_connection((host, port), timeout=seconds).close()
    except OSError as exc:
        reason = exc.strerror or str(exc) or type(exc).__name__
        raise ClusterError(f"no Dask scheduler answers at {scheduler}: {reason} (is it "
                           "running, and is the address its own?)") from None


def _client_within(distributed, scheduler: str, seconds: float):
    """A Client of ``scheduler`` that has answered (its workers listed) within ``seconds``:
    Client(timeout=) does not bound a scheduler that accepts the connection and never
    answers (stopped, wedged), so the handshake runs in a thread of its own, abandoned at
    the deadline with one line that says so."""
    _listening(scheduler, min(seconds, 5.0))
    box: dict = {}

    def handshake():
        try:
            client = distributed.Client(scheduler, timeout=f"{seconds}s")
            client.scheduler_info()
            box["client"] = client
        except BaseException as exc:  # (reported by the caller, below)
            box["error"] = exc

    thread = threading.Thread(target=handshake, name="glshade-dask-connect", daemon=True)
    thread.start()
    thread.join(seconds)
    if thread.is_alive():
        raise ClusterError(f"the Dask scheduler at {scheduler} did not answer within "
                           f"{seconds:g} s (stopped, wedged or overloaded?); "
                           "GLSHADE_SCHEDULER_TIMEOUT sets the wait")
    error = box.get("error")
    if error is not None:
        if isinstance(error, (OSError, TimeoutError)) or "Timed out" in str(error):
            raise ClusterError(f"cannot reach the Dask scheduler at {scheduler}: "
                               f"{error}") from None
        raise error
    return box["client"]


#: how long, after an interrupt, tasks already running may take to finish (a task cannot be
#: stopped once a worker runs it: its outputs would appear after glshade had reported)
DRAIN_TIMEOUT = 120.0


def _drain(client, futures) -> None:
    """Cancel the tasks no worker has started and wait for those it has (a running task
    cannot be stopped: its outputs would appear after the caller had reported), so that
    what the caller reports next -- a batch's manifest -- sees every output they write.
    Says how many it waits for; a second Ctrl-C stops the wait."""
    import warnings

    import distributed

    try:  # (the tasks the scheduler has handed to workers: running, or next in line)
        busy = {k for keys in client.processing().values() for k in keys}
    except Exception:  # the scheduler went away: nothing more can be learnt or waited for
        return
    started = [f for f in futures if f.key in busy and not f.done()]
    client.cancel([f for f in futures if f.key not in busy])
    if not started:
        return
    warnings.warn(f"waiting for the {len(started)} task(s) already running on the cluster "
                  "to finish (they cannot be stopped; their outputs will be accounted for)",
                  UserWarning, stacklevel=2)
    with contextlib.suppress(Exception):
        distributed.wait(started, timeout=DRAIN_TIMEOUT)


def host_of(address: str) -> str:
    """The host of a worker's address (``tcp://10.0.0.5:4000`` -> ``10.0.0.5``): workers
    on one host share its cores.

    Parameters
    ----------
    address : str
        A worker's address.
    """
    return address.split("://")[-1].rsplit(":", 1)[0]


#: a worker's own GLSHADE_WORKER_DEVICES, as it started (a client's replaces it for a job)
_OWN_DEVICES: dict = {}


class MesaThreads(WorkerPlugin):
    """Worker plugin, before the first GL context: share the host's cores among its Dask
    workers (llvmpipe starts a thread per core in every process otherwise), and number each
    worker among its host's (``GLSHADE_WORKER_RANK``: its turn of the host's devices where
    it has several, :func:`glshade.render.context.worker_devices`; the client's
    ``GLSHADE_WORKER_DEVICES``, if set, is dealt instead).

    Parameters
    ----------
    workers_per_host : dict
        Each host's number of workers.
    ranks : dict
        Each worker's address to its rank (0, 1, ...) among its host's workers.
    devices : list of str or None
        The devices to deal (None: each host's own GPUs).
    """

    idempotent = False
    name = "glshade-mesa-threads"

    def __init__(self, workers_per_host: dict, ranks: dict | None = None,
                 devices: list | None = None):
        self.workers_per_host = workers_per_host
        self.ranks, self.devices = ranks or {}, devices

    def setup(self, worker):
        n = self.workers_per_host.get(host_of(worker.address), 1)
        os.environ.setdefault("LP_NUM_THREADS", str(max(1, (os.cpu_count() or 1) // n)))
        if worker.address in self.ranks:
            os.environ["GLSHADE_WORKER_RANK"] = str(self.ranks[worker.address])
        own = _OWN_DEVICES.setdefault("value", os.environ.get("GLSHADE_WORKER_DEVICES"))
        dealt = ",".join(self.devices) if self.devices else own  # (a later job without
        if dealt:                                                 # the client's: the
            os.environ["GLSHADE_WORKER_DEVICES"] = dealt          # worker's own again)
        else:
            os.environ.pop("GLSHADE_WORKER_DEVICES", None)


def _worker_for(job: str, spec):
    slot = getattr(_slot, "value", None)
    if slot is None or slot[0] != job:
        if slot is not None and not isinstance(slot[1], BaseException):
            with contextlib.suppress(Exception):
                slot[1].close()  # the previous job's renderer, in the thread that made it
        factory, args = spec
        try:
            made = factory(*args)
        except Exception as exc:  # every item of this job reports it, none retries it
            made = exc
        _slot.value = slot = (job, made)
    if isinstance(slot[1], BaseException):
        raise slot[1]
    return slot[1]


def _run(item, spec, job):
    return _worker_for(job, spec)(item)


class DaskExecutor(Executor):
    """The items as Dask tasks on ``scheduler`` (``tcp://HOST:PORT`` or ``"local"``, with
    ``workers`` processes); the first error or Ctrl-C cancels the rest.

    Parameters
    ----------
    factory : callable
        ``factory(*args)`` makes a worker: ``worker(item)``, ``worker.close()``.
    args : tuple
        Its arguments (picklable for other processes).
    scheduler : str
        ``tcp://HOST:PORT`` or ``"local"``.
    workers : int or None
        A local cluster's worker processes.
    """

    def __init__(self, factory, args: tuple, scheduler: str, workers: int | None = None):
        super().__init__(factory, args)
        self.scheduler, self.workers = scheduler, workers
        _import_distributed()  # a missing extra fails before any work
        _listening(scheduler, 5.0)  # ... and an address where nothing listens

    def map(self, items):
        """``worker(item)`` for each item, in order, as tasks on the cluster.

        Parameters
        ----------
        items : iterable
            The work, in order.
        """
        items = list(items)
        with connect(self.scheduler, self.workers) as client:
            info = client.scheduler_info()["workers"]
            if not info:
                client.wait_for_workers(1, timeout=30)
                info = client.scheduler_info()["workers"]
            per_host: dict = {}
            ranks: dict = {}
            for address in sorted(info):
                ranks[address] = per_host.get(host_of(address), 0)
                per_host[host_of(address)] = ranks[address] + 1
            dealt = os.environ.get("GLSHADE_WORKER_DEVICES", "").strip()
            plugin = MesaThreads(per_host, ranks, [x.strip() for x in dealt.split(",")
                                                   if x.strip()] if dealt else None)
            client.register_plugin(plugin, name=plugin.name)
            [spec] = client.scatter([(self.factory, self.args)], broadcast=True, hash=False)
            job = uuid.uuid4().hex
            futures = client.map(_run, items, spec=spec, job=job, pure=False,
                                 key=[f"glshade-{job}-{i}" for i in range(len(items))])
            finished = False
            try:
                for future in futures:
                    check()
                    yield future.result()
                finished = True
            finally:
                if not finished:  # interrupted, or an error: let what runs finish first
                    _drain(client, futures)
                client.cancel(futures)

