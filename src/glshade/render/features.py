"""What a GL context can do, decided once when the context is made: its tier.

Every pass that has two ways of doing its work -- a GL 4.3 way (compute shaders, storage
buffers, image load/store) and a way that runs on OpenGL 4.1 core (what every Mac has) --
asks :class:`Features` which, and nothing else: never the platform's name, never a
refusal deep in a pass. A feature that truly needs more than the context has is refused
before any drawing, in one line naming the version it needs and what to use instead
(:meth:`Features.require`).

The tiers, by what the context reports (``GL_VERSION`` and ``GL_EXTENSIONS``):

- ``4.3``: compute shaders, storage buffers and image load/store (GL 4.3 core, or 4.2 with
  the three ARB extensions -- but glshade's 4.3 programs say ``#version 430``, so a 4.2
  context takes the 4.1 paths);
- ``4.1``: vertex, geometry and fragment programs, tessellation, dynamically uniform
  indexing of sampler arrays, occlusion queries, pixel buffers: every feature, some by a
  path of their own (shadow maps and exact shadows in fragment programs, exact
  transparency by depth peeling);
- ``3.3``: the plain modes, CSG, radiosity, exact shadows and transparency, the fragment
  path tracer; what needs GL 4.0 (tessellation, shadow maps: their lookups index arrays of
  samplers) says so.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..errors import EnvironmentFailure

__all__ = ["Features", "FEATURE_ROWS", "feature_table"]

@dataclass(frozen=True)
class Features:
    """What one context can do (:meth:`of`), and the path each feature takes there.

    Parameters
    ----------
    version : int
        The context's GL version code (410: 4.1).
    storage : bool
        Compute shaders, storage buffers, image load/store and atomics (GL 4.3): the
        tracer's compute kernel, exact shadows' compute pass, transparency's fragment lists.
    framebuffer_fetch : bool
        ``GL_EXT_shader_framebuffer_fetch`` (transparency's lists counted without atomics).
    detail : str
        The renderer's name (for messages).
    """

    version: int
    storage: bool
    framebuffer_fetch: bool = False
    detail: str = ""

    @classmethod
    def of(cls, ctx, detail: str = "") -> Features:
        """The features of a moderngl context, from its version and extensions.

        Parameters
        ----------
        ctx : moderngl.Context
            The context.
        detail : str
            The renderer's name.
        """
        version = int(ctx.version_code)
        extensions = set(ctx.extensions)
        # (a 4.3 core context has them whether or not it lists their ARB names)
        return cls(version, version >= 430, "GL_EXT_shader_framebuffer_fetch" in extensions,
                   detail)

    def capped(self, tier: str | None) -> Features:
        """These features held to an older GL's paths: ``"4.1"`` (what a Mac has) or
        ``"3.3"`` -- what a context made with ``create_context(tier=...)`` takes, to see
        (and test) on any machine the pictures an older GL gives; None: as they are.

        Parameters
        ----------
        tier : str or None
            ``"4.3"``, ``"4.1"``, ``"3.3"`` or None.
        """
        if tier is None:
            return self
        codes = {"4.3": 430, "4.1": 410, "3.3": 330}
        if str(tier) not in codes:
            from ..errors import OptionError

            raise OptionError(f"tier must be one of {', '.join(codes)}, got {tier!r}")
        version = min(self.version, codes[str(tier)])
        return replace(self, version=version, storage=self.storage and version >= 430)

    @property
    def tier(self) -> str:
        """``"4.3"``, ``"4.1"`` or ``"3.3"``: which paths this context takes."""
        return "4.3" if self.storage else "4.1" if self.version >= 410 else "3.3"

    @property
    def version_text(self) -> str:
        """The version as ``major.minor``."""
        return f"{self.version // 100}.{self.version % 100 // 10}"

    @property
    def sampler_arrays(self) -> bool:
        """Sampler arrays indexed in a loop (GLSL 4.00): a fragment looking several lights'
        shadow maps up; tessellation shaders come with the same version."""
        return self.version >= 400

    def require(self, version: int, what: str, instead: str) -> None:
        """Refuse, in one line, what this GL is too old for: ``version`` as GL's version
        code (430: 4.3); ``what`` ends in the verb ("kernel='compute' needs"); ``instead``
        names the way that works here.

        Parameters
        ----------
        version : int
            GL's version code needed (430: 4.3).
        what : str
            What needs it, ending in the verb.
        instead : str
            The way that works on this GL.
        """
        have = self.storage if version >= 430 else self.version >= version
        if not have:
            raise EnvironmentFailure(
                f"{what} OpenGL {version // 100}.{version % 100 // 10}; this GL is "
                f"{self.version_text} ({self.detail or 'unnamed renderer'}): {instead}")

    def paths(self) -> dict[str, str]:
        """Each feature and the path it takes on this GL (what ``glshade doctor`` prints)."""
        out = {
            "shading (flat, Gouraud, Phong)": "vertex/fragment programs (GL 3.3)",
            "shadows map": "depth maps looked up by fragment programs (GL 4.0)" if not
            self.storage else "depth maps; a read-back's lookups in a compute pass (GL 4.3)",
            "shadows exact": "fragment programs walking the BVH in textures (GL 3.3)" if not
            self.storage else "rays through the BVH in storage buffers (GL 4.3)",
            "transparency exact": "depth peeling, a pass a layer (GL 3.3)"
            if not self.storage else
            "per-pixel fragment lists in storage buffers (GL 4.3)",
            "transparency weighted": "fragment lists (GL 4.3)" if self.storage else
            "refused: needs OpenGL 4.3 (use transparency='exact' or 'blend')",
            "transparency blend": "blending in drawing order (GL 3.3)",
            "patches on the GPU": "tessellation shaders (GL 4.0)" if self.version >= 400 else
            "refused: needs OpenGL 4.0 (tessellation='cpu')",
            "path tracer kernel": "fragment or compute, measured (GL 4.3)" if self.storage
            else "fragment program (compute needs OpenGL 4.3)",
        }
        if not self.sampler_arrays:
            out["shadows map"] = "refused: needs OpenGL 4.0 (use shadows='exact')"
        return out


#: the feature rows ``glshade doctor`` prints, in order (:meth:`Features.paths`' keys)
FEATURE_ROWS = ("shading (flat, Gouraud, Phong)", "shadows map", "shadows exact",
                "transparency exact", "transparency weighted", "transparency blend",
                "patches on the GPU", "path tracer kernel")


def feature_table(features: Features) -> list[str]:
    """``doctor``'s lines: the tier, then each feature and its path on this GL.

    Parameters
    ----------
    features : Features
        The context's.
    """
    paths = features.paths()
    width = max(len(k) for k in FEATURE_ROWS)
    return [f"GL tier {features.tier} (OpenGL {features.version_text})"] + \
        [f"  {k:<{width}}  {paths[k]}" for k in FEATURE_ROWS]
