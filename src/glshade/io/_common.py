"""What the mesh readers and writers share: building a Mesh with errors that name the
file's line, and writing vertex and face lines in bulk."""

from __future__ import annotations

from typing import NoReturn

import re

import numpy as np

from ..errors import GeometryError, MeshFormatError
from ..geometry.mesh import Mesh

__all__ = ["build_mesh", "offsets_from_sizes", "write_vertices", "write_faces",
           "numeric_diagnose", "no_line", "float_fmt", "join_lines", "COMMENT"]

#: a ``#`` comment to the end of the line (OBJ and OFF)
COMMENT = re.compile(rb"#[^\n]*")


# --------------------------------------------------------------------------- helpers


def no_line(_: int) -> None:
    return None


def build_mesh(path, vertices, indices, offsets, *, line_of_face=no_line,
           line_of_vertex=no_line, **kwargs) -> Mesh:
    """Check indices and sizes here, where the file's line numbers are known."""
    vertices = np.asarray(vertices, np.float64)
    if len(offsets) < 2:
        raise MeshFormatError(path, "the file has no faces")
    bad = ~np.isfinite(vertices).all(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise MeshFormatError(path, f"vertex {i} has a non-finite coordinate "
                              f"{vertices[i].tolist()}", line=line_of_vertex(i))
    sizes = np.diff(offsets)
    small = sizes < 3
    if small.any():
        f = int(np.flatnonzero(small)[0])
        raise MeshFormatError(path, f"face {f} has {int(sizes[f])} vertices; a polygon needs "
                              "at least 3", line=line_of_face(f))
    indices = np.asarray(indices)
    if indices.dtype.kind == "f":  # read as numbers: whole ones only, never truncated
        bad = ~np.isfinite(indices) | (indices != np.round(indices))
        if bad.any():
            c = int(np.flatnonzero(bad)[0])
            f = int(np.searchsorted(offsets, c, side="right") - 1)
            raise MeshFormatError(path, f"face {f} has a non-integer index {indices[c]:g}",
                                  line=line_of_face(f))
        indices = np.where(np.abs(indices) < 2**62, indices, -1.0).astype(np.int64)
    out = (indices < 0) | (indices >= len(vertices))
    if out.any():
        c = int(np.flatnonzero(out)[0])
        f = int(np.searchsorted(offsets, c, side="right") - 1)
        raise MeshFormatError(
            path, f"face {f} refers to vertex {int(indices[c])} (0-based) but the file has "
            f"{len(vertices)} vertices", line=line_of_face(f))
    try:
        return Mesh.from_csr(vertices, indices, offsets, **kwargs)
    except GeometryError as exc:  # anything the checks above missed still names the file
        raise MeshFormatError(path, str(exc)) from None


def offsets_from_sizes(sizes) -> np.ndarray:
    off = np.zeros(len(sizes) + 1, np.int64)
    np.cumsum(sizes, out=off[1:])
    return off


def float_fmt(n: int) -> str:
    return " ".join(["%.17g"] * n)


def write_vertices(f, vertices, prefix: str) -> None:
    if len(vertices):
        f.write(((prefix + float_fmt(3) + "\n") * len(vertices) % tuple(vertices.ravel()))
                .encode())


def write_faces(f, mesh: Mesh, prefix: str, base: int, with_count: bool) -> None:
    """One line per face, any mix of sizes, formatted in C (no loop over faces)."""
    sizes = mesh.face_sizes
    kinds = np.unique(sizes)
    fmt = np.empty(int(kinds.max()) + 1, dtype=object)
    for k in kinds.tolist():
        fmt[k] = prefix + (f"{k} " if with_count else "") + " ".join(["%d"] * k) + "\n"
    text = "".join(fmt[sizes]) % tuple((mesh.face_indices + base).tolist())
    f.write(text.encode())


def numeric_diagnose(path, text, starts, ends, lines, what: str,
                     first_line: int = 1) -> NoReturn:
    for i in lines.tolist():
        for token in text[starts[i]:ends[i]].split():
            try:
                float(token)
            except ValueError:
                raise MeshFormatError(path, f"{what} data: {token.decode(errors='replace')!r} "
                                      "is not a number", line=i + first_line) from None
    raise MeshFormatError(path, f"malformed {what} data")


def join_lines(data: bytes, starts, ends, lines: np.ndarray) -> bytes:
    """The given lines (sorted indices) joined by newlines, one slice per contiguous run."""
    if len(lines) == 0:
        return b""
    brk = np.flatnonzero(np.diff(lines) != 1)
    first = np.concatenate([[0], brk + 1])
    last = np.concatenate([brk, [len(lines) - 1]])
    return b"\n".join(data[starts[lines[a]]:ends[lines[b]]]
                      for a, b in zip(first.tolist(), last.tolist()))
