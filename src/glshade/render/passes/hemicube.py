"""Form factors by the hemicube (Cohen and Greenberg 1985), drawn on the GPU.

From a point on a patch, the hemisphere above it is covered by half a cube: the top face
(looking along the normal) and four half side faces. Every patch is drawn into the five
faces with its id as an integer (never multisampled or blended) and the depth test keeps
the nearest; each pixel's *delta form factor* -- ``dA / (pi (x^2 + y^2 + 1)^2)`` on the
top face, ``z dA / (pi (x^2 + z^2 + 1)^2)`` on a side face, for a cube of half-size 1 --
is then summed per visible patch (a histogram: ``numpy.bincount``). The five faces are one
atlas (``3N x N``); the atlases of up to ``BATCH`` points are drawn one above the other and
read back together (a software rasterizer then bins them in one pass).
"""

from __future__ import annotations

import numpy as np

from ...errors import OptionError, UsageError
from ..base import GLResource
from ..programs import UniformWriter
from ..shaders import ShaderLibrary

__all__ = ["Hemicube", "BATCH", "BATCH_PIXELS"]

#: hemicubes drawn before one read-back: at most 16, in at most about a million pixels
BATCH, BATCH_PIXELS = 16, 2**20


def _cross(a, b) -> np.ndarray:
    """(numpy's cross costs more than the rest of a hemicube's Python)"""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])


def _look(origin, forward, up) -> np.ndarray:
    """View matrix from ``origin`` along the unit ``forward``, ``up`` unit and at right
    angles to it (a hemicube's axes are)."""
    s = _cross(forward, up)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = s, up, -forward
    m[:3, 3] = -m[:3, :3] @ origin
    return m


def _frustum(left, right, bottom, top, near, far) -> np.ndarray:
    return np.array([
        [2 * near / (right - left), 0, (right + left) / (right - left), 0],
        [0, 2 * near / (top - bottom), (top + bottom) / (top - bottom), 0],
        [0, 0, -(far + near) / (far - near), -2 * far * near / (far - near)],
        [0, 0, -1, 0]])


class Hemicube(GLResource):
    """Hemicubes of resolution ``N`` (the top face is ``N x N``) over uploaded patches;
    ``delta(N)`` gives each pixel's delta form factor, an ``(N, 3N)`` atlas (the chapter's
    numpy: :func:`glshade.radiosity.formfactors.delta_form_factors`).

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    resolution : int
        The top face, pixels a side.
    delta : callable
        ``delta(N)``: the ``(N, 3N)`` atlas of delta form factors.
    """

    def __init__(self, context, resolution: int, delta):
        n = int(resolution)
        if n != resolution or n < 4 or n % 2:
            raise OptionError(f"hemicube resolution must be an even whole number >= 4, "
                                f"got {resolution!r}")
        super().__init__(context)
        context.make_current()  # (another context may be current: GL objects go there)
        limit = context.ctx.info["GL_MAX_RENDERBUFFER_SIZE"]
        if 3 * n > limit:
            raise OptionError(f"hemicube resolution {n} needs a {3 * n}-pixel-wide "
                                f"target; this GL allows {limit} (use <= {limit // 3})")
        self.resolution = n
        self.batch = max(1, min(BATCH, BATCH_PIXELS // (3 * n * n), limit // n))
        self.weights = np.tile(np.asarray(delta(n), np.float64).ravel(), self.batch)
        ctx = context.ctx
        library = ShaderLibrary(context)
        try:
            self.program = self._keep(library.compile("hemicube.vert", "hemicube.frag"))
        finally:
            library.release()
        size = (3 * n, n * self.batch)
        self.ids = self._keep(ctx.renderbuffer(size, 1, dtype="i4"))
        self.depth = self._keep(ctx.depth_renderbuffer(size))
        self.fbo = self._keep(ctx.framebuffer([self.ids], self.depth))
        self._vao = self._vbo = None
        self._buffer = np.empty(3 * n * n * self.batch, np.int32)
        self.n_patches = 0

    def upload(self, vertices: np.ndarray, triangles: np.ndarray, patch: np.ndarray,
               n_patches: int) -> None:
        """The scene: triangles (T, 3) into vertices, each of patch ``patch[t]``.

        Parameters
        ----------
        vertices : ndarray
            ``(V, 3)`` positions.
        triangles : ndarray
            ``(T, 3)`` indices.
        patch : ndarray
            ``(T,)`` each triangle's patch.
        n_patches : int
            The patches.
        """
        self._check()
        self.context.make_current()
        for obj in (self._vao, self._vbo):
            if obj is not None:
                obj.release()
                self._objects.remove(obj)
        corners = np.asarray(vertices, "f4")[np.asarray(triangles).ravel()]
        ids = np.repeat(np.asarray(patch, np.int32) + 1, 3)
        data = np.empty(len(corners), dtype=[("p", "f4", 3), ("id", "i4")])
        data["p"], data["id"] = corners, ids
        ctx = self.context.ctx
        self._vbo = self._keep(ctx.buffer(data.tobytes()))
        self._vao = self._keep(ctx.vertex_array(self.program,
                                                [(self._vbo, "3f 1i", "in_position",
                                                  "in_patch")]))
        self.n_patches = int(n_patches)
        # patch ids of the k-th atlas of a batch counted from k (P + 1): one histogram
        self._offsets = np.repeat(np.arange(self.batch, dtype=np.int32) * (self.n_patches + 2),
                                  3 * self.resolution ** 2)
        self._put = UniformWriter().put
        self._put(self.program, "u_back_id", self.n_patches + 1)
        lo, hi = corners.min(0), corners.max(0)
        self.extent = float(np.linalg.norm(hi - lo)) or 1.0

    def faces(self, origin, normal, tangent) -> list[tuple[tuple, np.ndarray]]:
        """(viewport, view-projection) of the five faces at ``origin``.

        Parameters
        ----------
        origin : array_like
            ``(3,)`` the point (on a patch).
        normal : array_like
            ``(3,)`` the patch's unit normal.
        tangent : array_like
            ``(3,)`` a unit tangent turning the cube about the normal.
        """
        n = self.resolution
        # (the near plane: nearer, and the 24-bit depth cannot tell a light 0.5 mm below a
        # ceiling from the ceiling at 500 mm; farther, and a corner's neighbours are clipped)
        near = 2e-4 * self.extent
        far = 4.0 * self.extent
        normal = np.asarray(normal, np.float64)
        t = np.asarray(tangent, np.float64)
        b = _cross(normal, t)
        top = _frustum(-near, near, -near, near, near, far) @ _look(origin, normal, t)
        half = _frustum(-near, near, 0.0, near, near, far)
        out = [((0, 0, n, n), top)]
        for k, d in enumerate((t, -t, b, -b)):  # looking out sideways, up = the normal
            viewport = (n + (k // 2) * n, (k % 2) * (n // 2), n, n // 2)
            out.append((viewport, half @ _look(origin, d, normal)))
        return out

    def row(self, origin, normal, tangent) -> np.ndarray:
        """Form factors ``(P,)`` from the point ``origin`` (on a patch facing ``normal``;
        ``tangent`` turns the cube about it) to every patch.

        Parameters
        ----------
        origin : array_like
            ``(3,)`` the point (on a patch).
        normal : array_like
            ``(3,)`` the patch's unit normal.
        tangent : array_like
            ``(3,)`` a unit tangent turning the cube about the normal.
        """
        return self.rows([origin], normal, [tangent])[0]

    def rows(self, origins, normal, tangents, back: np.ndarray | None = None) -> np.ndarray:
        """Form factors ``(K, P)`` from each of the points ``origins`` on one patch, the
        cube at point k turned by ``tangents[k]``: drawn ``batch`` at a time, one read each.
        ``back`` (K,), when given, receives the share of each point's hemicube that meets
        patches from behind (1 for a point inside a closed solid, under a block).

        Parameters
        ----------
        origins : ndarray
            ``(K, 3)`` points on one patch.
        normal : array_like
            ``(3,)`` the patch's unit normal.
        tangents : ndarray
            ``(K, 3)`` each cube's turn.
        back : ndarray or None
            ``(K,)`` receives each point's share of hemicube meeting patches from behind.
        """
        import moderngl

        self._check()
        if self._vao is None:
            raise UsageError("upload the patches before asking for form factors")
        origins = np.atleast_2d(np.asarray(origins, np.float64))
        normal = np.asarray(normal, np.float64)
        ctx = self.context.ctx
        self.context.make_current()
        n, p1 = self.resolution, self.n_patches + 2
        out = np.empty((len(origins), self.n_patches))
        try:
            for start in range(0, len(origins), self.batch):
                chunk = origins[start:start + self.batch]
                used = (0, 0, 3 * n, n * len(chunk))
                self.fbo.use()
                self.fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0, viewport=used)
                ctx.enable(moderngl.DEPTH_TEST)
                ctx.disable(moderngl.CULL_FACE | moderngl.BLEND)
                for k, origin in enumerate(chunk):
                    origin = origin + 1e-6 * self.extent * normal
                    for (x, y, w, h), matrix in self.faces(origin, normal, tangents[start + k]):
                        ctx.viewport = (x, y + k * n, w, h)
                        self._put(self.program, "u_view_proj",
                                  np.ascontiguousarray(matrix.T, dtype="f4"))
                        self._vao.render(moderngl.TRIANGLES)
                m = len(chunk) * 3 * n * n
                self.fbo.read_into(self._buffer, viewport=used, components=1, dtype="i4")
                hist = np.bincount(self._buffer[:m] + self._offsets[:m],
                                   weights=self.weights[:m], minlength=len(chunk) * p1)
                per = hist.reshape(len(chunk), p1)
                out[start:start + len(chunk)] = per[:, 1:-1]
                if back is not None:
                    back[start:start + len(chunk)] = per[:, -1]
        finally:
            self.context.rest()  # (never leave a framebuffer bound that may be released)
        return out
