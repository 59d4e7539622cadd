"""OpenGL contexts: a ladder of headless backends, each one moderngl context.

1. ``egl``: moderngl's standalone EGL context. With a GPU this is the vendor's driver
   (``device=`` or ``GLSHADE_EGL_DEVICE`` picks one of several); without one it is Mesa's
   llvmpipe through EGL, surfaceless: no display needed. The default, and what CI uses.
2. ``osmesa``: Mesa's off-screen library (Debian ``libosmesa6``) through ctypes, for systems
   without EGL. Mesa 25.1 dropped OSMesa, so this is a fallback, never the default.

``auto`` walks the ladder (``GLSHADE_BACKEND`` overrides it, read when a context is made,
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

from ..errors import ContextError, EnvironmentFailure, OptionError
from ..interrupt import held
from ..modes import Backend

__all__ = ["Backend", "RenderContext", "create_context", "window_context", "probe_backends",
           "tune_malloc", "egl_devices", "device_index"]

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
    """

    def __init__(self, ctx, backend: Backend, detail: str = "", loader=None):
        self.ctx = ctx
        self.backend = backend
        self.detail = detail
        self._loader = loader
        self._children: list = []
        self.released = False
        # A framebuffer to bind while others are released: moderngl re-binds the previously
        # bound framebuffer after making a new one, and a deleted one would be an error.
        self._idle = ctx.simple_framebuffer((1, 1))
        self.thread = threading.get_ident()  # (the thread it is current on)

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
        return any(w in self.detail.lower() for w in ("llvmpipe", "softpipe", "swrast"))

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

    def require(self, version: int, what: str, instead: str) -> None:
        """Refuse, in one line, a feature this GL is too old for: ``version`` as GL's
        version code (430: 4.3); ``what`` ends in the verb ("shadows='exact' needs");
        ``instead`` names the way that works.

        Parameters
        ----------
        version : int
            GL's version code needed (430: 4.3).
        what : str
            What needs it, ending in the verb ("shadows='exact' needs").
        instead : str
            The way that works on this GL.
        """
        have = self.ctx.version_code
        if have < version:
            raise EnvironmentFailure(
                f"{what} OpenGL {version // 100}.{version % 100 // 10}; this GL is "
                f"{have // 100}.{have % 100 // 10} ({self.detail}): {instead}")

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


def egl_device_count() -> int:
    """How many EGL devices the driver lists (EGL_EXT_device_enumeration), 0 when it
    lists none or cannot say."""
    import ctypes
    import ctypes.util

    try:
        egl = ctypes.CDLL(ctypes.util.find_library("EGL") or "libEGL.so.1")
    except OSError:
        return 0
    egl.eglGetProcAddress.restype = ctypes.c_void_p
    egl.eglGetProcAddress.argtypes = [ctypes.c_char_p]
    address = egl.eglGetProcAddress(b"eglQueryDevicesEXT")
    if not address:
        return 0
    query = ctypes.CFUNCTYPE(ctypes.c_uint, ctypes.c_int, ctypes.POINTER(ctypes.c_void_p),
                             ctypes.POINTER(ctypes.c_int))(address)
    count = ctypes.c_int(0)
    if not query(0, None, ctypes.byref(count)):
        return 0
    return max(int(count.value), 0)


def egl_devices() -> list[dict]:
    """Every EGL device: ``{"index", "vendor", "renderer"}`` from a context made on it
    (or ``"error"``: why none could be) -- what ``glshade doctor`` lists and ``--device``
    / ``GLSHADE_EGL_DEVICE`` choose from, by index or by name."""
    import moderngl

    out = []
    for i in range(egl_device_count()):
        try:
            settings: dict[str, Any] = {"backend": "egl", "device_index": i}
            ctx = moderngl.create_context(standalone=True, require=REQUIRE, **settings)
        except Exception as exc:  # (glcontext raises bare Exceptions)
            out.append({"index": i, "vendor": "", "renderer": "",
                        "error": _explain_egl(exc)})
            continue
        out.append({"index": i, "vendor": ctx.info.get("GL_VENDOR", ""),
                    "renderer": ctx.info.get("GL_RENDERER", "")})
        ctx.release()
    return out


def device_index(spec) -> int:
    """An EGL device by index (``"1"``) or by name (a case-blind part of its vendor or
    renderer: ``"nvidia"``, ``"llvmpipe"``); one line naming those present when no device
    (or more than one, by name) matches.

    Parameters
    ----------
    spec : int or str
        An index (``1``, ``"1"``) or a case-blind part of a device's vendor or renderer name.
    """
    text = str(spec).strip()
    if text.isdigit() and int(text) < egl_device_count():
        return int(text)  # (no need to make a context on each device)
    devices = egl_devices()
    present = "; ".join(f"{d['index']}: {d['vendor']} {d['renderer']}".strip()
                        for d in devices) or "none"
    if text.isdigit():
        if int(text) < len(devices):
            return int(text)
        raise OptionError(f"EGL device {text} does not exist; present: {present}")
    hits = [d["index"] for d in devices
            if text.lower() in f"{d['vendor']} {d['renderer']}".lower()]
    if len(hits) == 1:
        return hits[0]
    raise OptionError(f"EGL device {text!r} " + ("matches several" if hits else
                      "matches none") + f"; present: {present}")


def _make_egl(device: int | str | None) -> RenderContext:
    import moderngl

    settings: dict[str, Any] = {"backend": "egl"}
    dev = device if device is not None else os.environ.get("GLSHADE_EGL_DEVICE")
    if dev not in (None, ""):
        try:
            settings["device_index"] = device_index(dev)
        except OptionError as exc:
            source = "" if device is not None else "GLSHADE_EGL_DEVICE: "
            raise OptionError(f"{source}{exc}") from None
    try:
        with held():  # (a Ctrl-C waits for the driver to finish making the context)
            ctx = moderngl.create_context(standalone=True, require=REQUIRE, **settings)
    except Exception as exc:  # moderngl/glcontext raise bare Exceptions with EGL text
        raise ContextError(_explain_egl(exc)) from None
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


def window_context() -> RenderContext:
    """The RenderContext of the window whose GL context is current (glfw's, made by the
    viewer): moderngl wraps it; the window keeps only this."""
    import moderngl

    ctx = moderngl.create_context(require=REQUIRE)
    return RenderContext(ctx, Backend.WINDOW, ctx.info.get("GL_RENDERER", ""))


_MAKERS = {Backend.EGL: (_make_egl, _EGL_HINT), Backend.OSMESA: (lambda d: _make_osmesa(),
                                                                 _OSMESA_HINT)}


def create_context(backend="auto", device: int | str | None = None) -> RenderContext:
    """A headless GL 3.3+ context: EGL, else OSMesa (``"auto"``), or the one asked for;
    ``device`` (or ``GLSHADE_EGL_DEVICE``): an EGL device's index or name (:func:`egl_devices`).

    Parameters
    ----------
    backend : Backend or str
        ``"auto"``, ``"egl"`` or ``"osmesa"``.
    device : int, str or None
        An EGL device's index or name (None: ``GLSHADE_EGL_DEVICE``, else the first).

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
                           "headless rendering uses egl or osmesa")
    ladder = [Backend.EGL, Backend.OSMESA] if choice is Backend.AUTO else [choice]
    failures = []
    for b in ladder:
        make, hint = _MAKERS[b]
        try:
            return make(device)
        except ContextError as exc:
            failures.append(f"  {b.value}: {exc}\n    fix: {hint}")
        except ImportError as exc:
            failures.append(f"  {b.value}: cannot import moderngl ({exc})\n"
                            "    fix: pip install moderngl")
    tried = ", ".join(b.value for b in ladder)
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
    for b in (Backend.EGL, Backend.OSMESA):
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
