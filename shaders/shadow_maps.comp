#version 430 core
// Shadow maps as the fast method: for each pixel's surface point (the G-buffer's view depth
// and world normal), how much of one light its depth map says reaches it, by
// percentage-closer filtering: the fraction of the (2 PCF_RADIUS + 1)^2 map texels around
// the point's own whose occluder lies beyond the point (minus a bias).
//
// A directional light has one orthographic map (u_faces = 1); a point light six square
// perspective faces of 90 degrees (a cube map, laid out as tiles of one depth texture, 3
// across and 2 down), chosen by the major axis of the point's direction from the light.
// The bias is the texel's footprint on the surface: one texel's width (at the point's
// distance) times (1 + PCF_RADIUS) times the slope tan(theta) of the surface against the
// light, capped, plus one texel: enough that a lit plane never shades itself, and no more.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(r8, binding = 0) writeonly uniform image2DArray u_visibility;
uniform isampler2D u_face_ids;
uniform usampler2D u_depth_bits;
uniform sampler2D u_normals;       // world normal as (n + 1) / 2
uniform sampler2D u_map;           // the light's depths in [0, 1] (window depth)
uniform mat4 u_inverse_proj;     // clip -> view (rays.glsl)
uniform mat4 u_camera_to_world; // view -> world
uniform vec4 u_viewport;
uniform vec3 u_eye;
uniform vec3 u_forward;
uniform float u_near;
uniform int u_layer;               // the light's layer of u_visibility
uniform vec4 u_light;              // point (xyz, 1) or direction TO it (xyz, 0)
uniform int u_faces;               // 1 (directional) or 6 (point)
uniform mat4 u_face_view[6];       // world -> each face's view (a right-handed camera)
uniform vec2 u_face_planes;        // near, far of a point light's faces
uniform vec4 u_ortho;              // directional: half width, half height, near, far
uniform int u_size;                // texels a side of one face

#define PCF_RADIUS 1

#include "rays.glsl"

// the light's depth map at integer texel t of face f: distance along the face's view axis
float occluder_distance(int f, ivec2 t) {
    t = clamp(t, ivec2(0), ivec2(u_size - 1));
    ivec2 tile = u_faces == 6 ? ivec2(f % 3, f / 3) * u_size : ivec2(0);
    float z = texelFetch(u_map, tile + t, 0).r;
    if (u_faces == 6) {  // (perspective: window depth back to distance)
        float n = u_face_planes.x, fa = u_face_planes.y;
        return n * fa / (fa - z * (fa - n));
    }
    return u_ortho.z + z * (u_ortho.w - u_ortho.z);
}

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    ivec2 px = id.xy + ivec2(u_viewport.xy);
    if (any(greaterThanEqual(id.xy, ivec2(u_viewport.zw)))) return;
    int face_id = texelFetch(u_face_ids, px, 0).r;
    if (face_id == 0 || u_light.w > 1.5) {
        imageStore(u_visibility, ivec3(px, u_layer), vec4(1.0));
        return;
    }
    float depth = uintBitsToFloat(texelFetch(u_depth_bits, px, 0).r);
    vec2 ndc = (vec2(px) + 0.5 - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0;
    vec3 origin, span;
    pixel_ray(u_inverse_proj, u_camera_to_world, ndc, origin, span);
    vec3 dir = normalize(span);
#ifdef ORTHOGRAPHIC
    vec3 p = origin + dir * (depth - u_near);
#else
    vec3 p = u_eye + dir * (depth / dot(dir, u_forward));
#endif
    vec3 n = normalize(texelFetch(u_normals, px, 0).xyz * 2.0 - 1.0);
    vec3 to_light = u_light.w > 0.5 ? normalize(u_light.xyz - p) : u_light.xyz;
    float cos_t = clamp(abs(dot(n, to_light)), 0.05, 1.0);
    float tan_t = sqrt(1.0 - cos_t * cos_t) / cos_t;
    // the face that holds the point (a cube's by the major axis of light -> point)
    int f = 0;
    if (u_faces == 6) {
        vec3 a = p - u_light.xyz, m = abs(a);
        f = m.x >= m.y && m.x >= m.z ? (a.x > 0.0 ? 0 : 1) :
            m.y >= m.z ? (a.y > 0.0 ? 2 : 3) : (a.z > 0.0 ? 4 : 5);
    }
    vec4 q = u_face_view[f] * vec4(p, 1.0);
    float dist = -q.z;                          // along the face's view axis
    vec2 uv;
    float texel;                                // a texel's width on the surface, world
    if (u_faces == 6) {
        uv = q.xy / dist * 0.5 + 0.5;           // (90 degrees: tan 45 = 1)
        texel = 2.0 * dist / float(u_size);
    } else {
        uv = q.xy / u_ortho.xy * 0.5 + 0.5;
        texel = 2.0 * u_ortho.x / float(u_size);
    }
    float bias = texel * (1.0 + float(PCF_RADIUS)) * min(tan_t, 8.0) + texel;
    vec2 at = uv * float(u_size) - 0.5;
    ivec2 base = ivec2(floor(at + 0.5));
    float lit = 0.0;
    for (int j = -PCF_RADIUS; j <= PCF_RADIUS; ++j) {
        for (int i = -PCF_RADIUS; i <= PCF_RADIUS; ++i) {
            lit += occluder_distance(f, base + ivec2(i, j)) + bias >= dist ? 1.0 : 0.0;
        }
    }
    float taps = float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
    imageStore(u_visibility, ivec3(px, u_layer), vec4(lit / taps));
}
