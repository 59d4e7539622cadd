"""Bezier and rational Bezier patches against oracles written here: closed-form quadrics,
a power-basis evaluation, finite differences, the patches' own subdivision; the teapot's
topology and data file; tessellation error against dense evaluation; crack-freeness."""

from math import comb

import numpy as np
import pytest

from glshade import patches as G
from glshade.errors import GeometryError, InputError
from glshade.patches import PatchSet, tessellate

RNG = np.random.default_rng(7)
U, V = RNG.random(40), RNG.random(40)


def power_basis(points, weights, u, v):
    """The test's own evaluation: each patch converted to the monomial basis,
    ``S(u, v) = sum c_ab u^a v^b`` on the mass-points, then projected."""
    h = np.concatenate([points * weights[..., None], weights[..., None]], -1)
    m, n = h.shape[1] - 1, h.shape[2] - 1

    def to_power(d):  # M[i, a]: the t^a coefficient of B_i^d(t)
        M = np.zeros((d + 1, d + 1))
        for i in range(d + 1):
            for a in range(i, d + 1):
                M[i, a] = comb(d, i) * comb(d - i, a - i) * (-1) ** (a - i)
        return M

    Mu, Mv = to_power(m), to_power(n)
    c = np.einsum("ia,jb,pijk->pabk", Mu, Mv, h)
    uu = u[:, None] ** np.arange(m + 1)
    vv = v[:, None] ** np.arange(n + 1)
    out = np.einsum("ka,kb,pabc->pkc", uu, vv, c)
    return out[..., :3] / out[..., 3:]


@pytest.mark.parametrize("name, exact", [
    ("sphere", lambda p: np.linalg.norm(p, axis=-1) - 1.0),
    ("torus", lambda p: np.hypot(np.hypot(p[..., 0], p[..., 2]) - 1.0, p[..., 1]) - 0.25),
    ("cylinder", None), ("cone", None)])
def test_quadric_patches_lie_on_the_exact_surface_with_radial_normals(name, exact):
    ps = getattr(G, name)()
    p, n = ps.evaluate(U, V), ps.normals(U, V)
    if name == "sphere":
        assert np.abs(exact(p)).max() < 1e-12
        assert np.abs(n - p).max() < 1e-12  # the unit sphere's normal is its point
    elif name == "torus":
        assert np.abs(exact(p)).max() < 1e-12
        rho = np.hypot(p[..., 0], p[..., 2])[..., None]
        ring = p * [1, 0, 1] / rho  # the nearest point of the tube's centre circle
        assert np.abs(n - (p - ring) / 0.25).max() < 1e-11
    elif name == "cylinder":  # radius 1, |y| <= 1, caps included
        rho = np.hypot(p[..., 0], p[..., 2])
        side = np.abs(np.abs(p[..., 1]) - 1) > 1e-12
        assert np.abs(rho[side] - 1).max() < 1e-12 and (rho <= 1 + 1e-12).all()
        assert np.abs(n[side] - p[side] * [1, 0, 1]).max() < 1e-12
        assert np.allclose(n[~side], [0, 1, 0] * np.sign(p[~side][:, 1:2]))
    else:  # cone: apex (0, 1, 0), base radius 1 at y = -1: rho = (1 - y) / 2
        rho = np.hypot(p[..., 0], p[..., 2])
        side = np.abs(p[..., 1] + 1) > 1e-12
        assert np.abs(rho[side] - (1 - p[..., 1][side]) / 2).max() < 1e-12
        expect = np.concatenate([2 * p[side][:, [0]] / rho[side][:, None],
                                 np.ones((side.sum(), 1)),
                                 2 * p[side][:, [2]] / rho[side][:, None]], 1) / np.sqrt(5)
        assert np.abs(n[side] - expect).max() < 1e-11


def random_patches(m, n, rational):
    pts = RNG.normal(size=(3, m + 1, n + 1, 3))
    w = RNG.uniform(0.3, 2.0, (3, m + 1, n + 1)) if rational else None
    return PatchSet(pts, w)


@pytest.mark.parametrize("m, n, rational", [(3, 3, False), (3, 2, True), (1, 4, True),
                                            (5, 1, False)])
def test_de_casteljau_equals_bernstein_equals_the_power_basis(m, n, rational):
    ps = random_patches(m, n, rational)
    bern = ps.evaluate(U, V)
    assert np.abs(ps.evaluate_de_casteljau(U[:8], V[:8]) - bern[:, :8]).max() < 1e-12
    assert np.abs(power_basis(ps.points, ps.weights, U, V) - bern).max() < 1e-11


@pytest.mark.parametrize("rational", [False, True])
def test_derivatives_match_finite_differences(rational):
    ps = random_patches(3, 2, rational)
    d = ps.derivatives(U, V, order=2)
    h = 1e-5
    S = lambda u, v: power_basis(ps.points, ps.weights, u, v)  # noqa: E731
    fd_u = (S(U + h, V) - S(U - h, V)) / (2 * h)
    fd_v = (S(U, V + h) - S(U, V - h)) / (2 * h)
    fd_uv = (S(U + h, V + h) - S(U + h, V - h) - S(U - h, V + h) + S(U - h, V - h)) / (4 * h * h)
    scale = np.abs(d["Su"]).max()
    assert np.abs(d["Su"] - fd_u).max() < 1e-6 * scale
    assert np.abs(d["Sv"] - fd_v).max() < 1e-6 * np.abs(d["Sv"]).max()
    assert np.abs(d["Suv"] - fd_uv).max() < 1e-3 * np.abs(d["Suv"]).max()


@pytest.mark.parametrize("direction", ["u", "v"])
def test_subdivision_reproduces_the_surface(direction):
    ps = random_patches(3, 3, True)
    a, b = ps.subdivide(0.3, direction)
    if direction == "u":
        left, right = ps.evaluate(0.3 * U, V), ps.evaluate(0.3 + 0.7 * U, V)
    else:
        left, right = ps.evaluate(U, 0.3 * V), ps.evaluate(U, 0.3 + 0.7 * V)
    assert np.abs(a.evaluate(U, V) - left).max() < 1e-12
    assert np.abs(b.evaluate(U, V) - right).max() < 1e-12
    # degree elevation too: the same surface with one more row
    assert np.abs(ps.elevated(4, 5).evaluate(U, V) - ps.evaluate(U, V)).max() < 1e-12


def test_normals_at_collapsed_edges_are_their_limits():
    s = G.sphere()  # (lower patches: the south pole at u = 0; upper: the north at u = 1)
    v = [0.0, 0.2, 0.5, 1.0]
    lower, upper = s[0::2].normals([0.0] * 4, v), s[1::2].normals([1.0] * 4, v)
    assert np.allclose(lower, [0, -1, 0]) and np.allclose(upper, [0, 1, 0])
    assert np.allclose(s[0::2].evaluate([0.0] * 4, v), [0, -1, 0])
    t = G.teapot()
    top = t.evaluate([0.0, 1.0], [0.5, 0.5]).reshape(-1, 3)
    up = t.normals([0.0, 1.0], [0.5, 0.5]).reshape(-1, 3)
    # the lid's knob top (highest point) faces up, the bottom's centre faces down
    assert up[np.argmax(top[:, 1])][1] > 0.999
    assert up[np.argmin(np.abs(top[:, 1]) + np.hypot(top[:, 0], top[:, 2]))][1] < -0.999


def test_the_teapot_as_a_b_rep():
    t = G.named("teapot")
    e = t.euler()
    # body (rim, body, bottom), lid, handle, spout; open at the handle's and spout's two
    # ends each, the lid's edge and the pot's rim: six boundary loops, no handles
    assert (e.F, e.C, e.B, e.G) == (32, 4, 6, 0) and e.holds and e.is_manifold
    for name, genus in (("sphere", 0), ("torus", 1), ("cylinder", 0), ("cone", 0)):
        r = G.named(name).euler()
        assert r.is_closed and r.G == genus and r.holds, name


def test_the_classic_patch_file_round_trips_and_bad_files_name_their_line(tmp_path):
    t = G.teapot()
    path = tmp_path / "teapot.txt"
    path.write_text(G.write_patches(t))
    again = G.read_patches(path)
    assert np.array_equal(again.points, t.points)
    lines = path.read_text().splitlines()
    lines[3] = "1,2,3"
    path.write_text("\n".join(lines))
    with pytest.raises(InputError, match=r"teapot.txt:4: expected 16 values, got 3"):
        G.read_patches(path)
    lines[3] = "1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,999"
    path.write_text("\n".join(lines))
    with pytest.raises(InputError, match=r"teapot.txt:4: a control-point index is outside"):
        G.read_patches(path)


def grid_positions(tess, p):
    """Patch ``p``'s vertices as its (nu+1, nv+1) grid, from the tessellation's uv."""
    nu, nv = tess.levels[p]
    mine = np.flatnonzero(tess.patch == p)
    i = np.rint(tess.uv[mine, 0] * nu).astype(int)
    j = np.rint(tess.uv[mine, 1] * nv).astype(int)
    grid = np.empty((nu + 1, nv + 1, 3))
    grid[i, j] = tess.mesh.vertices[mine]
    return grid


@pytest.mark.parametrize("name, tol", [("teapot", 2e-3), ("torus", 1e-3), ("sphere", 1e-4)])
def test_tessellation_error_is_below_the_tolerance(name, tol):
    surface = G.named(name)
    tess = tessellate(surface, tolerance=tol)
    worst = 0.0
    for p in range(len(surface.patches)):
        nu, nv = tess.levels[p]
        grid = grid_positions(tess, p)
        # dense points in every cell, against the cell's two triangles (a-b-c, a-c-d)
        s, t = np.meshgrid(np.linspace(0, 1, 7), np.linspace(0, 1, 7), indexing="ij")
        s, t = s.ravel(), t.ravel()
        ci, cj = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
        ci, cj = ci.ravel()[:, None], cj.ravel()[:, None]
        u, v = (ci + s) / nu, (cj + t) / nv
        exact = surface.patches[p].evaluate(u.ravel(), v.ravel())[0].reshape(u.shape + (3,))
        a, b = grid[ci, cj], grid[ci + 1, cj]
        c, d = grid[ci + 1, cj + 1], grid[ci, cj + 1]
        S, T = s[None, :, None], t[None, :, None]
        lower = a + S * (b - a) + T * (c - b)
        upper = a + T * (d - a) + S * (c - d)
        linear = np.where(S >= T, lower, upper)
        worst = max(worst, float(np.linalg.norm(linear - exact, axis=-1).max()))
    assert worst < tol, worst
    assert worst > tol / 50  # (and the bound is not wildly loose)


def test_shared_boundary_vertices_are_bit_identical_at_mixed_levels():
    surface = G.named("teapot")
    tess = tessellate(surface, tolerance=5e-3)
    assert len(np.unique(tess.levels)) > 3  # (mixed levels)
    e = surface.edges
    checked = 0
    for k in np.flatnonzero(e.uses == 2):
        (pa, sa), (pb, sb) = np.argwhere(e.side_edge == k)
        rows = []
        for p, s in ((pa, sa), (pb, sb)):
            g = grid_positions(tess, p)
            row = [g[0], g[-1], g[:, 0], g[:, -1]][s]
            rows.append(row[::-1] if e.side_reversed[p, s] else row)
        assert rows[0].shape == rows[1].shape
        assert rows[0].tobytes() == rows[1].tobytes()  # the same bits, point for point
        checked += 1
    assert checked >= 30


def test_a_scene_takes_patches_and_bad_requests_are_refused():
    from glshade import Scene

    scene = Scene()
    model = scene.add(G.named("torus"))
    assert model.mesh.normals_from_file is not None  # the exact normals
    with pytest.raises(GeometryError, match="one of level, tolerance or pixels"):
        tessellate(G.sphere())
    with pytest.raises(GeometryError, match="than the 512 allowed"):
        tessellate(G.teapot(), tolerance=1e-12)
    with pytest.raises(GeometryError, match="weights must be positive"):
        PatchSet(np.zeros((1, 2, 2, 3)), -np.ones((1, 2, 2)))


def test_the_command_line_renders_and_describes_patches(tmp_path):
    import json

    from tests.conftest import BACKEND, glshade

    out = tmp_path / "pot.png"
    r = glshade("render", "patches:teapot", "--tolerance", "1e-2", "-o", str(out),
                "--size", "96x72", "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    assert out.stat().st_size > 0
    r = glshade("info", "patches:teapot", "--json")
    assert r.returncode == 0, r.stderr
    info = json.loads(r.stdout)
    assert (info["patches"], info["degree"], info["topology"]["C"]) == (32, [3, 3], 4)
    assert info["topology"]["euler_holds"] and info["triangles"] > 1000
    for args, message in ((("info", "patches:kettle"), "unknown patch model 'kettle'"),
                          (("info", "primitive:cube", "--tolerance", "0.1"),
                           "--tolerance is for patches:NAME"),
                          (("info", "patches:teapot", "--tolerance", "-1"), "--tolerance")):
        r = glshade(*args)
        assert r.returncode == 2 and message in r.stderr, (args, r.stderr)
        assert "Traceback" not in r.stderr
