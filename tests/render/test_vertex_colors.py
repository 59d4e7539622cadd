"""Colours on geometry (Mesh.colors, Mesh.face_colors) against the notes' formula written out
in float64 numpy, with C per vertex or per polygon: camera rays meet each triangle
(Moller-Trumbore, here), and at the hit the formula
    I = Ia ka C M + Ip (kd max(L.N, 0) C M + ks max(R.V, 0)^n)      (M: the material colour)
is evaluated with C interpolated (Phong), evaluated at the corners with their own C and V
and interpolated (Gouraud), or evaluated once a polygon at its centre with the mean of its
corners' colours (flat). Every pixel whose eight neighbours show the same polygon agrees
within 1.5/255; the emission adds exactly; alpha is opacity; False ignores them."""

import numpy as np
import pytest

from glshade import Camera, DirectionalLight, Material, Mesh, Scene
from tests.oracle.neighbours import inside_regions

pytestmark = pytest.mark.gl

W, H = 96, 72
EYE = np.array([0.4, 0.9, 3.4])
CAMERA = Camera.look_at(eye=tuple(EYE), target=(0.0, 0.0, 0.0), fov_y=40.0)
LIGHT_DIR = np.array([-0.5, -0.8, -0.6])
AMBIENT = 0.3
MATERIAL = Material(color=(0.95, 0.8, 0.7), ka=0.25, kd=0.7, ks=0.35, shininess=12.0)


def triangles(seed=0, count=6):
    """``count`` separate triangles at different slants (each its own three vertices: a
    vertex normal is its triangle's), facing the camera more or less."""
    rng = np.random.default_rng(seed)
    shape = np.array([[-0.42, -0.4, 0.0], [0.42, -0.36, 0.0], [0.0, 0.44, 0.0]])
    tris = []
    for k in range(count):
        centre = np.array([(k % 3 - 1) * 0.9, (k // 3 - 0.5) * 0.95, 0.0])
        a, b = rng.uniform(-0.7, 0.7, 2)  # (a slant about x, then y)
        rx = np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])
        ry = np.array([[np.cos(b), 0, np.sin(b)], [0, 1, 0], [-np.sin(b), 0, np.cos(b)]])
        tris.append(centre + (shape + rng.uniform(-0.05, 0.05, (3, 3))) @ (ry @ rx).T)
    v = np.concatenate(tris)
    return v, np.arange(len(v)).reshape(-1, 3)


def notes_formula(p, n, c):
    """The notes' intensity at points ``p`` (N, 3) with unit normals ``n`` (turned towards
    the eye) and surface colours ``c`` (N, 3)."""
    to_light = -LIGHT_DIR / np.linalg.norm(LIGHT_DIR)
    v = EYE - p
    v /= np.linalg.norm(v, axis=-1, keepdims=True)
    ln = n @ to_light
    r = 2 * ln[:, None] * n - to_light
    rv = np.maximum((r * v).sum(-1), 0)
    lit = ln > 0
    m = np.asarray(MATERIAL.color)
    out = AMBIENT * MATERIAL.ka * c * m
    out += np.where(lit[:, None], MATERIAL.kd * ln[:, None] * c * m +
                    MATERIAL.ks * rv[:, None] ** MATERIAL.shininess, 0)
    return out


def oracle(vertices, faces, corner_c, mode):
    """``(H, W, 3)`` the formula's image (nan: no hit) and ``(H, W)`` the triangle hit."""
    o, d = CAMERA.rays((W, H))
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    image = np.full((len(o), 3), np.nan)
    which = np.full(len(o), -1)
    best = np.full(len(o), np.inf)
    for k, f in enumerate(faces):
        p0, p1, p2 = vertices[f]
        e1, e2 = p1 - p0, p2 - p0
        pv = np.cross(d, e2)
        det = pv @ e1
        with np.errstate(divide="ignore", invalid="ignore"):
            s = o - p0
            u = (s * pv).sum(1) / det
            q = np.cross(s, e1)
            w = (d * q).sum(1) / det
            t = (q @ e2) / det
        hit = (u >= 0) & (w >= 0) & (u + w <= 1) & (t > 0) & (t < best)
        if not hit.any():
            continue
        bary = np.stack([1 - u - w, u, w], 1)[hit]
        n = np.cross(e1, e2)
        n /= np.linalg.norm(n)
        if n @ (EYE - p0) < 0:  # (two-sided: the side the eye sees)
            n = -n
        cs = corner_c[3 * k:3 * k + 3]
        if mode == "phong":
            p = o[hit] + t[hit, None] * d[hit]
            value = notes_formula(p, np.broadcast_to(n, p.shape), bary @ cs)
        elif mode == "gouraud":
            at_corners = notes_formula(vertices[f], np.broadcast_to(n, (3, 3)), cs)
            value = bary @ at_corners
        else:  # flat: once, at the centre, with the corners' mean colour
            value = notes_formula(vertices[f].mean(0)[None], n[None], cs.mean(0)[None])
            value = np.broadcast_to(value, (int(hit.sum()), 3))
        image[hit], which[hit], best[hit] = value, k, t[hit]
    return np.clip(image, 0, 1).reshape(H, W, 3), which.reshape(H, W)


def scene_of(mesh, material=MATERIAL, light=True):
    s = Scene(ambient=(AMBIENT,) * 3, background=(0, 0, 0))
    s.add(mesh, material)
    # (no light: one of intensity 0 -- a scene without lights is lit by a default one)
    s.add_light(DirectionalLight(direction=tuple(LIGHT_DIR), intensity=1.0 if light else 0.0))
    return s


@pytest.mark.parametrize("per", ["vertex", "face"])
@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong"])
def test_colours_are_the_notes_c_in_every_scheme(make_renderer, mode, per):
    vertices, faces = triangles()
    rng = np.random.default_rng(3)
    if per == "vertex":
        colors = rng.uniform(0.1, 1.0, (len(vertices), 3))
        mesh = Mesh(vertices, faces, colors=colors)
        corner_c = colors
    else:
        colors = rng.uniform(0.1, 1.0, (len(faces), 3))
        mesh = Mesh(vertices, faces, face_colors=colors)
        corner_c = np.repeat(colors, 3, axis=0)
    want, which = oracle(vertices, faces, corner_c, mode)
    r = make_renderer(W, H, samples=0)
    frame = r.render_frame(scene_of(mesh), CAMERA, mode, color_dtype="f4")
    inside = inside_regions(which) & (which >= 0)
    assert inside.sum() > 0.1 * W * H
    diff = np.abs(frame.color[..., :3] - want)[inside]
    assert diff.max() <= 1.5 / 255, (mode, per, diff.max() * 255)
    # and without the mesh's colours, the material's alone (C = 1)
    plain, _ = oracle(vertices, faces, np.ones_like(corner_c), mode)
    ignored = r.render_frame(scene_of(mesh, Material(**{**MATERIAL.__dict__,
                                                        "vertex_colors": False})),
                             CAMERA, mode, color_dtype="f4")
    assert np.abs(ignored.color[..., :3] - plain)[inside].max() <= 1.5 / 255


def test_flat_shading_takes_the_mean_of_a_polygons_corners(make_renderer):
    """A pentagon and a quad with a colour at each corner: one colour each, the mean."""
    pent = [(np.cos(a) * 0.6 - 0.7, np.sin(a) * 0.6, 0.0)
            for a in np.linspace(0, 2 * np.pi, 6)[:-1] + 0.3]
    quad = [(0.2, -0.5, 0.1), (1.2, -0.5, -0.1), (1.2, 0.5, -0.1), (0.2, 0.5, 0.1)]
    vertices = np.array(pent + quad)
    rng = np.random.default_rng(5)
    colors = rng.uniform(0.0, 1.0, (9, 3))
    mesh = Mesh(vertices, [list(range(5)), list(range(5, 9))], colors=colors)
    r = make_renderer(W, H, samples=0)
    frame = r.render_frame(scene_of(mesh, light=False), CAMERA, "flat", color_dtype="f4")
    # (no light: the ambient term alone, Ia ka C M, one value a polygon)
    m = np.asarray(MATERIAL.color)
    for polygon, corners in ((0, slice(0, 5)), (1, slice(5, 9))):
        seen = frame.color[..., :3][frame.face_id == polygon]
        assert len(seen) > 50
        want = AMBIENT * MATERIAL.ka * colors[corners].mean(0) * m
        assert np.abs(seen - want).max() <= 1e-5, (polygon, seen[0], want)


@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong"])
def test_emission_adds_exactly(make_renderer, mode):
    """A black-lit emissive surface (no light, no ambient) shows its emission; lit, the
    emission adds to the lit colour."""
    vertices, faces = triangles()
    mesh = Mesh(vertices, faces)
    emission = (0.6, 0.15, 0.3)
    r = make_renderer(W, H, samples=0)
    dark = Scene(ambient=(0, 0, 0), background=(0, 0, 0))
    dark.add(mesh, Material(color=(0.5, 0.5, 0.5), emission=emission))
    dark.add_light(DirectionalLight(direction=tuple(LIGHT_DIR), intensity=0.0))
    frame = r.render_frame(dark, CAMERA, mode, color_dtype="f4")
    shown = frame.color[..., :3][frame.face_id >= 0]
    assert len(shown) > 500
    assert np.abs(shown - emission).max() <= 1e-6
    lit = r.render_frame(scene_of(mesh, MATERIAL), CAMERA, mode, color_dtype="f4").color
    glowing = scene_of(mesh, Material(**{**MATERIAL.__dict__, "emission": emission}))
    both = r.render_frame(glowing, CAMERA, mode, color_dtype="f4").color
    drawn = frame.face_id >= 0
    want = np.clip(lit[..., :3] + emission, 0, 1)
    assert np.abs(both[..., :3] - want)[drawn].max() <= 1e-6


def test_a_colours_alpha_is_its_opacity(make_renderer):
    """Face colours with alpha 0.5 make the mesh transparent: over a black background a
    pixel shows half the opaque colour."""
    vertices, faces = triangles(count=1)
    rgb = np.array([[0.9, 0.6, 0.3]])
    opaque = Mesh(vertices, faces, face_colors=rgb)
    half = Mesh(vertices, faces, face_colors=np.hstack([rgb, [[0.5]]]))
    r = make_renderer(W, H, samples=0)
    a = r.render_frame(scene_of(opaque), CAMERA, "flat", color_dtype="f4")
    b = r.render_frame(scene_of(half), CAMERA, "flat", color_dtype="f4")
    inside = inside_regions(a.face_id) & (a.face_id >= 0)
    assert inside.sum() > 100
    assert np.abs(b.color[..., :3] - 0.5 * a.color[..., :3])[inside].max() <= 1.5 / 255


def test_colours_pass_through_the_geometry_a_mesh_goes_through():
    """Subsets, welds, crease splits, joins and transforms keep each vertex's colour."""
    from glshade.geometry import merge
    from glshade.geometry import primitives as P

    base = P.cube()
    colors = (base.vertices + 0.5)  # (each corner its own colour: its position)
    mesh = Mesh(base.vertices, base.faces, colors=colors,
                face_colors=np.linspace(0.2, 1, base.n_faces)[:, None].repeat(3, 1))

    def agrees(m):
        assert np.allclose(m.colors[:, :3], np.clip(m.vertices + 0.5, 0, 1)), m
    agrees(mesh.split_creases(30))
    agrees(mesh.weld())
    agrees(mesh.subset([1, 3]))
    agrees(merge.concatenate([mesh, mesh]))
    moved = mesh.transformed(np.diag([1.0, 1.0, 1.0]))
    assert np.array_equal(moved.face_colors, mesh.face_colors)
    assert np.allclose(mesh.subset([1, 3]).face_colors, mesh.face_colors[[1, 3]])
