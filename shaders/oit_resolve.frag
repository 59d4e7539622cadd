#version 430 core
// The transparent surfaces of a pixel, composited over what the opaque pass drew there
// (u_behind, its copy): out = C + T behind, C premultiplied, T the layers' transmittance,
// rounded once.
//
// EXACT: the pixel's list (render/passes/transparency.py; its nodes in outputs.glsl) kept
// sorted nearest first, at most MAX_LAYERS (the farther ones counted, and left out), then
// "over" front to back: C += T a c, T *= 1 - a. Equal depths are ordered by the colour's
// and opacity's bits, so the result never depends on the order the fragments arrived in.
// WEIGHTED: McGuire and Bavoil's estimate (2013, eq. 7's weight) over the whole list,
// order-free: C = sum(w a c) / sum(w a) x (1 - prod(1 - a)).
// A list walk is bounded (LIST_BUDGET steps: llvmpipe stops a shader at 65,535): a pixel
// that runs out is counted (u_counts[2]) and composited from what it read.
// SORTED_SLOTS n (EXACT, where no pixel has more than n <= OIT_SLOTS fragments, so all are
// in its own slots): no list walk; the n slots sorted in registers by a network.
#ifdef OIT_FETCH
uniform usampler2D u_oit_heads;  // a pixel's fragment count, pool list head + 1
#else
// a pixel's fragment count at its index, its pool list head + 1 at u_oit_pixels + index
layout(std430, binding = BINDING_OIT_HEADS) readonly buffer OitHeads { uint oit_heads[]; };
#endif
layout(std430, binding = BINDING_OIT_NODES) readonly buffer OitNodes { uvec4 oit_nodes[]; };
// pixels over, fragments over, cut short, - (the fragments are summed from the heads when
// asked for: render/passes/transparency.py)
layout(std430, binding = BINDING_OIT_REPORT) buffer OitReport { uint u_counts[4]; };
uniform uint u_oit_width;
uniform uint u_oit_pixels;
uniform uint u_oit_base;
#ifndef OIT_SLOTS
#error "OIT_SLOTS comes from render/programs.py (OIT_SLOTS)"
#endif
#ifndef MAX_LAYERS
#define MAX_LAYERS 32
#endif
#define LIST_BUDGET LOOP_BUDGET

uniform sampler2D u_behind;
out vec4 frag_color;

float weight(float z, float a) {
    return a * clamp(10.0 / (1e-5 + pow(z / 5.0, 2.0) + pow(z / 200.0, 6.0)), 1e-2, 3e3);
}

// whether fragment a comes before fragment b: nearer, or (a tie) by colour and opacity bits
bool before(float da, uint rga, uint baa, float db, uint rgb, uint bab) {
    return da < db || (da == db && (rga < rgb || (rga == rgb && baa < bab)));
}

// put elements i < j of the registers' slots in order (one comparator of a sorting network)
#define ORDER(i, j) { \
    bool swap = before(sd[j], srg[j], sba[j], sd[i], srg[i], sba[i]); \
    float d_ = sd[i]; uint rg_ = srg[i], ba_ = sba[i]; \
    sd[i] = swap ? sd[j] : d_; srg[i] = swap ? srg[j] : rg_; sba[i] = swap ? sba[j] : ba_; \
    sd[j] = swap ? d_ : sd[j]; srg[j] = swap ? rg_ : srg[j]; sba[j] = swap ? ba_ : sba[j]; }

// The pixel's k-th fragment: its own slots first, then the pool's list (``i``: the next
// pool node + 1, advanced as the list is walked; 0 at its end).
uint g_first, g_slots, g_next;

bool next_node(out uvec4 node) {
    if (g_slots > 0u) {
        node = oit_nodes[g_first++];
        --g_slots;
        return true;
    }
    if (g_next == 0u) return false;
    node = oit_nodes[u_oit_base + g_next - 1u];
    g_next = node.w;
    return true;
}

// WEIGHTED: the estimate over the whole list, over ``behind``
vec4 weighted(vec4 behind) {
    uvec4 node;
    int steps = 0;
    vec3 sum_c = vec3(0.0);
    float sum_w = 0.0, t = 1.0;
    while (steps < LIST_BUDGET && next_node(node)) {
        ++steps;
        vec2 rg = unpackUnorm2x16(node.x), ba = unpackUnorm2x16(node.y);
        float w = weight(uintBitsToFloat(node.z), ba.y);
        sum_c += w * vec3(rg, ba.x);
        sum_w += w;
        t *= 1.0 - ba.y;
    }
    if (steps >= LIST_BUDGET) atomicAdd(u_counts[2], 1u);
    vec3 c = sum_w > 0.0 ? sum_c / sum_w : vec3(0.0);
    return vec4(c * (1.0 - t) + t * behind.rgb, behind.a);
}

#ifdef SORTED_SLOTS
// no pixel has more than SORTED_SLOTS fragments, all in its own slots: read them into
// registers (the empty ones last: depth +inf, opacity 0), sort them by a network and
// composite the same way as the lists (an empty slot adds 0 and keeps t: the same bytes).
// (llvmpipe runs every branch of a shader: a frame's resolve carries only the code its
// deepest pixel needs.) Returns the fragments past MAX_LAYERS.
uint composite_slots(uint count, out vec3 c, out float t) {
    float sd[SORTED_SLOTS];
    uint srg[SORTED_SLOTS], sba[SORTED_SLOTS];
    for (int i = 0; i < SORTED_SLOTS; ++i) {
        bool used = uint(i) < count;
        uvec4 slot = used ? oit_nodes[g_first + uint(i)] : uvec4(0u);
        sd[i] = used ? uintBitsToFloat(slot.z) : uintBitsToFloat(0x7F800000u);
        srg[i] = used ? slot.x : 0u;
        sba[i] = used ? slot.y : 0u;
    }
#if SORTED_SLOTS == 2
    ORDER(0, 1)
#elif SORTED_SLOTS == 4
    ORDER(0, 1) ORDER(2, 3) ORDER(0, 2) ORDER(1, 3) ORDER(1, 2)
#elif SORTED_SLOTS == 8
    ORDER(0, 1) ORDER(2, 3) ORDER(4, 5) ORDER(6, 7) ORDER(0, 2) ORDER(1, 3) ORDER(4, 6)
    ORDER(5, 7) ORDER(1, 2) ORDER(5, 6) ORDER(0, 4) ORDER(1, 5) ORDER(2, 6) ORDER(3, 7)
    ORDER(2, 4) ORDER(3, 5) ORDER(1, 2) ORDER(3, 4) ORDER(5, 6)
#elif SORTED_SLOTS != 1
#error "SORTED_SLOTS: 1, 2, 4 or 8 (render/passes/transparency.py)"
#endif
    c = vec3(0.0);
    t = 1.0;
    for (int k = 0; k < SORTED_SLOTS; ++k) {
        vec2 cr = unpackUnorm2x16(srg[k]), ca = unpackUnorm2x16(sba[k]);
        float a = k < MAX_LAYERS ? ca.y : 0.0;
        c += t * a * vec3(cr, ca.x);
        t *= 1.0 - a;
    }
    return count > uint(MAX_LAYERS) ? count - uint(MAX_LAYERS) : 0u;
}
#endif

// the pixel's list kept sorted nearest first, at most MAX_LAYERS of it, composited front to
// back; returns the fragments left out
uint composite_list(out vec3 c, out float t) {
    uvec4 node;
    int steps = 0;
    // (three arrays, element by element: llvmpipe lost whole-uvec4 copies between
    // dynamically indexed elements of one local array)
    float depth[MAX_LAYERS];
    uint rg[MAX_LAYERS], ba[MAX_LAYERS];
    int n = 0;
    uint dropped = 0u;
    while (steps < LIST_BUDGET && next_node(node)) {
        ++steps;
        float d = uintBitsToFloat(node.z);
        if (n == MAX_LAYERS && !before(d, node.x, node.y, depth[n - 1], rg[n - 1],
                                       ba[n - 1])) {
            ++dropped;
            continue;
        }
        if (n == MAX_LAYERS) {
            ++dropped;  // (the farthest kept one makes room)
            --n;
        }
        int k = n;
        while (k > 0 && before(d, node.x, node.y, depth[k - 1], rg[k - 1], ba[k - 1])) {
            ++steps;
            depth[k] = depth[k - 1];
            rg[k] = rg[k - 1];
            ba[k] = ba[k - 1];
            --k;
        }
        depth[k] = d;
        rg[k] = node.x;
        ba[k] = node.y;
        ++n;
    }
    if (steps >= LIST_BUDGET) atomicAdd(u_counts[2], 1u);
    c = vec3(0.0);
    t = 1.0;
    for (int k = 0; k < n; ++k) {
        vec2 cr = unpackUnorm2x16(rg[k]), ca = unpackUnorm2x16(ba[k]);
        c += t * ca.y * vec3(cr, ca.x);
        t *= 1.0 - ca.y;
    }
    return dropped;
}

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    uint pixel = uint(px.y) * u_oit_width + uint(px.x);
#ifdef OIT_FETCH
    uvec2 head = texelFetch(u_oit_heads, px, 0).xy;
#else
    uvec2 head = uvec2(oit_heads[pixel], oit_heads[u_oit_pixels + pixel]);
#endif
    uint count = head.x;
    if (count == 0u) discard;
    g_first = pixel * uint(OIT_SLOTS);
    g_slots = min(count, uint(OIT_SLOTS));
    g_next = head.y;
    vec4 behind = texelFetch(u_behind, px, 0);
#ifdef WEIGHTED
    frag_color = weighted(behind);
#else
    vec3 c;
    float t;
#ifdef SORTED_SLOTS
    uint dropped = composite_slots(count, c, t);
#else
    uint dropped = composite_list(c, t);
#endif
    if (dropped > 0u) {
        atomicAdd(u_counts[0], 1u);
        atomicAdd(u_counts[1], dropped);
    }
    frag_color = vec4(c + t * behind.rgb, behind.a);
#endif
}
