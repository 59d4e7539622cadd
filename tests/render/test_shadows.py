"""Cast shadows against a float64 numpy ray caster that shares no code with glshade: its
own pixel rays (from eye, target and field of view), closed-form intersections (a plane, a
box, a sphere, a box minus a cylinder's bore) and Moller-Trumbore over a torus's triangles.
The shadow of a sphere on a plane is the conic its closed form gives.

``exact``: every pixel whose 3x3 sub-pixel samples (its corners, edge midpoints and centre)
agree -- one surface, one answer for each light -- shows what the centre's ray finds: 0
mismatches outside that half-pixel band, at MSAA 0 and 4, EGL and OSMesa the same bytes."""

import os
import subprocess
import sys

import numpy as np
import pytest

import glshade as g
from glshade import quaternion as Q
from glshade.geometry import primitives as P
from glshade.solids.leaves import Box, Cylinder, Sphere
from tests.conftest import ROOT, require

W, H, FOV = 112, 84, 45.0
PLANE_HALF = 3.0
EPS = 1e-9

# ------------------------------------------------------------------ the oracle (float64)


def pixel_rays(eye, target, width, height, fov, offsets):
    """Unit directions ``(K, H, W, 3)`` through each pixel at sub-pixel ``offsets`` (K, 2),
    x right and y down from the pixel centre, for a camera at ``eye`` looking at
    ``target`` with y up."""
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    f = (target - eye) / np.linalg.norm(target - eye)
    r = np.cross(f, (0.0, 1.0, 0.0))
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    tan = np.tan(np.radians(fov) / 2)
    i = np.arange(width)[None, None, :] + 0.5 + offsets[:, 0, None, None]
    j = np.arange(height)[None, :, None] + 0.5 + offsets[:, 1, None, None]
    x = (2 * i / width - 1) * tan * width / height
    y = (1 - 2 * j / height) * tan
    d = f + x[..., None] * r + y[..., None] * u
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def hit_plane(o, d):
    """The quad y = 0, |x|, |z| <= PLANE_HALF: (t_in, t_out) as an interval of zero width."""
    with np.errstate(divide="ignore", invalid="ignore"):
        t = -o[..., 1] / d[..., 1]
    p = o + t[..., None] * d
    ok = (t > 0) & (np.abs(p[..., 0]) <= PLANE_HALF) & (np.abs(p[..., 2]) <= PLANE_HALF)
    t = np.where(ok, t, np.inf)
    return t, t


def slab(o, d, lo, hi):
    with np.errstate(divide="ignore", invalid="ignore"):
        t0, t1 = (np.asarray(lo) - o) / d, (np.asarray(hi) - o) / d
    tn = np.nan_to_num(np.minimum(t0, t1), nan=-np.inf).max(-1)
    tf = np.nan_to_num(np.maximum(t0, t1), nan=np.inf).min(-1)
    miss = tn > tf
    return np.where(miss, np.inf, tn), np.where(miss, -np.inf, tf)


def hit_sphere(o, d, c, r):
    oc = o - c
    b = np.einsum("...k,...k", oc, d)
    disc = b * b - (np.einsum("...k,...k", oc, oc) - r * r)
    s = np.sqrt(np.maximum(disc, 0))
    return np.where(disc > 0, -b - s, np.inf), np.where(disc > 0, -b + s, -np.inf)


def hit_bored(o, d, lo, hi, axis_xz, radius):
    """A box minus a vertical cylinder through it: the intervals' difference. Returns
    (box_in, box_out, bore_in, bore_out)."""
    a, b = slab(o, d, lo, hi)
    q = o[..., [0, 2]] - axis_xz
    e = d[..., [0, 2]]
    qa = np.einsum("...k,...k", e, e)
    qb = np.einsum("...k,...k", q, e)
    qc = np.einsum("...k,...k", q, q) - radius ** 2
    disc = qb * qb - qa * qc
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.sqrt(np.maximum(disc, 0))
        c0, c1 = (-qb - s) / qa, (-qb + s) / qa
    inside = qc < 0
    c0 = np.where(disc > 0, c0, np.where(inside & (qa == 0), -np.inf, np.inf))
    c1 = np.where(disc > 0, c1, np.where(inside & (qa == 0), np.inf, -np.inf))
    return a, b, c0, c1


def hit_triangles(o, d, tri, chunk=4096):
    """Nearest t > 0 of each ray against triangles ``(T, 3, 3)`` (Moller-Trumbore)."""
    o2, d2 = o.reshape(-1, 3), d.reshape(-1, 3)
    best = np.full(len(o2), np.inf)
    # only the rays that meet the triangles' bounding sphere ahead of their origin are
    # tested (a closed form: most of a picture's rays pass the object by)
    centre = tri.reshape(-1, 3).mean(0)
    radius = np.linalg.norm(tri.reshape(-1, 3) - centre, axis=1).max() * (1 + 1e-9) + 1e-9
    oc = o2 - centre
    dd2 = np.einsum("rk,rk->r", d2, d2)
    b = np.einsum("rk,rk->r", oc, d2)
    disc = b * b - dd2 * (np.einsum("rk,rk->r", oc, oc) - radius * radius)
    with np.errstate(invalid="ignore"):
        near = (disc >= 0) & (-b + np.sqrt(np.maximum(disc, 0)) >= 0)
    rays = np.flatnonzero(near)
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]

    def cross(a, b):
        return np.stack([a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
                         a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                         a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], -1)

    for s in range(0, len(rays), chunk):
        r = rays[s:s + chunk]
        oo, dd = o2[r, None], d2[r, None]
        pv = cross(dd, e2)
        det = np.einsum("rtk,tk->rt", pv, e1)
        with np.errstate(divide="ignore", invalid="ignore"):
            f = 1 / det
            sv = oo - tri[:, 0]
            u = f * np.einsum("rtk,rtk->rt", sv, pv)
            qv = cross(sv, e1)
            v = f * np.einsum("rtk,rtk->rt", dd, qv)
            t = f * np.einsum("rtk,tk->rt", qv, e2)
        ok = (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > EPS)
        best[r] = np.where(ok, t, np.inf).min(1)
    return best.reshape(o.shape[:-1])


class Oracle:
    """Objects the scene holds, each a function of rays -> (entry t, exit t)."""

    def __init__(self, kind):
        self.kind = kind

    def first_hit(self, o, d):
        """Nearest surface t and the object's index."""
        ts = [np.where(a > EPS, a, np.where(b > EPS, b, np.inf)) if not bored else
              _bored_first(*a_b) for (a, b, bored, a_b) in self._intervals(o, d)]
        ts = np.stack(ts)
        return ts.min(0), ts.argmin(0)

    def blocked(self, o, d, dist):
        """Whether anything lies on o + t d for t in (EPS, dist)."""
        out = np.zeros(o.shape[:-1], bool)
        for a, b, bored, a_b in self._intervals(o, d):
            if bored:
                box_in, box_out, c0, c1 = a_b
                lo, hi = np.maximum(box_in, EPS), np.minimum(box_out, dist)
                out |= (lo < hi) & ~((c0 <= lo) & (c1 >= hi))
            else:
                lo, hi = np.maximum(a, EPS), np.minimum(b, dist)
                out |= (lo <= hi) & np.isfinite(lo)
        return out

    def _intervals(self, o, d):
        t, _ = hit_plane(o, d)
        yield t, t, False, None
        if self.kind == "cube":
            a, b = slab(o, d, (-0.5, 0.0, -0.5), (0.5, 1.0, 0.5))
            yield a, b, False, None
        elif self.kind == "sphere":
            a, b = hit_sphere(o, d, np.array([0.0, 1.0, 0.0]), 0.6)
            yield a, b, False, None
        elif self.kind == "bored":
            parts = hit_bored(o, d, (-0.6, 0.2, -0.4), (0.6, 0.8, 0.4), np.array([0.1, 0.0]),
                              0.25)
            yield None, None, True, parts
        elif self.kind == "torus":
            t = hit_triangles(o, d, TORUS_TRIANGLES)
            yield t, t, False, None
        elif self.kind == "ball":
            t = hit_triangles(o, d, BALL_TRIANGLES)
            yield t, t, False, None


def _bored_first(box_in, box_out, c0, c1):
    """The first t > EPS where a ray meets a box minus a bore."""
    first = np.where((box_in > EPS) & ~((c0 <= box_in) & (box_in <= c1)), box_in, np.inf)
    exit_bore = np.where((c1 > EPS) & (c1 >= box_in) & (c1 <= box_out) &
                         ~((box_in > EPS) & ~((c0 <= box_in) & (box_in <= c1))), c1, np.inf)
    return np.where(box_in <= box_out, np.minimum(first, exit_bore), np.inf)


TORUS_ROTATION = Q.from_axis_angle((1, 0, 0.3), 0.6)
TORUS_MESH = P.torus(0.7, 0.22, 24, 12)
_tv = Q.rotate(TORUS_ROTATION, TORUS_MESH.vertices) + np.array([0.0, 1.1, 0.0])
TORUS_TRIANGLES = _tv[TORUS_MESH.triangles[0]]
#: a mesh sphere over the floor (a point light's cube map: the reported seam class)
BALL_MESH = P.icosphere(2, 0.6)
BALL_TRIANGLES = (BALL_MESH.vertices + np.array([0.0, 1.0, 0.0]))[BALL_MESH.triangles[0]]

LIGHTS = {"point": g.PointLight(position=(-1.2, 3.5, -1.0)),
          "directional": g.DirectionalLight(direction=(0.8, -1.5, 0.6))}
EYES = {"above": ((3.5, 4.0, 5.0), (0.0, 0.5, 0.0)),
        "grazing": ((4.0, 0.6, -3.5), (0.0, 0.3, 0.0))}
GRID = np.array([(x, y) for y in (-0.5, 0.0, 0.5) for x in (-0.5, 0.0, 0.5)])


def box_face(kind, p):
    """Which face of the scene's box a point lies on (0 to 5: the axis and side that are
    nearest the box's boundary), 6 on the bored block's bore; 0 for any other object (a
    sphere's or a torus's surface is one smooth face, the floor one plane)."""
    boxes = {"cube": ((0.0, 0.5, 0.0), (0.5, 0.5, 0.5)),
             "bored": ((0.0, 0.5, 0.0), (0.6, 0.3, 0.4))}
    if kind not in boxes:
        return np.zeros(p.shape[:-1], int)
    centre, half = (np.asarray(v) for v in boxes[kind])
    q = (p - centre) / half
    axis = np.abs(q).argmax(-1)
    side = np.take_along_axis(q, axis[..., None], -1)[..., 0] > 0
    face = 2 * axis + side
    if kind == "bored":  # (the bore: radius 0.25 about x = 0.1, z = 0)
        r = np.hypot(p[..., 0] - 0.1, p[..., 2])
        face = np.where(np.abs(r - 0.25) < np.abs(np.abs(q).max(-1) - 1) * half.min(), 6,
                        face)
    return face


def oracle_visibility(kind, eye, target, light, grid=GRID):
    """``(seen (H, W) bool, decided (H, W) bool, drawn (H, W) bool)`` at pixel centres;
    ``decided``: the 3x3 samples of ``grid`` (sub-pixel offsets, the centre in the middle)
    agree on the object and the face of it hit, and on the light's visibility."""
    o = np.broadcast_to(np.asarray(eye, float), (len(grid), H, W, 3))
    d = pixel_rays(eye, target, W, H, FOV, grid)
    oracle = Oracle(kind)
    t, which = oracle.first_hit(o, d)
    drawn = np.isfinite(t)
    p = o + np.where(drawn, t, 0)[..., None] * d
    if isinstance(light, g.PointLight):
        to = np.asarray(light.position) - p
        dist = np.linalg.norm(to, axis=-1)
        ld = to / dist[..., None]
    else:
        ld = np.broadcast_to(-np.asarray(light.direction), p.shape)
        dist = np.full(p.shape[:-1], np.inf)
    seen = ~oracle.blocked(p + 1e-7 * ld, ld, dist) & drawn
    centre = len(grid) // 2
    face = which * 8 + box_face(kind, p)
    agree = (face == face[centre]).all(0) & (seen == seen[centre]).all(0) & \
        (drawn == drawn[centre]).all(0)
    return seen[centre], agree & drawn[centre], drawn[centre]


# ------------------------------------------------------------------ the same scene in glshade


def scene_of(kind, light):
    s = g.Scene(ambient=(0.15, 0.15, 0.15), background=(0, 0, 0))
    s.add(P.plane(2 * PLANE_HALF), g.Material(color=(0.8, 0.8, 0.8)),
          rotation=Q.from_axis_angle((1, 0, 0), -np.pi / 2))
    if kind == "cube":
        s.add(P.cube(), g.Material(color=(0.9, 0.3, 0.2)), translation=(0, 0.5, 0))
    elif kind == "sphere":
        s.add(Sphere(0.6), g.Material(color=(0.3, 0.5, 0.9)), translation=(0, 1.0, 0))
    elif kind == "bored":
        bored = Box((1.2, 0.6, 0.8)) - Cylinder(0.25, 2.0).translated((0.1, 0.0, 0.0))
        s.add(bored, g.Material(color=(0.2, 0.7, 0.3)), translation=(0, 0.5, 0))
    elif kind == "torus":
        s.add(TORUS_MESH, g.Material(color=(0.7, 0.6, 0.2)), rotation=TORUS_ROTATION,
              translation=(0, 1.1, 0))
    elif kind == "ball":
        s.add(BALL_MESH, g.Material(color=(0.3, 0.5, 0.9)), translation=(0, 1.0, 0))
    s.add_light(light)
    return s


def light_and_eye(elevation, azimuth, eye_elevation, eye_azimuth, distance, point):
    """A sweep's light -- ``elevation`` and ``azimuth`` in degrees above the floor: a point
    light 5 units away that way, or a directional one from there -- and its eye, looking at
    the object's middle from ``distance`` at ``eye_elevation``, ``eye_azimuth``: ``(light,
    eye, target)``."""
    e, a = np.radians(elevation), np.radians(azimuth)
    towards = np.array([np.cos(e) * np.cos(a), np.sin(e), np.cos(e) * np.sin(a)])
    light = g.PointLight(position=tuple(5.0 * towards + (0, 0.5, 0))) if point else \
        g.DirectionalLight(direction=tuple(-towards))
    ee, ea = np.radians(eye_elevation), np.radians(eye_azimuth)
    target = (0.0, 0.5, 0.0)
    eye = tuple(np.array(target) + distance * np.array(
        [np.cos(ee) * np.cos(ea), np.sin(ee), np.cos(ee) * np.sin(ea)]))
    return light, eye, target


@pytest.fixture(scope="module")
def renderers(gl_context):
    from glshade.render.renderer import Renderer

    made = {s: Renderer(W, H, samples=s, context=gl_context) for s in (0, 4)}
    yield made
    for r in made.values():
        r.close()


#: the torus's cases are the costliest (its many thin shadows): they run once, on EGL; the
#: other kinds run on every backend
TORUS_ONCE = pytest.param("torus", marks=pytest.mark.once)


@pytest.mark.parametrize("eye", sorted(EYES))
@pytest.mark.parametrize("light", sorted(LIGHTS))
@pytest.mark.parametrize("kind", ["cube", "sphere", TORUS_ONCE, "bored"])
def test_exact_shadows_match_the_ray_cast_oracle(renderers, kind, light, eye):
    from tests.oracle.neighbours import inside_regions

    position, target = EYES[eye]
    seen, decided, drawn = oracle_visibility(kind, position, target, LIGHTS[light])
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    scene = scene_of(kind, LIGHTS[light])
    for samples, r in renderers.items():
        frame = r.render_frame(scene, camera, "phong", shadows="exact")
        got = frame.visibility[..., 0] > 0.5
        gpu_drawn = frame.face_id >= 0
        assert ((gpu_drawn != drawn) & decided).sum() == 0, (samples, "coverage")
        wrong = (got != seen) & decided
        assert wrong.sum() == 0, (samples, np.argwhere(wrong)[:10].tolist(),
                                  int(decided.sum()))
        # the test sees both answers in the picture: shadowed and lit pixels
        lit, dark = int((seen & decided).sum()), int((~seen & decided & drawn).sum())
        assert lit > 200 and dark > 100, (lit, dark)
        # a plain render traces as it shades (no visibility to read): its picture is this
        # one's at every pixel the oracle decides -- under MSAA away from polygon edges,
        # where each polygon's fragment answers for its own samples (at the terminator of
        # a coarse torus, a neighbour that faces away from the light is dark by its own
        # plane) and the G-buffer's pixel centre answers for them all
        forward = r.render(scene, camera, "phong", shadows="exact")
        off = np.abs(forward.astype(int) - frame.color.astype(int)).max(-1) > 1
        if samples:
            off &= inside_regions(frame.face_id)
        assert (off & decided).sum() == 0, (samples, np.argwhere(off & decided)[:10].tolist())


def test_the_shadow_of_a_sphere_on_a_plane_is_its_conic(renderers):
    """Closed form: a plane point P is dark where the segment P -> light passes within the
    sphere's radius of its centre (a quadratic's discriminant); the boundary is a conic."""
    light = LIGHTS["point"]
    position, target = EYES["above"]
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    frame = renderers[0].render_frame(scene_of("sphere", light), camera, "flat",
                                      shadows="exact")
    d = pixel_rays(position, target, W, H, FOV, np.zeros((1, 2)))[0]
    t = -position[1] / d[..., 1]
    p = np.asarray(position) + t[..., None] * d          # the plane y = 0 under each pixel
    on_plane = (t > 0) & (frame.face_id == 0)             # (polygon 0: the plane)
    L, c, r = np.asarray(light.position), np.array([0.0, 1.0, 0.0]), 0.6
    u = (L - p) / np.linalg.norm(L - p, axis=-1, keepdims=True)
    along = np.einsum("...k,...k", c - p, u)
    gap2 = np.einsum("...k,...k", c - p, c - p) - along ** 2
    margin = np.sqrt(np.abs(gap2)) - r                    # signed distance to the cone
    pixel = np.linalg.norm(p - position, axis=-1) * 2 * np.tan(np.radians(FOV) / 2) / H
    dark = (gap2 < r * r) & (along > 0)
    clear = np.abs(margin) > pixel * 2                    # beyond a pixel of the boundary
    got = frame.visibility[..., 0] < 0.5
    assert (on_plane & clear).sum() > 2000 and (on_plane & clear & dark).sum() > 100
    assert ((got != dark) & on_plane & clear).sum() == 0


@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong"])
def test_a_shadowed_pixel_is_the_render_of_the_lights_it_sees(renderers, mode):
    """Two lights: each pixel equals, within a level, the render with only the lights its
    point sees (ambient always)."""
    position, target = EYES["above"]
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    a, b = LIGHTS["point"], g.DirectionalLight(direction=(0.9, -1.4, -0.3),
                                               color=(0.5, 0.4, 0.3))
    scene = scene_of("cube", a)
    scene.add_light(b)
    r = renderers[0]
    frame = r.render_frame(scene, camera, mode, shadows="exact", color_dtype="f4")
    vis = frame.visibility > 0.5
    alone = {}
    for name, lights in {"ab": [a, b], "a": [a], "b": [b], "": []}.items():
        only = scene_of("cube", a)
        only.lights.clear()
        for x in lights:
            only.add_light(x)
        if not lights:  # (ambient alone: a light of no intensity)
            only.add_light(g.PointLight(position=a.position, intensity=0.0))
        alone[name] = r.render_frame(only, camera, mode, color_dtype="f4").color
    sees_a, sees_b = vis[..., 0:1], vis[..., 1:2]
    expected = np.where(sees_a & sees_b, alone["ab"],
                        np.where(sees_a, alone["a"], np.where(sees_b, alone["b"], alone[""])))
    drawn = frame.face_id >= 0
    assert vis[drawn].all(-1).any() and (~vis[drawn]).any()
    assert np.abs(frame.color - expected)[drawn].max() <= 1.5 / 255


@pytest.mark.parametrize("elevation", [1.0, 3.0, 10.0, 30.0, 60.0, 89.0])
def test_no_acne_on_a_convex_mesh_lit_at_any_elevation(make_renderer, elevation):
    """A convex polyhedron alone, lit from 1 to 89 degrees above its equator: no pixel
    whose polygon faces the light is in shadow (nothing else is there to cast one)."""
    mesh = P.icosphere(2)
    scene = g.Scene()
    scene.add(mesh, g.Material(color=(0.8, 0.8, 0.8)))
    e = np.radians(elevation)
    light = g.DirectionalLight(direction=(-np.cos(e), -np.sin(e), -0.0))
    scene.add_light(light)
    r = make_renderer(160, 120)
    for eye in ((0.0, 0.5, 3.5), (3.2, 0.2, 1.0)):
        camera = g.Camera.look_at(eye, (0, 0, 0))
        frame = r.render_frame(scene, camera, "flat", shadows="exact")
        facing = np.einsum("hwk,k->hw", frame.normal, -np.asarray(light.direction)) > 1e-6
        hidden = frame.visibility[..., 0] < 0.5
        assert facing.sum() > 500
        assert (facing & hidden).sum() == 0, elevation


def test_a_light_may_cast_no_shadows(make_renderer):
    position, target = EYES["above"]
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    light = g.PointLight(position=(1.5, 4.0, 1.2), shadows=False)
    r = make_renderer(W, H)
    frame = r.render_frame(scene_of("cube", light), camera, "phong", shadows="exact")
    plain = r.render(scene_of("cube", light), camera, "phong")
    assert (frame.visibility == 1).all()
    assert np.array_equal(frame.color, plain)


SNIPPET = """
import sys
import numpy as np
sys.path.insert(0, '.')
from tests.render.test_shadows import scene_of, LIGHTS, EYES, FOV, W, H
import glshade as g
position, target = EYES["above"]
camera = g.Camera.look_at(position, target, fov_y=FOV)
with g.Renderer(W, H, samples=0, backend=sys.argv[1]) as r:
    out = [r.render(scene_of(k, LIGHTS["point"]), camera, m, shadows="exact")
           for k in ("cube", "sphere") for m in ("flat", "phong")]
    print(r.backend)  # (the front-end that really drew: no fallback, no override)
np.save(sys.argv[2], np.stack(out))
"""


def test_egl_and_osmesa_give_the_same_bytes(tmp_path):
    """The same shadowed pictures through EGL and through OSMesa, each in a process of its
    own that says which front-end it drew with. (Here both front-ends drive Mesa's
    llvmpipe: what this proves is that the context, its framebuffers and its programs are
    made alike through either -- not that two rasterizers agree.)"""
    images = {}
    for backend in ("egl", "osmesa"):
        path = tmp_path / f"{backend}.npy"
        out = subprocess.run([sys.executable, "-c", SNIPPET, backend, str(path)],
                             capture_output=True, text=True, cwd=ROOT, timeout=300,
                             env={**os.environ, "GLSHADE_BACKEND": ""})
        assert out.returncode == 0, out.stderr
        assert out.stdout.split() == [backend], out.stdout  # (not the other, by fallback)
        images[backend] = np.load(path)
    assert np.array_equal(images["egl"], images["osmesa"])


@pytest.mark.parametrize("kind, light, eye", [
    *[pytest.param(k, light, eye, marks=[pytest.mark.once] if k == "torus" else [])
      for k in ("cube", "torus") for light in sorted(LIGHTS) for eye in sorted(EYES)],
    ("ball", "point", "above"), ("ball", "point", "grazing")])  # (a cube map's seams)
def test_map_shadows_differ_only_within_their_band(renderers, kind, light, eye):
    """Shadow maps against the same oracle: every pixel whose polygon faces the light and
    whose samples agree across a half pixel plus the band -- the texel footprint (from the
    draw's own report) times 1 + the PCF radius, plus a texel of bias -- matches."""
    from glshade.render.passes import shadow_maps

    position, target = EYES[eye]
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    scene = scene_of(kind, LIGHTS[light])
    r = renderers[0]
    frame = r.render_frame(scene, camera, "phong", shadows="map")
    (faces, size, footprint), = r.shadow_pass.maps.facts
    assert (faces, size) == ((6, shadow_maps.CUBE_SIZE) if light == "point" else
                             (1, shadow_maps.MAP_SIZE))
    assert 0 < footprint < 1  # (a texel smaller than a pixel at these sizes)
    band = 0.5 + footprint * (2 + shadow_maps.PCF_RADIUS)
    wrong, shadowed = _map_band_mismatches(r, scene, frame, kind, position, target,
                                           LIGHTS[light], band, eye == "above")
    assert wrong.sum() == 0, np.argwhere(wrong)[:10].tolist()
    # (shadows were there to find: at a grazing eye a thin band, undecided near its edges)
    assert shadowed > (20 if eye == "above" else 0)


def _map_band_mismatches(r, scene, frame, kind, position, target, light, band, above=True):
    """Pixels where the map's visibility differs from the oracle's outside ``band`` pixels
    of a shadow's boundary, on polygons facing the light; and the shadowed pixels the
    oracle decided (drawn ones where not ``above``)."""
    wide = np.array([(x, y) for y in (-band, 0.0, band) for x in (-band, 0.0, band)])
    seen, decided, drawn = oracle_visibility(kind, position, target, light, wide)
    flat = r.render_frame(scene, g.Camera.look_at(position, target, fov_y=FOV), "flat")
    if isinstance(light, g.PointLight):
        to = np.asarray(light.position) - _points(position, target, frame.depth)
    else:
        to = np.broadcast_to(-np.asarray(light.direction), flat.normal.shape)
    to = to / np.linalg.norm(to, axis=-1, keepdims=True)
    # (where the light lies within a level of the polygon's plane -- N.L under 2/255 -- its
    # term is under a level: seen or hidden are both right, as in the exact sweep)
    facing = np.einsum("hwk,hwk->hw", flat.normal, to) > 2 / 255
    got = frame.visibility[..., 0] > 0.5
    wrong = (got != seen) & decided & facing
    return wrong, int((~seen & (decided if above else drawn) & facing).sum())


def _points(eye, target, depth):
    """World points of the pixel centres at view-axis ``depth`` (H, W)."""
    d = pixel_rays(eye, target, W, H, FOV, np.zeros((1, 2)))[0]
    f = np.asarray(target, float) - eye
    f /= np.linalg.norm(f)
    t = np.where(np.isfinite(depth), depth, 0) / (d @ f)
    return np.asarray(eye, float) + t[..., None] * d


@pytest.mark.parametrize("method", ["exact", "map"])
def test_patches_cast_and_receive(renderers, method):
    """A patch sphere (rational, GPU-tessellated) casts the sphere's conic on the floor, up
    to its tessellation (a few pixels' band); its own lit side stays lit."""
    from glshade.patches import sphere

    light = LIGHTS["point"]
    position, target = EYES["above"]
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    scene = scene_of("cube", light)
    scene.models.pop()  # (the cube out: the floor alone, then the patch sphere)
    scene.add(sphere(), g.Material(color=(0.3, 0.5, 0.9)), translation=(0, 1.0, 0),
              scale=0.6)
    frame = renderers[0].render_frame(scene, camera, "phong", shadows=method)
    d = pixel_rays(position, target, W, H, FOV, np.zeros((1, 2)))[0]
    p = np.asarray(position) + (-position[1] / d[..., 1])[..., None] * d
    L, c, r = np.asarray(light.position), np.array([0.0, 1.0, 0.0]), 0.6
    u = (L - p) / np.linalg.norm(L - p, axis=-1, keepdims=True)
    along = np.einsum("...k,...k", c - p, u)
    gap = np.sqrt(np.abs(np.einsum("...k,...k", c - p, c - p) - along ** 2))
    pixel = np.linalg.norm(p - position, axis=-1) * 2 * np.tan(np.radians(FOV) / 2) / H
    dark = (gap < r) & (along > 0)
    clear = np.abs(gap - r) > 3 * pixel
    floor = frame.face_id == 0
    got = frame.visibility[..., 0] < 0.5
    assert (floor & clear & dark).sum() > 100
    assert ((got != dark) & floor & clear).sum() == 0
    on_sphere = frame.face_id >= 1
    normal = frame.normal[on_sphere]
    points = _points(position, target, frame.depth)[on_sphere]
    facing = np.einsum("nk,nk->n", normal, L - points) > 0.3 * np.linalg.norm(L - points,
                                                                               axis=1)
    assert facing.sum() > 30 and (frame.visibility[on_sphere][facing, 0] > 0.5).all()


def test_an_orthographic_camera_shadows_where_the_oracle_does(renderers):
    """Orthographic views rebuild their points along parallel rays: on the floor, exact
    shadows match the oracle's box (outside a pixel of its edges) and maps agree with them."""
    light = LIGHTS["directional"]
    position, target = np.asarray(EYES["above"][0]), np.asarray(EYES["above"][1])
    scene = scene_of("cube", light)
    height = 6.0
    camera = g.Camera.look_at(position, target, fov_y=FOV).replace(
        projection="orthographic", height=height)
    frames = {m: renderers[0].render_frame(scene, camera, "phong", shadows=m)
              for m in ("exact", "map")}
    f = (target - position) / np.linalg.norm(target - position)
    r = np.cross(f, (0.0, 1.0, 0.0))
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    px = height / H
    x = ((np.arange(W) + 0.5) - W / 2) * px
    y = (H / 2 - (np.arange(H) + 0.5)) * px
    origin = position + x[None, :, None] * r + y[:, None, None] * u
    t = -origin[..., 1] / f[1]
    p = origin + t[..., None] * f                        # the floor under each pixel
    to = np.broadcast_to(-np.asarray(light.direction), p.shape)
    dark = Oracle("cube").blocked(p + 1e-7 * to, to, np.full(p.shape[:-1], np.inf))
    # (a pixel's width on the floor, along the light: the band where a pixel straddles)
    near_edge = np.zeros_like(dark)
    for axis in (0, 1):
        for step in (1, -1):
            near_edge |= np.roll(dark, step, axis) != dark
    floor = frames["exact"].face_id == 0
    exact = frames["exact"].visibility[..., 0] < 0.5
    assert (floor & dark & ~near_edge).sum() > 50
    assert ((exact != dark) & floor & ~near_edge).sum() == 0
    mapped = frames["map"].visibility[..., 0] < 0.5
    assert ((mapped != exact) & floor & ~near_edge).sum() == 0


def test_a_surface_made_transparent_stops_casting(renderers):
    """The occluders are rebuilt when a model's opacity changes, not only its geometry (the
    BVH was keyed on meshes and transforms alone)."""
    light = LIGHTS["point"]
    position, target = EYES["above"]
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    scene = scene_of("cube", light)
    r = renderers[0]

    def dark_floor():
        frame = r.render_frame(scene, camera, "phong", shadows="exact")
        return int(((frame.visibility[..., 0] < 0.5) & (frame.face_id == 0)).sum())

    before = dark_floor()
    cube = scene.models[1]
    cube.material = g.Material(color=(0.9, 0.3, 0.2), opacity=0.5)
    assert before > 100 and dark_floor() == 0
    cube.material = g.Material(color=(0.9, 0.3, 0.2))
    assert dark_floor() == before


require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import assume, example, given, settings, strategies as st  # noqa: E402


@settings(max_examples=60)
@given(kind=st.sampled_from(["cube", "sphere", "bored"]),
       elevation=st.floats(2.0, 88.0), azimuth=st.floats(0.0, 360.0),
       eye_elevation=st.floats(3.0, 80.0), eye_azimuth=st.floats(0.0, 360.0),
       distance=st.floats(2.0, 9.0), point=st.booleans())
def test_exact_shadows_over_lights_and_eyes(renderers, kind, elevation, azimuth,
                                            eye_elevation, eye_azimuth, distance, point):
    """The oracle sweep over the range: a mesh or a CSG solid (a sphere, a bored block),
    lights from 2 to 88 degrees above the floor at any azimuth (directional, or a point
    light 5 units away that way), eyes from grazing to high at any azimuth and distance,
    inside the scene's box too (its fitted near plane then tiny); 0 mismatches outside the
    half-pixel band."""
    light, position, target = light_and_eye(elevation, azimuth, eye_elevation, eye_azimuth,
                                            distance, point)
    seen, decided, drawn = oracle_visibility(kind, position, target, light)
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    frame = renderers[0].render_frame(scene_of(kind, light), camera, "phong",
                                      shadows="exact")
    assert ((frame.face_id >= 0) != drawn)[decided].sum() == 0
    # (where the light lies within a level of the surface's own plane -- N.L under 2/255 --
    # its term is under a level, and the ray runs along the face: seen or hidden are both
    # right, and neither shows)
    flat = renderers[0].render_frame(scene_of(kind, light), camera, "flat").normal
    to = np.asarray(light.position) - _points(position, target, frame.depth) if point \
        else np.broadcast_to(-np.asarray(light.direction), flat.shape)
    to = to / np.linalg.norm(to, axis=-1, keepdims=True)
    decided &= np.abs(np.einsum("hwk,hwk->hw", flat, to)) > 2 / 255
    wrong = ((frame.visibility[..., 0] > 0.5) != seen) & decided
    assert wrong.sum() == 0, np.argwhere(wrong)[:5].tolist()
    # the plain render (traced as it shades) is this picture wherever the oracle decides
    forward = renderers[0].render(scene_of(kind, light), camera, "phong", shadows="exact")
    off = np.abs(forward.astype(int) - frame.color.astype(int)).max(-1) > 1
    assert (off & decided).sum() == 0, np.argwhere(off & decided)[:5].tolist()


@pytest.mark.parametrize("light", sorted(LIGHTS))
@pytest.mark.parametrize("kind", ["cube", "sphere", "torus", "bored"])
@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong"])
@pytest.mark.filterwarnings("ignore:CSG solids receive map shadows")
def test_forward_map_lookups_are_the_g_buffers(renderers, kind, light, mode):
    """``render`` looks the maps up in the fragment stage (no G-buffer: SHADOW_MAPS_FORWARD);
    ``render_frame`` through the G-buffer, to read the visibility back. Same maps, same
    lookup (shadow_lookup.glsl), so the same picture: within 1/255 except at most a few
    pixels (where the two surface points differ by a rounding at a shadow's edge), for
    meshes, CSG solids (which receive map shadows), every mode, both light kinds, MSAA and
    an orthographic view. (Under MSAA a silhouette pixel's two surfaces each get their own
    visibility forward, the pixel centre's through the G-buffer: silhouettes are left out.)"""
    scene = scene_of(kind, LIGHTS[light])
    eye, target = EYES["above"]
    for samples, camera in ((0, g.Camera.look_at(eye, target, fov_y=FOV)),
                            (4, g.Camera.look_at(eye, target).replace(
                                projection="orthographic", height=5.0))):
        r = renderers[samples]
        forward = r.render(scene, camera, mode, shadows="map")
        frame = r.render_frame(scene, camera, mode, shadows="map")
        d = np.abs(forward.astype(int) - frame.color.astype(int)).max(-1)
        from tests.oracle.neighbours import inside_regions

        d = d[inside_regions(frame.face_id)]
        assert (d > 1).sum() <= 0.002 * d.size, ((d > 1).sum(), d.max())
        if kind in ("cube", "torus"):  # (CSG solids cast no map shadows: they receive them)
            plain = r.render(scene, camera, mode)
            assert (plain.astype(int) - forward.astype(int)).max() > 40


@pytest.mark.parametrize("method", ["map", "exact"])
def test_forward_shadows_on_a_textured_mesh_and_gpu_patches(make_renderer, method):
    """Textured meshes (their own program variant) and GPU-tessellated patches (no mesh
    polygon: nothing of theirs skipped by a ray) find their shadows as they shade too --
    maps looked up, rays traced -- as the G-buffer's points do."""
    from glshade.patches import named

    scene = g.Scene(ambient=(0.2, 0.2, 0.2))
    scene.add(P.plane(6.0), g.Material(texture=g.Texture(np.full((2, 2, 3), 230, np.uint8))),
              rotation=Q.from_axis_angle((1, 0, 0), -np.pi / 2))
    scene.add(named("teapot"), g.Material(color=(0.8, 0.5, 0.3)), tessellation="gpu",
              level=6, scale=0.5)
    scene.add_light(g.PointLight((2.0, 5.0, 1.0)))
    camera = g.Camera.look_at((4, 4, 5), (0, 0.5, 0))
    r = make_renderer(96, 72, samples=0)
    forward = r.render(scene, camera, "phong", shadows=method)
    through = r.render_frame(scene, camera, "phong", shadows=method).color
    d = np.abs(forward.astype(int) - through.astype(int)).max(-1)
    assert (d > 1).sum() <= 0.002 * d.size
    assert (r.render(scene, camera, "phong").astype(int) - forward.astype(int)).max() > 40


@pytest.mark.parametrize("eye", sorted(EYES))
@pytest.mark.parametrize("kind", ["cube", "torus", "sphere"])
@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong"])
def test_forward_rays_are_the_g_buffers(renderers, monkeypatch, kind, mode, eye):
    """``render`` traces each fragment's own rays as it shades (no G-buffer:
    SHADOW_RAYS_FORWARD) where no CSG solid casts; ``render_frame`` traces the G-buffer's
    points in a compute pass (shadow_rays.comp), whose visibility the oracle tests check.
    One traversal (shadow_trace.glsl), so the same picture: within 1/255 except at most a
    few pixels (the two surface points differ by a rounding at a shadow's edge), under both
    lights at once (one fragment shares one loop budget among them), every mode, MSAA and
    an orthographic view. A scene with a solid ("sphere") takes the compute pass both ways.
    (Under MSAA a silhouette pixel's surfaces each trace forward: silhouettes left out.)"""
    from glshade.render.passes.shadows import ShadowPass
    from tests.oracle.neighbours import inside_regions

    traced = []
    trace = ShadowPass._trace
    monkeypatch.setattr(ShadowPass, "_trace", lambda *a: traced.append(1) or trace(*a))
    scene = scene_of(kind, LIGHTS["point"])
    scene.add_light(LIGHTS["directional"])
    position, target = EYES[eye]
    for samples, camera in ((0, g.Camera.look_at(position, target, fov_y=FOV)),
                            (4, g.Camera.look_at(position, target).replace(
                                projection="orthographic", height=5.0))):
        r = renderers[samples]
        traced.clear()
        forward = r.render(scene, camera, mode, shadows="exact")
        # (without storage buffers a fragment cannot count its rays that ran out: the
        # G-buffer's pass traces them)
        assert bool(traced) == (kind == "sphere" or not r.context.features.storage)
        frame = r.render_frame(scene, camera, mode, shadows="exact")
        d = np.abs(forward.astype(int) - frame.color.astype(int)).max(-1)
        d = d[inside_regions(frame.face_id)]
        assert (d > 1).sum() <= 0.002 * d.size, ((d > 1).sum(), d.max())
        shadowed = (frame.visibility < 0.5).any(-1) & (frame.face_id > 0)
        assert shadowed.sum() > 50  # (there were shadows to agree on)


@pytest.mark.parametrize("through", ["forward", "g-buffer"])
def test_rays_that_run_out_are_counted_and_shown_seen(renderers, monkeypatch, through):
    """A ray past its loop budget (llvmpipe's limit, here made tiny) is never silent: a
    RenderWarning with the count, ``shadow_pass.undecided``, and its light shown as seen."""
    from glshade.errors import RenderWarning
    from glshade.render.passes import shadows

    scene = scene_of("torus", LIGHTS["point"])
    position, target = EYES["above"]
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    r = renderers[0]
    draw = r.render if through == "forward" else (
        lambda *a, **k: r.render_frame(*a, **k).color)
    full = draw(scene, camera, "phong", shadows="exact")
    assert r.shadow_pass.undecided == 0
    monkeypatch.setattr(shadows, "RAY_BUDGET", 2)
    with pytest.warns(RenderWarning, match=r"shadow rays ran past"):
        cut = draw(scene, camera, "phong", shadows="exact")
    assert r.shadow_pass.undecided > 100
    lit = r.render(scene, camera, "phong")
    # (every changed pixel went from the shadowed colour to the lit one)
    changed = np.abs(cut.astype(int) - full.astype(int)).max(-1) > 1
    assert changed.sum() > 50
    assert (np.abs(cut[changed].astype(int) - lit[changed].astype(int)) <= 1).all()


@pytest.mark.parametrize("tier", ["4.1", "3.3"])
def test_an_older_gl_casts_shadows_or_is_told_what_to_use(gl_context, tier):
    """Without compute shaders (a context held to 4.1 or 3.3) exact shadows are traced by
    fragment programs, with the visibility of this driver's own tier bit for bit; maps need
    GL 4.0 (their lookups index sampler arrays): at 3.3 one line names the version and the
    way that works, and a plain draw still works."""
    from glshade.render.context import create_context
    from glshade.render.renderer import Renderer
    from tests.conftest import BACKEND

    scene = scene_of("cube", LIGHTS["point"])
    camera = g.Camera.look_at(*EYES["above"], fov_y=FOV)
    got = {}
    for held in (None, tier):
        with create_context(BACKEND, tier=held) as context:
            r = Renderer(32, 24, context=context)
            got[held] = {m: r.render_frame(scene, camera, "phong", shadows=m).visibility
                         for m in (("exact", "map") if held != "3.3" else ("exact",))}
            if held == "3.3":
                with pytest.raises(g.errors.EnvironmentFailure,
                                   match=r"shadows='map' needs OpenGL 4\.0; this GL is 3\.3 "
                                         r".*use shadows='exact'"):
                    r.render(scene, camera, "phong", shadows="map")
                assert r.render(scene, camera, "phong").shape == (24, 32, 4)
            r.close()
    for method, visibility in got[tier].items():
        assert np.array_equal(visibility, got[None][method]), method
    assert (got[tier]["exact"] == 0).any() and (got[tier]["exact"] == 1).any()


@pytest.mark.once  # (the lookup is one GLSL file: the backend tier runs the band tests)
@settings(max_examples=12, deadline=None)
@example(kind="cube", elevation=72.9, azimuth=318.8, reach=4.64, eye_elevation=22.2,
         eye_azimuth=276.7, distance=4.85)  # (the smooth normal's bias: a row of 27 px)
@example(kind="cube", elevation=12.2, azimuth=100.0, reach=1.98, eye_elevation=29.8,
         eye_azimuth=55.0, distance=7.04)  # (the top face 0.5 degrees from edge-on: 19 px)
@given(kind=st.sampled_from(["ball", "cube"]),  # (the torus: the band tests above)
       elevation=st.floats(3.0, 85.0), azimuth=st.floats(0.0, 360.0),
       reach=st.floats(0.9, 6.0), eye_elevation=st.floats(5.0, 75.0),
       eye_azimuth=st.floats(0.0, 360.0), distance=st.floats(4.0, 8.0))
def test_cube_map_shadows_over_lights_and_eyes(renderers, kind, elevation, azimuth, reach,
                                               eye_elevation, eye_azimuth, distance):
    """The map's band swept (the cube-map class: 7.2 px off on a sphere over a plane was
    reported): a point light anywhere above the object, from just off its surface (0.9
    from its middle: the light's texels small, faces near its terminator or level with it
    lit at a grazing angle) to 6 units off (shadows cross the cube map's faces and seams at
    every angle, the floor grazing to steep), eyes at any azimuth; outside the band the map
    promises -- a half pixel plus the texel footprint times 2 + the PCF radius -- 0
    mismatches with the exact ray cast. What it found: the bias took the surface's slope
    from the shading normal, which on a smooth mesh (a cube of 8 vertices, a sphere) bends
    towards the light near a crease; a lit face grazing the light then shaded itself along
    its edge (27 px in a row). The slope now comes from the polygon's own plane. Then: a
    face within 7 degrees of edge-on to the light (past the bias's slope cap, tan 8) shaded
    itself in bands -- a cube's top with the light level with it, a sphere's facets at its
    terminator (8 px from any boundary at 448 x 336); past the cap the point now moves
    off its plane by what the cap left (a normal offset)."""
    from glshade.render.passes import shadow_maps

    e, a = np.radians(elevation), np.radians(azimuth)
    at = reach * np.array([np.cos(e) * np.cos(a), np.sin(e), np.cos(e) * np.sin(a)]) + \
        (0.0, 0.6, 0.0)
    # (outside the object: the ball of 0.6 about (0, 1, 0), the cube [-0.5, 0.5]^2 x [0, 1])
    assume(np.linalg.norm(at - (0.0, 1.0, 0.0)) > 0.65 if kind == "ball" else
           (np.abs(at - (0.0, 0.5, 0.0)) > 0.55).any())
    light = g.PointLight(position=tuple(at))
    ee, ea = np.radians(eye_elevation), np.radians(eye_azimuth)
    target = (0.0, 0.5, 0.0)
    position = tuple(np.array(target) + distance * np.array(
        [np.cos(ee) * np.cos(ea), np.sin(ee), np.cos(ee) * np.sin(ea)]))
    camera = g.Camera.look_at(position, target, fov_y=FOV)
    scene = scene_of(kind, light)
    r = renderers[0]
    frame = r.render_frame(scene, camera, "phong", shadows="map")
    (_, _, footprint), = r.shadow_pass.maps.facts
    band = 0.5 + footprint * (2 + shadow_maps.PCF_RADIUS)
    wrong, _ = _map_band_mismatches(r, scene, frame, kind, position, target, light, band)
    assert wrong.sum() == 0, (band, np.argwhere(wrong)[:10].tolist())
