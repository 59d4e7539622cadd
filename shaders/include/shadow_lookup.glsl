// A shadow map lookup (render/passes/shadow_maps.py), shared by the compute pass that fills
// a pixel's visibility from the G-buffer (shadow_maps.comp) and by fragment programs that
// look their maps up as they shade (SHADOW_MAPS_FORWARD, shadow_mask.glsl): how much of
// light i reaches world point p with world normal n, by percentage-closer filtering -- the
// fraction of the (2 PCF_RADIUS + 1)^2 map texels around the point's own whose occluder
// lies beyond the point (minus a bias).
//
// A directional light has one orthographic map (faces 1); a point light six square
// perspective faces of 90 degrees (a cube map, laid out as tiles of one depth texture, 3
// across and 2 down), chosen by the major axis of the point's direction from the light.
// The bias is the texel's footprint on the surface: one texel's width (at the point's
// distance) times (1 + PCF_RADIUS) times the slope tan(theta) of the surface against the
// light, capped, plus one texel: enough that a lit plane never shades itself, and no more.
#ifndef SHADOW_LOOKUP_GLSL
#define SHADOW_LOOKUP_GLSL
#ifndef SHADOW_LIGHTS
#define SHADOW_LIGHTS 1
#endif
#define PCF_RADIUS 1

uniform sampler2D u_maps[SHADOW_LIGHTS];          // each light's depths in [0, 1]
uniform vec4 u_map_light[SHADOW_LIGHTS];          // point (xyz, 1), TO it (xyz, 0); w 2: none
uniform ivec2 u_map_shape[SHADOW_LIGHTS];         // (faces: 1 or 6, texels a side of one)
uniform mat4 u_face_view[6 * SHADOW_LIGHTS];      // world -> each face's view
uniform vec2 u_face_planes[SHADOW_LIGHTS];        // near, far of a point light's faces
uniform vec4 u_ortho[SHADOW_LIGHTS];              // directional: half w, half h, near, far

// light i's depth map at integer texel t of face f: distance along the face's view axis
float occluder_distance(int i, int f, ivec2 t) {
    int size = u_map_shape[i].y;
    t = clamp(t, ivec2(0), ivec2(size - 1));
    bool cube = u_map_shape[i].x == 6;
    ivec2 tile = cube ? ivec2(f % 3, f / 3) * size : ivec2(0);
    float z = texelFetch(u_maps[i], tile + t, 0).r;
    if (cube) {  // (perspective: window depth back to distance)
        float n = u_face_planes[i].x, fa = u_face_planes[i].y;
        return n * fa / (fa - z * (fa - n));
    }
    return u_ortho[i].z + z * (u_ortho[i].w - u_ortho[i].z);
}

float map_visibility(int i, vec3 p, vec3 n) {
    vec4 light = u_map_light[i];
    if (light.w > 1.5) return 1.0;  // (a light that casts no shadows)
    vec3 to_light = light.w > 0.5 ? normalize(light.xyz - p) : light.xyz;
    float cos_t = clamp(abs(dot(n, to_light)), 0.05, 1.0);
    float tan_t = sqrt(1.0 - cos_t * cos_t) / cos_t;
    // the face that holds the point (a cube's by the major axis of light -> point)
    bool cube = u_map_shape[i].x == 6;
    int size = u_map_shape[i].y;
    int f = 0;
    if (cube) {
        vec3 a = p - light.xyz, m = abs(a);
        f = m.x >= m.y && m.x >= m.z ? (a.x > 0.0 ? 0 : 1) :
            m.y >= m.z ? (a.y > 0.0 ? 2 : 3) : (a.z > 0.0 ? 4 : 5);
    }
    vec4 q = u_face_view[6 * i + f] * vec4(p, 1.0);
    float dist = -q.z;                          // along the face's view axis
    vec2 uv;
    float texel;                                // a texel's width on the surface, world
    if (cube) {
        uv = q.xy / dist * 0.5 + 0.5;           // (90 degrees: tan 45 = 1)
        texel = 2.0 * dist / float(size);
    } else {
        uv = q.xy / u_ortho[i].xy * 0.5 + 0.5;
        texel = 2.0 * u_ortho[i].x / float(size);
    }
    float bias = texel * (1.0 + float(PCF_RADIUS)) * min(tan_t, 8.0) + texel;
    vec2 at = uv * float(size) - 0.5;
    ivec2 base = ivec2(floor(at + 0.5));
    float lit = 0.0;
    for (int j = -PCF_RADIUS; j <= PCF_RADIUS; ++j) {
        for (int k = -PCF_RADIUS; k <= PCF_RADIUS; ++k) {
            lit += occluder_distance(i, f, base + ivec2(k, j)) + bias >= dist ? 1.0 : 0.0;
        }
    }
    return lit / float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
}
#endif
