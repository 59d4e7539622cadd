"""The path tracer's scene as the tables its GPU program reads (the numpy half of the GL
seam; :class:`glshade.render.passes.pathtrace.GpuPathTracer` uploads them)."""

from __future__ import annotations

import numpy as np

from ..geometry.bvh import NO_CHILDREN, build, packed_children

__all__ = ["pack", "environment_tables", "map_tables", "DATA_WIDTH"]

#: texels a row of the scene texture
DATA_WIDTH = 1024


def _bits(values) -> np.ndarray:
    """Integers carried in float32 texels as their bit patterns (floatBitsToInt reads them)."""
    return np.asarray(values, np.int32).view(np.float32)


def _rows(texels: np.ndarray) -> np.ndarray:
    """``texels (N, 4)`` padded with zeros to whole rows of DATA_WIDTH."""
    rows = -(-len(texels) // DATA_WIDTH)
    out = np.zeros((rows * DATA_WIDTH, 4), texels.dtype)
    out[:len(texels)] = texels
    return out


def pack(scene, compiled: np.ndarray | None = None) -> tuple[np.ndarray, dict]:
    """A :class:`~glshade.pathtrace.scene.TraceScene` as RGBA32F texels ``(rows *
    DATA_WIDTH, 4)`` and the offset of each table (see the shader's header): triangles
    (those ``compiled`` marks, ``(T,)`` bool, first, in the scene's order -- the tracer
    compiles them into its program -- then the rest in BVH order), materials, emitters;
    the layout's ``hierarchy`` holds the BVH of the rest as packed children
    (:func:`glshade.geometry.bvh.packed_children`), RGBA32UI texels in rows of DATA_WIDTH,
    its root and quantum as uniforms; ``compiled`` the count of those first.

    Parameters
    ----------
    scene : TraceScene
        The scene.
    compiled : ndarray or None
        ``(T,)`` bool: triangles kept out of the hierarchy.
    """
    apart = np.flatnonzero(compiled) if compiled is not None else np.zeros(0, np.int64)
    rest = np.setdiff1d(np.arange(len(scene.triangles)), apart)
    if len(rest):
        bvh = build(scene.triangles[rest])
        order = np.concatenate([apart, rest[bvh.order]])
        depth, n_nodes = bvh.depth, bvh.n_nodes
        packed = packed_children(bvh, first_triangle=len(apart))
    else:  # (a solid alone, or every triangle compiled in: no hierarchy)
        order, depth, n_nodes = apart, 0, 0
        packed = NO_CHILDREN
    tri = scene.triangles[order]
    n_tris = len(tri)
    tris = np.zeros((3 * n_tris, 4), np.float32)
    tris[0::3, :3] = tri[:, 0]
    tris[0::3, 3] = _bits(scene.material[order])
    tris[1::3, :3] = tri[:, 1] - tri[:, 0]
    tris[1::3, 3] = _bits(scene.model[order])  # (its model: a control variate's value)
    tris[2::3, :3] = tri[:, 2] - tri[:, 0]
    m = scene.materials
    mats = np.zeros((3 * len(m), 4), np.float32)
    mats[0::3, :3], mats[0::3, 3] = m[:, :3], m[:, 3]
    mats[1::3, :3], mats[1::3, 3] = m[:, 5:8], m[:, 4]
    mats[2::3] = m[:, 8:12]  # (glTF's model: metallic, roughness, flag; the opacity)
    where = np.empty(n_tris, np.int64)
    where[order] = np.arange(n_tris)  # (a triangle's place in BVH order)
    norms = np.zeros((3 * n_tris if scene.shading is not None else 1, 4), np.float32)
    if scene.shading is not None:
        norms[:, :3] = scene.shading[order].reshape(-1, 3)
    emit = np.zeros((max(len(scene.emitters), 1), 4), np.float32)
    emit[:len(scene.emitters), 0] = scene.emitter_cdf
    emit[:len(scene.emitters), 1] = _bits(where[scene.emitters])
    emit[:len(scene.emitters), 2] = scene.areas[scene.emitters]
    cols = np.zeros((3 * n_tris if scene.colors is not None else 1, 4), np.float32)
    if scene.colors is not None:
        cols[:, :3] = scene.colors[order].reshape(-1, 3)
    uvs = np.zeros((3 * n_tris if scene.uvs is not None else 1, 4), np.float32)
    if scene.uvs is not None:
        uvs[:, :2] = scene.uvs[order].reshape(-1, 2)
    maps, texdir, texels = map_tables(scene)
    frames = np.zeros((n_tris if scene.tangents is not None else 1, 4), np.float32)
    if scene.tangents is not None:
        frames[:] = scene.tangents[order]
    env, env_layout = environment_tables(scene.environment)
    tables = [tris, mats, emit, norms, env, cols, uvs, maps, texdir, texels, frames]
    offsets = np.cumsum([0] + [len(t) for t in tables])
    data = _rows(np.concatenate(tables))
    layout = {"u_tris": int(offsets[0]), "u_mats": int(offsets[1]),
              "u_emit": int(offsets[2]), "u_n_emit": len(scene.emitters),
              # (the emitters' power, as their cdf sums it: MIS's light density)
              "u_emit_power": float((scene.areas[scene.emitters] * scene.materials[
                  scene.material[scene.emitters], 5:8].mean(1)).sum()),
              "u_norms": int(offsets[3]), "u_env": int(offsets[4]), **env_layout,
              "u_cols": int(offsets[5]), "u_uvs": int(offsets[6]), "u_maps": int(offsets[7]),
              "u_texdir": int(offsets[8]), "u_tangents": int(offsets[10]),
              **packed.uniforms(),
              "depth": depth, "nodes": n_nodes, "width": DATA_WIDTH, "compiled": len(apart),
              "hierarchy": _rows(packed.entries.reshape(-1, 4))}
    return data, layout


def environment_tables(environment) -> tuple[np.ndarray, dict]:
    """An :class:`~glshade.Environment` as the tracer's texels (trace_environment.glsl):
    its ``H x W`` texels row by row, each (radiance in radiosity units -- pi x radiance --,
    its cumulative chance within its row), then a texel a row (the rows' cumulative chance,
    the row's chance). The chances are each texel's mean radiance times its row's solid
    angle (``sin theta`` at the row's middle): a direction is drawn by its row, then its
    column, then uniformly within the texel. None: no texels.

    Parameters
    ----------
    environment : Environment or None
        The sky.
    """
    if environment is None:
        return np.zeros((0, 4), np.float32), {"u_env_w": 0, "u_env_h": 0,
                                              "u_env_rotation": 0.0, "u_env_rows": 0}
    radiance = np.pi * environment.radiance
    h, w, _ = radiance.shape
    theta = np.pi * (np.arange(h) + 0.5) / h
    weight = radiance.mean(2) * np.sin(theta)[:, None]
    row_sum = weight.sum(1)
    # (a row of no light: its columns equally likely, and the row itself never chosen)
    within = np.where(row_sum[:, None] > 0, weight / np.where(row_sum > 0, row_sum, 1)[:, None],
                      1.0 / w)
    texels = np.zeros((h * w + h, 4), np.float32)
    texels[:h * w, :3] = radiance.reshape(-1, 3)
    texels[:h * w, 3] = np.cumsum(within, 1).reshape(-1)
    rows = row_sum / row_sum.sum()
    texels[h * w:, 0] = np.cumsum(rows)
    texels[h * w:, 1] = rows
    return texels, {"u_env_w": w, "u_env_h": h, "u_env_rotation": environment.rotation,
                    "u_env_rows": h * w}


def map_tables(scene) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The maps as the tracer's texels (trace_maps.glsl): each material's five map slots, 2
    texels each -- (texture, wrap, -, -), (scale u, scale v, offset u, offset v); a texel a
    texture -- (its first texel, as int bits, relative to the directory's end; width;
    height; -); then the textures' texels, row by row, each after the last.

    Parameters
    ----------
    scene : TraceScene
        The scene (its ``maps`` and ``textures``).
    """
    m = scene.maps if scene.maps is not None else np.full((len(scene.materials), 5, 6), -1.0)
    maps = np.zeros((10 * len(m), 4), np.float32)
    maps[0::2, :2] = m.reshape(-1, 6)[:, :2]
    maps[1::2] = m.reshape(-1, 6)[:, 2:]
    sizes = [t.shape[0] * t.shape[1] for t in scene.textures]
    firsts = np.cumsum([0] + sizes[:-1]) + len(scene.textures)
    texdir = np.zeros((len(scene.textures), 4), np.float32)
    for i, t in enumerate(scene.textures):  # (a row a texture, not a texel)
        texdir[i] = [_bits([firsts[i]])[0], t.shape[1], t.shape[0], 0.0]
    texels = (np.concatenate([t.reshape(-1, 4) for t in scene.textures]).astype(np.float32)
              if scene.textures else np.zeros((0, 4), np.float32))
    return maps, texdir, texels
