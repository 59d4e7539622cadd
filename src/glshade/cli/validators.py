"""Argument types for the command line: each converts one value's text or raises
``argparse.ArgumentTypeError`` with an example of what is expected. Where the library has a
rule for the value (sizes, MSAA samples, fields of view, the enums' choices), the text is
converted here and the rule is the library's own, with its message."""

from __future__ import annotations

import argparse
import math
import re

from ..errors import InputError, UsageError
from ..hidden import Algorithm
from ..modes import ShadingMode, Shadows, Transparency
from ..scene.camera import View

__all__ = ["size", "vec3", "count", "unit_float", "nonnegative_float", "mode", "modes",
           "levels", "samples", "fov", "degrees"]


def _rule(check, *values):
    """The library's rule for a value, its error as argparse's."""
    try:
        return check(*values)
    except InputError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def size(text: str) -> tuple[int, int]:
    """``WxH`` (e.g. 800x600) as (width, height) pixels."""
    from ..options import check_size

    m = re.fullmatch(r"\s*(\d+)\s*[xX]\s*(\d+)\s*", text)
    if not m:
        raise argparse.ArgumentTypeError(f"expected WIDTHxHEIGHT such as 800x600, got "
                                         f"{text!r}")
    return _rule(check_size, int(m.group(1)), int(m.group(2)))


def vec3(text: str) -> tuple[float, float, float]:
    """``x,y,z`` as three finite numbers."""
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != 3 or not all(map(math.isfinite, values)):
        raise argparse.ArgumentTypeError(f"expected three numbers x,y,z such as 1,2.5,-3, got "
                                         f"{text!r}")
    return values


def seed(text: str) -> int:
    if not text.strip().isdigit():
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0 such as 7, got "
                                         f"{text!r}")
    return int(text)


#: the largest count any option takes (a GL int; checked before any arithmetic)
MAX_COUNT = 2**31 - 1


def count(text: str) -> int:
    """A positive integer, at most MAX_COUNT."""
    if not text.strip().isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1 such as 4, got "
                                         f"{text!r}")
    if int(text) > MAX_COUNT:
        raise argparse.ArgumentTypeError(f"expected a whole number from 1 to {MAX_COUNT:,}, "
                                         f"got {text!r}")
    return int(text)


def _number(text: str, ok, expected: str) -> float:
    """``float(text)`` when ``ok`` holds for it, else an error quoting ``expected``."""
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if math.isinf(value):  # (1e400: a number, but not one glshade can compute with)
        raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}, which is not "
                                         "a finite number")
    if not (math.isfinite(value) and ok(value)):
        raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}")
    return value


def unit_float(text: str) -> float:
    """A number in [0, 1]."""
    return _number(text, lambda x: 0 <= x <= 1, "a number in [0, 1] such as 0.5")


def nonnegative_float(text: str) -> float:
    """A finite number >= 0."""
    return _number(text, lambda x: x >= 0, "a non-negative number such as 32")


def mode(text: str) -> ShadingMode:
    """A shading mode by name."""
    return _rule(ShadingMode.parse, text)


def compare_modes(text: str) -> list[str]:
    """A comma-separated list of compare's modes: shading modes, or schemes in glTF's
    model (``pbr-phong``)."""
    from ..compare.comparison import compare_mode
    from ..errors import ComparisonError

    names = [t.strip() for t in text.split(",") if t.strip()] or [""]
    try:
        return [compare_mode(t)[0] for t in names]
    except (ComparisonError, ValueError) as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def levels(text: str) -> list[int]:
    """``a..b`` or ``a,b,c`` as a list of tessellation levels (each sweep checks its own
    range: sphere subdivisions 0 to 8, patch tessellations 1 to 512)."""
    from ..patches.tessellation import MAX_LEVEL

    m = re.fullmatch(r"\s*(\d+)\s*\.\.\s*(\d+)\s*", text)
    if m and int(m.group(1)) <= int(m.group(2)) <= MAX_LEVEL:
        return list(range(int(m.group(1)), int(m.group(2)) + 1))
    try:
        values = [int(v) for v in text.split(",")]
    except ValueError:
        values = []
    if not values or min(values) < 0 or max(values) > MAX_LEVEL:
        raise argparse.ArgumentTypeError(f"expected levels such as 0..6 or 1,3,5 (0 to "
                                         f"{MAX_LEVEL}), got {text!r}")
    return values


def modes(text: str) -> list[ShadingMode]:
    """A comma-separated list of shading modes."""
    return [mode(t.strip()) for t in text.split(",") if t.strip()] or \
        [mode("")]  # an empty list reports the choices


def samples(text: str) -> int:
    """MSAA samples: 0 (off) or a power of two."""
    from ..options import check_samples

    if not text.strip().isdigit():
        raise argparse.ArgumentTypeError(f"expected a whole number of MSAA samples (0 or a "
                                         f"power of two such as 4), got {text!r}")
    return _rule(check_samples, int(text))


def fov(text: str) -> float:
    """A vertical field of view in degrees, from MIN_FOV_Y to under 180."""
    from ..scene.camera import check_fov

    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected degrees under 180 such as 45, got "
                                         f"{text!r}") from None
    return _rule(check_fov, value, "the field of view")


def radiosity_method(text: str):
    """A radiosity solver: a :class:`glshade.radiosity.Method` (an enum past the parser)."""
    from ..radiosity import Method

    return _rule(Method.parse, text)


#: --view's names: glshade.View's
VIEW_CHOICES = tuple(v.value for v in View)


def view(text: str) -> View:
    """A named view (front, back, left, right, top, bottom, iso): a :class:`View`."""
    return _rule(View.parse, text)


#: --algorithms of glshade hidden: the lab's, and the GPU's z-buffer as a reference
ALGORITHM_CHOICES = (*(a.value for a in Algorithm), "gpu")


def algorithms(text: str) -> list[str]:
    names = [t.strip() for t in text.split(",") if t.strip()]
    bad = [n for n in names if n not in ALGORITHM_CHOICES]
    if bad or not names:
        raise argparse.ArgumentTypeError(f"unknown algorithm {', '.join(bad) or '(none)'}; "
                                         f"choose from {', '.join(ALGORITHM_CHOICES)}")
    return names


def degrees(text: str) -> float:
    """An angle in degrees, in [0, 180]."""
    return _number(text, lambda x: 0 <= x <= 180, "an angle from 0 to 180 such as 30")


def outputs(text: str):
    """``color,depth,normal,face_id`` -> an Outputs flag (colour always included)."""
    from ..modes import Outputs

    names = {"color": Outputs.COLOR, "depth": Outputs.DEPTH, "normal": Outputs.NORMAL,
             "face_id": Outputs.FACE_ID, "id": Outputs.FACE_ID}
    flag = Outputs.COLOR
    for t in (t.strip().lower() for t in text.split(",")):
        if t not in names:
            raise argparse.ArgumentTypeError(f"unknown output {t!r}; choose from "
                                             "color, depth, normal, face_id")
        flag |= names[t]
    return flag


def scheduler(text: str) -> str:
    text = text.strip()
    if text != "local" and not (("://" in text) and text.rsplit(":", 1)[-1].isdigit()):
        raise argparse.ArgumentTypeError(f"expected a Dask scheduler address such as "
                                         f"tcp://10.0.0.5:8786, or 'local', got {text!r}")
    return text


def positive_float(text: str) -> float:
    """A finite number > 0."""
    return _number(text, lambda x: x > 0, "a number > 0")


def _methods(kind, example: str):
    """An argument type: one of ``kind``'s values, or several comma-separated (compare's)."""
    def parse(text: str) -> tuple:
        names = [t.strip().lower() for t in text.split(",")]
        known = [m.value for m in kind]
        if any(n not in known for n in names) or len(set(names)) != len(names):
            raise argparse.ArgumentTypeError(f"expected {', '.join(known)} (or several for "
                                             f"compare, e.g. {example}), got {text!r}")
        return tuple(kind(n) for n in names)

    return parse


#: --shadows: exact, map, off (several: compare's)
shadows = _methods(Shadows, "exact,map")
#: --transparency: exact, weighted, blend (several: compare's)
transparency = _methods(Transparency, "exact,weighted")


def texture_filter(text: str) -> str:
    """--texture-filter: nearest, linear or mipmap."""
    from ..scene.texture import FILTERS

    name = text.strip().lower()
    if name not in FILTERS:
        raise argparse.ArgumentTypeError(f"expected one of {', '.join(FILTERS)}, got {text!r}")
    return name


def fps(text: str) -> float:
    """Frames a second, in the range an animation file can hold."""
    from ..animate.writers import MAX_FPS, MIN_FPS

    return _number(text, lambda x: MIN_FPS <= x <= MAX_FPS,
                   f"frames a second from {MIN_FPS:g} to {MAX_FPS:g}")


def fraction(text: str) -> float:
    return _number(text, lambda x: 0 <= x < 1, "a fraction in [0, 1), such as 0.01")


def hemicube(text: str) -> int:
    if not text.strip().isdigit() or int(text) < 4 or int(text) % 2:
        raise argparse.ArgumentTypeError(f"expected an even whole number >= 4 (pixels a side "
                                         f"of the hemicube's top face), got {text!r}")
    return int(text)


def image_output(text: str) -> str:
    """An image file to write: its extension must be an image's (checked before any work)."""
    from ..errors import InputError
    from ..io.images import image_format

    if not text.strip():
        raise argparse.ArgumentTypeError("an empty file name")
    try:
        image_format(text)
    except InputError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return text


def check_outputs(files: dict, folders: dict | None = None) -> None:
    """Every output a run will write, checked before any work (so a typo does not cost the
    run, and nothing is left half done): ``files`` and ``folders`` map each option's name to
    its path (None: not asked for). All distinct; a file's folder must exist and the file
    must not be a folder; an output folder may exist (as a folder) or be made in a folder
    that exists."""
    import os

    for name, p in {**files, **(folders or {})}.items():
        if p is not None and not str(p).strip():
            raise UsageError(f"{name}: an empty file name")
    named = {k: v for k, v in {**files, **(folders or {})}.items() if v}
    paths = [os.path.abspath(str(v).rstrip("/")) for v in named.values()]
    if len(set(paths)) != len(paths):
        raise UsageError(f"{', '.join(named)} must be different files, got "
                         f"{', '.join(str(v) for v in named.values())}")
    for name, p in named.items():
        full = os.path.abspath(str(p).rstrip("/"))
        parent = os.path.dirname(full)
        if not os.path.isdir(parent):
            raise UsageError(f"{p}: the folder {parent} does not exist")
        if name in (folders or {}) and os.path.exists(full) and not os.path.isdir(full):
            raise UsageError(f"{p} ({name}): is a file, not a folder")
        if name in files and os.path.isdir(full):
            raise UsageError(f"{p} ({name}): is a folder, not a file")
