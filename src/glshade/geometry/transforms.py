"""Matrices for cameras and models, and the conventions every part of glshade follows.

- Right-handed world; a camera looks down its local -z with +y up (OpenGL).
- Column vectors: ``p2 = M @ p``. Matrices are row-major numpy arrays, so a mat4 goes to
  GLSL transposed; :func:`gl_bytes` is the one place that does it.
- pyrr builds matrices for ROW vectors (``p2 = p @ M``); :func:`perspective` and
  :func:`orthographic` transpose its output, here and nowhere else.
- Quaternions are scalar-last ``[x, y, z, w]``; radians everywhere, except a camera's
  ``fov_y`` in degrees.
- Front faces are counter-clockwise seen from outside.
"""

from __future__ import annotations

import math

import numpy as np
import pyrr
from numpy.typing import ArrayLike, NDArray

from ..errors import GeometryError

#: the largest coordinate, distance or scale glshade works with (and 1 / it the smallest
#: plane distance or scale): the square and the product of two such numbers stay finite in
#: float64, so lengths, ratios and matrix products never overflow or underflow
MAX_COORDINATE = 1e150
#: the largest world coordinate the GPU can draw or light from: its 32-bit arithmetic
#: squares lengths (3.4e38 is float32's largest)
MAX_DRAWABLE_COORDINATE = 1e18

__all__ = ["MAX_COORDINATE", "MAX_DRAWABLE_COORDINATE", "look_at", "perspective",
           "orthographic", "normal_matrix", "compose_transform",
           "gl_bytes", "box_corners", "z_up_to_y_up", "y_up_to_z_up", "model_matrices",
           "outside_frustum"]

Array = NDArray[np.float64]


def look_at(eye: ArrayLike, target: ArrayLike, up: ArrayLike = (0, 1, 0)) -> Array:
    """World-to-view matrix ``(4, 4)`` of a camera at ``eye`` looking at ``target``.

    Parameters
    ----------
    eye : array_like
        ``(3,)`` the camera's position.
    target : array_like
        ``(3,)`` the point it looks at.
    up : array_like
        ``(3,)`` roughly up.
    """
    # (three 3-vectors: plain floats, since a camera may be made every frame)
    try:
        (ex, ey, ez), (tx, ty, tz), (ux, uy, uz) = (
            [float(c) for c in a] for a in (eye, target, up))  # type: ignore[union-attr,arg-type]
    except (TypeError, ValueError):
        raise GeometryError("look_at: eye, target and up must be 3 numbers each") from None
    if not all(map(math.isfinite, (ex, ey, ez, tx, ty, tz, ux, uy, uz))):
        raise GeometryError("look_at: eye, target and up must be finite numbers")
    fx, fy, fz = tx - ex, ty - ey, tz - ez
    length = math.hypot(fx, fy, fz)  # (no overflow: a camera 1e300 away still has a view)
    if length == 0:
        raise GeometryError("look_at: eye and target are the same point")
    if not math.isfinite(length):
        raise GeometryError("look_at: eye and target are too far apart to subtract "
                            f"({length:g}): keep coordinates within 1e300")
    fx, fy, fz = fx / length, fy / length, fz / length
    up_length = math.hypot(ux, uy, uz)
    if up_length == 0:
        raise GeometryError("look_at: up must not be zero")
    ux, uy, uz = ux / up_length, uy / up_length, uz / up_length
    sx, sy, sz = fy * uz - fz * uy, fz * ux - fx * uz, fx * uy - fy * ux
    side = math.hypot(sx, sy, sz)
    if side < 1e-12:
        raise GeometryError(f"look_at: up {[ux, uy, uz]} is parallel to the view direction")
    sx, sy, sz = sx / side, sy / side, sz / side
    vx, vy, vz = sy * fz - sz * fy, sz * fx - sx * fz, sx * fy - sy * fx
    return np.array([[sx, sy, sz, -(sx * ex + sy * ey + sz * ez)],
                     [vx, vy, vz, -(vx * ex + vy * ey + vz * ez)],
                     [-fx, -fy, -fz, fx * ex + fy * ey + fz * ez],
                     [0.0, 0.0, 0.0, 1.0]])


def perspective(fov_y_deg: float, aspect: float, near: float, far: float) -> Array:
    """OpenGL perspective projection for column vectors (pyrr's, transposed).

    Parameters
    ----------
    fov_y_deg : float
        The vertical field of view in degrees.
    aspect : float
        Width over height.
    near, far : float
        The clip distances, 0 < near < far.
    """
    if not (0 < fov_y_deg < 180):
        raise GeometryError(f"fov_y must be in (0, 180) degrees, got {fov_y_deg}")
    if not (0 < near < far):
        raise GeometryError(f"need 0 < near < far, got near={near}, far={far}")
    if aspect <= 0:
        raise GeometryError(f"aspect must be positive, got {aspect}")
    return pyrr.matrix44.create_perspective_projection(
        fov_y_deg, aspect, near, far, dtype=np.float64).T


def orthographic(height: float, aspect: float, near: float, far: float) -> Array:
    """OpenGL orthographic projection of a view ``height`` world units tall (pyrr's,
    transposed).

    Parameters
    ----------
    height : float
        The view's height in world units.
    aspect : float
        Width over height.
    near, far : float
        The clip distances.
    """
    if height <= 0 or aspect <= 0:
        raise GeometryError(f"height and aspect must be positive, got {height}, {aspect}")
    if not near < far:
        raise GeometryError(f"need near < far, got near={near}, far={far}")
    h, w = height / 2, height * aspect / 2
    return pyrr.matrix44.create_orthogonal_projection(-w, w, -h, h, near, far,
                                                      dtype=np.float64).T


def normal_matrix(model_view: ArrayLike) -> Array:
    """Inverse transpose of the upper 3x3: maps normals so they stay perpendicular to
    surfaces under non-uniform scaling.

    Parameters
    ----------
    model_view : array_like
        ``(4, 4)`` (or ``(3, 3)``) the matrix that moves the points.
    """
    m = np.asarray(model_view, dtype=np.float64)[:3, :3]
    return np.linalg.inv(m).T


def compose_transform(rotation: ArrayLike | None = None, translation: ArrayLike = (0, 0, 0),
                      scale: ArrayLike = 1.0) -> Array:
    """``T @ R @ S`` as a 4x4 matrix from a quaternion, a translation and a (per-axis)
    scale.

    Parameters
    ----------
    rotation : array_like or None
        ``(4,)`` a unit quaternion ``(x, y, z, w)`` (None: none).
    translation : array_like
        ``(3,)`` scene units.
    scale : float or array_like
        Uniform, or ``(3,)`` per axis.
    """
    from ..quaternion import to_matrix

    m = np.eye(4)
    r = np.eye(3) if rotation is None else to_matrix(rotation)
    m[:3, :3] = r * np.broadcast_to(np.asarray(scale, dtype=np.float64), (3,))
    m[:3, 3] = translation
    return m


def gl_bytes(matrix: ArrayLike) -> bytes:
    """A matrix as GLSL wants it: float32, column-major (the transpose of numpy's rows).

    Parameters
    ----------
    matrix : array_like
        ``(4, 4)`` or ``(3, 3)``, numpy's row-major layout.
    """
    return np.ascontiguousarray(np.asarray(matrix, dtype=np.float32).T).tobytes()


def ray_uniforms(proj: ArrayLike, view: ArrayLike) -> dict[str, bytes]:
    """The matrices of a pixel's ray on the GPU (shaders' ``rays.glsl``): ``u_inverse_proj``
    (clip -> view) and ``u_camera_to_world`` (view -> world), inverted in float64. Kept
    apart, not one inverse view-projection: a tiny near plane's rounding then only
    scales a far point along its own ray."""
    return {"u_inverse_proj": gl_bytes(np.linalg.inv(np.asarray(proj, np.float64))),
            "u_camera_to_world": gl_bytes(np.linalg.inv(np.asarray(view, np.float64)))}


def pixel_rays(proj: ArrayLike, view: ArrayLike, viewport) -> dict[str, tuple]:
    """Each pixel's ray as affine uniforms, computed in float64 (a ray's origin on the near
    plane and its span to the far plane are affine in the pixel): ``u_origin0`` /
    ``u_span0`` at the centre of the viewport's first pixel, ``u_origin_dx`` /
    ``u_span_dx`` and ``..._dy`` a pixel's step in x and y. Pixel (i, j) of the viewport
    then has origin ``u_origin0 + i u_origin_dx + j u_origin_dy`` -- two fused
    multiply-adds a pixel where unprojecting costs three matrix products."""
    inverse_proj = np.linalg.inv(np.asarray(proj, np.float64))
    camera_to_world = np.linalg.inv(np.asarray(view, np.float64))
    _, _, w, h = (float(v) for v in viewport)

    def ray(i: float, j: float):
        ndc = np.array([(i + 0.5) / w * 2 - 1, (j + 0.5) / h * 2 - 1])
        a = inverse_proj @ np.array([*ndc, -1.0, 1.0])
        b = inverse_proj @ np.array([*ndc, 1.0, 1.0])
        near = a[:3] / a[3]
        origin = camera_to_world[:3, :3] @ near + camera_to_world[:3, 3]
        return origin, camera_to_world[:3, :3] @ (b[:3] / b[3] - near)

    (o0, s0), (ox, sx), (oy, sy) = ray(0, 0), ray(1, 0), ray(0, 1)
    return {"u_origin0": tuple(o0), "u_origin_dx": tuple(ox - o0),
            "u_origin_dy": tuple(oy - o0), "u_span0": tuple(s0), "u_span_dx": tuple(sx - s0),
            "u_span_dy": tuple(sy - s0)}


def box_corners(bounds) -> NDArray[np.float64]:
    """The 8 corners ``(..., 8, 3)`` of boxes given as ``(..., 2, 3)`` minimum and maximum.

    Parameters
    ----------
    bounds : array_like
        ``(..., 2, 3)`` boxes' minimum and maximum corners.
    """
    b = np.asarray(bounds, np.float64)
    index = np.array([[i >> 2 & 1, i >> 1 & 1, i & 1] for i in range(8)])
    return b[..., index, [0, 1, 2]]


def z_up_to_y_up(points: np.ndarray) -> np.ndarray:
    """Points ``(..., 3)`` of a z-up data set (Newell's teapot) in glshade's y-up world,
    keeping handedness: ``(x, y, z) -> (x, z, -y)`` (exact: a permutation and a sign).

    Parameters
    ----------
    points : ndarray
        ``(..., 3)`` positions.
    """
    return np.asarray(points, dtype=np.float64)[..., [0, 2, 1]] * [1.0, 1.0, -1.0]


def y_up_to_z_up(points: np.ndarray) -> np.ndarray:
    """The inverse of :func:`z_up_to_y_up`: ``(x, y, z) -> (x, -z, y)``.

    Parameters
    ----------
    points : ndarray
        ``(..., 3)`` positions.
    """
    return np.asarray(points, dtype=np.float64)[..., [0, 2, 1]] * [1.0, -1.0, 1.0]


def model_matrices(view: ArrayLike, models: ArrayLike) -> tuple[NDArray[np.float64], ...]:
    """What a model's draw needs of its placements, for K of them at once: the model-view
    matrices ``(K, 4, 4)``, the normal matrices in view and world space ``(K, 3, 3)``
    (inverse transposes) and whether each mirrors ``(K,)`` (its faces then wind the other
    way). One batched computation for a model drawn alone (K = 1) and for K instances, so
    both draws get the same float32 values.

    Parameters
    ----------
    view : array_like
        ``(4, 4)`` world-to-view matrix (rigid).
    models : array_like
        ``(K, 4, 4)`` model-to-world matrices.
    """
    view = np.asarray(view, np.float64)
    models = np.asarray(models, np.float64)
    normal_world = np.swapaxes(np.linalg.inv(models[:, :3, :3]), 1, 2)
    # (the view is rigid: its own inverse transpose)
    return (view @ models, view[:3, :3] @ normal_world, normal_world,
            np.linalg.det(models[:, :3, :3]) < 0)


def outside_frustum(view_proj: ArrayLike, corners: ArrayLike) -> NDArray[np.bool_]:
    """Which boxes lie wholly outside a view: all eight corners beyond one of the frustum's
    six planes (in clip space, with a margin of 1e-5 of w against rounding), so that
    nothing of what each box holds can reach a pixel. Conservative: a box beside a corner
    of the frustum, outside it but on no one plane's far side, counts as inside.

    Parameters
    ----------
    view_proj : array_like
        ``(4, 4)`` world-to-clip matrix.
    corners : array_like
        ``(K, 8, 3)`` each box's corners, world.
    """
    c = np.asarray(corners, np.float64)
    h = c @ np.asarray(view_proj, np.float64)[:3, :3].T + np.asarray(view_proj)[:3, 3]
    w = c @ np.asarray(view_proj, np.float64)[3, :3] + np.asarray(view_proj)[3, 3]
    margin = w + 1e-5 * np.abs(w)
    beyond = [(h[..., i] > margin).all(1) | (h[..., i] < -margin).all(1) for i in range(3)]
    return beyond[0] | beyond[1] | beyond[2]
