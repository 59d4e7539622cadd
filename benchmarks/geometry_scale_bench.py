"""Geometry at scale: point clouds, instances and a mesh of millions of triangles, against a
peer and the textbook floor.

1. Clouds of N points (uniform in a cube, radius 1/1000 of it) at 1024x768 as squares and
   as sphere impostors: frames a second, glshade against polyscope (headless EGL, its
   'quad' and 'sphere' modes) where it installs (the ``peers`` extra).
2. K instances of a 512-triangle part at 640x480 Phong, no MSAA: one instanced draw against the
   same K models added one by one, against all K copies merged into one mesh (one plain
   draw of the same triangles: what no batching of draw calls can beat), and polyscope
   drawing K meshes.
3. A terrain of T triangles at 640x480 Phong: binary PLY load seconds, first-draw upload
   seconds, GPU bytes a triangle against an indexed mesh's minimum (a float32 position and
   normal a vertex, three uint32 indices a triangle), frames a second against the textbook
   floor drawing the same triangles (one hand-written moderngl program, per-pixel Phong,
   read back each frame, in glshade's own context), and frames a second with the camera
   seeing about a tenth of it (the octree chunks out of view skipped).

Every series of a table runs interleaved, round by round; polyscope keeps its own GL
context in a worker process of its own (two contexts in one thread would fight over which
is current), asked for its frames between glshade's in the same rounds. Peak RSS is the
process's. Nothing here is asserted; the tests check the pictures.

    .venv/bin/python benchmarks/geometry_scale_bench.py [--points 1M,10M]
        [--instances 10000] [--triangles 10M] [--rounds 3] [--no-peers]
        [--only clouds,instances,mesh]
"""

from __future__ import annotations

import argparse
import json
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from _timing import table  # noqa: E402

import glshade  # noqa: E402
from glshade import Camera, Material, Scene  # noqa: E402
from glshade.geometry import primitives as P  # noqa: E402
from glshade.render.gpu_mesh import gpu_bytes  # noqa: E402

#: the polyscope worker: reads one JSON request a line, answers frames a second
PEER = r"""
import json, sys, time
import numpy as np
import polyscope as ps
ps.set_allow_headless_backends(True)
ps.set_verbosity(0)
ps.set_use_prefs_file(False)  # (no .polyscope.ini or imgui.ini left in the working folder)
ps.init("openGL3_egl")
ps.set_ground_plane_mode("none")
made = {}
for line in sys.stdin:
    job = json.loads(line)
    ps.set_window_size(*job["size"])
    key = (job["kind"], job["n"])
    if key not in made:
        ps.remove_all_structures()
        made.clear()
        if job["kind"] == "points":
            pts = np.random.default_rng(0).uniform(-1, 1, (job["n"], 3))
            made[key] = ps.register_point_cloud("pts", pts, radius=job["radius"])
        else:
            v, f = np.array(job["vertices"]), np.array(job["faces"])
            t = np.array(job["transforms"])
            for i, m in enumerate(t):
                ps.register_surface_mesh(f"part{i}", v @ m[:3, :3].T + m[:3, 3], f)
            made[key] = None
        ps.look_at(job["eye"], job["target"])
    if job["kind"] == "points":
        made[key].set_point_render_mode(job["mode"])
    ps.screenshot_to_buffer(False)
    start = time.perf_counter()
    for _ in range(job["frames"]):
        ps.screenshot_to_buffer(False)
    print(json.dumps(job["frames"] / (time.perf_counter() - start)), flush=True)
"""


class Peer:
    """polyscope in a worker process, or None where it does not install or start."""

    def __init__(self):
        self.proc = subprocess.Popen([sys.executable, "-c", PEER], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                     text=True)

    def fps(self, **job) -> float | None:
        try:
            self.proc.stdin.write(json.dumps(job) + "\n")
            self.proc.stdin.flush()
            line = self.proc.stdout.readline()
            return float(line) if line else None
        except (BrokenPipeError, ValueError):
            return None

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait(timeout=30)


def start_peer(enabled: bool) -> Peer | None:
    if not enabled:
        return None
    try:
        import polyscope  # noqa: F401
    except ImportError:
        return None
    return Peer()


def rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def fps_of(draw, frames: int) -> float:
    start = time.perf_counter()
    for _ in range(frames):
        draw()
    return frames / (time.perf_counter() - start)


def count(text: str) -> int:
    text = text.strip().upper()
    scale = {"K": 1_000, "M": 1_000_000}.get(text[-1], 1)
    return int(float(text.rstrip("KM")) * scale)


def clouds(sizes, rounds: int, peer) -> str:
    rows = []
    renderer = glshade.Renderer(1024, 768, samples=0)
    eye, target = (2.2, 1.6, 2.6), (0.0, 0.0, 0.0)
    camera = Camera.look_at(eye, target, fov_y=45)
    for n in sizes:
        points = np.random.default_rng(0).uniform(-1, 1, (n, 3))
        for style, theirs in (("square", "quad"), ("sphere", "sphere")):
            scene = Scene()
            scene.add(glshade.PointCloud(points, radius=0.002, style=style))
            renderer.render(scene, camera)  # (uploaded, compiled)
            frames = 2 if n >= 5_000_000 else 4
            ours, peers = [], []
            for _ in range(rounds):
                ours.append(fps_of(lambda s=scene: renderer.render(s, camera), frames))
                if peer is not None:
                    peers.append(peer.fps(kind="points", n=n, radius=0.001, mode=theirs,
                                          size=[1024, 768], eye=eye, target=target,
                                          frames=frames))
            mine = statistics.median(ours)
            other = statistics.median(peers) if peers and None not in peers else None
            rows.append((f"{n:,} points", style, f"{mine:.2f}",
                         f"{other:.2f}" if other else "not installed",
                         f"{mine / other:.2f}x" if other else "-", f"{rss_mb():,.0f}"))
    renderer.close()
    return table(rows, ("cloud", "style", "glshade fps", "polyscope fps", "glshade/peer",
                        "peak RSS MB"))


def instances(k: int, rounds: int, peer) -> str:
    from instances_bench import placements

    part = P.torus(1.0, 0.35, 16, 16)
    t, colors = placements(k)
    side = np.sqrt(k)
    eye, target = (0.0, 0.9 * side, 0.9 * side), (0.0, 0.0, 0.0)
    camera = Camera.look_at(eye, target, fov_y=50)
    grouped, single, merged = Scene(), Scene(), Scene()
    grouped.add(part, Material(), instances=t, colors=colors)
    for placement, colour in zip(t, colors):
        single.add(part, Material(color=tuple(colour)), transform=placement)
    tri, _ = part.triangles
    n = part.n_vertices
    copies = np.einsum("kij,vj->kvi", t[:, :3, :3], part.vertices) + t[:, None, :3, 3]
    merged.add(glshade.Mesh(copies.reshape(-1, 3),
                            (tri[None] + n * np.arange(k)[:, None, None]).reshape(-1, 3)))
    renderer = glshade.Renderer(640, 480, samples=0)  # (as polyscope: no MSAA)
    for scene in (grouped, single, merged):
        renderer.render(scene, camera)
    series: dict[str, list] = {"instanced": [], "one by one": [], "merged": [],
                               "polyscope": []}
    for _ in range(rounds):
        series["instanced"].append(fps_of(lambda: renderer.render(grouped, camera), 2))
        series["one by one"].append(fps_of(lambda: renderer.render(single, camera), 2))
        series["merged"].append(fps_of(lambda: renderer.render(merged, camera), 2))
        if peer is not None:
            series["polyscope"].append(peer.fps(
                kind="parts", n=k, vertices=part.vertices.tolist(), faces=tri.tolist(),
                transforms=t.tolist(), size=[640, 480], eye=eye, target=target, frames=2))
    renderer.close()
    med = {name: statistics.median(v) for name, v in series.items()
           if v and None not in v}
    peer_fps = med.get("polyscope")
    row = (f"{k:,} x {len(tri)} tris", f"{med['instanced']:.2f}",
           f"{med['one by one']:.2f}", f"{med['instanced'] / med['one by one']:.2f}x",
           f"{med['merged']:.2f}", f"{peer_fps:.2f}" if peer_fps else "not installed",
           f"{med['instanced'] / peer_fps:.2f}x" if peer_fps else "-")
    return table([row], ("scene", "instanced fps", "1-by-1 fps", "speed-up",
                         "one merged mesh fps", "polyscope fps", "glshade/peer"))


def terrain(n_triangles: int) -> glshade.Mesh:
    n = int(round(np.sqrt(n_triangles / 2)))
    x, y = np.meshgrid(np.linspace(-1, 1, n + 1), np.linspace(-1, 1, n + 1))
    z = 0.15 * np.sin(5 * x) * np.cos(4 * y)
    corner = (np.arange(n)[None, :] + np.arange(n)[:, None] * (n + 1)).ravel()
    tris = np.concatenate([np.c_[corner, corner + 1, corner + n + 2],
                           np.c_[corner, corner + n + 2, corner + n + 1]])
    return glshade.Mesh(np.c_[x.ravel(), y.ravel(), z.ravel()], tris, name="terrain")


class Floor:
    """The textbook floor: one hand-written program (per-pixel Phong, one directional
    light) drawing the mesh's indexed triangles, read back every frame."""

    VERT = """#version 330 core
    uniform mat4 u_mvp; in vec3 in_pos; in vec3 in_norm; out vec3 v_pos; out vec3 v_norm;
    void main() { v_pos = in_pos; v_norm = in_norm; gl_Position = u_mvp * vec4(in_pos, 1); }"""
    FRAG = """#version 330 core
    uniform vec3 u_eye; uniform vec3 u_light; in vec3 v_pos; in vec3 v_norm; out vec4 f;
    void main() { vec3 n = normalize(v_norm), v = normalize(u_eye - v_pos);
        float ln = dot(n, u_light); vec3 r = 2.0 * ln * n - u_light;
        float s = ln > 0.0 ? pow(max(dot(r, v), 0.0), 32.0) : 0.0;
        f = vec4(vec3(0.1 + 0.7 * max(ln, 0.0)) * vec3(0.8, 0.5, 0.3) + 0.5 * s, 1.0); }"""

    def __init__(self, ctx, mesh, size):
        import moderngl

        self.moderngl, self.ctx, self.size = moderngl, ctx, size
        self.prog = ctx.program(vertex_shader=self.VERT, fragment_shader=self.FRAG)
        tri, _ = mesh.triangles
        data = np.hstack([mesh.vertices, mesh.vertex_normals]).astype("f4")
        self.vao = ctx.vertex_array(self.prog, [(ctx.buffer(data), "3f 3f", "in_pos",
                                                 "in_norm")],
                                    ctx.buffer(tri.astype("u4")), 4)
        self.fbo = ctx.framebuffer([ctx.renderbuffer(size, 4)], ctx.depth_renderbuffer(size))
        self.prog["u_light"].value = tuple(np.array([1.0, 1.0, 1.0]) / np.sqrt(3))

    def frame(self, camera: Camera):
        vp = camera.projection_matrix(self.size[0] / self.size[1]) @ camera.view_matrix()
        self.prog["u_mvp"].write(np.ascontiguousarray(vp.T, "f4").tobytes())
        self.prog["u_eye"].value = tuple(camera.position)
        self.fbo.use()
        self.fbo.clear(0.0, 0.0, 0.0, 1.0, depth=1.0)
        self.ctx.enable(self.moderngl.DEPTH_TEST)
        self.ctx.disable(self.moderngl.CULL_FACE)
        self.vao.render()
        return self.fbo.read(components=4)


def big_mesh(n_triangles: int, rounds: int) -> str:
    mesh = terrain(n_triangles)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "terrain.ply"
        glshade.save_mesh(mesh, path, binary=True)
        del mesh
        start = time.perf_counter()
        mesh = glshade.load_mesh(path)
        load = time.perf_counter() - start
    scene = Scene()
    scene.add(mesh, Material(color=(0.8, 0.5, 0.3)))
    scene.add_light(glshade.DirectionalLight(direction=(-1.0, -1.0, -1.0)))
    whole = Camera.look_at((0.0, -1.9, 1.9), (0.0, 0.0, 0.0), fov_y=50).with_planes(
        scene.bounds)
    close = Camera.look_at((0.55, 0.55, 0.35), (0.75, 0.75, 0.0), fov_y=50).with_planes(
        scene.bounds)
    renderer = glshade.Renderer(640, 480, samples=0)
    start = time.perf_counter()
    renderer.render(scene, whole)
    first = time.perf_counter() - start
    start = time.perf_counter()
    renderer.render(scene, whole)
    upload = first - (time.perf_counter() - start)   # (the first draw less a later one)
    floor = Floor(renderer.ctx, mesh, (640, 480))
    floor.frame(whole)
    tri_count = mesh.n_faces
    series: dict[str, list] = {"glshade": [], "floor": [], "glshade, 10% in view": []}
    for _ in range(rounds):
        series["glshade"].append(fps_of(lambda: renderer.render(scene, whole), 2))
        series["floor"].append(fps_of(lambda: floor.frame(whole), 2))
        series["glshade, 10% in view"].append(fps_of(lambda: renderer.render(scene, close), 2))
    chunks = renderer.meshes.gpu_mesh(mesh).chunks
    n_chunks = 0 if chunks is None else len(chunks.starts) - 1
    renderer.render(scene, close)
    skipped = renderer.meshes.culled_chunks
    used = gpu_bytes(mesh)
    minimum = 24 * mesh.n_vertices + 12 * tri_count
    med = {name: statistics.median(v) for name, v in series.items()}
    renderer.close()
    rows = [(f"{tri_count:,} triangles", f"{load:.2f}", f"{upload:.2f}",
             f"{used / tri_count:.1f} ({used / minimum:.2f}x)", f"{med['glshade']:.2f}",
             f"{med['floor']:.2f}", f"{med['glshade'] / med['floor']:.2f}",
             f"{med['glshade, 10% in view']:.2f} ({skipped}/{n_chunks} chunks skipped)",
             f"{med['glshade, 10% in view'] / med['glshade']:.1f}x", f"{rss_mb():,.0f}")]
    return table(rows, ("mesh", "load s", "upload s", "GPU B/tri (vs min)", "fps",
                        "floor fps", "vs floor", "fps 10% in view", "speed-up",
                        "peak RSS MB"))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", default="1M,10M")
    parser.add_argument("--instances", type=int, default=10_000)
    parser.add_argument("--triangles", default="10M")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--no-peers", action="store_true")
    parser.add_argument("--only", default="clouds,instances,mesh")
    args = parser.parse_args()
    only = set(args.only.split(","))
    peer = start_peer(not args.no_peers)
    with glshade.Renderer(16, 16) as r:
        print(f"# {r.context.detail}; polyscope: "
              f"{'a worker process' if peer else 'not installed'}")
    if "clouds" in only:
        print("## point clouds, 1024x768")
        print(clouds([count(x) for x in args.points.split(",")], args.rounds, peer))
    if "instances" in only:
        print("\n## instances, 640x480 Phong")
        print(instances(args.instances, args.rounds, peer))
    if peer is not None:
        peer.close()
    if "mesh" in only:
        print("\n## a big mesh, 640x480 Phong")
        print(big_mesh(count(args.triangles), args.rounds))


if __name__ == "__main__":
    main()
