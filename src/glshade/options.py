"""How to draw: one frozen value shared by the renderer, the viewer, animation, comparison,
scene files and the command line, so no layer re-declares an option or its default."""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

from .errors import GeometryError
from .modes import Outputs, ShadingMode

__all__ = ["DrawOptions", "DEFAULT_SIZE"]

#: image size (width, height) when neither the command line nor a scene file gives one
DEFAULT_SIZE = (800, 600)


@dataclass(frozen=True)
class DrawOptions:
    """Everything that decides how a scene is drawn, apart from where (target, viewport).

    Parameters
    ----------
    mode : shading mode (a ShadingMode or its name).
    depth_test : the z-buffer; False draws in submission order.
    cull : back-face culling: "auto" (closed, consistently oriented meshes wholly beyond the
        near plane, so seen from outside; from inside a mesh its back faces are what shows),
        True or False.
    srgb : encode the linear result as sRGB for display.
    wireframe : draw polygon edges instead of filled polygons.
    outputs : what the draw writes besides colour (:class:`Outputs`).
    """

    mode: ShadingMode = ShadingMode.PHONG
    depth_test: bool = True
    cull: str | bool = "auto"
    srgb: bool = False
    wireframe: bool = False
    outputs: Outputs = Outputs.COLOR

    def __post_init__(self):
        object.__setattr__(self, "mode", ShadingMode.parse(self.mode))
        if not (isinstance(self.cull, bool) or self.cull == "auto"):
            raise GeometryError(f"cull must be 'auto', True or False, got {self.cull!r}")
        for name in ("depth_test", "srgb", "wireframe"):
            value = getattr(self, name)
            if not isinstance(value, bool):
                raise GeometryError(f"{name} must be True or False, got {value!r}")
        if not isinstance(self.outputs, Outputs) or not self.outputs & Outputs.COLOR:
            raise GeometryError(f"outputs must be an Outputs flag including COLOR, got "
                                f"{self.outputs!r}")

    def replace(self, **changes) -> DrawOptions:
        """A copy with ``changes``; an unknown option is named with the valid ones."""
        names = {f.name for f in fields(self)}
        unknown = sorted(set(changes) - names)
        if unknown:
            raise GeometryError(f"unknown draw option(s) {', '.join(unknown)}; valid: "
                                f"{', '.join(sorted(names))}")
        return replace(self, **changes)

    @classmethod
    def of(cls, options=None, **changes) -> DrawOptions:
        """Options from a DrawOptions, a shading mode (or its name) or nothing, with
        ``changes`` applied: what every public drawing function accepts. (The earlier
        keyword ``cull_back_faces`` is accepted for ``cull``.)"""
        if "cull_back_faces" in changes:
            changes["cull"] = changes.pop("cull_back_faces")
        if options is None:
            base = cls()
        elif isinstance(options, cls):
            base = options
        else:  # a mode's name or member: one frozen value per mode, made once
            mode = ShadingMode.parse(options)
            base = _BY_MODE.get(mode)
            if base is None:
                base = _BY_MODE[mode] = cls(mode=mode)
        if not changes:
            return base
        key = (base, tuple(sorted(changes.items())))
        try:
            found = _CHANGED.get(key)
        except TypeError:  # an unhashable value: let replace() say what is wrong
            return base.replace(**changes)
        if found is None:
            if len(_CHANGED) > 256:
                _CHANGED.clear()
            found = _CHANGED[key] = base.replace(**changes)
        return found


_BY_MODE: dict[ShadingMode, DrawOptions] = {}
_CHANGED: dict[tuple, DrawOptions] = {}  # (options, changes) -> the changed options
