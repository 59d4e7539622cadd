"""glTF's metallic-roughness model (PBRMaterial) against the notes' (Material) on the same
scene -- a 100k-triangle UV sphere, 512x512, three lights (directional, point, spot) --
in each scheme (flat, Gouraud, Phong), and against a hand-written floor: one moderngl
program with the textbook per-fragment Phong formula drawing the same triangles (no
culling, RGBA read back every frame); and textured: a 256x256 base colour map and a
metallic-roughness map on PBRMaterial, a diffuse map on Material. Interleaved in one
process, medians. Goals: PBR in Phong >= 0.8x the notes' model's frames/s, textured PBR
>= 0.7x.

Run: ``.venv/bin/python benchmarks/pbr_bench.py [--repeats 5] [--size 512]``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import frame_arguments, frame_header, interleaved, table  # noqa: E402
from render_bench import TEXTBOOK_FRAG, TEXTBOOK_VERT  # noqa: E402

import glshade as g  # noqa: E402
from glshade.geometry import primitives as P  # noqa: E402

def scene(material) -> g.Scene:
    s = g.Scene(ambient=(0.05, 0.05, 0.05))
    s.add(P.uv_sphere(159, 318), material)  # (100,806 triangles)
    s.add_light(g.DirectionalLight((-1.0, -1.0, -1.0), intensity=2.0))
    s.add_light(g.PointLight((2.0, 2.0, 3.0), intensity=10.0))
    s.add_light(g.SpotLight((0.0, 3.0, 2.0), (0.0, -1.0, -0.6), intensity=15.0,
                            inner_angle=0.3, outer_angle=0.6))
    return s


def floor(renderer, camera, size: int):
    """The hand-written draw of the same sphere: ``draw()`` renders and reads back."""
    ctx = renderer.context.ctx
    mesh = P.uv_sphere(159, 318)
    tri = mesh.triangles[0]
    normals = mesh.vertices / np.linalg.norm(mesh.vertices, axis=1, keepdims=True)
    vbo = ctx.buffer(np.hstack([mesh.vertices, normals]).astype("f4").tobytes())
    ibo = ctx.buffer(tri.astype("u4").tobytes())
    prog = ctx.program(vertex_shader=TEXTBOOK_VERT, fragment_shader=TEXTBOOK_FRAG)
    vao = ctx.vertex_array(prog, [(vbo, "3f 3f", "in_pos", "in_norm")], ibo)
    fbo = ctx.framebuffer([ctx.renderbuffer((size, size), 4)],
                          ctx.depth_renderbuffer((size, size)))
    mvp = camera.projection_matrix(1.0) @ camera.view_matrix()
    prog["u_mvp"].write(np.ascontiguousarray(mvp.T, "f4").tobytes())
    prog["u_eye"].value = tuple(float(x) for x in camera.position)
    prog["u_light_dir"].value = tuple((np.ones(3) / np.sqrt(3)).tolist())
    prog["u_color"].value = (0.9, 0.6, 0.2)

    def draw():
        fbo.use()
        ctx.enable(ctx.DEPTH_TEST)
        fbo.clear(0, 0, 0, 1)
        vao.render()
        return fbo.read(components=4)
    return draw


def main() -> None:
    args = frame_arguments(__doc__)
    camera = g.Camera.look_at((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), fov_y=45)
    notes = scene(g.Material(color=(0.9, 0.6, 0.2), ks=0.5, shininess=40))
    pbr = scene(g.PBRMaterial(base_color=(0.9, 0.6, 0.2), metallic=0.5, roughness=0.4))
    rng = np.random.default_rng(0)
    image = g.Texture(rng.integers(0, 256, (256, 256, 3), dtype=np.uint8))
    packed = g.Texture(rng.integers(0, 256, (256, 256, 3), dtype=np.uint8))
    notes_mapped = scene(g.Material(color=(0.9, 0.6, 0.2), ks=0.5, shininess=40,
                                    texture=image))
    pbr_mapped = scene(g.PBRMaterial(base_color=(0.9, 0.6, 0.2), metallic=0.5, roughness=0.4,
                                     base_color_texture=image,
                                     metallic_roughness_texture=packed))
    rows = []
    with g.Renderer(args.size, args.size, samples=0) as r:
        print(frame_header(r, args.size, args.repeats))
        hand = floor(r, camera, args.size)
        for mode in ("flat", "gouraud", "phong"):
            series = {"floor": hand,
                      "Material": lambda mode=mode: r.render(notes, camera, mode, cull=False),
                      "PBRMaterial": lambda mode=mode: r.render(pbr, camera, mode, cull=False),
                      "Material mapped": lambda mode=mode: r.render(notes_mapped, camera, mode,
                                                                    cull=False),
                      "PBR mapped": lambda mode=mode: r.render(pbr_mapped, camera, mode,
                                                               cull=False)}
            for fn in series.values():
                fn()  # (compiled and sized before the clock)
            med = interleaved(series, args.repeats)
            rows.append((mode, *(f"{med[k] * 1000:.1f}" for k in series),
                         f"{med['Material'] / med['PBRMaterial']:.2f}",
                         f"{med['Material'] / med['PBR mapped']:.2f}",
                         f"{med['floor'] / med['PBRMaterial']:.2f}"))
    print(table(rows, ("scheme", "floor ms", "Material ms", "PBRMaterial ms",
                       "Material mapped ms", "PBR mapped ms", "PBR / notes fps",
                       "PBR mapped / notes fps", "PBR / floor fps")))


if __name__ == "__main__":
    main()
