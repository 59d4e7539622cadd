"""OpenGL contexts: a ladder of headless backends, each one moderngl context.

1. ``egl``: moderngl's standalone EGL context. With a GPU this is the vendor's driver
   (``device=`` or ``GLSHADE_EGL_DEVICE`` picks one of several); without one it is Mesa's
   llvmpipe through EGL, surfaceless: no display needed. The default, and what CI uses.
2. ``native``: moderngl's default standalone context for the platform -- CGL on macOS, WGL
   on Windows, GLX on Linux (an X display: a desktop, or ``xvfb-run``). The first rung on
   macOS and Windows, where EGL and OSMesa do not exist; a Mac's GL is 4.1 core, and the
   passes take the paths its :class:`~glshade.render.features.Features` say.
3. ``osmesa``: Mesa's off-screen library (Debian ``libosmesa6``) through ctypes, for systems
   without EGL. Mesa 25.1 dropped OSMesa, so this is a fallback, never the default.

``auto`` walks the ladder (:func:`ladder`: EGL, native, OSMesa on Linux; native first
elsewhere) (``GLSHADE_BACKEND`` overrides it, read when a context is made,
never at import). One backend per process is the simple rule: after an OSMesa context has
been current, an EGL context made later in the same process can silently draw nothing.
"""

from __future__ import annotations

from typing import Any

import ctypes
import threading
import ctypes.util
import os
import re
import sys

from ..errors import ContextError, NoGpuError, OptionError
from .features import Features
from ..interrupt import held
from ..modes import Backend

__all__ = ["Backend", "RenderContext", "create_context", "window_context", "probe_backends",
           "tune_malloc", "egl_devices", "device_index", "worker_devices", "ladder"]

REQUIRE = 330


_EGL_ERRORS = {
    0x3000: "EGL_SUCCESS", 0x3001: "EGL_NOT_INITIALIZED (no usable EGL driver)",
    0x3002: "EGL_BAD_ACCESS", 0x3003: "EGL_BAD_ALLOC (out of memory)",
    0x3004: "EGL_BAD_ATTRIBUTE", 0x3005: "EGL_BAD_CONFIG (no matching framebuffer config)",
    0x3006: "EGL_BAD_CONTEXT", 0x3007: "EGL_BAD_CURRENT_SURFACE",
    0x3008: "EGL_BAD_DISPLAY (the device or display cannot be opened)",
    0x3009: "EGL_BAD_MATCH (the driver cannot make this context)",
    0x300A: "EGL_BAD_NATIVE_PIXMAP", 0x300B: "EGL_BAD_NATIVE_WINDOW",
    0x300C: "EGL_BAD_PARAMETER", 0x300D: "EGL_BAD_SURFACE",
    0x300E: "EGL_CONTEXT_LOST",
}

_EGL_HINT = ("install Mesa's EGL (Debian/Ubuntu: apt-get install libegl1 libegl-mesa0 "
             "libgl1-mesa-dri; Fedora: mesa-libEGL mesa-dri-drivers), or a GPU driver with EGL")
_OSMESA_HINT = "install Mesa's OSMesa (Debian/Ubuntu: apt-get install libosmesa6)"


def _explain_egl(exc: BaseException) -> str:
    text = str(exc).strip() or type(exc).__name__

    def word(m):
        code = int(m.group(0), 16)
        return f"{m.group(0)} = {_EGL_ERRORS.get(code, 'unknown EGL error')}"

    return re.sub(r"0x3[0-9a-fA-F]{3}", word, text)


# ------------------------------------------------------------------------------ OSMesa

_OSMESA_RGBA = 0x1908
_OSMESA_FORMAT, _OSMESA_DEPTH_BITS, _OSMESA_STENCIL_BITS = 0x22, 0x30, 0x31
_OSMESA_PROFILE, _OSMESA_CORE_PROFILE = 0x33, 0x34
_OSMESA_MAJOR, _OSMESA_MINOR = 0x36, 0x37
_GL_UNSIGNED_BYTE = 0x1401


def _find_osmesa() -> str:
    override = os.environ.get("GLSHADE_OSMESA_LIBRARY")
    if override:
        return override
    return ctypes.util.find_library("OSMesa") or "libOSMesa.so.8"


class OSMesaLoader:
    """An OSMesa context made current on a small private buffer, in the shape moderngl
    wants for a custom context: ``load_opengl_function(name)`` and ``release()``."""

    def __init__(self):
        name = _find_osmesa()
        try:
            lib = ctypes.CDLL(name)
        except OSError as exc:
            raise ContextError(f"cannot load {name}: {exc}") from None
        for fn in ("OSMesaCreateContextAttribs", "OSMesaMakeCurrent", "OSMesaGetProcAddress",
                   "OSMesaDestroyContext"):
            if not hasattr(lib, fn):
                raise ContextError(f"{name} lacks {fn} (Mesa too old for core profiles)")
        lib.OSMesaCreateContextAttribs.restype = ctypes.c_void_p
        lib.OSMesaCreateContextAttribs.argtypes = [ctypes.POINTER(ctypes.c_int), ctypes.c_void_p]
        lib.OSMesaMakeCurrent.restype = ctypes.c_int
        lib.OSMesaMakeCurrent.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int,
                                          ctypes.c_int, ctypes.c_int]
        lib.OSMesaGetProcAddress.restype = ctypes.c_void_p
        lib.OSMesaGetProcAddress.argtypes = [ctypes.c_char_p]
        lib.OSMesaDestroyContext.argtypes = [ctypes.c_void_p]
        attribs = (ctypes.c_int * 13)(
            _OSMESA_FORMAT, _OSMESA_RGBA, _OSMESA_DEPTH_BITS, 24, _OSMESA_STENCIL_BITS, 8,
            _OSMESA_PROFILE, _OSMESA_CORE_PROFILE, _OSMESA_MAJOR, 3, _OSMESA_MINOR, 3, 0)
        handle = lib.OSMesaCreateContextAttribs(attribs, None)
        if not handle:
            raise ContextError(f"{name}: OSMesaCreateContextAttribs failed to make a 3.3 core "
                               "context")
        self._buffer = (ctypes.c_ubyte * (4 * 4 * 4))()
        if not lib.OSMesaMakeCurrent(handle, self._buffer, _GL_UNSIGNED_BYTE, 4, 4):
            lib.OSMesaDestroyContext(handle)
            raise ContextError(f"{name}: OSMesaMakeCurrent failed")
        self._lib, self._handle, self.library = lib, handle, name

    def __enter__(self):
        """Make this context current again (moderngl calls it from ``ctx.__enter__``)."""
        if self._handle:
            self._lib.OSMesaMakeCurrent(self._handle, self._buffer, _GL_UNSIGNED_BYTE, 4, 4)
        return self

    def __exit__(self, *exc):
        return None

    def load_opengl_function(self, name: str) -> int:
        return self._lib.OSMesaGetProcAddress(name.encode()) or 0

    def release(self) -> None:
        if self._handle:
            self._lib.OSMesaDestroyContext(self._handle)
            self._handle = None


# -------------------------------------------------------------------------- contexts

class RenderContext:
    """Owns one moderngl context and every GL object made through it.

    Children register with :meth:`track`; :meth:`release` frees them in reverse creation
    order, then the context. Usable with ``with``; a second release does nothing.

    Parameters
    ----------
    ctx : moderngl.Context
        The context it owns.
    backend : Backend
        The headless backend that made it.
    detail : str
        What the backend says of itself (the renderer's name, the device).
    loader : object or None
        The backend's library handle, kept alive as long as the context.
    tier : str or None
        Hold the context to an older GL's paths (``"4.1"``: a Mac's; ``"3.3"``):
        :meth:`Features.capped <glshade.render.features.Features.capped>`.
    """

    def __init__(self, ctx, backend: Backend, detail: str = "", loader=None,
                 tier: str | None = None):
        self.ctx = ctx
        self.backend = backend
        self.detail = detail
        self._loader = loader
        self._children: list = []
        self.released = False
        self._features: Features | None = None  # (read from the driver when first asked)
        self._tier: str | None = tier
        # A framebuffer to bind while others are released: moderngl re-binds the previously
        # bound framebuffer after making a new one, and a deleted one would be an error.
        self._idle = ctx.simple_framebuffer((1, 1))
        self.thread = threading.get_ident()  # (the thread it is current on)
        # (moderngl's ``info`` asks for every limit, compute shaders' too: on a GL before 4.3
        # those queries leave GL_INVALID_ENUM, read and cleared here)
        _ = ctx.error

    def make_current(self) -> None:
        """Make this context current on the calling thread: with several contexts in one
        process, whichever was made or used last is current, and GL calls go there. A
        context stays current on the thread that made it, so another thread is refused
        (EGL cannot make it current there: its draws would go nowhere)."""
        self.check()
        if threading.get_ident() != self.thread:
            raise ContextError(
                f"this GL context ({self.backend.value}) was made on thread {self.thread} "
                f"and is used from thread {threading.get_ident()}: a context belongs to "
                "the thread that made it; make the Renderer (or context) in the thread that "
                "draws with it")
        self.ctx.__enter__()

    def rest(self) -> None:
        """Bind the context's own 1x1 framebuffer (before releasing a bound one)."""
        if not self.released:
            self._idle.use()

    def track(self, obj):
        """Keep ``obj`` to release with the context (in reverse order of making); returns it.

        Parameters
        ----------
        obj : GL object
            A moderngl object or a GLResource.
        """
        self._children.append(obj)
        return obj

    def untrack(self, obj) -> None:
        """Forget ``obj`` (released by its owner first).

        Parameters
        ----------
        obj : GL object
            What :meth:`track` was given.
        """
        try:
            self._children.remove(obj)
        except ValueError:
            pass

    @property
    def software(self) -> bool:
        """Whether this GL rasterizes on the CPU (Mesa's llvmpipe, softpipe, swrast)."""
        return any(w in self.detail.lower() for w in SOFTWARE_RENDERERS)

    @property
    def info(self) -> dict:
        self.check()
        i = self.ctx.info
        return {
            "backend": self.backend.value,
            "vendor": i.get("GL_VENDOR"), "renderer": i.get("GL_RENDERER"),
            "version": i.get("GL_VERSION"), "glsl": i.get("GL_SHADING_LANGUAGE_VERSION"),
            "max_samples": self.ctx.max_samples,
            "max_texture_size": i.get("GL_MAX_TEXTURE_SIZE"),
            "detail": self.detail,
        }

    def check(self) -> None:
        if self.released:
            raise ContextError("this RenderContext was released; make a new one")

    @property
    def features(self) -> Features:
        """What this context can do and the path each feature takes here
        (:class:`~glshade.render.features.Features`), decided once from its version and
        extensions."""
        if self._features is None:
            self._features = Features.of(self.ctx, self.detail).capped(self._tier)
        return self._features

    def hold_to(self, tier: str | None) -> None:
        """Take an older GL's paths from now on (``"4.1"``: a Mac's, ``"3.3"``), or the
        context's own (None) -- before anything is drawn with it: passes keep what they
        made for the tier they found.

        Parameters
        ----------
        tier : str or None
            ``"4.3"``, ``"4.1"``, ``"3.3"`` or None.
        """
        self._features = Features.of(self.ctx, self.detail).capped(tier)
        self._tier = tier

    def require(self, version: int, what: str, instead: str) -> None:
        """Refuse, in one line, a feature this GL is too old for
        (:meth:`Features.require <glshade.render.features.Features.require>`).

        Parameters
        ----------
        version : int
            GL's version code needed (430: 4.3).
        what : str
            What needs it, ending in the verb ("kernel='compute' needs").
        instead : str
            The way that works on this GL.
        """
        self.features.require(version, what, instead)

    def release(self) -> None:
        if self.released:
            return
        self.ctx.__enter__()
        for child in reversed(self._children):
            child.release()
        self._children.clear()
        self._idle.release()
        self.ctx.release()
        if self._loader is not None:
            self._loader.release()
        self.released = True

    def __enter__(self) -> RenderContext:
        return self

    def __exit__(self, *exc):
        self.release()

    def __repr__(self) -> str:
        state = "released" if self.released else self.detail
        return f"<RenderContext {self.backend.value}: {state}>"


#: what a software rasterizer's GL_RENDERER string holds (Mesa's)
SOFTWARE_RENDERERS = ("llvmpipe", "softpipe", "swrast")
#: device files whose presence says a GPU is on the machine (NVIDIA's, and DRM render
#: nodes): a software rasterizer chosen beside them is worth a warning
GPU_DEVICE_FILES = ("/dev/nvidia[0-9]*", "/dev/dri/renderD*")
#: why a software rasterizer answers where a GPU was wanted, most often
NO_GPU_CAUSE = ("usually a container started without the GPU (docker run --gpus all) or "
                "without NVIDIA's EGL vendor file (/usr/share/glvnd/egl_vendor.d/"
                "10_nvidia.json); glshade doctor lists the devices EGL sees")


def require_gpu_wanted(require_gpu: bool | None) -> bool:
    """``require_gpu`` as given, else the environment's ``GLSHADE_REQUIRE_GPU`` (1, true,
    yes: what ``--require-gpu`` sets for a run and its workers).

    Parameters
    ----------
    require_gpu : bool or None
        The caller's choice (None: the environment's).
    """
    if require_gpu is not None:
        return bool(require_gpu)
    return os.environ.get("GLSHADE_REQUIRE_GPU", "").strip().lower() in ("1", "true", "yes")


def check_gpu(context: RenderContext, require_gpu: bool | None = None,
              release: bool = True) -> None:
    """Refuse a software rasterizer where a GPU is required (the context released, one
    line naming what was found and the usual cause: :class:`NoGpuError`); else warn when
    one is chosen while the machine has GPU device files (a fallback nobody would notice).

    Parameters
    ----------
    context : RenderContext
        The context just made.
    require_gpu : bool or None
        Whether a GPU is required (None: ``GLSHADE_REQUIRE_GPU``).
    release : bool
        Release the context when refusing it (not one the caller owns).
    """
    import glob
    import warnings

    if not context.software:
        return
    if require_gpu_wanted(require_gpu):
        found = f"{context.backend.value}: {context.detail}"
        if release:
            context.release()
        raise NoGpuError(f"a GPU was required, and this GL is a software rasterizer "
                         f"({found}): {NO_GPU_CAUSE}")
    present = sorted(p for pattern in GPU_DEVICE_FILES for p in glob.glob(pattern))
    if present:
        from ..errors import RenderWarning

        warnings.warn(f"rendering on a software rasterizer ({context.detail}) although this "
                      f"machine has GPU device files ({', '.join(present[:3])}): "
                      f"{NO_GPU_CAUSE}", RenderWarning, stacklevel=3)


#: eglQueryDeviceStringEXT's and eglQueryDeviceAttribEXT's names (EGL_EXT_device_query,
#: EGL_EXT_device_drm, EGL_EXT_device_drm_render_node, EGL_EXT_device_query_name,
#: EGL_NV_device_cuda)
_EGL_EXTENSIONS, _EGL_VENDOR, _EGL_RENDERER = 0x3055, 0x3053, 0x335F
_EGL_DRM_DEVICE_FILE, _EGL_DRM_RENDER_NODE_FILE, _EGL_CUDA_DEVICE_NV = 0x3233, 0x3377, 0x323A


class _EglDevices:
    """The driver's EGL devices, through EGL_EXT_device_enumeration and _query: their
    handles and what each says of itself -- no context made on any (on a node where a
    scheduler granted one GPU of eight, a context on each would be slow at best)."""

    def __init__(self):
        self.handles: list = []
        self.egl: Any = None
        try:
            self.egl = ctypes.CDLL(ctypes.util.find_library("EGL") or "libEGL.so.1")
        except OSError:
            return
        self.egl.eglGetProcAddress.restype = ctypes.c_void_p
        self.egl.eglGetProcAddress.argtypes = [ctypes.c_char_p]
        query = self._function("eglQueryDevicesEXT", ctypes.c_uint, ctypes.c_int,
                               ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_int))
        count = ctypes.c_int(0)
        if query is None or not query(0, None, ctypes.byref(count)) or count.value <= 0:
            return
        found = (ctypes.c_void_p * count.value)()
        if query(count.value, found, ctypes.byref(count)):
            self.handles = list(found)[:count.value]

    def _function(self, name: str, restype, *argtypes):
        address = self.egl.eglGetProcAddress(name.encode())
        return ctypes.CFUNCTYPE(restype, *argtypes)(address) if address else None

    def string(self, handle, name: int) -> str | None:
        query = self._function("eglQueryDeviceStringEXT", ctypes.c_char_p, ctypes.c_void_p,
                               ctypes.c_int)
        if query is None:
            return None
        value = query(handle, name)
        return value.decode("utf-8", "replace") if value else None

    def attribute(self, handle, name: int) -> int | None:
        query = self._function("eglQueryDeviceAttribEXT", ctypes.c_uint, ctypes.c_void_p,
                               ctypes.c_int, ctypes.POINTER(ctypes.c_ssize_t))
        value = ctypes.c_ssize_t(0)
        if query is None or not query(handle, name, ctypes.byref(value)):
            return None
        return int(value.value)

    def describe(self, index: int) -> dict:
        """One device: ``index``, ``name`` (its vendor and renderer where the driver names
        them, else its kind), ``software``, ``cuda`` (its CUDA ordinal, where the driver
        has EGL_NV_device_cuda), ``node`` (its DRM render node or device file) and
        ``extensions``."""
        handle = self.handles[index]
        extensions = (self.string(handle, _EGL_EXTENSIONS) or "").split()
        software = "EGL_MESA_device_software" in extensions
        vendor = self.string(handle, _EGL_VENDOR) if \
            "EGL_EXT_device_query_name" in extensions else None
        renderer = self.string(handle, _EGL_RENDERER) if vendor is not None else None
        cuda = self.attribute(handle, _EGL_CUDA_DEVICE_NV) if \
            "EGL_NV_device_cuda" in extensions else None
        node = (self.string(handle, _EGL_DRM_RENDER_NODE_FILE) if
                "EGL_EXT_device_drm_render_node" in extensions else None) or \
            (self.string(handle, _EGL_DRM_DEVICE_FILE) if "EGL_EXT_device_drm" in extensions
             else None)
        if vendor or renderer:
            name = " ".join(x for x in (vendor, renderer) if x)
        elif software:  # (Mesa's software device: llvmpipe unless GALLIUM_DRIVER says)
            name = f"Mesa software ({os.environ.get('GALLIUM_DRIVER', 'llvmpipe')})"
        elif cuda is not None:
            name = f"NVIDIA (CUDA {cuda})"
        else:
            name = f"GPU ({node})" if node else "unnamed device"
        return {"index": index, "name": name, "software": software, "cuda": cuda,
                "node": node, "extensions": extensions}


def egl_device_count() -> int:
    """How many EGL devices the driver lists (EGL_EXT_device_enumeration), 0 when it
    lists none or cannot say."""
    return len(_EglDevices().handles)


def egl_devices() -> list[dict]:
    """Every EGL device, described by the driver without a context made on any (see
    :meth:`_EglDevices.describe`: ``index``, ``name``, ``software``, ``cuda``, ``node``,
    ``extensions``) -- what ``glshade doctor`` lists and ``--device`` /
    ``GLSHADE_EGL_DEVICE`` choose from, by index, CUDA ordinal or name."""
    found = _EglDevices()
    return [found.describe(i) for i in range(len(found.handles))]


def _cuda_shown() -> list[str] | None:
    """The devices ``CUDA_VISIBLE_DEVICES`` shows a program, in order, as CUDA reads it (up
    to the first ``-1``); None where it is unset or empty (every device)."""
    visible = os.environ.get("CUDA_VISIBLE_DEVICES")
    if visible is None or not visible.strip():
        return None
    listed = [x.strip() for x in visible.split(",") if x.strip()]
    return listed[:listed.index("-1")] if "-1" in listed else listed


def _cuda_visible(ordinal: int) -> int:
    """A CUDA ordinal as a program sees it (``cuda:N``) to the device's own, through
    ``CUDA_VISIBLE_DEVICES`` as CUDA reads it (a list of ordinals; UUIDs cannot be mapped
    without NVIDIA's management library: refused in one line)."""
    visible = os.environ.get("CUDA_VISIBLE_DEVICES")
    listed = _cuda_shown()
    if listed is None:
        return ordinal
    if not all(x.isdigit() for x in listed):
        raise OptionError(f"cuda:{ordinal}: CUDA_VISIBLE_DEVICES={visible!r} names devices "
                          "by UUID, which EGL cannot match: give ordinals there, or an EGL "
                          "index (glshade doctor lists them)")
    shown = [int(x) for x in listed]
    if ordinal >= len(shown):
        raise OptionError(f"cuda:{ordinal} does not exist: CUDA_VISIBLE_DEVICES={visible!r} "
                          f"shows {len(shown)} device{'s' if len(shown) != 1 else ''}")
    return shown[ordinal]


def device_index(spec) -> int:
    """An EGL device by index (``"1"``), by CUDA ordinal (``"cuda:1"``: the CUDA device a
    program sees as 1, through ``CUDA_VISIBLE_DEVICES``, matched to its EGL device by
    EGL_NV_device_cuda) or by name (a case-blind part of it: ``"nvidia"``, ``"llvmpipe"``);
    one line naming those present when no device (or more than one, by name) matches.

    Parameters
    ----------
    spec : int or str
        An index (``1``, ``"1"``), ``"cuda:N"``, or a case-blind part of a device's name.
    """
    text = str(spec).strip()
    devices = egl_devices()
    present = "; ".join(f"{d['index']}: {d['name']}" +
                        (f" (cuda:{d['cuda']})" if d["cuda"] is not None else "")
                        for d in devices) or "none"
    if text.isdigit():
        if int(text) < len(devices):
            return int(text)
        raise OptionError(f"EGL device {text} does not exist; present: {present}")
    if text.lower().startswith("cuda:"):
        number = text[5:].strip()
        if not number.isdigit():
            raise OptionError(f"{text!r}: a CUDA device is cuda:N, N a whole number")
        ordinal = _cuda_visible(int(number))
        hits = [d["index"] for d in devices if d["cuda"] == ordinal]
        if hits:
            return hits[0]
        raise OptionError(f"{text} (CUDA device {ordinal}) is no EGL device here: no device "
                          f"says it is (EGL_NV_device_cuda); present: {present}")
    hits = [d["index"] for d in devices if text.lower() in d["name"].lower()]
    if len(hits) == 1:
        return hits[0]
    raise OptionError(f"EGL device {text!r} " + ("matches several" if hits else
                      "matches none") + f"; present: {present}")


def worker_devices() -> list[str]:
    """The devices a pool's workers are dealt, one each in turn (their
    ``GLSHADE_WORKER_RANK``, which :mod:`glshade.parallel` sets, modulo their number):
    ``GLSHADE_WORKER_DEVICES`` (a comma list of what ``--device`` takes), else the GPUs CUDA
    shows (``cuda:0`` to ``cuda:K-1`` under ``CUDA_VISIBLE_DEVICES``, as a scheduler grants
    them), else every GPU EGL lists; none where there is at most one (each worker takes
    what a render would). Listed without a context on any device."""
    spec = os.environ.get("GLSHADE_WORKER_DEVICES", "").strip()
    if spec:
        return [x.strip() for x in spec.split(",") if x.strip()]
    try:
        gpus = [d for d in egl_devices() if not d["software"]]
    except Exception:  # (no EGL here: the worker's own backend decides)
        return []
    shown = _cuda_shown()
    if shown is not None and any(d["cuda"] is not None for d in gpus):
        return [f"cuda:{k}" for k in range(len(shown))] if len(shown) > 1 else []
    return [str(d["index"]) for d in gpus] if len(gpus) > 1 else []


def _asked(device) -> tuple[str, str, str] | None:
    """The device a context is asked to take, ``(spec, where, why)`` -- ``where`` the
    prefix that names it in an error: ``device`` if given, else ``GLSHADE_EGL_DEVICE``,
    else a pool worker's turn of :func:`worker_devices` (its ``GLSHADE_WORKER_RANK``, which
    :mod:`glshade.parallel` sets); None where nothing asks (the driver's choice)."""
    if device not in (None, ""):
        return str(device), "", "asked for (--device / device=)"
    env = os.environ.get("GLSHADE_EGL_DEVICE", "").strip()
    if env:
        return env, "GLSHADE_EGL_DEVICE: ", "GLSHADE_EGL_DEVICE"
    rank = os.environ.get("GLSHADE_WORKER_RANK", "").strip()
    devices = worker_devices() if rank.isdigit() else []
    if not devices:
        return None
    spec = devices[int(rank) % len(devices)]
    source = "GLSHADE_WORKER_DEVICES" if os.environ.get("GLSHADE_WORKER_DEVICES", "").strip() \
        else "its host's GPUs"
    return spec, "GLSHADE_WORKER_DEVICES: ", f"dealt to pool worker {rank} from {source}: {spec}"


def _index(asked: tuple[str, str, str]) -> int:
    """The EGL index of an :func:`_asked` device; one line naming where it was asked."""
    try:
        return device_index(asked[0])
    except OptionError as exc:
        raise OptionError(f"{asked[1]}{exc}") from None


def chosen_device(device: int | str | None = None) -> tuple[int | None, str]:
    """Which EGL device a context would be made on, and why: ``device`` if given, else
    ``GLSHADE_EGL_DEVICE``, else a pool worker's turn of the devices
    (:func:`worker_devices`), else the driver's first (glcontext's default, or its own
    ``GLCONTEXT_DEVICE_INDEX``, which it reads from the environment).

    Parameters
    ----------
    device : int, str or None
        The caller's choice.
    """
    asked = _asked(device)
    if asked is not None:
        return _index(asked), asked[2]
    other = os.environ.get("GLCONTEXT_DEVICE_INDEX", "").strip()
    if other.isdigit():
        return int(other), "GLCONTEXT_DEVICE_INDEX (glcontext's own)"
    return (0, "the driver's first") if egl_device_count() else (None, "no EGL device")


def _make_egl(device: int | str | None) -> RenderContext:
    import moderngl

    settings: dict[str, Any] = {"backend": "egl"}
    asked = _asked(device)
    if asked is not None:
        settings["device_index"] = _index(asked)
        other = os.environ.get("GLCONTEXT_DEVICE_INDEX", "").strip()
        if other and other != str(settings["device_index"]):
            import warnings

            from ..errors import RenderWarning

            warnings.warn(f"GLCONTEXT_DEVICE_INDEX={other} is set and disagrees with the EGL "
                          f"device asked for ({settings['device_index']}): glcontext lets it "
                          "override a program's choice, so glshade sets it to its own for "
                          "the context it makes; unset it to avoid doubt",
                          RenderWarning, stacklevel=4)
    saved = os.environ.get("GLCONTEXT_DEVICE_INDEX")
    try:
        with held():  # (a Ctrl-C waits for the driver to finish making the context)
            if "device_index" in settings and saved is not None:
                # (glcontext reads this over the index it is given: the choice made here wins)
                os.environ["GLCONTEXT_DEVICE_INDEX"] = str(settings["device_index"])
            ctx = moderngl.create_context(standalone=True, require=REQUIRE, **settings)
    except Exception as exc:  # moderngl/glcontext raise bare Exceptions with EGL text
        raise ContextError(_explain_egl(exc)) from None
    finally:
        if saved is not None:
            os.environ["GLCONTEXT_DEVICE_INDEX"] = saved
    return RenderContext(ctx, Backend.EGL, ctx.info.get("GL_RENDERER", ""))


def _make_osmesa() -> RenderContext:
    import moderngl

    loader = OSMesaLoader()
    try:
        # (moderngl's stubs want a dict for ``context``; glcontext takes a loader object)
        with held():
            ctx = moderngl.create_context(standalone=True, require=REQUIRE,
                                          context=loader)  # type: ignore[arg-type]
    except Exception as exc:
        loader.release()
        raise ContextError(f"moderngl could not use the OSMesa context: {exc}") from None
    return RenderContext(ctx, Backend.OSMESA, ctx.info.get("GL_RENDERER", ""), loader)


def _make_native() -> RenderContext:
    import moderngl

    try:
        with held():
            # (glcontext's default for the platform: CGL on macOS, WGL on Windows, GLX on
            # Linux, which wants an X display)
            ctx = moderngl.create_context(standalone=True, require=REQUIRE)
    except Exception as exc:
        text = str(exc).strip() or type(exc).__name__
        if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
            text += " (GLX needs an X display: DISPLAY is not set)"
        raise ContextError(text) from None
    return RenderContext(ctx, Backend.NATIVE, ctx.info.get("GL_RENDERER", ""))


def window_context() -> RenderContext:
    """The RenderContext of the window whose GL context is current (glfw's, made by the
    viewer): moderngl wraps it; the window keeps only this."""
    import moderngl

    ctx = moderngl.create_context(require=REQUIRE)
    return RenderContext(ctx, Backend.WINDOW, ctx.info.get("GL_RENDERER", ""))


_NATIVE_HINT = ("on Linux, run under an X display (DISPLAY set, or xvfb-run) or use egl; on "
                "macOS and Windows, the system's OpenGL driver makes it (update the graphics "
                "driver)")
_MAKERS = {Backend.EGL: (_make_egl, _EGL_HINT),
           Backend.OSMESA: (lambda d: _make_osmesa(), _OSMESA_HINT),
           Backend.NATIVE: (lambda d: _make_native(), _NATIVE_HINT)}


def ladder() -> list[Backend]:
    """The backends ``auto`` tries, in order: on Linux EGL (no display needed), the
    platform's own (GLX), then OSMesa; elsewhere the platform's own first (CGL on macOS,
    WGL on Windows: EGL and OSMesa are Mesa's, on Linux)."""
    if sys.platform.startswith("linux"):
        return [Backend.EGL, Backend.NATIVE, Backend.OSMESA]
    return [Backend.NATIVE, Backend.EGL, Backend.OSMESA]


def create_context(backend="auto", device: int | str | None = None, *,
                   require_gpu: bool | None = None, tier: str | None = None) -> RenderContext:
    """A headless GL 3.3+ context: EGL, else OSMesa (``"auto"``), or the one asked for;
    ``device`` (or ``GLSHADE_EGL_DEVICE``): an EGL device's index or name (:func:`egl_devices`).
    A software rasterizer is refused where ``require_gpu`` (or ``GLSHADE_REQUIRE_GPU=1``)
    asks for a GPU, and warned about where the machine has one (:func:`check_gpu`).

    Parameters
    ----------
    backend : Backend or str
        ``"auto"``, ``"egl"`` or ``"osmesa"``.
    device : int, str or None
        An EGL device's index or name (None: ``GLSHADE_EGL_DEVICE``, else the first).
    require_gpu : bool or None
        Refuse a software rasterizer (None: ``GLSHADE_REQUIRE_GPU``).
    tier : str or None
        Hold the context to an older GL's paths -- ``"4.1"`` (a Mac's) or ``"3.3"`` -- to
        see on any machine what they draw (None: ``GLSHADE_GL_TIER``, else the context's
        own).

    Raises
    ------
    ContextError
        Naming every backend tried, why each failed (EGL errors in words) and what to
        install.
    """
    if os.environ.get("GLSHADE_TUNE_MALLOC", "") not in ("", "0"):
        tune_malloc()
    choice = Backend.parse(backend)
    if choice is Backend.AUTO:
        env = os.environ.get("GLSHADE_BACKEND", "").strip()
        try:
            choice = Backend.parse(env) if env else Backend.AUTO
        except OptionError as exc:
            raise OptionError(f"GLSHADE_BACKEND: {exc}") from None
    if choice is Backend.WINDOW:
        raise OptionError("the window backend belongs to the viewer (glshade view); "
                           "headless rendering uses egl, native or osmesa")
    if tier is None:
        tier = os.environ.get("GLSHADE_GL_TIER", "").strip() or None
    Features(330, False).capped(tier)  # (a bad tier refused before any context is made)
    tried_backends = ladder() if choice is Backend.AUTO else [choice]
    failures = []
    for b in tried_backends:
        make, hint = _MAKERS[b]
        try:
            made = make(device)
        except ContextError as exc:
            failures.append(f"  {b.value}: {exc}\n    fix: {hint}")
        except ImportError as exc:
            failures.append(f"  {b.value}: cannot import moderngl ({exc})\n"
                            "    fix: pip install moderngl")
        else:
            check_gpu(made, require_gpu)
            if tier is not None:
                with held():  # (the driver answers its queries whole)
                    made.hold_to(tier)
            return made
    tried = ", ".join(b.value for b in tried_backends)
    raise ContextError(f"no OpenGL {REQUIRE // 100}.{REQUIRE % 100 // 10} context could be "
                       f"made (tried {tried}):\n" + "\n".join(failures))


_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3


def tune_malloc(mmap_threshold: int = 32 * 2**20, trim_threshold: int = 256 * 2**20) -> bool:
    """Opt-in: pin glibc's malloc thresholds for software rendering.

    llvmpipe allocates and frees large per-frame buffers; with glibc's default dynamic
    thresholds they are mapped and unmapped (and page-faulted in) every frame, which was
    measured to cost up to 1.45x on mid-size meshes. Pinning ``M_MMAP_THRESHOLD`` and
    ``M_TRIM_THRESHOLD`` keeps them in the heap. Process-wide, so it is never done behind
    your back: call it once (or set ``GLSHADE_TUNE_MALLOC=1`` before making a Renderer).
    Returns False where glibc's ``mallopt`` is not available.

    Parameters
    ----------
    mmap_threshold : int
        Bytes above which glibc maps an allocation (M_MMAP_THRESHOLD).
    trim_threshold : int
        Free bytes at the heap's top above which glibc returns them (M_TRIM_THRESHOLD).
    """
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes = [ctypes.c_int, ctypes.c_int]
    return bool(mallopt(_M_MMAP_THRESHOLD, int(mmap_threshold))) and \
        bool(mallopt(_M_TRIM_THRESHOLD, int(trim_threshold)))


def probe_backends() -> dict[str, str]:
    """Try each backend in a fresh subprocess (one backend per process) and say whether it
    works: ``{"egl": "ok: llvmpipe ...", "osmesa": "failed: ..."}``."""
    import subprocess
    import sys

    out = {}
    for b in ladder():
        code = ("import sys\nfrom glshade.render.context import create_context\n"
                f"c = create_context({b.value!r})\nprint(c.info['renderer'], '|', "
                "c.info['version'])\nc.release()\n")
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           timeout=60)
        if r.returncode == 0:
            out[b.value] = "ok: " + r.stdout.strip()
        else:
            last = [line for line in r.stderr.strip().splitlines() if line.strip()]
            out[b.value] = "failed: " + (" ".join(last[-3:]) if last else "unknown error")
    return out
