"""A laptop's process model: macOS and Windows have no ``fork`` for Python's pools (macOS
defaults to spawn, Windows has nothing else). A process pool's batch and a Dask batch run
in a process where ``os.fork`` raises and the start method is ``spawn`` -- on a pool of
two, a Dask cluster of workers and a local Dask cluster (whose nannies start their
workers) -- and give the same bytes."""

import hashlib
import subprocess
import sys

import pytest

from tests.conftest import BACKEND, ROOT

pytestmark = [pytest.mark.gl, pytest.mark.once]

_NO_FORK = """
import multiprocessing, os, sys
def _no_fork(*a, **k):
    raise AssertionError("fork called: macOS and Windows have none for Python's pools")
os.fork = os.forkpty = _no_fork
multiprocessing.set_start_method("spawn", force=True)
from glshade.cli import main
sys.exit(main(sys.argv[1:]))
"""


def _batch(out, *extra):
    args = ["batch", str(ROOT / "assets" / "teapot.obj"), str(ROOT / "assets" / "torus.off"),
            "-o", str(out), "--size", "48x36", "--modes", "flat,phong", "--backend", BACKEND,
            *extra]
    return subprocess.run([sys.executable, "-c", _NO_FORK, *args], capture_output=True,
                          text=True, timeout=300, cwd=ROOT)


def _pictures(folder) -> dict:
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*.png"))}


def test_a_spawned_pool_and_a_dask_batch_need_no_fork(tmp_path, dask_cluster):
    pool = _batch(tmp_path / "pool", "--jobs", "2")
    assert pool.returncode == 0, pool.stderr
    dask = _batch(tmp_path / "dask", "--scheduler", dask_cluster.address)
    assert dask.returncode == 0, dask.stderr
    # (a cluster of this machine's own: Dask's nannies start their workers by spawn)
    local = _batch(tmp_path / "local", "--scheduler", "local", "--jobs", "2")
    assert local.returncode == 0, local.stderr
    first = _pictures(tmp_path / "pool")
    assert len(first) == 4
    for run in ("dask", "local"):
        assert _pictures(tmp_path / run) == first, run
    assert "fork called" not in pool.stderr + dask.stderr + local.stderr
