"""The front door's docstrings say what each parameter is: every function, class and
public method reached from ``glshade``'s own names, ``glshade.pathtrace``'s and those of
the modules documented whole (the quaternion algebra, data sets, modes, options, errors,
atomic writes, mass-points, colour maps, examples; glshade.scene's, the mesh kernel's,
the files', the renderer's, CSG solids', the winged-edge B-Rep's, Bezier patches' and
the octree's, and the comparisons' and radiosity's) has a
numpydoc ``Parameters`` section naming each of its parameters, and no other (the docs
build renders them)."""

import enum
import inspect
import re
import types

import pytest

import glshade
from glshade import (atomic, colormaps, dataset, errors, examples, masspoint, modes,
                     options, pathtrace, quaternion)
from glshade import octree
from glshade.brep import winged_edge
from glshade.compare import methods, metrics
from glshade.cpu import lighting, raycast
from glshade.geometry import transforms
from glshade.hidden import raster
from glshade.io import text
from glshade.patches import quadrics
from glshade.radiosity import formfactors, patches, problem, solvers
from glshade.geometry import merge, mesh, polygon, primitives
from glshade.patches import bezier
from glshade.solids import leaves, tree
from glshade.io import images, meshes, scenefile
from glshade.render import (annotate, context, gpu_mesh, passes, programs, renderer, shaders,
                            state, target)
from glshade.render.passes import gbuffer
from glshade.render.passes import mesh as mesh_pass
from glshade.render.passes import patches as patch_pass
from glshade.scene import camera, intrinsics, keyframes, lights, material, occluders, texture
from glshade.scene import scene as scene_module

#: the chapters' modules documented whole so far
SCENE = (camera, intrinsics, keyframes, lights, material, occluders, texture, scene_module,
         merge, mesh, polygon, primitives, images, meshes, scenefile, annotate, context,
         renderer, tree, leaves, winged_edge, bezier, octree, metrics, methods, solvers,
         formfactors, patches, problem, lighting, raycast, transforms, raster, text,
         quadrics, target, programs, gpu_mesh, state, shaders, passes, gbuffer, mesh_pass,
         patch_pass)

FRONT = [(n, getattr(glshade, n)) for n in glshade.__all__
         if not n.startswith("__") and not isinstance(getattr(glshade, n), types.ModuleType)]
FRONT += [(f"pathtrace.{n}", getattr(pathtrace, n)) for n in pathtrace.__all__]
#: and the modules documented whole so far: the notes' algebra, the data sets
FRONT += [(f"{m.__name__}.{n}", getattr(m, n))
          for m in (quaternion, dataset, modes, options, errors, atomic, masspoint,
                    colormaps, examples, *SCENE)
          for n in m.__all__ if getattr(getattr(m, n), "__module__", m.__name__) == m.__name__]


def _callables():
    for name, obj in FRONT:
        if inspect.isclass(obj) and issubclass(obj, BaseException):
            continue  # (an error's one parameter is its message)
        if inspect.isfunction(obj):
            yield name, obj
        elif inspect.isclass(obj):
            if not issubclass(obj, enum.Enum):
                yield name, obj
            for key, value in vars(obj).items():
                if key.startswith("_"):
                    continue
                if isinstance(value, (classmethod, staticmethod)):
                    value = value.__func__
                if inspect.isfunction(value):
                    yield f"{name}.{key}", value


def documented(doc: str) -> set:
    """The names a numpydoc Parameters section lists (``a, b : type`` lines, ``**kw``)."""
    found = re.search(r"^(?:Parameters|Attributes)\n-+\n(.*?)(?:\n\n[A-Z][A-Za-z ]+\n-+\n|\Z)",
                      doc, re.S | re.M)  # (a dataclass may list its fields as Attributes)
    if found is None:
        return set()
    names = set()
    entry = re.compile(r"^(\*{0,2}\w+(?:, \*{0,2}\w+)*)(?: : .*)?$")
    for line in found.group(1).splitlines():
        match = entry.match(line)
        if match:
            names.update(part.strip().lstrip("*") for part in match.group(1).split(","))
    return names


def test_the_section_reader():
    doc = ("Say.\n\nParameters\n----------\nx, y : float\n    The point.\n**changes\n"
           "    More.\n\nReturns\n-------\nfloat\n    Not a parameter.\n")
    assert documented(doc) == {"x", "y", "changes"}


CASES = list(_callables())


@pytest.mark.parametrize("name, obj", CASES, ids=[c[0] for c in CASES])
def test_every_parameter_is_documented(name, obj):
    params = list(inspect.signature(obj).parameters)
    if "." in obj.__qualname__ and params and params[0] in ("self", "cls"):
        params = params[1:]  # (a method's own object; a function's cls is a parameter)
    wanted = {p for p in params if not p.startswith("_")}  # (a dataclass's private field)
    if not wanted:
        return
    assert documented(inspect.getdoc(obj) or "") == wanted
