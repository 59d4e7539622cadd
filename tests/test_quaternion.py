"""The quaternion algebra against the notes (equation 3.7, Propositions 3.2-3.6) and
against scipy's rotations as an independent oracle."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

from glshade import GeometryError
from glshade import quaternion as Q

O = np.array([0.0, 0, 0, 1])
I, J, K = np.eye(4)[0], np.eye(4)[1], np.eye(4)[2]


def random_unit(rng, n):
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def pure(v):
    v = np.asarray(v, float)
    return np.concatenate([v, np.zeros(v.shape[:-1] + (1,))], axis=-1)


def angle(a, b):
    """Angle between vectors (..., 3)."""
    c = np.einsum("...i,...i->...", a, b)
    s = np.linalg.norm(np.cross(a, b), axis=-1)
    return np.arctan2(s, c)


# ----------------------------------------------------------------------- algebra

def hamilton(p, q):
    """The product written out term by term from the basis rules (an independent oracle)."""
    x1, y1, z1, w1 = p
    x2, y2, z2, w2 = q
    return np.array([
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
    ])


def test_product_matches_hand_expanded_hamilton(rng):
    p, q = rng.normal(size=(2, 500, 4))
    expected = np.stack([hamilton(a, b) for a, b in zip(p, q)])
    np.testing.assert_allclose(Q.multiply(p, q), expected, atol=1e-12)


def test_basis_rules():
    m = Q.multiply
    for e in (I, J, K):
        np.testing.assert_array_equal(m(e, e), -O)
        np.testing.assert_array_equal(m(O, e), e)
        np.testing.assert_array_equal(m(e, O), e)
    np.testing.assert_array_equal(m(O, O), O)
    np.testing.assert_array_equal(m(I, J), K)
    np.testing.assert_array_equal(m(J, I), -K)
    np.testing.assert_array_equal(m(J, K), I)
    np.testing.assert_array_equal(m(K, J), -I)
    np.testing.assert_array_equal(m(K, I), J)
    np.testing.assert_array_equal(m(I, K), -J)


def test_product_of_vectors_eq_3_6(rng):
    u, v = rng.normal(size=(2, 100, 3))
    uv = Q.multiply(pure(u), pure(v))
    np.testing.assert_allclose(uv[:, 3], -np.einsum("ij,ij->i", u, v), atol=1e-12)
    np.testing.assert_allclose(uv[:, :3], np.cross(u, v), atol=1e-12)
    # the ERRATA's corrected components: O part -(u1v1 + u2v2 + u3v3), i part u2v3 - u3v2
    np.testing.assert_allclose(uv[:, 0], u[:, 1] * v[:, 2] - u[:, 2] * v[:, 1], atol=1e-12)


def test_associative_not_commutative_and_norm_multiplicative(rng):
    p, q, r = rng.normal(size=(3, 200, 4))
    np.testing.assert_allclose(Q.multiply(Q.multiply(p, q), r), Q.multiply(p, Q.multiply(q, r)),
                               atol=1e-10)
    assert not np.allclose(Q.multiply(p, q), Q.multiply(q, p))
    np.testing.assert_allclose(Q.norm(Q.multiply(p, q)), Q.norm(p) * Q.norm(q), rtol=1e-12)


def test_conjugate_inverse_identity(rng):
    q = rng.normal(size=(50, 4))
    np.testing.assert_allclose(Q.multiply(q, Q.inverse(q)), np.broadcast_to(O, q.shape),
                               atol=1e-12)
    np.testing.assert_allclose(Q.multiply(q, Q.conjugate(q))[:, 3], Q.norm(q) ** 2)
    np.testing.assert_array_equal(Q.identity((2,)), [O, O])
    with pytest.raises(GeometryError, match="no inverse"):
        Q.inverse([0, 0, 0, 0])
    with pytest.raises(GeometryError, match=r"\(\.\.\., 4\)"):
        Q.multiply([1, 2, 3], O)


# ------------------------------------------------------------- Propositions 3.2 - 3.6

def q_theta(n, theta):
    """The notes' q(N, theta) = cos(theta) O + sin(theta) N of Propositions 3.2 and 3.3."""
    return np.append(np.sin(theta) * n, np.cos(theta))


def in_plane_angle(p, p_rotated, basis_a, basis_b):
    """Signed angle of a rotation inside the plane spanned by two orthonormal 4-vectors."""
    a = np.array([p @ basis_a, p @ basis_b])
    b = np.array([p_rotated @ basis_a, p_rotated @ basis_b])
    return np.arctan2(a[0] * b[1] - a[1] * b[0], a @ b)


def test_proposition_3_2_plane_of_O_and_N(rng):
    n = rng.normal(size=3)
    n /= np.linalg.norm(n)
    theta = 0.7
    q = q_theta(n, theta)
    p = 0.3 * O + 1.9 * pure(n)  # a quaternion in the plane of O, N
    basis = (O, pure(n))
    assert in_plane_angle(p, Q.multiply(q, p), *basis) == pytest.approx(theta)
    assert in_plane_angle(p, Q.multiply(p, q), *basis) == pytest.approx(theta)
    assert in_plane_angle(p, Q.multiply(p, Q.conjugate(q)), *basis) == pytest.approx(-theta)
    np.testing.assert_allclose(Q.multiply(Q.multiply(q, p), Q.conjugate(q)), p, atol=1e-12)


def test_proposition_3_3_plane_perpendicular_to_O_and_N(rng):
    n = np.array([0.0, 0.0, 1.0])
    theta = 0.4
    q = q_theta(n, theta)
    v = pure([1.0, 0.0, 0.0])
    # the plane perpendicular to O and N, oriented by N (right hand): i, j
    basis = (pure([1, 0, 0]), pure([0, 1, 0]))
    assert in_plane_angle(v, Q.multiply(q, v), *basis) == pytest.approx(theta)
    assert in_plane_angle(v, Q.multiply(v, q), *basis) == pytest.approx(-theta)
    assert in_plane_angle(v, Q.multiply(v, Q.conjugate(q)), *basis) == pytest.approx(theta)
    s = Q.multiply(Q.multiply(q, v), Q.conjugate(q))
    assert in_plane_angle(v, s, *basis) == pytest.approx(2 * theta)


def test_proposition_3_4_sandwich_rotates_by_phi_about_n(rng):
    axes = rng.normal(size=(200, 3))
    phis = rng.uniform(-np.pi, np.pi, 200)
    v = rng.normal(size=(200, 3))
    q = Q.from_axis_angle(axes, phis)
    expected = Rotation.from_rotvec(axes / np.linalg.norm(axes, axis=1, keepdims=True)
                                    * phis[:, None]).apply(v)
    np.testing.assert_allclose(Q.rotate(q, v), expected, atol=1e-12)
    # literally the sandwich q v q*
    sandwich = Q.multiply(Q.multiply(q, pure(v)), Q.conjugate(q))
    np.testing.assert_allclose(sandwich[:, :3], expected, atol=1e-12)
    np.testing.assert_allclose(sandwich[:, 3], 0, atol=1e-12)


def test_z_quarter_turn_maps_x_to_y():
    q = Q.from_axis_angle([0, 0, 1], np.pi / 2)
    np.testing.assert_allclose(Q.rotate(q, [1, 0, 0]), [0, 1, 0], atol=1e-15)
    np.testing.assert_allclose(Q.to_matrix(q) @ [1, 0, 0], [0, 1, 0], atol=1e-15)
    np.testing.assert_allclose([1, 0, 0] @ Q.to_matrix(q, "row"), [0, 1, 0], atol=1e-15)


def test_proposition_3_5_mirror(rng):
    n = rng.normal(size=(100, 3))
    v = rng.normal(size=(100, 3))
    m = Q.mirror(n, v)
    unit = n / np.linalg.norm(n, axis=1, keepdims=True)
    # N v N as quaternion products
    nvn = Q.multiply(Q.multiply(pure(unit), pure(v)), pure(unit))
    np.testing.assert_allclose(nvn[:, :3], m, atol=1e-12)
    # flips the normal component, keeps the rest, twice is the identity
    np.testing.assert_allclose(np.einsum("ij,ij->i", m, unit), -np.einsum("ij,ij->i", v, unit),
                               atol=1e-12)
    np.testing.assert_allclose(np.cross(m, unit), np.cross(v, unit), atol=1e-12)
    np.testing.assert_allclose(Q.mirror(n, m), v, atol=1e-12)


def test_proposition_3_6_scale_and_conformal(rng):
    v = rng.normal(size=(10, 3))
    np.testing.assert_allclose(Q.scale(2.5, v), 2.5 * v)
    with pytest.raises(GeometryError, match=">= 0"):
        Q.scale(-1, v)
    # Theorem 3.1: any quaternion = rotation by its direction, scaling by |q|^2
    q = rng.normal(size=4) * 3
    unit = q / np.linalg.norm(q)
    np.testing.assert_allclose(Q.conformal(q, v), np.dot(q, q) * Q.rotate(unit, v),
                               atol=1e-12)
    # composition of sandwiches is the product (3.12)
    p = rng.normal(size=4)
    np.testing.assert_allclose(Q.conformal(Q.compose(p, q), v),
                               Q.conformal(p, Q.conformal(q, v)), atol=1e-10)


def test_sandwich_preserves_length_and_angles(rng):
    q = random_unit(rng, 100)
    a, b = rng.normal(size=(2, 100, 3))
    ra, rb = Q.rotate(q, a), Q.rotate(q, b)
    np.testing.assert_allclose(np.linalg.norm(ra, axis=1), np.linalg.norm(a, axis=1))
    np.testing.assert_allclose(angle(ra, rb), angle(a, b), atol=1e-12)


def test_points_about_a_fixed_point(rng):
    q = Q.from_axis_angle([0, 0, 1], np.pi / 2)
    center = np.array([1.0, 1.0, 0.0])
    np.testing.assert_allclose(Q.transform_points(q, [2.0, 1.0, 5.0], center), [1, 2, 5],
                               atol=1e-15)
    np.testing.assert_allclose(Q.mirror_points([1, 0, 0], [3.0, 2.0, 1.0], [1, 0, 0]),
                               [-1, 2, 1])


def test_axis_angle_round_trip(rng):
    axes = rng.normal(size=(100, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    angles = rng.uniform(0, np.pi, 100)
    axis, ang = Q.to_axis_angle(Q.from_axis_angle(axes, angles))
    np.testing.assert_allclose(ang, angles, atol=1e-12)
    np.testing.assert_allclose(axis, axes, atol=1e-9)


# ------------------------------------------------------------------ matrices vs scipy

def scipy_quat(r):
    return r.as_quat()  # scalar-last, like glshade


def matrix_cases(rng):
    r = Rotation.random(500, random_state=1)
    near = Rotation.from_rotvec(rng.normal(size=(100, 3)) * 1e-9)
    axes = rng.normal(size=(100, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    half_turns = Rotation.from_rotvec(axes * np.pi)  # trace = -1
    axis_turns = Rotation.from_rotvec(np.pi * np.eye(3))  # the exact axis-aligned ones
    return Rotation.concatenate([r, near, half_turns, axis_turns])


def test_to_matrix_matches_scipy(rng):
    r = matrix_cases(rng)
    np.testing.assert_allclose(Q.to_matrix(scipy_quat(r)), r.as_matrix(), atol=1e-12)


def test_from_matrix_is_exact_for_all_rotations(rng):
    r = matrix_cases(rng)
    q = Q.from_matrix(r.as_matrix())
    np.testing.assert_allclose(Q.norm(q), 1.0, atol=1e-15)
    assert (Q.angle_between(q, scipy_quat(r)) < 1e-7).all()
    np.testing.assert_allclose(Q.to_matrix(q), r.as_matrix(), atol=1e-12)
    # the 180-degree ones, where trace = -1
    trace = np.trace(r.as_matrix()[-103:], axis1=1, axis2=2)
    np.testing.assert_allclose(trace, -1, atol=1e-12)
    np.testing.assert_allclose(Q.to_matrix(q[-103:]), r.as_matrix()[-103:], atol=1e-12)


def test_rotate_matches_scipy(rng):
    r = Rotation.random(1000, random_state=3)
    v = rng.normal(size=(1000, 3))
    np.testing.assert_allclose(Q.rotate(scipy_quat(r), v), r.apply(v), atol=1e-12)


# ----------------------------------------------------------------------------- slerp

def test_slerp_matches_scipy_for_10000_pairs(rng):
    n = 10_000
    r0, r1 = Rotation.random(n, random_state=5), Rotation.random(n, random_state=6)
    t = rng.uniform(0, 1, n)
    ours = Q.slerp(r0.as_quat(), r1.as_quat(), t)
    # scipy: one Slerp over alternating keys, evaluated inside each pair's interval
    keys = Rotation.concatenate([r0, r1])
    order = np.stack([np.arange(n), n + np.arange(n)], 1).ravel()
    times = np.arange(2 * n, dtype=float)
    sc = Slerp(times, keys[order])(2 * np.arange(n) + t)
    theirs = sc.as_quat()
    aligned = np.where((np.einsum("ij,ij->i", ours, theirs) < 0)[:, None], -theirs, theirs)
    np.testing.assert_allclose(ours, aligned, atol=1e-12)


def test_slerp_unit_length_and_exact_ends(rng):
    q0, q1 = random_unit(rng, 1000), random_unit(rng, 1000)
    t = np.linspace(0, 1, 11)[:, None]
    s = Q.slerp(q0, q1, t)
    np.testing.assert_allclose(Q.norm(s), 1.0, atol=1e-14)
    np.testing.assert_array_equal(Q.slerp(q0, q1, 0.0), q0)
    end = Q.slerp(q0, q1, 1.0)
    sign = np.sign(np.einsum("ij,ij->i", q0, q1))[:, None]
    np.testing.assert_allclose(end, sign * q1, atol=1e-15)


def test_slerp_constant_angular_speed(rng):
    q0, q1 = random_unit(rng, 50), random_unit(rng, 50)
    frames = Q.slerp(q0, q1, np.linspace(0, 1, 21)[:, None])  # (21, 50, 4)
    steps = Q.angle_between(frames[:-1], frames[1:])
    np.testing.assert_allclose(steps, steps[:1].repeat(20, 0), atol=1e-12)
    total = Q.angle_between(q0, q1)
    np.testing.assert_allclose(steps.sum(0), total, atol=1e-10)


def test_slerp_shortest_arc_for_opposite_signs(rng):
    q0 = random_unit(rng, 100)
    q1 = -Q.multiply(q0, Q.from_axis_angle([0, 1, 0], 0.2))  # 0.2 rad away, opposite sign
    mid = Q.slerp(q0, q1, 0.5)
    np.testing.assert_allclose(Q.angle_between(q0, mid), 0.1, atol=1e-12)


def test_slerp_nearly_equal_and_equal_keys(rng):
    q0 = random_unit(rng, 100)
    for eps in (1e-9, 1e-13, 0.0):
        q1 = Q.normalize(q0 + eps * rng.normal(size=q0.shape))
        s = Q.slerp(q0, q1, 0.3)
        assert np.isfinite(s).all()
        np.testing.assert_allclose(Q.norm(s), 1.0, atol=1e-15)
        np.testing.assert_allclose(s, q0 + 0.3 * (q1 - q0), atol=1e-14)


def test_slerp_extrapolates_on_the_same_great_circle():
    q0 = Q.identity()
    q1 = Q.from_axis_angle([0, 0, 1], 0.5)
    np.testing.assert_allclose(Q.slerp(q0, q1, 2.0), Q.from_axis_angle([0, 0, 1], 1.0),
                               atol=1e-15)
    np.testing.assert_allclose(Q.slerp(q0, q1, -1.0), Q.from_axis_angle([0, 0, 1], -0.5),
                               atol=1e-15)


# ------------------------------------------------------------------- spline (C1)

def angular_velocity(q, dt):
    """World-frame angular velocity (rad/s) between consecutive samples."""
    rel = Q.multiply(q[1:], Q.conjugate(q[:-1]))
    rel = Q.canonical(rel)
    return 2 * Q.log(rel) / dt


def test_spline_passes_keys_and_is_c1(rng):
    times = np.array([0.0, 1.0, 2.5, 3.0, 5.0])
    keys = random_unit(rng, 5)
    at_keys = Q.spline(times, keys, times)
    assert (Q.angle_between(at_keys, keys) < 1e-7).all()
    dt = 1e-5
    for tk in times[1:-1]:
        before = angular_velocity(Q.spline(times, keys, [tk - 2 * dt, tk - dt]), dt)
        after = angular_velocity(Q.spline(times, keys, [tk + dt, tk + 2 * dt]), dt)
        np.testing.assert_allclose(before[0], after[0], atol=1e-3)
        # piecewise slerp has a kink in angular velocity there
        i = int(np.searchsorted(times, tk))
        s_before = angular_velocity(Q.slerp(keys[i - 1], keys[i], np.array([1 - dt / (
            times[i] - times[i - 1]), 1.0])), dt)
        s_after = angular_velocity(Q.slerp(keys[i], keys[i + 1], np.array([0.0, dt / (
            times[i + 1] - times[i])])), dt)
        assert np.linalg.norm(s_before - s_after) > 1e-2


def test_squad_endpoints(rng):
    q0, q1, s0, s1 = random_unit(rng, 4)
    np.testing.assert_allclose(Q.squad(q0, q1, s0, s1, 0.0), q0, atol=1e-15)
    assert Q.angle_between(Q.squad(q0, q1, s0, s1, 1.0), q1) < 1e-7


def test_canonical_and_log_exp(rng):
    q = random_unit(rng, 100)
    c = Q.canonical(q)
    assert (c[:, 3] >= 0).all()
    assert (Q.angle_between(c, q) < 1e-7).all()
    np.testing.assert_allclose(Q.exp(Q.log(c)), c, atol=1e-12)


def test_normalisation_against_drift(rng):
    """Composing a million small rotations: without renormalising the norm drifts; with
    it, it stays at 1 within a few ulps. 100 chains of 10,000 steps each."""
    steps = Q.from_axis_angle(rng.normal(size=(100, 3)), 1e-3 * np.ones(100))
    raw = Q.identity((100,))
    kept = Q.identity((100,))
    for _ in range(10_000):
        raw = Q.multiply(raw, steps)
        kept = Q.normalize(Q.multiply(kept, steps))
    drift_raw = np.abs(Q.norm(raw) - 1).max()
    drift_kept = np.abs(Q.norm(kept) - 1).max()
    assert drift_kept <= 4e-16
    assert drift_raw > 10 * max(drift_kept, 1e-16)


def test_from_matrix_refuses_mirrors_and_flat_frames(rng):
    """A rotation's determinant is +1; a mirror's -1 has no quaternion (it used to come back
    as some rotation without a word)."""
    r = Rotation.random(4, random_state=1).as_matrix()
    mirrored = r.copy()
    mirrored[2] = r[2] @ np.diag([1.0, 1.0, -1.0])
    with pytest.raises(GeometryError, match=r"matrix \(2,\) is not a rotation: its "
                                            r"determinant is -1"):
        Q.from_matrix(mirrored)
    with pytest.raises(GeometryError, match="the matrix is not a rotation.*determinant is 0"):
        Q.from_matrix(np.zeros((3, 3)))
    np.testing.assert_allclose(np.abs(Q.from_matrix(r)), np.abs(Rotation.from_matrix(r)
                                                                 .as_quat()), atol=1e-12)
