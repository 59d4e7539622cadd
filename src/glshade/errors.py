"""Every exception glshade raises on purpose, in one hierarchy.

Every message says what was expected, what arrived and, where there is one, the fix. Two
families decide the command line's exit status (:func:`exit_status`):

* :class:`InputError` (also a ``ValueError``): something the user gave is wrong -- an
  argument, a mesh or scene file, a value handed to the API. Exit status 2.
* :class:`EnvironmentFailure` (also a ``RuntimeError``): the machine cannot do it -- no GL
  context, a shader the driver refuses, a missing optional package. Exit status 1.

Errors carry their facts as attributes (file, line, key frame ...), so no caller has to
recover them by parsing another error's message.
"""

from __future__ import annotations

from typing import Any

__all__ = [
    "GlshadeError", "InputError", "EnvironmentFailure", "NoGpuError",
    "GeometryError", "OptionError", "SceneError", "TopologyError", "MeshFormatError",
    "SceneFormatError", "PathFormatError",
    "OutputError", "UsageError", "SettingError", "ComparisonError", "DisplayError",
    "ContextError", "ShaderError", "VideoUnavailable", "OutputWriteError", "ClusterError",
    "DepthSortCycle",
    "RenderWarning", "warn_user", "plain", "exit_status", "EXIT_OK", "EXIT_ENVIRONMENT",
    "EXIT_USAGE",
]

EXIT_OK, EXIT_ENVIRONMENT, EXIT_USAGE = 0, 1, 2


class GlshadeError(Exception):
    """Base class of every error glshade raises on purpose. One made by :meth:`must`
    carries its ``subject`` and ``rule``, so a caller can restate the rule for its own
    subject (a scene file's key) without parsing the message."""

    exit_status = EXIT_ENVIRONMENT
    subject: str | None = None
    rule: str | None = None

    @classmethod
    def must(cls, subject: str, rule: str):
        """``"{subject} must {rule}"``, with both kept as attributes.

        Parameters
        ----------
        subject : str
            What the rule is about (an option's or a key's name).
        rule : str
            What it must be, after "must" ("be a number > 0, got -1").
        """
        error = cls(f"{subject} must {rule}")
        error.subject, error.rule = subject, rule
        return error


class InputError(GlshadeError, ValueError):
    """Bad input from the user: arguments, files, values (exit status 2)."""

    exit_status = EXIT_USAGE


class EnvironmentFailure(GlshadeError, RuntimeError):
    """The environment cannot do what was asked: GL, drivers, optional packages (exit 1)."""

    exit_status = EXIT_ENVIRONMENT


# ------------------------------------------------------------------ input errors

class GeometryError(InputError):
    """Bad shapes or values of geometry: vertices, faces, polygons, solids, quaternions,
    transforms. (Options are :class:`OptionError`; scene values :class:`SceneError`.)"""


class OptionError(InputError):
    """A bad option or argument value: a shading mode, a backend's name, an image size, a
    sample count, a dtype. Names the option, what arrived and the valid choices."""


class SceneError(InputError):
    """A scene value that cannot be drawn: a camera (eye at its target, a field of view
    out of range), a light, a material, a key-frame path, a model's transform."""


class TopologyError(GeometryError):
    """Invalid topology (non-manifold edges, inconsistent orientation, ...)."""


class MeshFormatError(InputError):
    """A mesh file that cannot be read: names the path, the line (or byte) and the fault."""

    def __init__(self, path, message: str, line: int | None = None, byte: int | None = None):
        self.path = str(path)
        self.line = line
        self.byte = byte
        self.reason = message
        where = self.path
        if line is not None:
            where += f":{line}"
        elif byte is not None:
            where += f" (byte {byte})"
        super().__init__(f"{where}: {message}")

    def __reduce__(self):  # (crosses process boundaries from worker pools)
        return type(self), (self.path, self.reason, self.line, self.byte)


class DepthSortCycle(GeometryError):
    """Depth sort without splitting met polygons that overlap cyclically or pierce each
    other: names two of them."""


class SceneFormatError(InputError):
    """A scene file that cannot be used: names the file, the line and the key."""


class PathFormatError(SceneError):
    """A camera path that cannot be read. ``keyframe`` is the 1-based number of the key
    frame at fault (None when the fault is not in one), so a scene file can point at its
    line."""

    def __init__(self, message: str, keyframe: int | None = None, reason: str | None = None):
        self.keyframe = keyframe
        self.reason = reason if reason is not None else message
        super().__init__(message)

    def __reduce__(self):
        return type(self), (str(self), self.keyframe, self.reason)

    @classmethod
    def at(cls, source: str, keyframe: int, reason: str) -> PathFormatError:
        """The fault ``reason`` in key frame ``keyframe`` (1-based) of ``source``.

        Parameters
        ----------
        source : str
            The file (or ``"<dict>"``).
        keyframe : int
            The key frame, counted from 1.
        reason : str
            What is wrong with it.
        """
        return cls(f"{source}: keyframe {keyframe}: {reason}", keyframe, reason)


class OutputError(InputError):
    """An output name glshade cannot write (a bad extension, a non-empty folder)."""


class UsageError(InputError):
    """A combination of arguments that cannot work together."""


class SettingError(InputError):
    """A setting this machine cannot honour (MSAA samples, image size). ``setting`` names
    it, so a command can say where the value came from (a scene file's line)."""

    def __init__(self, setting: str, message: str):
        self.setting = setting
        super().__init__(message)

    def __reduce__(self):
        return type(self), (self.setting, str(self))


class ComparisonError(InputError):
    """A comparison that cannot be made: no analytic surface, a reference of another size."""


# ------------------------------------------------------------------ environment failures

class ContextError(EnvironmentFailure):
    """No OpenGL context could be made: says which backends were tried and why each failed."""


class NoGpuError(ContextError):
    """A GPU was required (``require_gpu=True``, ``--require-gpu``,
    ``GLSHADE_REQUIRE_GPU=1``) and the GL found is a software rasterizer: the message names
    it and the usual cause. Exit status 2, as a refused request: run as it is, the same
    command fails the same way until the machine changes."""

    exit_status = EXIT_USAGE


class DisplayError(EnvironmentFailure):
    """No display to open a window on: the machine lacks what the command needs (exit
    status 1), with the headless alternative in the message."""


class ShaderError(EnvironmentFailure):
    """A GLSL program failed to compile or link: names the file, the line and the driver's text."""


class OutputWriteError(EnvironmentFailure):
    """An output that could not be written (no permission, a full disk, a broken encoder):
    names the output asked for, never the temporary file it was going to."""

    def __init__(self, path, reason: str):
        self.path, self.reason = str(path), reason
        super().__init__(f"cannot write {self.path}: {reason}")

    def __reduce__(self):
        return type(self), (self.path, self.reason)


class VideoUnavailable(EnvironmentFailure):
    """MP4 output needs imageio-ffmpeg (the ``video`` extra), which ships ffmpeg."""


class ClusterError(EnvironmentFailure):
    """Work cannot go to a Dask cluster: the ``distributed`` extra is missing, or the
    scheduler cannot be reached. Says which, and the fix."""


class RenderWarning(UserWarning):
    """A render that worked but shows nothing (a blank image), with the reason when known."""


def plain(value, digits: int = 4) -> str:
    """Numbers as a person writes them in a message: ``1.4``, ``(1.4, 0.2, 0)``, ``nan``,
    ``1e+300`` -- Python's ``g`` format to ``digits`` significant digits, never numpy's
    reprs (``np.float64(1.4)``, ``array([...])``).

    Parameters
    ----------
    value
        A number, or a sequence or array of them (shown as a tuple).
    digits
        Significant digits.
    """
    import numpy as np

    a = np.asarray(value)
    if a.dtype.kind in "iub":
        items = [f"{int(x):,}" for x in a.ravel()]
    else:
        items = [f"{float(x):.{digits}g}" for x in a.astype(np.float64).ravel()]
    if a.ndim == 0:
        return items[0]
    return "(" + ", ".join(items) + ")"


def warn_user(message: str, category: type[Warning] = UserWarning) -> None:
    """Warn at the first caller outside glshade: the line of the user's code that asked for
    the work, however deep in a pipeline of passes the finding was made.

    Parameters
    ----------
    message : str
        The warning's one line.
    category : type
        The Warning class (UserWarning, RenderWarning ...).
    """
    import sys
    import warnings

    package = __name__.rsplit(".", 1)[0] + "."
    level = 2
    frame: Any = sys._getframe(1)
    while frame is not None and frame.f_globals.get("__name__", "").startswith(package):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level)


def exit_status(exc: BaseException) -> int:
    """The command line's exit status for an error: 2 for bad input, 1 for the environment
    (an ``OSError`` such as an unwritable output included).

    Parameters
    ----------
    exc : BaseException
        The error a command ended with.
    """
    if isinstance(exc, GlshadeError):
        return exc.exit_status
    return EXIT_ENVIRONMENT
