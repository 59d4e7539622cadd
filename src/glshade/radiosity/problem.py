"""A scene as a radiosity problem: its polygons cut into patches, each with the emission E
and the diffuse reflectance rho of its model's material (RGB)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from .patches import Patches, subdivide
from ..scene import Scene

__all__ = ["PatchScene", "concatenate_patches", "without_zero_area"]


def concatenate_patches(parts: list[Patches]) -> Patches:
    """One Patches of several (vertex and patch indices shifted).

    Parameters
    ----------
    parts : list of Patches
        In order.
    """
    v_off = np.cumsum([0] + [len(p.vertices) for p in parts])
    p_off = np.cumsum([0] + [p.n_patches for p in parts])
    return Patches(
        np.concatenate([p.vertices for p in parts]),
        np.concatenate([p.triangles + v_off[i] for i, p in enumerate(parts)]),
        np.concatenate([p.triangle_patch + p_off[i] for i, p in enumerate(parts)]),
        np.concatenate([p.source for p in parts]),
        np.concatenate([p.centers for p in parts]),
        np.concatenate([p.normals for p in parts]),
        np.concatenate([p.areas for p in parts]),
        np.concatenate([np.where(p.corners >= 0, p.corners + v_off[i], -1)
                        for i, p in enumerate(parts)]),
        sum(p.split for p in parts))


#: the most patches a solve takes (each costs memory for its form-factor row, its
#: quadrature points and its display); about 1,300 make the Cornell box at 50 mm
MAX_PATCHES = 200_000
#: a patch's share of the memory a solve needs, for the estimate in the refusal (bytes)
BYTES_PER_PATCH = 4096
#: a polygon whose area is below this fraction of the scene's diagonal squared has none
ZERO_AREA = 1e-12


def polygon_extents(mesh) -> np.ndarray:
    """``(F,)`` each polygon's largest distance from its first corner (about its longest
    side): what the number of its patches follows."""
    if mesh.n_faces == 0:
        return np.zeros(0)
    lo, hi = mesh.face_offsets[:-1], mesh.face_offsets[1:]
    first = mesh.vertices[mesh.face_indices[lo]]
    longest = np.zeros(mesh.n_faces)
    for k in range(int((hi - lo).max())):  # (per corner position: a handful of passes)
        has = lo + k < hi
        idx = np.where(has, lo + k, lo)
        d = np.linalg.norm(mesh.vertices[mesh.face_indices[idx]] - first, axis=1)
        longest = np.maximum(longest, np.where(has, d, 0.0))
    return longest


def estimated_patches(mesh, patch_size: float) -> float:
    """About how many patches ``mesh`` is cut into at ``patch_size``, from its polygons'
    extents, before anything is allocated (an upper estimate: a square grid per polygon)."""
    per_side = np.maximum(np.ceil(polygon_extents(mesh) / patch_size), 1.0)
    return float(np.square(per_side).sum())


def without_zero_area(mesh, name: str, diagonal: float):
    """``mesh`` without the polygons of (relatively) zero area, which can neither give nor
    receive light (an emitter of zero area would count as one; a receiver's radiosity is
    divided by its area); dropped with a warning.

    Parameters
    ----------
    mesh : Mesh
        The model's mesh.
    name : str
        Its name, for the message.
    diagonal : float
        The scene's diagonal, the scale of "zero".
    """
    area = mesh.face_areas
    zero = area <= ZERO_AREA * diagonal ** 2
    if not zero.any():
        return mesh, ""
    note = (f"{name}: {int(zero.sum())} of its {mesh.n_faces} polygons have no area "
            "(collinear or repeated corners) and are left out")
    from ..geometry.mesh import Mesh

    keep = np.flatnonzero(~zero)
    sizes = np.diff(mesh.face_offsets)[keep]
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    # (the kept faces' index runs, gathered at once: their old starts, shifted to the new)
    at = np.repeat(mesh.face_offsets[keep] - offsets[:-1], sizes) + np.arange(offsets[-1])
    return Mesh.from_csr(mesh.vertices, mesh.face_indices[at], offsets, name=mesh.name), note


@dataclass
class PatchScene:
    """Patches in world space with ``emission`` and ``rho`` (P, 3), the ``model`` (P,) each
    came from and the models' ``names``.

    Parameters
    ----------
    patches : Patches
        Every model's patches in world space.
    emission : ndarray
        ``(P, 3)`` radiosity each patch gives off by itself.
    rho : ndarray
        ``(P, 3)`` diffuse reflectance.
    model : ndarray
        ``(P,)`` the model each came from.
    names : list of str
        The models' names.
    patch_size : float
        The patch size used.
    meshes : list
        The models' world meshes.
    """

    patches: Patches
    emission: np.ndarray
    rho: np.ndarray
    model: np.ndarray
    names: list[str]
    patch_size: float
    #: the models' polygons in world space, as they were cut (what a ray tracer of the same
    #: problem meets: :mod:`glshade.radiosity.montecarlo`)
    meshes: list = field(default_factory=list, repr=False)

    @property
    def n_patches(self) -> int:
        return self.patches.n_patches

    @property
    def closed(self) -> bool:
        """Whether the models' polygons, their vertices welded, close a surface facing in
        (a room with no opening: light that leaves a patch meets another; a closed surface
        facing out sends its light away)."""
        from ..geometry.merge import concatenate, weld

        if not self.meshes:
            return False
        mesh = weld(concatenate(self.meshes))
        if not mesh.closed_and_oriented:
            return False
        tri, _ = mesh.triangles
        v = mesh.vertices[tri]
        volume = np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6
        return bool(volume < 0)  # (normals in: the signed volume is negative)

    @classmethod
    def from_scene(cls, scene: Scene, patch_size: float | None = None) -> PatchScene:
        """Cut every visible model of ``scene`` into patches of about ``patch_size``
        (default: a 24th of the scene's diagonal). A scene with nothing emitting, or a
        reflectance above 1, is refused with the model named.

        Parameters
        ----------
        scene : Scene
            The models (emission and reflectance from their materials).
        patch_size : float or None
            About how long a patch's edge is (None: a 24th of the scene's diagonal).
        """
        models = [(i, m) for i, m in enumerate(scene.models) if m.visible]
        if not models:
            raise InputError("radiosity needs a scene with at least one visible mesh")
        solids = [str(s.name) for s in scene.solids if s.visible]
        if solids:
            import warnings

            warnings.warn(f"the scene's CSG solids ({', '.join(solids)}) are not polygons: "
                          "radiosity leaves them out (they neither block, receive nor give "
                          "light, and are not drawn)", UserWarning, stacklevel=2)
        if patch_size is None:
            b = scene.bounds
            patch_size = float(np.linalg.norm(b[1] - b[0])) / 24
        if not np.isfinite(patch_size) or patch_size <= 0:
            raise InputError(f"patch size must be a positive number, got {patch_size!r}")
        b = scene.bounds
        diagonal = float(np.linalg.norm(b[1] - b[0])) or 1.0
        if patch_size >= diagonal:  # (every polygon one patch: its light one number)
            import warnings

            warnings.warn(f"a patch size of {patch_size:g} is more than the scene's whole "
                          f"diagonal ({diagonal:.4g}): each polygon is one patch, lit "
                          "evenly (a patch size of a 24th of it, the default, shows the "
                          "light's gradients)", UserWarning, stacklevel=2)
        cleaned = [without_zero_area(m.mesh.transformed(m.transform), m.name or
                                      f"mesh {i + 1}", diagonal) for i, m in models]
        meshes = [mesh for mesh, _ in cleaned]
        notes = [note for _, note in cleaned if note]
        with np.errstate(over="ignore"):
            estimate = sum(estimated_patches(mesh, patch_size) for mesh in meshes)
        if not estimate <= MAX_PATCHES:
            extents = np.concatenate([polygon_extents(mesh) for mesh in meshes])
            smallest = float(np.sqrt(np.square(extents).sum() / MAX_PATCHES))
            gib = estimate * BYTES_PER_PATCH / 2 ** 30
            many = (f"about {estimate:.3g} patches (about {gib:.3g} GiB)"
                    if np.isfinite(estimate) else "more patches than can be counted")
            raise InputError(f"a patch size of {patch_size:g} would cut the scene into "
                             f"{many}, more than the {MAX_PATCHES:,} glshade solves: use a "
                             f"patch size of at least {smallest:.3g}")
        names, parts, emission, rho, owner = [], [], [], [], []
        for k, ((i, m), mesh) in enumerate(zip(models, meshes)):
            name = m.name or f"mesh {i + 1}"
            names.append(name)
            r = np.asarray(m.material.rho)
            if (r > 1).any():
                raise InputError(f"{name}: diffuse reflectance kd * color = "
                                 f"({', '.join(f'{float(x):.4g}' for x in r)}) exceeds 1 "
                                 "(radiosity needs 0 <= rho <= 1: lower kd or color, or give "
                                 "reflectance)")
            if mesh.n_faces == 0:
                continue
            p = subdivide(mesh, patch_size)
            parts.append(p)
            emission.append(np.broadcast_to(m.material.emission, (p.n_patches, 3)))
            rho.append(np.broadcast_to(r, (p.n_patches, 3)))
            owner.append(np.full(p.n_patches, k))
        emitted = np.concatenate(emission).astype(np.float64) if emission else np.zeros((0, 3))
        if not (emitted > 0).any():
            gone = f" ({'; '.join(notes)})" if notes else ""
            raise InputError(f"the scene has no emitter{gone}: radiosity moves light that "
                             "surfaces give off; set a material's emission (e.g. emission = "
                             "[15, 15, 15] on the light's mesh)")
        if notes:
            import warnings

            for note in notes:
                warnings.warn(note, UserWarning, stacklevel=2)
        patches = concatenate_patches(parts)
        return cls(patches, emitted, np.concatenate(rho).astype(np.float64),
                   np.concatenate(owner), names, float(patch_size), meshes)

    def summary(self) -> str:
        p = self.patches
        text = (f"{p.n_patches:,} patches (size {self.patch_size:g}) from {len(self.names)} "
                f"meshes, {int((self.emission.sum(1) > 0).sum()):,} emitting")
        if p.split:
            text += f"; {p.split} non-planar quads split in two"
        return text
