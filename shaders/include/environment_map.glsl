// An environment's equirectangular map (scene/environment.py holds the convention): a
// map-frame direction's (u, v) and back, for the tracer's sky (trace_environment.glsl), the
// rasterizer's image-based light (environment_light.glsl) and background (background.frag).
#ifndef ENVIRONMENT_MAP_GLSL
#define ENVIRONMENT_MAP_GLSL
#define ENV_PI 3.14159265358979

// u = 0.5 + atan2(x, -z) / (2 pi), v = acos(y) / pi: both in [0, 1)
vec2 env_map_uv(vec3 d) {
    float u = 0.5 + atan(d.x, -d.z) / (2.0 * ENV_PI);
    float v = acos(clamp(d.y, -1.0, 1.0)) / ENV_PI;
    return vec2(u - floor(u), min(v, 0.9999999));
}

vec3 env_map_direction(vec2 uv) {
    float phi = (uv.x - 0.5) * 2.0 * ENV_PI, theta = uv.y * ENV_PI;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

// a world direction in the map's frame, the map turned by ``rotation`` about +y
vec3 env_map_frame(vec3 d, float rotation) {
    float c = cos(rotation), s = sin(rotation);
    return vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}
#endif
