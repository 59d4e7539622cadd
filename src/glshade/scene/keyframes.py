"""Camera key frames interpolated with quaternions (the notes' use of slerp).

Orientation between neighbouring keys is slerp (constant angular speed, shortest arc) or a
C1 quaternion spline; position is linear or Catmull-Rom.

One file format: a path is a scene file's ``[camera]`` table with its key frames, so a path
saved by :meth:`CameraPath.save` (or the viewer's ``P``) can be pasted into a scene file,
and :meth:`CameraPath.load` reads a scene file's path::

    [camera]
    interpolation = "slerp"                  # or "spline" ("squad")
    position_interpolation = "linear"        # or "catmull-rom"
    fov_y = 45.0                             # the lens, where a key gives none

    [[camera.keyframe]]
    time = 0.0
    eye = [0.0, 1.0, 5.0]
    target = [0.0, 0.0, 0.0]

    [[camera.keyframe]]
    time = 2.0
    position = [5.0, 1.0, 0.0]
    orientation = [0.0, 0.7071068, 0.0, 0.7071068]   # [x, y, z, w]
    fov_y = 35.0

(Top-level ``[[keyframe]]`` tables, the earlier form, are read too.)
"""

from __future__ import annotations

import enum
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import OptionError, PathFormatError, SceneError
from ..modes import parse_enum
from .. import quaternion as quat
from ..atomic import atomic_write
from .camera import Camera

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["Keyframe", "CameraPath", "OrientationInterp", "PositionInterp"]


class OrientationInterp(str, enum.Enum):
    """How orientations go between key frames."""

    SLERP = "slerp"    # constant angular speed within a segment (a kink at the keys)
    SPLINE = "spline"  # C1 through the keys (Shoemake's squad; "squad" is accepted)

    @classmethod
    def parse(cls, value: object) -> OrientationInterp:
        """An OrientationInterp or its name; a bad name lists the choices.

        Parameters
        ----------
        value : OrientationInterp or str
            A member or its name.
        """
        if value == "squad":  # (Shoemake's name for the same curve)
            return cls.SPLINE
        try:
            return parse_enum(cls, value, "orientation interpolation")
        except OptionError:
            raise OptionError(f"unknown orientation interpolation {value!r}; choose one of "
                              "slerp, spline (or squad, the spline's other name)") from None


class PositionInterp(str, enum.Enum):
    """How positions go between key frames."""

    LINEAR = "linear"
    CATMULL_ROM = "catmull-rom"  # C1 through the keys

    @classmethod
    def parse(cls, value: object) -> PositionInterp:
        """A PositionInterp or its name; a bad name lists the choices.

        Parameters
        ----------
        value : PositionInterp or str
            A member or its name.
        """
        return parse_enum(cls, value, "position interpolation")


ORIENTATION_INTERP = tuple(m.value for m in OrientationInterp)
POSITION_INTERP = tuple(m.value for m in PositionInterp)


@dataclass(frozen=True)
class Keyframe:
    """One key: a time (seconds), a camera position and orientation, optionally a fov.

    Parameters
    ----------
    time : float
        Seconds from the path's start.
    position : ndarray
        ``(3,)`` the camera's position (world).
    orientation : ndarray
        ``(4,)`` a unit quaternion ``(x, y, z, w)``, camera to world.
    fov_y : float or None
        The vertical field of view in degrees (None: the path's).
    """

    time: float
    position: NDArray[np.float64]
    orientation: NDArray[np.float64]
    fov_y: float | None = None

    @classmethod
    def look_at(cls, time: float, eye, target, up=(0, 1, 0), fov_y=None) -> Keyframe:
        """A key at ``time`` with the camera at ``eye`` looking at ``target``.

        Parameters
        ----------
        time : float
            Seconds from the path's start.
        eye : array_like
            ``(3,)`` the camera's position (world).
        target : array_like
            ``(3,)`` the point it looks at.
        up : array_like
            ``(3,)`` roughly up.
        fov_y : float or None
            The vertical field of view in degrees (None: the path's).
        """
        cam = Camera.look_at(eye, target, up)
        return cls(float(time), cam.position, cam.orientation, fov_y)


class CameraPath:
    """Cameras along key frames.

    Parameters
    ----------
    keyframes : sequence of Keyframe, times strictly increasing.
    orientation_interp : "slerp" (default; constant angular speed within a segment, a kink
        in angular velocity at the keys) or "spline" (C1 through the keys; "squad" is an
        alias).
    position_interp : "linear" (default) or "catmull-rom" (C1 through the keys).
    camera : a Camera whose lens settings (fov_y, near, far, projection) the path uses
        where a key does not give its own fov.
    """

    def __init__(self, keyframes, *,
                 orientation_interp: OrientationInterp | str = OrientationInterp.SLERP,
                 position_interp: PositionInterp | str = PositionInterp.LINEAR,
                 camera: Camera | None = None):
        keys = list(keyframes)
        if not keys:
            raise SceneError("a camera path needs at least one key frame")
        orientation = OrientationInterp.parse(orientation_interp)
        position = PositionInterp.parse(position_interp)
        self.keyframes = keys
        self.times = np.array([k.time for k in keys], dtype=np.float64)
        steps = np.diff(self.times)
        if (steps <= 0).any():
            i = int(np.flatnonzero(steps <= 0)[0])
            raise SceneError(f"key frame times must increase: key {i + 2} has time "
                                f"{self.times[i + 1]:g} after {self.times[i]:g} (keys count "
                                "from 1)")
        self.positions = np.stack([np.asarray(k.position, np.float64) for k in keys])
        # same hemisphere for consecutive keys, so every segment takes the shorter arc
        self.orientations = quat.same_hemisphere(
            quat.normalize(np.stack([np.asarray(k.orientation, np.float64) for k in keys])))
        base = camera or Camera()
        self.fovs = np.array([base.fov_y if k.fov_y is None else k.fov_y for k in keys])
        self.camera = base
        self.orientation_interp = orientation
        self.position_interp = position

    @classmethod
    def turntable(cls, camera: Camera, center, duration: float = 4.0, degrees: float = 360.0,
                  up=(0.0, 1.0, 0.0)) -> CameraPath:
        """``camera`` carried ``degrees`` round the axis ``up`` through ``center`` in
        ``duration`` seconds, at constant speed: keys every 5 degrees at most, orientations by
        slerp (exact for a turn about one axis), positions along the chords (within 0.1% of
        the circle).

        Parameters
        ----------
        camera : Camera
            The camera at the start.
        center : array_like
            ``(3,)`` a point on the axis (world).
        duration : float
            Seconds the turn takes.
        degrees : float
            The angle turned.
        up : array_like
            ``(3,)`` the axis' direction.
        """
        if not duration > 0:
            raise SceneError(f"a turntable needs a duration > 0, got {duration}")
        n = max(1, int(np.ceil(abs(degrees) / 5.0)))
        turns = quat.from_axis_angle(up, np.radians(degrees) * np.arange(n + 1) / n)
        keys = []
        for i, q in enumerate(turns):
            cam = camera.orbit(q, center)
            keys.append(Keyframe(duration * i / n, cam.position, cam.orientation))
        return cls(keys, camera=camera)

    @property
    def start(self) -> float:
        return float(self.times[0])

    @property
    def end(self) -> float:
        return float(self.times[-1])

    def __repr__(self) -> str:
        return (f"<CameraPath: {len(self.keyframes)} keys over {self.duration:g} s, "
                f"{self.orientation_interp.value} / {self.position_interp.value}>")

    def _repr_html_(self) -> str:
        """In a notebook: the eye's track seen from above (x right, z down) and the keys."""
        from ..display import facts_html

        eyes = np.array([c.position for c in self.sample(200)])
        keys = np.array([k.position for k in self.keyframes])
        image = np.full((160, 160, 3), 255, np.uint8)
        lo, hi = eyes[:, [0, 2]].min(0), eyes[:, [0, 2]].max(0)
        scale = 140 / max(float((hi - lo).max()), 1e-12)
        for pts, colour, r in ((eyes, (60, 90, 200), 0), (keys, (220, 60, 40), 2)):
            xy = np.round((pts[:, [0, 2]] - lo) * scale + 10).astype(int)
            for dx in range(-r, r + 1):
                for dy in range(-r, r + 1):  # (a few offsets: a dot of radius r)
                    image[np.clip(xy[:, 1] + dy, 0, 159), np.clip(xy[:, 0] + dx, 0, 159)] = \
                        colour
        facts = [f"key {i + 1} at {k.time:g} s: eye "
                 f"({', '.join(f'{x:.3g}' for x in k.position)})"
                 for i, k in enumerate(self.keyframes[:8])]
        return facts_html(repr(self), facts, image)

    @property
    def duration(self) -> float:
        return self.end - self.start

    def __len__(self) -> int:
        return len(self.keyframes)

    # ------------------------------------------------------------------ sampling
    def _segments(self, t):
        k = len(self.times)
        seg = np.clip(np.searchsorted(self.times, t, side="right") - 1, 0, max(k - 2, 0))
        if k == 1:
            return seg, np.zeros_like(t)
        h = self.times[seg + 1] - self.times[seg]
        return seg, np.clip((t - self.times[seg]) / h, 0.0, 1.0)

    def evaluate(self, t: ArrayLike) -> tuple[NDArray, NDArray, NDArray]:
        """Positions ``(..., 3)``, orientations ``(..., 4)`` and fovs ``(...)`` at times ``t``
        (clamped to the path), all at once.

        Parameters
        ----------
        t : array_like
            Times in seconds, any shape.
        """
        t = np.asarray(t, dtype=np.float64)
        if len(self.times) == 1:
            shape = t.shape
            return (np.broadcast_to(self.positions[0], shape + (3,)).copy(),
                    np.broadcast_to(self.orientations[0], shape + (4,)).copy(),
                    np.full(shape, self.fovs[0]))
        seg, u = self._segments(t)
        if self.orientation_interp is OrientationInterp.SLERP:
            q = quat.slerp(self.orientations[seg], self.orientations[seg + 1], u)
        else:
            q = quat.spline(self.times, self.orientations, t)
        p0, p1 = self.positions[seg], self.positions[seg + 1]
        if self.position_interp is PositionInterp.LINEAR:
            pos = p0 + u[..., None] * (p1 - p0)
        else:
            pos = self._catmull_rom(seg, u)
        fov = self.fovs[seg] + u * (self.fovs[seg + 1] - self.fovs[seg])
        return pos, q, fov

    def _catmull_rom(self, seg, u):
        """Cubic Hermite with tangents from neighbouring keys, weighted for uneven times."""
        p, t = self.positions, self.times
        k = len(t)
        tangent = np.zeros_like(p)
        d = np.diff(p, axis=0) / np.diff(t)[:, None]  # segment velocities
        tangent[0], tangent[-1] = d[0], d[-1]
        if k > 2:
            h = np.diff(t)
            tangent[1:-1] = (h[1:, None] * d[:-1] + h[:-1, None] * d[1:]) / \
                (h[:-1] + h[1:])[:, None]
        h = (t[seg + 1] - t[seg])[..., None]
        u = u[..., None]
        h00, h10 = 2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u
        h01, h11 = -2 * u**3 + 3 * u**2, u**3 - u**2
        return (h00 * p[seg] + h10 * h * tangent[seg] + h01 * p[seg + 1]
                + h11 * h * tangent[seg + 1])

    def at(self, t: float) -> Camera:
        """The camera at time ``t`` (clamped to the path's time range).

        Parameters
        ----------
        t : float
            The time in seconds.
        """
        pos, q, fov = self.evaluate(float(t))
        return self.camera.replace(position=pos, orientation=q, fov_y=float(fov))

    def frame_times(self, n: int) -> NDArray[np.float64]:
        """``n`` evenly spaced times from the first key to the last, both included.

        Parameters
        ----------
        n : int
            The number of frames, >= 1.
        """
        if n < 1:
            raise SceneError(f"need at least one frame, got {n}")
        return np.linspace(self.start, self.end, n) if n > 1 else np.array([self.start])

    def sample(self, n: int) -> list[Camera]:
        """Cameras of ``n`` evenly spaced frames (interpolation done in one vectorized pass).

        Parameters
        ----------
        n : int
            The number of frames, >= 1.
        """
        pos, q, fov = self.evaluate(self.frame_times(n))
        return [self.camera.replace(position=p, orientation=o, fov_y=float(f))
                for p, o, f in zip(pos, q, fov)]

    # ------------------------------------------------------------------ TOML
    @classmethod
    def from_dict(cls, data: dict, source: str = "<dict>", **kwargs) -> CameraPath:
        """Build from parsed TOML: a scene file's ``{"camera": {"keyframe": [...],
        "interpolation": ..., "fov_y": ...}}`` or ``{"keyframe": [{time, eye, target |
        position, orientation, fov_y, up}, ...]}``.

        Parameters
        ----------
        data : dict
            The parsed TOML.
        source : str
            What the data came from, for messages (a file's path).
        **kwargs
            Path settings that the data does not give (``interpolation`` ...).
        """
        camera = data.get("camera")
        if "keyframe" not in data and isinstance(camera, dict):
            data = camera
            kwargs.setdefault("orientation_interp", camera.get("interpolation", "slerp"))
            kwargs.setdefault("position_interp",
                              camera.get("position_interpolation", "linear"))
            lens = {k: camera[k] for k in ("fov_y", "near", "far") if k in camera}
            if lens and "camera" not in kwargs:
                try:
                    kwargs["camera"] = Camera(**lens)
                except SceneError as exc:
                    raise PathFormatError(f"{source}: [camera]: {exc}") from None
        entries = data.get("keyframe")
        if not isinstance(entries, list) or not entries:
            raise PathFormatError(f"{source}: no [[camera.keyframe]] tables")
        allowed = {"time", "eye", "target", "up", "position", "orientation", "fov_y"}
        keys: list[Keyframe] = []
        for i, e in enumerate(entries, start=1):
            unknown = set(e) - allowed
            if unknown:
                raise PathFormatError.at(source, i, f"unknown key(s) {sorted(unknown)}; "
                                         f"allowed: {sorted(allowed)}")
            if "time" not in e or not isinstance(e["time"], (int, float)) or \
                    isinstance(e["time"], bool) or not np.isfinite(e["time"]):
                raise PathFormatError.at(source, i, "'time' must be a finite number")
            if keys and e["time"] <= keys[-1].time:
                raise PathFormatError.at(source, i, f"key frame times must increase, got "
                                         f"{e['time']:g} after {keys[-1].time:g}")
            fov = e.get("fov_y")
            if fov is not None and not isinstance(fov, (int, float)):
                raise PathFormatError.at(source, i, "'fov_y' must be a number")
            try:
                if "eye" in e or "target" in e:
                    if "eye" not in e or "target" not in e:
                        raise PathFormatError.at(source, i, "give both 'eye' and 'target'")
                    keys.append(Keyframe.look_at(e["time"], e["eye"], e["target"],
                                                 e.get("up", (0, 1, 0)), fov))
                elif "position" in e and "orientation" in e:
                    q = np.asarray(e["orientation"], dtype=np.float64)
                    if q.shape != (4,) or np.linalg.norm(q) == 0:
                        raise PathFormatError.at(source, i, "'orientation' must be a "
                                                 "non-zero [x, y, z, w]")
                    pos = np.asarray(e["position"], dtype=np.float64)
                    if pos.shape != (3,):
                        raise PathFormatError.at(source, i, "'position' must be [x, y, z]")
                    keys.append(Keyframe(float(e["time"]), pos, quat.normalize(q), fov))
                else:
                    raise PathFormatError.at(source, i, "give 'eye' and 'target', or "
                                             "'position' and 'orientation'")
            except (SceneError, ValueError, TypeError) as exc:
                if isinstance(exc, PathFormatError):
                    raise
                raise PathFormatError.at(source, i, str(exc)) from None
        try:
            return cls(keys, **kwargs)
        except SceneError as exc:
            raise PathFormatError(f"{source}: {exc}") from None

    @classmethod
    def load(cls, path, **kwargs) -> CameraPath:
        """Read a TOML key-frame file (see the module docstring).

        Parameters
        ----------
        path : str or Path
            The TOML file.
        **kwargs
            As :meth:`from_dict`.
        """
        path = Path(path)
        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
        except FileNotFoundError:
            raise PathFormatError(f"{path}: no such file") from None
        except tomllib.TOMLDecodeError as exc:
            raise PathFormatError(f"{path}: {exc}") from None
        return cls.from_dict(data, str(path), **kwargs)

    def to_toml(self) -> str:
        def arr(a):
            return "[" + ", ".join(repr(float(x)) for x in a) + "]"

        out = [f"# camera path: {len(self)} key frames, {self.duration:g} s\n",
               f"[camera]\ninterpolation = \"{self.orientation_interp.value}\"\n"
               f"position_interpolation = \"{self.position_interp.value}\"\n"
               f"fov_y = {float(self.camera.fov_y)!r}\n\n"]
        for k, p, q in zip(self.keyframes, self.positions, self.orientations):
            out.append(f"[[camera.keyframe]]\ntime = {float(k.time)!r}\nposition = {arr(p)}\n"
                       f"orientation = {arr(q)}\n")
            if k.fov_y is not None:
                out.append(f"fov_y = {float(k.fov_y)!r}\n")
            out.append("\n")
        return "".join(out)

    def save(self, path) -> None:
        """Write the path as TOML (atomically).

        Parameters
        ----------
        path : str or Path
            Where to write.
        """
        with atomic_write(path, "w") as f:
            f.write(self.to_toml())
