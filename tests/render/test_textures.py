"""Textured surfaces against a numpy oracle that shares no code with the renderer: float64
camera rays meet each triangle (Moller-Trumbore), the hit's barycentrics weigh its corners'
texture coordinates (perspective-correct by construction: the interpolation is in 3D), and
the texel is looked up by hand (sRGB decoded by the IEC formula). NEAREST is exact at every
pixel centre further than 0.01 px from a texel edge, LINEAR within 1/255, in flat, Gouraud
and Phong shading; the MTL illum models against the notes' formula written out in numpy."""

import numpy as np
import pytest

import glshade
from glshade import Camera, DirectionalLight, Material, Mesh, Scene, Texture
from tests.oracle.neighbours import inside_regions

W, H = 96, 80
# 7 x 5 texels (odd sizes), every texel's colour far from every other's (so that which texel
# a pixel shows is never in doubt, whatever the GPU's sRGB decode rounds)
_levels = np.array([40, 90, 140, 190, 240], np.uint8)
IMAGE = np.stack(np.meshgrid(_levels, _levels, _levels, indexing="ij"), -1).reshape(-1, 3)
IMAGE = IMAGE[np.random.default_rng(7).permutation(len(IMAGE))[:35]].reshape(5, 7, 3)
#: how far a GPU's sRGB decode of 8-bit values may be from the IEC formula (llvmpipe
#: approximates it by a polynomial: 1.2e-3 at worst, a third of an 8-bit step)
DECODE = 2e-3


def srgb_decode(c):
    c = np.asarray(c, np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def tilted_quad(tilt, uv_scale=1.0):
    """A unit square turned ``tilt`` degrees about x (and a little about y), the image
    over it ``uv_scale`` times each way."""
    a, b = np.radians(tilt), np.radians(17.0)
    rx = np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])
    ry = np.array([[np.cos(b), 0, np.sin(b)], [0, 1, 0], [-np.sin(b), 0, np.cos(b)]])
    v = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float) @ (ry @ rx).T
    uv = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float) * uv_scale
    return Mesh(v, [[0, 1, 2, 3]], uv=uv)


def oracle_uv(mesh, camera, size):
    """Per pixel: the texture coordinate the camera ray meets (nan: none), and whether
    the pixel is well inside a triangle (its 8 neighbours hit the same one)."""
    o, d = camera.rays(size)
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    corners = mesh.corner_triangles
    verts = mesh.vertices[mesh.face_indices[corners]]          # (T, 3, 3)
    best_t = np.full(len(o), np.inf)
    best_uv = np.full((len(o), 2), np.nan)
    which = np.full(len(o), -1)
    for k, (p0, p1, p2) in enumerate(verts):   # (a handful of triangles: a loop is fine)
        e1, e2 = p1 - p0, p2 - p0
        pv = np.cross(d, e2)
        det = pv @ e1
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / det
            s = o - p0
            u = (s * pv).sum(1) * inv
            q = np.cross(s, e1)
            v = (d * q).sum(1) * inv
            t = (q @ e2) * inv
        hit = (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0) & (t < best_t)
        tex = mesh.uv[corners[k]]
        uvs = (1 - u - v)[:, None] * tex[0] + u[:, None] * tex[1] + v[:, None] * tex[2]
        best_t[hit], best_uv[hit], which[hit] = t[hit], uvs[hit], k
    w, h = size
    which = which.reshape(h, w)
    return best_uv.reshape(h, w, 2), inside_regions(which) & (which >= 0)


def nearest_texels(uv):
    th, tw = IMAGE.shape[:2]
    uv = np.nan_to_num(uv)
    i = np.floor(uv[..., 0] * tw).astype(int) % tw
    j = np.floor(uv[..., 1] * th).astype(int) % th
    return srgb_decode(IMAGE[th - 1 - j, i])


def bilinear_texels(uv):
    th, tw = IMAGE.shape[:2]
    uv = np.nan_to_num(uv)
    x, y = uv[..., 0] * tw - 0.5, uv[..., 1] * th - 0.5
    x0, y0 = np.floor(x), np.floor(y)
    fx, fy = (x - x0)[..., None], (y - y0)[..., None]
    lin = srgb_decode(IMAGE)

    def at(i, j):
        return lin[th - 1 - (j.astype(int) % th), i.astype(int) % tw]
    return ((1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x0 + 1, y0) +
            (1 - fx) * fy * at(x0, y0 + 1) + fx * fy * at(x0 + 1, y0 + 1))


def edge_distance_px(uv):
    """Each pixel's distance to the nearest texel edge, in pixels (the texel coordinate's
    distance to a whole number over its rate of change across the screen)."""
    th, tw = IMAGE.shape[:2]
    out = np.full(uv.shape[:2], np.inf)
    for axis, n in ((0, tw), (1, th)):
        c = uv[..., axis] * n
        gy, gx = np.gradient(c)
        rate = np.hypot(gx, gy)
        frac = c - np.floor(c)
        out = np.minimum(out, np.minimum(frac, 1 - frac) / np.maximum(rate, 1e-12))
    return out


CAMERA = Camera.look_at((0.3, 0.2, 3.2), (0, 0, 0), fov_y=50)


def render(gl_context, mesh, material, mode, lights=(), camera=CAMERA):
    scene = Scene(ambient=(1.0, 1.0, 1.0))
    scene.add(mesh, material)
    for light in lights:
        scene.add_light(light)
    with glshade.Renderer(W, H, samples=0, context=gl_context) as r:
        return r.render_frame(scene, camera, mode, color_dtype="f4").color[..., :3]


@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong"])
@pytest.mark.parametrize("tilt,scale", [(0, 1.0), (55, 1.0), (70, 2.5), (-40, 3.0)])
def test_nearest_texels_are_exact_away_from_texel_edges(gl_context, mode, tilt, scale):
    """illum 0 (the diffuse colour, unlit) with a white Kd: each pixel shows exactly its
    texel (the texel whose colour is nearest the pixel's is the oracle's, and within the
    sRGB decode's rounding of it) under a perspective view of a steeply tilted quad -- so
    the interpolation is perspective-correct (screen-linear uv misses texels by whole
    texels here) -- and with the image repeated."""
    mesh = tilted_quad(tilt, scale)
    material = Material(diffuse=(1, 1, 1), illum=0, texture=Texture(IMAGE, filter="nearest"))
    got = render(gl_context, mesh, material, mode)
    uv, inside = oracle_uv(mesh, CAMERA, (W, H))
    keep = inside & (edge_distance_px(uv) > 0.01)
    assert keep.sum() > 300
    want = nearest_texels(uv)
    palette = srgb_decode(IMAGE.reshape(-1, 3))
    shown = np.abs(got[keep][:, None] - palette[None]).sum(-1).argmin(1)
    meant = np.abs(want[keep][:, None] - palette[None]).sum(-1).argmin(1)
    assert (shown == meant).all(), np.argwhere(keep)[np.flatnonzero(shown != meant)[:5]]
    assert np.abs(got - want)[keep].max() <= DECODE


@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong"])
@pytest.mark.parametrize("tilt", [20, 65])
def test_linear_filtering_within_one_level(gl_context, mode, tilt):
    mesh = tilted_quad(tilt, 2.0)
    material = Material(diffuse=(1, 1, 1), illum=0, texture=Texture(IMAGE, filter="linear"))
    got = render(gl_context, mesh, material, mode)
    uv, inside = oracle_uv(mesh, CAMERA, (W, H))
    err = np.abs(got - bilinear_texels(uv))[inside]
    assert inside.sum() > 300
    assert err.max() <= 1 / 255, err.max()  # (the decode's rounding included)


def test_screen_linear_interpolation_would_fail_the_oracle(gl_context):
    """The oracle can tell: the same quad's texture coordinates interpolated linearly on
    the screen (what perspective-correct interpolation avoids) miss the texel at many
    pixels of a tilted quad."""
    mesh = tilted_quad(70, 2.5)
    uv, inside = oracle_uv(mesh, CAMERA, (W, H))
    # screen-linear: interpolate uv by the corners' screen positions (one triangle's affine map)
    view = CAMERA.view_matrix()
    proj = CAMERA.projection_matrix(W / H)
    p = np.c_[mesh.vertices, np.ones(4)] @ (proj @ view).T
    ndc = p[:, :2] / p[:, 3:]
    xs = np.stack([(ndc[:, 0] + 1) * W / 2, (1 - ndc[:, 1]) * H / 2], 1)
    jj, ii = np.meshgrid(np.arange(W) + 0.5, np.arange(H) + 0.5)
    a, b, c = xs[0], xs[1], xs[2]
    m = np.array([[b[0] - a[0], c[0] - a[0]], [b[1] - a[1], c[1] - a[1]]])
    lam = np.linalg.solve(m, np.stack([jj - a[0], ii - a[1]], -1)[..., None])[..., 0]
    uv_lin = (1 - lam.sum(-1))[..., None] * mesh.uv[0] + lam[..., :1] * mesh.uv[1] + \
        lam[..., 1:] * mesh.uv[2]
    first = inside & (lam.min(-1) >= 0) & (lam.sum(-1) <= 1)
    differ = (np.floor(uv_lin * [7, 5]) != np.floor(uv * [7, 5])).any(-1) & first
    assert differ.sum() > 0.2 * first.sum()


def notes_formula(n, p, eye, light_dir, ambient, ka, kd, ks, shininess, illum, ip=1.0):
    """The notes' I = Ia ka + Ip (kd max(N.L, 0) + ks max(R.V, 0)^n), with RGB
    coefficients, for a directional light; illum 1 without the specular term, 0 the
    diffuse colour unlit."""
    if illum == 0:
        return np.broadcast_to(np.asarray(kd, float), p.shape)
    to_light = np.asarray(light_dir, float) / np.linalg.norm(light_dir)
    ln = float(n @ to_light)
    v = eye - p
    v /= np.linalg.norm(v, axis=-1, keepdims=True)
    r = 2 * ln * n - to_light
    rv = np.clip(v @ r, 0, None)
    spec = rv ** shininess if illum == 2 else np.zeros_like(rv)
    out = np.asarray(ambient) * ka + ip * (np.asarray(kd) * max(ln, 0.0) +
                                           np.asarray(ks) * spec[..., None] * (ln > 0))
    return out


@pytest.mark.parametrize("illum", [0, 1, 2])
def test_each_illum_model_is_the_notes_formula(gl_context, illum):
    """A plane with RGB Ka, Kd, Ks (as an MTL gives them) under a directional light, Phong
    shading: each pixel equals the notes' formula evaluated in numpy at the point the
    camera ray meets (1e-4)."""
    mesh = glshade.geometry.primitives.plane(4.0)
    ka, kd, ks = (0.3, 0.1, 0.05), (0.2, 0.5, 0.7), (0.6, 0.5, 0.4)
    material = Material(ambient=ka, diffuse=kd, specular=ks, shininess=12, illum=illum)
    light = DirectionalLight((-0.3, -0.5, -1.0))  # (travelling: L = (0.3, 0.5, 1))
    camera = Camera.look_at((0.4, 0.3, 2.5), (0, 0, 0), fov_y=60)
    got = render(gl_context, mesh, material, "phong", [light], camera)
    o, d = camera.rays((W, H))
    t = -o[..., 2] / d[..., 2]
    p = o + t[..., None] * d
    want = notes_formula(np.array([0, 0, 1.0]), p, camera.position, (0.3, 0.5, 1.0),
                         (1, 1, 1), ka, kd, ks, 12, illum)
    inside = (np.abs(p[..., :2]) < 1.95).all(-1)
    err = np.abs(got - np.clip(want, 0, 1))[inside]
    assert err.max() <= 1e-4, err.max()


@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong"])
def test_the_texture_multiplies_ambient_and_diffuse_the_specular_map_specular(gl_context,
                                                                              mode):
    """A directional light on a flat quad (no specular term: the lit colour is the same at
    every vertex): every mode gives (Ia Ka + Ip Kd N.L) x texel -- the lit colour made per
    vertex (Gouraud) or polygon (flat), the texel per pixel."""
    mesh = tilted_quad(30, 1.0)
    n = np.cross(mesh.vertices[1] - mesh.vertices[0], mesh.vertices[2] - mesh.vertices[0])
    n /= np.linalg.norm(n)
    light_dir = n + np.array([0.2, -0.1, 0.0])
    ka, kd = (0.2, 0.25, 0.3), (0.6, 0.5, 0.4)
    material = Material(ambient=ka, diffuse=kd, specular=(0, 0, 0), illum=2,
                        texture=Texture(IMAGE, filter="nearest"))
    got = render(gl_context, mesh, material, mode, [DirectionalLight(tuple(-light_dir))])
    uv, inside = oracle_uv(mesh, CAMERA, (W, H))
    keep = inside & (edge_distance_px(uv) > 0.01)
    ln = float(n @ (light_dir / np.linalg.norm(light_dir)))
    want = (np.asarray(ka) + np.asarray(kd) * ln) * nearest_texels(uv)
    assert np.abs(got - np.clip(want, 0, 1))[keep].max() <= DECODE


def test_textures_need_coordinates_and_say_so():
    scene = Scene()
    with pytest.warns(UserWarning, match="no texture coordinates"):
        scene.add(glshade.geometry.primitives.icosphere(1),
                  Material(texture=Texture(IMAGE)))


def test_a_texture_over_the_gl_limit_is_refused_with_the_limit(gl_context):
    from glshade.render.textures import TextureCache

    with TextureCache(gl_context) as cache:
        cache.max_size = 4  # (the real limit is 16384 here: a 16k image is 1 GiB)
        with pytest.raises(glshade.SceneError, match=r"7x5 texels; this GL takes at most 4x4"):
            cache.get(Texture(IMAGE))


def test_bad_textures_are_refused_by_name(tmp_path):
    with pytest.raises(glshade.SceneError, match="no such image file"):
        Texture(tmp_path / "missing.png")
    (tmp_path / "bad.png").write_bytes(b"not a png")
    with pytest.raises(glshade.SceneError, match="bad.png: not an image"):
        Texture(tmp_path / "bad.png")
    with pytest.raises(glshade.SceneError, match="filter must be one of"):
        Texture(IMAGE, filter="cubic")
    with pytest.raises(glshade.SceneError, match="shape"):
        Texture(np.zeros((2, 2, 2)))
    with pytest.raises(glshade.GeometryError, match="one \\(u, v\\) per face corner"):
        Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], uv=[[0, 0]])


def test_the_specular_map_multiplies_the_specular_term(gl_context):
    """Phong, a plane under a directional light, a specular map only: each pixel is
    Ia Ka + Ip Kd N.L + Ip Ks (R.V)^n x its specular texel (the notes' formula, numpy)."""
    mesh = glshade.geometry.primitives.plane(4.0)
    ka, kd, ks = (0.1, 0.1, 0.1), (0.2, 0.3, 0.2), (0.8, 0.8, 0.8)
    material = Material(ambient=ka, diffuse=kd, specular=ks, shininess=6,
                        specular_texture=Texture(IMAGE, filter="nearest"))
    camera = Camera.look_at((0.4, 0.3, 2.5), (0, 0, 0), fov_y=60)
    got = render(gl_context, mesh, material, "phong",
                 [DirectionalLight((-0.2, -0.1, -1.0))], camera)
    uv, inside = oracle_uv(mesh, camera, (W, H))
    keep = inside & (edge_distance_px(uv) > 0.01)
    o, d = camera.rays((W, H))
    p = o + (-o[..., 2] / d[..., 2])[..., None] * d
    lit = notes_formula(np.array([0, 0, 1.0]), p, camera.position, (0.2, 0.1, 1.0),
                        (1, 1, 1), ka, kd, (0, 0, 0), 6, 2)
    spec = notes_formula(np.array([0, 0, 1.0]), p, camera.position, (0.2, 0.1, 1.0),
                         (0, 0, 0), ka, (0, 0, 0), ks, 6, 2)
    want = lit + spec * nearest_texels(uv)
    assert keep.sum() > 1000 and spec[keep].max() > 0.2   # (a highlight to see)
    assert np.abs(got - np.clip(want, 0, 1))[keep].max() <= DECODE


@pytest.mark.parametrize("transparency", ["exact", "blend"])
def test_the_opacity_map_lets_what_is_behind_show(gl_context, transparency):
    """A white quad whose opacity map is 0 on its left half and 255 on its right, over a
    red one: unlit (illum 0), the left shows the red quad, the right the white one, and
    the opacity (0.5 everywhere) weighs them: 0.5 white + 0.5 red on the right."""
    alpha = np.zeros((2, 2), np.uint8)
    alpha[:, 1] = 255
    front = Material(diffuse=(1, 1, 1), illum=0, opacity=0.5,
                     opacity_texture=Texture(alpha, filter="nearest"))
    scene = Scene(background=(0, 0, 0))
    back = glshade.geometry.primitives.plane(2.0)
    scene.add(back, Material(diffuse=(1, 0, 0), illum=0), translation=(0, 0, -0.5))
    scene.add(glshade.geometry.primitives.plane(2.0), front)
    camera = Camera.look_at((0, 0, 3), (0, 0, 0), fov_y=30)
    with glshade.Renderer(W, H, samples=0, context=gl_context) as r:
        got = r.render_frame(scene, camera, "phong", color_dtype="f4",
                             transparency=transparency).color[..., :3]
    assert np.abs(got[H // 2, W // 2 - 8] - [1, 0, 0]).max() <= 2e-3       # left: red
    assert np.abs(got[H // 2, W // 2 + 8] - [1, 0.5, 0.5]).max() <= 4e-3   # right: mixed
