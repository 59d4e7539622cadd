"""glshade's light units beside pyrender's, on the same scene: a rough white dielectric ball
(metallic 0, roughness 1) seen head-on, lit in turn by a directional light (lux), a point
light and a spot light (candela) given the same numbers in both. Printed: the linear
radiance each returns at the pixels that see the ball's front (N.V > 0.9, where the two
BRDFs' visibility terms agree), their ratio, and the ratio the two shaders' formulas
predict -- pyrender's diffuse colour is base x 0.96 x (1 - metallic), glshade's base x
(1 - metallic) as glTF's Appendix B says; pyrender encodes with gamma 2.2 (decoded here),
glshade returns linear floats. A ratio at its prediction says the units are the same: a
pyrender intensity is a glshade intensity (docs/guide/pyrender.md).

    bash benchmarks/peers.sh pyrender           # once: .peers/pyrender
    .venv/bin/python benchmarks/pyrender_units.py
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

import glshade
from glshade.geometry import primitives

ROOT = Path(__file__).resolve().parents[1]
PEER = ROOT / ".peers" / "pyrender" / "bin" / "python"
SIZE, FOV, EYE = 128, 40.0, 4.0
BASE = (0.9, 0.9, 0.9)

#: the lights, as both libraries take them: kind, intensity, position, cone (radians)
LIGHTS = [("directional", 2.0, None, None), ("point", 5.0, (0.0, 0.0, 3.0), None),
          ("spot", 5.0, (0.0, 0.0, 3.0), (0.15, 0.35))]

PYRENDER = """
import json, sys, numpy as np, trimesh, pyrender
data = json.loads(sys.argv[1])
ball = np.load(sys.argv[2])
tm = trimesh.Trimesh(ball["vertices"], ball["faces"], vertex_normals=ball["normals"],
                     process=False)
# (floats: pyrender reads a list of ints as bytes, 0..255)
mat = pyrender.MetallicRoughnessMaterial(baseColorFactor=[*data["base"], 1.0],
                                         metallicFactor=0.0, roughnessFactor=1.0)
r = pyrender.OffscreenRenderer(data["size"], data["size"])
out = []
for kind, intensity, position, cone in data["lights"]:
    scene = pyrender.Scene(ambient_light=[0.0, 0.0, 0.0], bg_color=[0.0, 0.0, 0.0, 0.0])
    scene.add(pyrender.Mesh.from_trimesh(tm, material=mat, smooth=True))
    pose = np.eye(4); pose[2, 3] = data["eye"]
    scene.add(pyrender.PerspectiveCamera(yfov=np.radians(data["fov"])), pose=pose)
    light_pose = np.eye(4)  # (its -z: towards the ball)
    if position is not None:
        light_pose[:3, 3] = position
    white = [1.0, 1.0, 1.0]
    light = {"directional": lambda: pyrender.DirectionalLight(white, intensity),
             "point": lambda: pyrender.PointLight(white, intensity),
             "spot": lambda: pyrender.SpotLight(white, intensity, innerConeAngle=cone[0],
                                                outerConeAngle=cone[1])}[kind]()
    scene.add(light, pose=light_pose)
    color, _ = r.render(scene)
    out.append(color[..., 0])
np.save(sys.argv[3], np.array(out))
"""


def glshade_images(ball) -> list[np.ndarray]:
    camera = glshade.Camera.look_at((0, 0, EYE), (0, 0, 0), fov_y=FOV)
    images = []
    with glshade.Renderer(SIZE, SIZE, samples=0) as renderer:
        for kind, intensity, position, cone in LIGHTS:
            scene = glshade.Scene(ambient=(0, 0, 0), background=(0, 0, 0))
            scene.add(ball, glshade.PBRMaterial(base_color=BASE, metallic=0.0, roughness=1.0))
            if kind == "directional":
                scene.add_light(glshade.DirectionalLight((0, 0, -1), intensity=intensity))
            elif kind == "point":
                scene.add_light(glshade.PointLight(position, intensity=intensity))
            else:
                scene.add_light(glshade.SpotLight(position, (0, 0, -1), intensity=intensity,
                                                  inner_angle=cone[0], outer_angle=cone[1]))
            frame = renderer.render_frame(scene, camera, "phong", color_dtype="f4")
            images.append(frame.color[..., 0].astype(np.float64))
    return images


def front(n: int) -> np.ndarray:
    """Pixels whose centre sees the unit ball where N.V > 0.9 (ray-sphere, closed form)."""
    ndc = (np.arange(n) + 0.5) / (n / 2) - 1
    x, y = np.meshgrid(ndc, -ndc)
    t = np.tan(np.radians(FOV) / 2)
    d = np.stack([x * t, y * t, -np.ones_like(x)], -1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    o = np.array([0.0, 0.0, EYE])
    b = d @ o
    disc = b * b - (o @ o - 1)
    hit = disc > 0
    s = -b - np.sqrt(np.where(hit, disc, 0))
    normal = o + s[..., None] * d
    return hit & (np.einsum("...k,...k", normal, -d) > 0.9)


def main() -> int:
    if not PEER.exists():
        print(f"pyrender_units: skipped, pyrender is not installed ({PEER}): "
              "bash benchmarks/peers.sh pyrender")
        return 0
    ball = primitives.uv_sphere(96, 192)
    with tempfile.TemporaryDirectory() as tmp:
        np.savez(Path(tmp) / "ball.npz", vertices=ball.vertices, faces=ball.triangles[0],
                 normals=ball.vertices)
        data = {"base": BASE, "size": SIZE, "fov": FOV, "eye": EYE, "lights": LIGHTS}
        env = dict(os.environ, PYOPENGL_PLATFORM="egl")
        r = subprocess.run([str(PEER), "-c", PYRENDER, json.dumps(data),
                            str(Path(tmp) / "ball.npz"), str(Path(tmp) / "out.npy")],
                           capture_output=True, text=True, env=env, timeout=600)
        if r.returncode != 0:
            print(r.stderr[-2000:])
            return 1
        theirs = (np.load(Path(tmp) / "out.npy") / 255.0) ** 2.2  # (gamma 2.2 decoded)
    ours = glshade_images(ball)
    where = front(SIZE)
    print(f"pyrender 0.1.45 and glshade {glshade.__version__}: {SIZE}x{SIZE}, the ball's "
          f"front ({where.sum()} pixels, N.V > 0.9), linear red")
    print("| light | intensity | glshade mean | pyrender mean | ratio (median, 5-95%) | "
          "predicted |")
    print("|---|---|---|---|---|---|")
    for (kind, intensity, _, _), mine, peer in zip(LIGHTS, ours, theirs):
        lit = where & (peer > 0.02)  # (pyrender's 8 bits: enough levels to compare)
        ratio = mine[lit] / peer[lit]
        lo, mid, hi = np.percentile(ratio, [5, 50, 95])
        print(f"| {kind} | {intensity:g} | {mine[lit].mean():.4f} | {peer[lit].mean():.4f} | "
              f"{mid:.3f} ({lo:.3f}-{hi:.3f}) | {1 / 0.96:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
