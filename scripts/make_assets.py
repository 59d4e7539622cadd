"""Regenerate the sample meshes in assets/ from glshade's own primitives (same licence as
the code). Run with `make assets`."""

from pathlib import Path

import numpy as np

from glshade import Mesh, save_mesh
from glshade.geometry import primitives

ASSETS = Path(__file__).resolve().parent.parent / "assets"


def l_prism() -> Mesh:
    """An L-shaped prism: two concave hexagon caps and six quad sides."""
    outline = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    n = len(outline)
    bottom = np.c_[outline[:, 0], np.zeros(n), outline[:, 1]]
    top = bottom + [0, 1, 0]
    v = np.vstack([bottom, top])
    sides = [[i, n + i, n + (i + 1) % n, (i + 1) % n] for i in range(n)]
    return Mesh(v, [list(range(n)), [n + i for i in reversed(range(n))], *sides], name="lprism")


def cornell_box() -> None:
    """assets/cornell/*.obj (the published box, one file per part) and the scene file
    assets/scenes/cornell-box.toml with its materials and camera."""
    from glshade.geometry.primitives import cornell_parts
    from glshade.radiosity.cornell import CORNELL_CAMERA, CORNELL_MATERIALS

    (ASSETS / "cornell").mkdir(exist_ok=True)
    lines = ["# The Cornell box from its published measurements (millimetres), lit by its",
             "# light alone: `glshade radiosity assets/scenes/cornell-box.toml -o box.png`.",
             "# Reflectances and emission are RGB approximations of the measured spectra.",
             "[render]", "size = [512, 512]", 'mode = "radiosity"', "srgb = true",
             "ambient = [0.0, 0.0, 0.0]", ""]
    for name, mesh in cornell_parts().items():
        save_mesh(mesh, ASSETS / "cornell" / f"{name}.obj")
        rho, emission = CORNELL_MATERIALS[name]
        lines += ["[[mesh]]", f'name = "{name}"', f'source = "../cornell/{name}.obj"',
                  f"reflectance = {list(rho)}", f"color = {list(rho)}", "kd = 1.0",
                  "ka = 0.0", "ks = 0.0"]
        if any(emission):
            lines.append(f"emission = {[float(x) for x in emission]}")
        lines.append("")
    c = CORNELL_CAMERA
    lines += ["[camera]", f"eye = {list(c['eye'])}", f"target = {list(c['target'])}",
              f"fov_y = {round(c['fov_y'], 4)}", "near = 10.0", "far = 3000.0"]
    (ASSETS / "scenes" / "cornell-box.toml").write_text("\n".join(lines) + "\n")


def spotlit() -> None:
    """``spotlit.glb``: a gold ball and a checkered floor in glTF's metallic-roughness
    model, a KHR_lights_punctual spot light above and a camera -- a file as modern tools
    write it (meshes and materials through trimesh, the lights and camera added to its
    JSON, which trimesh does not write)."""
    import json
    import struct

    import trimesh
    from PIL import Image

    ball = trimesh.creation.icosphere(3, radius=0.6)
    ball.apply_translation([0, 0.6, 0])
    ball.visual = trimesh.visual.TextureVisuals(material=trimesh.visual.material.PBRMaterial(
        name="gold", baseColorFactor=[255, 196, 84, 255], metallicFactor=1.0,
        roughnessFactor=0.35))
    floor = trimesh.Trimesh([[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]],
                            [[0, 2, 1], [0, 3, 2]], process=False)
    checks = (np.indices((8, 8)).sum(0) % 2 * 150 + 60).astype(np.uint8)
    floor.visual = trimesh.visual.TextureVisuals(
        uv=[[0, 0], [1, 0], [1, 1], [0, 1]],
        material=trimesh.visual.material.PBRMaterial(
            name="floor", baseColorTexture=Image.fromarray(checks).convert("RGB"),
            metallicFactor=0.0, roughnessFactor=0.8))
    scene = trimesh.Scene()
    scene.add_geometry(ball, geom_name="ball")
    scene.add_geometry(floor, geom_name="floor")
    data = scene.export(file_type="glb")
    length, _ = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + length])
    s = float(np.sqrt(0.5))
    doc["extensionsUsed"] = doc.get("extensionsUsed", []) + ["KHR_lights_punctual"]
    doc.setdefault("extensions", {})["KHR_lights_punctual"] = {"lights": [
        {"type": "spot", "name": "lamp", "color": [1.0, 0.95, 0.85], "intensity": 40.0,
         "spot": {"innerConeAngle": 0.35, "outerConeAngle": 0.6}}]}
    doc["cameras"] = [{"type": "perspective", "name": "view",
                       "perspective": {"yfov": 0.7, "znear": 0.1}}]
    first = len(doc["nodes"])
    # (the lamp 3.5 above the floor pointing down; the camera at (0, 2, 5) looking down
    # 15 degrees: a quaternion about x)
    tilt = np.radians(-15) / 2
    doc["nodes"] += [
        {"name": "lamp", "translation": [0.5, 3.5, 0.5], "rotation": [-s, 0, 0, s],
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "view", "translation": [0, 2, 5],
         "rotation": [float(np.sin(tilt)), 0, 0, float(np.cos(tilt))], "camera": 0}]
    doc["scenes"][doc.get("scene", 0)]["nodes"] += [first, first + 1]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    rest = data[20 + length:]
    (ASSETS / "spotlit.glb").write_bytes(
        struct.pack("<III", 0x46546C67, 2, 20 + len(text) + len(rest)) +
        struct.pack("<II", len(text), 0x4E4F534A) + text + rest)


def main() -> None:
    ASSETS.mkdir(exist_ok=True)
    save_mesh(primitives.teapot(6), ASSETS / "teapot.obj")
    save_mesh(primitives.torus(1.0, 0.35, 24, 12), ASSETS / "torus.off")
    save_mesh(l_prism(), ASSETS / "lprism.obj")
    cornell_box()
    spotlit()
    for p in sorted(ASSETS.glob("*.*")):
        print(p.name, p.stat().st_size)


if __name__ == "__main__":
    main()
