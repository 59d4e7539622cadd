"""The bridge to trimesh (the ``formats`` extra): meshes to and from ``trimesh.Trimesh``
and ``trimesh.Scene``; ``glshade.io`` reads every format trimesh reads (glTF/GLB, 3MF, ...)
through it. trimesh is never needed by the rest of glshade."""

from __future__ import annotations

import numpy as np

from .._srgb import linear_to_srgb, srgb_to_linear
from ..errors import EnvironmentFailure, MeshFormatError
from .mesh import Mesh

__all__ = ["from_trimesh", "to_trimesh", "trimesh_formats", "trimesh_module", "trimesh_parts",
           "HINT"]

HINT = "pip install 'glshade[formats]'"


def trimesh_module():
    """trimesh, imported on first use, or an InputError saying how to install it."""
    try:
        import trimesh
    except ImportError:
        raise EnvironmentFailure(f"this needs trimesh: {HINT}") from None
    return trimesh


def trimesh_formats() -> tuple[str, ...]:
    """The file extensions trimesh can read here (empty when it is not installed)."""
    try:
        import trimesh
    except ImportError:
        return ()
    return tuple(sorted(trimesh.available_formats()))


def _colors_of(m, linear: bool):
    """A trimesh mesh's vertex and face colours as ``(N, 4)`` linear RGBA (None where it has
    none): trimesh holds RGBA bytes -- sRGB-encoded as its viewer shows them and PLY files
    store them, or linear (``linear``: a glTF's ``COLOR_0``, which trimesh scales to bytes
    without a curve)."""
    visual = m.visual
    kind = getattr(visual, "kind", None)
    found = {"vertex": None, "face": None}
    if kind == "vertex":
        found["vertex"] = visual.vertex_colors
    elif kind == "face":
        found["face"] = visual.face_colors
    elif kind == "texture" and "color" in getattr(visual, "vertex_attributes", {}):
        found["vertex"] = visual.vertex_attributes["color"]  # (a glTF's COLOR_0 beside a map)
    out: list = []
    for c in (found["vertex"], found["face"]):
        if c is None:
            out.append(None)
            continue
        c = np.asarray(c)
        c = c / 255.0 if c.dtype.kind in "iu" else np.asarray(c, np.float64)
        if c.shape[1] == 3:
            c = np.hstack([c, np.ones((len(c), 1))])
        if not linear:
            c = np.hstack([srgb_to_linear(c[:, :3]), c[:, 3:]])
        out.append(np.clip(c, 0.0, 1.0))
    return out[0], out[1]


def from_trimesh(tm, name: str | None = None, linear_colors: bool = False) -> Mesh:
    """A glshade Mesh from a ``trimesh.Trimesh`` (triangles), or from a ``trimesh.Scene``
    with every node's transform applied (all its meshes joined, in the order of
    :func:`trimesh_parts`; or such a list itself), with their texture coordinates and
    vertex and face colours. (Their materials are the reader's: ``glshade.io.meshes``.)

    Parameters
    ----------
    tm : trimesh.Trimesh or trimesh.Scene
        The mesh or scene.
    name : str or None
        The mesh's name.
    linear_colors : bool
        trimesh's colour bytes are linear (a glTF's ``COLOR_0``); else sRGB-encoded, as
        trimesh shows them and PLY files hold them.
    """
    trimesh = trimesh_module()
    meshes = tm if isinstance(tm, list) else trimesh_parts(tm, name)
    if not all(isinstance(m, trimesh.Trimesh) for m in meshes):
        raise MeshFormatError(name or "<trimesh object>", f"holds a {type(tm).__name__}, not "
                              "a surface (a point cloud or a path has no faces)")
    vertices, faces, uvs, base = [], [], [], 0
    colors = [_colors_of(m, linear_colors) for m in meshes]
    for m in meshes:
        vertices.append(np.asarray(m.vertices, np.float64))
        f = np.asarray(m.faces, np.int64)
        faces.append(f + base)
        uv = getattr(m.visual, "uv", None) if getattr(m.visual, "kind", None) == "texture" \
            else None
        uvs.append(None if uv is None or len(uv) != len(m.vertices) else
                   np.asarray(uv, np.float64)[f].reshape(-1, 2))
        base += len(m.vertices)
    textured = any(u is not None for u in uvs)
    vertex_colors = face_colors = None
    if any(c[0] is not None for c in colors):  # (white where a part has none)
        vertex_colors = np.concatenate([c[0] if c[0] is not None else np.ones((len(v), 4))
                                        for c, v in zip(colors, vertices)])
    if any(c[1] is not None for c in colors):
        face_colors = np.concatenate([c[1] if c[1] is not None else np.ones((len(f), 4))
                                      for c, f in zip(colors, faces)])
    out = Mesh(np.concatenate(vertices), np.concatenate(faces),
               name=name or meshes[0].metadata.get("name"),
               uv=np.concatenate([u if u is not None else np.zeros((3 * len(f), 2))
                                  for u, f in zip(uvs, faces)]) if textured else None,
               colors=vertex_colors, face_colors=face_colors)
    _describe_materials(out, meshes)
    return out


def _describe_materials(mesh: Mesh, meshes: list) -> None:
    """Each part's material as a material part of ``mesh``, described as plain data (the
    scene makes the material: ``glshade.scene.material.material_from_description``): a
    glTF's metallic-roughness factors and maps, or a simple material's diffuse colour and
    image."""
    start = 0
    for k, m in enumerate(meshes):
        count = len(m.faces)
        material = getattr(m.visual, "material", None)
        if material is not None:
            description = _description(material)
            if description is not None:
                name = getattr(material, "name", None) or f"material {k}"
                if name in mesh.materials:
                    name = f"{name} ({k})"  # (a name used twice: a part each, never merged)
                mesh.materials[name] = {**description, "name": name}
                mesh.material_groups[name] = np.arange(start, start + count)
        start += count


def _rgba(value, default) -> np.ndarray:
    rgba = np.asarray(value if value is not None else default, np.float64).ravel()
    rgba = rgba / 255.0 if rgba.max(initial=0) > 1 else rgba
    return np.concatenate([rgba, np.ones(4 - len(rgba))]) if len(rgba) < 4 else rgba[:4]


def _description(material) -> dict | None:
    """A trimesh material as plain data, or None for one that says nothing."""
    if hasattr(material, "baseColorFactor") or hasattr(material, "metallicFactor"):
        rgba = _rgba(getattr(material, "baseColorFactor", None), [1.0] * 4)
        out = {"kind": "pbr", "base_color": rgba[:3].tolist(), "opacity": float(rgba[3]),
               "metallic": _factor(getattr(material, "metallicFactor", None), 1.0),
               "roughness": _factor(getattr(material, "roughnessFactor", None), 1.0),
               "emissive": _rgba(getattr(material, "emissiveFactor", None),
                                 [0.0, 0.0, 0.0])[:3].tolist(),
               "alpha_mode": getattr(material, "alphaMode", None),
               "maps": {key: image for key, attr in (
                   ("base_color_texture", "baseColorTexture"),
                   ("metallic_roughness_texture", "metallicRoughnessTexture"),
                   ("normal_texture", "normalTexture"),
                   ("occlusion_texture", "occlusionTexture"),
                   ("emissive_texture", "emissiveTexture"))
                   if (image := getattr(material, attr, None)) is not None}}
        return out
    image = getattr(material, "image", None)
    diffuse = getattr(material, "diffuse", None)
    if image is None and diffuse is None:
        return None
    rgba = _rgba(diffuse, [255] * 4)
    return {"kind": "simple", "color": rgba[:3].tolist(), "opacity": float(rgba[3]),
            "maps": {"texture": image} if image is not None else {}}


def _factor(value, default: float) -> float:
    return float(default if value is None else value)


def trimesh_parts(tm, name: str | None = None) -> list:
    """The triangle meshes a trimesh object holds, placed: itself, or a scene's dumped.

    Parameters
    ----------
    tm : trimesh.Trimesh or trimesh.Scene
        The mesh or scene.
    name : str or None
        The name its parts take.
    """
    trimesh = trimesh_module()
    if not isinstance(tm, trimesh.Scene):
        return [tm]
    meshes = [g for g in tm.dump() if isinstance(g, trimesh.Trimesh)]
    if not meshes:
        raise MeshFormatError(name or "<trimesh scene>", "the scene holds no triangle mesh")
    return meshes


def to_trimesh(mesh: Mesh, image=None):
    """A ``trimesh.Trimesh`` of the mesh's triangulation (polygons are split; trimesh only
    knows triangles). Vertices are kept as they are, except where texture coordinates
    differ between a vertex's corners (a seam: trimesh holds one uv a vertex, so the vertex
    is copied per uv). Colours go over as trimesh's sRGB-encoded RGBA bytes: per vertex,
    or per triangle (its polygon's) where the mesh has face colours; uv as a texture
    visual, with ``image`` as its map where given.

    Parameters
    ----------
    mesh : Mesh
        The mesh.
    image : PIL.Image.Image or None
        A texture image for the texture visual (a material's map).
    """
    trimesh = trimesh_module()
    tri, owner = mesh.triangles
    vertices, source = mesh.vertices, None
    if mesh.uv is not None:  # (one uv a vertex: split vertices by their corners' uv)
        rows = np.column_stack([mesh.face_indices, mesh.uv])
        unique, corner_vertex = np.unique(rows, axis=0, return_inverse=True)
        source = unique[:, 0].astype(np.int64)
        vertices = mesh.vertices[source]
        tri = corner_vertex.ravel()[mesh.corner_triangles]

    def srgb_bytes(c):
        encoded = np.hstack([linear_to_srgb(c[:, :3]), c[:, 3:]])
        return np.round(np.clip(encoded, 0, 1) * 255).astype(np.uint8)

    kwargs = {}
    polygon_colors = mesh.polygon_colors
    if mesh.face_colors is not None and polygon_colors is not None:
        # (a triangle's colour is its polygon's: the corners' mean in flat shading)
        kwargs["face_colors"] = srgb_bytes(polygon_colors[owner])
    elif mesh.colors is not None:
        kwargs["vertex_colors"] = srgb_bytes(mesh.colors if source is None else
                                             mesh.colors[source])
    out = trimesh.Trimesh(vertices=vertices.copy(), faces=tri.copy(), process=False,
                          metadata={"name": mesh.name}, **kwargs)
    if mesh.uv is not None:
        visual = trimesh.visual.TextureVisuals(uv=unique[:, 1:3], image=image)
        if "vertex_colors" in kwargs:  # (kept beside the map, as trimesh keeps COLOR_0)
            visual.vertex_attributes["color"] = kwargs["vertex_colors"]
        out.visual = visual
    return out
