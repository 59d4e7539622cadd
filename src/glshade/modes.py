"""The enums that name what a draw does: shading modes, outputs, back-face culling and the
camera's projection. Strings are accepted at the edges and converted once by
:func:`parse_enum`, whose error lists the choices."""

from __future__ import annotations

import enum
from typing import TypeVar

from .errors import OptionError

__all__ = ["ShadingMode", "LightingModel", "Outputs", "Culling", "Shadows", "Transparency",
           "Projection",
           "Backend", "Sampler", "LobeSampling", "Accel", "Kernel", "Tessellation",
           "PointStyle", "LineUnits", "LineCaps", "LineJoins",
           "HEADLESS_BACKENDS", "parse_enum", "choose"]


E = TypeVar("E", bound=enum.Enum)


def parse_enum(cls: type[E], value: object, what: str) -> E:
    """``cls(value)`` for a member or its (case-insensitive) value; a bad one raises
    :class:`OptionError` listing the choices.

    Parameters
    ----------
    cls : type
        The enum.
    value : object
        A member, or its value in any case.
    what : str
        The option's name, as the message says it.
    """
    if isinstance(value, cls):
        return value
    try:
        return cls(str(value).lower())
    except ValueError:
        choices = ", ".join(str(m.value) for m in cls)
        raise OptionError(f"unknown {what} {value!r}; choose one of {choices}") from None


def choose(cls: type[E], value: object, what: str, error: type = OptionError) -> E:
    """``cls``'s member for ``value`` (itself, or its value in any case); else ``error``
    saying ``"{what} must be 'a', 'b' or 'c', got {value!r}"``.

    Parameters
    ----------
    cls
        The enum.
    value
        A member, or its value as a string.
    what
        The option's name, as the message says it.
    error
        The exception class to raise (OptionError; SceneError where a scene is built).
    """
    if isinstance(value, cls):
        return value
    try:
        return cls(str(value).lower())
    except ValueError:
        names = [f"'{m.value}'" for m in cls]
        listed = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]
        must = getattr(error, "must", None)  # (a GlshadeError keeps its subject and rule)
        raise (must(what, f"be {listed}, got {value!r}") if must else
               error(f"{what} must be {listed}, got {value!r}")) from None


def _option_member(cls: type[E], value: object, option: str, true: E | None = None,
                   false: E | None = None, rule: str = "be one of {names}") -> E:
    """A member of a draw option's enum from itself, its (case-insensitive) value, or True
    and False where the option gives them a meaning; else OptionError naming the option."""
    if isinstance(value, cls):
        return value
    if value is True and true is not None:
        return true
    if value is False and false is not None:
        return false
    try:
        return cls(str(value).lower())
    except ValueError:
        names = ", ".join(str(m.value) for m in cls)
        raise OptionError.must(option, rule.format(names=names) + f", got {value!r}") from None


class ShadingMode(enum.Enum):
    """How a surface is shaded (the notes' three, a radiosity solution's display, and two
    debug views)."""

    FLAT = "flat"          # uniform shading: one intensity per polygon
    GOURAUD = "gouraud"    # intensities at the vertices, interpolated
    PHONG = "phong"        # normals interpolated, lit per pixel
    NORMALS = "normals"    # debug: world normal as colour
    DEPTH = "depth"        # debug: view depth as grey
    RADIOSITY = "radiosity"  # per-vertex radiosities (Model.vertex_colors), interpolated, unlit

    @classmethod
    def parse(cls, value) -> ShadingMode:
        """Accept a ShadingMode or its name; a bad name lists the choices.

        Parameters
        ----------
        value : ShadingMode or str
            A member or its name.
        """
        return parse_enum(cls, value, "shading mode")

    @property
    def per_polygon(self) -> bool:
        """Whether the program needs vertices duplicated per triangle corner."""
        return self is ShadingMode.FLAT


class Outputs(enum.Flag):
    """What one draw produces besides the picture. Anything beyond COLOR is drawn into a
    target with integer id and depth buffers (never blended by an MSAA resolve)."""

    COLOR = enum.auto()
    DEPTH = enum.auto()      # distance along the view axis
    NORMAL = enum.auto()     # world-space unit normal
    FACE_ID = enum.auto()    # id of the source polygon
    INSTANCE = enum.auto()   # the model's instance_id (Scene.add), from the polygon ids
    SEMANTIC = enum.auto()   # the model's label's class id (Scene.labels)
    ALL = COLOR | DEPTH | NORMAL | FACE_ID | INSTANCE | SEMANTIC

    @property
    def auxiliary(self) -> bool:
        """Whether anything beyond colour is asked for."""
        return bool(self.value & ~Outputs.COLOR.value)


class Culling(enum.Enum):
    """Back-face culling. ``True``, ``False`` and ``"auto"`` are accepted for ON, OFF, AUTO."""

    AUTO = "auto"  # closed, consistently oriented meshes wholly beyond the near plane
    ON = "on"      # every back face (from inside a mesh nothing shows)
    OFF = "off"    # none: both sides are drawn, back faces lit as seen

    @classmethod
    def parse(cls, value: object) -> Culling:
        """A Culling, True (ON), False (OFF) or a member's name.

        Parameters
        ----------
        value : Culling, bool or str
            A member, a bool or a member's name.
        """
        return _option_member(cls, value, "cull", cls.ON, cls.OFF,
                              "be 'auto', True or False (or one of {names})")

    def __bool__(self) -> bool:  # (so `if options.cull:` reads as before: AUTO and ON cull)
        return self is not Culling.OFF


class LightingModel(enum.Enum):
    """What a shading scheme (flat, Gouraud, Phong) evaluates: the lighting model a material
    is written for. Each is one GLSL include and one material class, compiled into a program
    variant (never a branch through the passes)."""

    NOTES = "notes"  # the course notes' ambient + diffuse + specular (Material, lighting.glsl)
    PBR = "pbr"      # glTF 2.0's metallic-roughness BRDF, its Appendix B (PBRMaterial, pbr.glsl)


class Shadows(enum.Enum):
    """Cast shadows: a light the shaded point cannot see adds nothing there (the ambient
    term and the other lights' terms stay)."""

    OFF = "off"      # every light reaches every surface facing it (the notes' model)
    EXACT = "exact"  # one ray from each pixel's surface point to each light, through a BVH
    MAP = "map"      # shadow maps (2D for directional lights, cube for point lights), PCF

    @classmethod
    def parse(cls, value: object) -> Shadows:
        """A Shadows, its name, or True (EXACT) / False or None (OFF).

        Parameters
        ----------
        value : Shadows, bool, None or str
            A member, a bool, None or a member's name.
        """
        return _option_member(cls, cls.OFF if value is None else value, "shadows",
                              cls.EXACT, cls.OFF)


class Transparency(enum.Enum):
    """How surfaces with ``Material.opacity`` below 1 are composited over what lies behind."""

    EXACT = "exact"        # per-pixel fragment lists, sorted by depth, "over" front to back
    WEIGHTED = "weighted"  # McGuire and Bavoil's weighted blended estimate (order-free)
    BLEND = "blend"        # "over" in the order the surfaces are drawn (teaching: wrong
                           # wherever that is not back to front)

    @classmethod
    def parse(cls, value: object) -> Transparency:
        """A Transparency or its name; a bad name lists the choices.

        Parameters
        ----------
        value : Transparency or str
            A member or its name.
        """
        return _option_member(cls, value, "transparency")


class Projection(str, enum.Enum):
    """A camera's projection (equal to its value as a string, so older comparisons hold)."""

    PERSPECTIVE = "perspective"
    ORTHOGRAPHIC = "orthographic"

    @classmethod
    def parse(cls, value: object) -> Projection:
        """A Projection or its name; a bad name lists the choices.

        Parameters
        ----------
        value : Projection or str
            A member or its name.
        """
        return parse_enum(cls, value, "projection")


class Backend(enum.Enum):
    """Where a GL context comes from (:func:`glshade.create_context`). WINDOW is the
    viewer's own; headless rendering takes AUTO (on Linux EGL, the platform's own, then
    OSMesa; elsewhere the platform's own first), EGL, OSMESA or NATIVE."""

    AUTO = "auto"
    EGL = "egl"
    OSMESA = "osmesa"
    NATIVE = "native"  # the platform's own: CGL on macOS, WGL on Windows, GLX on Linux
    WINDOW = "window"

    @classmethod
    def parse(cls, value: object) -> Backend:
        """A Backend or a headless backend's name; a bad name lists the choices.

        Parameters
        ----------
        value : Backend or str
            A member or its name.
        """
        if isinstance(value, cls):
            return value
        try:
            return cls(str(value).lower())
        except ValueError:
            raise OptionError(f"unknown backend {value!r}; choose one of "
                              f"{', '.join(HEADLESS_BACKENDS)}") from None


#: the backends a headless render may name (the command line's --backend choices)
HEADLESS_BACKENDS = tuple(b.value for b in Backend if b is not Backend.WINDOW)


class Sampler(str, enum.Enum):
    """Where a path tracer's random numbers come from (equal to its value as a string)."""

    PCG = "pcg"      # independent: a PCG stream per pixel and sample
    SOBOL = "sobol"  # Owen-scrambled Sobol points at the first three vertices


class LobeSampling(str, enum.Enum):
    """How a path tracer draws a bounce's direction (equal to its value as a string): the
    same mean every way, the noise not."""

    VISIBLE_NORMALS = "visible-normals"  # glTF's specular lobe by GGX's visible normals
    NORMALS = "normals"                  # ... by its normals' distribution D(h) N.H
    UNIFORM = "uniform"                  # every material: uniform over the hemisphere


class Kernel(str, enum.Enum):
    """Which program a path tracer's passes run (equal to its value as a string): the same
    pass either way (shaders/include/trace_integrator.glsl), the same numbers."""

    AUTO = "auto"          # the faster here, by a short measurement on first use per GL
    FRAGMENT = "fragment"  # a fragment program over a full-screen triangle
    COMPUTE = "compute"    # a compute kernel, 8x8 invocations a group (GL 4.3)


class Accel(str, enum.Enum):
    """How a path tracer's rays find triangles (equal to its value as a string)."""

    AUTO = "auto"      # flat up to FLAT_LIMIT triangles, hybrid with small models, else bvh
    BVH = "bvh"        # the hierarchy's walk
    FLAT = "flat"      # every triangle in turn, compiled into the program
    HYBRID = "hybrid"  # the small models compiled in, the hierarchy for the rest


class PointStyle(str, enum.Enum):
    """How a point cloud's points are drawn (equal to its value as a string)."""

    SPHERE = "sphere"  # impostors ray cast per pixel: exact depth and normals
    DISC = "disc"      # splats oriented by the points' normals, ray cast per pixel
    SQUARE = "square"  # screen-aligned squares at the point's depth: the cheap mode


class LineUnits(str, enum.Enum):
    """What a polyline's width is measured in."""

    PIXELS = "pixels"  # the same width on screen at any depth
    WORLD = "world"    # scene units: narrower far away


class LineCaps(str, enum.Enum):
    """How a polyline's two ends are drawn."""

    BUTT = "butt"    # cut square at the end point
    ROUND = "round"  # a half disc of the line's width beyond it


class LineJoins(str, enum.Enum):
    """How two segments of a polyline meet."""

    MITER = "miter"  # the outer edges extended until they meet (bevelled when too long)
    ROUND = "round"  # a disc of the line's width at the joint


class Tessellation(str, enum.Enum):
    """Where a patch model is tessellated (equal to its value as a string)."""

    CPU = "cpu"  # once, when it is added: a mesh
    GPU = "gpu"  # at every draw, by GL 4.0 tessellation shaders: a PatchModel
