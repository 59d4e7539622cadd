"""Where each GL program finds what it reads: texture units, storage-buffer bindings and
image units, in one table.

A texture unit is the GL's global state: two things that one program samples, or that one
draw binds before another reads, must not share a number (the edge overlay's depth copy and
a CSG solid's tree were both on unit 7). Each number lives here, once; the Python side binds
and writes its uniform from it, and the GLSL side's storage-buffer bindings are the
``BINDING_*`` defines :func:`glsl_defines` puts into every program (``layout(std430,
binding = BINDING_OIT_HEADS)``), so a binding is never written twice.
"""

from __future__ import annotations

__all__ = ["Unit", "Binding", "glsl_defines"]


class Unit:
    """Texture units. A frame's shading programs (every stage of the pipeline) bind theirs
    together, so theirs are all different; the compute passes, the transparency resolve,
    the path tracer and the viewer's labels run programs of their own between draws and
    number from 0."""

    # ---- a frame's shading programs
    #: the shadow pass's visibility array (shaders/include/shadow_mask.glsl)
    SHADOW_VISIBILITY = 6
    #: a CSG solid's tree data (csg.frag: a texture, or a uniform block's binding)
    CSG_TREE = 7
    #: the surfaces' depth, copied for the edge overlay (edges.frag)
    EDGE_DEPTH = 8
    #: an instanced draw's rows of matrices and colours (shaders/include/instances.glsl)
    INSTANCES = 9
    #: a material's diffuse, specular and opacity maps (shaders/include/textures.glsl)
    MAP_DIFFUSE, MAP_SPECULAR, MAP_OPACITY = 10, 11, 12
    #: a PBRMaterial's maps (shaders/include/textures.glsl, PBR_TEXTURED): a program samples
    #: one lighting model's maps, so glTF's take the notes' units, and one more
    MAP_BASE, MAP_METALLIC_ROUGHNESS, MAP_OCCLUSION = MAP_DIFFUSE, MAP_SPECULAR, MAP_OPACITY
    MAP_EMISSIVE = 15
    #: a PBRMaterial's normal map (after the forward light maps' eight)
    MAP_NORMAL = 27
    #: a big mesh's tables: each triangle's polygon, each polygon's normal and centroid
    #: (shaders/include/polygon_fetch.glsl)
    POLYGONS, POLYGON_PLANES = 13, 14
    #: a forward map-shadowed draw's light maps, one a light from here (up to 8)
    LIGHT_MAPS = 16
    #: depth peeling's depths: the last layer's, this layer's, the opaque surfaces'
    #: (shaders/include/outputs.glsl, OIT_PEEL)
    PEEL_BEFORE, PEEL_NEAR, PEEL_OPAQUE = 24, 25, 26
    #: a scene's sky (render/passes/environment.py): prefiltered by roughness, its
    #: irradiance and the split-sum table, read by glTF's model (environment_light.glsl),
    #: and the map itself, drawn as the background (background.frag)
    ENV_SPECULAR, ENV_IRRADIANCE, ENV_SPLIT_SUM, ENV_BACKGROUND = 28, 29, 30, 31

    # ---- the shadow pass's compute programs (shadow_rays.comp, shadow_maps.comp)
    GBUFFER_FACE, GBUFFER_DEPTH, GBUFFER_NORMAL = 0, 1, 3
    #: a casting CSG solid's tree (shadow_rays.comp's CSG_SOLID variant)
    CAST_TREE = 2
    #: the light map a lookup pass reads
    LOOKUP_MAP = 4
    #: without storage buffers (a GL 4.1 context): the hierarchy's nodes, triangles and
    #: polygon normals as textures, and the visibility so far a solid's cast reads
    #: (shadow_rays.frag)
    WALK_NODES, WALK_TRIANGLES, WALK_NORMALS, CAST_PREVIOUS = 5, 6, 7, 8

    # ---- the transparency resolve (oit_resolve.frag)
    OIT_BEHIND, OIT_HEADS = 2, 3
    #: depth peeling's composite (peel_composite.frag): the layers' accumulation, over the
    #: opaque copy on OIT_BEHIND
    PEEL_ACCUM = 4

    # ---- the path tracer (pathtrace.frag): its tables, given rays, the solid's tree,
    # seven targets, the hierarchy's texture, the adaptive extras
    TRACE_DATA, TRACE_RAYS, TRACE_CSG, TRACE_TARGETS = 0, 1, 2, 3
    TRACE_BVH = TRACE_TARGETS + 7
    TRACE_EXTRA = TRACE_BVH + 1
    #: the sums the viewer's progressive picture shows (pathtrace_show.frag)
    TRACE_SHOW = 0

    # ---- the viewer's text bands
    LABEL = 0


class Binding:
    """Storage-buffer bindings (``layout(std430, binding = ...)``), and the image unit of
    the shadow pass's visibility array."""

    #: the shadow rays' hierarchy, triangles, run-out count and polygon normals
    #: (shaders/include/shadow_trace.glsl); the path tracer's walk uses the first two
    WALK_NODES, WALK_TRIANGLES, RAY_COUNTS, POLYGON_NORMALS = 0, 1, 2, 3
    #: transparent fragments' lists (shaders/include/outputs.glsl, oit_resolve.frag)
    OIT_HEADS, OIT_NODES, OIT_COUNT, OIT_REPORT = 4, 5, 6, 7
    #: the visibility array as an image (shadow_rays.comp, shadow_maps.comp)
    VISIBILITY_IMAGE = 0
    #: the path tracer's compute kernel: its seven targets written as images, from here
    #: (pathtrace.comp)
    TRACE_IMAGES = 0


def glsl_defines() -> tuple[str, ...]:
    """``#define BINDING_<NAME> <n>`` for every binding: compiled into every program."""
    return tuple(f"BINDING_{name} {value}" for name, value in vars(Binding).items()
                 if name.isupper())
