"""A camera whose orientation is a unit quaternion.

The orientation takes camera axes to world axes: the camera looks down its local -z with
+y up (OpenGL). See :mod:`glshade.geometry.transforms` for the conventions.
"""

from __future__ import annotations

import copy
import enum
import math

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import SceneError
from ..modes import Projection, parse_enum
from .. import quaternion as quat
from ..geometry.transforms import MAX_COORDINATE, look_at, orthographic, perspective
from .intrinsics import (GL_FROM_CV, check_intrinsics, check_rotation, intrinsics_of, lens_of,
                         projection_from_lens)

__all__ = ["Camera", "View", "default_camera"]

PROJECTIONS = tuple(p.value for p in Projection)


#: the narrowest field of view (degrees): a camera framing a scene through a narrower one
#: would stand further off than a float can say
MIN_FOV_Y = 1e-4


def check_fov(fov_y: object, what: str = "fov_y") -> float:
    """The one rule for a vertical field of view: degrees in [MIN_FOV_Y, 180)."""
    try:
        value = float(fov_y)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        value = float("nan")
    if not MIN_FOV_Y <= value < 180:
        raise SceneError.must(what, f"be from {MIN_FOV_Y:g} to under 180 degrees, got "
                                    f"{fov_y!r}")
    return value


def _vec3(value, name) -> NDArray[np.float64]:
    a = np.array(value, dtype=np.float64)  # (a copy: the camera keeps it read-only)
    if a.shape != (3,) or not np.isfinite(a).all():
        shown = ", ".join(f"{float(x):g}" for x in np.ravel(a)) if a.dtype.kind in "fiu" \
            else repr(value)
        raise SceneError(f"{name} must be 3 finite numbers, got ({shown})")
    return a


@dataclass(frozen=True)
class Camera:
    """A pinhole (or orthographic) camera.

    Parameters
    ----------
    position : (3,) world position of the eye.
    orientation : (4,) unit quaternion [x, y, z, w], camera axes to world axes.
    fov_y : vertical field of view in degrees (perspective).
    near, far : clip distances along the view axis; None (the default): from the scene's
        bounds at every draw (:meth:`with_planes`), so nothing in front of the camera is
        ever clipped away, wherever it moves.
    projection : :class:`~glshade.Projection` (or "perspective", "orthographic").
    height : view height in world units (orthographic).
    lens : (4,) or None: a pinhole's intrinsics as fractions of the image --
        fx / W, fy / H, (cx + 0.5) / W and (cy + 0.5) / H: what :meth:`from_opencv` keeps
        of K (fx != fy and an off-centre principal point); ``fov_y`` then follows from
        fy. None: square pixels, the principal point at the centre, ``fov_y``.
    """

    position: NDArray[np.float64] = field(default_factory=lambda: np.array([0.0, 0.0, 3.0]))
    orientation: NDArray[np.float64] = field(default_factory=lambda: quat.identity())
    fov_y: float = 45.0
    near: float | None = None
    far: float | None = None
    projection: Projection = Projection.PERSPECTIVE
    height: float = 2.0
    lens: tuple[float, float, float, float] | None = None

    def __post_init__(self):
        object.__setattr__(self, "position", _vec3(self.position, "position"))
        q = np.asarray(self.orientation, dtype=np.float64)
        if q.shape != (4,) or not np.isfinite(q).all() or np.linalg.norm(q) == 0:
            raise SceneError(f"orientation must be a non-zero quaternion [x, y, z, w], "
                                f"got {self.orientation!r}")
        object.__setattr__(self, "orientation", quat.normalize(q))
        for name in ("position", "orientation"):  # a value: never changed in place
            getattr(self, name).setflags(write=False)
        object.__setattr__(self, "projection", Projection.parse(self.projection))
        if self.lens is not None:
            lens = np.asarray(self.lens, dtype=np.float64)
            if lens.shape != (4,) or not np.isfinite(lens).all() or not (lens[:2] > 0).all():
                raise SceneError(f"lens must be (fx / W, fy / H, (cx + 0.5) / W, (cy + 0.5) "
                                 f"/ H), finite, the focal lengths > 0, got {self.lens!r}")
            if self.projection is not Projection.PERSPECTIVE:
                raise SceneError("a lens (K) is a pinhole's: the projection must be "
                                 "perspective")
            object.__setattr__(self, "lens", tuple(float(v) for v in lens))
            # (the vertical field of view K's fy gives: what framing and the viewer read)
            object.__setattr__(self, "fov_y", float(np.degrees(2 * np.arctan(0.5 / lens[1]))))
        object.__setattr__(self, "fov_y", check_fov(self.fov_y))
        for name in ("near", "far"):
            value = getattr(self, name)
            if value is not None:
                if isinstance(value, bool) or not isinstance(value, (int, float, np.number)) \
                        or not 1 / MAX_COORDINATE <= float(value) <= MAX_COORDINATE:
                    raise SceneError(f"{name} must be a distance from {1 / MAX_COORDINATE:g} "
                                     f"to {MAX_COORDINATE:g} (or None: from the scene), got "
                                     f"{value!r}")
                object.__setattr__(self, name, float(value))
        if self.near is not None and self.far is not None and not self.near < self.far:
            raise SceneError(f"need 0 < near < far, got near={self.near}, far={self.far}")

    # ------------------------------------------------------------------ construction
    @classmethod
    def look_at(cls, eye: ArrayLike, target: ArrayLike, up: ArrayLike = (0, 1, 0),
                **kwargs) -> Camera:
        """A camera at ``eye`` looking at ``target`` with ``up`` roughly up.

        Parameters
        ----------
        eye : array_like
            ``(3,)`` the camera's position (world).
        target : array_like
            ``(3,)`` the point it looks at.
        up : array_like
            ``(3,)`` roughly up (not parallel to the view direction).
        **kwargs
            The camera's other fields (``fov_y``, ``near``, ``far``, ``projection`` ...).
        """
        view = look_at(eye, target, up)
        camera = cls(position=np.asarray(eye, np.float64),
                     orientation=quat.from_matrix(view[:3, :3].T), **kwargs)
        view.setflags(write=False)  # (its view matrix is this one: no conversion back from
        camera.__dict__["_view"] = view  # the quaternion when it is drawn, a frame each)
        return camera

    @classmethod
    def from_opencv(cls, K: ArrayLike, R: ArrayLike, t: ArrayLike, size,
                    **kwargs) -> Camera:
        """The camera OpenCV describes by ``K`` and the pose ``x_cam = R @ X + t`` (camera
        x right, y down, z forward; integer pixel coordinates at pixel centres): a world
        point that ``cv2.projectPoints`` sends to (u, v) is drawn in column floor(u + 0.5),
        row floor(v + 0.5) of a ``size`` image. Refused, naming the fault: skew, focal
        lengths <= 0, a principal point more than the image away, an R that is not a
        rotation within 1e-6.

        Parameters
        ----------
        K : array_like
            ``(3, 3)`` intrinsics in pixels: ``[[fx, 0, cx], [0, fy, cy], [0, 0, 1]]``.
        R : array_like
            ``(3, 3)`` world-to-camera rotation.
        t : array_like
            ``(3,)`` world-to-camera translation (scene units).
        size : (int, int)
            The image's width and height in pixels, K's.
        **kwargs
            The camera's other fields (``near``, ``far``).
        """
        k, r = check_intrinsics(K, size), check_rotation(R)
        t = _vec3(t, "t")
        c2w = r.T @ GL_FROM_CV  # (camera axes, OpenGL's, to world)
        return cls(position=-r.T @ t, orientation=quat.from_matrix(c2w),
                   lens=lens_of(k, size), **kwargs)

    def intrinsics(self, size) -> NDArray[np.float64]:
        """K ``(3, 3)`` for a ``size`` image, OpenCV's (pixel centres at integers): the
        lens's, or for a camera without one square pixels with the principal point at the
        image's centre, ``fy = H / (2 tan(fov_y / 2))``.

        Parameters
        ----------
        size : (int, int)
            The image's width and height in pixels.
        """
        if self.projection is not Projection.PERSPECTIVE:
            raise SceneError("an orthographic camera has no pinhole intrinsics (K)")
        if self.lens is not None:
            return intrinsics_of(self.lens, size)
        w, h = size
        f = h / (2 * np.tan(np.radians(self.fov_y) / 2))
        return intrinsics_of((f / w, f / h, 0.5, 0.5), size)

    def to_opencv(self, size) -> tuple[NDArray[np.float64], NDArray[np.float64],
                                       NDArray[np.float64]]:
        """``(K, R, t)``: this camera in OpenCV's terms for a ``size`` image
        (:meth:`from_opencv`'s inverse, exact to rounding).

        Parameters
        ----------
        size : (int, int)
            The image's width and height in pixels.
        """
        K = self.intrinsics(size)
        R = GL_FROM_CV @ self.rotation.T
        return K, R, -R @ self.position

    def replace(self, **changes) -> Camera:
        """A copy of this camera with ``changes``.

        Parameters
        ----------
        **changes
            Fields to replace, by name (checked as the constructor checks them).
        """
        return replace(self, **changes)

    # ------------------------------------------------------------------ frames
    @property
    def rotation(self) -> NDArray[np.float64]:
        """Camera-to-world rotation ``(3, 3)`` (columns: right, up, back)."""
        return quat.to_matrix(self.orientation)

    @property
    def forward(self) -> NDArray[np.float64]:
        return quat.rotate(self.orientation, [0.0, 0.0, -1.0])

    @property
    def up(self) -> NDArray[np.float64]:
        return quat.rotate(self.orientation, [0.0, 1.0, 0.0])

    @property
    def right(self) -> NDArray[np.float64]:
        return quat.rotate(self.orientation, [1.0, 0.0, 0.0])

    def view_matrix(self) -> NDArray[np.float64]:
        """World-to-view ``(4, 4)`` for column vectors (read-only; computed once per camera,
        so redrawing from the same camera converts no quaternion)."""
        m = self.__dict__.get("_view")
        if m is None:
            rt = self.rotation.T
            m = np.zeros((4, 4))
            m[:3, :3] = rt
            m[:3, 3] = -(rt @ self.position)
            m[3, 3] = 1.0
            m.setflags(write=False)
            self.__dict__["_view"] = m  # (a frozen dataclass: a cache, not a field)
        return m

    def projection_matrix(self, aspect: float) -> NDArray[np.float64]:
        """View-to-clip ``(4, 4)`` for column vectors; ``aspect`` = width / height. (Planes
        not given and not yet fitted to a scene by :meth:`with_planes`: 0.1 and 100.)

        Parameters
        ----------
        aspect : float
            The image's width over its height.
        """
        near, far = self.planes()
        if self.lens is not None:
            return projection_from_lens(self.lens, near, far)
        if self.projection is Projection.PERSPECTIVE:
            return perspective(self.fov_y, aspect, near, far)
        return orthographic(self.height, aspect, near, far)

    def rays(self, size: tuple[int, int], jitter: ArrayLike | None = None
             ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The pixel rays of a ``size = (width, height)`` image: world-space origins and unit
        directions ``(H, W, 3)``, through pixel centres, row 0 at the top -- the one pixel-ray
        convention every numpy ray caster, picker and oracle-facing twin uses (the GPU's is
        ``shaders/include/rays.glsl``). Perspective rays start at the eye, orthographic ones
        on the image plane through it. ``jitter`` ``(H, W, 2)`` (or broadcastable) moves each
        sample from its pixel's centre, in pixels (x right, y down).

        Parameters
        ----------
        size : (int, int)
            The image's width and height in pixels.
        jitter : array_like or None
            ``(H, W, 2)`` (or broadcastable) offsets from each pixel's centre, in pixels.
        """
        width, height = int(size[0]), int(size[1])
        j, i = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
        if jitter is not None:
            offset = np.broadcast_to(np.asarray(jitter, np.float64), (height, width, 2))
            j, i = j + offset[..., 0], i + offset[..., 1]
        return self.rays_through((width, height), j, i)

    def rays_through(self, size: tuple[int, int], x: ArrayLike, y: ArrayLike
                     ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The rays through image points ``(x, y)`` of a ``size = (width, height)`` image,
        in pixels from its top-left corner (x right, y down: pixel (i, j)'s centre is
        (i + 0.5, j + 0.5)) -- :meth:`rays`'s convention at any points (a picked pixel, a
        sample).

        Parameters
        ----------
        size : (int, int)
            The image's width and height in pixels.
        x, y : array_like
            The points' coordinates in pixels, any broadcastable shapes.

        Returns
        -------
        origins, directions : ndarray
            ``(..., 3)`` float64 world-space origins and unit directions.
        """
        width, height = int(size[0]), int(size[1])
        x = 2 * np.asarray(x, np.float64) / width - 1
        y = 1 - 2 * np.asarray(y, np.float64) / height
        x, y = np.broadcast_arrays(x, y)
        r = self.rotation
        if self.lens is not None:  # (OpenCV's pinhole: (u - cx) / fx, (v - cy) / fy)
            a, b, px, py = self.lens
            d = np.stack([((x + 1) / 2 - px) / a, ((y + 1) / 2 - (1 - py)) / b,
                          -np.ones_like(x)], -1) @ r.T
            d /= np.linalg.norm(d, axis=-1, keepdims=True)
            o = np.broadcast_to(self.position, d.shape)
        elif self.projection == "perspective":
            t = np.tan(np.radians(self.fov_y) / 2)
            d = np.stack([x * t * width / height, y * t, -np.ones_like(x)], -1) @ r.T
            d /= np.linalg.norm(d, axis=-1, keepdims=True)
            o = np.broadcast_to(self.position, d.shape)
        else:
            half_h = self.height / 2
            offset3 = np.stack([x * half_h * width / height, y * half_h, np.zeros_like(x)], -1)
            o = self.position + offset3 @ r.T
            d = np.broadcast_to(self.forward, o.shape)
        return o, d

    def planes(self, bounds: ArrayLike | None = None) -> tuple[float, float]:
        """``(near, far)``: the camera's own, else fitted to ``bounds`` ``(2, 3)`` -- the far
        plane just beyond the farthest corner of the box, the near plane just before the
        nearest (``PLANE_RATIO`` of the far one when the camera is inside the box) -- else
        (no bounds) 0.1 and 100.

        Parameters
        ----------
        bounds : array_like or None
            ``(2, 3)`` the scene's box (min and max corners), to fit missing planes to.
        """
        if self.near is not None and self.far is not None:
            return self.near, self.far
        if bounds is None:
            near, far = FALLBACK_PLANES
        else:
            b = np.asarray(bounds, np.float64)
            row = self.view_matrix()[2]
            # the view depth of a box's corners: the nearest and farthest are its extremes
            # along the view axis, one coordinate at a time (no corner list, per frame)
            lo, hi = b[0] * row[:3], b[1] * row[:3]
            d_near = -(float(np.maximum(lo, hi).sum()) + row[3])
            d_far = -(float(np.minimum(lo, hi).sum()) + row[3])
            extent = math.dist(b[0], b[1]) or 1.0
            far = max(d_far, 0.0) * 1.01 + extent * 1e-3
            near = max(d_near * 0.99, far * PLANE_RATIO)
        if self.far is not None:
            far = self.far
        if self.near is not None:
            near = self.near
        if not near < far:  # (one plane given, the scene's other beyond it)
            far = near * 1e4 if self.far is None else far
            near = far * PLANE_RATIO if self.near is None else near
        return near, far

    def with_planes(self, bounds: ArrayLike) -> Camera:
        """This camera with its missing clip planes fitted to ``bounds`` (itself when it has
        both): what every draw uses, so a camera made by :meth:`frame` or :meth:`look_at`
        never clips the scene in front of it, however it is moved.

        Parameters
        ----------
        bounds : array_like
            ``(2, 3)`` the scene's box (min and max corners).
        """
        if self.near is not None and self.far is not None:
            return self
        near, far = self.planes(bounds)
        fitted = copy.copy(self)  # (a copy, not replace(): nothing to check again, per frame)
        object.__setattr__(fitted, "near", near)
        object.__setattr__(fitted, "far", far)
        return fitted

    # ------------------------------------------------------------------ moves
    def orbit(self, q: ArrayLike, center: ArrayLike = (0.0, 0.0, 0.0)) -> Camera:
        """Rotate the camera about ``center`` by the rotation ``q`` (position and
        orientation alike, so the centre stays where it is on screen).

        Parameters
        ----------
        q : array_like
            ``(4,)`` a unit quaternion ``(x, y, z, w)``.
        center : array_like
            ``(3,)`` the point orbited (world).
        """
        q = quat.normalize(q)
        center = _vec3(center, "center")
        return self.replace(position=quat.transform_points(q, self.position, center),
                            orientation=quat.multiply(q, self.orientation))

    def frame(self, target, aspect: float = 1.0, margin: float = 1.1) -> Camera:
        """Move the camera along its view axis so that the bounding sphere of ``target`` (a
        Mesh, or bounds ``(2, 3)``) fits in view with the given ``margin``; the clip planes
        are left to each draw (None: fitted to the scene then).

        Parameters
        ----------
        target : Mesh or array_like
            What to fit: a Mesh or bounds ``(2, 3)``.
        aspect : float
            The image's width over its height.
        margin : float
            How much larger than the bounding sphere the view is (1: touching).
        """
        bounds = getattr(target, "bounds", target)
        b = np.asarray(bounds, dtype=np.float64)
        if b.shape != (2, 3):
            raise SceneError(f"frame needs a mesh or bounds of shape (2, 3), got {b.shape}")
        center = b.mean(axis=0)
        radius = max(float(np.linalg.norm(b[1] - b[0])) / 2, 1e-9) * margin
        if self.projection is Projection.PERSPECTIVE:
            half_y = np.radians(self.fov_y) / 2
            half_x = np.arctan(np.tan(half_y) * aspect)
            distance = radius / np.sin(min(half_x, half_y))
            return self.replace(position=center - self.forward * distance, near=None,
                                far=None)
        distance = 2 * radius
        return self.replace(position=center - self.forward * distance, near=None, far=None,
                            height=2 * radius * max(1.0, 1.0 / aspect))

    # ------------------------------------------------------------------ the usual moves
    def azimuth(self, degrees: float, center: ArrayLike = (0.0, 0.0, 0.0)) -> Camera:
        """Orbit ``degrees`` about the world's up axis (+y) through ``center``
        (counter-clockwise seen from above).

        Parameters
        ----------
        degrees : float
            The angle to orbit by.
        center : array_like
            ``(3,)`` the point orbited (world).
        """
        return self.orbit(quat.from_axis_angle((0.0, 1.0, 0.0), np.radians(degrees)), center)

    def elevation(self, degrees: float, center: ArrayLike = (0.0, 0.0, 0.0)) -> Camera:
        """Orbit ``degrees`` up (positive) or down about the camera's right axis through
        ``center``.

        Parameters
        ----------
        degrees : float
            The angle to orbit by (positive: up).
        center : array_like
            ``(3,)`` the point orbited (world).
        """
        return self.orbit(quat.from_axis_angle(self.right, -np.radians(degrees)), center)

    def roll(self, degrees: float) -> Camera:
        """Turn ``degrees`` about the view axis (counter-clockwise on screen).

        Parameters
        ----------
        degrees : float
            The angle to turn by.
        """
        q = quat.from_axis_angle(self.forward, -np.radians(degrees))
        return self.replace(orientation=quat.multiply(q, self.orientation))

    def dolly(self, distance: float) -> Camera:
        """Move ``distance`` along the view axis (positive: forward), looking the same way;
        the clip planes follow at the next draw (None planes are fitted to the scene).

        Parameters
        ----------
        distance : float
            Scene units along the view axis (positive: forward).
        """
        return self.replace(position=self.position + self.forward * float(distance))

    def zoom(self, factor: float) -> Camera:
        """Magnify by ``factor`` (> 1: closer) without moving: a narrower field of view, or
        a smaller orthographic view height.

        Parameters
        ----------
        factor : float
            The magnification, > 0 (> 1: closer).
        """
        f = float(factor)
        if not 0 < f < float("inf"):
            raise SceneError(f"zoom factor must be a positive number, got {factor!r}")
        if self.projection is Projection.ORTHOGRAPHIC:
            return self.replace(height=self.height / f)
        if self.lens is not None:
            a, b, px, py = self.lens
            return self.replace(lens=(a * f, b * f, px, py))
        half = np.arctan(np.tan(np.radians(self.fov_y) / 2) / f)
        return self.replace(fov_y=float(np.degrees(2 * half)))

    @classmethod
    def named(cls, view: View | str, bounds, aspect: float = 1.0, *,
              margin: float = 1.1, **lens) -> Camera:
        """A camera looking at the centre of ``bounds`` (a Mesh, a Scene or ``(2, 3)``) from
        one of the named views (:class:`View`), framed to fit: front looks down -z, right
        down -x, top down -y (with -z up on screen), iso from (+x, +y, +z).

        Parameters
        ----------
        view : View or str
            The named view (``"front"``, ``"right"``, ``"top"``, ``"iso"`` ...).
        bounds : Mesh, Scene or array_like
            What to look at and frame: its bounds ``(2, 3)``.
        aspect : float
            The image's width over its height.
        margin : float
            How much larger than the bounding sphere the view is.
        **lens
            The camera's lens fields (``fov_y``, ``projection`` ...).
        """
        chosen = View.parse(view)
        b = np.asarray(getattr(bounds, "bounds", bounds), np.float64)
        direction, up = _VIEWS[chosen]
        center = b.mean(axis=0)
        eye = center + np.asarray(direction, np.float64)
        return cls.look_at(eye, center, up=up, **lens).frame(b, aspect=aspect, margin=margin)

    def __eq__(self, other) -> bool:
        if not isinstance(other, Camera):
            return NotImplemented
        return (np.array_equal(self.position, other.position)
                and np.array_equal(self.orientation, other.orientation)
                and (self.fov_y, self.near, self.far, self.projection, self.height)
                == (other.fov_y, other.near, other.far, other.projection, other.height))

    __hash__ = None  # type: ignore[assignment]


class View(str, enum.Enum):
    """The named views: where the camera looks from, towards the scene's centre."""

    FRONT = "front"
    BACK = "back"
    LEFT = "left"
    RIGHT = "right"
    TOP = "top"
    BOTTOM = "bottom"
    ISO = "iso"

    @classmethod
    def parse(cls, value: object) -> View:
        """A View, or a view's name; a bad name lists the choices.

        Parameters
        ----------
        value : View or str
            A member or its name.
        """
        return parse_enum(cls, value, "view")


#: each view: (from where, relative to the centre; up on screen)
_VIEWS = {View.FRONT: ((0, 0, 1), (0, 1, 0)), View.BACK: ((0, 0, -1), (0, 1, 0)),
          View.LEFT: ((-1, 0, 0), (0, 1, 0)), View.RIGHT: ((1, 0, 0), (0, 1, 0)),
          View.TOP: ((0, 1, 0), (0, 0, -1)), View.BOTTOM: ((0, -1, 0), (0, 0, 1)),
          View.ISO: ((1, 1, 1), (0, 1, 0))}

#: the near plane of a camera inside the scene's box, as a fraction of the far plane (a
#: 24-bit depth buffer then still resolves 1/1600 of the far distance there)
PLANE_RATIO = 1e-4
#: the largest far / near a draw takes without a warning: past it float32 window depth
#: rounds to 1 and a perspective draw loses pixels (a sphere seen from inside, measured on
#: llvmpipe: none at 2e5, 0.1% at 8e5, 2% at 1e6, 20% at 1.6e6, 98% at 1e7)
MAX_PLANE_RATIO = 3e5
#: the clip planes of a camera with none, before a draw fits them to a scene
FALLBACK_PLANES = (0.1, 100.0)

#: the direction the default camera looks from (towards the centre): front, right, above
DEFAULT_VIEW_FROM = (0.55, 0.45, 1.0)


def default_camera(bounds, aspect: float = 1.0, **kwargs) -> Camera:
    """The auto-framed camera that ``glshade render`` and ``glshade view`` start from:
    looking at the centre of ``bounds`` (a Mesh, a Scene or bounds ``(2, 3)``) from the
    front-right, above, with everything in view.

    Parameters
    ----------
    bounds : Mesh, Scene or array_like
        What to frame: its bounds ``(2, 3)``.
    aspect : float
        The image's width over its height.
    **kwargs
        The camera's other fields (``fov_y``, ``projection`` ...).
    """
    b = np.asarray(getattr(bounds, "bounds", bounds), dtype=np.float64)
    center = b.mean(axis=0)
    direction = np.asarray(DEFAULT_VIEW_FROM)
    cam = Camera.look_at(center + direction, center, **kwargs)
    return cam.frame(b, aspect=aspect, margin=1.0)
