"""``glshade info``: counts, polygon sizes, bounds, area and topology of a mesh."""

from __future__ import annotations

import json
from pathlib import Path

from ..errors import EXIT_OK, UsageError
from ..io.meshes import load_source
from .arguments import InfoArgs

__all__ = ["info", "mesh_summary", "topology_summary"]


def mesh_summary(mesh) -> dict:
    """Counts, polygon sizes, bounds and area of a mesh, as plain JSON-able data."""
    import numpy as np

    from ..render.gpu_mesh import gpu_bytes

    sizes, counts = np.unique(mesh.face_sizes, return_counts=True)
    return {
        "name": mesh.name,
        "vertices": mesh.n_vertices,
        "faces": mesh.n_faces,
        "edges": mesh.n_edges,
        "polygon_sizes": {int(k): int(c) for k, c in zip(sizes, counts)},
        "bounds": {"min": mesh.bounds[0].tolist(), "max": mesh.bounds[1].tolist()},
        "total_area": mesh.total_area,
        "degenerate_faces": int(len(mesh.degenerate_faces)),
        "euler_characteristic": mesh.n_vertices - mesh.n_edges + mesh.n_faces,
        "signed_volume": mesh.signed_volume(),
        "texture_coordinates": mesh.uv is not None,
        # (which colours the mesh carries: "vertex", "face", both or neither)
        "colors": [k for k, c in (("vertex", mesh.colors), ("face", mesh.face_colors))
                   if c is not None],
        "materials": materials_summary(mesh),
        "unused_material_statements": list(mesh.material_notes),
        "gpu_bytes": gpu_bytes(mesh),
    }


def _texture_summary(t) -> dict:
    return {"file": str(t.path) if t.path else None, "size": list(t.size),
            "filter": t.filter, "wrap": t.wrap}


def material_summary(material, faces: int | None = None) -> dict:
    """One material's coefficients and textures, as plain JSON-able data, with its lighting
    model (``"notes"`` or ``"pbr"``)."""
    if material.lighting.value == "pbr":
        maps = {k.removesuffix("_texture"): getattr(material, k) for k in (
            "base_color_texture", "metallic_roughness_texture", "normal_texture",
            "occlusion_texture", "emissive_texture")}
        out = {"name": material.name, "model": "pbr", "base_color": list(material.base_color),
               "metallic": material.metallic, "roughness": material.roughness,
               "emissive": list(material.emissive), "opacity": material.opacity,
               "vertex_colors": material.vertex_colors,
               "textures": {k: _texture_summary(t) for k, t in maps.items() if t is not None}}
        if faces is not None:
            out["faces"] = faces
        return out
    out = {"name": material.name, "model": "notes", "ambient": list(material.ambient_rgb),
           "diffuse": list(material.diffuse_rgb), "specular": list(material.specular_rgb),
           "shininess": material.shininess, "opacity": material.opacity,
           "illum": material.illum, "emission": list(material.emission),
           "vertex_colors": material.vertex_colors,
           "textures": {k: _texture_summary(t) for k, t in material.textures.items()}}
    if faces is not None:
        out["faces"] = faces
    return out


def materials_summary(mesh) -> list[dict]:
    """The material parts of a mesh (an OBJ's usemtl): each part's material and faces; a
    part whose material no library defined is listed with ``name`` and no coefficients."""
    out = []
    for name, faces in mesh.material_groups.items():
        material = mesh.materials.get(name)
        out.append(material_summary(material, len(faces)) if material is not None else
                   {"name": name, "faces": len(faces), "missing": True})
    return out


def _print_materials(materials: list[dict], notes: list[str]) -> None:
    if not materials:
        return
    print(f"materials ({len(materials)}):      faces  Kd (diffuse)            Ns  illum  "
          "textures")
    for m in materials:
        if m.get("missing"):
            print(f"  {str(m['name'])[:18]:<18} {m['faces']:>7,}  (in no material library: "
                  "drawn with the default)")
            continue
        faces = f"{m['faces']:>7,}" if "faces" in m else " " * 7
        maps = "; ".join(f"{k} {Path(t['file']).name if t['file'] else 'an image'} "
                         f"{t['size'][0]}x{t['size'][1]} {t['filter']}"
                         for k, t in m["textures"].items()) or "-"
        if m.get("model") == "pbr":  # (glTF's metallic-roughness: its factors and maps)
            base = ", ".join(f"{x:.3g}" for x in m["base_color"])
            emits = (f", emissive ({', '.join(f'{x:.3g}' for x in m['emissive'])})"
                     if any(m["emissive"]) else "")
            print(f"  {str(m['name'])[:18]:<18} {faces}  PBR base ({base}), metallic "
                  f"{m['metallic']:.3g}, roughness {m['roughness']:.3g}{emits}"
                  f"{'; ' + maps if m['textures'] else ''}")
            continue
        kd = ", ".join(f"{x:.3g}" for x in m["diffuse"])
        print(f"  {str(m['name'])[:18]:<18} {faces}  ({kd}){' ' * max(0, 20 - len(kd))} "
              f"{m['shininess']:>5g}  {m['illum']:>5}  {maps}")
    if notes:
        print(f"  not drawn ({len(notes)}): " + "; ".join(notes[:6]) +
              (f"; ... {len(notes) - 6} more" if len(notes) > 6 else ""))


def topology_summary(mesh) -> dict:
    """Euler's formula and the validity checks of the mesh's winged-edge structure."""
    from ..brep import WingedEdge

    w = WingedEdge.from_mesh(mesh, strict=False)
    out = w.euler().as_dict()
    out["problems"] = w.report.message() or None
    return out


#: leaf tests an ``info`` octree may make (cells classified times leaves): its depth is
#: the deepest that stays within it, so a large tree stays quick
OCTREE_BUDGET = 3_000_000


def octree_depth(leaves: int, deepest: int = 6) -> int:
    """The octree depth for a tree of ``leaves``: boundary cells grow about 4x a level, so
    each level deeper costs 4x; at least 2."""
    depth = deepest
    while depth > 2 and 8 * 6 * 4 ** (depth - 1) * leaves > OCTREE_BUDGET:
        depth -= 1
    return depth


def solid_summary(solid, depth: int | None = None) -> dict:
    """Volume (Monte Carlo, and the octree's bounds), bounds, leaves, tree depth and the
    octree's cells and memory per level (its depth from :func:`octree_depth` unless
    given), with the seconds it took."""
    import time

    from ..octree import Octree

    start = time.perf_counter()
    leaves = solid.n_leaves
    depth = octree_depth(leaves) if depth is None else depth
    volume, error = solid.volume()
    tree = Octree.from_solid(solid, depth)
    inner, outer = tree.volume_bounds()
    b = solid.bounds
    return {"kind": "CSG solid", "leaves": leaves, "tree_depth": solid.depth,
            "bounds": {"min": b[0].tolist(), "max": b[1].tolist()},
            "volume": volume, "volume_error": error, "octree_depth": depth,
            "octree_volume_bounds": [inner, outer], "octree_levels": tree.counts(),
            "seconds": time.perf_counter() - start}


def _solid_info(args: InfoArgs, solid) -> int:
    s = solid_summary(solid)
    s["source"] = args.mesh
    if args.json:
        print(json.dumps(s, indent=2))
        return EXIT_OK
    lo, hi = s["bounds"]["min"], s["bounds"]["max"]
    source = args.mesh if len(args.mesh) <= 90 else \
        f"{args.mesh[:80]}... ({len(args.mesh):,} characters)"
    print(f"source        {source}")
    print(f"kind          CSG solid, {s['leaves']:,} leaves, {s['tree_depth']} levels deep")
    print(f"bounding box  [{', '.join(f'{x:.4g}' for x in lo)}] .. "
          f"[{', '.join(f'{x:.4g}' for x in hi)}]")
    print(f"volume        {s['volume']:.6g} +- {s['volume_error']:.2g} (Monte Carlo); "
          f"octree depth {s['octree_depth']}: {s['octree_volume_bounds'][0]:.6g} .. "
          f"{s['octree_volume_bounds'][1]:.6g}")
    print("octree:  level    inside   outside  boundary     bytes")
    for c in s["octree_levels"]:
        print(f"         {c['level']:>5} {c['inside']:>9,} {c['outside']:>9,} "
              f"{c['boundary']:>9,} {c['bytes']:>9,}")
    print(f"({s['seconds']:.2f} s)")
    return EXIT_OK


def scene_summary(scene_file) -> dict:
    """A scene file's models (counts, closedness, world bounds), solids, lights, camera path
    and render settings, as plain JSON-able data."""
    sf, st = scene_file, scene_file.settings
    models = []
    for m in sf.scene.models:
        corners = m.corners
        models.append({"name": m.name, "faces": m.mesh.n_faces, "vertices": m.mesh.n_vertices,
                       "closed": bool(m.mesh.closed_and_oriented), "visible": m.visible,
                       "emission": list(map(float, m.material.emission)),
                       "material": material_summary(m.material),
                       "bounds": {"min": corners.min(0).tolist(),
                                  "max": corners.max(0).tolist()}})
    lights = lights_summary(sf.scene.lights)
    return {"kind": "scene", "models": models,
            "solids": [{"name": x.name, "leaves": len(x.solid.leaves())}
                       for x in sf.scene.solids],
            "lights": lights, "keyframes": len(sf.path), "duration": sf.path.duration,
            "size": list(st.size), "mode": st.options.mode.value, "fps": st.fps,
            "samples": st.samples}


def _scene_info(args: InfoArgs) -> int:
    from ..io.scenefile import load_scene

    s = scene_summary(load_scene(args.mesh))
    s["source"] = args.mesh
    if args.json:
        print(json.dumps(s, indent=2))
        return EXIT_OK
    print(f"source  {args.mesh}")
    print(f"render  {s['size'][0]}x{s['size'][1]} {s['mode']}, {s['samples']} samples, "
          f"{s['fps']:g} fps; camera path of {s['keyframes']} key frame"
          f"{'s' if s['keyframes'] != 1 else ''}, {s['duration']:g} s")
    print(f"models ({len(s['models'])}):        faces  vertices  closed  emits  bounding box")
    for m in s["models"]:
        lo, hi = m["bounds"]["min"], m["bounds"]["max"]
        print(f"  {str(m['name'])[:18]:<18} {m['faces']:>7,} {m['vertices']:>9,}  "
              f"{'yes' if m['closed'] else 'no':>6}  {'yes' if any(m['emission']) else 'no':>5}"
              f"  [{', '.join(f'{x:.4g}' for x in lo)}] .. [{', '.join(f'{x:.4g}' for x in hi)}]")
    for x in s["solids"]:
        print(f"  {str(x['name'])[:18]:<18} CSG solid, {x['leaves']} leaves")
    # (each model's material, in its lighting model: the notes' or glTF's)
    _print_materials([dict(m["material"], name=m["name"]) for m in s["models"]], [])
    _print_lights(s["lights"])
    return EXIT_OK


def lights_summary(lights) -> list[dict]:
    """Lights as plain JSON-able data: kind, position (or direction), colour, intensity,
    a spot's cone and a range."""
    from ..scene import DirectionalLight

    return [{"kind": "directional" if isinstance(x, DirectionalLight) else
             "spot" if hasattr(x, "spot_vector") else "point",
             "at": list(map(float, x.direction if isinstance(x, DirectionalLight)
                            else x.position)),
             "color": list(map(float, x.color)), "intensity": float(x.intensity),
             "range": getattr(x, "range", None),
             **({"direction": list(map(float, x.direction)),
                 "inner_angle": x.inner_angle, "outer_angle": x.outer_angle}
                if hasattr(x, "spot_vector") else {})}
            for x in lights]


def _numbers(values) -> str:
    """A vector as a reader wants it: 3 digits, a rounding error of 0 shown as 0."""
    return ", ".join(f"{v:.3g}" for v in (0.0 if abs(v) < 1e-12 else v for v in values))


def _print_lights(lights: list[dict]) -> None:
    print(f"lights ({len(lights)}):" if lights else "lights: none (a headlight at the camera)")
    for x in lights:
        where = "shining along" if x["kind"] == "directional" else "at"
        cone = (f", pointing ({_numbers(x['direction'])}), cone "
                f"{x['inner_angle']:.3g} to {x['outer_angle']:.3g} rad"
                if x["kind"] == "spot" else "")
        reach = f", range {x['range']:g}" if x.get("range") is not None else ""
        print(f"  {x['kind']:<11} {where} ({_numbers(x['at'])}), "
              f"intensity {x['intensity']:g}{cone}{reach}")


def _patch_info(args: InfoArgs, surface) -> int:
    """Patches, degree, the adaptive tessellation's size and Euler's formula on the
    patches' B-Rep."""
    import time

    from ..patches import tessellate

    b = surface.patches.bounds()
    lo, hi = b[:, 0].min(0), b[:, 1].max(0)
    tol = args.tolerance or 1e-3 * float((hi - lo).max())
    t0 = time.perf_counter()
    tess = tessellate(surface, tolerance=tol)
    seconds = time.perf_counter() - t0
    e = surface.euler()
    m, n = surface.patches.degree
    info = {"source": args.mesh, "patches": len(surface.patches), "degree": [m, n],
            "rational": surface.patches.rational,
            "tolerance": tol, "triangles": tess.n_triangles,
            "samples_per_side": {"min": int(tess.levels.min()), "max": int(tess.levels.max())},
            "seconds": seconds, "bounds": {"min": lo.tolist(), "max": hi.tolist()},
            "topology": e.as_dict()}
    if args.json:
        print(json.dumps(info, indent=2))
        return EXIT_OK
    rows = [("source", args.mesh),
            ("patches", f"{len(surface.patches)} of degree {m}x{n}"
                        f"{' (rational)' if surface.patches.rational else ''}"),
            ("adaptive mesh", f"{tess.n_triangles:,} triangles within {tol:.3g} "
                              f"({int(tess.levels.min())}..{int(tess.levels.max())} samples a "
                              f"patch side; {seconds:.2f} s)"),
            ("bounding box", f"[{', '.join(f'{x:.4g}' for x in lo)}] .. "
                             f"[{', '.join(f'{x:.4g}' for x in hi)}]"),
            ("B-Rep", f"V {e.V}, E {e.E} boundary curves, F {e.F} patches"),
            ("Euler", e.formula + ("" if e.holds else "  (does not hold)")),
            ("surface", ("closed" if e.is_closed else f"open: {e.B} boundary loops") +
             f", {e.C} component{'s' if e.C != 1 else ''}, genus "
             f"{'?' if e.G is None else e.G}")]
    width = max(len(k) for k, _ in rows)
    for k, v in rows:
        print(f"{k:<{width}}  {v}")
    return EXIT_OK


def _points_info(args: InfoArgs, cloud) -> int:
    """A point set's counts, bounds, arrays and GPU bytes."""
    if args.tolerance is not None:
        raise UsageError(f"--tolerance is for patches:NAME, not {args.mesh}")
    from ..render.passes.points import cloud_gpu_bytes

    lo, hi = cloud.points.min(0), cloud.points.max(0)
    gpu = cloud_gpu_bytes(cloud)
    info = {"source": args.mesh, "points": cloud.n_points,
            "bounds": {"min": lo.tolist(), "max": hi.tolist()},
            "normals": cloud.normals is not None, "colors": cloud.colors is not None,
            "radius": cloud.radius, "gpu_bytes": gpu}
    if args.json:
        print(json.dumps(info, indent=2))
        return EXIT_OK
    rows = [("source", args.mesh), ("points", f"{cloud.n_points:,}"),
            ("bounding box", f"[{', '.join(f'{x:.4g}' for x in lo)}] .. "
                             f"[{', '.join(f'{x:.4g}' for x in hi)}]"),
            ("normals", "yes" if info["normals"] else "no"),
            ("colours", "yes" if info["colors"] else "no"),
            ("radius", f"{cloud.radius:.4g} (1/200 of the box's diagonal)"),
            ("GPU bytes", f"{gpu:,} ({gpu // cloud.n_points} a point)")]
    width = max(len(k) for k, _ in rows)
    for k, v in rows:
        print(f"{k:<{width}}  {v}")
    return EXIT_OK


def info(args: InfoArgs) -> int:
    """``glshade info``: counts, sizes, bounds, area and topology of a mesh, scene or solid."""
    from dataclasses import replace

    from .. import examples
    from ..solids.tree import Solid
    from .inputs import is_scene_file

    args = replace(args, mesh=examples.resolve(args.mesh))  # (an example's name: its file)
    if is_scene_file(args.mesh):
        return _scene_info(args)
    asset = None
    if args.mesh.lower().endswith((".gltf", ".glb")):  # (its lights and cameras too)
        from ..io.gltf import load_gltf

        asset = load_gltf(args.mesh)
        mesh = asset.mesh
    else:
        mesh = load_source(args.mesh)
    if isinstance(mesh, Solid):
        return _solid_info(args, mesh)
    from ..patches import PatchSurface

    if isinstance(mesh, PatchSurface):
        return _patch_info(args, mesh)
    from ..geometry.points import PointCloud

    if isinstance(mesh, PointCloud):
        return _points_info(args, mesh)
    if args.tolerance is not None:
        raise UsageError(f"--tolerance is for patches:NAME, not {args.mesh}")
    info = mesh_summary(mesh)
    info["source"] = args.mesh
    info["topology"] = topology_summary(mesh)
    if asset is not None:
        info["lights"] = lights_summary(asset.lights)
        info["cameras"] = [{"name": c.name, "projection": c.camera.projection.value,
                            "position": c.camera.position.tolist(),
                            "fov_y": c.camera.fov_y, "aspect": c.aspect}
                           for c in asset.cameras]
    if args.json:
        print(json.dumps(info, indent=2))
        return EXIT_OK
    _print_mesh(args, mesh, info)
    return EXIT_OK


def _print_mesh(args: InfoArgs, mesh, info: dict) -> None:
    """``info``'s table of a mesh (and of a glTF file's lights and cameras)."""
    lo, hi = info["bounds"]["min"], info["bounds"]["max"]
    rows = [
        ("source", args.mesh),
        ("vertices", f"{info['vertices']:,}"),
        ("faces", f"{info['faces']:,}"),
        ("edges", f"{info['edges']:,}"),
        ("V - E + F", str(info["euler_characteristic"])),
        ("bounding box", f"[{', '.join(f'{x:.4g}' for x in lo)}] .. "
                         f"[{', '.join(f'{x:.4g}' for x in hi)}]"),
        ("total area", f"{info['total_area']:.6g}"),
        ("signed volume", f"{info['signed_volume']:.6g}"),
        ("degenerate faces", str(info["degenerate_faces"])),
        ("GPU bytes", f"{info['gpu_bytes']:,} ({info['gpu_bytes'] / max(mesh.n_faces, 1):.1f} "
                      "a polygon, drawn smooth; flat and id draws add corner copies)"),
    ]
    width = max(len(k) for k, _ in rows)
    for k, v in rows:
        print(f"{k:<{width}}  {v}")
    print("polygon sizes:")
    total = max(info["faces"], 1)
    for k, c in info["polygon_sizes"].items():
        bar = "#" * max(1, round(40 * c / total))
        print(f"  {k:>4}-gon  {c:>10,}  {bar}")
    t = info["topology"]
    print("topology (winged edge):")
    print("     V       E       F     H    C    G  closed  manifold  oriented  boundary loops")
    g = "?" if t["G"] is None else t["G"]
    print(f"  {t['V']:>4} {t['E']:>7} {t['F']:>7} {t['H']:>5} {t['C']:>4} {g:>4}  "
          f"{'yes' if t['closed'] else 'no':>6}  {'yes' if t['manifold'] else 'no':>8}  "
          f"{'yes' if t['oriented'] else 'no':>8}  {t['boundary_loops']:>14}")
    kind = ("for closed surfaces" if t["closed"] else
             "for surfaces with boundary (each boundary loop counts as a face, B)")
    print(f"  Euler's formula {kind} {'holds' if t['euler_holds'] else 'does NOT hold'}: "
          f"{t['formula']}")
    if t["problems"]:
        print(f"  problems: {t['problems']}")
    if info["texture_coordinates"]:
        print("texture coordinates: yes (vt, one per face corner)")
    if info["colors"]:
        print(f"colours: per {' and per '.join(info['colors'])} (linear RGBA; the surface "
              "colour C, times the material's)")
    _print_materials(info["materials"], info["unused_material_statements"])
    if "lights" in info:  # (a glTF file's)
        _print_lights(info["lights"])
        if info["cameras"]:
            print(f"cameras ({len(info['cameras'])}):")
        for c in info["cameras"]:
            lens = (f"{c['fov_y']:.3g} degrees high" if c["projection"] == "perspective"
                    else "parallel")
            print(f"  {str(c['name'])[:18]:<18} at ({_numbers(c['position'])}), {lens}")


