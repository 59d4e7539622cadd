"""Read and write polygon meshes: Wavefront OBJ, OFF, PLY and STL.

Polygons are preserved (a quad stays a quad); STL, which only knows triangles, is welded
on load so that its topology is usable. Parsing is vectorized with numpy; a malformed file
raises :class:`~glshade.errors.MeshFormatError` naming the path, the line (or byte offset)
and what was wrong.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from .._atomic import atomic_write
from ..errors import GeometryError, MeshFormatError
from ..geometry.mesh import Mesh
from ._text import (
    line_starts, normalize_whitespace, parse_decimals, parse_numbers, ragged_take, token_counts,
)

__all__ = ["load_mesh", "save_mesh", "FORMATS"]

FORMATS = ("obj", "off", "ply", "stl")

# --------------------------------------------------------------------------- helpers


def _format_of(path: Path, fmt: str | None) -> str:
    fmt = (fmt or path.suffix.lstrip(".")).lower()
    if fmt not in FORMATS:
        raise MeshFormatError(
            path, f"unknown mesh format {fmt!r}; supported: {', '.join(FORMATS)}"
        )
    return fmt


def _no_line(_: int) -> None:
    return None


def _build(path, vertices, indices, offsets, *, line_of_face=_no_line,
           line_of_vertex=_no_line, **kwargs) -> Mesh:
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


def _offsets(sizes) -> np.ndarray:
    off = np.zeros(len(sizes) + 1, np.int64)
    np.cumsum(sizes, out=off[1:])
    return off


def load_mesh(path, format: str | None = None) -> Mesh:
    """Load a mesh from an OBJ, OFF, PLY or STL file (format from the extension).

    Raises
    ------
    MeshFormatError
        The file is missing, unreadable or malformed; the message names the path and the
        line (or byte offset) and says what was wrong.
    """
    path = Path(path)
    fmt = _format_of(path, format)
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise MeshFormatError(path, "no such file") from None
    except IsADirectoryError:
        raise MeshFormatError(path, "is a directory, not a mesh file") from None
    except OSError as exc:
        raise MeshFormatError(path, f"cannot read: {exc.strerror or exc}") from None
    if not data.strip():
        raise MeshFormatError(path, "the file is empty")
    mesh = _READERS[fmt](path, data)
    mesh.name = mesh.name or path.stem
    return mesh


def save_mesh(mesh: Mesh, path, format: str | None = None, *, binary: bool = True) -> None:
    """Write ``mesh`` to ``path`` (atomically). PLY and STL are binary unless
    ``binary=False``; STL stores the triangulation. Coordinates keep full precision."""
    path = Path(path)
    fmt = _format_of(path, format)
    with atomic_write(path, "wb") as f:
        _WRITERS[fmt](mesh, f, binary)


def _float_fmt(n: int) -> str:
    return " ".join(["%.17g"] * n)


def _write_vertices(f, vertices, prefix: str) -> None:
    if len(vertices):
        f.write(((prefix + _float_fmt(3) + "\n") * len(vertices) % tuple(vertices.ravel()))
                .encode())


def _write_faces(f, mesh: Mesh, prefix: str, base: int, with_count: bool) -> None:
    """One line per face, any mix of sizes, formatted in C (no loop over faces)."""
    sizes = mesh.face_sizes
    kinds = np.unique(sizes)
    fmt = np.empty(int(kinds.max()) + 1, dtype=object)
    for k in kinds.tolist():
        fmt[k] = prefix + (f"{k} " if with_count else "") + " ".join(["%d"] * k) + "\n"
    text = "".join(fmt[sizes]) % tuple((mesh.face_indices + base).tolist())
    f.write(text.encode())


# ------------------------------------------------------------------------------- OBJ

_OBJ_KEYWORDS = {
    b"v", b"vt", b"vn", b"vp", b"f", b"l", b"p", b"o", b"g", b"s", b"mg", b"usemtl",
    b"mtllib", b"cstype", b"deg", b"bmat", b"step", b"curv", b"curv2", b"surf", b"parm",
    b"trim", b"hole", b"scrv", b"sp", b"end", b"con", b"lod", b"usemap", b"maplib",
    b"shadow_obj", b"trace_obj", b"ctech", b"stech", b"bevel", b"c_interp", b"d_interp",
    b"call", b"csh",
}
_SLASH_TAIL = re.compile(rb"/\S*")


def _join_lines(data: bytes, starts, ends, lines: np.ndarray) -> bytes:
    """The given lines (sorted indices) joined by newlines, one slice per contiguous run."""
    if len(lines) == 0:
        return b""
    brk = np.flatnonzero(np.diff(lines) != 1)
    first = np.concatenate([[0], brk + 1])
    last = np.concatenate([brk, [len(lines) - 1]])
    return b"\n".join(data[starts[lines[a]]:ends[lines[b]]]
                      for a, b in zip(first.tolist(), last.tolist()))


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


def _read_obj(path, data: bytes) -> Mesh:
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
            data = normalize_whitespace(_COMMENT.sub(b"", data))
    starts, ends = line_starts(data)
    arr = np.frombuffer(data, np.uint8)
    b0 = arr[starts]
    b1 = np.where(ends - starts > 1, arr[np.minimum(starts + 1, len(arr) - 1)], 10)
    one = (ends - starts == 1) | (b1 == 32)
    is_v = (b0 == ord("v")) & one
    is_f = (b0 == ord("f")) & one
    b0 = np.where(ends > starts, b0, 10)
    skip = (b0 == 10) | (b0 == ord("#")) | (
        (b0 == ord("v")) & ((b1 == ord("n")) | (b1 == ord("t")) | (b1 == ord("p"))))
    other = np.flatnonzero(~(is_v | is_f | skip))
    group_lines, group_names = [], []
    for i in other.tolist():
        line = data[starts[i]:ends[i]].split(b"#", 1)[0].split()
        if not line:
            continue
        if line[0] not in _OBJ_KEYWORDS:
            _obj_diagnose(path, data)
        if line[0] in (b"o", b"g"):
            group_lines.append(i)
            group_names.append(b" ".join(line[1:]).decode("utf-8", "replace") or "default")

    v_lines = np.flatnonzero(is_v)
    f_lines = np.flatnonzero(is_f)
    vblob = _join_lines(data, starts, ends, v_lines)
    numbers = _blank_keyword(vblob, b"v") if len(v_lines) else b""
    values = parse_decimals(numbers)
    if values is None:
        values = parse_numbers(numbers)
    if values is None:
        _obj_diagnose(path, data)
        raise MeshFormatError(path, "malformed vertex data")
    if len(values) == 3 * len(v_lines):
        vertices = values.reshape(-1, 3)
    else:
        counts = token_counts(normalize_whitespace(vblob), len(v_lines)) - 1
        bad = ~np.isin(counts, (3, 4, 6, 7))
        if bad.any() or counts.sum() != len(values):
            _obj_diagnose(path, data)
            raise MeshFormatError(path, "malformed vertex data")
        vertices = ragged_take(values, _offsets(counts)[:-1], np.full(len(counts), 3))
        vertices = vertices.reshape(-1, 3)

    if len(f_lines) == 0:
        raise MeshFormatError(path, "the file has no faces ('f' lines)")
    fblob = _join_lines(data, starts, ends, f_lines)  # data is normalized already
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
    bad = (idx < 0) | (idx >= len(vertices))
    if bad.any():
        c = int(np.flatnonzero(bad)[0])
        f = int(np.searchsorted(_offsets(sizes), c, side="right") - 1)
        raise MeshFormatError(path, f"face index {int(written[c])} is out of range: the file "
                              f"defines {len(vertices)} vertices", line=int(f_lines[f]) + 1)

    groups = {}
    if group_lines:
        owner = np.searchsorted(np.asarray(group_lines), f_lines) - 1
        for g, name in enumerate(group_names):
            members = np.flatnonzero(owner == g)
            if len(members):
                groups[name] = np.concatenate([groups[name], members]) if name in groups \
                    else members

    def line_of_face(f):
        return int(f_lines[f]) + 1

    def line_of_vertex(i):
        return int(v_lines[i]) + 1

    return _build(path, vertices, idx, _offsets(sizes), line_of_face=line_of_face,
                  line_of_vertex=line_of_vertex, groups=groups)


def _write_obj(mesh: Mesh, f, binary: bool) -> None:
    f.write(f"# glshade: {mesh.n_vertices} vertices, {mesh.n_faces} faces\n".encode())
    _write_vertices(f, mesh.vertices, "v ")
    _write_faces(f, mesh, "f ", 1, with_count=False)


# ------------------------------------------------------------------------------- OFF

_COMMENT = re.compile(rb"#[^\n]*")


def _read_off(path, data: bytes) -> Mesh:
    if b"#" in data:
        data = _COMMENT.sub(b"", data)
    text = normalize_whitespace(data)
    # drop blank lines but remember the original line numbers
    starts, ends = line_starts(text)
    keep = np.flatnonzero(ends > starts)
    if len(keep) == 0:
        raise MeshFormatError(path, "the file is empty")
    first = text[starts[keep[0]]:ends[keep[0]]].split()
    header = first[0]
    if not header.endswith(b"OFF") or header.startswith(b"4") or header.startswith(b"n"):
        raise MeshFormatError(path, f"not an OFF file: the first word is "
                              f"{header.decode(errors='replace')!r}, expected 'OFF'", line=1)
    rest = first[1:]
    pos = 1
    if len(rest) < 2:
        if len(keep) < 2:
            raise MeshFormatError(path, "missing the 'vertices faces edges' counts line")
        rest = text[starts[keep[1]]:ends[keep[1]]].split()
        pos = 2
    try:
        nv, nf = int(rest[0]), int(rest[1])
    except (ValueError, IndexError):
        counts = b" ".join(rest).decode(errors="replace")
        raise MeshFormatError(path, f"bad counts line {counts!r}, expected 'vertices faces "
                              "edges'", line=int(keep[pos - 1]) + 1) from None
    if nv < 0 or nf < 0:
        raise MeshFormatError(path, f"negative counts {nv} {nf}", line=int(keep[pos - 1]) + 1)
    vl, fl = keep[pos:pos + nv], keep[pos + nv:pos + nv + nf]
    if len(vl) < nv or len(fl) < nf:
        raise MeshFormatError(path, f"the header promises {nv} vertices and {nf} faces, but "
                              f"the file ends after {len(vl)} vertices and {len(fl)} faces "
                              "(truncated?)")
    vblob = _join_lines(text, starts, ends, vl)
    vals = parse_numbers(vblob)
    vcount = token_counts(vblob, nv)
    if vals is None or len(vals) != vcount.sum():
        _numeric_diagnose(path, text, starts, ends, vl, "vertex")
    bad = vcount < 3
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise MeshFormatError(path, f"vertex {i} has {int(vcount[i])} numbers, expected 3",
                              line=int(vl[i]) + 1)
    vertices = ragged_take(vals, _offsets(vcount)[:-1], np.full(nv, 3)).reshape(-1, 3)
    fblob = _join_lines(text, starts, ends, fl)
    fvals = parse_numbers(fblob)
    fcount = token_counts(fblob, nf)
    if fvals is None or len(fvals) != fcount.sum():
        _numeric_diagnose(path, text, starts, ends, fl, "face")
    line_off = _offsets(fcount)[:-1]
    k = fvals[line_off] if nf else np.zeros(0)
    bad = (k != np.round(k)) | (k < 0) | (fcount < k + 1)
    if bad.any():
        f = int(np.flatnonzero(bad)[0])
        raise MeshFormatError(path, f"face {f} says it has {fvals[line_off[f]]:g} vertices but "
                              f"lists {int(fcount[f]) - 1} numbers", line=int(fl[f]) + 1)
    k = k.astype(np.int64)
    idx = ragged_take(fvals, line_off + 1, k)
    if (idx != np.round(idx)).any():
        c = int(np.flatnonzero(idx != np.round(idx))[0])
        f = int(np.searchsorted(_offsets(k), c, side="right") - 1)
        raise MeshFormatError(path, f"face {f} has a non-integer index {idx[c]:g}",
                              line=int(fl[f]) + 1)
    return _build(path, vertices, idx.astype(np.int64), _offsets(k),
                  line_of_face=lambda f: int(fl[f]) + 1,
                  line_of_vertex=lambda i: int(vl[i]) + 1)


def _numeric_diagnose(path, text, starts, ends, lines, what: str, first_line: int = 1):
    for i in lines.tolist():
        for token in text[starts[i]:ends[i]].split():
            try:
                float(token)
            except ValueError:
                raise MeshFormatError(path, f"{what} data: {token.decode(errors='replace')!r} "
                                      "is not a number", line=i + first_line) from None
    raise MeshFormatError(path, f"malformed {what} data")


def _write_off(mesh: Mesh, f, binary: bool) -> None:
    f.write(f"OFF\n{mesh.n_vertices} {mesh.n_faces} {mesh.n_edges}\n".encode())
    _write_vertices(f, mesh.vertices, "")
    _write_faces(f, mesh, "", 0, with_count=True)


# ------------------------------------------------------------------------------- PLY

_PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
    "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}


def _ply_header(path, data: bytes):
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise MeshFormatError(path, "not a PLY file: it must start with 'ply' and have an "
                              "'end_header' line", line=1)
    nl = data.find(b"\n", end)
    body_start = len(data) if nl < 0 else nl + 1
    lines = data[:end].decode("ascii", "replace").splitlines()
    fmt, elements = None, []
    for number, line in enumerate(lines, start=1):
        words = line.split()
        if not words or words[0] in ("ply", "comment", "obj_info"):
            continue
        if words[0] == "format":
            if len(words) < 2 or words[1] not in ("ascii", "binary_little_endian",
                                                  "binary_big_endian"):
                raise MeshFormatError(path, f"unknown PLY format {line!r}", line=number)
            fmt = words[1]
        elif words[0] == "element":
            if len(words) != 3 or not words[2].isdigit():
                raise MeshFormatError(path, f"bad element line {line!r}", line=number)
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property":
            if not elements:
                raise MeshFormatError(path, "property before any element", line=number)
            if len(words) == 5 and words[1] == "list":
                if words[2] not in _PLY_TYPES or words[3] not in _PLY_TYPES:
                    raise MeshFormatError(path, f"unknown type in {line!r}", line=number)
                elements[-1][2].append((words[4], "list", _PLY_TYPES[words[2]],
                                        _PLY_TYPES[words[3]]))
            elif len(words) == 3 and words[1] in _PLY_TYPES:
                elements[-1][2].append((words[2], "scalar", _PLY_TYPES[words[1]], None))
            else:
                raise MeshFormatError(path, f"bad property line {line!r}", line=number)
        else:
            raise MeshFormatError(path, f"unknown header keyword {words[0]!r}", line=number)
    if fmt is None:
        raise MeshFormatError(path, "the header has no 'format' line")
    names = [e[0] for e in elements]
    if "vertex" not in names or "face" not in names:
        raise MeshFormatError(path, f"a mesh needs 'vertex' and 'face' elements, found {names}")
    return fmt, elements, body_start, len(lines) + 2


def _vertex_columns(path, props):
    names = [p[0] for p in props]
    if any(p[1] == "list" for p in props):
        raise MeshFormatError(path, "list properties on vertices are not supported")
    missing = [c for c in "xyz" if c not in names]
    if missing:
        raise MeshFormatError(path, f"vertex element lacks properties {missing}")
    cols = [names.index(c) for c in "xyz"]
    ncols = [names.index(c) for c in ("nx", "ny", "nz")] if all(
        c in names for c in ("nx", "ny", "nz")) else None
    return cols, ncols


def _face_layout(path, props):
    lists = [i for i, p in enumerate(props) if p[1] == "list"]
    if len(lists) < 1 or props[lists[0]][0] not in ("vertex_indices", "vertex_index"):
        raise MeshFormatError(path, "face element needs a 'vertex_indices' list property")
    if len(lists) > 1:
        raise MeshFormatError(path, "face elements with several lists are not supported")
    return lists[0]


def _read_ply(path, data: bytes) -> Mesh:
    fmt, elements, pos, first_body_line = _ply_header(path, data)
    if fmt == "ascii":
        return _read_ply_ascii(path, data[pos:], elements, first_body_line)
    order = "<" if fmt == "binary_little_endian" else ">"
    vertices = normals = idx = sizes = None
    for name, count, props in elements:
        if name == "vertex":
            cols, ncols = _vertex_columns(path, props)
            dt = np.dtype([(f"p{i}", order + p[2]) for i, p in enumerate(props)])
            if pos + count * dt.itemsize > len(data):
                raise MeshFormatError(path, f"truncated: {count} vertices need "
                                      f"{count * dt.itemsize} bytes, {len(data) - pos} remain",
                                      byte=len(data))
            rec = np.frombuffer(data, dt, count=count, offset=pos)
            vertices = np.stack([rec[f"p{c}"] for c in cols], 1).astype(np.float64)
            if ncols:
                normals = np.stack([rec[f"p{c}"] for c in ncols], 1).astype(np.float64)
            pos += count * dt.itemsize
        elif name == "face":
            li = _face_layout(path, props)
            idx, sizes, pos = _ply_binary_faces(path, data, pos, count, props, li, order)
            break
        else:
            if any(p[1] == "list" for p in props):
                raise MeshFormatError(path, f"element {name!r} with list properties before "
                                      "the faces is not supported")
            pos += count * sum(np.dtype(p[2]).itemsize for p in props)
    mesh = _build(path, vertices, idx, _offsets(sizes))
    if normals is not None and np.isfinite(normals).all():
        mesh = Mesh.from_csr(mesh.vertices, mesh.face_indices, mesh.face_offsets,
                             normals=normals)
    return mesh


def _ply_binary_faces(path, data, pos, count, props, li, order):
    """Faces of a binary PLY. Same-size faces are one frombuffer; mixed sizes find the
    record starts by pointer doubling over the byte positions (vectorized)."""
    pre = sum(np.dtype(p[2]).itemsize for p in props[:li])
    post = sum(np.dtype(p[2]).itemsize for p in props[li + 1:])
    ctype = np.dtype(order + props[li][2])
    itype = np.dtype(order + props[li][3])
    head = pre + ctype.itemsize
    if count == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), pos
    if pos + head > len(data):
        raise MeshFormatError(path, "truncated: the face data is missing", byte=len(data))
    k0 = int(np.frombuffer(data, ctype, count=1, offset=pos + pre)[0])
    rec_size = head + k0 * itype.itemsize + post
    if k0 >= 3 and pos + count * rec_size <= len(data):
        dt = np.dtype([("pre", "V%d" % pre) if pre else ("pre", "u1", (0,)),
                       ("n", ctype), ("i", itype, (k0,)),
                       ("post", "V%d" % post) if post else ("post", "u1", (0,))])
        rec = np.frombuffer(data, dt, count=count, offset=pos)
        if (rec["n"] == k0).all():
            idx = rec["i"].astype(np.int64).ravel()
            return idx, np.full(count, k0, np.int64), pos + count * rec_size
    # Mixed sizes: next(p) = p + head + n(p) * isize + post for every byte position p.
    body = np.frombuffer(data, np.uint8, offset=pos)
    n_pos = len(body) - head + 1
    if n_pos <= 0:
        raise MeshFormatError(path, "truncated face data", byte=len(data))
    counts_at = np.zeros(len(body) + 1, np.int64)
    raw = np.lib.stride_tricks.sliding_window_view(body, ctype.itemsize)[pre:pre + n_pos]
    counts_at[:n_pos] = raw.copy().view(ctype).ravel()
    sentinel = len(body)
    nxt = np.minimum(np.arange(len(body) + 1) + head + counts_at * itype.itemsize + post,
                     sentinel)
    nxt[n_pos:] = sentinel
    nxt[sentinel] = sentinel
    # depth[p] = number of records from p to the end... instead: reach all records from 0
    reached = np.zeros(len(body) + 1, bool)
    reached[0] = True
    jump = nxt
    steps = 1
    while steps < count:
        reached[jump[reached]] = True
        jump = jump[jump]
        steps *= 2
    starts = np.flatnonzero(reached[:sentinel])
    if len(starts) < count:
        raise MeshFormatError(path, f"truncated: the header promises {count} faces, the data "
                              f"holds {len(starts)}", byte=len(data))
    starts = starts[:count]
    sizes = counts_at[starts]
    end = starts[-1] + head + sizes[-1] * itype.itemsize + post
    if end > len(body):
        raise MeshFormatError(path, f"truncated: face {count - 1} runs past the end of the "
                              "file", byte=len(data))
    corner = np.repeat(starts + head, sizes) + itype.itemsize * (
        np.arange(int(sizes.sum())) - np.repeat(_offsets(sizes)[:-1], sizes))
    window = np.lib.stride_tricks.sliding_window_view(body, itype.itemsize)
    idx = window[corner].copy().view(itype).ravel().astype(np.int64)
    return idx, sizes, pos + int(end)


def _read_ply_ascii(path, body: bytes, elements, first_line: int) -> Mesh:
    text = normalize_whitespace(body)
    starts, ends = line_starts(text)
    keep = np.flatnonzero(ends > starts)
    line = 0
    vertices = normals = idx = sizes = None
    for name, count, props in elements:
        lines = keep[line:line + count]
        if len(lines) < count:
            raise MeshFormatError(path, f"truncated: the header promises {count} {name} lines, "
                                  f"the file has {len(lines)}")
        line += count
        blob = _join_lines(text, starts, ends, lines)
        vals = parse_numbers(blob)
        counts = token_counts(blob, count)
        if vals is None or len(vals) != counts.sum():
            _numeric_diagnose(path, text, starts, ends, lines, name, first_line)
        if name == "vertex":
            cols, ncols = _vertex_columns(path, props)
            bad = counts != len(props)
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                raise MeshFormatError(path, f"vertex {i} has {int(counts[i])} values, the "
                                      f"header declares {len(props)}",
                                      line=int(lines[i]) + first_line)
            table = vals.reshape(count, len(props))
            vertices = table[:, cols]
            normals = table[:, ncols] if ncols else None
        elif name == "face":
            li = _face_layout(path, props)
            off = _offsets(counts)[:-1]
            k = vals[off + li] if count else np.zeros(0)
            extra = len(props) - 1
            bad = (k != np.round(k)) | (counts != k + 1 + extra)
            if bad.any():
                f = int(np.flatnonzero(bad)[0])
                raise MeshFormatError(path, f"face {f} declares {vals[off[f] + li]:g} vertices "
                                      f"but has {int(counts[f]) - 1 - extra} indices",
                                      line=int(lines[f]) + first_line)
            sizes = k.astype(np.int64)
            idx = ragged_take(vals, off + li + 1, sizes).astype(np.int64)
            break
    mesh = _build(path, vertices, idx, _offsets(sizes))
    if normals is not None:
        mesh = Mesh.from_csr(mesh.vertices, mesh.face_indices, mesh.face_offsets,
                             normals=normals)
    return mesh


def _write_ply(mesh: Mesh, f, binary: bool) -> None:
    fmt = "binary_little_endian" if binary else "ascii"
    f.write((f"ply\nformat {fmt} 1.0\ncomment glshade\nelement vertex {mesh.n_vertices}\n"
             "property double x\nproperty double y\nproperty double z\n"
             f"element face {mesh.n_faces}\nproperty list uchar int vertex_indices\n"
             "end_header\n").encode())
    if int(mesh.face_sizes.max(initial=0)) > 255:
        raise GeometryError("PLY stores polygon sizes as uchar: faces of more than 255 "
                            "vertices cannot be written")
    if not binary:
        _write_vertices(f, mesh.vertices, "")
        _write_faces(f, mesh, "", 0, with_count=True)
        return
    f.write(mesh.vertices.astype("<f8").tobytes())
    sizes = mesh.face_sizes
    face_byte = mesh.face_offsets[:-1] * 4 + np.arange(mesh.n_faces)
    buf = np.zeros(mesh.n_faces + 4 * len(mesh.face_indices), np.uint8)
    buf[face_byte] = sizes
    corner_byte = np.repeat(face_byte + 1, sizes) + 4 * (
        np.arange(len(mesh.face_indices)) - np.repeat(mesh.face_offsets[:-1], sizes))
    buf[corner_byte[:, None] + np.arange(4)] = (
        mesh.face_indices.astype("<i4").view(np.uint8).reshape(-1, 4))
    f.write(buf.tobytes())


# ------------------------------------------------------------------------------- STL

_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])
_STL_VERTEX = re.compile(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)")


def _weld_exact(path, triangles: np.ndarray) -> Mesh:
    """Merge bit-identical corners (STL repeats every vertex once per triangle)."""
    flat = np.ascontiguousarray(triangles.reshape(-1, 3).astype(np.float64))
    flat[flat == 0] = 0.0  # -0.0 and 0.0 are the same point
    key = flat.view(np.dtype((np.void, 24))).ravel()
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    return _build(path, flat[first], inverse.ravel().astype(np.int64),
                  np.arange(len(triangles) + 1, dtype=np.int64) * 3)


def _read_stl(path, data: bytes) -> Mesh:
    if len(data) >= 84:
        n = int(np.frombuffer(data, "<u4", count=1, offset=80)[0])
        binary_size = 84 + 50 * n
    else:
        n, binary_size = 0, -1
    if data.lstrip().startswith(b"solid") and len(data) != binary_size:
        return _read_stl_ascii(path, data)
    if len(data) < 84:
        raise MeshFormatError(path, f"truncated: a binary STL needs at least 84 bytes, the file "
                              f"has {len(data)}", byte=len(data))
    if len(data) != binary_size:
        raise MeshFormatError(path, f"binary STL header says {n} triangles ({binary_size} bytes)"
                              f" but the file has {len(data)} bytes", byte=len(data))
    if n == 0:
        raise MeshFormatError(path, "the file has no triangles")
    rec = np.frombuffer(data, _STL_RECORD, count=n, offset=84)
    return _weld_exact(path, rec["v"])


def _read_stl_ascii(path, data: bytes) -> Mesh:
    found = _STL_VERTEX.findall(data)
    n_facet = len(re.findall(rb"\bendfacet\b", data))
    n_start = len(re.findall(rb"\bfacet\b", data))
    if n_facet == 0:
        raise MeshFormatError(path, "ascii STL without any 'facet'", line=1)
    if n_start != n_facet or len(found) != 3 * n_facet:
        # find the first facet that does not have exactly 3 vertices
        count, line_no, start_line = 0, 0, 0
        for line_no, raw in enumerate(data.split(b"\n"), start=1):
            w = raw.split()
            if w[:1] == [b"facet"]:
                count, start_line = 0, line_no
            elif w[:1] == [b"vertex"]:
                count += 1
            elif w[:1] == [b"endfacet"] and count != 3:
                raise MeshFormatError(path, f"facet has {count} vertices, expected 3",
                                      line=start_line)
        raise MeshFormatError(path, f"{n_start} 'facet' and {n_facet} 'endfacet' with "
                              f"{len(found)} vertices: the file is truncated or malformed",
                              line=line_no)
    vals = parse_numbers(b" ".join(b" ".join(t) for t in found))
    if vals is None or len(vals) != 9 * n_facet:
        for line_no, raw in enumerate(data.split(b"\n"), start=1):
            w = raw.split()
            if w[:1] == [b"vertex"]:
                try:
                    [float(x) for x in w[1:4]]
                except ValueError:
                    raise MeshFormatError(path, f"vertex coordinate is not a number: "
                                          f"{raw.strip().decode(errors='replace')!r}",
                                          line=line_no) from None
        raise MeshFormatError(path, "malformed vertex data")
    return _weld_exact(path, vals.reshape(-1, 3, 3))


def _write_stl(mesh: Mesh, f, binary: bool) -> None:
    tri, owner = mesh.triangles
    p = mesh.vertices[tri]
    n = mesh.face_normals[owner]
    if binary:
        header = b"glshade binary STL".ljust(80, b" ")
        rec = np.zeros(len(tri), _STL_RECORD)
        rec["normal"] = n
        rec["v"] = p
        f.write(header + np.uint32(len(tri)).tobytes() + rec.tobytes())
        return
    name = (mesh.name or "glshade").replace(" ", "_")
    facet = ("facet normal %.9g %.9g %.9g\n outer loop\n" + "  vertex %.17g %.17g %.17g\n" * 3
             + " endloop\nendfacet\n")
    table = np.concatenate([n, p.reshape(-1, 9)], axis=1)
    f.write(f"solid {name}\n".encode())
    f.write((facet * len(tri) % tuple(table.ravel())).encode())
    f.write(f"endsolid {name}\n".encode())


_READERS = {"obj": _read_obj, "off": _read_off, "ply": _read_ply, "stl": _read_stl}
_WRITERS = {"obj": _write_obj, "off": _write_off, "ply": _write_ply, "stl": _write_stl}
del os
