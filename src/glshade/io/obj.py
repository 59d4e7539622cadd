"""Wavefront OBJ: polygons (``f`` lines with ``v/vt/vn`` references), groups and objects; other
keywords are skipped."""

from __future__ import annotations

from typing import Any

import re
from pathlib import Path

import numpy as np

from ..errors import MeshFormatError
from ..geometry.mesh import Mesh
from ._common import COMMENT, build_mesh, join_lines, offsets_from_sizes, write_vertices
from .text import (
    line_starts, normalize_whitespace, parse_decimals, parse_numbers, ragged_take, token_counts,
)

__all__ = ["read", "read_points", "write"]

_OBJ_KEYWORDS = {
    b"v", b"vt", b"vn", b"vp", b"f", b"l", b"p", b"o", b"g", b"s", b"mg", b"usemtl",
    b"mtllib", b"cstype", b"deg", b"bmat", b"step", b"curv", b"curv2", b"surf", b"parm",
    b"trim", b"hole", b"scrv", b"sp", b"end", b"con", b"lod", b"usemap", b"maplib",
    b"shadow_obj", b"trace_obj", b"ctech", b"stech", b"bevel", b"c_interp", b"d_interp",
    b"call", b"csh",
}
_SLASH_TAIL = re.compile(rb"/\S*")


def _blank_keyword(blob: bytes, keyword: bytes) -> bytes:
    """Replace the one-letter keyword starting every line by a space."""
    return (b" " + blob[1:]).replace(b"\n" + keyword, b"\n ")


def _obj_diagnose(path, data: bytes) -> None:
    """Slow line-by-line check, run only when the fast parse failed: raises at the first
    bad line."""
    n_vertices = 0
    for number, raw in enumerate(data.split(b"\n"), start=1):
        tokens = raw.split(b"#", 1)[0].split()
        if not tokens:
            continue
        key, args = tokens[0], tokens[1:]
        text = raw.strip().decode("utf-8", "replace")
        if key == b"v":
            if len(args) not in (3, 4, 6, 7):
                raise MeshFormatError(path, f"a vertex needs 3 coordinates, got {len(args)}: "
                                      f"{text!r}", line=number)
            try:
                [float(a) for a in args]
            except ValueError:
                raise MeshFormatError(path, f"vertex coordinate is not a number: {text!r}",
                                      line=number) from None
            n_vertices += 1
        elif key == b"f":
            if len(args) < 3:
                raise MeshFormatError(path, f"a face needs at least 3 vertices, got "
                                      f"{len(args)}: {text!r}", line=number)
            for a in args:
                head = a.split(b"/")[0]
                try:
                    i = int(head)
                except ValueError:
                    raise MeshFormatError(path, f"face index {a.decode(errors='replace')!r} is"
                                          f" not an integer: {text!r}", line=number) from None
                if i == 0:
                    raise MeshFormatError(path, "face index 0: OBJ indices start at 1",
                                          line=number)
                if i > n_vertices or -i > n_vertices:
                    raise MeshFormatError(path, f"face index {i} but only {n_vertices} vertices"
                                          " are defined before this line", line=number)
        elif key not in _OBJ_KEYWORDS:
            raise MeshFormatError(path, f"unknown statement {key.decode(errors='replace')!r}",
                                  line=number)


def read(path, data: bytes) -> Mesh:
    """The Mesh in OBJ bytes ``data`` (``path`` names it in errors: file and line).

    Parameters
    ----------
    path : str or Path
        The file, named in errors.
    data : bytes
        Its contents.
    """
    data = _clean(path, data)
    starts, ends, b0, b1 = _line_heads(data)
    one = (ends - starts == 1) | (b1 == 32)
    is_v = (b0 == ord("v")) & one
    is_f = (b0 == ord("f")) & one
    b0 = np.where(ends > starts, b0, 10)
    skip = (b0 == 10) | (b0 == ord("#")) | (
        (b0 == ord("v")) & ((b1 == ord("n")) | (b1 == ord("t")) | (b1 == ord("p"))))
    is_vt = (b0 == ord("v")) & (b1 == ord("t"))
    parts: dict[bytes, tuple[list, list]] = {b"g": ([], []), b"usemtl": ([], []),
                                             b"mtllib": ([], [])}
    for i in np.flatnonzero(~(is_v | is_f | skip)).tolist():
        line = data[starts[i]:ends[i]].split(b"#", 1)[0].split()
        if not line:
            continue
        if line[0] not in _OBJ_KEYWORDS:
            _obj_diagnose(path, data)
        key = b"g" if line[0] == b"o" else line[0]
        if key in parts:
            parts[key][0].append(i)
            parts[key][1].append(b" ".join(line[1:]).decode("utf-8", "replace") or "default")
    v_lines, f_lines = np.flatnonzero(is_v), np.flatnonzero(is_f)
    vertices, colors = _vertices(path, data, starts, ends, v_lines)
    idx, sizes = _faces(path, data, starts, ends, f_lines, v_lines, len(vertices))
    uv = _texture_coordinates(path, data, starts, ends, np.flatnonzero(is_vt), f_lines, sizes) \
        if is_vt.any() else None
    mesh = build_mesh(path, vertices, idx, offsets_from_sizes(sizes),
                      line_of_face=lambda f: int(f_lines[f]) + 1,
                      line_of_vertex=lambda i: int(v_lines[i]) + 1,
                      groups=_named_parts(*parts[b"g"], f_lines), uv=uv, colors=colors)
    if parts[b"usemtl"][0]:
        mesh.material_groups = _named_parts(*parts[b"usemtl"], f_lines)
        mesh.materials, mesh.material_notes = _materials(
            path, parts[b"mtllib"], mesh.material_groups, parts[b"usemtl"])
    return mesh


def _named_parts(lines: list, names: list, f_lines: np.ndarray) -> dict[str, np.ndarray]:
    """The faces after each of ``lines`` (until the next), by the names given there."""
    groups: dict[str, Any] = {}
    if lines:
        owner = np.searchsorted(np.asarray(lines), f_lines) - 1
        for g, name in enumerate(names):
            members = np.flatnonzero(owner == g)
            if len(members):
                groups[name] = np.concatenate([groups[name], members]) if name in groups \
                    else members
    return groups


def _materials(path, mtllib: tuple, used: dict, usemtl: tuple) -> tuple[dict, list]:
    """The materials ``usemtl`` names, read from the ``mtllib`` files beside the OBJ; a
    missing library or material is a warning naming the OBJ line (its faces are drawn
    with the default material)."""
    import warnings

    from .mtl import MaterialLibrary, read_mtl

    library = MaterialLibrary()
    read = 0
    for line, names in zip(*mtllib):
        for name in names.split():
            file = Path(path).parent / name
            if not file.is_file():
                warnings.warn(f"{Path(path).name}:{line + 1}: material library {name!r} not "
                              f"found beside the OBJ; its materials are drawn with defaults",
                              UserWarning, stacklevel=4)
                continue
            read_mtl(file, library=library)
            read += 1
    missing = {}
    for line, name in zip(*usemtl):
        if name in used and name not in library.materials and name not in missing:
            missing[name] = line + 1
    for name, line in missing.items():
        if read:  # (without a library read, the warning above said it, or there is none)
            warnings.warn(f"{Path(path).name}:{line}: material {name!r} is in no material "
                          "library; drawn with the default material", UserWarning,
                          stacklevel=4)
    return ({name: m for name, m in library.materials.items() if name in used},
            library.unused)


def _texture_coordinates(path, data: bytes, starts, ends, vt_lines, f_lines, sizes):
    """Each face corner's ``vt`` (C, 2) -- (0, 0) where a corner names none."""
    blob = join_lines(data, starts, ends, vt_lines)
    counts = token_counts(normalize_whitespace(blob), len(vt_lines)) - 1
    values = parse_numbers(blob.replace(b"vt", b"  "))
    if values is None or (counts < 1).any() or (counts > 3).any() or \
            counts.sum() != len(values):
        bad = int(np.flatnonzero((counts < 1) | (counts > 3))[0]) if ((counts < 1) |
                                                                        (counts > 3)).any() else 0
        raise MeshFormatError(path, "a texture coordinate (vt) needs 1 to 3 numbers",
                              line=int(vt_lines[bad]) + 1)
    first = offsets_from_sizes(counts)[:-1]
    if not np.isfinite(values).all():
        bad = int(np.searchsorted(first, int(np.flatnonzero(~np.isfinite(values))[0]),
                                  side="right") - 1)
        raise MeshFormatError(path, "a texture coordinate (vt) is not finite",
                              line=int(vt_lines[bad]) + 1)
    table = np.zeros((len(vt_lines), 2))
    table[:, 0] = values[first]
    two = counts >= 2
    table[two, 1] = values[first[two] + 1]
    fblob = _blank_keyword(join_lines(data, starts, ends, f_lines), b"f")
    n = int(sizes.sum())
    corner_vt = np.zeros(n, np.int64)
    if b"/" in fblob:
        fields = parse_numbers(fblob.replace(b"//", b"/0/").replace(b"/", b" "), np.int64)
        for k in (2, 3):
            if fields is not None and len(fields) == k * n:
                corner_vt = fields.reshape(n, k)[:, 1]
                break
        else:
            corner_vt = _corner_vt_slow(path, data, starts, ends, f_lines, n)
    vt_before = np.repeat(np.searchsorted(vt_lines, f_lines), sizes)
    index = np.where(corner_vt < 0, corner_vt + vt_before, corner_vt - 1)
    bad = (corner_vt != 0) & ((index < 0) | (index >= len(vt_lines)))
    if bad.any():
        c = int(np.flatnonzero(bad)[0])
        f = int(np.searchsorted(offsets_from_sizes(sizes), c, side="right") - 1)
        raise MeshFormatError(path, f"texture coordinate index {int(corner_vt[c])} is out of "
                              f"range: the file defines {len(vt_lines)}",
                              line=int(f_lines[f]) + 1)
    return np.where((corner_vt != 0)[:, None], table[np.clip(index, 0, None)], 0.0)


def _corner_vt_slow(path, data: bytes, starts, ends, f_lines, n: int) -> np.ndarray:
    """Corners' vt indices where faces mix ``v``, ``v/vt`` and ``v/vt/vn`` forms (a line
    at a time: the bulk parse found them uneven)."""
    out = np.zeros(n, np.int64)
    c = 0
    for i in f_lines.tolist():
        for token in data[starts[i]:ends[i]].split()[1:]:
            fields = token.split(b"/")
            if len(fields) > 1 and fields[1]:
                try:
                    out[c] = int(fields[1])
                except ValueError:
                    raise MeshFormatError(path, "a texture coordinate index is not an "
                                          f"integer: {token.decode(errors='replace')!r}",
                                          line=i + 1) from None
            c += 1
    return out


def _clean(path, data: bytes) -> bytes:
    """OBJ bytes with one space between tokens, one newline between lines, no comments
    after data; binary data refused."""
    if b"\0" in data[:4096]:
        raise MeshFormatError(path, "binary data in a text OBJ file", byte=data.index(b"\0"))
    lead = data[:1] in (b" ", b"\t")
    if lead or b"\r" in data or b"\t" in data or b"\n " in data:
        data = normalize_whitespace(data)
    if b"#" in data:
        arr = np.frombuffer(data, np.uint8)
        hashes = np.flatnonzero(arr == ord("#"))
        inline = hashes[hashes > 0]
        if (arr[inline - 1] != 10).any():  # a comment after data: cut it off
            data = normalize_whitespace(COMMENT.sub(b"", data))
    return data


def _line_heads(data: bytes):
    """Each line's start and end, and its first two bytes (a newline for none): what
    tells a ``v`` line from a ``vt``, an ``f`` from an ``fo``."""
    starts, ends = line_starts(data)
    arr = np.frombuffer(data, np.uint8)
    b0 = arr[starts]
    b1 = np.where(ends - starts > 1, arr[np.minimum(starts + 1, len(arr) - 1)], 10)
    return starts, ends, b0, b1


def read_points(path, data: bytes) -> dict:
    """The ``v`` lines of OBJ bytes ``data`` as a point set: ``points`` ``(N, 3)`` and
    ``colors`` (the common ``v x y z r g b`` extension, as written; None unless every
    vertex has one); faces and other lines are ignored.

    Parameters
    ----------
    path : str or Path
        The file, named in errors.
    data : bytes
        Its contents.
    """
    data = _clean(path, data)
    starts, ends, b0, b1 = _line_heads(data)
    v_lines = np.flatnonzero((b0 == ord("v")) & ((ends - starts == 1) | (b1 == 32)))
    if not len(v_lines):
        raise MeshFormatError(path, "no 'v' lines: a point set needs vertices")
    points, _ = _vertices(path, data, starts, ends, v_lines)
    colors = None
    vblob = join_lines(data, starts, ends, v_lines)
    counts = token_counts(normalize_whitespace(vblob), len(v_lines)) - 1
    if (counts == 6).all():
        values = parse_numbers(_blank_keyword(vblob, b"v"))
        if values is not None:
            colors = values.reshape(-1, 6)[:, 3:]
    return {"points": points, "normals": None, "colors": colors, "integer_colors": False}


def _vertices(path, data: bytes, starts, ends, v_lines):
    """The ``v`` lines' positions ``(V, 3)`` (a w after them dropped), and their colours
    ``(V, 3)`` where lines carry ``v x y z r g b`` (None where none does; white on a line
    without one where others have one)."""
    vblob = join_lines(data, starts, ends, v_lines)
    numbers = _blank_keyword(vblob, b"v") if len(v_lines) else b""
    values = parse_decimals(numbers)
    if values is None:
        values = parse_numbers(numbers)
    if values is None:
        _obj_diagnose(path, data)
        raise MeshFormatError(path, "malformed vertex data")
    if len(values) == 3 * len(v_lines):
        return values.reshape(-1, 3), None
    counts = token_counts(normalize_whitespace(vblob), len(v_lines)) - 1
    bad = ~np.isin(counts, (3, 4, 6, 7))
    if bad.any() or counts.sum() != len(values):
        _obj_diagnose(path, data)
        raise MeshFormatError(path, "malformed vertex data")
    first = offsets_from_sizes(counts)[:-1]
    vertices = ragged_take(values, first, np.full(len(counts), 3)).reshape(-1, 3)
    colored = counts >= 6
    if not colored.any():
        return vertices, None
    colors = np.ones((len(counts), 3))
    # (x y z r g b, or x y z w r g b: the colour is the last three)
    at = first[colored] + counts[colored] - 3
    colors[colored] = values[at[:, None] + np.arange(3)]
    wrong = ~(np.isfinite(colors) & (colors >= 0) & (colors <= 1)).all(1)
    if wrong.any():
        i = int(np.flatnonzero(wrong)[0])
        raise MeshFormatError(path, f"vertex colour {colors[i].tolist()} is not in [0, 1] "
                              "(v x y z r g b: linear RGB)", line=int(v_lines[i]) + 1)
    return vertices, colors


def _faces(path, data: bytes, starts, ends, f_lines, v_lines, n_vertices: int):
    """The ``f`` lines' vertex indices (0-based, negative ones resolved) and sizes."""
    if len(f_lines) == 0:
        raise MeshFormatError(path, "the file has no faces ('f' lines)")
    fblob = join_lines(data, starts, ends, f_lines)  # data is normalized already
    sizes = token_counts(fblob, len(f_lines)) - 1
    body = _blank_keyword(fblob, b"f")
    if b"/" in body:
        body = _SLASH_TAIL.sub(b"", body)
    idx = parse_numbers(body, np.int64)
    if idx is None or len(idx) != sizes.sum() or (idx == 0).any():
        _obj_diagnose(path, data)
        raise MeshFormatError(path, "malformed face data")
    written = idx
    if idx.min() < 0:
        # negative indices count back from the vertices defined before their line
        v_before = np.repeat(np.searchsorted(v_lines, f_lines), sizes)
        idx = np.where(idx < 0, idx + v_before, idx - 1)
    else:
        idx = idx - 1
    bad = (idx < 0) | (idx >= n_vertices)
    if bad.any():
        c = int(np.flatnonzero(bad)[0])
        f = int(np.searchsorted(offsets_from_sizes(sizes), c, side="right") - 1)
        raise MeshFormatError(path, f"face index {int(written[c])} is out of range: the file "
                              f"defines {n_vertices} vertices", line=int(f_lines[f]) + 1)
    return idx, sizes


def write(mesh: Mesh, f, binary: bool, mtllib: str | None = None) -> None:
    """Write ``mesh`` as OBJ to the open file ``f`` (text; ``binary`` is ignored): its
    texture coordinates as ``vt`` (``f v/vt``), its material parts as ``usemtl`` runs, in
    face order, after ``mtllib`` (the library's file name) when given.

    Parameters
    ----------
    mesh : Mesh
        What to write.
    f : file
        An open binary file.
    binary : bool
        Ignored: OBJ is text.
    mtllib : str or None
        The material library's file name to reference (None: none).
    """
    f.write(f"# glshade: {mesh.n_vertices} vertices, {mesh.n_faces} faces\n".encode())
    if mtllib is not None and mesh.material_groups:
        f.write(f"mtllib {mtllib}\n".encode())
    write_vertices(f, mesh.vertices, "v ")
    corner_vt = None
    if mesh.uv is not None:
        table, corner_vt = np.unique(mesh.uv, axis=0, return_inverse=True)
        corner_vt = corner_vt.ravel()
        f.write(("vt %.17g %.17g\n" * len(table) % tuple(table.ravel())).encode())
    part = np.full(mesh.n_faces, -1)
    names = list(mesh.material_groups)
    for k, faces in enumerate(mesh.material_groups.values()):
        part[faces] = k
    cuts = np.flatnonzero(np.diff(part)) + 1
    for start, stop in zip(np.r_[0, cuts].tolist(), np.r_[cuts, mesh.n_faces].tolist()):
        if names and part[start] >= 0:
            f.write(f"usemtl {names[part[start]]}\n".encode())
        elif names:
            f.write(b"usemtl default\n")
        _write_faces(f, mesh, start, stop, corner_vt)


def _write_faces(f, mesh: Mesh, start: int, stop: int, corner_vt) -> None:
    """Faces ``start:stop`` as ``f`` lines (``v/vt`` pairs where there are coordinates)."""
    sizes = mesh.face_sizes[start:stop]
    a, b = int(mesh.face_offsets[start]), int(mesh.face_offsets[stop])
    if corner_vt is None:
        cell, values = "%d", mesh.face_indices[a:b] + 1
    else:
        cell = "%d/%d"
        values = np.stack([mesh.face_indices[a:b] + 1, corner_vt[a:b] + 1], 1).ravel()
    kinds = np.unique(sizes)
    fmt = np.empty(int(kinds.max()) + 1, dtype=object)
    for k in kinds.tolist():
        fmt[k] = "f " + " ".join([cell] * k) + "\n"
    f.write(("".join(fmt[sizes]) % tuple(values.tolist())).encode())
