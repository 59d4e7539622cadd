"""What one draw is, as one frozen value that every pass receives.

:meth:`DrawState.of` works out, once per draw, the camera's matrices, the lights, the program
variant, the uniforms every program shares, the target's viewport and orientation -- and
every decision a pass acts on (does this draw cast shadows, found where, is the visibility
read back). Each pass reads them from this value instead of from the renderer, so no pass
reaches into another object's state, no rule is written twice, and what a pass may depend
on is written here.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..geometry.transforms import box_corners, gl_bytes, outside_frustum
from ..modes import Projection, ShadingMode, Shadows
from ..options import DrawOptions
from ..scene import Camera, Scene
from .programs import Forward, Variant, light_kind

__all__ = ["DrawState", "SHADOWED_MODES", "TRANSPARENT_MODES", "sees_through"]

#: the modes whose lights a shadow hides (the others show no light: normals, depth,
#: radiosity's solved values)
SHADOWED_MODES = (ShadingMode.FLAT, ShadingMode.GOURAUD, ShadingMode.PHONG)
#: the modes in which a transparent material is seen through (the debug modes' colours are
#: values to read, not surfaces to see through)
TRANSPARENT_MODES = SHADOWED_MODES + (ShadingMode.RADIOSITY,)

_FLIP_Y = np.diag([1.0, -1.0, 1.0, 1.0])


def sees_through(options, scene) -> bool:
    """Whether a draw with ``options`` has transparent surfaces to composite: a shown mesh
    model whose material is transparent, in a mode that sees through it (the rule
    :meth:`DrawState.transparent` applies model by model).

    Parameters
    ----------
    options : DrawOptions
        The draw's options (its mode).
    scene : Scene
        What is drawn.
    """
    return options.mode in TRANSPARENT_MODES and any(
        m.visible and m.transparent for m in scene.models)


@dataclass(frozen=True, eq=False)
class DrawState:
    """One draw's facts.

    Attributes
    ----------
    scene, camera, options
        what is drawn, from where, how.
    view
        (4, 4) float64 world-to-view matrix (column vectors).
    proj
        (4, 4) float64 projection, flipped in y for a top-row-first target.
    lights
        the lights of the draw (the scene's, or the default headlight), in order.
    variant
        the program variant's fields (mode, aux outputs, light kinds, sRGB, orthographic,
        shadows and where they are found) that every program of the draw shares;
        ``variant.shadows`` is *the* answer to "does this draw cast shadows".
    frame_uniforms
        ``(name, value)`` pairs every program of the draw takes (projection, lights in view
        space, depth range; the shadow pass adds its own).
    viewport
        ``(x, y, w, h)`` in the target's pixels.
    flip_rows
        whether the target stores row 0 at the top (its winding is mirrored).
    target
        what is drawn into (an OffscreenTarget, a window's; ``bind(outputs)``).
    read_visibility
        the frame reads each light's visibility back (``Frame.visibility``): the shadows go
        through a G-buffer and a visibility array.
    clear
        the target is cleared before the draw (else drawn over, e.g. a viewport of a
        window's grid).
    """

    scene: Scene
    camera: Camera
    options: DrawOptions
    view: np.ndarray
    proj: np.ndarray
    lights: tuple
    variant: Variant
    frame_uniforms: tuple
    viewport: tuple[int, int, int, int]
    flip_rows: bool
    target: Any = None
    read_visibility: bool = False
    clear: bool = True

    @classmethod
    def of(cls, target, scene: Scene, camera: Camera, options: DrawOptions,
           viewport: tuple[int, int, int, int] | None = None, *,
           read_visibility: bool = False, clear: bool = True,
           traced_forward: bool = True) -> DrawState:
        """The facts of drawing ``scene`` seen by ``camera`` (its planes already fitted)
        with ``options`` into ``target``.

        Parameters
        ----------
        target
            what is drawn into; its ``width``, ``height`` and ``rows_top_down``.
        scene, camera, options
            what is drawn, from where, how.
        viewport
            ``(x, y, w, h)`` in the target's pixels; the whole target when None.
        read_visibility
            the frame reads each light's visibility back, so the shadows go through a
            G-buffer (not found by the shading programs as they shade).
        clear
            the target is cleared first.
        traced_forward
            the shading programs can trace their own shadow rays (they count those that
            run out in a storage buffer: GL 4.3); else exact shadows go through a G-buffer.
        """
        view = camera.view_matrix()
        vx, vy, vw, vh = viewport or (0, 0, target.width, target.height)
        proj = camera.projection_matrix(vw / vh)
        flip_rows = bool(getattr(target, "rows_top_down", False))
        if flip_rows:  # image row 0 first in memory; this mirrors the winding on screen
            proj = _FLIP_Y @ proj
        lights = tuple(scene.lights_for(camera))
        shadows = (options.shadows is not Shadows.OFF and options.mode in SHADOWED_MODES
                   and not options.wireframe)
        # shadows found by the programs as they shade (maps looked up, rays traced), unless
        # the frame reads the visibility back or a CSG solid casts (its rays are a compute
        # pass's) -- then through a G-buffer
        forward = Forward.ARRAY
        if shadows and not read_visibility:
            if options.shadows is Shadows.MAP:
                forward = Forward.MAPS
            elif not scene.solids and traced_forward:
                forward = Forward.RAYS
        variant = Variant(options.mode, options.outputs.auxiliary,
                          tuple(light_kind(x) for x in lights), options.srgb,
                          camera.projection is Projection.ORTHOGRAPHIC, shadows, forward,
                          scene.environment is not None)
        frame = _frame_uniforms(scene, camera, lights, view, proj, options.mode)
        return cls(scene, camera, options, view, proj, lights, variant, tuple(frame),
                   (vx, vy, vw, vh), flip_rows, target, read_visibility and shadows, clear)

    @property
    def view_proj(self) -> np.ndarray:
        """(4, 4) world-to-clip matrix."""
        return self.proj @ self.view

    def outside(self, models) -> np.ndarray:
        """``(K,)`` bool: which of ``models`` (each with ``corners``, its world box) lie
        wholly outside the view (:func:`~glshade.geometry.transforms.outside_frustum`),
        with frustum culling on; none for a single model (out of view, its frame is blank
        anyway: the test would cost more than it saves).

        Parameters
        ----------
        models : sequence
            The models, each with ``corners`` ``(8, 3)``.
        """
        if not self.options.frustum_cull or len(models) < 2:
            return np.zeros(len(models), bool)
        return outside_frustum(self.view_proj, np.stack([m.corners for m in models]))

    def screen_uniforms(self) -> dict:
        """What a program that casts each pixel's ray (or works in window pixels) reads:
        the inverse projection, the camera's placement and the viewport."""
        x, y, w, h = (float(v) for v in self.viewport)
        return {"u_inverse_proj": gl_bytes(np.linalg.inv(self.proj)),
                "u_camera_to_world": gl_bytes(np.linalg.inv(self.view)),
                "u_viewport_origin": (x, y), "u_viewport_size": (w, h)}

    def with_uniforms(self, values: dict) -> DrawState:
        """This state with more uniforms every program of the draw takes (a pass's).

        Parameters
        ----------
        values : dict
            Uniforms by name.
        """
        return dataclasses.replace(self, frame_uniforms=self.frame_uniforms +
                                   tuple(values.items()))

    def transparent(self, model) -> bool:
        """Whether ``model`` is drawn by the transparency pass (after every opaque
        surface), not with the opaque ones.

        Parameters
        ----------
        model : Model
            A scene model.
        """
        return model.transparent and self.options.mode in TRANSPARENT_MODES

    def drawn(self, model) -> bool:
        """Whether ``model``'s mesh is drawn at all: shown, with triangles.

        Parameters
        ----------
        model : Model
            A scene model.
        """
        return model.visible and len(model.mesh.triangles[0]) > 0


def _frame_uniforms(scene, camera, lights, view, proj, mode) -> list:
    """The uniforms every program of one draw shares: matrices, lights, ambient."""
    # (only as many entries as lights: a program's arrays are cut to what it uses)
    pos = np.array([light.view_vector(view) for light in lights], dtype="f4")
    att = np.array([light.attenuation for light in lights], dtype="f4")
    # (a spot light's cone: its axis times the cone's scale, and its offset; 0 elsewhere)
    spot = np.array([light.spot_vector(view) if hasattr(light, "spot_vector") else
                     np.zeros(4) for light in lights], dtype="f4")
    out: list[tuple[str, Any]] = [
        ("u_proj", gl_bytes(proj)), ("u_light_pos_view", pos.tobytes()),
        ("u_light_attenuation", att.tobytes()), ("u_light_spot", spot.tobytes())]
    if scene.environment is not None:  # (view directions to the sky map's frame)
        from ..scene.environment import map_frame

        basis = map_frame(scene.environment.rotation) @ view[:3, :3].T
        out.append(("u_env_basis", gl_bytes(basis)))
    if mode is ShadingMode.DEPTH:
        corners = box_corners(scene.bounds)
        d = -(corners @ view[:3, :3].T + view[:3, 3])[:, 2]
        planes = camera.planes()
        near, far = max(planes[0], d.min()), min(planes[1], d.max())
        out.append(("u_depth_range", (float(near), float(max(far, near + 1e-6)))))
    return out
