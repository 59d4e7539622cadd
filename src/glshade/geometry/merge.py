"""Merging and splitting vertices, winding faces consistently, and joining meshes.

Welding merges vertices that coincide; crease splitting duplicates vertices along sharp
edges so smooth shading keeps them. Both keep what follows the surface: file normals (the
first merged vertex's) and the exact analytic surface.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from ..errors import GeometryError, TopologyError
from .edges import orientation_flips
from .graph import component_labels
from .mesh import Mesh
from .tolerance import tol

__all__ = ["weld", "split_creases", "split_point_contacts", "oriented", "concatenate"]


def _with(mesh: Mesh, vertices, indices, offsets, normals=None, groups=None,
          uv=None, colors=None, face_colors=None) -> Mesh:
    out = Mesh.from_csr(vertices, indices, offsets, normals=normals,
                        groups=mesh.groups if groups is None else groups, name=mesh.name,
                        uv=uv, colors=colors, face_colors=face_colors)
    out.analytic = mesh.analytic
    out.materials, out.material_groups = mesh.materials, mesh.material_groups
    return out


def split_creases(mesh: Mesh, angle_deg: float = 30.0) -> Mesh:
    """Duplicate vertices along sharp edges, so smooth shading keeps creases.

    Two faces sharing an edge stay smooth across it when their normals differ by less than
    ``angle_deg``; corners of a vertex joined by smooth edges share one copy of it. Edges of
    more than two faces are creases.

    Parameters
    ----------
    mesh : Mesh
        The mesh.
    angle_deg : float
        Edges whose faces' normals differ by more than this many degrees stay sharp.
    """
    if not 0 <= angle_deg <= 180:
        raise GeometryError(f"angle_deg must be in [0, 180], got {angle_deg}")
    c0, c1 = mesh.edge_groups.pairs()
    f0, f1 = mesh.corner_face[c0], mesh.corner_face[c1]
    cos = np.einsum("ij,ij->i", mesh.face_normals[f0], mesh.face_normals[f1])
    smooth = cos >= np.cos(np.radians(angle_deg)) - 1e-12
    c0, c1 = c0[smooth], c1[smooth]
    # corners at the same vertex on both sides of the shared edge (the twin runs the other
    # way, or the same way where orientation is inconsistent)
    n0, n1 = mesh.corner_next[c0], mesh.corner_next[c1]
    same_dir = mesh.face_indices[c0] == mesh.face_indices[c1]
    a = np.concatenate([c0, n0])
    b = np.concatenate([np.where(same_dir, c1, n1), np.where(same_dir, n1, c1)])
    labels = component_labels(len(mesh.face_indices), a, b)
    uniq, corner_vertex = np.unique(labels, return_inverse=True)
    source = mesh.face_indices[uniq]
    normals = mesh.normals_from_file[source] if mesh.normals_from_file is not None else None
    return _with(mesh, mesh.vertices[source], corner_vertex.astype(np.int64),
                 mesh.face_offsets.copy(), normals, uv=mesh.uv,  # (the same corners)
                 colors=mesh.colors[source] if mesh.colors is not None else None,
                 face_colors=mesh.face_colors)


def dihedral_angles(mesh: Mesh) -> np.ndarray:
    """Degrees between the normals of the two faces at each edge two faces share (0: flat,
    90: a box's edge)."""
    c0, c1 = mesh.edge_groups.pairs()
    f0, f1 = mesh.corner_face[c0], mesh.corner_face[c1]
    cos = np.einsum("ij,ij->i", mesh.face_normals[f0], mesh.face_normals[f1])
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


#: the crease detector's bounds: angles under MIN_CREASE are a curved surface's facets (a
#: coarse torus of 12 x 8 turns 45 degrees an edge), and a gap in the angles must be
#: CREASE_GAP degrees wide to separate creases from them
MIN_CREASE, CREASE_GAP = 50.0, 15.0


def detect_crease(mesh: Mesh) -> float | None:
    """The crease angle a mesh's own edges suggest (degrees), or None for a smooth one:
    CAD-like parts have facet angles of a few degrees and hard edges of 90 or so; the
    threshold is the middle of the widest gap below a crease (one of MIN_CREASE or more),
    at least CREASE_GAP wide, and never under MIN_CREASE; MIN_CREASE where every angle is
    past it (a box)."""
    angles = np.sort(dihedral_angles(mesh))
    angles = angles[angles > 1e-3]  # (a polygon's triangulation: flat)
    if not len(angles) or angles[-1] < MIN_CREASE:
        return None
    if angles[0] >= MIN_CREASE:
        return MIN_CREASE
    gaps = np.diff(angles)
    above = angles[1:] >= MIN_CREASE
    k = int(np.argmax(np.where(above, gaps, -1.0)))
    if gaps[k] < CREASE_GAP:
        return None
    return float(max((angles[k] + angles[k + 1]) / 2, MIN_CREASE))


def split_point_contacts(mesh: Mesh) -> Mesh:
    """Give each piece of surface its own copy of a vertex where pieces only touch at that
    point (a handle's end resting on a body). Pieces are faces joined through shared edges;
    a vertex used by several pieces becomes one vertex per piece, so the surface stops
    being pinched there.

    Parameters
    ----------
    mesh : Mesh
        The mesh.
    """
    c0, c1 = mesh.edge_groups.pairs()
    piece = component_labels(mesh.n_faces, mesh.corner_face[c0], mesh.corner_face[c1])
    key = mesh.face_indices * max(mesh.n_faces, 1) + piece[mesh.corner_face]
    uniq, corner_vertex = np.unique(key, return_inverse=True)
    if len(uniq) == mesh.n_vertices:
        return mesh
    source = uniq // max(mesh.n_faces, 1)
    normals = mesh.normals_from_file[source] if mesh.normals_from_file is not None else None
    return _with(mesh, mesh.vertices[source], corner_vertex.ravel().astype(np.int64),
                 mesh.face_offsets.copy(), normals, uv=mesh.uv,
                 colors=mesh.colors[source] if mesh.colors is not None else None,
                 face_colors=mesh.face_colors)


def oriented(mesh: Mesh) -> Mesh:
    """A copy whose faces are wound consistently: neighbours traverse their shared edge
    in opposite directions. Each connected piece keeps the winding of its lowest-numbered
    face; a closed result is turned to face outward (positive volume). Raises
    TopologyError for a surface that cannot be oriented (a Moebius strip).

    Parameters
    ----------
    mesh : Mesh
        The mesh.
    """
    flip, orientable = orientation_flips(mesh.half_edges, mesh.corner_face, mesh.n_faces,
                                         mesh.n_vertices)
    if not orientable:
        raise TopologyError("the surface cannot be oriented (a Moebius strip or Klein "
                            "bottle is one-sided)")
    out = mesh._replace(mesh.vertices, flip=flip, normals=mesh.normals_from_file,
                        analytic=mesh.analytic)
    if out.closed_and_oriented and out.signed_volume() < 0:
        out = out._replace(out.vertices, flip=True, normals=out.normals_from_file,
                           analytic=out.analytic)
    return out


def weld(mesh: Mesh, tolerance: float | None = None) -> Mesh:
    """Merge vertices closer than ``tolerance`` (default: relative to the bounding box) and
    drop those no face uses; faces that collapse below 3 corners are removed (and from the
    named groups).

    Parameters
    ----------
    mesh : Mesh
        The mesh.
    tolerance : float or None
        The distance in scene units under which vertices merge (None: relative to the
        bounding box).
    """
    if tolerance is None:
        tolerance = tol.merge * max(np.sqrt(mesh._area_scale), 1e-300)
    q = np.round(mesh.vertices / tolerance).astype(np.int64)
    _, first, inverse = np.unique(q, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.ravel()
    idx = inverse[mesh.face_indices]
    # drop repeated consecutive corners (pole collapse), then faces with < 3 corners
    keep = idx != idx[mesh.corner_next]
    keep_count = np.bincount(mesh.corner_face[keep], minlength=mesh.n_faces)
    ok_face = keep_count >= 3
    keep &= ok_face[mesh.corner_face]
    offsets = np.zeros(int(ok_face.sum()) + 1, np.int64)
    np.cumsum(keep_count[ok_face], out=offsets[1:])
    vertices = mesh.vertices[first]
    used = np.zeros(len(vertices), bool)
    used[idx[keep]] = True
    remap = np.cumsum(used) - 1
    normals = None
    if mesh.normals_from_file is not None:
        normals = mesh.normals_from_file[first][used]
    face_number = np.cumsum(ok_face) - 1
    groups = {name: face_number[g[ok_face[g]]] for name, g in mesh.groups.items()}
    # (a welded vertex keeps the colour of the first of the vertices merged into it)
    out = _with(mesh, vertices[used], remap[idx[keep]], offsets, normals, groups,
                uv=mesh.uv[keep] if mesh.uv is not None else None,
                colors=mesh.colors[first][used] if mesh.colors is not None else None,
                face_colors=mesh.face_colors[ok_face] if mesh.face_colors is not None
                else None)
    out.material_groups = {name: face_number[g[ok_face[g]]]
                           for name, g in mesh.material_groups.items()}
    return out


def concatenate(meshes: Iterable[Mesh], names: Iterable[str] | None = None) -> Mesh:
    """Join meshes into one; with ``names`` each input becomes a named group of faces.
    Texture coordinates are kept where any input has them ((0, 0) for the corners of one
    that has none), colours likewise (white); material parts and their materials too.

    Parameters
    ----------
    meshes : iterable of Mesh
        The meshes, in order.
    names : iterable of str or None
        One group name a mesh (None: no groups).
    """
    meshes = list(meshes)
    labels: list[str | None] = list(names) if names is not None else [None] * len(meshes)
    if len(labels) != len(meshes):
        raise GeometryError(f"got {len(meshes)} meshes but {len(labels)} names")
    vert, idx, sizes, groups = [], [], [], {}
    parts: dict = {}
    materials: dict = {}
    v0 = f0 = 0
    for m, name in zip(meshes, labels):
        vert.append(m.vertices)
        idx.append(m.face_indices + v0)
        sizes.append(m.face_sizes)
        if name is not None:
            groups[name] = np.arange(f0, f0 + m.n_faces)
        for gname, g in m.groups.items():
            groups[f"{name}/{gname}" if name else gname] = g + f0
        for part, g in m.material_groups.items():
            old = parts.get(part)
            parts[part] = g + f0 if old is None else np.concatenate([old, g + f0])
        materials.update(m.materials)
        v0 += m.n_vertices
        f0 += m.n_faces
    size = np.concatenate(sizes) if sizes else np.zeros(0, np.int64)
    offsets = np.zeros(len(size) + 1, np.int64)
    np.cumsum(size, out=offsets[1:])
    uv = None
    if any(m.uv is not None for m in meshes):
        uv = np.concatenate([m.uv if m.uv is not None else np.zeros((len(m.face_indices), 2))
                             for m in meshes])
    # (colours where any input has them: white for one that has none)
    colors = face_colors = None
    if any(m.colors is not None for m in meshes):
        colors = np.concatenate([m.colors if m.colors is not None else
                                 np.ones((m.n_vertices, 4)) for m in meshes])
    if any(m.face_colors is not None for m in meshes):
        face_colors = np.concatenate([m.face_colors if m.face_colors is not None else
                                      np.ones((m.n_faces, 4)) for m in meshes])
    out = Mesh.from_csr(
        np.concatenate(vert) if vert else np.zeros((0, 3)),
        np.concatenate(idx) if idx else np.zeros(0, np.int64),
        offsets,
        groups=groups, uv=uv, colors=colors, face_colors=face_colors,
    )
    out.material_groups, out.materials = parts, materials
    return out
