"""An interactive viewer in a notebook: a widget (anywidget) whose kernel side renders with
glshade's own headless renderer and whose browser side shows the frames on a canvas and
sends the gestures back -- the same controls as the window (:mod:`glshade.viewer.controls`):
drag to turn (arcball), right- or shift-drag to pan, the wheel to dolly, keys 1-5 for the
modes, ``v`` the named views, ``o`` orthographic, ``r`` reset, ``t`` path tracing (the
picture refines a sample a pixel a frame while the camera rests, up to ``trace_samples``:
glTF's materials, textures, emitters, spot lights and the sky, as ``glshade pathtrace``
traces them); buttons for the modes, a split compare of two modes, and a click to pick
(``pick=True``). No display is needed, so it works
on a remote kernel; the picture is the one ``glshade render`` makes of the same view.

Needs the ``notebook`` extra (``pip install 'glshade[notebook]'``: anywidget).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..errors import UsageError
from ..modes import ShadingMode
from ..scene import Camera, Scene
from ..viewer.controls import MODE_KEYS, Controls

__all__ = ["NotebookViewer", "view", "camera_from_view", "view_of"]

_STATIC = Path(__file__).with_name("static")
#: the widget class, made on first use (anywidget imported then: ``__getattr__``)
NotebookViewer: Any


def view_of(camera: Camera) -> dict:
    """A camera as plain numbers (what the widget syncs to the browser as ``view``).

    Parameters
    ----------
    camera : Camera
        The camera.
    """
    return {"position": [float(x) for x in camera.position],
            "orientation": [float(x) for x in camera.orientation],
            "fov_y": float(camera.fov_y), "projection": camera.projection.value,
            "height": float(camera.height), "near": camera.near, "far": camera.far}


def camera_from_view(view: dict) -> Camera:
    """The camera of a widget's ``view`` (the inverse of :func:`view_of`).

    Parameters
    ----------
    view : dict
        The widget's ``view`` trait.
    """
    return Camera(position=view["position"], orientation=view["orientation"],
                  fov_y=view["fov_y"], projection=view["projection"], height=view["height"],
                  near=view.get("near"), far=view.get("far"))


#: (for the type checker: the traits and the widget's methods come with anywidget.AnyWidget,
#: which _widget_class mixes in)
_Widget: Any = object


class _Behaviour(_Widget):
    """What the widget does, apart from its synced traits (kept out of
    :func:`_widget_class` so the class can be made on first use, when anywidget is
    imported, without writing its methods inside a function)."""

    def __init__(self, scene: Scene, camera: Camera | None = None, *,
                 size=(480, 360), mode="phong", compare: str = "", samples: int = 4,
                 pick: bool = False, backend=None, trace_samples: int = 256, **kwargs):
        from concurrent.futures import ThreadPoolExecutor

        from ..errors import OptionError
        from ..render.renderer import Renderer

        w, h = int(size[0]), int(size[1])
        if int(trace_samples) != trace_samples or trace_samples < 1:
            raise OptionError(f"trace_samples must be a whole number >= 1, got "
                              f"{trace_samples!r}")
        super().__init__(width=w, height=h, **kwargs)
        self.controls = _Controls(self, scene, camera, (w, h), mode, pick=pick)
        self.split = _mode_name(compare) if compare else ""
        self.trace_samples = int(trace_samples)
        #: the path tracer while tracing is on (made, used and closed on the GL thread)
        self.tracer: Any = None
        self._trace_exposure: float | None = None
        self._stepping = False
        # A GL context belongs to one thread, and a kernel answers widget messages on
        # another than the one that runs cells: every GL call goes to a thread of its own.
        self._gl = ThreadPoolExecutor(1, thread_name_prefix="glshade-notebook-gl")
        self.renderer = self._on_gl(Renderer, w, h, samples=samples,
                                    backend=backend or "auto")
        self.on_msg(self._on_message)
        self.refresh()

    def _on_gl(self, fn, *args, **kwargs):
        """``fn(*args, **kwargs)`` on the widget's GL thread (its result, or its error)."""
        return self._gl.submit(fn, *args, **kwargs).result()

    @property
    def scene(self) -> Scene:
        return self.controls.scene

    @property
    def camera(self) -> Camera:
        """The view now shown."""
        return self.controls.camera

    @camera.setter
    def camera(self, camera: Camera) -> None:
        self.controls.camera = camera
        self.refresh()

    def image(self) -> np.ndarray:
        """The frame now shown ``(H, W, 3) uint8``: the mode, and right of the middle
        the compared mode when there is one -- or, while tracing, the traced picture so
        far."""
        return self._on_gl(self._image)

    def _image(self) -> np.ndarray:  # (on the GL thread)
        if self.tracer is not None:
            return self._traced()
        r, c = self.renderer, self.controls
        left = r.render(c.scene, c.camera, c.options)[..., :3]
        if not self.split:
            return left
        right = r.render(c.scene, c.camera, c.options.replace(mode=self.split))[..., :3]
        out = left.copy()
        out[:, self.width // 2:] = right[:, self.width // 2:]
        return out

    def refresh(self) -> None:
        """Render the current view and send it to the browser (both on the GL thread, as
        the tracing's frames are: one thread sends every frame)."""
        self._on_gl(lambda: self._show(self._image()))
        if self.tracer is not None:  # (a new view refines from here)
            self._gl.submit(self._kick)

    def _show(self, image: np.ndarray) -> None:
        """A frame and what it shows, to the browser in one message."""
        from ..display import png_bytes

        png = png_bytes(image)
        c = self.controls
        tracer = self.tracer
        with self.hold_sync():
            self.mode = c.options.mode.value
            self.view = view_of(c.camera)
            self.png = png
            self.status = (f"path tracing, {tracer.samples:,} samples a pixel"
                           + (" (done: t or a mode key ends it)"
                              if tracer.samples >= self.trace_samples else "")
                           if tracer is not None else c.messages[-1] if c.messages else "")
            self.revision += 1

    def trace(self, on: bool = True) -> None:
        """Path tracing on (the window's ``t``): the picture starts over at each new view
        and refines, one sample a pixel a frame, while the camera rests, up to
        ``trace_samples``; off: the mode's picture again. A scene the tracer cannot take
        is said in the status line.

        Parameters
        ----------
        on : bool
            Trace (True) or stop (False).
        """
        from ..errors import GlshadeError

        if not on:
            self._on_gl(self._stop_tracing)
            self.refresh()
            return
        if self.tracer is None:
            try:
                self._on_gl(self._start_tracing)
            except GlshadeError as exc:  # (a scene it cannot trace: no light at all ...)
                self.controls._say(f"cannot path-trace this scene: {exc}")
        self.refresh()

    def _start_tracing(self) -> None:  # (on the GL thread)
        from ..pathtrace import PathTracer

        c = self.controls
        self.tracer = PathTracer(c.scene, (self.width, self.height),
                                 context=self.renderer.context, camera=c.camera, smooth=True)
        self._trace_exposure = None

    def _stop_tracing(self) -> None:  # (on the GL thread)
        if self.tracer is not None:
            self.tracer.close()
            self.tracer = None

    def _traced(self) -> np.ndarray:  # (on the GL thread)
        """The traced picture for the view now shown (a new view: its first sample)."""
        c = self.controls
        restarted = self.tracer.camera != c.camera and self.tracer.add(c.camera, 1)
        return self._picture(restarted)

    def _picture(self, restarted: bool) -> np.ndarray:  # (on the GL thread)
        """The traced picture so far, at the exposure of its view's first sample."""
        traced = self.tracer.result()
        if restarted or self._trace_exposure is None:
            self._trace_exposure = traced.auto_exposure()
        return traced.rgba8(self._trace_exposure, bool(self.controls.options.srgb))[..., :3]

    def _kick(self) -> None:  # (on the GL thread)
        if not self._stepping:
            self._stepping = True
            self._step()

    def _step(self) -> None:  # (on the GL thread: a sample a pixel, a frame, the next)
        tracer = self.tracer
        if tracer is None or tracer.samples >= self.trace_samples and \
                tracer.camera == self.controls.camera:
            self._stepping = False
            return
        self._show(self._picture(tracer.add(self.controls.camera, 1)))
        self._gl.submit(self._step)

    def pick(self, x: float, y: float):
        """What pixel (x, y) of the view shows (:meth:`Renderer.pick`), kept in
        ``picked`` and said in the status line; None over the background."""
        c = self.controls
        found = self._on_gl(self.renderer.pick, c.scene, c.camera, x, y)
        c.picks.append(found)
        if found is None:
            self.picked = {}
            c._say("pick: background")
        else:
            self.picked = {"face": found.face_id, "point": [float(v) for v in found.point],
                           "normal": [float(v) for v in found.normal],
                           "depth": float(found.depth)}
            c._say(f"pick: {found}")
        return found

    def recentre(self, x: float, y: float) -> bool:
        """Orbit about the surface point under (x, y) from now on (a double-click)."""
        c = self.controls
        found = self._on_gl(self.renderer.pick, c.scene, c.camera, x, y)
        if found is None:
            return False
        point = np.asarray(found.point, np.float64)
        c.camera = c.camera.replace(position=c.camera.position + point - c.center)
        c.center = point
        return True

    def _on_message(self, _widget, content: dict, _buffers) -> None:
        """A gesture from the browser (an unknown mode or key is said in the status
        line: a kernel would only log an exception raised here)."""
        from ..errors import GlshadeError

        try:
            self._gesture(content)
        except GlshadeError as exc:
            self.controls._say(f"error: {exc}")
            self.refresh()

    def _gesture(self, content: dict) -> None:
        event, c = content.get("event"), self.controls
        if event == "down":
            c.mouse_down(float(content["x"]), float(content["y"]),
                         str(content.get("button", "left")), bool(content.get("shift")))
        elif event == "move":
            c.mouse_move(float(content["x"]), float(content["y"]))
        elif event == "up":
            c.mouse_up()
        elif event == "wheel":
            c.scroll(float(content.get("dy", 0)))
        elif event == "key":
            key = str(content.get("key", ""))
            if key == "t":
                return self.trace(self.tracer is None)
            if key in MODE_KEYS and self.tracer is not None:
                self._on_gl(self._stop_tracing)
            c.key(key)
        elif event == "mode":
            self._on_gl(self._stop_tracing)
            c.options = c.options.replace(mode=_mode_name(content["mode"]))
        elif event == "compare":
            self.split = _mode_name(content["mode"]) if content.get("mode") else ""
        else:
            return
        self.refresh()  # (every gesture is answered by a frame: the browser's pacing)

    def close(self) -> None:
        """Close the widget and release its renderer (on its GL thread)."""
        if getattr(self, "renderer", None) is not None:
            self._on_gl(self._stop_tracing)
            self._on_gl(self.renderer.close)
            self._gl.shutdown()
            self.renderer = None
        super().close()


def _widget_class():
    try:
        import anywidget
        import traitlets
    except ImportError as exc:
        raise UsageError("the notebook viewer needs anywidget: pip install "
                         "'glshade[notebook]'") from exc

    class NotebookViewer(_Behaviour, anywidget.AnyWidget):
        """The widget; see the module docstring.

        Parameters
        ----------
        scene : Scene
            What to show.
        camera : Camera or None
            The first view (None: framed).
        size : (int, int)
            Width and height in pixels.
        mode : str
            The shading mode.
        compare : str
            A second mode shown right of the middle (the ``split`` trait), or "" for none.
        samples : int
            MSAA samples (4, as ``glshade render``).
        pick : bool
            Report the polygon under a click.
        backend : str or None
            The renderer's backend (auto, egl, osmesa).
        trace_samples : int
            Samples a pixel at which path tracing (key ``t``, :meth:`trace`) rests.
        **kwargs
            The widget's traits.
        """

        _esm = _STATIC / "viewer.js"
        _css = _STATIC / "viewer.css"
        png = traitlets.Bytes(b"").tag(sync=True)
        width = traitlets.Int(480).tag(sync=True)
        height = traitlets.Int(360).tag(sync=True)
        mode = traitlets.Unicode("phong").tag(sync=True)
        split = traitlets.Unicode("").tag(sync=True)
        view = traitlets.Dict().tag(sync=True)
        status = traitlets.Unicode("").tag(sync=True)
        picked = traitlets.Dict().tag(sync=True)
        revision = traitlets.Int(0).tag(sync=True)

    return NotebookViewer


class _Controls(Controls):
    """The window's controls, picking and re-centring through the widget's renderer."""

    def __init__(self, widget, *args, **kwargs):
        self.widget = widget
        super().__init__(*args, **kwargs)

    def pick(self, x: float, y: float):
        return self.widget.pick(x, y)

    def recentre(self, x: float, y: float) -> bool:
        return self.widget.recentre(x, y)


def _mode_name(mode) -> str:
    return ShadingMode.parse(mode).value


_CLASS: Any = None


def __getattr__(name: str):
    if name == "NotebookViewer":
        global _CLASS
        if _CLASS is None:
            _CLASS = _widget_class()
        return _CLASS
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def view(scene_or_mesh, camera: Camera | None = None, **kwargs):
    """An interactive viewer widget of a scene or mesh (``NotebookViewer``'s keywords:
    size, mode, compare, samples, pick); display it by leaving it last in a cell.

    Parameters
    ----------
    scene_or_mesh : Scene or Mesh
        What to show.
    camera : Camera or None
        The first view.
    **kwargs
        NotebookViewer's keywords.
    """
    scene = scene_or_mesh
    if not isinstance(scene, Scene):
        scene = Scene()
        scene.add(scene_or_mesh)
    return __getattr__("NotebookViewer")(scene, camera, **kwargs)
