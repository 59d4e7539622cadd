"""A user's file, as the README writes the API: the type checker (``make lint``, and
``tests/test_typing.py``) must see every name's real type, not ``Any``."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from typing_extensions import assert_type

import glshade
from glshade.geometry import primitives
from glshade.solids import Box, Sphere, Solid

mesh = glshade.load_mesh("assets/teapot.obj")
assert_type(mesh, glshade.Mesh)
scene = glshade.Scene()
scene.add(mesh, glshade.Material(color=(0.85, 0.55, 0.3), ks=0.5, shininess=40))
scene.add_light(glshade.PointLight((4.0, 6.0, 8.0)))
camera = glshade.Camera.look_at(eye=(4, 3, 6), target=(0, 1.2, 0))
assert_type(camera, glshade.Camera)

with glshade.Renderer(64, 48, samples=0) as renderer:
    assert_type(renderer, glshade.Renderer)
    image = renderer.render(scene, camera, mode="phong")
    assert_type(image, np.ndarray)
    frame = renderer.render_frame(scene, camera, "flat")
    assert_type(frame, glshade.Frame)
    options = glshade.DrawOptions(mode="gouraud", cull=True, srgb=True)
    assert_type(renderer.render(scene, camera, options), np.ndarray)
config = glshade.RenderConfig(64, 48, samples=0)
assert_type(glshade.Renderer(config=config).render(scene, camera), np.ndarray)

assert_type(mesh.face_normals, NDArray[np.float64])
part: Solid = Box(2) - Sphere(1.2)
assert_type(part.volume(), tuple[float, float])
report = glshade.brep.WingedEdge.from_mesh(primitives.torus()).euler()
assert_type(report, glshade.brep.EulerReport)
q = glshade.quaternion.from_axis_angle([0, 1, 0], 0.5)
assert_type(glshade.quaternion.slerp(q, q, 0.25), NDArray[np.float64])
path = glshade.CameraPath.turntable(camera, center=(0, 1.2, 0))
assert_type(path, glshade.CameraPath)
assert_type(glshade.ShadingMode.parse("flat"), glshade.ShadingMode)
assert_type(glshade.Culling.parse(True), glshade.Culling)
