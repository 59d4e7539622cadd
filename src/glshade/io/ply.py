"""PLY (Stanford polygon file format): ascii and binary (little- and big-endian), any mix of
polygon sizes."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import GeometryError, MeshFormatError
from ..geometry.mesh import Mesh
from ._common import (
    build_mesh, join_lines, numeric_diagnose, offsets_from_sizes, write_faces, write_vertices,
)
from ..scene.texture import srgb_to_linear
from .text import line_starts, normalize_whitespace, parse_numbers, ragged_take, token_counts

__all__ = ["read", "read_points", "write"]

_PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
    "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}


def _ply_header(path, data: bytes, points: bool = False):
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise MeshFormatError(path, "not a PLY file: it must start with 'ply' and have an "
                              "'end_header' line", line=1)
    nl = data.find(b"\n", end)
    body_start = len(data) if nl < 0 else nl + 1
    lines = data[:end].decode("ascii", "replace").splitlines()
    fmt: str | None = None
    elements: list[Any] = []
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
    if points:
        if "vertex" not in names:
            raise MeshFormatError(path, f"a point set needs a 'vertex' element, found {names}")
        return fmt, elements, body_start, len(lines) + 2
    if names == ["vertex"]:
        raise MeshFormatError(path, "a point set (only a 'vertex' element, no faces): load "
                              "it with glshade.load_points")
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
    return cols, ncols, _uv_columns(names)


#: the names PLY writers give a vertex's (or a face's) colour, and its alpha
_COLOR_NAMES = (("red", "green", "blue"), ("r", "g", "b"), ("diffuse_red", "diffuse_green",
                                                            "diffuse_blue"))
_ALPHA_NAMES = ("alpha", "a", "diffuse_alpha")


def _color_columns(props) -> tuple[list, bool] | None:
    """The columns of an element's colour (RGB, and alpha where given) among ``props``, and
    whether they are integers (bytes, sRGB-encoded: BOP's models) or floats (linear)."""
    names = [p[0] for p in props]
    for trio, alpha in zip(_COLOR_NAMES, _ALPHA_NAMES):
        if all(c in names for c in trio):
            cols = [names.index(c) for c in trio]
            if alpha in names:
                cols.append(names.index(alpha))
            return cols, np.dtype(props[cols[0]][2]).kind in "iu"
    return None


def _linear_colors(path, table, found, what: str):
    """``(N, 3|4)`` linear RGB(A) from an element's colour columns: integers are
    sRGB-encoded bytes (0-255; alpha linear), floats linear in [0, 1]; None without."""
    if found is None:
        return None
    cols, integer = found
    c = table[:, cols].astype(np.float64)
    top = 255.0 if integer else 1.0
    bad = ~(np.isfinite(c) & (c >= 0) & (c <= top)).all(1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        rule = "integer colours lie in 0-255" if integer else "float colours lie in 0-1"
        raise MeshFormatError(path, f"{what} {i} has colour {c[i].tolist()}: {rule}")
    if integer:
        c = c / 255.0
        c[:, :3] = srgb_to_linear(c[:, :3])
    return c


#: the names PLY writers give a vertex's texture coordinates
_UV_NAMES = (("u", "v"), ("s", "t"), ("texture_u", "texture_v"), ("texture_s", "texture_t"))


def _uv_columns(names: list) -> list | None:
    for pair in _UV_NAMES:
        if all(c in names for c in pair):
            return [names.index(c) for c in pair]
    return None


def _finish(path, vertices, idx, sizes, normals, uv, colors=None, face_colors=None) -> Mesh:
    """The mesh, with file normals, per-vertex texture coordinates (made per corner) and
    vertex and face colours where the file has them."""
    mesh = build_mesh(path, vertices, idx, offsets_from_sizes(sizes))
    if normals is not None and not np.isfinite(normals).all():
        normals = None
    if uv is not None and not np.isfinite(uv).all():
        raise MeshFormatError(path, f"vertex {int(np.flatnonzero(~np.isfinite(uv).all(1))[0])}"
                              " has a non-finite texture coordinate")
    if normals is None and uv is None and colors is None and face_colors is None:
        return mesh
    return Mesh.from_csr(mesh.vertices, mesh.face_indices, mesh.face_offsets, normals=normals,
                         uv=None if uv is None else uv[mesh.face_indices], colors=colors,
                         face_colors=face_colors)


def _binary_vertices(path, data: bytes, pos: int, count: int, props, order: str):
    """The vertex element's ``count`` records at ``pos`` as float64 columns ``(count,
    len(props))``, and the position after them; a file too short for them refused."""
    dt = np.dtype([(f"p{i}", order + p[2]) for i, p in enumerate(props)])
    if pos + count * dt.itemsize > len(data):
        raise MeshFormatError(path, f"truncated: {count} vertices need "
                              f"{count * dt.itemsize} bytes, {len(data) - pos} remain",
                              byte=len(data))
    rec = np.frombuffer(data, dt, count=count, offset=pos)
    table = np.stack([rec[f"p{i}"].astype(np.float64) for i in range(len(props))], 1) \
        if len(props) else np.zeros((count, 0))
    return table, pos + count * dt.itemsize


def _face_layout(path, props):
    lists = [i for i, p in enumerate(props) if p[1] == "list"]
    if len(lists) < 1 or props[lists[0]][0] not in ("vertex_indices", "vertex_index"):
        raise MeshFormatError(path, "face element needs a 'vertex_indices' list property")
    if len(lists) > 1:
        raise MeshFormatError(path, "face elements with several lists are not supported")
    return lists[0]


def read(path, data: bytes) -> Mesh:
    """The Mesh in PLY bytes ``data``, ASCII or binary (``path`` names it in errors).

    Parameters
    ----------
    path : str or Path
        The file, named in errors.
    data : bytes
        Its contents.
    """
    fmt, elements, pos, first_body_line = _ply_header(path, data)
    if fmt == "ascii":
        return _read_ply_ascii(path, data[pos:], elements, first_body_line)
    order = "<" if fmt == "binary_little_endian" else ">"
    vertices = normals = idx = sizes = uv = colors = face_colors = None
    for name, count, props in elements:
        if name == "vertex":
            cols, ncols, uvcols = _vertex_columns(path, props)
            table, pos = _binary_vertices(path, data, pos, count, props, order)
            vertices = table[:, cols]
            if ncols:
                normals = table[:, ncols]
            if uvcols:
                uv = table[:, uvcols]
            colors = _linear_colors(path, table, _color_columns(props), "vertex")
        elif name == "face":
            li = _face_layout(path, props)
            start = pos
            idx, sizes, pos, starts = _ply_binary_faces(path, data, pos, count, props, li,
                                                        order)
            found = _color_columns(props)
            if found is not None:
                table = _binary_face_scalars(data, start, starts, sizes, props, li, order)
                face_colors = _linear_colors(path, table, found, "face")
            break
        else:
            if any(p[1] == "list" for p in props):
                raise MeshFormatError(path, f"element {name!r} with list properties before "
                                      "the faces is not supported")
            pos += count * sum(np.dtype(p[2]).itemsize for p in props)
    return _finish(path, vertices, idx, sizes, normals, uv, colors, face_colors)


def _binary_face_scalars(data, pos, starts, sizes, props, li, order):
    """``(F, len(props))`` float64: each face record's scalar properties (the list's column
    left 0), read at the records' starts (bytes after ``pos``)."""
    table = np.zeros((len(starts), len(props)))
    body = np.frombuffer(data, np.uint8, offset=pos)
    offset = np.zeros(len(starts), np.int64)
    for k, p in enumerate(props):
        if k == li:  # (the count, then its indices)
            offset += np.dtype(p[2]).itemsize + sizes * np.dtype(p[3]).itemsize
            continue
        t = np.dtype(order + p[2])
        at = starts + offset
        window = np.lib.stride_tricks.sliding_window_view(body, t.itemsize)
        table[:, k] = window[at].copy().view(t).ravel().astype(np.float64)
        offset += t.itemsize
    return table


def _ply_binary_faces(path, data, pos, count, props, li, order):
    """Faces of a binary PLY, and each record's start (bytes after ``pos``). Same-size
    faces are one frombuffer; mixed sizes find the record starts by pointer doubling over
    the byte positions (vectorized)."""
    pre = sum(np.dtype(p[2]).itemsize for p in props[:li])
    post = sum(np.dtype(p[2]).itemsize for p in props[li + 1:])
    ctype = np.dtype(order + props[li][2])
    itype = np.dtype(order + props[li][3])
    head = pre + ctype.itemsize
    if count == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), pos, np.zeros(0, np.int64)
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
            return (idx, np.full(count, k0, np.int64), pos + count * rec_size,
                    np.arange(count, dtype=np.int64) * rec_size)
    # Mixed sizes: next(p) = p + head + n(p) * isize + post for every byte position p.
    body = np.frombuffer(data, np.uint8, offset=pos)
    n_pos = len(body) - head + 1
    if n_pos <= 0:
        raise MeshFormatError(path, "truncated face data", byte=len(data))
    counts_at = np.zeros(len(body) + 1, np.int64)
    raw = np.lib.stride_tricks.sliding_window_view(body, ctype.itemsize)[pre:pre + n_pos]
    counts_at[:n_pos] = raw.copy().view(ctype).ravel()
    sentinel = len(body)
    # (a negative count, at a real record or at a byte that is not one, must not step
    # backwards: it steps as if 0, and the size check below reports a real one)
    step = head + np.maximum(counts_at, 0) * itype.itemsize + post
    nxt = np.minimum(np.arange(len(body) + 1) + step, sentinel)
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
    small = sizes < 3
    if small.any():  # (before any index is read: a count of 0 has none to read)
        f = int(np.flatnonzero(small)[0])
        raise MeshFormatError(path, f"face {f} has {int(sizes[f])} vertices; a polygon needs "
                              "at least 3", byte=pos + int(starts[f]))
    end = starts[-1] + head + sizes[-1] * itype.itemsize + post
    if end > len(body):
        raise MeshFormatError(path, f"truncated: face {count - 1} runs past the end of the "
                              "file", byte=len(data))
    corner = np.repeat(starts + head, sizes) + itype.itemsize * (
        np.arange(int(sizes.sum())) - np.repeat(offsets_from_sizes(sizes)[:-1], sizes))
    window = np.lib.stride_tricks.sliding_window_view(body, itype.itemsize)
    idx = window[corner].copy().view(itype).ravel().astype(np.int64)
    return idx, sizes, pos + int(end), starts


def _read_ply_ascii(path, body: bytes, elements, first_line: int) -> Mesh:
    text = normalize_whitespace(body)
    starts, ends = line_starts(text)
    keep = np.flatnonzero(ends > starts)
    line = 0
    vertices = normals = idx = sizes = uv = colors = face_colors = None
    for name, count, props in elements:
        lines = keep[line:line + count]
        if len(lines) < count:
            raise MeshFormatError(path, f"truncated: the header promises {count} {name} lines, "
                                  f"the file has {len(lines)}")
        line += count
        blob = join_lines(text, starts, ends, lines)
        vals = parse_numbers(blob)
        counts = token_counts(blob, count)
        if vals is None or len(vals) != counts.sum():
            numeric_diagnose(path, text, starts, ends, lines, name, first_line)
        if name == "vertex":
            cols, ncols, uvcols = _vertex_columns(path, props)
            bad = counts != len(props)
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                raise MeshFormatError(path, f"vertex {i} has {int(counts[i])} values, the "
                                      f"header declares {len(props)}",
                                      line=int(lines[i]) + first_line)
            table = vals.reshape(count, len(props))
            vertices = table[:, cols]
            normals = table[:, ncols] if ncols else None
            uv = table[:, uvcols] if uvcols else None
            colors = _linear_colors(path, table, _color_columns(props), "vertex")
        elif name == "face":
            li = _face_layout(path, props)
            off = offsets_from_sizes(counts)[:-1]
            k = vals[off + li] if count else np.zeros(0)
            extra = len(props) - 1
            with np.errstate(invalid="ignore"):  # nan and inf counts are caught here
                bad = ~np.isfinite(k) | (k != np.round(k)) | (counts != k + 1 + extra)
            if bad.any():
                f = int(np.flatnonzero(bad)[0])
                raise MeshFormatError(path, f"face {f} declares {vals[off[f] + li]:g} vertices "
                                      f"but has {int(counts[f]) - 1 - extra} indices",
                                      line=int(lines[f]) + first_line)
            sizes = k.astype(np.int64)
            idx = ragged_take(vals, off + li + 1, sizes)
            found = _color_columns(props)
            if found is not None:  # (a face's scalars: before the list, or after it)
                at = np.arange(len(props))
                shift = np.where(at > li, sizes[:, None], 0)
                table = vals[off[:, None] + at[None] + shift]
                face_colors = _linear_colors(path, table, found, "face")
            break
    return _finish(path, vertices, idx, sizes, normals, uv, colors, face_colors)


def read_points(path, data: bytes) -> dict:
    """The vertices of PLY bytes ``data`` as a point set: ``points`` ``(N, 3)``, and
    ``normals`` and ``colors`` (as stored: 0-255 for integer types, else as written; None
    where absent) -- any faces are ignored.

    Parameters
    ----------
    path : str or Path
        The file, named in errors.
    data : bytes
        Its contents.
    """
    fmt, elements, pos, first_line = _ply_header(path, data, points=True)
    table = None
    for name, count, props in elements:
        if name == "vertex":
            _vertex_columns(path, props)
            if fmt == "ascii":
                table = _ascii_vertex_table(path, data[pos:], elements, count, props,
                                            first_line)
            else:
                order = "<" if fmt == "binary_little_endian" else ">"
                table, _ = _binary_vertices(path, data, pos, count, props, order)
            names = [p[0] for p in props]
            cols, ncols, _ = _vertex_columns(path, props)
            ccols = next(([names.index(c) for c in trio] for trio in _COLOR_NAMES
                          if all(c in names for c in trio)), None)
            integer = ccols is not None and np.dtype(props[ccols[0]][2]).kind in "iu"
            return {"points": table[:, cols], "normals": table[:, ncols] if ncols else None,
                    "colors": table[:, ccols] if ccols else None, "integer_colors": integer}
        if fmt != "ascii":  # (an element before the vertices: skipped)
            if any(p[1] == "list" for p in props):
                raise MeshFormatError(path, f"element {name!r} with list properties before "
                                      "the vertices is not supported")
            pos += count * sum(np.dtype(p[2]).itemsize for p in props)
    raise MeshFormatError(path, "no 'vertex' element")  # (the header has one: unreachable)


def _ascii_vertex_table(path, body: bytes, elements, count: int, props, first_line: int):
    """The vertex element's rows of an ASCII PLY body (the elements before it skipped)."""
    text = normalize_whitespace(body)
    starts, ends = line_starts(text)
    keep = np.flatnonzero(ends > starts)
    before = 0
    for name, n, _ in elements:
        if name == "vertex":
            break
        before += n
    lines = keep[before:before + count]
    if len(lines) < count:
        raise MeshFormatError(path, f"truncated: the header promises {count} vertex lines, "
                              f"the file has {len(lines)}")
    blob = join_lines(text, starts, ends, lines)
    vals = parse_numbers(blob)
    counts = token_counts(blob, count)
    if vals is None or len(vals) != counts.sum():
        numeric_diagnose(path, text, starts, ends, lines, "vertex", first_line)
    bad = counts != len(props)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise MeshFormatError(path, f"vertex {i} has {int(counts[i])} values, the header "
                              f"declares {len(props)}", line=int(lines[i]) + first_line)
    return vals.reshape(count, len(props))


def write(mesh: Mesh, f, binary: bool) -> None:
    """Write ``mesh`` as PLY to the open file ``f``, binary little-endian or ASCII, with its
    file normals (``nx ny nz``) and vertex colours (``red green blue [alpha]``, uchar sRGB)
    where it has them.

    Parameters
    ----------
    mesh : Mesh
        What to write.
    f : file
        An open binary file.
    binary : bool
        Binary little-endian (else ASCII).
    """
    fmt = "binary_little_endian" if binary else "ascii"
    if int(mesh.face_sizes.max(initial=0)) > 255:
        raise GeometryError("PLY stores polygon sizes as uchar: faces of more than 255 "
                            "vertices cannot be written")
    table, fields = _vertex_table(mesh)
    props = "".join(f"property {'double' if kind == '<f8' else 'uchar'} {name}\n"
                    for name, kind in fields)
    f.write((f"ply\nformat {fmt} 1.0\ncomment glshade\nelement vertex {mesh.n_vertices}\n"
             f"{props}element face {mesh.n_faces}\nproperty list uchar int vertex_indices\n"
             "end_header\n").encode())
    if not binary:
        if len(fields) == 3:
            write_vertices(f, mesh.vertices, "")
        else:  # (normals and colours: each column as its type writes)
            columns = " ".join("%.17g" if kind == "<f8" else "%d" for _, kind in fields)
            cells = np.stack([table[name].astype(object) for name, _ in fields], 1)
            f.write(((columns + "\n") * len(table) % tuple(cells.ravel())).encode())
        write_faces(f, mesh, "", 0, with_count=True)
        return
    f.write(table.tobytes())
    sizes = mesh.face_sizes
    face_byte = mesh.face_offsets[:-1] * 4 + np.arange(mesh.n_faces)
    buf = np.zeros(mesh.n_faces + 4 * len(mesh.face_indices), np.uint8)
    buf[face_byte] = sizes
    corner_byte = np.repeat(face_byte + 1, sizes) + 4 * (
        np.arange(len(mesh.face_indices)) - np.repeat(mesh.face_offsets[:-1], sizes))
    buf[corner_byte[:, None] + np.arange(4)] = (
        mesh.face_indices.astype("<i4").view(np.uint8).reshape(-1, 4))
    f.write(buf.tobytes())


def _vertex_table(mesh: Mesh) -> tuple[np.ndarray, list[tuple[str, str]]]:
    """The vertex element as written: x y z (double), then the file's normals nx ny nz
    (double) where the mesh has them, then its colours red green blue [alpha] (uchar,
    sRGB-encoded: what the reader decodes) where it has them; and its fields, (name,
    numpy type) in order."""
    from .._srgb import linear_to_srgb

    fields = [(c, "<f8") for c in ("x", "y", "z")]
    normals = mesh.normals_from_file
    if normals is not None:
        fields += [(c, "<f8") for c in ("nx", "ny", "nz")]
    colors = mesh.colors
    channels = ("red", "green", "blue") + (
        ("alpha",) if colors is not None and (colors[:, 3] < 1).any() else ())
    if colors is not None:
        fields += [(c, "u1") for c in channels]
    table = np.empty(mesh.n_vertices, np.dtype(fields))
    for i, c in enumerate("xyz"):
        table[c] = mesh.vertices[:, i]
    if normals is not None:
        for i, c in enumerate(("nx", "ny", "nz")):
            table[c] = normals[:, i]
    if colors is not None:
        encoded = np.concatenate([linear_to_srgb(colors[:, :3]), colors[:, 3:]], 1)
        for i, c in enumerate(channels):
            table[c] = np.round(np.clip(encoded[:, i], 0, 1) * 255)
    return table, fields
