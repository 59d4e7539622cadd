"""What a glTF/GLB file holds beside its meshes: KHR_lights_punctual's lights and the
cameras, placed by the node tree (trimesh reads the meshes and materials; it exposes
neither the lights nor every camera, so the file's JSON is read here), and what it holds
that glshade does not draw, named for the one warning a load gives.

Conventions (glTF 2.0, section 3.5 and KHR_lights_punctual): a node's matrix is its
``matrix`` or ``T * R * S`` from ``translation``, ``rotation`` (a unit quaternion ``[x, y,
z, w]``) and ``scale``; a camera and a light look down their node's local -Z with +Y up; a
light's intensity is candela for point and spot lights, lux for directional ones -- what
:class:`~glshade.PBRMaterial`'s lighting takes as it is. No GL."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import MeshFormatError
from ..geometry.mesh import Mesh
from .gltf_json import gltf_document, gltf_unread

__all__ = ["GltfFile", "load_gltf", "gltf_lights", "gltf_cameras", "gltf_unread"]


def _node_matrix(node: dict) -> np.ndarray:
    """A node's local matrix (glTF stores ``matrix`` column-major)."""
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
    x, y, z, w = (float(v) for v in node.get("rotation", (0.0, 0.0, 0.0, 1.0)))
    rotation = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    m = np.eye(4)
    m[:3, :3] = rotation * np.asarray(node.get("scale", (1.0, 1.0, 1.0)), np.float64)
    m[:3, 3] = node.get("translation", (0.0, 0.0, 0.0))
    return m


def _placed_nodes(doc: dict) -> list[tuple[dict, np.ndarray]]:
    """Every node of the default scene (else of every root) with its world matrix, in
    the file's order of nodes."""
    nodes = doc.get("nodes", [])
    scenes = doc.get("scenes", [])
    if scenes:
        roots = scenes[doc.get("scene", 0)].get("nodes", [])
    else:
        children = {c for n in nodes for c in n.get("children", [])}
        roots = [i for i in range(len(nodes)) if i not in children]
    out: list[tuple[int, np.ndarray]] = []
    stack = [(i, np.eye(4)) for i in roots]
    seen: set[int] = set()
    while stack:
        index, parent = stack.pop()
        if index in seen:  # (a cycle is no tree: each node is placed once)
            continue
        seen.add(index)
        world = parent @ _node_matrix(nodes[index])
        out.append((index, world))
        stack.extend((c, world) for c in nodes[index].get("children", []))
    return [(nodes[i], world) for i, world in sorted(out, key=lambda p: p[0])]


def gltf_lights(path) -> list:
    """The KHR_lights_punctual lights of a glTF/GLB file, placed by its nodes.

    Directional lights become :class:`~glshade.DirectionalLight` (lux), point lights
    :class:`~glshade.PointLight` and spot lights :class:`~glshade.SpotLight` (candela,
    ``range`` kept), each aimed down its node's -Z.

    Parameters
    ----------
    path : str or Path
        The .gltf or .glb file.

    Raises
    ------
    MeshFormatError
        A light the file describes out of its extension's bounds (a negative intensity,
        cone angles outside 0 <= inner < outer <= pi/2), naming the file and the light.
    """
    from ..errors import SceneError
    from ..scene.lights import DirectionalLight, PointLight, SpotLight

    path = Path(path)
    doc = gltf_document(path)
    table = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    lights: list = []
    for node, world in _placed_nodes(doc):
        index = node.get("extensions", {}).get("KHR_lights_punctual", {}).get("light")
        if index is None:
            continue
        light = table[index]
        position = tuple(world[:3, 3].tolist())
        direction = tuple((world[:3, :3] @ np.array([0.0, 0.0, -1.0])).tolist())
        common: dict = {"color": tuple(light.get("color", (1.0, 1.0, 1.0))),
                  "intensity": float(light.get("intensity", 1.0))}
        kind = light.get("type")
        name = light.get("name", f"light {index}")
        try:
            if kind == "directional":
                lights.append(DirectionalLight(direction, **common))
            elif kind == "point":
                lights.append(PointLight(position, range=light.get("range"), **common))
            elif kind == "spot":
                cone = light.get("spot", {})
                lights.append(SpotLight(position, direction, range=light.get("range"),
                                        inner_angle=cone.get("innerConeAngle", 0.0),
                                        outer_angle=cone.get("outerConeAngle", math.pi / 4),
                                        **common))
            else:
                raise SceneError(f"type must be directional, point or spot, got {kind!r}")
        except SceneError as exc:
            raise MeshFormatError(path, f"light {name!r}: {exc}") from None
    return lights


@dataclass(frozen=True)
class GltfCamera:
    """A glTF camera: the :class:`~glshade.Camera` its node places, and the aspect ratio
    (width / height) the file asks for (None: the image's)."""

    name: str
    camera: object
    aspect: float | None = None


def gltf_cameras(path) -> list[GltfCamera]:
    """The cameras of a glTF/GLB file, one for each node that holds one, in the file's
    order of nodes: perspective ones with their vertical field of view and clip planes (no
    ``zfar``: the scene's), orthographic ones with ``ymag`` as half their height.

    Parameters
    ----------
    path : str or Path
        The .gltf or .glb file.
    """
    from .. import quaternion as quat
    from ..errors import SceneError
    from ..modes import Projection
    from ..scene.camera import Camera

    path = Path(path)
    doc = gltf_document(path)
    table = doc.get("cameras", [])
    out = []
    for node, world in _placed_nodes(doc):
        if "camera" not in node:
            continue
        index = node["camera"]
        spec = table[index]
        name = spec.get("name", node.get("name", f"camera {index}"))
        axes = world[:3, :3] / np.linalg.norm(world[:3, :3], axis=0)  # (scale dropped)
        place: dict = {"position": world[:3, 3], "orientation": quat.from_matrix(axes)}
        try:
            if spec.get("type") == "orthographic":
                o = spec.get("orthographic", {})
                camera = Camera(**place, projection=Projection.ORTHOGRAPHIC,
                                height=2.0 * float(o.get("ymag", 1.0)),
                                near=o.get("znear") or None, far=o.get("zfar"))
                xmag, ymag = o.get("xmag"), o.get("ymag")
                aspect = float(xmag) / float(ymag) if xmag and ymag else None
            else:
                p = spec.get("perspective", {})
                camera = Camera(**place, fov_y=math.degrees(float(p.get("yfov", 0.8))),
                                near=p.get("znear"), far=p.get("zfar"))
                aspect = p.get("aspectRatio")
        except SceneError as exc:
            raise MeshFormatError(path, f"camera {name!r}: {exc}") from None
        out.append(GltfCamera(name, camera, None if aspect is None else float(aspect)))
    return out


@dataclass
class GltfFile:
    """A glTF/GLB file as glshade reads it: its meshes (one :class:`~glshade.Mesh`, each
    part with its material), its lights and its cameras.

    Attributes
    ----------
    mesh : Mesh
        Every mesh of the default scene, placed by its nodes.
    lights : list
        KHR_lights_punctual's lights (:func:`gltf_lights`).
    cameras : list of GltfCamera
        Its cameras (:func:`gltf_cameras`).
    """

    mesh: Mesh
    lights: list = field(default_factory=list)
    cameras: list = field(default_factory=list)

    def scene(self, **kwargs):
        """A :class:`~glshade.Scene` of the mesh lit by the file's lights (none: the
        default headlight), for pyrender's ``Scene.from_trimesh_scene`` plus the lights.

        Parameters
        ----------
        **kwargs
            The Scene's own (``background``, ``ambient``).
        """
        from ..scene.scene import Scene

        scene = Scene(**kwargs)
        scene.add(self.mesh)
        for light in self.lights:
            scene.add_light(light)
        return scene


def load_gltf(path) -> GltfFile:
    """Read a glTF/GLB file whole: its meshes and materials (through trimesh, the
    ``formats`` extra), its KHR_lights_punctual lights and its cameras. What it holds
    beyond those is one warning naming it.

    Parameters
    ----------
    path : str or Path
        The .gltf or .glb file.

    Examples
    --------
    >>> asset = glshade.load_gltf("robot.glb")          # doctest: +SKIP
    >>> frame = renderer.render(asset.scene(), asset.cameras[0].camera)  # doctest: +SKIP
    """
    from .meshes import read_mesh

    path = Path(path)
    if path.suffix.lower() not in (".gltf", ".glb"):
        raise MeshFormatError(path, "load_gltf reads .gltf and .glb files")
    mesh = read_mesh(path, extras_taken=True)
    return GltfFile(mesh, gltf_lights(path), gltf_cameras(path))
