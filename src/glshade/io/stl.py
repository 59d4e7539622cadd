"""STL: ascii and binary triangles. Every triangle repeats its corners, so the corners are
welded on load (bit-identical points become one vertex)."""

from __future__ import annotations

import re

import numpy as np

from ..errors import MeshFormatError
from ..geometry.mesh import Mesh
from ._common import build_mesh
from .text import parse_numbers

__all__ = ["read", "write"]

_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])
_STL_VERTEX = re.compile(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)")


def _weld_exact(path, triangles: np.ndarray) -> Mesh:
    """Merge bit-identical corners (STL repeats every vertex once per triangle)."""
    flat = np.ascontiguousarray(triangles.reshape(-1, 3).astype(np.float64))
    flat[flat == 0] = 0.0  # -0.0 and 0.0 are the same point
    key = flat.view(np.dtype((np.void, 24))).ravel()
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    return build_mesh(path, flat[first], inverse.ravel().astype(np.int64),
                  np.arange(len(triangles) + 1, dtype=np.int64) * 3)


def read(path, data: bytes) -> Mesh:
    """The Mesh in STL bytes ``data``, ASCII or binary (``path`` names it in errors).

    Parameters
    ----------
    path : str or Path
        The file, named in errors.
    data : bytes
        Its contents.
    """
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


def write(mesh: Mesh, f, binary: bool) -> None:
    """Write ``mesh`` as STL to the open file ``f``, binary or ASCII (polygons triangulated).

    Parameters
    ----------
    mesh : Mesh
        What to write.
    f : file
        An open binary file.
    binary : bool
        Binary (else ASCII).
    """
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
