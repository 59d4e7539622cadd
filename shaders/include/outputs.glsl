// What every shading program writes: colour, world-space normal, source polygon id and
// view-axis depth. Depth and ids go to integer targets, so MSAA resolves never blend them.

// Programs compiled without GLSHADE_AUX_OUTPUTS write colour only (plain renders).

#ifdef OIT_FETCH
// a transparent surface's capture: this pixel's fragment count and pool list head + 1, read
// as the earlier fragments left them (framebuffer fetch keeps primitive order per pixel:
// no atomics) and written back
layout(location = 0) inout uvec2 oit_head;
#else
layout(location = 0) out vec4 frag_color;
#endif
#ifdef GLSHADE_AUX_OUTPUTS
layout(location = 1) out vec4 frag_normal;     // world-space unit normal, w = 1 where drawn
layout(location = 2) out int frag_face_id;     // polygon id + 1 (0 = background)
layout(location = 3) out uint frag_depth_bits; // floatBitsToUint(distance along view axis)
#ifndef POLYGON_ID_IN  // (else shadow_mask.glsl declared them)
#ifdef INSTANCED
#include "instances.glsl"
#define u_face_id_base instance_face_base()
#else
uniform int u_face_id_base;
#endif
#ifdef POLYGON_FETCH
#include "polygon_fetch.glsl"
#define v_polygon polygon_of(gl_PrimitiveID)
#elif !defined(PATCH_IDS)
flat in int v_polygon;                         // this mesh's polygon (polygon_id.glsl)
#endif
#endif
#endif

// (SRGB is defined for programs that encode for display: no cost for the others)
#include "srgb.glsl"

#if defined(OIT_CAPTURE) || defined(OIT_BLEND) || defined(OIT_PEEL)
uniform float u_opacity;                       // the surface's Material.opacity
#endif
#ifdef OIT_PEEL
// Depth peeling, exact transparency without storage buffers (render/passes/peeling.py): a
// layer is the nearest of a pixel's transparent fragments beyond the last layer peeled
// and before the opaque surface. Its depth is found first (OIT_PEEL_DEPTH: every fragment
// left writes its depth into an R32F target blended by MIN -- a program of its own, so the
// compiler drops the lighting it does not use), then its colour (the fragments at exactly
// that depth, premultiplied, blended under the layers before). Depths
// are compared as the same float32 gl_FragCoord.z each pass computes: none is lost or
// peeled twice; fragments at one depth are one layer, composited in drawing order.
uniform sampler2D u_peel_before;  // the last layer's depth (-1: none yet)
uniform sampler2D u_peel_near;    // this layer's (its colour pass)
uniform sampler2D u_peel_opaque;  // the opaque surfaces' depth
#endif
#if defined(TEXTURED) || defined(VERTEX_COLORS)
// its opacity map here (textures.glsl), times the mesh colour's alpha (surface_color.glsl)
float g_map_opacity = 1.0;
#define SURFACE_OPACITY (u_opacity * g_map_opacity)
#else
#define SURFACE_OPACITY u_opacity
#endif
#ifdef OIT_CAPTURE
// A transparent surface's fragment joins its pixel's list (render/passes/transparency.py):
// a node is (colour RG, BA as 16-bit fractions, view depth, the next node). A pixel's first
// OIT_SLOTS fragments take its own slots (a per-pixel count, no shared counter to contend
// for); the rest go to a shared pool, linked from the pixel's pool head. Counts and heads
// are storage-buffer words (atomics on them cost llvmpipe less than on an image's texels).
// The opaque depth test runs first (nothing hidden joins).
layout(early_fragment_tests) in;
#ifndef OIT_FETCH
// a pixel's fragment count at its index, its pool list head + 1 at u_oit_pixels + index
layout(std430, binding = BINDING_OIT_HEADS) coherent buffer OitHeads { uint oit_heads[]; };
#endif
layout(std430, binding = BINDING_OIT_NODES) buffer OitNodes { uvec4 oit_nodes[]; };
// the pool's nodes taken; oit_deep[i] set where some pixel reached 2, 3, 5 fragments (plain
// stores of one value: the resolve sorts only as many slots as the deepest pixel needs)
layout(std430, binding = BINDING_OIT_COUNT) buffer OitCount { uint oit_count; uint oit_deep[3]; };
uniform uint u_oit_capacity;  // nodes in the pool
uniform uint u_oit_width;     // the target's width (a pixel's index: y width + x)
uniform uint u_oit_pixels;    // the target's pixels
uniform uint u_oit_base;      // where the pool starts (after every pixel's slots)
#ifndef OIT_SLOTS
#error "OIT_SLOTS comes from render/programs.py (OIT_SLOTS)"
#endif
#endif

#ifdef EMISSIVE
uniform vec3 u_emission;                       // what the surface gives off by itself
#endif

void write_outputs(vec3 color, vec3 n_world, float depth_view) {
#ifdef EMISSIVE
    color += u_emission;  // (added to the lit colour in every mode, as glTF adds it)
#endif
    color = clamp(color, 0.0, 1.0);
#ifdef SRGB
    color = encode_srgb(color);
#endif
#ifdef OIT_CAPTURE
    // (with MSAA a pixel's fragment is its sample 0's: two triangles that share an edge
    // through the pixel would both be listed otherwise)
    if ((gl_SampleMaskIn[0] & 1) != 0) {
        uint pixel = uint(gl_FragCoord.y) * u_oit_width + uint(gl_FragCoord.x);
        uvec4 node = uvec4(packUnorm2x16(color.rg), packUnorm2x16(vec2(color.b, SURFACE_OPACITY)),
                           floatBitsToUint(depth_view), 0u);
#ifdef OIT_FETCH
        uint slot = oit_head.x;
        oit_head.x = slot + 1u;
#else
        uint slot = atomicAdd(oit_heads[pixel], 1u);
#endif
        if (slot == 1u || slot == 2u || slot == 4u) oit_deep[findMSB(slot)] = 1u;
        if (slot < uint(OIT_SLOTS)) {
            oit_nodes[pixel * uint(OIT_SLOTS) + slot] = node;
        } else {
            uint i = atomicAdd(oit_count, 1u);
            if (i < u_oit_capacity) {  // (beyond: counted; the pass runs again with room)
#ifdef OIT_FETCH
                node.w = oit_head.y;
                oit_head.y = i + 1u;
#else
                node.w = atomicExchange(oit_heads[u_oit_pixels + pixel], i + 1u);
#endif
                oit_nodes[u_oit_base + i] = node;
            }
        }
    }
#ifndef OIT_FETCH
    frag_color = vec4(0.0);  // (masked: the resolve pass composites)
#endif
#elif defined(OIT_BLEND)
    frag_color = vec4(color, SURFACE_OPACITY);
#elif defined(OIT_PEEL)
    ivec2 peel_px = ivec2(gl_FragCoord.xy);
    float z = gl_FragCoord.z;
    if (z <= texelFetch(u_peel_before, peel_px, 0).r ||
        z >= texelFetch(u_peel_opaque, peel_px, 0).r) discard;
#ifdef OIT_PEEL_DEPTH
    frag_color = vec4(z, 0.0, 0.0, 1.0);
#else
    if (z != texelFetch(u_peel_near, peel_px, 0).r) discard;
    frag_color = vec4(color * SURFACE_OPACITY, SURFACE_OPACITY);
#endif
#else
    frag_color = vec4(color, 1.0);
#endif
#ifdef GLSHADE_AUX_OUTPUTS
#ifdef PATCH_IDS
    int polygon = gl_PrimitiveID;  // (tessellated on the GPU: the patch's number)
#else
    int polygon = v_polygon;
#endif
    frag_normal = vec4(normalize(n_world), 1.0);
    frag_face_id = u_face_id_base + polygon + 1;
    frag_depth_bits = floatBitsToUint(depth_view);
#endif
}
