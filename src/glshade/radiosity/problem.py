"""A scene as a radiosity problem: its polygons cut into patches, each with the emission E
and the diffuse reflectance rho of its model's material (RGB)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .patches import Patches, subdivide
from ..scene import Scene

__all__ = ["PatchScene", "concatenate_patches"]


def concatenate_patches(parts: list[Patches]) -> Patches:
    """One Patches of several (vertex and patch indices shifted)."""
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


@dataclass
class PatchScene:
    """Patches in world space with ``emission`` and ``rho`` (P, 3), the ``model`` (P,) each
    came from and the models' ``names``."""

    patches: Patches
    emission: np.ndarray
    rho: np.ndarray
    model: np.ndarray
    names: list[str]
    patch_size: float

    @property
    def n_patches(self) -> int:
        return self.patches.n_patches

    @classmethod
    def from_scene(cls, scene: Scene, patch_size: float | None = None) -> PatchScene:
        """Cut every visible model of ``scene`` into patches of about ``patch_size``
        (default: a 24th of the scene's diagonal). A scene with nothing emitting, or a
        reflectance above 1, is refused with the model named."""
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
        names, parts, emission, rho, owner = [], [], [], [], []
        for k, (i, m) in enumerate(models):
            name = m.name or f"mesh {i + 1}"
            names.append(name)
            r = np.asarray(m.material.rho)
            if (r > 1).any():
                raise InputError(f"{name}: diffuse reflectance kd * color = "
                                 f"{tuple(round(x, 4) for x in r)} exceeds 1 (radiosity "
                                 "needs 0 <= rho <= 1: lower kd or color, or give "
                                 "reflectance)")
            p = subdivide(m.mesh.transformed(m.transform), patch_size)
            parts.append(p)
            emission.append(np.broadcast_to(m.material.emission, (p.n_patches, 3)))
            rho.append(np.broadcast_to(r, (p.n_patches, 3)))
            owner.append(np.full(p.n_patches, k))
        patches = concatenate_patches(parts)
        emitted = np.concatenate(emission).astype(np.float64)
        if not (emitted > 0).any():
            raise InputError("the scene has no emitter: radiosity moves light that surfaces "
                             "give off; set a material's emission (e.g. emission = [15, 15, "
                             "15] on the light's mesh)")
        return cls(patches, emitted, np.concatenate(rho).astype(np.float64),
                   np.concatenate(owner), names, float(patch_size))

    def summary(self) -> str:
        p = self.patches
        text = (f"{p.n_patches:,} patches (size {self.patch_size:g}) from {len(self.names)} "
                f"meshes, {int((self.emission.sum(1) > 0).sum()):,} emitting")
        if p.split:
            text += f"; {p.split} non-planar quads split in two"
        return text
