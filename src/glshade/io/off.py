"""OFF (Object File Format): a header, vertex lines and face lines with their sizes. Comments
(``#``) are allowed anywhere."""

from __future__ import annotations

import re

import numpy as np

from ..errors import MeshFormatError
from ..geometry.mesh import Mesh
from ..scene.texture import srgb_to_linear
from ._common import (
    COMMENT, build_mesh, join_lines, numeric_diagnose, offsets_from_sizes, write_faces,
    write_vertices,
)
from .text import line_starts, normalize_whitespace, parse_numbers, ragged_take, token_counts

__all__ = ["read", "write"]

def read(path, data: bytes) -> Mesh:
    """The Mesh in OFF bytes ``data`` (``path`` names it in errors: file and line).

    Parameters
    ----------
    path : str or Path
        The file, named in errors.
    data : bytes
        Its contents.
    """
    if b"#" in data:
        data = COMMENT.sub(b"", data)
    text = normalize_whitespace(data)
    # drop blank lines but remember the original line numbers
    starts, ends = line_starts(text)
    keep = np.flatnonzero(ends > starts)
    if len(keep) == 0:
        raise MeshFormatError(path, "the file is empty")
    first = text[starts[keep[0]]:ends[keep[0]]].split()
    header, rest, pos, normals = _header(path, first)
    keyword = _KEYWORD.fullmatch(header) if header else None
    texture_words = bool(keyword and keyword.group(1))  # (STOFF: s t last on a vertex line)
    color_words = bool(keyword and keyword.group(2))    # (COFF: a colour on each)
    if len(rest) < 2:
        if len(keep) < pos + 1:
            raise MeshFormatError(path, "missing the 'vertices faces edges' counts line")
        rest = text[starts[keep[pos]]:ends[keep[pos]]].split()
        pos += 1
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
    vblob = join_lines(text, starts, ends, vl)
    vals = parse_numbers(vblob)
    vcount = token_counts(vblob, nv)
    if vals is None or len(vals) != vcount.sum():
        numeric_diagnose(path, text, starts, ends, vl, "vertex")
    bad = vcount < 3
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise MeshFormatError(path, f"vertex {i} has {int(vcount[i])} numbers, expected 3",
                              line=int(vl[i]) + 1)
    vertex_start = offsets_from_sizes(vcount)[:-1]
    vertices = ragged_take(vals, vertex_start, np.full(nv, 3)).reshape(-1, 3)
    vertex_normals = None
    if normals and nv and (vcount >= 6).all():  # NOFF: x y z nx ny nz [colour] [s t]
        vertex_normals = ragged_take(vals, vertex_start + 3, np.full(nv, 3)).reshape(-1, 3)
    fblob = join_lines(text, starts, ends, fl)
    fvals = parse_numbers(fblob)
    fcount = token_counts(fblob, nf)
    if fvals is None or len(fvals) != fcount.sum():
        numeric_diagnose(path, text, starts, ends, fl, "face")
    line_off = offsets_from_sizes(fcount)[:-1]
    k = fvals[line_off] if nf else np.zeros(0)
    with np.errstate(invalid="ignore"):  # nan and inf counts are caught here
        bad = ~np.isfinite(k) | (k != np.round(k)) | (k < 0) | (fcount < k + 1)
    if bad.any():
        f = int(np.flatnonzero(bad)[0])
        raise MeshFormatError(path, f"face {f} says it has {fvals[line_off[f]]:g} vertices but "
                              f"lists {int(fcount[f]) - 1} numbers", line=int(fl[f]) + 1)
    k = k.astype(np.int64)
    idx = ragged_take(fvals, line_off + 1, k)
    colors = face_colors = None
    if color_words and nv:  # COFF: x y z [nx ny nz] r g b [a] [s t]
        at = 3 + 3 * (vertex_normals is not None)
        width = vcount - at - 2 * texture_words
        colors = _colors(path, vals, vertex_start + at, width, "vertex", vl)
    extra = fcount - 1 - k  # (a face's colour after its indices: r g b [a])
    if nf and (extra >= 3).all():
        face_colors = _colors(path, fvals, line_off + 1 + k, extra, "face", fl)
    return build_mesh(path, vertices, idx, offsets_from_sizes(k),
                      line_of_face=lambda f: int(fl[f]) + 1,
                      line_of_vertex=lambda i: int(vl[i]) + 1, normals=vertex_normals,
                      colors=colors, face_colors=face_colors)


def _colors(path, vals, start, width, what: str, lines):
    """``(N, 4)`` linear RGBA of OFF colour columns (3 or 4 numbers at ``start``): 0-255
    bytes, sRGB-encoded, where any number of the file's colours is above 1, else linear
    floats in [0, 1]."""
    bad = (width != 3) & (width != 4)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise MeshFormatError(path, f"{what} {i} has {int(width[i])} colour numbers, expected "
                              "r g b or r g b a", line=int(lines[i]) + 1)
    rgba = np.ones((len(start), 4))
    rgba[:, :3] = vals[start[:, None] + np.arange(3)]
    four = width == 4
    rgba[four, 3] = vals[start[four] + 3]
    bytes_ = (rgba > 1).any()
    top = 255.0 if bytes_ else 1.0
    bad = ~(np.isfinite(rgba) & (rgba >= 0) & (rgba <= top)).all(1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise MeshFormatError(path, f"{what} {i} has colour {rgba[i].tolist()}: colours lie "
                              "in 0-1 (floats) or 0-255 (bytes)", line=int(lines[i]) + 1)
    if bytes_:
        rgba[:, :3] = srgb_to_linear(rgba[:, :3] / 255.0)
        rgba[:, 3] = np.where(four, rgba[:, 3] / 255.0, 1.0)
    return rgba


#: the keyword's optional prefixes: texture coordinates, colours, normals, 4-D, n-D
_KEYWORD = re.compile(rb"(ST)?(C)?(N)?(4)?(n)?OFF")


def _is_number(token: bytes) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _header(path, first: list[bytes]):
    """The keyword line: ``(keyword, tokens after it, lines used, has normals)``. The
    keyword is optional (the counts line may come first); a 4-D or n-D file other than
    3-D, and binary OFF, are refused by name rather than misread."""
    if _is_number(first[0]):
        return b"", [], 0, False
    m = _KEYWORD.fullmatch(first[0])
    word = first[0].decode(errors="replace")
    if not m:
        raise MeshFormatError(path, f"not an OFF file: the first word is {word!r}, expected "
                              "'OFF' (or [ST][C][N][4][n]OFF) or the counts line", line=1)
    rest = first[1:]
    if m.group(4):
        raise MeshFormatError(path, f"{word} holds 4-D vertices; glshade reads 3-D meshes "
                              "(project them to 3-D first)", line=1)
    if m.group(5):
        if not rest or not rest[0].isdigit():
            raise MeshFormatError(path, f"{word} needs the dimension after it", line=1)
        if int(rest[0]) != 3:
            raise MeshFormatError(path, f"{word} {int(rest[0])}: {int(rest[0])}-D vertices; "
                                  "glshade reads 3-D meshes", line=1)
        rest = rest[1:]
    if rest and rest[0].upper() == b"BINARY":
        raise MeshFormatError(path, "binary OFF is not supported; write it as text OFF or PLY",
                              line=1)
    return first[0], rest, 1, bool(m.group(3))



def write(mesh: Mesh, f, binary: bool) -> None:
    """Write ``mesh`` as OFF to the open file ``f`` (text; ``binary`` is ignored).

    Parameters
    ----------
    mesh : Mesh
        What to write.
    f : file
        An open binary file.
    binary : bool
        Ignored: OFF is text here.
    """
    f.write(f"OFF\n{mesh.n_vertices} {mesh.n_faces} {mesh.n_edges}\n".encode())
    write_vertices(f, mesh.vertices, "")
    write_faces(f, mesh, "", 0, with_count=True)
