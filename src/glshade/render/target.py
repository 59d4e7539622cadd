"""Offscreen render targets: colour, world normal, polygon id and view depth.

Drawing goes to a multisampled framebuffer when ``samples > 0``; reads come from a
single-sampled copy resolved by a blit. Colour and normals are averaged by the resolve;
ids and depth live in integer buffers, which the resolve copies from one sample, so they
are never blended. A colour-only framebuffer shares the colour and depth buffers, for
renders that need nothing else.
"""

from __future__ import annotations

import numpy as np

from ..errors import OptionError, SettingError
from ..modes import Outputs
from .base import GLResource

__all__ = ["OffscreenTarget", "WindowTarget", "check_fits", "max_side"]


#: bytes per pixel and sample of an offscreen target: colour (up to 16 as float), normal
#: (16), polygon id (4), view depth (4) and the z-buffer (4)
_BYTES_PER_SAMPLE = 44


def max_side(context) -> int:
    """The largest framebuffer side this GL makes, in pixels (its renderbuffers' and
    viewports' limits).

    Parameters
    ----------
    context : RenderContext
        The context.
    """
    info = context.ctx.info
    return min(int(info.get("GL_MAX_RENDERBUFFER_SIZE") or 16384),
               *[int(x) for x in (info.get("GL_MAX_VIEWPORT_DIMS") or (16384, 16384))])


def check_fits(context, width: int, height: int, samples: int = 0,
               bytes_per_pixel: int = 0, image: tuple[int, int] | None = None) -> None:
    """Refuse, up front and by name, what this GL cannot make: MSAA sample counts it lacks,
    images wider than its framebuffers, and (on a software renderer, which draws in main
    memory) images larger than the machine's memory.

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    width, height : int
        The image's size in pixels.
    samples : int
        MSAA samples.
    bytes_per_pixel : int
        The memory a pixel takes (0: the renderer's targets').
    image : (int, int) or None
        The image asked for, where the targets are laid out otherwise (the path tracer's
        film in blocks): the message names it and the targets it takes.
    """
    import os

    max_samples = context.ctx.max_samples
    side = max_side(context)
    if samples and (samples > max_samples or samples & (samples - 1)):
        counts = ", ".join(str(2**i) for i in range(int(np.log2(max(max_samples, 1))) + 1))
        raise SettingError("samples", f"samples must be 0 (off) or one of {counts} on this "
                                      f"GL ({context.detail}), got {samples}")
    if max(width, height) > side:
        if image is not None:
            raise SettingError("size", f"an image of {image[0]}x{image[1]} takes targets of "
                                       f"{width}x{height} (its film laid out in blocks), "
                                       f"larger than this GL's largest framebuffer, {side} "
                                       f"pixels a side ({context.detail}): trace a smaller "
                                       "size")
        raise SettingError("size", f"an image of {width}x{height} is larger than this GL's "
                                   f"largest framebuffer, {side} pixels a side "
                                   f"({context.detail})")
    need = width * height * (bytes_per_pixel or
                             _BYTES_PER_SAMPLE * (samples + 1 if samples else 1))
    software = context.software
    try:
        memory = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        memory = 0
    if software and memory and need > memory // 3:
        what = f"with {samples} samples " if not bytes_per_pixel else ""
        raise SettingError("size", f"an image of {width}x{height} {what}"
                                   f"needs about {need / 2**30:.1f} GiB of framebuffers; this "
                                   "software renderer draws in main memory "
                                   f"({memory / 2**30:.0f} GiB): ask for fewer pixels or "
                                   "samples")


class OffscreenTarget(GLResource):
    """One set of framebuffers of a given size; ``release()`` frees them.

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    width, height : int
        The image's size in pixels.
    samples : int
        MSAA samples (0: none).
    color_dtype : str
        ``"f1"`` (8-bit) or ``"f4"`` (float) colour.
    """

    #: drawn with y flipped, so that GL's first row in memory is the image's top row and a
    #: read needs no flip (and no second copy of the pixels)
    rows_top_down = True

    def __init__(self, context, width: int, height: int, samples: int = 0,
                 color_dtype: str = "f1"):
        if width < 1 or height < 1:
            raise OptionError(f"image size must be positive, got {width}x{height}")
        super().__init__(context)
        self.width, self.height, self.samples = int(width), int(height), int(samples)
        self.color_dtype = color_dtype
        self._read_buffers: dict[tuple, np.ndarray] = {}
        self._unresolved: Outputs | None = None  # a drawing marked for resolving
        ctx = context.ctx
        try:
            def buffers(samples):
                size = (self.width, self.height)
                rb = ctx.renderbuffer
                color = self._keep(rb(size, 4, samples=samples, dtype=color_dtype))
                normal = self._keep(rb(size, 4, samples=samples, dtype="f4"))
                face = self._keep(rb(size, 1, samples=samples, dtype="i4"))
                depth = self._keep(rb(size, 1, samples=samples, dtype="u4"))
                zbuf = self._keep(ctx.depth_renderbuffer(size, samples=samples))
                return color, normal, face, depth, zbuf

            c, n, f, d, z = buffers(self.samples)
            self.fbo_draw_all = self._keep(ctx.framebuffer([c, n, f, d], z))
            self.fbo_draw_color = self._keep(ctx.framebuffer([c], z))
            # integer and normal targets are cleared to zero (background) on their own
            self.fbo_clear_aux = self._keep(ctx.framebuffer([n, f, d]))
            if self.samples:
                c, n, f, d, z = buffers(0)
                self.fbo_read_all = self._keep(ctx.framebuffer([c, n, f, d], z))
                self.fbo_read_color = self._keep(ctx.framebuffer([c], z))
            else:
                self.fbo_read_all, self.fbo_read_color = self.fbo_draw_all, self.fbo_draw_color
        except BaseException:
            self.release()  # nothing half-made stays registered with the context
            raise

    @property
    def size(self) -> tuple[int, int]:
        return self.width, self.height

    def begin(self, background, outputs: Outputs) -> None:
        """Bind for drawing and clear: colour to the background, the rest to zero (each
        through a framebuffer of its own: a clear reaches every colour attachment, and the
        background colour in an id or depth buffer would read as a polygon at a distance).

        Parameters
        ----------
        background : tuple
            The clear colour, RGBA.
        outputs : Outputs
            What the draw writes besides colour.
        """
        self._check()
        self._unresolved = None  # (a new drawing: the last one's copy is not wanted)
        if outputs.auxiliary:
            self.fbo_clear_aux.use()
            self.fbo_clear_aux.clear(0.0, 0.0, 0.0, 0.0)
        self.fbo_draw_color.use()
        self.fbo_draw_color.clear(*background, depth=1.0)
        if outputs.auxiliary:
            self.fbo_draw_all.use()

    def bind(self, outputs: Outputs) -> None:
        """Bind for drawing without clearing.

        Parameters
        ----------
        outputs : Outputs
            What the draw writes besides colour.
        """
        (self.fbo_draw_all if outputs.auxiliary else self.fbo_draw_color).use()

    def depth_source(self):
        """The framebuffer whose depth buffer holds what has been drawn (to copy from)."""
        return self.fbo_draw_color

    def resolve(self, outputs: Outputs) -> None:
        """Mark the multisampled drawing for copying into the single-sampled buffers that
        are read; the copy is made by the first read (a software driver makes it on the
        calling thread once the drawing is done: made at the draw, it would keep the next
        frame's draw from overlapping this one's).

        Parameters
        ----------
        outputs : Outputs
            What the draw writes besides colour.
        """
        self._unresolved = outputs if self.samples else None

    def _resolved(self) -> None:
        """Make the copy :meth:`resolve` marked, once."""
        outputs, self._unresolved = self._unresolved, None
        if outputs is not None:
            ctx = self.context.ctx
            if outputs.auxiliary:
                ctx.copy_framebuffer(self.fbo_read_all, self.fbo_draw_all)
            else:
                ctx.copy_framebuffer(self.fbo_read_color, self.fbo_draw_color)

    def _read(self, attachment: int, components: int, dtype: str, fresh: bool = False):
        """The attachment's pixels ``(H, W, components)``, row 0 at the top -- the renderer
        draws offscreen targets upside down (``rows_top_down``), so GL's first row is the
        image's top and no flip is needed. ``fresh``: into a new array for the caller;
        else into a buffer this target keeps and reuses (for reads that copy anyway)."""
        self._resolved()
        fbo = self.fbo_read_all if attachment else self.fbo_read_color
        np_dtype = np.dtype(dtype.replace("f1", "u1"))
        shape = (self.height, self.width, components)
        buffer: np.ndarray | None
        if fresh:
            buffer = np.empty(shape, np_dtype)
        else:
            key = (attachment, components, dtype)
            buffer = self._read_buffers.get(key)
            if buffer is None:
                buffer = self._read_buffers[key] = np.zeros(shape, np_dtype)
        fbo.read_into(buffer, components=components, attachment=attachment, dtype=dtype)
        return buffer

    def read_color(self) -> np.ndarray:
        """``(H, W, 4)``: uint8, or float32 for a float colour target."""
        return self._read(0, 4, self.color_dtype, fresh=True)

    def read_normal(self) -> np.ndarray:
        return np.ascontiguousarray(self._read(1, 4, "f4")[..., :3])

    def read_face_id(self) -> np.ndarray:
        return self._read(2, 1, "i4")[..., 0] - 1  # stored as id + 1; background -> -1
        # (the subtraction makes the copy)

    def read_depth(self) -> np.ndarray:
        bits = self._read(3, 1, "u4")[..., 0]  # (a view of the kept buffer)
        depth = bits.view(np.float32).copy()
        depth[bits == 0] = np.inf  # never drawn
        return depth

    def _release_extra(self) -> None:
        self.context.rest()  # never release the bound framebuffer


class WindowTarget:
    """A window's default framebuffer, in the shape the Renderer draws into: colour only
    (the window has no id or normal buffers).

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    width, height : int
        The window's framebuffer size in pixels.
    """

    rows_top_down = False  # a window shows GL's first row at the bottom
    samples = 0  # (single-sampled: its depth at a pixel is the pixel centre's)

    def __init__(self, context, width: int, height: int):
        self.context = context
        self.width, self.height = int(width), int(height)

    def resize(self, width: int, height: int) -> None:
        """The window's new framebuffer size.

        Parameters
        ----------
        width, height : int
            In pixels.
        """
        self.width, self.height = max(1, int(width)), max(1, int(height))

    def _fbo(self):
        ctx = self.context.ctx
        return ctx.screen if ctx.screen is not None else ctx.detect_framebuffer(0)

    def begin(self, background, outputs: Outputs) -> None:
        """Bind the window's framebuffer and clear it to the background.

        Parameters
        ----------
        background : tuple
            The clear colour, RGBA.
        outputs : Outputs
            What the draw writes besides colour.
        """
        fbo = self._fbo()
        fbo.use()
        self.context.ctx.viewport = (0, 0, self.width, self.height)
        fbo.clear(*background, depth=1.0)

    def bind(self, outputs: Outputs) -> None:
        """Bind the window's framebuffer without clearing.

        Parameters
        ----------
        outputs : Outputs
            What the draw writes besides colour.
        """
        self._fbo().use()

    def depth_source(self):
        return self._fbo()

    def resolve(self, outputs: Outputs) -> None:
        """Nothing: the window is single-sampled and shown as drawn.

        Parameters
        ----------
        outputs : Outputs
            What the draw writes besides colour.
        """
        pass

    def read_color(self) -> np.ndarray:
        """The window's pixels ``(H, W, 4) uint8``, row 0 at the top (the back buffer, read
        before the swap)."""
        data = self._fbo().read(viewport=(0, 0, self.width, self.height), components=4)
        return np.frombuffer(data, np.uint8).reshape(self.height, self.width, 4)[::-1].copy()

    def read_depth_at(self, x: int, y_from_top: int) -> float:
        """Window depth in [0, 1] at one pixel (1 = nothing drawn).

        Parameters
        ----------
        x : int
            The column.
        y_from_top : int
            The row, 0 at the top.
        """
        y = self.height - 1 - int(y_from_top)
        data = self._fbo().read(viewport=(int(x), y, 1, 1), components=1, attachment=-1,
                                dtype="f4")
        return float(np.frombuffer(data, np.float32)[0])

    def release(self) -> None:
        pass
