#version 330 core
// A polyline's segment (lines with adjacency: before, start, end, after) as the quad that
// holds its shape on screen (wide_lines.glsl); lines.frag keeps the pixels inside the
// shape: the band of the line's width about the segment (a trapezoid in world units: the
// width shrinks with depth), cut at each end by the bisector of the angle with the
// neighbour (a miter), or square at the end point where there is none (a cap), where the
// miter would reach past MITER_LIMIT half-widths (a bevel: the triangle between the two
// outer corners, drawn by the later segment) or where joins or caps are round (a disc of
// the width about the end point).
layout(lines_adjacency) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 u_viewport_origin;
uniform vec2 u_viewport_size;
uniform mat4 u_proj;
uniform float u_half_width;          // pixels, or view units (LINE_WORLD)

flat in int v_index[];
#ifdef LINE_COLORS
in vec3 v_color[];
flat out vec3 f_color_a;
flat out vec3 f_color_b;
#endif
flat out vec4 f_ends;                // the segment's two end points, window pixels
flat out vec2 f_half;                // half widths at the ends, pixels
flat out vec4 f_cuts;                // the end cuts' normals (along the segment)
flat out ivec2 f_round;              // a disc at each end
flat out vec4 f_bevel;               // a bevel triangle's outer corners at the start
flat out int f_bevelled;
flat out vec4 f_depth;               // NDC z and clip w at each end
flat out int f_segment;

#include "wide_lines.glsl"

float half_width(vec4 clip) {
#ifdef LINE_WORLD
    return u_half_width * abs(u_proj[1][1]) * 0.5 * u_viewport_size.y / clip.w;
#else
    return u_half_width;
#endif
}

// The cut between this segment (unit direction u) and a neighbour's (unit direction d,
// both pointing along the polyline): the bisector's normal, or u where the miter is too
// long (a bevel) or the joins are round.
vec2 cut(vec2 u, vec2 d, out bool bevel) {
    vec2 m = u + d;
    bevel = false;
#ifdef ROUND_JOINS
    return u;
#else
    if (dot(m, m) < 1e-12 || dot(normalize(m), u) < 1.0 / MITER_LIMIT) {
        bevel = true;
        return u;
    }
    return normalize(m);
#endif
}

// One end of the segment (window point w, half width h; u the segment's direction away
// from the end, s = -1 at the start, +1 at the end): the cut there and whether it is round
// or bevelled, from the neighbour's clip position (none: a cap). Returns how far the
// shape may reach beyond the end.
float end_shape(vec2 w, float h, vec2 u, bool neighbour, vec4 other, vec4 self_clip,
                float s, bool cut_end, out vec2 cut_normal, out int round, out bool bevel,
                out vec4 corners) {
    cut_normal = u;
    round = 0;
    bevel = false;
    corners = vec4(0.0);
    if (neighbour) {
        vec4 p = other, q = self_clip;
        clip_near(p, q);
        vec2 d = -s * (w - to_window(p, u_viewport_origin, u_viewport_size));
        d = dot(d, d) > 1e-12 ? normalize(d) : u;
        cut_normal = cut(u, d, bevel);
        if (bevel && s < 0.0) {  // the outer corners: on the side away from the turn
            float side = d.x * u.y - d.y * u.x > 0.0 ? -1.0 : 1.0;
            corners = vec4(w + side * h * vec2(-d.y, d.x), w + side * h * vec2(-u.y, u.x));
        }
#ifdef ROUND_JOINS
        round = 1;
#endif
    } else {
#ifdef ROUND_CAPS
        round = cut_end ? 0 : 1;
#endif
    }
    if (neighbour && !bevel && round == 0) return MITER_LIMIT * h + 1.0;
    return (round == 1 || bevel) ? h + 1.0 : 1.0;
}

void main() {
    vec4 a = gl_in[1].gl_Position, b = gl_in[2].gl_Position;
    vec4 a0 = a, b0 = b;
    if (!clip_near(a, b)) return;
    bool cut_a = a != a0, cut_b = b != b0;            // (ends cut by the near plane)
    // where the ends now are along the segment (clip space is linear in the world)
    float da = a0.z + a0.w, db = b0.z + b0.w;
    float ta = cut_a ? da / (da - db) : 0.0, tb = cut_b ? 1.0 - db / (db - da) : 1.0;
    vec2 wa = to_window(a, u_viewport_origin, u_viewport_size);
    vec2 wb = to_window(b, u_viewport_origin, u_viewport_size);
    float ha = half_width(a), hb = half_width(b);
    vec2 along = wb - wa;
    if (dot(along, along) < 1e-12) {
#if !defined(ROUND_JOINS) && !defined(ROUND_CAPS)
        return;                                        // (no length, no discs: nothing)
#endif
        along = vec2(1.0, 0.0);
    }
    vec2 u = normalize(along), ca, cb;
    ivec2 round;
    bool bevel_a, bevel_b;
    vec4 bevel, unused;
    float reach_a = end_shape(wa, ha, u, v_index[0] != v_index[1] && !cut_a,
                              gl_in[0].gl_Position, a, -1.0, cut_a, ca, round.x, bevel_a, bevel);
    float reach_b = end_shape(wb, hb, u, v_index[3] != v_index[2] && !cut_b,
                              gl_in[3].gl_Position, b, 1.0, cut_b, cb, round.y, bevel_b, unused);
    vec2 corners[4];
    segment_quad(wa, wb, max(ha, hb) + 1.0, reach_a, reach_b, corners);
    for (int i = 0; i < 4; ++i) {
        f_ends = vec4(wa, wb);
        f_half = vec2(ha, hb);
        f_cuts = vec4(ca, cb);
        f_round = round;
        f_bevel = bevel;
        f_bevelled = bevel_a ? 1 : 0;
        f_depth = vec4(a.z / a.w, b.z / b.w, a.w, b.w);
        f_segment = gl_PrimitiveIDIn;
#ifdef LINE_COLORS
        f_color_a = mix(v_color[1], v_color[2], ta);
        f_color_b = mix(v_color[1], v_color[2], tb);
#endif
        gl_Position = vec4(to_ndc(corners[i], u_viewport_origin, u_viewport_size), 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
