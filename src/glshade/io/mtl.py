"""Wavefront MTL material libraries: the notes' lighting model as files give it.

=================  ==============================================================
MTL                glshade
=================  ==============================================================
``newmtl NAME``    a :class:`~glshade.Material` named NAME
``Ka r g b``       ``ambient`` (an RGB ka)
``Kd r g b``       ``diffuse`` (an RGB kd C), and ``color``
``Ks r g b``       ``specular`` (an RGB ks)
``Ns n``           ``shininess`` (the exponent n)
``d a``            ``opacity`` a (``Tr t``: opacity 1 - t)
``Ke r g b``       ``emission`` (what radiosity gives off)
``illum 0|1|2``    ``illum``: 0 the colour unlit, 1 no specular, 2 the whole formula
                   (3 and up -- reflection, refraction -- are drawn as 2, and reported)
``map_Kd FILE``    ``texture`` (sRGB; multiplies the ambient and diffuse terms)
``map_Ks FILE``    ``specular_texture`` (sRGB)
``map_d FILE``     ``opacity_texture`` (its alpha, or its red channel if opaque)
``-clamp on``      the map's ``wrap="clamp"`` (default: repeat)
``-o u v``         the map's texture-coordinate ``offset``
``-s u v``         the map's texture-coordinate ``scale``
``Pr r``           the PBR extension's roughness: a block that has it or ``Pm`` is
                   glTF's model, a :class:`~glshade.PBRMaterial` (``Kd`` its base colour,
                   ``Ke`` its emissive, ``d`` its opacity; metallic 0 and roughness 1
                   where not given); with ``map_Kd`` it is drawn by the notes' model,
                   textured, and ``Pr``/``Pm`` are reported
``Pm m``           the PBR extension's metallic, likewise
=================  ==============================================================

The PBR extension's maps (``map_Pr``, ``map_Pm``, ``norm``, ``map_Ke``) and its other keys
(``Ps``, ``Pc``, ``Pcr``, ``aniso``, ``anisor``) are reported with the rest.

Anything else (``Ni``, ``Tf``, ``map_Ka``, ``bump``, other map options ...) is kept in the
library's ``unused`` report, by statement and line, and does not change the picture. A
malformed line is an error naming the file and line; a map whose image is missing or
unreadable is a warning naming the line, and the material is drawn without it.
"""

from __future__ import annotations

import warnings
from typing import Any
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import MeshFormatError, SceneError
from ..scene.material import Material
from ..scene.texture import Texture

__all__ = ["MaterialLibrary", "read_mtl", "write_mtl"]

_COLOURS = {"Ka": "ambient", "Kd": "diffuse", "Ks": "specular", "Ke": "emission"}
_MAPS = {"map_Kd": "texture", "map_Ks": "specular_texture", "map_d": "opacity_texture"}
#: map options and how many values each takes (those glshade applies: -clamp, -o, -s)
_MAP_OPTIONS = {"-clamp": 1, "-o": None, "-s": None, "-t": None, "-blendu": 1, "-blendv": 1,
                "-bm": 1, "-boost": 1, "-mm": 2, "-texres": 1, "-imfchan": 1, "-cc": 1,
                "-type": 1}


@dataclass
class MaterialLibrary:
    """Materials by name, in file order, and what the files said that glshade does not
    use (``unused``: ``"file:line: statement"``).

    Parameters
    ----------
    materials : dict
        Materials by name, in file order.
    unused : list of str
        Statements glshade does not use, ``"file:line: statement"``.
    """

    materials: dict[str, Any] = field(default_factory=dict)
    unused: list[str] = field(default_factory=list)


def read_mtl(path, filter: str | None = None, library: MaterialLibrary | None = None
             ) -> MaterialLibrary:
    """The materials of an MTL file (added to ``library`` if given). ``filter``: the
    textures' filter (``"nearest"``, ``"linear"``, ``"mipmap"``; default linear).

    Parameters
    ----------
    path : str or Path
        The MTL file.
    filter : str or None
        The textures' filter (None: the default).
    library : MaterialLibrary or None
        A library to add to (None: a new one).
    """
    path = Path(path)
    library = library if library is not None else MaterialLibrary()
    try:
        text = path.read_bytes().decode("utf-8", "replace")
    except OSError as exc:
        raise MeshFormatError(path, f"cannot read: {exc.strerror or exc}") from None
    current: dict | None = None
    name = ""

    def finish():
        if current is not None:
            try:
                library.materials[name] = _material(name, current, library)
            except SceneError as exc:
                raise MeshFormatError(path, f"material {name!r}: {exc}") from None

    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        key, _, rest = line.partition(" ")
        args = rest.split()
        where = f"{path.name}:{number}"
        if key == "newmtl":
            finish()
            # (no name: the one an OBJ's bare "usemtl" gets -- Blender writes both)
            name, current = rest.strip() or "default", {}
            continue
        if current is None:
            raise MeshFormatError(path, f"{key!r} before any newmtl", line=number)
        _statement(path, number, where, key, args, rest, current, library, filter)
    finish()
    return library


def _material(name: str, current: dict, library: MaterialLibrary):
    """The block's material: glTF's (PBRMaterial) where it gives Pr or Pm and no map, else
    the notes' (the PBR keys reported where a map makes it the notes')."""
    pbr = {k[4:]: v for k, v in current.items() if k.startswith("pbr ")}
    notes = {k: v for k, v in current.items() if not k.startswith("pbr ")}
    if not pbr:
        return Material(name=name, **notes)
    maps = [k for k in ("texture", "specular_texture", "opacity_texture") if k in notes]
    if maps:
        for key, (_, where) in pbr.items():
            library.unused.append(f"{where}: {key} (a textured material is drawn by the "
                                  "notes' model)")
        return Material(name=name, **notes)
    from ..scene.pbr import PBRMaterial

    return PBRMaterial(name=name, base_color=notes.get("diffuse", (1.0, 1.0, 1.0)),
                       metallic=pbr.get("Pm", (0.0, None))[0],
                       roughness=pbr.get("Pr", (1.0, None))[0],
                       emissive=notes.get("emission", (0.0, 0.0, 0.0)),
                       opacity=notes.get("opacity", 1.0))


def _numbers(path, number: int, key: str, args: list, counts: tuple) -> list[float]:
    try:
        values = [float(a) for a in args]
    except ValueError:
        values = []
    if len(values) not in counts or not all(v == v and abs(v) < 1e300 for v in values):
        want = " or ".join(str(c) for c in counts)
        raise MeshFormatError(path, f"{key} needs {want} number(s), got {' '.join(args)!r}",
                              line=number)
    return values


def _statement(path, number, where, key, args, rest, current, library, filter) -> None:
    """One statement of a material's block into ``current`` (Material fields)."""
    if key in _COLOURS:
        if args[:1] in (["spectral"], ["xyz"]):
            library.unused.append(f"{where}: {key} {args[0]} (only RGB is read)")
            return
        values = _numbers(path, number, key, args, (1, 3))
        current[_COLOURS[key]] = tuple(values * 3 if len(values) == 1 else values)
        if key == "Kd":
            current["color"] = current["diffuse"]
    elif key == "Ns":
        current["shininess"] = _numbers(path, number, key, args, (1,))[0]
    elif key in ("d", "Tr"):
        if args[:1] == ["-halo"]:
            library.unused.append(f"{where}: d -halo")
            args = args[1:]
        value = _numbers(path, number, key, args, (1,))[0]
        current["opacity"] = value if key == "d" else 1.0 - value
    elif key == "illum":
        value = _numbers(path, number, key, args, (1,))[0]
        if value != int(value) or not 0 <= value <= 10:
            raise MeshFormatError(path, f"illum must be a model number 0..10, got {rest!r}",
                                  line=number)
        if value > 2:
            library.unused.append(f"{where}: illum {int(value)} (drawn as illum 2)")
        current["illum"] = min(int(value), 2)
    elif key in _MAPS:
        texture = _map(path, number, where, key, rest, library, filter)
        if texture is not None:
            current[_MAPS[key]] = texture
    elif key in ("Pr", "Pm"):  # (the PBR extension: glTF's model, finish() decides)
        current["pbr " + key] = (_numbers(path, number, key, args, (1,))[0], where)
    else:
        library.unused.append(f"{where}: {key}")


def _map(path, number, where, key, rest, library, filter) -> Texture | None:
    """A map statement's texture (None, with a warning, if its image cannot be read)."""
    tokens = rest.split()  # (not shell rules: Windows paths' backslashes are separators)
    options: dict[str, list[str]] = {}
    i = 0
    while i < len(tokens) and tokens[i].startswith("-") and tokens[i] in _MAP_OPTIONS:
        option, count = tokens[i], _MAP_OPTIONS[tokens[i]]
        i += 1
        values: list[str] = []
        if count is not None:   # (a fixed count: taken whatever follows)
            values, i = tokens[i:i + count], i + count
        else:                   # (1 to 3 numbers, the file name after them)
            while i < len(tokens) - 1 and len(values) < 3 and _is_number(tokens[i]):
                values.append(tokens[i])
                i += 1
        options[option] = values
    if i >= len(tokens):
        raise MeshFormatError(path, f"{key} names no image file", line=number)
    image = " ".join(tokens[i:])
    for option in options:
        if option not in ("-clamp", "-o", "-s"):
            library.unused.append(f"{where}: {key} {option}")
    uv = {}
    for option, field_name in (("-o", "offset"), ("-s", "scale")):
        if option in options:
            given = _numbers(path, number, f"{key} {option}", options[option], (1, 2, 3))
            uv[field_name] = (given[0], given[1] if len(given) > 1 else
                              (given[0] if option == "-s" else 0.0))
    clamp = options.get("-clamp", ["off"])[:1] == ["on"]
    file = (path.parent / image.replace("\\", "/"))
    try:
        return Texture(file, filter=filter or "linear", wrap="clamp" if clamp else "repeat",
                       **uv)
    except SceneError as exc:
        warnings.warn(f"{where}: {key}: {exc}; the material is drawn without it",
                      UserWarning, stacklevel=2)
        return None


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _colour(name: str, value) -> str:
    return f"{name} {value[0]:.9g} {value[1]:.9g} {value[2]:.9g}\n"


def write_mtl(materials: dict[str, Any], f, base: Path | None = None) -> None:
    """``materials`` as MTL text into the open text file ``f`` (maps by their file paths,
    relative to ``base``, the library's folder, where they can be; a map made from an
    array has none and is left out).

    Parameters
    ----------
    materials : dict
        Materials by name.
    f : file
        An open text file.
    base : Path or None
        The library's folder, against which map paths are made relative.
    """
    import os

    for name, m in materials.items():
        f.write(f"newmtl {name}\n")
        if m.lighting.value == "pbr":  # (glTF's model: the PBR extension's keys)
            f.write(_colour("Kd", m.base_color) + f"Pm {m.metallic:.9g}\nPr {m.roughness:.9g}\n")
            if any(m.emission):
                f.write(_colour("Ke", m.emission))
            f.write(f"d {m.opacity:.9g}\n\n")
            continue
        f.write(_colour("Ka", m.ambient_rgb) + _colour("Kd", m.diffuse_rgb) +
                _colour("Ks", m.specular_rgb))
        if any(m.emission):
            f.write(_colour("Ke", m.emission))
        f.write(f"Ns {m.shininess:.9g}\nd {m.opacity:.9g}\nillum {m.illum}\n")
        for key, attr in _MAPS.items():
            t = getattr(m, attr)
            if t is not None and t.path is not None:
                options = " -clamp on" if t.wrap == "clamp" else ""
                if t.scale != (1.0, 1.0):
                    options += f" -s {t.scale[0]:.9g} {t.scale[1]:.9g}"
                if t.offset != (0.0, 0.0):
                    options += f" -o {t.offset[0]:.9g} {t.offset[1]:.9g}"
                file = str(t.path)
                if base is not None:
                    try:
                        file = os.path.relpath(t.path, base)
                    except ValueError:  # (another drive)
                        pass
                f.write(f"{key}{options} {file}\n")
        f.write("\n")
