// What every shading program writes: colour, world-space normal, source polygon id and
// view-axis depth. Depth and ids go to integer targets, so MSAA resolves never blend them.

// Programs compiled without GLSHADE_AUX_OUTPUTS write colour only (plain renders).

layout(location = 0) out vec4 frag_color;
#ifdef GLSHADE_AUX_OUTPUTS
layout(location = 1) out vec4 frag_normal;     // world-space unit normal, w = 1 where drawn
layout(location = 2) out int frag_face_id;     // polygon id + 1 (0 = background)
layout(location = 3) out uint frag_depth_bits; // floatBitsToUint(distance along view axis)
uniform int u_face_id_base;
uniform isampler2D u_face_ids;                 // triangle -> polygon id of this mesh
#endif

// (SRGB is defined for programs that encode for display: no cost for the others)
#include "srgb.glsl"

void write_outputs(vec3 color, vec3 n_world, float depth_view) {
    color = clamp(color, 0.0, 1.0);
#ifdef SRGB
    color = encode_srgb(color);
#endif
    frag_color = vec4(color, 1.0);
#ifdef GLSHADE_AUX_OUTPUTS
#ifdef PATCH_IDS
    int polygon = gl_PrimitiveID;  // (tessellated on the GPU: the patch's number)
#else
    int width = textureSize(u_face_ids, 0).x;
    int tri = gl_PrimitiveID;
    int polygon = texelFetch(u_face_ids, ivec2(tri % width, tri / width), 0).r;
#endif
    frag_normal = vec4(normalize(n_world), 1.0);
    frag_face_id = u_face_id_base + polygon + 1;
    frag_depth_bits = floatBitsToUint(depth_view);
#endif
}
