"""What each subcommand was given, as one typed, frozen value made at the edge.

The parser (:mod:`.parser`) names, for each subcommand, its command function and its
arguments' class; ``main`` turns argparse's ``Namespace`` into that class once
(:func:`from_namespace`), so no command reads a ``Namespace`` or asks ``getattr`` whether
an option exists: a value it was not given is the dataclass's default (None: "not given",
decided where the value is used -- the scene file, then the library's dataclasses).
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any, TypeVar

from ..modes import Backend, Outputs, ShadingMode
from ..options import HEMICUBE_RESOLUTION
from ..radiosity import Method
from ..scene.camera import View

__all__ = ["RenderArgs", "InfoArgs", "RenderCommandArgs", "AnimateArgs", "CompareArgs",
           "BatchArgs", "RadiosityArgs", "HiddenArgs", "ViewArgs", "DoctorArgs", "DatasetArgs",
           "from_namespace"]

Vec3 = tuple[float, float, float]


@dataclass(frozen=True, kw_only=True)
class RenderArgs:
    """The options every drawing command shares (render, view, compare, batch, animate,
    hidden, radiosity): None where the command line did not give one."""

    size: tuple[int, int] | None = None
    samples: int | None = None
    eye: Vec3 | None = None
    target: Vec3 | None = None
    fov: float | None = None
    light: tuple[Vec3, ...] = ()
    color: Vec3 | None = None
    background: Vec3 | None = None
    ka: float | None = None
    kd: float | None = None
    ks: float | None = None
    shininess: float | None = None
    opacity: float | None = None
    texture_filter: str | None = None
    transparency: tuple | None = None  # (Transparency members; several only for compare)
    crease: float | None = None
    tolerance: float | None = None
    backend: Backend = Backend.AUTO
    srgb: bool | None = None
    mode: ShadingMode | None = None
    time: float | None = None
    view: View | None = None
    ortho: bool = False
    edges: bool | None = None
    shadows: tuple | None = None  # (Shadows members; several only for compare)

    def given(self, *names: str) -> dict[str, Any]:
        """The named options that were given (not None), by name."""
        return {n: getattr(self, n) for n in names if getattr(self, n) is not None}


@dataclass(frozen=True, kw_only=True)
class InfoArgs:
    mesh: str
    json: bool = False
    tolerance: float | None = None


@dataclass(frozen=True, kw_only=True)
class RenderCommandArgs(RenderArgs):
    mesh: str
    output: str
    quiet: bool = False


@dataclass(frozen=True, kw_only=True)
class ExecutorArgs:
    """Where repeated work runs: local processes (``jobs``) or a Dask cluster."""

    jobs: int | None = None
    scheduler: str | None = None


@dataclass(frozen=True, kw_only=True)
class AnimateArgs(RenderArgs, ExecutorArgs):
    scene: str
    output: str
    fps: float | None = None
    duration: float | None = None
    frames: int | None = None
    modes: tuple[ShadingMode, ...] | None = None
    quiet: bool = False


@dataclass(frozen=True, kw_only=True)
class CompareArgs(RenderArgs, ExecutorArgs):
    mesh: str
    output: str
    modes: tuple[str, ...] = ()  # (shading modes, and schemes in glTF's model: pbr-phong)
    diff: bool = True
    reference: str = "auto"
    spp: int = 64
    scale: float | None = None
    save_tiles: str | None = None
    json: str | None = None
    csv: str | None = None
    sweep: bool = False
    levels: tuple[int, ...] | None = None  # (None: the sweep's own default)
    patch_size: float | None = None  # (the radiosity mode's patches)


@dataclass(frozen=True, kw_only=True)
class BatchArgs(RenderArgs, ExecutorArgs):
    inputs: tuple[str, ...]
    output: str
    modes: tuple[ShadingMode, ...] = (ShadingMode.PHONG,)
    outputs: Outputs = Outputs.COLOR
    views: int = 1
    overwrite: bool = False
    quiet: bool = False


@dataclass(frozen=True, kw_only=True)
class RadiosityArgs(RenderArgs):
    scene: str
    output: str
    patch_size: float | None = None
    hemicube: int = HEMICUBE_RESOLUTION
    method: Method = Method.PROGRESSIVE
    particles: int = 200_000
    until: float = 0.01
    iterations: int | None = None
    steps: str | None = None
    plot: str | None = None
    exposure: float | None = None
    no_ambient: bool = False
    seed: int = 0
    quiet: bool = False


@dataclass(frozen=True, kw_only=True)
class PathtraceArgs(RenderArgs):
    scene: str
    output: str
    spp: int | None = None
    until: float | None = None
    seed: int = 0
    max_depth: int | None = None
    exposure: float | None = None
    no_lights: bool = False
    sampler: str = "pcg"
    kernel: str = "auto"
    streams: int | None = None
    coherent: bool = False
    control: bool = False
    adaptive: bool = False
    no_mis: bool = False
    quiet: bool = False


@dataclass(frozen=True, kw_only=True)
class HiddenArgs(RenderArgs):
    mesh: str
    output: str
    algorithms: tuple[str, ...] = ()
    steps: str | None = None


@dataclass(frozen=True, kw_only=True)
class ViewArgs(RenderArgs):
    mesh: str
    compare: bool = False
    screenshot: str | None = None
    frames: int | None = None
    hidden: bool = False
    pick: bool = False


@dataclass(frozen=True, kw_only=True)
class DatasetArgs(ExecutorArgs):
    scene: str
    output: str
    views: int = 1
    format: str = "bop"
    size: tuple[int, int] | None = None
    samples: int | None = None
    images: str = "raster"
    spp: int | None = None
    until: float | None = None
    depth_scale: float = 1.0
    units: str = "m"
    backend: Backend = Backend.AUTO
    device: str | None = None
    quiet: bool = False


@dataclass(frozen=True, kw_only=True)
class DoctorArgs:
    backend: Backend = Backend.AUTO


A = TypeVar("A")


def from_namespace(cls: type[A], namespace: object) -> A:
    """``cls`` from the parsed arguments: each field the parser gave (lists as tuples), the
    default for the others."""
    values = {}
    for f in fields(cls):  # type: ignore[arg-type]
        if hasattr(namespace, f.name):
            value = getattr(namespace, f.name)
            values[f.name] = tuple(value) if isinstance(value, list) else value
    if values.get("light") is None and "light" in values:
        values["light"] = ()
    if "backend" in values:
        values["backend"] = Backend.parse(values["backend"])
    return cls(**values)
