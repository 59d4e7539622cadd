"""A glshade scene as Mitsuba 3 sees it (for the path tracer's third-party oracle): each
material's triangles as an OBJ, diffuse BSDFs of rho_d, area emitters of radiance E / pi
(glshade's emission is a radiosity), a constant sky as Mitsuba's constant emitter, the
same pinhole camera. Shares nothing with glshade's
tracer but the TraceScene's triangles and numbers."""

from __future__ import annotations

import os

import numpy as np


def render(trace_scene, camera: dict, size: int, spp: int, folder, seed: int = 0,
           sampler: str = "independent"):
    """Mitsuba's ``scalar_rgb`` picture ``(size, size, 3)`` in radiosity units (pi x its
    radiance). ``camera``: eye, target, up, fov_y (degrees); ``sampler``: Mitsuba's
    (``independent``; ``ldsampler`` its low-discrepancy one)."""
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    return picture(load(trace_scene, camera, size, spp, folder, seed, sampler))


def picture(scene) -> np.ndarray:
    """A loaded scene rendered by the variant set now, in radiosity units."""
    import mitsuba as mi

    return np.array(mi.render(scene), np.float64)[..., :3] * np.pi


def load(trace_scene, camera: dict, size: int, spp: int, folder, seed: int = 0,
         sampler: str = "independent"):
    """The scene loaded by the variant set now (see :func:`render`)."""
    import mitsuba as mi

    scene = {"type": "scene", "integrator": {"type": "path", "max_depth": 64},
             "sensor": _sensor(camera, size, spp, seed, sampler)}
    ts = trace_scene
    for m, row in enumerate(ts.materials):
        tri = ts.triangles[ts.material == m]
        if not len(tri):
            continue
        path = os.path.join(folder, f"material{m}.obj")
        with open(path, "w") as f:
            f.write("".join(f"v {x:.9g} {y:.9g} {z:.9g}\n" for x, y, z in tri.reshape(-1, 3)))
            f.write("".join(f"f {3 * k + 1} {3 * k + 2} {3 * k + 3}\n" for k in range(len(tri))))
        entry = {"type": "obj", "filename": path, "face_normals": True,
                 "bsdf": _bsdf(row)}
        if row[5:8].sum() > 0:
            entry["emitter"] = {"type": "area",
                                "radiance": {"type": "rgb", "value": (row[5:8] / np.pi).tolist()}}
        scene[f"material{m}"] = entry
    sky = getattr(ts, "environment", None)
    if sky is not None and sky.constant:  # (Mitsuba's constant emitter, radiance as given)
        scene["sky"] = {"type": "constant", "radiance": {
            "type": "rgb", "value": sky.radiance[0, 0].tolist()}}
    elif sky is not None:  # (an image: Mitsuba's envmap -- its own orientation, so for
        # speed alone, not for pictures)
        scene["sky"] = {"type": "envmap",
                        "bitmap": mi.Bitmap(np.ascontiguousarray(sky.radiance, np.float32))}
    return mi.load_dict(scene)


def _sensor(camera: dict, size: int, spp: int, seed: int, sampler: str) -> dict:
    """glshade's pinhole camera as Mitsuba's perspective sensor: a square box-filtered
    film of ``size`` pixels a side, ``spp`` samples of ``sampler`` each."""
    import mitsuba as mi

    return {"type": "perspective", "fov": float(camera["fov_y"]), "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(
                origin=list(camera["eye"]), target=list(camera["target"]),
                up=list(camera["up"])),
            "film": {"type": "hdrfilm", "width": size, "height": size,
                     "rfilter": {"type": "box"}},
            "sampler": {"type": sampler, "sample_count": spp, "seed": seed}}


def _bsdf(row) -> dict:
    """A material row as Mitsuba's BSDF: the notes' diffuse model exactly; glTF's model
    approximately (a metal as ``roughconductor`` of reflectance the base colour, a
    dielectric as ``roughplastic`` of diffuse reflectance the base colour and IOR 1.5: F0
    = 0.04 -- their Fresnel exact, not Schlick's, their Smith term separable, not
    height-correlated): for speed, not for pictures."""
    if len(row) > 10 and row[10] > 0:
        alpha = max(float(row[9]) ** 2, 1e-3)
        if row[8] >= 0.5:
            return {"type": "roughconductor", "distribution": "ggx", "alpha": alpha,
                    "specular_reflectance": {"type": "rgb", "value": row[:3].tolist()}}
        return {"type": "roughplastic", "distribution": "ggx", "alpha": alpha,
                "int_ior": 1.5, "diffuse_reflectance": {"type": "rgb",
                                                         "value": row[:3].tolist()}}
    return {"type": "diffuse", "reflectance": {"type": "rgb", "value": row[:3].tolist()}}


def render_ball(bsdf: dict, sky: float, camera: dict, size: int, spp: int, seed: int = 0
                ) -> np.ndarray:
    """Mitsuba's own unit sphere (its analytic shape) of ``bsdf`` (a Mitsuba BSDF dict) at
    the origin under a constant sky of radiance ``sky``: ``scalar_rgb``, ``(size, size,
    3)`` in radiosity units (pi x its radiance)."""
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    scene = {"type": "scene", "integrator": {"type": "path", "max_depth": 64},
             "sensor": _sensor(camera, size, spp, seed, "independent"),
             "ball": {"type": "sphere", "center": [0.0, 0.0, 0.0], "radius": 1.0,
                      "bsdf": bsdf},
             "sky": {"type": "constant", "radiance": {"type": "rgb",
                                                      "value": [sky, sky, sky]}}}
    return picture(mi.load_dict(scene))
