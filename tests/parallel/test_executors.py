"""The executors behind animate, compare --sweep and batch: results in order, errors as
raised where the work ran, one renderer per worker, and Dask only when asked for."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from glshade.batch import BatchSpec, Task
from glshade.batch.worker import BatchWorker
from glshade.compare.sweeps import icosphere_level, sweep
from glshade.errors import ClusterError, InputError, OutputWriteError
from glshade.geometry import primitives
from glshade.io.meshes import save_mesh
from glshade.parallel import make_executor

from ..conftest import BACKEND, ROOT, glshade

pytestmark = pytest.mark.gl


def _tasks(folder: Path, n: int) -> list[Task]:
    tasks = []
    for i in range(n):
        src = folder / f"s{i}.obj"
        save_mesh(primitives.uv_sphere(4 + i, 8), src)
        tasks.append(Task(str(src), (str(folder / f"s{i}.png"),), ()))
    return tasks


def test_importing_parallel_loads_no_dask():
    code = ("import sys, glshade.parallel, glshade.batch; "
            "sys.exit('distributed' in sys.modules or 'dask' in sys.modules)")
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0


@pytest.mark.parametrize("where", [{"jobs": 1}, {"jobs": 2}, {"scheduler": "cluster"}])
def test_results_come_back_in_item_order(tmp_path, where, request):
    if where.get("scheduler"):
        where = {"scheduler": request.getfixturevalue("dask_cluster").address}
    tasks = _tasks(tmp_path, 7)
    executor = make_executor(BatchWorker, (BatchSpec(size=(32, 32), backend=BACKEND),),
                             items=len(tasks), **where)
    rows = list(executor.map(tasks))
    # sphere i has (4 + i) * 8 faces: the order of the rows is the order of the items
    assert [r.polygons for r in rows] == [(4 + i) * 8 for i in range(7)]
    assert all(os.path.exists(t.images[0]) for t in tasks)


def test_a_task_error_arrives_as_raised(tmp_path, dask_cluster):
    [task] = _tasks(tmp_path, 1)
    blocked = tmp_path / "file"
    blocked.write_text("a file where a folder should be")
    bad = Task(task.input, (str(blocked / "out.png"),), ())
    executor = make_executor(BatchWorker, (BatchSpec(size=(16, 16), backend=BACKEND),),
                             scheduler=dask_cluster.address)
    with pytest.raises(OutputWriteError) as info:
        list(executor.map([bad]))
    assert str(blocked) in str(info.value)


@pytest.mark.filterwarnings("ignore:waiting for the")  # (the drain after the error)
def test_a_worker_that_cannot_start_reports_every_item(dask_cluster):
    executor = make_executor(BatchWorker, (BatchSpec(size=(16, 16), samples=-1,
                                                     backend=BACKEND),),
                             scheduler=dask_cluster.address)
    with pytest.raises(InputError, match="samples"):
        list(executor.map([Task("x.obj", ("x.png",), ())] * 3))


def test_unreachable_scheduler_and_missing_extra(monkeypatch):
    with pytest.raises(InputError, match="tcp://HOST:PORT"):
        list(make_executor(BatchWorker, (BatchSpec(),), scheduler="nowhere").map([1]))
    monkeypatch.setitem(sys.modules, "distributed", None)
    with pytest.raises(ClusterError, match=r"pip install 'glshade\[distributed\]'"):
        make_executor(BatchWorker, (BatchSpec(),), scheduler="local")


def test_animate_on_a_cluster_equals_one_process(tmp_path, dask_cluster):
    scene = "assets/scenes/teapot-orbit.toml"
    base = ["animate", scene, "--frames", "5", "--size", "64x48", "--backend", BACKEND, "-q"]
    one = glshade(*base, "-o", str(tmp_path / "one/"), "--jobs", "1")
    many = glshade(*base, "-o", str(tmp_path / "dask/"), "--scheduler", dask_cluster.address)
    assert one.returncode == many.returncode == 0, many.stderr
    frames = sorted(p.name for p in (tmp_path / "one").iterdir())
    assert len(frames) == 5
    for name in frames:
        assert (tmp_path / "one" / name).read_bytes() == (tmp_path / "dask" / name).read_bytes()
    assert [p.name for p in tmp_path.iterdir() if ".part" in p.name] == []  # spool removed
    assert not (ROOT / "frames").exists()


def test_sweep_in_worker_processes_equals_one_process():
    kw = dict(modes=("flat", "phong"), size=(48, 48), backend=BACKEND)
    serial = sweep(icosphere_level, [0, 1, 2], **kw)
    pooled = sweep(icosphere_level, [0, 1, 2], jobs=2, **kw)
    assert [r["faces"] for r in pooled] == [20, 80, 320]
    for a, b in zip(serial, pooled):
        assert a["flat"].mean_abs == b["flat"].mean_abs
        assert a["phong"].mean_abs == b["phong"].mean_abs
    assert np.all(np.diff([r["flat"].mean_abs for r in pooled]) < 0)  # finer is closer


def test_mesa_threads_share_the_cores(dask_cluster):
    from distributed import Client

    from glshade.parallel.dask import MesaThreads, host_of

    with Client(dask_cluster.address, timeout="30s") as client:
        workers = list(client.scheduler_info()["workers"])
        plugin = MesaThreads({host_of(workers[0]): len(workers)})
        client.register_plugin(plugin, name=plugin.name)
        got = client.run(lambda: os.environ.get("LP_NUM_THREADS"))
    expected = str(max(1, (os.cpu_count() or 1) // len(workers)))
    assert set(got.values()) == {expected}


_START_WITH_CTRL_C = """
import multiprocessing as mp, os, signal, sys
from glshade.parallel import make_executor
from tests.parallel.workers import SignalMaskWorker
if sys.argv[1] == "interrupt":  # Ctrl-C lands while the pool launches its first worker
    launch = mp.context.SpawnProcess._Popen
    def interrupted(process_obj):
        os.kill(os.getpid(), signal.SIGINT)
        return launch(process_obj)
    mp.context.SpawnProcess._Popen = staticmethod(interrupted)
try:
    print(list(make_executor(SignalMaskWorker, (), jobs=2).map(range(4))))
except KeyboardInterrupt:
    print("interrupted", len(mp.active_children()))
"""


def test_ctrl_c_while_workers_start_stops_the_pool():
    """A Ctrl-C that lands while a worker is being launched is held, not ignored, and stops
    the pool once it exists; the workers themselves start with Ctrl-C blocked."""
    def run(mode):
        done = subprocess.run([sys.executable, "-c", _START_WITH_CTRL_C, mode], cwd=ROOT,
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr
        return done.stdout.strip()

    assert run("interrupt") == "interrupted 0"
    assert run("plain") == str([(i, True, True) for i in range(4)])


_UNLOADABLE = """
from glshade.parallel import make_executor
from tests.parallel.workers import SignalMaskWorker

class OnlyHere:  # (defined in this script: a worker process cannot load it)
    pass

try:
    list(make_executor(SignalMaskWorker, (OnlyHere(),), jobs=2).map(range(4)))
except Exception as exc:
    print(type(exc).__name__, "OnlyHere" in str(exc))
"""


def test_a_factory_the_workers_cannot_load_is_an_error_not_a_hang():
    done = subprocess.run([sys.executable, "-c", _UNLOADABLE], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)
    assert done.stdout.strip() == "AttributeError True", done.stdout + done.stderr


def test_a_pool_whose_stop_hangs_is_left_behind_with_its_workers_killed():
    """Pool.terminate can wait forever on a half-written message; the stop is bounded and
    the workers are killed instead (a stand-in pool, so the hang is certain)."""
    import threading
    import time

    from glshade.parallel.executors import terminate

    class Worker:
        killed = False

        def kill(self):
            self.killed = True

    class HangingPool:
        _pool = [Worker(), Worker()]

        def terminate(self):
            threading.Event().wait()  # (forever)

    pool = HangingPool()
    t0 = time.perf_counter()
    assert terminate(pool, timeout=0.3) is False
    assert time.perf_counter() - t0 < 2 and all(w.killed for w in pool._pool)

    class QuickPool:
        _pool: list = []

        def terminate(self):
            pass

    assert terminate(QuickPool(), timeout=5) is True
