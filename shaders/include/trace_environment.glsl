// The path tracer's sky (ENVIRONMENT defined; scene/environment.py gives the map's
// convention, pathtrace/pack.py environment_tables the texels): its radiance where a ray
// leaves the scene, a direction drawn by importance (a row by the rows' chances, a column
// by the row's, a point uniform in the texel) and that draw's density, for next-event
// estimation and its MIS weight against the bounce's.
#ifndef TRACE_ENVIRONMENT_GLSL
#define TRACE_ENVIRONMENT_GLSL
uniform int u_env;           // its texels: H x W, row by row, (pi L, cumulative in the row)
uniform int u_env_rows;      // then, from u_env + u_env_rows, a texel a row: (cumulative, p)
uniform int u_env_w, u_env_h;
uniform float u_env_rotation;  // radians the map turns about +y

#include "environment_map.glsl"

// a world direction's place on the map, (u, v) in [0, 1)^2
vec2 env_uv(vec3 d) {
    return env_map_uv(env_map_frame(d, u_env_rotation));
}

// the map's direction at (u, v), in the world (turned by the rotation)
vec3 env_direction(vec2 uv) {
    return env_map_frame(env_map_direction(uv), -u_env_rotation);
}

ivec2 env_texel(vec2 uv) {
    return min(ivec2(uv * vec2(u_env_w, u_env_h)), ivec2(u_env_w - 1, u_env_h - 1));
}

// pi x the radiance arriving along -d (seen looking along d)
vec3 env_radiance(vec3 d) {
    ivec2 t = env_texel(env_uv(d));
    return fetch(u_env + t.y * u_env_w + t.x).xyz;
}

// the density (solid angle) with which env_sample draws d
float env_pdf(vec3 d) {
    vec2 uv = env_uv(d);
    ivec2 t = env_texel(uv);
    float row = fetch(u_env + u_env_rows + t.y).y;
    int at = u_env + t.y * u_env_w + t.x;
    float within = fetch(at).w - (t.x > 0 ? fetch(at - 1).w : 0.0);
    float sin_t = sin(uv.y * PI);
    return sin_t > 0.0 ? row * within * float(u_env_w * u_env_h) / (2.0 * PI * PI * sin_t)
                       : 0.0;
}

// the first of n cumulative chances from ``first`` (stride 1) that reaches r
int env_search(int first, int n, float r, int column) {
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        ++g_iter;
        int mid = (lo + hi) / 2;
        vec4 t = fetch(first + mid);
        if ((column == 0 ? t.x : t.w) < r) lo = mid + 1; else hi = mid;
    }
    return lo;
}

// a direction drawn by importance from u in [0, 1)^2 (a row, a column; where each number
// fell within its interval places the point in the texel), and its density
vec3 env_sample(vec2 u, out float pdf) {
    int first_row = u_env + u_env_rows;
    int r = env_search(first_row, u_env_h, u.x, 0);
    vec4 row = fetch(first_row + r);
    float sv = clamp((u.x - (row.x - row.y)) / max(row.y, 1e-30), 0.0, 0.9999999);
    int first = u_env + r * u_env_w;
    int c = env_search(first, u_env_w, u.y, 1);
    float lo = c > 0 ? fetch(first + c - 1).w : 0.0;
    float su = clamp((u.y - lo) / max(fetch(first + c).w - lo, 1e-30), 0.0, 0.9999999);
    vec3 d = env_direction((vec2(c, r) + vec2(su, sv)) / vec2(u_env_w, u_env_h));
    pdf = env_pdf(d);
    return d;
}
#endif
