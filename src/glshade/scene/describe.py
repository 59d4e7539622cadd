"""Materials from what files say: a reader (``glshade.geometry.trimesh_bridge``) describes a
part's material as plain data, and this makes the material its lighting model draws -- a
glTF metallic-roughness one a :class:`~glshade.PBRMaterial`, a simple one a
:class:`~glshade.Material` -- warning once, by name, about anything it holds that glshade
does not draw."""

from __future__ import annotations

import warnings

from .material import Material
from .pbr import PBRMaterial
from .texture import Texture

__all__ = ["material_from_description"]


def material_from_description(description, where: str):
    """The material a file's description (``glshade.geometry.trimesh_bridge``: plain data)
    asks for: a glTF metallic-roughness material as a :class:`~glshade.PBRMaterial`, a
    simple one as a :class:`Material`; what it holds and glshade does not draw is one warning
    naming it (``where`` says whose). A material object passes through.

    Parameters
    ----------
    description : dict, Material or PBRMaterial
        The description (or a material, returned as it is).
    where : str
        The file and material, for the warning.
    """
    if not isinstance(description, dict):
        return description
    d = description
    maps = dict(d.get("maps", {}))
    if d["kind"] == "simple":
        image = maps.get("texture")
        return Material(name=d.get("name"), color=tuple(d["color"]), diffuse=tuple(d["color"]),
                        opacity=d["opacity"], texture=Texture(image) if image is not None
                        else None)
    alpha_mode = (d.get("alpha_mode") or "OPAQUE").upper()
    dropped = []
    if alpha_mode == "MASK":
        dropped.append("alphaMode MASK (drawn opaque)")
    opacity = d["opacity"] if alpha_mode == "BLEND" else 1.0
    textures: dict = {k: Texture(image) for k, image in maps.items()}
    material = PBRMaterial(base_color=tuple(d["base_color"]), metallic=d["metallic"],
                           roughness=d["roughness"], emissive=tuple(d["emissive"]),
                           opacity=opacity, name=d.get("name"), **textures)
    if dropped:
        warnings.warn(f"{where}: not drawn: {', '.join(dropped)}", UserWarning, stacklevel=3)
    return material
