"""Renderer behaviour against formulas, geometry and invariants."""

import warnings

import numpy as np
import pytest

from glshade import Camera, Mesh
from glshade.errors import RenderWarning
from glshade.geometry import primitives as P
from glshade.scene import DirectionalLight, Material, PointLight, Scene
from tests.oracle.raycast import hit_ellipsoid, pixel_rays, render_ellipsoid, shade

EPS8 = 1 / 255 + 1e-6
EYE = np.array([0.0, 0.0, 3.0])
FRONT = Camera.look_at(EYE, [0, 0, 0], fov_y=50.0)


def quad_scene(mat, lights, ambient=(1, 1, 1)):
    s = Scene(ambient=ambient)
    s.add(P.plane(2.0), mat)
    for light in lights:
        s.add_light(light)
    return s


# ------------------------------------------------------------------------ lighting terms

@pytest.mark.parametrize("term", ["ka", "kd", "ks"])
def test_single_terms_match_formula_at_centre(make_renderer, term):
    coeffs = {"ka": 0.0, "kd": 0.0, "ks": 0.0, term: 0.8}
    mat = Material(color=(0.9, 0.6, 0.3), shininess=8, **coeffs)
    light = (1.0, 0.5, 3.0)
    img = make_renderer(32, 32).render(quad_scene(mat, [PointLight(light)]), FRONT, "flat")
    expected = shade(np.zeros(3), np.array([0.0, 0, 1]), EYE, [(light, (1, 1, 1))], mat)
    np.testing.assert_allclose(img[16, 16, :3] / 255, expected, atol=EPS8)
    assert expected.max() > 0.1  # the term is really there


def test_light_behind_surface_gives_ambient_only(make_renderer):
    mat = Material(color=(0.5, 0.5, 0.5), ka=0.3, kd=0.7, ks=0.9)
    scene = quad_scene(mat, [PointLight((0.0, 0.0, -3.0))])
    for mode in ("flat", "gouraud", "phong"):
        img = make_renderer(16, 16).render(scene, FRONT, mode)
        np.testing.assert_allclose(img[4:12, 4:12, :3] / 255, 0.15, atol=EPS8)


def test_lights_sum_and_colours_multiply(make_renderer):
    mat = Material(color=(0.5, 0.25, 1.0), ka=0.1, kd=0.5, ks=0.3, shininess=4)
    a = PointLight((2.0, 0.0, 2.0), color=(1.0, 0.5, 0.5))
    b = DirectionalLight((0.5, 1.0, -1.0), color=(0.2, 1.0, 0.4), intensity=0.5)
    r = make_renderer(16, 16)

    def centre(lights, ambient=(1, 1, 1)):
        f = r.render_frame(quad_scene(mat, lights, ambient), FRONT, "flat", color_dtype="f4")
        return f.color[8, 8, :3].astype(float)

    amb = np.asarray(mat.color) * mat.ka
    both = centre([a, b])
    np.testing.assert_allclose(both - amb, (centre([a]) - amb) + (centre([b]) - amb),
                               atol=1e-5)
    light_b = (-np.asarray(b.direction) * 1e6, np.asarray(b.color) * b.intensity)
    expected = shade(np.zeros(3), np.array([0.0, 0, 1]), EYE, [(a.position, a.color), light_b], mat)
    np.testing.assert_allclose(both, expected, atol=1e-5)
    # ambient multiplies the material colour
    dark = centre([PointLight((0, 0, -3.0))], ambient=(0.5, 1.0, 0.0))
    np.testing.assert_allclose(dark, [0.025, 0.025, 0.0], atol=1e-6)


def test_srgb_encoding(make_renderer):
    mat = Material(color=(0.2, 0.5, 0.9), ka=0.3, kd=0.5, ks=0.0)
    scene = quad_scene(mat, [PointLight((1.0, 1.0, 3.0))])
    r = make_renderer(16, 16)
    linear = r.render_frame(scene, FRONT, "flat", color_dtype="f4").color[8, 8, :3]
    encoded = r.render(scene, FRONT, "flat", srgb=True)[8, 8, :3] / 255
    c = np.clip(linear, 0, 1)
    srgb = np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)
    np.testing.assert_allclose(encoded, srgb, atol=EPS8)
    assert (encoded > linear + 0.05).all()


def test_no_light_means_headlight(make_renderer):
    mat = Material(color=(1, 1, 1), ka=0.0, kd=1.0, ks=0.0)
    s = Scene()
    s.add(P.plane(2.0), mat)
    img = make_renderer(16, 16).render(s, FRONT, "flat")
    np.testing.assert_allclose(img[8, 8, :3] / 255, 1.0, atol=EPS8)  # L = V = N


# ------------------------------------------------------------------------- flat shading

def test_flat_cube_one_value_per_face(make_renderer):
    s = Scene()
    s.add(P.cube(), Material(color=(0.7, 0.7, 0.7)))
    s.add_light(PointLight((2.0, 3.0, 4.0)))
    cam = Camera.look_at([2.0, 1.5, 2.5], [0, 0, 0])
    f = make_renderer(96, 96).render_frame(s, cam, "flat")
    visible = [i for i in range(6) if (f.face_id == i).sum() > 20]
    assert len(visible) == 3
    for i in visible:
        colors = f.color[f.face_id == i][:, :3]
        assert len(np.unique(colors, axis=0)) == 1, i  # no seam along the diagonal


def test_flat_non_planar_quad_is_one_colour(make_renderer):
    quad = Mesh([[-1, -1, 0.3], [1, -1, -0.3], [1, 1, 0.3], [-1, 1, -0.3]], [[0, 1, 2, 3]])
    s = Scene()
    s.add(quad, Material(ks=0.5, shininess=5))
    s.add_light(PointLight((0.5, 1.0, 2.0)))
    f = make_renderer(48, 48).render_frame(s, Camera.look_at([0.3, 0.2, 3.0], [0, 0, 0]), "flat")
    colors = f.color[f.face_id == 0][:, :3]
    assert len(colors) > 500
    assert len(np.unique(colors, axis=0)) == 1
    g = make_renderer(48, 48).render_frame(s, Camera.look_at([0.3, 0.2, 3.0], [0, 0, 0]),
                                           "gouraud")
    assert len(np.unique(g.color[g.face_id == 0][:, :3], axis=0)) > 10  # smooth modes vary


# ------------------------------------------------------------------------------ depth

def two_quads(order):
    near = P.plane(1.5).transformed(np.array([[1, 0, 0, 0.3], [0, 1, 0, 0], [0, 0, 1, 0.5],
                                              [0, 0, 0, 1.0]]))
    far = P.plane(1.5).transformed(np.array([[1, 0, 0, -0.3], [0, 1, 0, 0], [0, 0, 1, -0.5],
                                             [0, 0, 0, 1.0]]))
    s = Scene()
    meshes = {"near": (near, Material(color=(1, 0, 0))), "far": (far, Material(color=(0, 0, 1)))}
    for name in order:
        s.add(*meshes[name])
    return s


def test_depth_test_makes_order_irrelevant(make_renderer):
    r = make_renderer(64, 64)
    a = r.render(two_quads(["far", "near"]), FRONT, "flat")
    b = r.render(two_quads(["near", "far"]), FRONT, "flat")
    np.testing.assert_array_equal(a, b)
    c = r.render(two_quads(["far", "near"]), FRONT, "flat", depth_test=False)
    d = r.render(two_quads(["near", "far"]), FRONT, "flat", depth_test=False)
    assert not np.array_equal(c, d)
    np.testing.assert_array_equal(c, a)  # near drawn last wins anyway
    overlap = (d[..., 2] > 0) & (a[..., 0] > 0)
    assert overlap.sum() > 100  # there the far quad, drawn last, covers the near one


@pytest.mark.parametrize("distance", [0.7, 3.0, 25.0])
def test_render_depth_of_facing_plane(make_renderer, distance):
    s = Scene()
    s.add(P.plane(100.0))
    cam = Camera.look_at([0, 0, distance], [0, 0, 0], near=0.05, far=200.0)
    depth = make_renderer(32, 24).render_depth(s, cam)
    assert depth.shape == (24, 32) and depth.dtype == np.float32
    np.testing.assert_allclose(depth, distance, rtol=1e-3)
    with pytest.warns(RenderWarning, match="nothing to draw"):
        empty = make_renderer(8, 8).render_depth(Scene(), cam)
    assert np.isinf(empty).all()


# --------------------------------------------------------------------- spheres, normals

def test_backlit_shiny_sphere_has_no_specular_leak(make_renderer):
    mat = Material(color=(0.6, 0.6, 0.6), ka=0.2, kd=0.5, ks=1.0, shininess=4)
    light = (0.3, 0.2, -4.0)
    s = Scene()
    s.add(P.icosphere(4), mat)
    s.add_light(PointLight(light))
    cam = Camera.look_at([0, 0, 3.5], [0, 0, 0], fov_y=40)
    o, d = pixel_rays(cam, 64, 64)
    p, n, hit = hit_ellipsoid(o, d, (1, 1, 1))
    to_light = np.asarray(light) - p
    away = hit & (np.einsum("...i,...i", to_light, n) < -0.2)
    assert away.sum() > 500
    for mode in ("gouraud", "phong"):
        f = make_renderer(64, 64).render_frame(s, cam, mode)
        covered = away & (f.face_id >= 0)  # the mesh is inscribed: skip the rim it misses
        assert covered.sum() > 400
        np.testing.assert_allclose(f.color[covered][:, :3] / 255, 0.12, atol=EPS8)


def test_non_uniformly_scaled_sphere_uses_inverse_transpose(make_renderer):
    radii = (1.4, 0.6, 1.0)
    mat = Material(color=(0.9, 0.8, 0.7), ka=0.1, kd=0.6, ks=0.5, shininess=16)
    light = (2.0, 3.0, 4.0)
    s = Scene()
    s.add(P.icosphere(5), mat, scale=radii)
    s.add_light(PointLight(light))
    cam = Camera.look_at([0.4, 0.9, 3.5], [0, 0, 0], fov_y=45)
    ref, hit = render_ellipsoid(cam, 128, 128, radii, [(light, (1, 1, 1))], mat)
    f = make_renderer(128, 128).render_frame(s, cam, "phong", color_dtype="f4")
    both = hit & (f.face_id >= 0)
    err = np.abs(f.color[..., :3] - ref)[both] * 255
    assert err.mean() < 0.25 and err.max() < 6, (err.mean(), err.max())
    # world normals come out as the ellipsoid's
    o, d = pixel_rays(cam, 128, 128)
    _, n, _ = hit_ellipsoid(o, d, radii)
    cos = np.einsum("...i,...i", f.normal, n)[both]
    assert np.degrees(np.arccos(np.clip(cos, -1, 1))).mean() < 0.5


# --------------------------------------------------------------------------- face ids

def cube_face_oracle(cam, w, h):
    """Which face of the unit cube each pixel centre's ray hits first (-1: none)."""
    o, d = pixel_rays(cam, w, h)
    with np.errstate(divide="ignore", invalid="ignore"):
        t0 = (-0.5 - o) / d
        t1 = (0.5 - o) / d
    tmin = np.minimum(t0, t1)
    enter = tmin.max(-1)
    leave = np.maximum(t0, t1).min(-1)
    hit = enter < leave
    axis = tmin.argmax(-1)
    sign = np.take_along_axis(np.where(d > 0, -1, 1), axis[..., None], -1)[..., 0]
    face = 2 * axis + (sign > 0)  # box(): -x, +x, -y, +y, -z, +z
    return np.where(hit, face, -1)


@pytest.mark.parametrize("samples", [0, 4])
def test_face_ids_on_flat_cube(make_renderer, samples):
    s = Scene()
    s.add(P.cube())
    cam = Camera.look_at([1.8, 1.3, 2.2], [0, 0, 0])
    f = make_renderer(80, 80, samples=samples).render_frame(s, cam, "flat")
    oracle = cube_face_oracle(cam, 80, 80)
    assert set(np.unique(f.face_id)) <= set(range(-1, 6))  # no blended ids
    # compare away from edges: pixels whose 3x3 neighbourhood is one face in the oracle
    pad = np.pad(oracle, 1, mode="edge")
    same = np.ones_like(oracle, bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            same &= pad[1 + dy:81 + dy, 1 + dx:81 + dx] == oracle
    assert same.sum() > 3000
    np.testing.assert_array_equal(f.face_id[same], oracle[same])
    if samples:
        depth_values = np.unique(f.depth[np.isfinite(f.depth)])
        assert np.isfinite(f.depth[same & (oracle >= 0)]).all()
        assert len(depth_values) > 10


def test_face_ids_are_polygons_not_triangles(make_renderer):
    s = Scene()
    s.add(P.cylinder(12))  # 12 quads and two 12-gons = 10 triangles each
    cam = Camera.look_at([0, 3, 3], [0, 0, 0])
    f = make_renderer(64, 64).render_frame(s, cam, "phong")
    ids = set(np.unique(f.face_id)) - {-1}
    assert 12 in ids and max(ids) <= 13


# ---------------------------------------------------------------------- resources

def test_thousand_frames_do_not_grow_memory(make_renderer):
    import resource  # noqa: F401 (Linux only; the suite runs on Linux)

    def rss_mb():
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * 4096 / 2**20

    r = make_renderer(64, 64, samples=4)
    s = Scene()
    s.add(P.icosphere(2))
    cams = [FRONT.orbit([0, np.sin(a / 2), 0, np.cos(a / 2)]) for a in np.linspace(0, 6, 50)]
    for _ in r.render_many(s, cams):  # (Frames, colour only; its own targets, freed after)
        pass
    r.render(s, cams[0])  # (the target every later render reuses)
    before = rss_mb()
    children = len(r.context._children)
    for i in range(1000):
        r.render(s, cams[i % 50])
    assert rss_mb() - before < 40
    assert len(r.context._children) == children
    assert r.cached_meshes == 1


def test_meshes_are_uploaded_once(make_renderer):
    r = make_renderer(32, 32)
    s = Scene()
    mesh = P.icosphere(1)
    s.add(mesh)
    r.render(s, FRONT)
    gpu = r.meshes.gpu_mesh(mesh)
    r.render(s, FRONT.orbit([0, 0.2, 0, 0.98]))
    assert r.meshes.gpu_mesh(mesh) is gpu
    del s, mesh
    import gc

    gc.collect()
    with pytest.warns(RenderWarning):
        r.render(Scene(), FRONT)
    assert r.cached_meshes == 0 and gpu.released


def test_closed_renderer_and_bad_arguments(make_renderer):
    from glshade import GlshadeError, OptionError

    r = make_renderer(8, 8)
    with pytest.raises(OptionError, match="unknown shading mode 'toon'; choose one of flat"):
        r.render(Scene(), FRONT, "toon")
    with pytest.raises(OptionError, match="cull must be 'auto', True or False"):
        r.render(Scene(), FRONT, cull_back_faces="sometimes")  # (the earlier keyword)
    r.close()
    r.close()  # a second close does nothing
    with pytest.raises(GlshadeError, match="closed"):
        r.render(Scene(), FRONT)


#: a fresh process that reports, by glibc's own count of mapped blocks (mallinfo2's hblks),
#: whether a 31 MB malloc is mapped (1) or served from the heap (0): first on its own (the
#: dynamic threshold starts at 128 KB: mapped, and the threshold rises to 30 MB when freed),
#: after making a Renderer, and after tune_malloc() pins the threshold at 32 MB
_MALLOC_PROBE = """
import ctypes
libc = ctypes.CDLL("libc.so.6")
class Info(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in
                "arena ordblks smblks hblks hblkhd usmblks fsmblks uordblks fordblks "
                "keepcost".split()]
libc.mallinfo2.restype = Info
libc.malloc.restype = ctypes.c_void_p
libc.malloc.argtypes = [ctypes.c_size_t]
libc.free.argtypes = [ctypes.c_void_p]
def mapped(megabytes):
    before = libc.mallinfo2().hblks
    p = libc.malloc(int(megabytes * (1 << 20)))
    after = libc.mallinfo2().hblks
    libc.free(p)
    return after - before
first = mapped(30)
import glshade
with glshade.Renderer(8, 8, samples=0) as r:
    r.render(glshade.Scene(), glshade.Camera())
made = mapped(31)
tuned = glshade.tune_malloc()
print(first, made, tuned, mapped(31.5))
"""


@pytest.mark.parametrize("env, expect", [({}, "1 1 True 0"),
                                         ({"GLSHADE_TUNE_MALLOC": "1"}, "1 0 True 0")])
def test_tune_malloc_is_opt_in_and_works(env, expect):
    """Making a Renderer leaves glibc's malloc alone (a large block is still mapped) unless
    GLSHADE_TUNE_MALLOC asks; tune_malloc() pins the mmap threshold (the same block then
    comes from the heap) -- read from glibc's own counters, not from the function's word."""
    import os
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-c", _MALLOC_PROBE], capture_output=True,
                         text=True, env={**os.environ, **env}, timeout=120)
    assert out.stdout.strip() == expect, out.stderr


@pytest.mark.parametrize("samples", [0, 4])
def test_the_background_colour_stays_out_of_ids_depth_and_normals(make_renderer, samples):
    """Background pixels: the background colour, and no polygon (-1), no depth (inf), no
    normal (0) -- whatever the colour (a clear reaches every attachment it is given)."""
    s = Scene(background=(0.12, 0.5, 0.9))
    s.add(P.icosphere(2))
    frame = make_renderer(48, 48, samples).render_frame(s, FRONT, "phong")
    empty = frame.face_id < 0
    assert 0.3 < empty.mean() < 0.9
    assert np.array_equal(empty, np.isinf(frame.depth))
    # (with MSAA, colour and normals are averaged at the silhouette: look one pixel away)
    pad = np.pad(empty, 1, constant_values=True)
    clear = np.all([pad[1 + dy:49 + dy, 1 + dx:49 + dx] for dy in (-1, 0, 1)
                    for dx in (-1, 0, 1)], axis=0)
    assert (frame.normal[clear] == 0).all()
    assert (frame.color[clear][:, :3] == np.round(np.array([0.12, 0.5, 0.9]) * 255)).all()


def test_outputs_choose_what_a_frame_reads_and_colour_is_the_same(make_renderer):
    from glshade import Outputs

    s = Scene()
    s.add(P.cube(), Material(color=(0.7, 0.5, 0.3)))
    cam = Camera.look_at([2.0, 1.5, 2.5], [0, 0, 0])
    r = make_renderer(48, 48)
    full = r.render_frame(s, cam, "phong")
    depth_only = r.render_frame(s, cam, "phong", outputs=Outputs.DEPTH)
    assert depth_only.normal is None and depth_only.face_id is None
    np.testing.assert_array_equal(depth_only.depth, full.depth)
    np.testing.assert_array_equal(full.color, r.render(s, cam, "phong"))
    assert set(np.unique(full.face_id)) <= {-1, 0, 1, 2, 3, 4, 5}
    np.testing.assert_array_equal(np.isfinite(full.depth), full.face_id >= 0)


@pytest.mark.parametrize("case, reason", [
    ("empty", "nothing to draw"),
    ("collinear", "zero area"),
    ("tiny", "smaller than a pixel"),
    ("behind", "no part of the scene lies in the camera's view"),
    ("inside, culled", r"back faces are culled \(cull=True\) and the camera may be inside"),
])
def test_a_blank_render_warns_and_says_why(make_renderer, case, reason):
    s = Scene()
    cam = FRONT
    if case == "inside, culled":  # (the camera, at z = 3, inside a closed sphere)
        s.add(P.icosphere(2), scale=5.0)
    elif case == "collinear":
        s.add(Mesh([[0, 0, 0], [1, 1, 1], [2, 2, 2]], [[0, 1, 2]]))
    elif case == "tiny":
        s.add(P.cube().transformed(np.diag([1e-12, 1e-12, 1e-12, 1.0])))
    elif case == "behind":
        s.add(P.cube(), translation=(0, 0, 10))
    with pytest.warns(RenderWarning, match=reason):
        img = make_renderer(16, 16).render(s, cam, cull=case == "inside, culled")
    assert (img[..., :3] == 0).all()


@pytest.mark.parametrize("where", ["outside", "inside", "cut by the near plane"])
def test_auto_culling_only_where_back_faces_are_hidden(make_renderer, where):
    """'auto' culls a closed mesh seen from outside -- the same picture as no culling, half
    the work -- and not one the camera is inside or whose front the near plane cuts away."""
    s = Scene()
    s.add(P.icosphere(3), Material(color=(0.9, 0.6, 0.3)))
    cam = {"outside": FRONT,
           "inside": Camera.look_at((0.2, 0.1, 0.3), (0, 0, -1)),
           "cut by the near plane": Camera.look_at((0, 0, 1.5), (0, 0, 0), near=0.8)}[where]
    r = make_renderer(48, 48)
    auto = r.render_frame(s, cam, "phong", color_dtype="f4")
    kept = r.render_frame(s, cam, "phong", color_dtype="f4", cull=False)
    with warnings.catch_warnings():  # (culled, the inside can be blank: that is the point)
        warnings.simplefilter("ignore", RenderWarning)
        culled = r.render_frame(s, cam, "phong", color_dtype="f4", cull=True)
    assert (kept.face_id >= 0).mean() > 0.3
    np.testing.assert_array_equal(auto.color, kept.color)
    np.testing.assert_array_equal(auto.face_id, kept.face_id)
    used = {k.two_sided for k in r.shaders._programs}
    if where == "outside":
        np.testing.assert_array_equal(auto.color, culled.color)  # nothing hidden was lost
        assert used == {False, True}  # (auto drew one-sided, culled; False two-sided)
    else:
        assert (culled.face_id >= 0).sum() < (kept.face_id >= 0).sum()  # what culling loses


def test_crease_keeps_a_cubes_faces_flat_under_smooth_shading(make_renderer):
    """Oracle: with creases split, every covered pixel's normal is its face's axis normal;
    without, the corners' averaged normals bend it."""
    cam = Camera.look_at([2.0, 1.5, 2.5], [0, 0, 0])
    r = make_renderer(64, 64)
    normals = {}
    for crease in (None, 30.0):
        s = Scene()
        s.add(P.cube(), crease=crease)
        f = r.render_frame(s, cam, "phong")
        normals[crease] = f.normal[f.face_id >= 0]
    axis = np.abs(normals[30.0]).max(axis=1)
    np.testing.assert_allclose(axis, 1.0, atol=1e-5)
    assert np.abs(normals[None]).max(axis=1).min() < 0.9


def test_specialised_programs_match_the_formula_for_every_light_kind(make_renderer):
    """One program per light set, compiled once; each kind's term equals the oracle."""
    from tests.oracle.raycast import shade_any

    mat = Material(color=(0.6, 0.8, 0.4), ka=0.15, kd=0.6, ks=0.4, shininess=12)
    lights = [PointLight((1.0, 0.5, 2.0), color=(1.0, 0.7, 0.5), attenuation=(1.0, 0.2, 0.1)),
              PointLight((-0.5, 0.2, 1.5), intensity=0.5),
              DirectionalLight((0.3, -0.2, -1.0), color=(0.2, 0.4, 1.0))]
    r = make_renderer(16, 16)
    scene = quad_scene(mat, lights)
    from glshade.cpu.raycast import pixel_rays

    origin, direction = pixel_rays(FRONT, 16, 16)
    hit = origin[8, 8] + direction[8, 8] * (-origin[8, 8, 2] / direction[8, 8, 2])
    specs = [("point", (1.0, 0.5, 2.0), (1.0, 0.7, 0.5), (1.0, 0.2, 0.1)),
             ("point", (-0.5, 0.2, 1.5), (0.5, 0.5, 0.5), (1.0, 0.0, 0.0)),
             ("directional", (0.3, -0.2, -1.0), (0.2, 0.4, 1.0))]
    # flat: lit once at the polygon's centroid (the origin); phong: at the pixel's point
    for mode, p in (("flat", np.zeros(3)), ("phong", hit)):
        got = r.render_frame(scene, FRONT, mode, color_dtype="f4").color[8, 8, :3]
        v = (EYE - p) / np.linalg.norm(EYE - p)
        oracle = shade_any(p, np.array([0.0, 0, 1]), v, specs, mat)
        np.testing.assert_allclose(got, oracle, atol=1e-5)
    programs = len(r.shaders._programs)
    for _ in range(3):  # a moving camera compiles nothing new
        r.render(scene, FRONT.orbit([0, 0.1, 0, 0.995]), "phong")
        r.render(scene, FRONT, "phong")
    assert len(r.shaders._programs) == programs + 1  # phong without auxiliary outputs


@pytest.mark.parametrize("samples", [0, 2, 4])
def test_auxiliary_outputs_are_exact_whatever_the_colours_samples(gl_context, samples):
    """render_frame with MSAA: normals unit where a polygon is drawn and zero elsewhere,
    depth inf exactly where the id is -1, and ids and depth equal to the single-sampled
    render's -- no blend of a silhouette's samples (it gave normals as short as 0.25 and
    background pixels with normals); the colour keeps its MSAA."""
    from glshade import Renderer
    from glshade.geometry import primitives as P

    scene = Scene(background=(0.3, 0.2, 0.1))
    scene.add(P.icosphere(2))
    scene.add(P.cube(), translation=(0.9, 0.2, -0.6))
    camera = Camera.look_at((0.5, 1.0, 3.5), (0.3, 0, 0))
    with Renderer(80, 64, samples=0, context=gl_context) as r0, \
            Renderer(80, 64, samples=samples, context=gl_context) as r:
        ref = r0.render_frame(scene, camera, "phong")
        f = r.render_frame(scene, camera, "phong")
        color_only = r.render(scene, camera, "phong")
    drawn = f.face_id >= 0
    assert drawn.any() and (~drawn).any()
    lengths = np.linalg.norm(f.normal, axis=2)
    np.testing.assert_allclose(lengths[drawn], 1.0, atol=1e-5)
    assert (f.normal[~drawn] == 0).all()
    assert np.isinf(f.depth[~drawn]).all() and np.isfinite(f.depth[drawn]).all()
    assert np.array_equal(f.face_id, ref.face_id)
    assert np.array_equal(f.depth, ref.depth)
    np.testing.assert_allclose(f.normal, ref.normal, atol=1e-6)
    assert np.array_equal(f.color, color_only)  # (the colour is the MSAA render's)
    if samples:
        assert not np.array_equal(f.color, ref.color)  # (it really is multisampled)
