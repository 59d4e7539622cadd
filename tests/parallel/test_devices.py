"""Each worker its own device: a pool numbers its workers (local processes, or a Dask
cluster's by rank on their host: GLSHADE_WORKER_RANK) and each one's context takes its turn
of the devices -- GLSHADE_WORKER_DEVICES, else the GPUs CUDA shows or EGL lists where there
are several. On this machine EGL lists one software device, named two ways ("0",
"llvmpipe"), so the dealing is seen by name."""

import os
from collections import defaultdict

import pytest

from glshade.errors import OptionError
from glshade.parallel import make_executor
from glshade.render.context import chosen_device, egl_devices, worker_devices

pytestmark = pytest.mark.gl


def test_what_is_dealt(monkeypatch):
    for name in ("GLSHADE_WORKER_DEVICES", "GLSHADE_EGL_DEVICE", "GLSHADE_WORKER_RANK"):
        monkeypatch.delenv(name, raising=False)
    gpus = [d for d in egl_devices() if not d["software"]]
    # here: no GPU, or one -- nothing to deal, each worker takes what a render would
    assert worker_devices() == ([str(d["index"]) for d in gpus] if len(gpus) > 1 else [])
    assert chosen_device()[1] == "the driver's first"
    monkeypatch.setenv("GLSHADE_WORKER_DEVICES", " 0, llvmpipe ,cuda:1 ")
    assert worker_devices() == ["0", "llvmpipe", "cuda:1"]
    assert chosen_device()[1] == "the driver's first"  # (not a pool's worker)
    whys = []
    for rank in range(5):
        monkeypatch.setenv("GLSHADE_WORKER_RANK", str(rank))
        if rank % 3 == 2:
            with pytest.raises(OptionError, match="^GLSHADE_WORKER_DEVICES: cuda:1 "):
                chosen_device()
        else:
            index, why = chosen_device()
            assert index == 0
            whys.append(why.rsplit(": ", 1)[1])
    assert whys == ["0", "llvmpipe", "0", "llvmpipe"]
    monkeypatch.setenv("GLSHADE_EGL_DEVICE", "0")  # (one device asked for: every worker's)
    assert chosen_device()[1] == "GLSHADE_EGL_DEVICE"


def test_local_workers_are_dealt_a_device_each(monkeypatch):
    from tests.parallel.workers import DeviceWorker

    monkeypatch.delenv("GLSHADE_EGL_DEVICE", raising=False)
    monkeypatch.setenv("GLSHADE_WORKER_DEVICES", "0,llvmpipe")
    seen = defaultdict(set)
    for pid, device, why in make_executor(DeviceWorker, (), jobs=2).map(range(8)):
        seen[pid].add((device, why))
    assert len(seen) == 2  # (both workers took items)
    assert sorted(why.rsplit(": ", 1)[1] for ds in seen.values() for _, why in ds) == \
        ["0", "llvmpipe"]


def test_a_bad_worker_device_is_one_line(monkeypatch):
    from tests.parallel.workers import DeviceWorker

    monkeypatch.setenv("GLSHADE_WORKER_DEVICES", "7,0")
    with pytest.raises(OptionError, match=r"^GLSHADE_WORKER_DEVICES: EGL device 7 does "
                                          r"not exist; present: 0: "):
        list(make_executor(DeviceWorker, (), jobs=2).map(range(4)))


def test_dask_workers_are_dealt_a_device_each(tmp_path, dask_cluster, monkeypatch):
    """A cluster's workers, by rank on their host, each set their own device before the
    job's renderers are made -- and the job draws on them."""
    from distributed import Client

    from glshade.batch import BatchSpec, Task
    from glshade.batch.worker import BatchWorker
    from glshade.geometry import primitives
    from glshade.io.meshes import save_mesh

    monkeypatch.setenv("GLSHADE_WORKER_DEVICES", "llvmpipe,0")
    save_mesh(primitives.cube(), tmp_path / "cube.obj")
    tasks = [Task(str(tmp_path / "cube.obj"), (str(tmp_path / f"{i}.png"),), ())
             for i in range(4)]
    try:
        rows = list(make_executor(BatchWorker, (BatchSpec(size=(16, 16)),),
                                  scheduler=dask_cluster.address).map(tasks))
        assert [r.polygons for r in rows] == [6] * 4
        with Client(dask_cluster.address, timeout="30s") as client:
            got = client.run(lambda: __import__(  # (a lambda travels by value)
                "glshade.render.context", fromlist=["chosen_device"]).chosen_device()[1])
        assert sorted(why.rsplit(": ", 1)[1] for why in got.values()) == ["0", "llvmpipe"]
    finally:  # (the cluster serves the rest of the run: its workers as they were)
        with Client(dask_cluster.address, timeout="30s") as client:
            client.run(lambda: [os.environ.pop(name, None) for name in
                                ("GLSHADE_WORKER_DEVICES", "GLSHADE_WORKER_RANK")])
