"""Scene files: TOML describing meshes, materials, transforms, lights, render settings and
a camera (one view, or key frames). Read with ``tomllib``; every error names the file, the
line and the key.

Example (``assets/scenes/teapot-orbit.toml``)::

    [render]
    size = [512, 384]
    mode = "phong"                     # and srgb, depth_test, cull, wireframe: DrawOptions
    background = [0.12, 0.12, 0.14]
    fps = 24

    [[mesh]]
    source = "primitive:teapot"        # or a path, relative to this file
    color = [0.85, 0.55, 0.3]
    ks = 0.5
    shininess = 40
    translation = [0.0, -1.5, 0.0]

    [[light]]
    position = [4.0, 6.0, 8.0]

    [[camera.keyframe]]
    time = 0.0
    eye = [6.0, 2.0, 0.0]
    target = [0.0, 0.0, 0.0]

``[[solid]]`` tables hold CSG trees (``tree = "box(2) - sphere(1.2)"``), ``[[patches]]``
tables Bezier patches (``source = "patches:teapot"`` or a ``.bpt`` file, ``level`` segments
a side, ``tessellation = "cpu"`` or ``"gpu"``), with the mesh's material and placement keys.
A ``[[mesh]]`` with ``instances = "transforms.npy"`` (a ``(K, 4, 4)`` array beside the file,
or a table of K matrices) is K copies (``Scene.add``'s ``instances``), each coloured by
``instance_colors`` (``(K, 3)``, the same two forms) where given; ``vertex_colors = false``
ignores the colours its mesh file holds. A ``[[light]]`` is a point light (``position``), a
directional one (``direction``), or with ``type = "spot"`` a spot light (``position``,
``direction``, ``inner_angle``, ``outer_angle`` in radians); a point or spot light's
``range`` is KHR_lights_punctual's (the light ends there). ``pbr = { base_color = [r, g,
b], metallic = 0.5, roughness = 0.4 }`` on a ``[[mesh]]`` gives it glTF's metallic-roughness
material (:class:`~glshade.PBRMaterial`) instead of the notes' keys.
"""

from __future__ import annotations

import dataclasses
import re
import sys
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from ..errors import GlshadeError, PathFormatError, SceneError, SceneFormatError
from ..modes import Culling, ShadingMode, Shadows, Tessellation, Transparency, choose
from ..options import DEFAULT_SIZE, DrawOptions, check_samples, check_size
from ..scene.camera import check_fov
from ..scene.keyframes import OrientationInterp, PositionInterp
from ..scene.material import check_illum
from ..scene.texture import check_texture_filter, check_texture_wrap
from ..scene import (
    Camera, CameraPath, DirectionalLight, Keyframe, Material, PointLight, Scene, SpotLight,
    default_camera,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["SceneFile", "RenderSettings", "load_scene"]


@dataclass
class RenderSettings:
    """A scene file's ``[render]`` table: how to draw (the same :class:`DrawOptions` the
    renderer takes, passed through animation unchanged), and the image and timing.

    Parameters
    ----------
    options : DrawOptions
        How to draw.
    width, height : int
        The image's size in pixels.
    samples : int
        MSAA samples.
    fps : float
        Frames a second of an animation.
    duration : float or None
        An animation's length in seconds (None: its path's).
    origin : dict
        Where each setting came from, ``{"samples": "scene.toml:3"}``.
    """

    options: DrawOptions = field(default_factory=DrawOptions)
    width: int = DEFAULT_SIZE[0]
    height: int = DEFAULT_SIZE[1]
    samples: int = 4
    fps: float = 30.0
    duration: float | None = None
    #: where each setting came from, ``{"samples": "scene.toml:3"}`` (scene files only)
    origin: dict = field(default_factory=dict)

    @property
    def size(self) -> tuple[int, int]:
        return self.width, self.height


@dataclass
class SceneFile:
    """What a scene file holds: the scene, the camera path (one key for a still) and the
    render settings.

    Parameters
    ----------
    scene : Scene
        The models and lights.
    path : CameraPath
        The camera's key frames (one for a still).
    settings : RenderSettings
        The [render] table.
    source : Path
        The file read.
    """

    scene: Scene
    path: CameraPath
    settings: RenderSettings
    source: Path

    @property
    def camera(self) -> Camera:
        return self.path.at(self.path.start)


NUMBER = (int, float)
_SCHEMA = {
    "render": {"size": "size", "mode": "mode", "samples": "samples", "srgb": "bool",
               "depth_test": "bool", "cull": "cull", "wireframe": "bool",
               "shadows": "shadows", "transparency": "transparency",
               "fps": "positive", "duration": "positive", "background": "color",
               "ambient": "color"},
    "mesh": {"source": "str", "name": "str", "color": "color", "ka": "unit", "kd": "unit",
             "ks": "unit", "shininess": "nonneg", "translation": "vec3", "rotation": "quat",
             "scale": "scale", "transform": "mat4", "visible": "bool", "crease": "degrees",
             "emission": "color", "reflectance": "reflectance", "opacity": "unit",
             "ambient": "color", "diffuse": "color", "specular": "color", "illum": "illum",
             "texture": "str", "specular_texture": "str", "opacity_texture": "str",
             "texture_filter": "texture_filter", "texture_wrap": "texture_wrap",
             "vertex_colors": "bool", "label": "str", "instances": "array",
             "instance_colors": "array", "pbr": "pbr"},
    "light": {"type": "light_type", "position": "vec3", "direction": "vec3", "color": "color",
              "intensity": "nonneg", "attenuation": "vec3", "shadows": "bool",
              "inner_angle": "nonneg", "outer_angle": "nonneg", "range": "positive"},
    "camera": {"eye": "vec3", "target": "vec3", "up": "vec3", "position": "vec3",
               "orientation": "quat", "fov_y": "fov", "near": "positive", "far": "positive",
               "interpolation": "interp", "position_interpolation": "pinterp",
               "keyframe": "keyframes", "K": "mat3", "R": "mat3", "t": "vec3"},
}
_TEXTURE_KEYS = ("texture", "specular_texture", "opacity_texture", "texture_filter",
                 "texture_wrap",  # (meshes only: solids and patches have no uv)
                 "pbr")  # (and glTF's model: meshes only)
_SCHEMA["solid"] = {k: v for k, v in _SCHEMA["mesh"].items()
                    if k not in ("source", "crease", *_TEXTURE_KEYS)} | {"tree": "str"}
# patches: source = "patches:NAME" or a .bpt file; level segments a side; tessellation
_SCHEMA["patches"] = {k: v for k, v in _SCHEMA["mesh"].items()
                      if k not in ("crease", *_TEXTURE_KEYS)} | {
    "level": "level", "tessellation": "tessellation"}
_TOP = {"render", "mesh", "solid", "patches", "light", "camera"}
_MANY = ("mesh", "solid", "patches", "light")


class _Locator:
    """Find the line of a key in the TOML text (tomllib gives values, not positions)."""

    def __init__(self, text: str):
        self.lines = text.splitlines()

    def line(self, table: str, index: int | None, key: str | None) -> int | None:
        header = re.compile(r"^\s*\[\[?\s*" + re.escape(table) + r"\s*\]\]?\s*(#.*)?$")
        seen, start = -1, None
        for i, line in enumerate(self.lines):
            if header.match(line):
                seen += 1
                if index is None or seen == index:
                    start = i
                    break
        if start is None:
            return None
        if key is None:
            return start + 1
        pat = re.compile(r"^\s*" + re.escape(key) + r"\s*=")
        for j in range(start + 1, len(self.lines)):
            if re.match(r"^\s*\[", self.lines[j]):
                break
            if pat.match(self.lines[j]):
                return j + 1
        return start + 1


def _size(value: object) -> tuple[int, int]:
    if not isinstance(value, list) or len(value) != 2:
        raise SceneFormatError(f"size must be [width, height] in pixels, such as [640, 480], "
                               f"got {value!r}")
    return check_size(*value)


def _expected(what: str, value) -> SceneFormatError:
    """What a scene file's value must be, in the file's words (:func:`_check` puts the
    key's place as its subject)."""
    return SceneFormatError.must("the value", f"be {what}, got {value!r}")


def _number(value) -> float:
    if not isinstance(value, NUMBER) or isinstance(value, bool) or not np.isfinite(value):
        raise _expected("a finite number", value)
    return float(value)


def _numbers(n: int):
    def check(value) -> list:
        if not isinstance(value, list) or len(value) != n or \
                not all(isinstance(v, NUMBER) and not isinstance(v, bool) for v in value):
            raise _expected(f"a list of {n} numbers", value)
        if not all(np.isfinite(v) for v in value):
            raise _expected(f"a list of {n} finite numbers", value)
        return [float(v) for v in value]
    return check


def _such(convert, holds, expected: str):
    """A check: ``convert`` the value, then it must satisfy ``holds`` (else ``expected``)."""
    def check(value):
        v = convert(value)
        if not holds(v):
            raise _expected(expected, value)
        return v
    return check


def _is(test, expected: str):
    return _such(lambda v: v, test, expected)


def _whole(minimum: int, expected: str):
    return _is(lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= minimum,
               expected)


def _scale(value):
    if isinstance(value, NUMBER) and not isinstance(value, bool) and value > 0:
        return float(value)
    return _such(_numbers(3), lambda s: min(s) > 0,
                 "a positive number or three positive numbers")(value)


def _matrix(value, n: int):
    if not isinstance(value, list) or len(value) != n or \
            not all(isinstance(r, list) and len(r) == n for r in value):
        raise _expected(f"a {n}x{n} list of lists", value)
    if not all(isinstance(v, NUMBER) and not isinstance(v, bool) and np.isfinite(v)
               for r in value for v in r):
        raise _expected(f"a {n}x{n} list of lists of finite numbers", value)
    return np.array(value, dtype=float)


def _mat4(value):
    return _matrix(value, 4)


#: each kind of value a scene file holds, and its check: the file's own forms (lists of
#: numbers, TOML's types), or the API's rule for the value where the API has one -- one
#: rule, one message, restated with the file's key as its subject
_KINDS = {
    "str": _is(lambda v: isinstance(v, str) and bool(v), "a non-empty string"),
    "bool": _is(lambda v: isinstance(v, bool), "true or false"),
    "level": _whole(1, "a whole number of segments >= 1"),
    "unit": _such(_number, lambda v: 0 <= v <= 1, "a number in [0, 1]"),
    "nonneg": _such(_number, lambda v: v >= 0, "a number >= 0"),
    "positive": _such(_number, lambda v: v > 0, "a number > 0"),
    "degrees": _such(_number, lambda v: 0 <= v <= 180, "an angle in degrees from 0 to 180"),
    "color": _such(_numbers(3), lambda c: min(c) >= 0, "three numbers >= 0 (linear r, g, b)"),
    "reflectance": _such(_numbers(3), lambda c: 0 <= min(c) and max(c) <= 1,
                         "three numbers in [0, 1] (a surface reflects at most what it "
                         "receives)"),
    "vec3": _numbers(3),
    "quat": _such(_numbers(4), any, "a non-zero quaternion [x, y, z, w]"),
    "scale": _scale,
    "mat4": _mat4,
    "mat3": lambda value: _matrix(value, 3),
    "light_type": _is(lambda v: v in ("point", "directional", "spot"),
                      "'point', 'directional' or 'spot'"),
    "array": _is(lambda v: (isinstance(v, str) and bool(v)) or isinstance(v, list),
                 "a .npy file (its path) or a table of numbers"),
    "pbr": _is(lambda v: isinstance(v, dict) and bool(v),
               "a table of glTF's factors: { base_color = [r, g, b], metallic = m, "
               "roughness = r, emissive = [r, g, b], opacity = a }"),
    # (the API's own rules)
    "size": _size, "samples": check_samples, "fov": check_fov,
    "mode": ShadingMode.parse, "interp": OrientationInterp.parse,
    "pinterp": PositionInterp.parse, "cull": Culling.parse, "shadows": Shadows.parse,
    "transparency": Transparency.parse, "illum": check_illum,
    "texture_filter": check_texture_filter, "texture_wrap": check_texture_wrap,
    "tessellation": lambda v: choose(Tessellation, v, "tessellation", SceneError),
}


def _check(kind: str, value, where: str):
    """Validate one value by its kind's check (:data:`_KINDS`); return it converted, or
    raise one line naming the file's place."""
    check = _KINDS.get(kind)
    if check is None:
        return value
    try:
        return check(value)
    except (GlshadeError, ValueError, TypeError) as exc:
        # the rule's own words, with the file's key as their subject
        rule = getattr(exc, "rule", None)
        raise SceneFormatError(f"{where} must {rule}" if rule else f"{where}: {exc}") from None


def _add_solid(scene, m: dict, i: int, loc: _Locator, source: str) -> None:
    """A ``[[solid]]`` table: a CSG ``tree`` in the syntax of :mod:`glshade.solids.text`."""
    from ..solids.text import parse_solid

    if "tree" not in m:
        raise SceneFormatError(f"{source}:{loc.line('solid', i, None)}: [[solid]] {i + 1} "
                               "needs a 'tree', e.g. tree = \"box(2) - sphere(1.2)\"")
    solid = parse_solid(m["tree"], f"{source}:{loc.line('solid', i, 'tree')}: tree")
    try:
        model = scene.add(solid, Material.from_values(m), m.get("transform"),
                          rotation=m.get("rotation"), translation=m.get("translation",
                                                                        (0, 0, 0)),
                          scale=m.get("scale", 1.0), name=m.get("name"),
                          label=m.get("label"))
    except GlshadeError as exc:
        raise SceneFormatError(f"{source}:{loc.line('solid', i, None)}: [[solid]] {i + 1}: "
                               f"{exc}") from None
    model.visible = m.get("visible", True)


def _validate(data: dict, loc: _Locator, source: str):
    for key in data:
        if key not in _TOP:
            value = data[key]
            if isinstance(value, dict) or isinstance(value, list) and value and \
                    all(isinstance(v, dict) for v in value):
                what, line = f"table [{key}]", loc.line(key, None, None)
            else:  # (a key = value before any table)
                what = f"top-level key '{key}' (keys go in a table, such as [render])"
                line = next((i + 1 for i, text in enumerate(loc.lines)
                             if re.match(rf"\s*{re.escape(key)}\s*=", text)), None)
            raise SceneFormatError(f"{source}:{line or 1}: unknown {what}; allowed tables: "
                                   f"{', '.join(sorted(_TOP))}")
    out = {}
    for table, schema in _SCHEMA.items():
        raw = data.get(table)
        if raw is None:
            continue
        many = table in _MANY
        if many and not isinstance(raw, list):
            raise SceneFormatError(f"{source}:{loc.line(table, None, None)}: write meshes and "
                                   f"lights as [[{table}]] tables")
        if not many and not isinstance(raw, dict):
            raise SceneFormatError(f"{source}: [{table}] must be a table")
        items = raw if many else [raw]
        checked = []
        for i, item in enumerate(items):
            name = f"[[{table}]] {i + 1}" if many else f"[{table}]"
            clean = {}
            for key, value in item.items():
                line = loc.line(table, i if many else None, key)
                where = f"{source}:{line}: {name} key '{key}'"
                if key not in schema:
                    raise SceneFormatError(f"{source}:{line}: unknown key '{key}' in {name}; "
                                           f"allowed: {', '.join(sorted(schema))}")
                clean[key] = value if schema[key] == "keyframes" else \
                    _check(schema[key], value, where)
            checked.append(clean)
        out[table] = checked if many else checked[0]
    return out


def load_scene(path) -> SceneFile:
    """Read a scene file: the Scene, its CameraPath and its RenderSettings.

    Parameters
    ----------
    path : str or Path
        The TOML scene file.
    """
    path = Path(path)
    from .._paths import file_fault

    fault = file_fault(path)
    if fault is not None:
        raise SceneFormatError(f"{path}: {fault}")
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneFormatError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise SceneFormatError(f"{path}: cannot read: {exc}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneFormatError(f"{path}: {exc}") from None
    loc = _Locator(text)
    source = str(path)
    d = _validate(data, loc, source)

    r = d.get("render", {})
    # the [render] table's drawing keys are DrawOptions' own fields, by the same names
    drawing = {f.name for f in fields(DrawOptions)} - {"outputs"}
    options = DrawOptions.of(None, **{k: r[k] for k in drawing if k in r})
    settings = RenderSettings(options, **{k: r[k] for k in ("samples", "fps", "duration")
                                          if k in r})
    if "size" in r:
        settings.width, settings.height = r["size"]
    settings.origin = {k: f"{source}:{loc.line('render', None, k)}: [render] {k}" for k in r}
    scene = Scene(**{k: r[k] for k in ("ambient", "background") if k in r})
    meshes = d.get("mesh", [])
    if not meshes and not d.get("solid") and not d.get("patches"):
        raise SceneFormatError(f"{source}: the scene has no [[mesh]], [[solid]] or "
                               "[[patches]]")
    for i, m in enumerate(meshes):
        _add_mesh(scene, m, i, loc, source, path.parent)
    for i, m in enumerate(d.get("solid", [])):
        _add_solid(scene, m, i, loc, source)
    for i, m in enumerate(d.get("patches", [])):
        _add_patches(scene, m, i, loc, source, path.parent)
    for i, light in enumerate(d.get("light", [])):
        where = f"{source}:{loc.line('light', i, None)}: [[light]] {i + 1}"
        kind = light.get("type", "direction" in light and "directional" or "point")
        for needs in {"point": ("position",), "directional": ("direction",),
                      "spot": ("position", "direction")}[kind]:
            if needs not in light:
                raise SceneFormatError(f"{where}: a {kind} light needs a '{needs}'")
        cone = [k for k in ("inner_angle", "outer_angle") if k in light]
        if cone and kind != "spot":
            raise SceneFormatError(f"{where}: '{cone[0]}' is a spot light's (type = \"spot\"), "
                                   f"not a {kind} light's")
        if "range" in light and kind == "directional":
            raise SceneFormatError(f"{where}: 'range' is a point or spot light's; a "
                                   "directional light reaches everywhere")
        try:  # (a value the light refuses -- a zero direction -- is named with its line)
            obj: PointLight | DirectionalLight | SpotLight
            if kind == "spot":
                obj = SpotLight(**{k: light[k] for k in (
                    "position", "direction", "color", "intensity", "inner_angle",
                    "outer_angle", "attenuation", "shadows", "range") if k in light})
            elif kind == "point":
                obj = PointLight(**{k: light[k] for k in ("position", "color", "intensity",
                                                          "attenuation", "shadows", "range")
                                    if k in light})
            else:
                obj = DirectionalLight(**{k: light[k] for k in ("direction", "color",
                                                                "intensity", "shadows")
                                          if k in light})
            scene.add_light(obj)
        except GlshadeError as exc:
            raise SceneFormatError(f"{where}: {exc}") from None
    camera_path = _camera(d.get("camera"), data.get("camera"), scene, settings, loc, source)
    if settings.duration is None:
        settings.duration = camera_path.duration or 0.0
    return SceneFile(scene, camera_path, settings, path)


def _add_mesh(scene, m: dict, i: int, loc: _Locator, source: str, base: Path) -> None:
    """A ``[[mesh]]`` table: its source (a file relative to the scene file, or
    primitive:NAME), material and placement."""
    if "source" not in m:
        raise SceneFormatError(f"{source}:{loc.line('mesh', i, None)}: [[mesh]] {i + 1} "
                               "needs a 'source' (a file or primitive:NAME)")
    mesh = _load_mesh(m["source"], base, f"{source}:{loc.line('mesh', i, 'source')}")
    material = _material(m, mesh, base, lambda key: f"{source}:{loc.line('mesh', i, key)}: "
                                                    f"[[mesh]] {i + 1}")
    arrays = {key: _array(m[key], base, f"{source}:{loc.line('mesh', i, key)}: [[mesh]] "
                                        f"{i + 1}'s {key}")
              for key in ("instances", "instance_colors") if key in m}
    try:
        model = scene.add(mesh, material, m.get("transform"), rotation=m.get("rotation"),
                          translation=m.get("translation", (0, 0, 0)),
                          scale=m.get("scale", 1.0), name=m.get("name"),
                          label=m.get("label"),
                          crease=m.get("crease"), instances=arrays.get("instances"),
                          colors=arrays.get("instance_colors"))
    except GlshadeError as exc:
        raise SceneFormatError(f"{source}:{loc.line('mesh', i, None)}: [[mesh]] {i + 1}: "
                               f"{exc}") from None
    for each in getattr(model, "models", (model,)):
        each.visible = m.get("visible", True)


def _array(value, base: Path, where: str):
    """A [[mesh]]'s ``instances`` or ``instance_colors``: the table as given, or the array
    of a ``.npy`` file (relative to the scene file); Scene.add checks its shape."""
    if isinstance(value, list):
        return value
    path = base / value
    try:
        return np.load(path, allow_pickle=False)
    except FileNotFoundError:
        raise SceneFormatError(f"{where}: no such file: {path}") from None
    except (OSError, ValueError) as exc:
        raise SceneFormatError(f"{where}: {path} is not a .npy array ({exc})") from None


#: a [[mesh]]'s keys that make its material (without any, an OBJ's own materials are kept)
_MATERIAL_KEYS = ("color", "ka", "kd", "ks", "shininess", "emission", "reflectance", "opacity",
                  "ambient", "diffuse", "specular", "illum", "texture", "specular_texture",
                  "opacity_texture", "vertex_colors")


def _material(m: dict, mesh, base: Path, where):
    """A [[mesh]]'s material: its keys (textures' paths relative to the scene file), or
    None where it gives none and the mesh has its own (an OBJ's MTL); ``texture_filter``
    and ``texture_wrap`` apply to either's textures. ``where(key)``: the key's place, for
    errors."""
    from ..scene.texture import Texture

    look = {k: m[k] for k in ("texture_filter", "texture_wrap") if k in m}
    sampling = {"filter": look["texture_filter"]} if "texture_filter" in look else {}
    if "texture_wrap" in look:
        sampling["wrap"] = look["texture_wrap"]
    if not any(k in m for k in (*_MATERIAL_KEYS, "pbr")) and getattr(mesh, "material_groups",
                                                                     None):
        if sampling:
            mesh.materials = {name: dataclasses.replace(
                mat, **{k: t.replace(**sampling) for k, t in mat.textures.items()})
                for name, mat in mesh.materials.items()}
        return None
    if "pbr" in m:  # (glTF's model: its factors, checked by PBRMaterial itself)
        from ..scene.pbr import PBRMaterial

        notes = [k for k in _MATERIAL_KEYS if k in m and k != "vertex_colors"]
        if notes:
            raise SceneFormatError(f"{where('pbr')} key 'pbr' and '{notes[0]}' are two "
                                   "lighting models' materials: give one")
        fields_ = {"base_color", "metallic", "roughness", "emissive", "opacity", "ka"}
        unknown = sorted(set(m["pbr"]) - fields_)
        if unknown:
            raise SceneFormatError(f"{where('pbr')} key 'pbr': unknown factor '{unknown[0]}'; "
                                   f"allowed: {', '.join(sorted(fields_))}")
        try:
            return PBRMaterial(**m["pbr"], vertex_colors=m.get("vertex_colors", True),
                               name=m.get("name"))
        except (GlshadeError, TypeError, ValueError) as exc:
            raise SceneFormatError(f"{where('pbr')} key 'pbr': {exc}") from None
    values = dict(m)
    for key in ("texture", "specular_texture", "opacity_texture"):
        if key in m:
            file = beside(base, m[key])
            try:
                values[key] = Texture(file, **sampling)
            except GlshadeError as exc:
                raise SceneFormatError(f"{where(key)} key '{key}': {exc}") from None
    try:
        return Material.from_values(values)
    except GlshadeError as exc:
        raise SceneFormatError(f"{where(None)}: {exc}") from None


def _add_patches(scene, m: dict, i: int, loc: _Locator, source: str, base: Path) -> None:
    """A ``[[patches]]`` table: ``source`` a named model (``patches:NAME``) or a ``.bpt``
    file (relative to the scene file), tessellated on the CPU or the GPU at ``level``."""
    from ..patches import PatchSurface, named
    from ..patches.files import read_patches

    where = f"{source}:{loc.line('patches', i, None)}: [[patches]] {i + 1}"
    if "source" not in m:
        raise SceneFormatError(f"{where} needs a 'source' (patches:NAME or a .bpt file)")
    spec = m["source"]
    try:
        if spec.startswith("patches:"):
            surface = named(spec[len("patches:"):])
        else:
            file = beside(base, spec)
            surface = PatchSurface(read_patches(file), file.stem)
        model = scene.add(surface, Material.from_values(m), m.get("transform"),
                          rotation=m.get("rotation"),
                          translation=m.get("translation", (0, 0, 0)),
                          scale=m.get("scale", 1.0), name=m.get("name"),
                          tessellation=m.get("tessellation", "cpu"), level=m.get("level"),
                          label=m.get("label"))
    except GlshadeError as exc:
        raise SceneFormatError(f"{where}: {exc}") from None
    model.visible = m.get("visible", True)


def beside(base: Path, spec: str) -> Path:
    """The file a scene file names: relative to the scene's folder ``base`` unless absolute,
    with either separator -- a scene written on Windows (``models\\part.obj``) reads on
    macOS and Linux, where a backslash is a letter of a name: taken as a separator when the
    file does not exist by the name as written.

    Parameters
    ----------
    base : Path
        The scene file's folder.
    spec : str
        The path as written.
    """
    file = Path(spec) if Path(spec).is_absolute() else base / spec
    if "\\" in spec and not file.exists():
        other = Path(spec.replace("\\", "/"))
        other = other if other.is_absolute() else base / other
        if other.exists():
            return other
    return file


def _load_mesh(spec: str, base: Path, where: str):
    from ..geometry import primitives
    from .meshes import load_mesh

    try:
        if spec.startswith("primitive:"):
            return primitives.from_spec(spec)
        file = beside(base, spec)
        if not file.exists():
            raise SceneFormatError(f"{where}: mesh file {str(file)!r} does not exist")
        return load_mesh(file)
    except SceneFormatError:
        raise
    except GlshadeError as exc:
        raise SceneFormatError(f"{where}: {exc}") from None


def _opencv_camera(cam, settings, loc, source) -> CameraPath:
    """[camera] given as OpenCV's K, R and t (``x_cam = R @ X + t``) for the [render] size:
    one view."""
    line = loc.line("camera", None, None)
    missing = [k for k in ("K", "R", "t") if k not in cam]
    clash = [k for k in ("eye", "target", "position", "orientation", "keyframe", "fov_y")
             if k in cam]
    if missing or clash:
        said = f"needs {', '.join(missing)} too" if missing else \
            f"cannot also give {', '.join(clash)}"
        raise SceneFormatError(f"{source}:{line}: [camera] with K, R and t (OpenCV's camera) "
                               f"{said}")
    try:
        base = Camera.from_opencv(cam["K"], cam["R"], cam["t"],
                                  (settings.width, settings.height),
                                  **{k: cam[k] for k in ("near", "far") if k in cam})
    except GlshadeError as exc:
        raise SceneFormatError(f"{source}:{line}: [camera]: {exc}") from None
    return CameraPath([Keyframe(0.0, base.position, base.orientation, base.fov_y)],
                      camera=base)


def _camera(cam, raw, scene, settings, loc, source) -> CameraPath:
    aspect = settings.width / settings.height
    if not cam:
        base = default_camera(scene.bounds, aspect)
        return CameraPath([Keyframe(0.0, base.position, base.orientation)], camera=base)
    lens = {k: cam[k] for k in ("fov_y", "near", "far") if k in cam}  # (planes: the scene's)
    if "K" in cam or "R" in cam or "t" in cam:  # (OpenCV's camera: K, and R, t world to it)
        return _opencv_camera(cam, settings, loc, source)
    try:
        base = Camera(**lens)
    except GlshadeError as exc:
        raise SceneFormatError(f"{source}:{loc.line('camera', None, None)}: [camera]: {exc}") \
            from None
    interp = {"orientation_interp": cam.get("interpolation", "slerp"),
              "position_interp": cam.get("position_interpolation", "linear"), "camera": base}
    keys = cam.get("keyframe")
    line = loc.line("camera", None, None)
    single = keys is None  # (one view: eye and target in [camera] itself)
    if single:
        one = {k: raw[k] for k in ("eye", "target", "up", "position", "orientation")
               if k in raw}
        if not one:
            view = default_camera(scene.bounds, aspect)
            return CameraPath([Keyframe(0.0, view.position, view.orientation)], camera=base)
        keys = [dict(one, time=0.0)]
    if not isinstance(keys, list):
        raise SceneFormatError(f"{source}:{line}: write key frames as [[camera.keyframe]]")
    try:
        return CameraPath.from_dict({"keyframe": keys}, source, **interp)
    except PathFormatError as exc:
        if exc.keyframe is None or single:
            raise SceneFormatError(f"{source}:{line}: [camera]: {exc.reason}") from None
        kline = loc.line("camera.keyframe", exc.keyframe - 1, None)
        raise SceneFormatError(f"{source}:{kline}: [camera] keyframe {exc.keyframe}: "
                               f"{exc.reason}") from None
