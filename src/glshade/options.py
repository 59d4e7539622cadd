"""How to draw and what to draw with: two frozen values shared by the renderer, the viewer,
animation, comparison, batches, radiosity, scene files and the command line, so no layer
re-declares an option, its default or its rule.

- :class:`DrawOptions`: how one draw looks (mode, depth test, culling, sRGB, outputs).
- :class:`RenderConfig`: what a Renderer is built with (image size, MSAA samples, backend).

Each value's rules are checked here, where it is made; the command line and the scene files
convert text and add where it came from."""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

from typing import Any

import numpy as np

from .errors import OptionError
from .modes import (Accel, Backend, Culling, Kernel, LobeSampling, Outputs, Sampler,
                    ShadingMode, Shadows, Transparency, choose)

__all__ = ["DrawOptions", "RenderConfig", "TraceOptions", "MAX_PATH_DEPTH", "MAX_STREAMS",
           "COHERENT_TILE", "DEFAULT_SIZE", "MAX_SIZE", "MSAA_COUNTS", "check_whole", "check_size",
           "check_samples", "HEMICUBE_RESOLUTION"]

#: the largest image side glshade makes (GL's framebuffers go no further on most drivers)
MAX_SIZE = 16384
#: the MSAA sample counts a draw may ask for (0: off); the GL may offer fewer
MSAA_COUNTS = (0, 1, 2, 4, 8, 16, 32, 64)

#: the most transparent layers a pixel's exact composite keeps (its sort runs per pixel)
MAX_LAYERS = 256

#: image size (width, height) when neither the command line nor a scene file gives one
DEFAULT_SIZE = (800, 600)
#: the hemicube's resolution unless one is asked for: the top face's pixels a side (the API,
#: the CLI and scene files all quote this one)
HEMICUBE_RESOLUTION = 128


@dataclass(frozen=True, init=False)
class DrawOptions:
    """Everything that decides how a scene is drawn, apart from where (target, viewport).

    Parameters
    ----------
    mode : shading mode (a ShadingMode or its name).
    depth_test : the z-buffer; False draws in submission order.
    cull : back-face culling (:class:`Culling`, or True, False, "auto"): AUTO culls closed,
        consistently oriented meshes wholly beyond the near plane, so seen from outside
        (from inside a mesh its back faces are what shows).
    srgb : encode the linear result as sRGB for display.
    wireframe : draw the polygons' edges alone, in their material's colour, instead of
        filled polygons (every edge shows: nothing is filled to hide the far ones).
    edges : draw the polygons' edges over the filled picture (dark; hidden edges stay
        hidden). Edges are each polygon's boundary, never its triangulation's diagonals.
    outputs : what the draw writes besides colour (:class:`Outputs`).
    shadows : cast shadows (:class:`Shadows` or its name): "off" (default), "exact" (a ray
        from each pixel's surface point to each light) or "map" (shadow maps with PCF). They
        shade the flat, Gouraud and Phong modes; the other modes show no light to shadow.
    transparency : how surfaces of opacity below 1 are composited (:class:`Transparency` or
        its name): "exact" (default: per-pixel fragment lists sorted by depth), "weighted"
        (McGuire-Bavoil's estimate) or "blend" (in drawing order).
    max_layers : the transparent surfaces "exact" keeps a pixel (the nearest; more are
        counted, reported and left out), default 32.
    frustum_cull : skip the opaque meshes and instances whose bounding box lies wholly
        outside the camera's view (one side of the frustum): the same picture, ids and
        depth, less work in scenes larger than the view. False draws everything.
    """

    mode: ShadingMode = ShadingMode.PHONG
    depth_test: bool = True
    cull: Culling = Culling.AUTO
    srgb: bool = False
    wireframe: bool = False
    outputs: Outputs = Outputs.COLOR
    edges: bool = False
    shadows: Shadows = Shadows.OFF
    transparency: Transparency = Transparency.EXACT
    max_layers: int = 32
    frustum_cull: bool = True

    def __init__(self, mode: ShadingMode | str = ShadingMode.PHONG, depth_test: bool = True,
                 cull: Culling | bool | str = Culling.AUTO, srgb: bool = False,
                 wireframe: bool = False, outputs: Outputs = Outputs.COLOR,
                 edges: bool = False, shadows: Shadows | str | bool = Shadows.OFF,
                 transparency: Transparency | str = Transparency.EXACT,
                 max_layers: int = 32, frustum_cull: bool = True) -> None:
        # (written out so that names are accepted where members are stored: a mode's name,
        # cull=True; the stored fields are the enums, and type checkers see both)
        put = object.__setattr__
        put(self, "mode", ShadingMode.parse(mode))
        put(self, "cull", Culling.parse(cull))
        put(self, "depth_test", depth_test)
        put(self, "srgb", srgb)
        put(self, "wireframe", wireframe)
        put(self, "outputs", outputs)
        put(self, "edges", edges)
        put(self, "shadows", Shadows.parse(shadows))
        put(self, "transparency", Transparency.parse(transparency))
        put(self, "max_layers", max_layers)
        put(self, "frustum_cull", frustum_cull)
        self._check()

    def _check(self) -> None:
        for name in ("depth_test", "srgb", "wireframe", "edges", "frustum_cull"):
            value = getattr(self, name)
            if not isinstance(value, bool):
                raise OptionError(f"{name} must be True or False, got {value!r}")
        if isinstance(self.max_layers, bool) or not isinstance(self.max_layers, int) or \
                not 1 <= self.max_layers <= MAX_LAYERS:
            raise OptionError(f"max_layers must be a whole number from 1 to {MAX_LAYERS}, got "
                              f"{self.max_layers!r}")
        if not isinstance(self.outputs, Outputs) or not self.outputs & Outputs.COLOR:
            raise OptionError(f"outputs must be an Outputs flag including COLOR, got "
                                f"{self.outputs!r}")

    def replace(self, **changes: Any) -> DrawOptions:
        """A copy with ``changes``; an unknown option is named with the valid ones.

        Parameters
        ----------
        **changes
            Options to replace, by name.
        """
        names = {f.name for f in fields(self)}
        unknown = sorted(set(changes) - names)
        if unknown:
            raise OptionError(f"unknown draw option(s) {', '.join(unknown)}; valid: "
                                f"{', '.join(sorted(names))}")
        return replace(self, **changes)

    @classmethod
    def of(cls, options: DrawOptions | ShadingMode | str | None = None,
           **changes: Any) -> DrawOptions:
        """Options from a DrawOptions, a shading mode (or its name) or nothing, with
        ``changes`` applied: what every public drawing function accepts. (The earlier
        keyword ``cull_back_faces`` is accepted for ``cull``.)

        Parameters
        ----------
        options : DrawOptions, ShadingMode, str or None
            The base (None: the defaults).
        **changes
            Options to replace, by name.
        """
        if "cull_back_faces" in changes:
            changes["cull"] = changes.pop("cull_back_faces")
        if options is None:
            base = cls()
        elif isinstance(options, cls):
            base = options
        else:  # a mode's name or member: one frozen value per mode, made once
            mode = ShadingMode.parse(options)
            made = _BY_MODE.get(mode)
            if made is None:
                made = _BY_MODE[mode] = cls(mode=mode)
            base = made
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


def check_whole(name: str, value: object, minimum: int) -> int:
    """``value`` as an int when it is a whole number >= ``minimum`` (bools refused).

    Parameters
    ----------
    name : str
        The option's name, as the message says it.
    value : object
        The value given.
    minimum : int
        The least it may be.
    """
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise OptionError(f"{name} must be a whole number >= {minimum}, got {value!r}")
    return int(value)


def check_size(width: object, height: object) -> tuple[int, int]:
    """The one rule for an image size: whole pixels, 1 to MAX_SIZE a side.

    Parameters
    ----------
    width, height : object
        The image's width and height in pixels, as given.
    """
    ok = all(not isinstance(v, bool) and isinstance(v, (int, np.integer))
             and 1 <= v <= MAX_SIZE for v in (width, height))
    if not ok:
        raise OptionError.must("size", f"be whole pixels from 1 to {MAX_SIZE} a side (width "
                               f"x height such as 800x600), got {width!r}x{height!r}")
    return int(width), int(height)  # type: ignore[call-overload]


def check_samples(samples: object) -> int:
    """The one rule for MSAA samples: 0 (off) or a power of two up to 64.

    Parameters
    ----------
    samples : object
        MSAA samples, as given.
    """
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) \
            or samples not in MSAA_COUNTS:
        raise OptionError.must("samples (MSAA)", "be 0 (off) or a power of two up to 64 "
                               f"such as 4, got {samples!r}")
    return int(samples)


@dataclass(frozen=True, init=False)
class RenderConfig:
    """What a Renderer is built with: one value that ``compare``, ``batch``, ``animate``,
    radiosity and the command line pass along, so each rule is checked once.

    Parameters
    ----------
    width, height : image size in pixels (>= 1).
    samples : MSAA samples per pixel (0 = off, which exact per-pixel comparisons use).
        Whether this GL offers the count is checked when the Renderer is made.
    backend : where the GL context comes from (:class:`Backend` or its name).
    device : which GPU, for EGL on a machine with several (None: the default).
    require_gpu : refuse a software rasterizer (None: ``GLSHADE_REQUIRE_GPU``).
    """

    width: int = 512
    height: int = 512
    samples: int = 4
    backend: Backend = Backend.AUTO
    device: int | None = None
    require_gpu: bool | None = None

    def __init__(self, width: int = 512, height: int = 512, samples: int = 4,
                 backend: Backend | str = Backend.AUTO, device: int | None = None,
                 require_gpu: bool | None = None) -> None:
        put = object.__setattr__
        width, height = check_size(width, height)
        put(self, "width", width)
        put(self, "height", height)
        put(self, "samples", check_samples(samples))
        put(self, "backend", Backend.parse(backend))
        put(self, "device", None if device is None else check_whole("device", device, 0))
        put(self, "require_gpu", None if require_gpu is None else bool(require_gpu))

    @property
    def size(self) -> tuple[int, int]:
        """``(width, height)`` in pixels."""
        return self.width, self.height

    def replace(self, **changes: Any) -> RenderConfig:
        """A copy with ``changes`` (checked like the original).

        Parameters
        ----------
        **changes
            Fields to replace, by name.
        """
        return replace(self, **changes)

    @classmethod
    def of(cls, config: RenderConfig | None = None, *, size: tuple[int, int] | None = None,
           samples: int | None = None, backend: Backend | str | None = None,
           base: RenderConfig | None = None) -> RenderConfig:
        """The config a function was given, or one from its convenience keywords laid over
        ``base`` (the function's defaults): what animate, compare, sweeps and batches take.

        Parameters
        ----------
        config : RenderConfig or None
            A whole config (then no other keyword may be given).
        size : (int, int) or None
            Width and height in pixels.
        samples : int or None
            MSAA samples (0 or a power of two up to 64).
        backend : Backend, str or None
            The headless backend.
        base : RenderConfig or None
            The calling function's defaults.
        """
        if config is not None:
            if not isinstance(config, RenderConfig):
                raise OptionError(f"config must be a RenderConfig, got "
                                  f"{type(config).__name__}")
            return config
        out = base or cls()
        changes: dict[str, Any] = {}
        if size is not None:
            changes["width"], changes["height"] = tuple(size)
        if samples is not None:
            changes["samples"] = samples
        if backend is not None:
            changes["backend"] = backend
        return out.replace(**changes) if changes else out


# ---- the path tracer's options ------------------------------------------------------------
# How paths are traced, as one value: TraceOptions, checked when it is made and then passed
# whole -- from the ``glshade pathtrace`` command or glshade.pathtrace.trace through
# PathTracer down to the GL pass that compiles it into its program. No layer below checks
# an option again, and none can be lost on the way: a new option is a field here, not a
# keyword threaded through three signatures.

#: the most vertices ``max_depth`` may ask of a path (a GL int, checked before any
#: arithmetic; far past what Russian roulette lets a path reach)
MAX_PATH_DEPTH = 1_000_000
#: the most streams a pixel's samples may be shared among (``TraceOptions.streams``)
MAX_STREAMS = 64
#: the pixels that share random numbers with ``coherent=True``: llvmpipe shades a 4x2 block
#: in one 8-wide SIMD step (docs/guide/speed.md: measured against 2x2 to 8x8)
COHERENT_TILE = (4, 2)


def _tile(coherent: Any) -> tuple[int, int]:
    """The (width, height) of the blocks of pixels ``coherent`` asks to share random
    numbers: False (1, 1), True ``COHERENT_TILE``, or a pair of whole numbers 1 to 64."""
    if coherent is False or coherent is None:
        return (1, 1)
    if coherent is True:
        return COHERENT_TILE
    try:
        pair = tuple(coherent)
        ok = len(pair) == 2 and all(float(v) == int(v) and 1 <= int(v) <= 64 for v in pair)
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise OptionError(f"coherent must be True, False or a block's (width, height) in "
                          f"pixels, each from 1 to 64, got {coherent!r}")
    return int(pair[0]), int(pair[1])


def _path_depth(value: object) -> int:
    """``max_depth`` as an int: a whole number of vertices, 1 to MAX_PATH_DEPTH."""
    number = check_whole("max_depth", value, 1)
    if number > MAX_PATH_DEPTH:  # (a GL int; checked before any arithmetic)
        raise OptionError(f"max_depth must be at most {MAX_PATH_DEPTH:,} (vertices a path "
                          f"may have), got {number:,}")
    return number


@dataclass(frozen=True)
class TraceOptions:
    """Everything that decides how paths are traced, apart from the scene, the camera and
    how many samples: checked once, when made (each field takes an enum member or its
    name; a bad value raises :class:`~glshade.errors.OptionError` naming the field).

    Parameters
    ----------
    max_depth : int or None
        Vertices a path may have, 1 to ``MAX_PATH_DEPTH`` (None: no limit -- Russian
        roulette ends paths, so the answer is the rendering equation's).
    accel : Accel or str
        How rays find triangles: ``"bvh"`` (a hierarchy), ``"flat"`` (each in turn,
        compiled into the program), ``"hybrid"`` (the smallest models compiled in, the
        hierarchy for the rest) or ``"auto"`` (flat for small scenes, else hybrid where
        small models sit beside large ones, else the hierarchy) -- the same picture, to
        rounding, every way.
    sampler : Sampler or str
        ``"pcg"`` (independent random numbers) or ``"sobol"`` (Owen-scrambled Sobol points
        at a path's first vertices: less error for the same samples, unbiased either way).
    mis : bool
        Emission found by next-event estimation and by the bounce alike, weighed by Veach's
        power heuristic (False: next-event estimation alone after the first vertex).
    lobe_sampling : LobeSampling or str
        How a bounce's direction is drawn: ``"visible-normals"`` (glTF's specular lobe by
        GGX's visible normals, Heitz 2018; the diffuse lobe by the cosine; the lobe by its
        Fresnel weight), ``"normals"`` (the specular lobe by its normals' distribution
        D(h) cos(theta_h), Walter et al. 2007, as Mitsuba's ``sample_visible=false``) or
        ``"uniform"`` (every material uniformly over the hemisphere: no importance at all,
        the baseline the others are measured against) -- the same mean every way, the
        noise not.
    coherent : bool or (int, int)
        Blocks of pixels (True: ``COHERENT_TILE``, or a (width, height) in pixels, 1 to 64)
        that draw the same random numbers, so their rays run together in a SIMD step: each
        pixel's estimate as unbiased and as noisy, the block's errors correlated. Stored as
        the block's size, (1, 1) for none.
    storage : bool or None
        Whether the hierarchy's walk reads storage buffers (GL 4.3) rather than texel
        fetches (GL 3.3's way) -- the same picture to the byte (None: where the GL has
        them).
    kernel : Kernel or str
        ``"fragment"`` (a fragment program a pass), ``"compute"`` (a compute kernel, GL
        4.3: what a GPU with few graphics units wants) or ``"auto"`` (the faster on this
        GL, measured on first use and kept per renderer and driver) -- the same passes,
        the same numbers.
    streams : int or None
        Invocations that share each pixel's samples, 1 to ``MAX_STREAMS`` (sample k goes
        to stream k mod ``streams``; the sums are added when read): a GPU holds far more
        invocations at once than a small picture has pixels (an H100 about 270,000, a 128²
        picture 16,384), and one invocation a pixel would leave most of it idle. The same
        samples, the same picture to rounding. None: one on a software renderer, else
        enough for the tracer's ``FILL_INVOCATIONS``.

    Examples
    --------
    >>> from glshade.pathtrace import TraceOptions
    >>> options = TraceOptions.of(sampler="sobol", coherent=True)
    >>> options.sampler, options.coherent
    (<Sampler.SOBOL: 'sobol'>, (4, 2))
    """

    max_depth: int | None = None
    accel: Accel = Accel.AUTO
    sampler: Sampler = Sampler.PCG
    mis: bool = True
    lobe_sampling: LobeSampling = LobeSampling.VISIBLE_NORMALS
    coherent: tuple[int, int] = (1, 1)
    storage: bool | None = None
    kernel: Kernel = Kernel.AUTO
    streams: int | None = None

    def __post_init__(self) -> None:
        put = object.__setattr__  # (frozen: each field replaced by its checked form)
        if self.max_depth is not None:
            put(self, "max_depth", _path_depth(self.max_depth))
        put(self, "accel", choose(Accel, self.accel, "accel"))
        put(self, "sampler", choose(Sampler, self.sampler, "sampler"))
        put(self, "kernel", choose(Kernel, self.kernel, "kernel"))
        put(self, "lobe_sampling", choose(LobeSampling, self.lobe_sampling, "lobe_sampling"))
        if not isinstance(self.mis, bool):
            raise OptionError(f"mis must be True or False, got {self.mis!r}")
        if not isinstance(self.storage, bool) and self.storage is not None:
            raise OptionError(f"storage must be True, False or None (where the GL has "
                              f"storage buffers), got {self.storage!r}")
        put(self, "coherent", _tile(self.coherent))
        if self.streams is not None:
            put(self, "streams", check_whole("streams", self.streams, 1))
            if self.streams > MAX_STREAMS:
                raise OptionError(f"streams must be 1 to {MAX_STREAMS} (invocations sharing "
                                  f"a pixel's samples), got {self.streams}")

    @classmethod
    def of(cls, options: TraceOptions | None = None, **changes: Any) -> TraceOptions:
        """``options`` (default: the defaults) with ``changes`` applied and checked: what
        every tracing function accepts beside its own keywords.

        Parameters
        ----------
        options : TraceOptions or None
            The base value.
        **changes
            Fields to replace, by name (an unknown name is refused, naming the fields).
        """
        if options is not None and not isinstance(options, cls):
            raise OptionError(f"options must be a TraceOptions, got {type(options).__name__}")
        base = options or cls()
        names = {f.name for f in fields(cls)}
        unknown = sorted(set(changes) - names)
        if unknown:
            raise OptionError(f"TraceOptions has no {', '.join(unknown)}: its fields are "
                              f"{', '.join(sorted(names))}")
        return replace(base, **changes) if changes else base
