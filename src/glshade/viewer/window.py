"""The glfw window: events in, frames out. All drawing goes through the headless
Renderer's programs and buffers; this module only supplies the framebuffer and the
camera control.

Keys: 1 flat, 2 Gouraud, 3 Phong, 4 normals, 5 depth, 6 radiosity; z depth test; w
polygon edges; x cast shadows (off, exact, map); c back-face culling (auto / on / off); v
the named views in turn (front, back, left, right, top, bottom, iso); o orthographic /
perspective; l light at the camera; t path tracing (the rendering equation, refined while
the camera rests; t again or a mode key: back); k add a key frame; p play/pause the path;
P save the path as TOML; s screenshot; r reset;
h or ? help; Esc or q quit. Left-drag: arcball; right- or shift-drag: pan; wheel: dolly
(the clip planes follow: nothing in front of the camera is cut away); double-click:
re-centre on the surface; with --pick a click prints the polygon under it.
"""

from __future__ import annotations

from typing import Any

import os
import sys
import time
from pathlib import Path

import numpy as np

from ..errors import DisplayError
from ..modes import ShadingMode
from ..scene import Camera, CameraPath, Keyframe, Scene
from .controls import MODE_KEYS, Controls

__all__ = ["Viewer", "HELP"]

HELP = __doc__.split("\n\n", 1)[1].strip()


def _has_display() -> bool:
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


class Viewer(Controls):
    """A window showing ``scene``; ``run()`` until closed, or ``step()`` frame by frame.

    Parameters
    ----------
    scene
        What to show.
    camera
        The initial view (default: the auto-framed camera of ``glshade render``).
    size
        Window size in screen coordinates.
    options
        The initial DrawOptions (or a mode's name); keys change them.
    samples
        MSAA samples of the window (0 = off).
    compare
        Flat, Gouraud and Phong side by side with one camera.
    visible
        False for a hidden window (tests).
    title : str
        The window's title.
    screenshot_dir : str or Path
        Where the viewer saves files (the ``s`` key's screenshots, a recorded camera path).
    pick
        Print what a click lands on (:meth:`pick`).
    """

    def __init__(self, scene: Scene, camera: Camera | None = None, *, size=(960, 720),
                 options=None, samples: int = 4, compare: bool = False, visible: bool = True,
                 title: str = "glshade", screenshot_dir: str | Path = ".", pick: bool = False):
        if not _has_display():
            raise DisplayError("no display to open a window on (DISPLAY is not set); use "
                               "'glshade render' for images, or run under 'xvfb-run'")
        import glfw

        from ..render.context import window_context
        from ..render.renderer import Renderer
        from ..render.target import WindowTarget

        if not glfw.init():
            raise DisplayError("glfw could not initialise the display "
                               f"{os.environ.get('DISPLAY', '')!r}; is an X server running?")
        self._glfw = glfw
        glfw.window_hint(glfw.CONTEXT_VERSION_MAJOR, 3)
        glfw.window_hint(glfw.CONTEXT_VERSION_MINOR, 3)
        glfw.window_hint(glfw.OPENGL_PROFILE, glfw.OPENGL_CORE_PROFILE)
        glfw.window_hint(glfw.OPENGL_FORWARD_COMPAT, True)
        glfw.window_hint(glfw.SAMPLES, int(samples))
        glfw.window_hint(glfw.VISIBLE, bool(visible))
        glfw.window_hint(glfw.DOUBLEBUFFER, True)
        self.window: Any = glfw.create_window(int(size[0]), int(size[1]), title, None, None)
        if not self.window:
            glfw.terminate()
            raise DisplayError("glfw could not open a window with an OpenGL 3.3 core context")
        glfw.make_context_current(self.window)
        glfw.swap_interval(0)
        self.context = window_context()
        fb_w, fb_h = glfw.get_framebuffer_size(self.window)
        self.target = WindowTarget(self.context, fb_w, fb_h)
        self.renderer = Renderer(fb_w, fb_h, samples=0, context=self.context)
        super().__init__(scene, camera, glfw.get_window_size(self.window), options, compare,
                         pick)
        self.title = title
        self.screenshot_dir = Path(screenshot_dir)
        self.keyframes: list[Keyframe] = []
        self.playing = False
        self.play_time = 0.0
        self.path: CameraPath | None = None
        self._cursor = (0.0, 0.0)
        self._fps, self._frames, self._t0 = 0.0, 0, time.perf_counter()
        self.frame_count = 0
        self.closed = False
        self.tracer: Any = None  # (a PathTracer while the t mode is on)
        self._trace_exposure: float | None = None
        glfw.set_key_callback(self.window, self._key_event)
        glfw.set_mouse_button_callback(self.window, self._button_event)
        glfw.set_cursor_pos_callback(self.window, self._cursor_event)
        glfw.set_scroll_callback(self.window, self._scroll_event)
        glfw.set_framebuffer_size_callback(self.window, self._resize_event)
        glfw.set_window_size_callback(self.window, self._window_size_event)

    # ------------------------------------------------------------------ geometry
    def _aspect(self) -> float:
        w, h = self.target.width, self.target.height
        return (w / 3 if self.compare else w) / max(h, 1)

    def _scale(self) -> float:
        """Framebuffer pixels per window coordinate (2 on HiDPI screens)."""
        ww, _ = self._glfw.get_window_size(self.window)
        return self.target.width / max(ww, 1)

    @property
    def triangles(self) -> int:
        return sum(len(m.mesh.triangles[0]) for m in self.scene.models if m.visible)

    # ------------------------------------------------------------------ drawing
    def draw(self) -> None:
        """Draw one frame into the back buffer (no swap). The edge overlay (``w``) is the
        renderer's own (``DrawOptions.edges``): the polygons' edges, not the triangles'."""
        self._glfw.make_context_current(self.window)
        r, t = self.renderer, self.target
        if self.tracer is not None:
            self._draw_traced()
        elif self.compare:
            w3 = t.width // 3
            for i, m in enumerate((ShadingMode.FLAT, ShadingMode.GOURAUD, ShadingMode.PHONG)):
                viewport = (i * w3, 0, w3, t.height)
                r.draw(t, self.scene, self.camera, self.options.replace(mode=m),
                       viewport=viewport, clear=(i == 0))
                self._labels().draw(m.value, viewport)  # named like the compare grid's tiles
        else:
            r.draw(t, self.scene, self.camera, self.options)

    def _draw_traced(self) -> None:
        """One more sample a pixel of the path tracer, shown; a new view (or size) starts
        it over, with an exposure taken from its first sample."""
        t = self.target
        if (self.tracer.gpu.width, self.tracer.gpu.height) != (t.width, t.height):
            self._start_tracing()
            if self.tracer is None:
                return
        if self.tracer.add(self.camera, 1) or self._trace_exposure is None:
            self._trace_exposure = self.tracer.result().auto_exposure()
        self.tracer.gpu.show(t._fbo(), self._trace_exposure, bool(self.options.srgb))

    def _start_tracing(self) -> None:
        from ..errors import GlshadeError
        from ..pathtrace import PathTracer

        self._stop_tracing()
        try:
            self.tracer = PathTracer(self.scene, (self.target.width, self.target.height),
                                     context=self.context, camera=self.camera, smooth=True)
        except GlshadeError as exc:  # (a scene it cannot trace: no emitter, rho > 1 ...)
            self._say(f"cannot path-trace this scene: {exc}")
            return
        self._trace_exposure = None

    def _stop_tracing(self) -> None:
        if self.tracer is not None:
            self.tracer.close()
            self.tracer = None

    def _labels(self):
        if getattr(self, "_label_overlay", None) is None:
            from ..render.passes.labels import LabelOverlay

            self._label_overlay = LabelOverlay(self.context, self.renderer.shaders)
        return self._label_overlay

    def screenshot(self, path=None) -> np.ndarray:
        """The window's pixels now ``(H, W, 4) uint8``; saved as PNG when ``path`` is given.

        Parameters
        ----------
        path : str or Path or None
            Where to save a PNG (None: only returned).
        """
        self.draw()
        img = self.target.read_color()
        if path is not None:
            from ..io.images import save_image

            if (img == img[:1, :1]).all() and self.tracer is None:  # (one colour: a blank)
                import warnings

                from ..errors import RenderWarning
                from ..render.diagnostics import why_blank

                warnings.warn(why_blank(self.scene, self.camera.with_planes(self.scene.bounds),
                                        self.options.cull), RenderWarning, stacklevel=2)

            save_image(img, path)
            self._say(f"saved {path}")
        return img

    def step(self, dt: float | None = None) -> None:
        """Handle events, advance playback, draw and show one frame.

        Parameters
        ----------
        dt : float or None
            Seconds to advance playback (None: a sixtieth).
        """
        glfw = self._glfw
        glfw.poll_events()
        if glfw.window_should_close(self.window):
            self.closed = True
            return
        now = time.perf_counter()
        if self.playing and self.path is not None:
            self.play_time += dt if dt is not None else 1 / 60
            if self.play_time > self.path.end:
                self.play_time = self.path.start
            self.camera = self.path.at(self.play_time)
        self.draw()
        glfw.swap_buffers(self.window)
        self.frame_count += 1
        self._frames += 1
        if now - self._t0 >= 0.5:
            self._fps = self._frames / (now - self._t0)
            self._frames, self._t0 = 0, now
        glfw.set_window_title(self.window, self.status())

    def status(self) -> str:
        mode = "flat | gouraud | phong" if self.compare else self.options.mode.value
        if self.tracer is not None:
            mode = f"path tracing, {self.tracer.samples:,} samples a pixel"
        extra = "" if self.options.depth_test else "  [no depth test]"
        if self.playing:
            extra += "  [playing]"
        return (f"{self.title} - {mode} - {self._fps:.0f} fps - {self.triangles:,} triangles"
                f"{extra}")

    def run(self, frames: int | None = None) -> None:
        """Show frames until the window closes (or ``frames`` have been drawn).

        Parameters
        ----------
        frames : int or None
            The most frames (None: until the window closes).
        """
        n = 0
        last = time.perf_counter()
        while not self.closed and (frames is None or n < frames):
            now = time.perf_counter()
            self.step(now - last)
            last = now
            n += 1

    def close(self) -> None:
        if getattr(self, "window", None) is None:
            return
        self._glfw.make_context_current(self.window)
        self._stop_tracing()
        self.renderer.close()
        self.context.release()
        self._glfw.destroy_window(self.window)
        self.window = None
        self.closed = True

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # ------------------------------------------------------------------ actions
    def key(self, char: str) -> bool:
        """Act on a key as typed (what the key callback calls; tests call it directly):
        the view's and options' keys (:meth:`Controls.key`), then the window's own.

        Parameters
        ----------
        char : str
            The key as typed.
        """
        if char == "r":
            self.playing = False
        if char == "t":
            if self.tracer is None:
                self._start_tracing()
                if self.tracer is not None:
                    self._say("path tracing: the picture refines while the camera rests "
                              "(t or a mode key: back)")
            else:
                self._stop_tracing()
            return True
        if super().key(char):
            if char in MODE_KEYS:
                self._stop_tracing()
            return True
        if char == "k":
            t = self.keyframes[-1].time + 1.0 if self.keyframes else 0.0
            self.keyframes.append(Keyframe(t, self.camera.position, self.camera.orientation,
                                           self.camera.fov_y))
            self._say(f"key frame {len(self.keyframes)} at t = {t:g}")
        elif char == "p":
            if len(self.keyframes) >= 2:
                self.path = CameraPath(self.keyframes, camera=self.camera)
                self.playing = not self.playing
            else:
                self._say("add two key frames with k before playing")
        elif char == "P":
            if self.keyframes:
                out = self.screenshot_dir / f"glshade-path-{time.strftime('%Y%m%d-%H%M%S')}.toml"
                CameraPath(self.keyframes, camera=self.camera).save(out)
                self._say(f"saved {out}")
        elif char == "s":
            out = self.screenshot_dir / f"glshade-{time.strftime('%Y%m%d-%H%M%S')}-" \
                                        f"{self.frame_count}.png"
            self.screenshot(out)
        elif char in ("h", "?"):
            self._say(HELP)
        elif char in ("q", "escape"):
            self._glfw.set_window_should_close(self.window, True)
            self.closed = True
        else:
            return False
        return True

    def _say(self, text: str) -> None:
        """A message for the user, on the terminal (the title shows the state)."""
        super()._say(text)
        print(text, file=sys.stderr)

    def mouse_move(self, x: float, y: float) -> None:
        """The cursor moved to window coordinates: drags turn or pan the view.

        Parameters
        ----------
        x, y : float
            Window coordinates.
        """
        self._cursor = (x, y)
        super().mouse_move(x, y)

    def pick(self, x: float, y: float):
        """What is under window point (x, y): polygon id, world point, normal and depth
        (:meth:`Renderer.pick`), printed and kept in ``picks``; None over the background.

        Parameters
        ----------
        x, y : float
            Window coordinates.
        """
        if self.compare:
            self._say("picking works in the single view (press 1, 2 or 3)")
            return None
        s = self._scale()
        found = self.renderer.pick(self.scene, self.camera, x * s, y * s)
        self.picks.append(found)
        self._say(f"pick: {found}" if found is not None else "pick: background")
        return found

    def recentre(self, x: float, y: float) -> bool:
        """Re-centre the view on the surface point under (x, y), from the depth buffer.

        Parameters
        ----------
        x, y : float
            Window coordinates.
        """
        self.draw()
        s = self._scale()
        px, py = int(x * s), int(y * s)
        if not (0 <= px < self.target.width and 0 <= py < self.target.height):
            return False
        depth = self.target.read_depth_at(px, py)
        if depth >= 1.0:
            return False
        ndc = np.array([2 * (px + 0.5) / self.target.width - 1,
                        1 - 2 * (py + 0.5) / self.target.height, 2 * depth - 1, 1.0])
        camera = self.camera.with_planes(self.scene.bounds)  # (the planes it was drawn with)
        m = camera.projection_matrix(self._aspect()) @ camera.view_matrix()
        p = np.linalg.inv(m) @ ndc
        point = p[:3] / p[3]
        self.camera = self.camera.replace(position=self.camera.position + point - self.center)
        self.center = point
        return True

    # ------------------------------------------------------------------ glfw callbacks
    def _key_event(self, window, key, scancode, action, mods):
        glfw = self._glfw
        if action != glfw.PRESS:
            return
        shift = bool(mods & glfw.MOD_SHIFT)
        if key == glfw.KEY_ESCAPE:
            self.key("escape")
        elif key == glfw.KEY_SLASH and shift:
            self.key("?")
        elif glfw.KEY_0 <= key <= glfw.KEY_9:
            self.key(chr(key))
        elif glfw.KEY_A <= key <= glfw.KEY_Z:
            c = chr(key).lower()
            self.key(c.upper() if shift and c == "p" else c)

    def _button_event(self, window, button, action, mods):
        glfw = self._glfw
        x, y = glfw.get_cursor_pos(window)
        if action == glfw.PRESS:
            name = {glfw.MOUSE_BUTTON_LEFT: "left", glfw.MOUSE_BUTTON_RIGHT: "right"}.get(
                button, "other")
            self.mouse_down(x, y, name, bool(mods & glfw.MOD_SHIFT))
        else:
            self.mouse_up()

    def _cursor_event(self, window, x, y):
        self.mouse_move(x, y)

    def _scroll_event(self, window, dx, dy):
        self.scroll(dy)

    def _resize_event(self, window, width, height):
        self.target.resize(width, height)

    def _window_size_event(self, window, width, height):
        self.arcball.resize(width, height)
