"""What a batch renders: the mesh files named by paths, folders (searched recursively) and
globs, and the outputs each one gets under the output folder (its path relative to the
inputs' common folder, so a tree of meshes gives a tree of images)."""

from __future__ import annotations

import dataclasses
import glob
import os
from pathlib import Path

from ..errors import UsageError
from ..io.meshes import FORMATS
from ..modes import Outputs

__all__ = ["Task", "find_inputs", "plan", "MESH_SUFFIXES"]

#: the file kinds a folder is searched for (trimesh's formats join when it is installed)
MESH_SUFFIXES = tuple(f".{f}" for f in FORMATS)


@dataclasses.dataclass(frozen=True)
class Task:
    """One input mesh and every file it is rendered to (absolute paths: a cluster's workers
    may start elsewhere)."""

    input: str
    images: tuple[str, ...]  # view-major, then mode
    arrays: tuple[str, ...]  # one .npz per view, when depth/normal/id are asked for

    @property
    def outputs(self) -> tuple[str, ...]:
        return self.images + self.arrays

    def done(self) -> bool:
        return all(os.path.exists(p) for p in self.outputs)


def _suffixes() -> tuple[str, ...]:
    from ..geometry.trimesh_bridge import trimesh_formats

    return MESH_SUFFIXES + tuple(f".{f}" for f in trimesh_formats() if f not in FORMATS)


def find_inputs(specs) -> list[Path]:
    """The mesh files named by ``specs`` (files, folders searched recursively for mesh
    files, and globs), each once, in a stable order. A spec that names nothing is an
    error naming it; a file given by name is kept whatever its extension (its loader will
    say if it is not a mesh)."""
    found: dict[Path, None] = {}
    suffixes = None
    for spec in specs:
        p = Path(spec)
        if p.is_dir():
            suffixes = suffixes or _suffixes()
            hits = sorted(q for q in p.rglob("*") if q.is_file() and
                          q.suffix.lower() in suffixes and not q.name.startswith("."))
        elif p.exists():
            hits = [p]
        elif glob.has_magic(spec):
            hits = sorted(Path(q) for q in glob.glob(spec, recursive=True) if Path(q).is_file())
        else:
            raise UsageError(f"{spec}: no such file or folder")
        if not hits:
            raise UsageError(f"{spec}: no mesh files there" if p.is_dir() else
                             f"{spec}: matches no files")
        for h in hits:
            found.setdefault(h.resolve(), None)
    return list(found)


def plan(inputs: list[Path], outdir, modes, outputs: Outputs, views: int) -> list[Task]:
    """The outputs of each input under ``outdir``: ``REL[.vK].MODE.png`` per view and mode,
    and ``REL[.vK].npz`` (arrays ``depth``, ``normal``, ``face_id`` as asked) per view, where
    REL is the input's path relative to the inputs' common folder without its extension
    (kept where two inputs would otherwise collide, e.g. ``cube.obj`` and ``cube.ply``)."""
    outdir = Path(outdir).resolve()
    if not inputs:
        return []
    root = Path(os.path.commonpath([p.parent for p in inputs]))
    stems = [p.relative_to(root).with_suffix("") for p in inputs]
    clash = {s for s in stems if stems.count(s) > 1}
    tasks = []
    for p, stem in zip(inputs, stems):
        if stem in clash:
            stem = stem.with_name(f"{stem.name}_{p.suffix.lstrip('.').lower()}")
        base = outdir / stem
        tags = [""] if views == 1 else [f".v{k:02d}" for k in range(views)]
        images = tuple(f"{base}{t}.{m}.png" for t in tags for m in modes)
        arrays = tuple(f"{base}{t}.npz" for t in tags) if outputs.auxiliary else ()
        tasks.append(Task(str(p), images, arrays))
    return tasks
