"""Primitive meshes, each with consistent outward orientation (counter-clockwise seen from
outside) and y up. Polygons are kept: a cube is six quads, a cylinder's caps are n-gons.
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError
from .analytic import AnalyticSphere
from .edges import edge_groups
from .merge import concatenate, split_point_contacts
from .mesh import Mesh

__all__ = [
    "cube", "box", "uv_sphere", "icosphere", "torus", "cylinder", "plane", "cornell_box",
    "cornell_parts", "teapot", "voxels", "PRIMITIVES", "from_spec",
]


#: the most faces a primitive makes (a level beyond it would exhaust memory, not refine)
MAX_FACES = 4 * 2**20


def _check_int(name: str, value, minimum: int, maximum: int = 2**20) -> int:
    try:
        ok = np.isfinite(value) and int(value) == value and minimum <= value <= maximum
    except (TypeError, ValueError, OverflowError):
        ok = False
    if not ok:
        raise GeometryError(f"{name} must be an integer from {minimum} to {maximum}, got "
                            f"{value!r}")
    return int(value)


def _check_faces(what: str, count: int) -> None:
    if count > MAX_FACES:
        raise GeometryError(f"{what} would make {count:,} faces; primitives stop at "
                            f"{MAX_FACES:,}")


def box(size=(1.0, 1.0, 1.0), center=(0.0, 0.0, 0.0)) -> Mesh:
    """An axis-aligned box of six quads.

    Parameters
    ----------
    size : float or (float, float, float)
        Edge lengths along x, y, z (scene units).
    center : (float, float, float)
        The box's centre.
    """
    s = np.asarray(size, float) / 2
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    quads = [
        [0, 1, 3, 2],  # -x
        [4, 6, 7, 5],  # +x
        [0, 4, 5, 1],  # -y
        [2, 3, 7, 6],  # +y
        [0, 2, 6, 4],  # -z
        [1, 5, 7, 3],  # +z
    ]
    return Mesh(corners * s + np.asarray(center, float), quads, name="box",
                uv=np.tile(_QUAD_UV, (6, 1)))


#: a quad's corners' texture coordinates: the whole image, counter-clockwise
_QUAD_UV = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


def cube() -> Mesh:
    """The unit cube ``[-0.5, 0.5]^3``: 8 vertices, 6 quads, volume 1."""
    m = box()
    m.name = "cube"
    return m


def uv_sphere(stacks: int = 16, slices: int = 32, radius: float = 1.0) -> Mesh:
    """A latitude/longitude sphere: quads, with triangle fans at the poles (y axis).

    Parameters
    ----------
    stacks : int
        Bands from pole to pole, >= 2.
    slices : int
        Segments around the y axis, >= 3.
    radius : float
        The sphere's radius.
    """
    stacks = _check_int("stacks", stacks, 2)
    slices = _check_int("slices", slices, 3)
    _check_faces(f"uv_sphere({stacks}, {slices})", stacks * slices)
    theta = np.pi * np.arange(1, stacks) / stacks  # polar angle of the inner rings
    phi = 2 * np.pi * np.arange(slices) / slices
    t, p = np.meshgrid(theta, phi, indexing="ij")
    ring = np.stack([np.sin(t) * np.sin(p), np.cos(t), np.sin(t) * np.cos(p)], -1).reshape(-1, 3)
    v = np.vstack([[0, 1, 0], ring, [0, -1, 0]]) * radius
    south = len(v) - 1
    r = np.arange(stacks - 2)[:, None]
    s = np.arange(slices)[None, :]
    s1 = (s + 1) % slices
    a = 1 + r * slices + s
    b = 1 + r * slices + s1
    quads = np.stack([a, a + slices, b + slices, b], -1).reshape(-1, 4)
    top = np.stack([np.zeros(slices, int), 1 + s[0], 1 + s1[0]], -1)
    last = 1 + (stacks - 2) * slices
    bottom = np.stack([np.full(slices, south), last + s1[0], last + s[0]], -1)
    faces = [*top.tolist(), *quads.tolist(), *bottom.tolist()]
    # texture: u the longitude (0 at +z, growing towards +x), v the latitude (1 at the
    # north pole); a pole's corner takes its triangle's middle longitude
    u0, u1 = s[0] / slices, (s[0] + 1) / slices
    lat = 1 - np.arange(1, stacks) / stacks
    top_uv = np.stack([np.stack([(u0 + u1) / 2, np.ones(slices)], -1),
                       np.stack([u0, np.full(slices, lat[0])], -1),
                       np.stack([u1, np.full(slices, lat[0])], -1)], 1)
    qu0, qu1 = np.broadcast_to(u0, (stacks - 2, slices)), np.broadcast_to(u1, (stacks - 2, slices))
    la, lb = np.broadcast_to(lat[:-1, None], qu0.shape), np.broadcast_to(lat[1:, None], qu0.shape)
    quad_uv = np.stack([np.stack([qu0, la], -1), np.stack([qu0, lb], -1),
                        np.stack([qu1, lb], -1), np.stack([qu1, la], -1)], 2)
    bottom_uv = np.stack([np.stack([(u0 + u1) / 2, np.zeros(slices)], -1),
                          np.stack([u1, np.full(slices, lat[-1])], -1),
                          np.stack([u0, np.full(slices, lat[-1])], -1)], 1)
    uv = np.concatenate([top_uv.reshape(-1, 2), quad_uv.reshape(-1, 2),
                         bottom_uv.reshape(-1, 2)])
    m = Mesh(v, faces, name="uv_sphere", uv=uv)
    m.analytic = AnalyticSphere(radius)
    return m


_ICO_T = (1 + 5**0.5) / 2
_ICO_V = np.array([
    [-1, _ICO_T, 0], [1, _ICO_T, 0], [-1, -_ICO_T, 0], [1, -_ICO_T, 0],
    [0, -1, _ICO_T], [0, 1, _ICO_T], [0, -1, -_ICO_T], [0, 1, -_ICO_T],
    [_ICO_T, 0, -1], [_ICO_T, 0, 1], [-_ICO_T, 0, -1], [-_ICO_T, 0, 1],
])
_ICO_F = np.array([
    [0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11],
    [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
    [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
    [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1],
])


def icosphere(subdivisions: int = 3, radius: float = 1.0) -> Mesh:
    """A sphere of triangles from a subdivided icosahedron; every vertex lies on the sphere.

    Level k has ``20 * 4**k`` triangles.

    Parameters
    ----------
    subdivisions : int
        Times each triangle is split in four, >= 0.
    radius : float
        The sphere's radius.
    """
    subdivisions = _check_int("subdivisions", subdivisions, 0, 8)  # 8: 1.3M triangles
    v = _ICO_V / np.linalg.norm(_ICO_V, axis=1, keepdims=True)
    f = _ICO_F.copy()
    for _ in range(subdivisions):
        e = np.stack([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], 1).reshape(-1, 2)
        g = edge_groups(e[:, 0], e[:, 1], len(v))
        inv = g.group
        mid = v[g.lo] + v[g.hi]
        mid /= np.linalg.norm(mid, axis=1, keepdims=True)
        m = (len(v) + inv).reshape(-1, 3)  # midpoints of edges (01, 12, 20) per face
        v = np.vstack([v, mid])
        a, b, c = f.T
        ab, bc, ca = m.T
        f = np.stack([
            np.stack([a, ab, ca], 1), np.stack([b, bc, ab], 1),
            np.stack([c, ca, bc], 1), np.stack([ab, bc, ca], 1),
        ], 1).reshape(-1, 3)
    sphere = Mesh(v * radius, f, name="icosphere")
    sphere.analytic = AnalyticSphere(radius)
    return sphere


def torus(R: float = 1.0, r: float = 0.35, n: int = 32, m: int = 16) -> Mesh:
    """A ring torus of quads around the y axis: ``n`` segments around, ``m`` across.

    Parameters
    ----------
    R : float
        Distance from the y axis to the tube's centre.
    r : float
        The tube's radius, below ``R`` (a ring torus).
    n : int
        Segments around the y axis, >= 3.
    m : int
        Segments around the tube, >= 3.
    """
    n = _check_int("n", n, 3)
    m = _check_int("m", m, 3)
    _check_faces(f"torus with n={n}, m={m}", n * m)
    if not 0 < r < R:
        raise GeometryError(f"need 0 < r < R for a ring torus, got R={R}, r={r}")
    u = 2 * np.pi * np.arange(n) / n
    w = 2 * np.pi * np.arange(m) / m
    uu, ww = np.meshgrid(u, w, indexing="ij")
    rho = R + r * np.cos(ww)
    v = np.stack([rho * np.cos(uu), r * np.sin(ww), -rho * np.sin(uu)], -1).reshape(-1, 3)
    i = np.arange(n)[:, None]
    j = np.arange(m)[None, :]
    i1, j1 = (i + 1) % n, (j + 1) % m
    quads = np.stack([i * m + j, i1 * m + j, i1 * m + j1, i * m + j1], -1).reshape(-1, 4)
    # texture: u around the ring, v around the tube (each from 0 to 1 once)
    a, b = np.broadcast_to(i / n, (n, m)), np.broadcast_to(j / m, (n, m))
    a1, b1 = a + 1 / n, b + 1 / m
    uv = np.stack([np.stack([a, b], -1), np.stack([a1, b], -1), np.stack([a1, b1], -1),
                   np.stack([a, b1], -1)], 2).reshape(-1, 2)
    return Mesh(v, quads, name="torus", uv=uv)


def cylinder(n: int = 32, radius: float = 1.0, height: float = 2.0) -> Mesh:
    """A closed cylinder along y: ``n`` side quads and two n-gon caps.

    Parameters
    ----------
    n : int
        Side quads around the axis, >= 3.
    radius : float
        The radius.
    height : float
        Its length along y, centred at the origin.
    """
    n = _check_int("n", n, 3)
    a = 2 * np.pi * np.arange(n) / n
    ring = np.stack([radius * np.sin(a), np.zeros(n), radius * np.cos(a)], 1)
    h = height / 2
    v = np.vstack([ring + [0, -h, 0], ring + [0, h, 0]])
    i = np.arange(n)
    i1 = (i + 1) % n
    sides = np.stack([i, i1, n + i1, n + i], 1).tolist()
    top = (n + i).tolist()
    bottom = i[::-1].tolist()
    return Mesh(v, [*sides, top, bottom], name="cylinder")


def plane(size: float = 2.0) -> Mesh:
    """One square quad in the xy plane, centred at the origin, facing +z.

    Parameters
    ----------
    size : float
        The square's edge length.
    """
    s = size / 2
    return Mesh([[-s, -s, 0], [s, -s, 0], [s, s, 0], [-s, s, 0]], [[0, 1, 2, 3]], name="plane",
                uv=_QUAD_UV)


#: Diffuse colours of the Cornell box's parts (linear RGB).
def cornell_parts() -> dict[str, Mesh]:
    """The Cornell box's parts from its published measurements (millimetres,
    :mod:`glshade.geometry.data.cornell`), each a Mesh of quads: walls face into the room,
    the blocks outward, the light down."""
    from .data.cornell import CENTER, CORNELL_PARTS, LIGHT_DROP

    out = {}
    for name, quads in CORNELL_PARTS.items():
        q = np.array(quads, dtype=np.float64)
        if name == "light":
            q[..., 1] -= LIGHT_DROP
        v = q.reshape(-1, 3)
        f = np.arange(len(v)).reshape(-1, 4)
        n = np.cross(q[:, 2] - q[:, 0], q[:, 3] - q[:, 1])  # (diagonals: planar quads)
        if name.endswith("block"):
            toward = q.mean(1) - q.reshape(-1, 3).mean(0)  # outward from the block
        elif name == "light":
            toward = np.tile([0.0, -1.0, 0.0], (len(q), 1))
        else:
            toward = np.asarray(CENTER) - q.mean(1)  # into the room
        flip = np.einsum("ij,ij->i", n, toward) < 0
        f[flip] = f[flip][:, ::-1]
        out[name] = Mesh(v, f, name=name).weld()
    return out


def cornell_box() -> Mesh:
    """The published Cornell box (millimetres) as one mesh, each part a named group; the
    radiosity chapter's materials and camera are in :mod:`glshade.radiosity.cornell`."""
    parts = cornell_parts()
    m = concatenate(parts.values(), parts.keys())
    m.name = "cornell_box"
    return m


def _bernstein(t: np.ndarray) -> np.ndarray:
    """Cubic Bernstein basis ``(len(t), 4)``."""
    s = 1 - t
    return np.stack([s**3, 3 * t * s**2, 3 * t**2 * s, t**3], 1)


def teapot(tessellation: int = 8) -> Mesh:
    """The Utah teapot from Newell's 32 Bezier patches, ``tessellation`` quads per patch
    side, welded along patch seams; y up, resting on y = 0.

    Parameters
    ----------
    tessellation : int
        Quads a patch side, >= 1.
    """
    from .data.teapot import control_nets

    k = _check_int("tessellation", tessellation, 1, 256)
    nets = control_nets()  # (32, 4, 4, 3), y up
    b = _bernstein(np.linspace(0, 1, k + 1))  # (k+1, 4)
    # surface points of every patch at once: (32, k+1, k+1, 3)
    pts = np.einsum("ui,vj,pijc->puvc", b, b, nets)
    n_per = (k + 1) ** 2
    i = np.arange(k)[:, None]
    j = np.arange(k)[None, :]
    local = np.stack([i * (k + 1) + j, (i + 1) * (k + 1) + j,
                      (i + 1) * (k + 1) + j + 1, i * (k + 1) + j + 1], -1).reshape(-1, 4)
    quads = (local[None] + n_per * np.arange(len(nets))[:, None, None]).reshape(-1, 4)
    v = pts.reshape(-1, 3)
    m = Mesh(v, quads)
    # The patch data winds the body one way and the rest the other: take each patch's
    # orientation from its agreement with the outward direction of its points.
    per_patch = k * k
    normal = m.face_normals.reshape(len(nets), per_patch, 3)
    out = (m.face_centroids - [0, 1.2, 0]).reshape(len(nets), per_patch, 3)
    agree = np.einsum("pfc,pfc->p", normal, out)
    q = quads.reshape(len(nets), per_patch, 4)
    q = np.where((agree < 0)[:, None, None], q[..., ::-1], q).reshape(-1, 4)  # type: ignore[assignment]
    # weld the patch seams; the handle's and spout's ends touch the body at single points,
    # which welding would pinch together: those pieces keep their own vertices there
    welded = split_point_contacts(Mesh(v, q).weld(1e-6))
    welded.name = "teapot"
    return welded


def voxels(occupancy, size: float = 1.0) -> Mesh:
    """The boundary of a union of unit cubes as quads (outward), for solids of any genus:
    ``occupancy`` is a boolean ``(nx, ny, nz)`` array; cell (i, j, k) spans
    ``[i, i+1] x [j, j+1] x [k, k+1]`` times ``size``. Cubes touching only along an edge
    give a non-manifold surface.

    Parameters
    ----------
    occupancy : array_like
        ``(nx, ny, nz)`` bool: the cells that are solid.
    size : float
        A cell's edge length.
    """
    occ = np.pad(np.asarray(occupancy, dtype=bool), 1)
    shape = np.array(occ.shape) + 1  # lattice points
    quads = []

    def lattice(i, j, k):
        return (i * shape[1] + j) * shape[2] + k

    corners = {  # unit-square corners for a face normal to each axis, counter-clockwise
        0: [(0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)],
        1: [(0, 0, 0), (0, 0, 1), (1, 0, 1), (1, 0, 0)],
        2: [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)],
    }
    for axis in range(3):
        a = np.take(occ, range(occ.shape[axis] - 1), axis=axis)
        b = np.take(occ, range(1, occ.shape[axis]), axis=axis)
        for filled_first in (True, False):
            where = np.argwhere((a & ~b) if filled_first else (~a & b))
            base = where.copy()
            base[:, axis] += 1  # the face between cell and cell + 1
            q = np.stack([lattice(*(base + off).T) for off in np.array(corners[axis])], 1)
            quads.append(q if filled_first else q[:, ::-1])
    q = np.concatenate(quads)
    i, j, k = np.unravel_index(np.arange(np.prod(shape)), tuple(shape))
    pts = (np.stack([i, j, k], 1) - 1) * size
    used, remap = np.unique(q, return_inverse=True)
    return Mesh(pts[used].astype(float), remap.reshape(q.shape), name="voxels")


PRIMITIVES = {
    "cube": cube, "box": box, "uv_sphere": uv_sphere, "icosphere": icosphere,
    "torus": torus, "cylinder": cylinder, "plane": plane, "cornell_box": cornell_box,
    "teapot": teapot,
}


def from_spec(spec: str) -> Mesh:
    """Build a primitive from text: ``"icosphere"``, ``"icosphere:3"``, ``"torus:1,0.3"``.

    A leading ``primitive:`` is accepted. Arguments are numbers, comma-separated.

    Parameters
    ----------
    spec : str
        ``NAME`` or ``NAME:ARGS`` (numbers, comma-separated), optionally after ``primitive:``.
    """
    text = spec.removeprefix("primitive:")
    name, _, args = text.partition(":")
    if name not in PRIMITIVES:
        raise GeometryError(
            f"unknown primitive {name!r}; choose one of {', '.join(sorted(PRIMITIVES))}"
        )
    values = []
    for a in filter(None, args.split(",")):
        try:
            values.append(int(a) if a.strip().lstrip("-").isdigit() else float(a))
        except ValueError:
            raise GeometryError(
                f"primitive argument {a!r} in {spec!r} is not a number "
                f"(example: primitive:icosphere:3)"
            ) from None
    try:
        return PRIMITIVES[name](*values)
    except TypeError as exc:
        raise GeometryError(f"bad arguments for primitive {name!r}: {exc}") from None
