#version 330 core
// A polyline's segment: the pixels whose centres lie in its shape (lines.geom), unlit --
// its colour (interpolated along the segment, perspective-correct) or the material's. Its
// depth at a pixel is the centre line's nearest point's (NDC z is affine along a line on
// screen), written to gl_FragDepth: depth-tested against everything drawn.
#include "srgb.glsl"

uniform vec3 u_line_color;
uniform mat4 u_inverse_proj;          // clip -> view
uniform mat4 u_camera_to_world;       // view -> world
uniform vec2 u_depth_range;

flat in vec4 f_ends;
flat in vec2 f_half;
flat in vec4 f_cuts;
flat in ivec2 f_round;
flat in vec4 f_bevel;
flat in int f_bevelled;
flat in vec4 f_depth;
flat in int f_segment;
#ifdef LINE_COLORS
flat in vec3 f_color_a;
flat in vec3 f_color_b;
#endif
uniform int u_face_id_base;

layout(location = 0) out vec4 frag_color;
#ifdef GLSHADE_AUX_OUTPUTS
layout(location = 1) out vec4 frag_normal;
layout(location = 2) out int frag_face_id;
layout(location = 3) out uint frag_depth_bits;
#endif

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

bool in_triangle(vec2 p, vec2 a, vec2 b, vec2 c) {
    float s1 = cross2(b - a, p - a), s2 = cross2(c - b, p - b), s3 = cross2(a - c, p - c);
    return (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0);
}

void main() {
    vec2 p = gl_FragCoord.xy;
    vec2 a = f_ends.xy, b = f_ends.zw;
    vec2 along = b - a;
    float len2 = dot(along, along);
    vec2 u = len2 > 1e-12 ? along / sqrt(len2) : vec2(1.0, 0.0);
    float s = len2 > 1e-12 ? dot(p - a, along) / len2 : 0.0;
    float perp = dot(p - a, vec2(-u.y, u.x));
    float h = mix(f_half.x, f_half.y, clamp(s, 0.0, 1.0));
    bool inside = len2 > 1e-12 && abs(perp) <= h && dot(p - a, f_cuts.xy) >= 0.0 &&
                  dot(p - b, f_cuts.zw) <= 0.0;
    inside = inside || (f_round.x == 1 && distance(p, a) <= f_half.x) ||
             (f_round.y == 1 && distance(p, b) <= f_half.y) ||
             (f_bevelled == 1 && in_triangle(p, a, f_bevel.xy, f_bevel.zw));
    if (!inside) discard;
    float t = clamp(s, 0.0, 1.0);
    float z = mix(f_depth.x, f_depth.y, t);
    gl_FragDepth = 0.5 * z + 0.5;
    // the segment's own parameter there: 1/w is affine on screen
    float k = t / f_depth.w / mix(1.0 / f_depth.z, 1.0 / f_depth.w, t);
#ifdef LINE_COLORS
    vec3 color = mix(f_color_a, f_color_b, k);
#else
    vec3 color = u_line_color;
#endif
    vec4 q = u_inverse_proj * vec4(0.0, 0.0, z, 1.0);
    float depth = -q.z / q.w;
    vec3 n_world = normalize(mat3(u_camera_to_world) * vec3(0.0, 0.0, 1.0));
#if defined(SHOW_NORMALS)
    color = 0.5 * n_world + 0.5;
#elif defined(SHOW_DEPTH)
    color = vec3(1.0 - clamp((depth - u_depth_range.x) / (u_depth_range.y - u_depth_range.x),
                             0.0, 1.0));
#endif
    color = clamp(color, 0.0, 1.0);
#ifdef SRGB
    color = encode_srgb(color);
#endif
    frag_color = vec4(color, 1.0);
#ifdef GLSHADE_AUX_OUTPUTS
    frag_normal = vec4(n_world, 1.0);
    frag_face_id = u_face_id_base + f_segment + 1;
    frag_depth_bits = floatBitsToUint(depth);
#endif
}
