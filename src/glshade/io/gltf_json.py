"""A glTF/GLB file's JSON, read for what trimesh does not report: the document itself
(:mod:`glshade.io.gltf` places its lights and cameras from it) and what it holds that
glshade does not draw (the one warning a load gives, :mod:`glshade.io.meshes`). No GL."""

from __future__ import annotations

import json
import struct
from pathlib import Path

__all__ = ["gltf_document", "gltf_unread", "READ_HERE"]

#: the extensions the loaders read beside the meshes (not named in the "not drawn" warning)
READ_HERE = ("KHR_lights_punctual",)


def gltf_document(path: Path) -> dict:
    """The JSON of a .gltf, or a .glb's JSON chunk (a 12-byte header, then the chunk);
    ``{}`` when it is neither (trimesh's reader then says what is wrong with the file).

    Parameters
    ----------
    path : Path
        The .gltf or .glb file.
    """
    data = Path(path).read_bytes()
    try:
        if data[:4] == b"glTF":
            length, kind = struct.unpack_from("<II", data, 12)
            doc = json.loads(data[20:20 + length]) if kind == 0x4E4F534A else {}
        else:
            doc = json.loads(data)
    except (ValueError, struct.error):
        return {}
    return doc if isinstance(doc, dict) else {}


def gltf_unread(path, *, extras_taken: bool = False) -> list[str]:
    """What a glTF/GLB file holds that glshade does not draw -- its extensions (clearcoat,
    transmission, volume ...), skins, morph targets and animations -- each named with its
    count, from the file's JSON (trimesh drops them in silence). Its lights and cameras
    are named too unless ``extras_taken`` (the caller reads them: :func:`load_gltf`).

    Parameters
    ----------
    path : str or Path
        The .gltf or .glb file.
    extras_taken : bool
        Whether the lights and cameras are read by the caller.
    """
    doc = gltf_document(Path(path))
    out = [f"extension {name}" for name in doc.get("extensionsUsed", [])
           if name not in READ_HERE]
    targets = sum(len(p.get("targets", [])) for m in doc.get("meshes", [])
                  for p in m.get("primitives", []))
    counts = [(len(doc.get("skins", [])), "skin"), (targets, "morph target"),
              (len(doc.get("animations", [])), "animation")]
    if not extras_taken:
        lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
        counts += [(len(lights), "light (glshade.load_gltf reads it)"),
                   (len(doc.get("cameras", [])), "camera (glshade.load_gltf reads it)")]
    for count, what in counts:
        if count:
            noun, _, hint = what.partition(" (")
            plural = "s" if count > 1 else ""
            out.append(f"{count} {noun}{plural}" + (f" ({hint}" if hint else ""))
    return out
