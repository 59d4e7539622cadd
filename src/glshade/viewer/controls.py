"""The viewer's camera and option controls, with no window and no GL: what a drag, the
wheel or a key does to the view. The glfw window (:mod:`.window`) and the notebook widget
(:mod:`glshade.notebook`) both drive one, so the same gesture gives the same view in each.

Coordinates are the control's own (window or canvas pixels, y down); ``size`` is theirs.
"""

from __future__ import annotations

import time

import numpy as np

from .. import quaternion as quat
from ..modes import Culling, ShadingMode, Shadows
from ..options import DrawOptions
from ..scene import Camera, PointLight, Scene, default_camera
from .arcball import Arcball

__all__ = ["Controls", "MODE_KEYS", "DOUBLE_CLICK_S"]

MODE_KEYS = {"1": ShadingMode.FLAT, "2": ShadingMode.GOURAUD, "3": ShadingMode.PHONG,
             "4": ShadingMode.NORMALS, "5": ShadingMode.DEPTH, "6": ShadingMode.RADIOSITY}
#: two left presses within this many seconds are a double-click (re-centre)
DOUBLE_CLICK_S = 0.3


class Controls:
    """The state a viewer shows -- ``camera``, ``options``, ``compare``, the orbit
    ``center`` -- and the gestures that change it. ``size`` ``(w, h)``: the control's extent
    in its own coordinates; ``aspect``: the drawn view's width over height (default w / h;
    a third of it in compare mode). Subclasses supply :meth:`pick` and :meth:`recentre`.

    Parameters
    ----------
    scene : Scene
        What is shown.
    camera : Camera or None
        The first view (None: framed).
    size : (float, float)
        The control's extent in its own coordinates.
    options : DrawOptions, ShadingMode, str or None
        How it is drawn.
    compare : bool
        Show the shading modes side by side.
    pick : bool
        Report what a click lands on.
    """

    def __init__(self, scene: Scene, camera: Camera | None, size, options=None,
                 compare: bool = False, pick: bool = False):
        self.scene = scene
        self.options = DrawOptions.of(options)
        self.compare = bool(compare)
        self.picking = bool(pick)
        self.picks: list = []
        self.messages: list[str] = []
        self.arcball = Arcball(*size)
        self.center = scene.bounds.mean(axis=0)
        self.home = camera or default_camera(scene.bounds, self._aspect())
        self.camera = self.home
        self._view = -1  # (the last named view the v key chose)
        self._drag: tuple | None = None  # (kind, start camera, x, y, start centre)
        self._last_click = 0.0

    def _aspect(self) -> float:
        w, h = self.arcball.width, self.arcball.height
        return (w / 3 if self.compare else w) / max(h, 1)

    def _say(self, text: str) -> None:
        """A message for the user (a window prints it; a widget shows it)."""
        self.messages.append(text)

    def pick(self, x: float, y: float):  # pragma: no cover - each viewer has its own
        """What is under (x, y) (each viewer finds it its own way).

        Parameters
        ----------
        x, y : float
            The position in pixels, y down.
        """
        raise NotImplementedError

    def recentre(self, x: float, y: float) -> bool:  # pragma: no cover
        """Re-centre the view on the surface point under (x, y); whether there was one.

        Parameters
        ----------
        x, y : float
            The position in pixels, y down.
        """
        raise NotImplementedError

    # ------------------------------------------------------------------ keys
    def key(self, char: str) -> bool:
        """Act on a key that changes the view or the options; False for any other key.

        Parameters
        ----------
        char : str
            The key as typed.
        """
        o = self.options
        if char in MODE_KEYS:
            self.options = o.replace(mode=MODE_KEYS[char])
            self.compare = False
        elif char == "z":
            self.options = o.replace(depth_test=not o.depth_test)
        elif char == "w":
            self.options = o.replace(edges=not o.edges)
        elif char == "x":  # cast shadows: off, exact, map
            shadow_turn = {Shadows.OFF: Shadows.EXACT, Shadows.EXACT: Shadows.MAP,
                           Shadows.MAP: Shadows.OFF}
            self.options = o.replace(shadows=shadow_turn[o.shadows])
            self._say(f"shadows: {self.options.shadows.value}")
        elif char == "c":
            turn = {Culling.AUTO: Culling.ON, Culling.ON: Culling.OFF, Culling.OFF: Culling.AUTO}
            self.options = o.replace(cull=turn[o.cull])
            self._say(f"back-face culling: {self.options.cull.value}")
        elif char == "l":
            self.scene.lights = [PointLight(tuple(self.camera.position))]
        elif char == "r":
            self.camera = self.home
            self.center = self.scene.bounds.mean(axis=0)
        elif char == "v":  # the named views in turn, framed
            from ..scene.camera import View

            self._view = (self._view + 1) % len(View)
            chosen = list(View)[self._view]
            self.camera = Camera.named(chosen, self.scene.bounds, self._aspect(),
                                       fov_y=self.camera.fov_y).replace(
                projection=self.camera.projection)
            if self.camera.projection.value == "orthographic":
                self.camera = self.camera.frame(self.scene.bounds, self._aspect())
            self.center = self.scene.bounds.mean(axis=0)
            self._say(f"view: {chosen.value}")
        elif char == "o":  # perspective <-> orthographic, the view's centre kept in frame
            ortho = self.camera.projection.value == "perspective"
            self.camera = self.camera.replace(
                projection="orthographic" if ortho else "perspective")
            if ortho:
                distance = float(np.linalg.norm(self.center - self.camera.position))
                self.camera = self.camera.replace(
                    height=2 * distance * np.tan(np.radians(self.camera.fov_y) / 2))
            self._say(f"projection: {self.camera.projection.value}")
        else:
            return False
        return True

    # ------------------------------------------------------------------ mouse
    def mouse_down(self, x: float, y: float, button: str = "left",
                   shift: bool = False) -> None:
        """A button pressed at (x, y): left drags turn the view, right or shift drags pan;
        a left double-click re-centres on the surface.

        Parameters
        ----------
        x, y : float
            The position in pixels, y down.
        button : str
            ``"left"`` or ``"right"``.
        shift : bool
            Shift held (a pan).
        """
        now = time.perf_counter()
        if button == "left" and now - self._last_click < DOUBLE_CLICK_S:
            self.recentre(x, y)
        self._last_click = now if button == "left" else 0.0
        kind = "pan" if button == "right" or shift else "rotate"
        self._drag = (kind, self.camera, x, y, self.center.copy())
        if kind == "rotate":
            self.arcball.begin(x, y)

    def mouse_move(self, x: float, y: float) -> None:
        """The pointer moved to (x, y): drags turn (arcball) or pan the view.

        Parameters
        ----------
        x, y : float
            The position in pixels, y down.
        """
        if self._drag is None:
            return
        kind, start, x0, y0, center0 = self._drag
        if kind == "rotate":
            q_view = self.arcball.drag(x, y)
            # the object turns by q_view in view space: the camera orbits the other way
            q_world = quat.multiply(quat.multiply(start.orientation, q_view),
                                    quat.conjugate(start.orientation))
            self.camera = start.orbit(quat.conjugate(q_world), self.center)
        else:
            distance = float(np.linalg.norm(start.position - self.center))
            per_px = 2 * distance * np.tan(np.radians(start.fov_y) / 2) / \
                max(self.arcball.height, 1)
            shift = (-(x - x0) * start.right + (y - y0) * start.up) * per_px
            self.camera = start.replace(position=start.position + shift)
            self.center = center0 + shift

    def mouse_up(self) -> None:
        """The button let go: the drag ends (a click that did not move picks, with
        ``pick=True``)."""
        if self.picking and self._drag is not None:
            _, start, x0, y0, _ = self._drag
            if start is self.camera:  # (nothing moved: a click)
                self.pick(x0, y0)
        self._drag = None
        self.arcball.end()

    def scroll(self, dy: float) -> None:
        """Dolly towards (dy > 0) or away from the centre.

        Parameters
        ----------
        dy : float
            The wheel's steps (positive: towards).
        """
        to_center = self.center - self.camera.position
        self.camera = self.camera.replace(position=self.camera.position +
                                          to_center * (1 - 0.9 ** dy))
