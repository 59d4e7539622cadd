"""Patch data sets in the classic format of Newell's teapot files: the number of patches,
one line per patch with its 16 control-point indices (1-based, commas or spaces), the number
of vertices, then one ``x, y, z`` line per vertex. Bicubic patches, z up in the file."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import GeometryError, InputError
from ..geometry.transforms import y_up_to_z_up, z_up_to_y_up
from .bezier import PatchSet

__all__ = ["read_patches", "parse_patches", "write_patches", "teapot", "EXTENSION"]


def _numbers(line: str, kind, path, number: int, count: int | None = None) -> list:
    parts = line.replace(",", " ").split()
    try:
        values = [kind(p) for p in parts]
    except ValueError:
        raise InputError(f"{path}:{number}: expected {'integers' if kind is int else 'numbers'}"
                         f", got {line.strip()!r}") from None
    if count is not None and len(values) != count:
        raise InputError(f"{path}:{number}: expected {count} values, got {len(values)}")
    return values


def parse_patches(text: str, path: str = "<patches>", up: str = "z") -> PatchSet:
    """The bicubic patches of a file's text (``up``: the file's up axis; glshade's is y).

    Parameters
    ----------
    text : str
        The file's text.
    path : str
        Its name, for errors.
    up : str
        Its up axis.
    """
    lines = [(i + 1, s) for i, s in enumerate(text.splitlines()) if s.strip()]
    if not lines:
        raise InputError(f"{path}: empty")
    it = iter(lines)

    def take(what: str):
        try:
            return next(it)
        except StopIteration:
            raise InputError(f"{path}: ended before {what}") from None

    number, line = take("the patch count")
    (n_patches,) = _numbers(line, int, path, number, 1)
    if n_patches < 1:
        raise InputError(f"{path}:{number}: a patch count must be positive, got {n_patches}")
    index = np.array([_numbers(take(f"patch {k + 1}")[1], int, path, lines[k + 1][0], 16)
                      for k in range(n_patches)])
    number, line = take("the vertex count")
    (n_vertices,) = _numbers(line, int, path, number, 1)
    rows, numbers = [], []
    for k in range(n_vertices):
        number, line = take(f"vertex {k + 1}")
        rows.append(_numbers(line, float, path, number, 3))
        numbers.append(number)
    extra = next(it, None)
    if extra is not None:
        raise InputError(f"{path}:{extra[0]}: unexpected content after the last vertex: "
                         f"{extra[1].strip()[:40]!r}")
    points = np.array(rows, np.float64).reshape(-1, 3)
    if not np.isfinite(points).all():
        k = int(np.argwhere(~np.isfinite(points))[0, 0])
        raise InputError(f"{path}:{numbers[k]}: vertex {k + 1} is not finite")
    bad = (index < 1) | (index > n_vertices)
    if bad.any():
        k = int(np.argwhere(bad)[0, 0])
        raise InputError(f"{path}:{lines[k + 1][0]}: a control-point index is outside 1.."
                         f"{n_vertices}")
    cp = points[index - 1].reshape(-1, 4, 4, 3)
    if up == "z":
        cp = z_up_to_y_up(cp)
    try:
        return PatchSet(cp)
    except GeometryError as exc:  # (patch k of the file: the set's refusal, with the file)
        raise InputError(f"{path}: {exc}") from None


#: the file extension of the classic format (Newell's teapot data, z up)
EXTENSION = ".bpt"


def read_patches(path, up: str = "z") -> PatchSet:
    """The patches of a file in the classic format (errors name the file and line; a path
    that is not a regular file is refused before reading).

    Parameters
    ----------
    path : str or Path
        The file.
    up : str
        Its up axis, ``"z"`` or ``"y"``.
    """
    from .._paths import file_fault

    p = Path(path)
    fault = file_fault(p)
    if fault is not None:
        raise InputError(f"{p}: {fault}")
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"{p}: cannot read: {exc}") from None
    return parse_patches(text, str(p), up)


def write_patches(patches: PatchSet) -> str:
    """Bicubic polynomial patches in the classic format (y up as z up, as the files are).

    Parameters
    ----------
    patches : PatchSet
        Bicubic polynomial patches.
    """
    if patches.degree != (3, 3) or patches.rational:
        raise InputError("the classic patch format holds bicubic polynomial patches only")
    pts = y_up_to_z_up(patches.points)
    flat, index = np.unique(pts.reshape(-1, 3), axis=0, return_inverse=True)
    out = [str(len(patches))]
    out += [",".join(str(int(i) + 1) for i in row) for row in index.reshape(-1, 16)]
    out.append(str(len(flat)))
    out += [",".join(repr(float(x)) for x in p) for p in flat]
    return "\n".join(out) + "\n"


def teapot() -> PatchSet:
    """Newell's teapot: 32 bicubic patches, y up, resting on y = 0, oriented outward (the
    data winds the body one way and the rest the other: :meth:`PatchSurface.oriented`)."""
    from ..geometry.data.teapot import control_nets
    from .surface import PatchSurface

    return PatchSurface(PatchSet(control_nets()), "teapot").oriented().patches
