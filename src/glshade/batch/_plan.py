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
#: what a folder input is searched for: mesh files and patch files (the classic .bpt)
MESH_SUFFIXES = tuple(f".{f}" for f in FORMATS) + (".bpt",)


@dataclasses.dataclass(frozen=True)
class Task:
    """One input mesh and every file it is rendered to (absolute paths: a cluster's workers
    may start elsewhere)."""

    input: str
    images: tuple[str, ...]  # view-major, then mode
    arrays: tuple[str, ...]  # one .npz per view, when depth/normal/id are asked for
    root: str = ""           # the output folder (resolved): nothing is written outside it

    @property
    def outputs(self) -> tuple[str, ...]:
        return self.images + self.arrays

    def done(self) -> bool:
        """Whether every output is there and whole (a torn one is made again)."""
        from ..atomic import is_whole

        return all(is_whole(p) for p in self.outputs)

    def fault(self) -> str | None:
        """Why this task's outputs cannot be written where planned, or None: a name longer
        than the file system takes, or a link that leads out of the output folder."""
        for p in self.outputs:
            name = os.fsencode(os.path.basename(p))
            limit = _name_max(os.path.dirname(p))
            if len(name) > limit:
                return (f"its output name {os.path.basename(p)!r} is {len(name)} bytes, more "
                        f"than the {limit} this file system allows")
            if self.root:
                link = escapes(p, self.root)
                if link is not None:
                    return (f"its output {p} would be written outside the output folder "
                            f"{self.root}, through the link {link}")
        return None


def _name_max(folder: str) -> int:
    while folder and not os.path.isdir(folder):
        folder = os.path.dirname(folder)
    try:
        return os.pathconf(folder or ".", "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        return 255


def escapes(path: str, root: str) -> str | None:
    """The link through which ``path`` would leave the folder ``root`` (a symlink that
    exists on the way, pointing elsewhere), or None when it stays inside."""
    real_root = os.path.realpath(root)
    rel = os.path.relpath(os.path.abspath(path), os.path.abspath(root))
    if rel == os.pardir or rel.startswith(os.pardir + os.sep):
        return path
    here = os.path.abspath(root)
    for part in Path(rel).parts[:-1]:
        here = os.path.join(here, part)
        if os.path.islink(here):
            target = os.path.realpath(here)
            if not (target == real_root or target.startswith(real_root + os.sep)):
                return here
    return None


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
            hits = sorted(_glob(spec))
        else:
            raise UsageError(f"{spec}: no such file or folder")
        if not hits:
            raise UsageError(f"{spec}: no mesh files there" if p.is_dir() else
                             f"{spec}: matches no files")
        for h in hits:
            found.setdefault(h.resolve(), None)
    return list(found)


def _glob(spec: str) -> list[Path]:
    """The files a glob names, ``**`` for any folders between, walking the tree without
    following links to folders (as folder inputs are searched): a link loop cannot hang it."""
    import fnmatch

    parts = Path(spec).parts
    fixed = next((i for i, part in enumerate(parts) if glob.has_magic(part)), len(parts))
    root = Path(*parts[:fixed]) if fixed else Path(".")
    pattern = parts[fixed:]
    if "**" not in pattern:  # (no recursion: the standard module cannot loop)
        return [Path(q) for q in glob.glob(spec) if Path(q).is_file()]

    def match(names, pats) -> bool:
        if not pats:
            return not names
        if pats[0] == "**":
            return any(match(names[k:], pats[1:]) for k in range(len(names) + 1))
        return bool(names) and fnmatch.fnmatchcase(names[0], pats[0]) and \
            match(names[1:], pats[1:])

    found = []
    for folder, dirs, files in os.walk(root, followlinks=False):
        dirs.sort()
        rel = Path(folder).relative_to(root).parts
        for name in sorted(files):
            if not name.startswith(".") and match((*rel, name), pattern):
                q = Path(folder) / name
                if q.is_file():
                    found.append(q)
    return found


def plan(inputs: list[Path], outdir, modes, outputs: Outputs, views: int) -> list[Task]:
    """The outputs of each input under ``outdir``: ``REL[.vK].MODE.png`` per view and mode,
    and ``REL[.vK].npz`` (arrays ``depth``, ``normal``, ``face_id`` as asked) per view, where
    REL is the input's path relative to the inputs' common folder without its extension
    (kept where two inputs would otherwise collide, e.g. ``cube.obj`` and ``cube.ply``;
    names that still collide, even only in case as ``cube.obj`` and ``cube.OBJ`` do on a
    case-insensitive file system, get ``-2``, ``-3`` ... in input order): no two inputs
    share an output."""
    if str(outdir).strip() == "":
        raise UsageError("the output folder must be named (got an empty name)")
    outdir = Path(outdir).absolute()
    if not inputs:
        return []
    root = Path(os.path.commonpath([p.parent for p in inputs]))
    stems = [p.relative_to(root).with_suffix("") for p in inputs]
    clash = {s for s in stems if stems.count(s) > 1}
    tasks, taken = [], set()
    for p, stem in zip(inputs, stems):
        if stem in clash:
            stem = stem.with_name(f"{stem.name}_{p.suffix.lstrip('.')}")
        unique, k = stem, 1
        while str(unique).casefold() in taken:
            k += 1
            unique = stem.with_name(f"{stem.name}-{k}")
        taken.add(str(unique).casefold())
        base = outdir / unique
        tags = [""] if views == 1 else [f".v{k:02d}" for k in range(views)]
        images = tuple(f"{base}{t}.{m}.png" for t in tags for m in modes)
        arrays = tuple(f"{base}{t}.npz" for t in tags) if outputs.auxiliary else ()
        tasks.append(Task(str(p), images, arrays, str(outdir)))
    return tasks
