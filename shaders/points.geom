#version 330 core
// The quad on screen that holds a point (render/passes/points.py). A sphere's or disc's is
// the exact screen box of its sphere -- in perspective, the tangent planes through the eye
// along each screen axis (the projected sphere is an ellipse, not a circle about the
// projected centre) -- grown by a pixel against rounding; the fragment stage casts the
// pixel's ray. A sphere that reaches the near plane (or the eye) gets the whole viewport.
// A square's is the square itself, at its centre's depth, in the view plane.
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

uniform mat4 u_proj;
uniform vec2 u_viewport_size;
uniform float u_near;               // the near plane's distance
#ifdef PIXEL_SIZE
uniform float u_pixel_size;         // a diameter on screen, pixels
#endif

in vec3 g_centre[];
in float g_radius[];
flat in int g_index[];
flat out vec3 f_centre;
flat out float f_radius;
flat out int f_index;
#ifdef POINT_COLORS
in vec3 g_color[];
flat out vec3 f_color;
#endif
#ifdef POINT_NORMALS
in vec3 g_normal[];
flat out vec3 f_normal;
#endif

float g_r;                          // the point's radius, view units (main sets it)

void corner(vec4 clip) {
    f_centre = g_centre[0];
    f_radius = g_r;
    f_index = g_index[0];
#ifdef POINT_COLORS
    f_color = g_color[0];
#endif
#ifdef POINT_NORMALS
    f_normal = g_normal[0];
#endif
    gl_Position = clip;
    EmitVertex();
}

void quad(vec2 lo, vec2 hi) {  // NDC, at mid depth (the fragment stage writes the depth)
    corner(vec4(lo.x, lo.y, 0.0, 1.0));
    corner(vec4(hi.x, lo.y, 0.0, 1.0));
    corner(vec4(lo.x, hi.y, 0.0, 1.0));
    corner(vec4(hi.x, hi.y, 0.0, 1.0));
    EndPrimitive();
}

#ifndef ORTHOGRAPHIC
// The two slopes (x / depth) of the planes through the eye that touch a circle of radius r
// about (u, w) (w the depth, > r): the circle's direction turned by the angle it subtends.
vec2 tangent_slopes(float u, float w, float r) {
    float l2 = u * u + w * w;
    float t = sqrt(max(l2 - r * r, 0.0));
    vec2 a = vec2(u * t + w * r, w * t - u * r);  // turned one way (times l^2: same slope)
    vec2 b = vec2(u * t - w * r, w * t + u * r);  // and the other
    return vec2(a.x / a.y, b.x / b.y);
}
#endif

void main() {
    vec3 c = g_centre[0];
    float r = g_radius[0];
    vec4 clip = u_proj * vec4(c, 1.0);
#ifdef PIXEL_SIZE
    // the radius whose diameter at the centre's depth is u_pixel_size pixels
    r = u_pixel_size / u_viewport_size.y * clip.w / abs(u_proj[1][1]);
#endif
#ifdef STYLE_SQUARE
    if (clip.w <= 0.0) return;
#ifdef PIXEL_SIZE
    vec2 half_size = u_pixel_size / u_viewport_size * clip.w;
#else
    vec2 half_size = vec2(r * u_proj[0][0], r * u_proj[1][1]);
#endif
    g_r = r;
    corner(clip + vec4(-half_size.x, -half_size.y, 0.0, 0.0));
    corner(clip + vec4(half_size.x, -half_size.y, 0.0, 0.0));
    corner(clip + vec4(-half_size.x, half_size.y, 0.0, 0.0));
    corner(clip + vec4(half_size.x, half_size.y, 0.0, 0.0));
    EndPrimitive();
#else
    vec2 pixel = 2.0 / u_viewport_size;  // (one pixel in NDC: the margin)
#ifdef ORTHOGRAPHIC
    if (c.z - r > -u_near) return;          // wholly before the near plane
    vec4 lo4 = u_proj * vec4(c - vec3(r, r, 0.0), 1.0);
    vec4 hi4 = u_proj * vec4(c + vec3(r, r, 0.0), 1.0);
    vec2 lo = min(lo4.xy, hi4.xy), hi = max(lo4.xy, hi4.xy);
#else
    float w = -c.z;
    if (w + r <= u_near) return;            // wholly before the near plane
    vec2 lo, hi;
    if (w - r <= u_near * 1.001) {          // cut by the near plane, or round the eye
        lo = vec2(-1.0);
        hi = vec2(1.0);
    } else {
        // ndc x = P00 (x / w) - P02 and ndc y = P11 (y / w) - P12 (no skew)
        vec2 sx = u_proj[0][0] * tangent_slopes(c.x, w, r) - u_proj[2][0];
        vec2 sy = u_proj[1][1] * tangent_slopes(c.y, w, r) - u_proj[2][1];
        lo = vec2(min(sx.x, sx.y), min(sy.x, sy.y));
        hi = vec2(max(sx.x, sx.y), max(sy.x, sy.y));
    }
#endif
    lo = max(lo - pixel, vec2(-1.0));
    hi = min(hi + pixel, vec2(1.0));
    if (any(greaterThanEqual(lo, hi))) return;
    g_r = r;
    quad(lo, hi);
#endif
}
