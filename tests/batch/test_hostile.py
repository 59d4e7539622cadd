"""Hostile layouts for glshade batch: outputs never leave OUTDIR (symlinks in it, a
property test over random layouts), globs through link loops end, file names that are not
UTF-8 or too long fail alone, names differing only in case keep their own outputs, and a
run refused up front writes nothing."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from glshade.batch import BatchSpec, batch, find_inputs, plan
from glshade.errors import ClusterError, OptionError, UsageError
from glshade.geometry import primitives
from glshade.io.meshes import save_mesh
from glshade.modes import Outputs

from ..conftest import BACKEND

pytestmark = pytest.mark.gl

SPEC = BatchSpec(size=(16, 16), samples=0, backend=BACKEND)


def _files(folder: Path) -> set:
    return {p.relative_to(folder) for p in folder.rglob("*") if p.is_file()}


@pytest.mark.parametrize("seed", range(6))
def test_no_output_is_ever_written_outside_outdir(tmp_path, seed):
    """Random trees of meshes, and an OUTDIR holding links (to folders outside it, to
    folders inside it, nested) where the mirrored outputs go: every file the run writes is
    inside OUTDIR (the outside folder is untouched), and an input whose output would go
    through a link out of OUTDIR is an error row naming the link."""
    rng = np.random.default_rng(seed)
    src, out, elsewhere = tmp_path / "src", tmp_path / "out", tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "keep.txt").write_text("mine")
    names = []
    for k in range(int(rng.integers(3, 7))):
        depth = int(rng.integers(0, 3))
        folder = src.joinpath(*[f"d{int(rng.integers(0, 3))}" for _ in range(depth)])
        folder.mkdir(parents=True, exist_ok=True)
        names.append(folder / f"m{k}.obj")
        save_mesh(primitives.cube(), names[-1])
    out.mkdir()
    (out / "inside").mkdir()
    links = {}
    for d in {p.parent.relative_to(src) for p in names if p.parent != src}:
        where = out / d
        where.parent.mkdir(parents=True, exist_ok=True)
        if not where.exists() and rng.random() < 0.6:
            target = elsewhere if rng.random() < 0.6 else out / "inside"
            where.symlink_to(target, target_is_directory=True)
            links[where] = target
    before = _files(elsewhere)
    result = batch([str(src)], out, SPEC, overwrite=True)
    assert _files(elsewhere) == before  # nothing written outside OUTDIR
    for row in result.rows:
        rel = Path(row.input).resolve().relative_to(src.resolve()).parent
        leaves = any(out / rel == link or (out / rel).is_relative_to(link)
                     for link, t in links.items() if t == elsewhere)
        if leaves:
            assert row.status == "error" and "outside the output folder" in row.message
        else:
            assert row.status == "ok", row.message
            for o in row.outputs:
                real = Path(os.path.realpath(o))
                assert real.is_relative_to(out.resolve()), o


def test_a_recursive_glob_through_a_link_loop_ends(tmp_path):
    t = tmp_path / "t"
    (t / "a" / "b").mkdir(parents=True)
    save_mesh(primitives.cube(), t / "a" / "b" / "x.obj")
    save_mesh(primitives.cube(), t / "top.obj")
    (t / "a" / "b" / "loop").symlink_to(t, target_is_directory=True)  # t/a/b/loop -> t
    (t / "a" / "self").symlink_to(t / "a", target_is_directory=True)
    out = subprocess.run([sys.executable, "-c", "import sys; from glshade.batch import "
                          "find_inputs; print(len(find_inputs([sys.argv[1]])))",
                          str(t / "**" / "*.obj")], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "2"
    assert len(find_inputs([str(t)])) == 2  # (a folder input: the same rule)


def test_names_that_are_not_utf8_or_too_long_fail_alone(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    save_mesh(primitives.cube(), src / "good.obj")
    odd = os.fsdecode(b"caf\xe9.obj")  # latin-1 bytes: not UTF-8
    save_mesh(primitives.cube(), src / odd)
    long = "x" * 246 + ".obj"  # the input fits (250 bytes); x...x.phong.png (256) does not
    (src / long).write_text((src / "good.obj").read_text())
    result = batch([str(src)], tmp_path / "out", SPEC)
    by = {Path(r.input).name: r for r in result.rows}
    assert by["good.obj"].status == "ok" and by[odd].status == "ok"
    assert by[long].status == "error" and "bytes, more than the 255" in by[long].message
    again = batch([str(src)], tmp_path / "out", SPEC)  # the manifest reads back: a resume
    assert {Path(r.input).name: r.status for r in again.rows}[odd] == "exists"


def test_names_that_differ_only_in_case_keep_their_own_outputs(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    save_mesh(primitives.cube(), src / "cube.obj")
    save_mesh(primitives.icosphere(1), src / "cube.OBJ")
    save_mesh(primitives.torus(), src / "Cube.obj")
    tasks = plan(find_inputs([str(src)]), tmp_path / "out", ("phong",), Outputs.COLOR, 1)
    images = [t.images[0].casefold() for t in tasks]
    assert len(set(images)) == 3, images  # distinct even on a case-insensitive disk
    result = batch([str(src)], tmp_path / "out", SPEC)
    assert [r.status for r in result.rows] == ["ok"] * 3
    from PIL import Image

    pictures = {np.asarray(Image.open(p)).tobytes() for r in result.rows for p in r.outputs}
    assert len(pictures) == 3  # three different meshes, three different pictures


def test_a_run_refused_up_front_writes_nothing(tmp_path, monkeypatch):
    src = tmp_path / "src"
    src.mkdir()
    save_mesh(primitives.cube(), src / "a.obj")
    out = tmp_path / "out"
    with pytest.raises(OptionError, match="samples"):
        batch([str(src)], out, BatchSpec(size=(16, 16), samples=3, backend=BACKEND))
    import glshade.parallel.dask as dask_module

    def missing():
        raise ClusterError("running on a Dask cluster needs Dask distributed")

    monkeypatch.setattr(dask_module, "_import_distributed", missing)  # (the extra missing)
    with pytest.raises(ClusterError):
        batch([str(src)], out, SPEC, scheduler="tcp://127.0.0.1:8786")
    assert not out.exists()
    with pytest.raises(UsageError, match="output folder must be named"):
        batch([str(src)], "", SPEC)
    r = subprocess.run([sys.executable, "-m", "glshade", "batch", str(src), "-o", ""],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "src"][1:]  # (no manifest)
