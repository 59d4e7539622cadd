// A shadow map lookup (render/passes/shadow_maps.py), shared by the compute pass that fills
// a pixel's visibility from the G-buffer (shadow_maps.comp) and by fragment programs that
// look their maps up as they shade (SHADOW_MAPS_FORWARD, shadow_mask.glsl): how much of
// light i reaches world point p with world normal n, by percentage-closer filtering -- the
// fraction of the (2 PCF_RADIUS + 1)^2 map texels around the point's own whose occluder
// lies beyond the point (minus a bias).
//
// A directional light has one orthographic map (faces 1); a point light six square
// perspective faces of 90 degrees (a cube map, laid out as tiles of one depth texture, 3
// across and 2 down), chosen by the major axis of the direction from the light.
// The bias is the texel's footprint on the surface: one texel's width (at the point's
// distance) times (1 + PCF_RADIUS) times the slope tan(theta) of the surface against the
// light, capped at 8, plus one texel; past the cap the point moves off its plane (a normal
// offset) by what the cap left: enough that a lit plane never shades itself, and no more.
// A cube map's PCF texels that fall off the point's face are read from the face that holds
// them (cube_visibility).
#ifndef SHADOW_LOOKUP_GLSL
#define SHADOW_LOOKUP_GLSL
#ifndef SHADOW_LIGHTS
#define SHADOW_LIGHTS 1
#endif
#define PCF_RADIUS 1
#define SLOPE_CAP 8.0  // the bias's largest slope tan(theta); past it the point moves off

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

// the face of a point light's cube map that holds direction d (its major axis)
int cube_face(vec3 d) {
    vec3 m = abs(d);
    return m.x >= m.y && m.x >= m.z ? (d.x > 0.0 ? 0 : 1) :
           m.y >= m.z ? (d.y > 0.0 ? 2 : 3) : (d.z > 0.0 ? 4 : 5);
}

// A point light's PCF: the texels around the point's own on its face, each looked up along
// its own ray from the light -- which may leave the face: then on the face that holds it
// (clamping to the face's border read the wrong texels along every seam), against the
// point's own distance along that face's axis.
float cube_visibility(int i, vec3 p, float tan_t) {
    vec3 light = u_map_light[i].xyz;
    int size = u_map_shape[i].y;
    vec3 a = p - light;
    int f = cube_face(a);
    vec3 q = mat3(u_face_view[6 * i + f]) * a;
    float dist = -q.z;                           // along the face's view axis
    vec2 at = (q.xy / dist * 0.5 + 0.5) * float(size) - 0.5;
    ivec2 base = ivec2(floor(at + 0.5));
    float texel = 2.0 * dist / float(size);      // a texel's width at the point, world
    float bias = texel * (1.0 + float(PCF_RADIUS)) * min(tan_t, SLOPE_CAP) + texel;
    mat3 from_face = transpose(mat3(u_face_view[6 * i + f]));
    float lit = 0.0;
    for (int j = -PCF_RADIUS; j <= PCF_RADIUS; ++j) {
        for (int k = -PCF_RADIUS; k <= PCF_RADIUS; ++k) {
            ivec2 t = base + ivec2(k, j);
            int g = f;
            float along = dist;
            if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, ivec2(size)))) {
                vec2 tc = (vec2(t) + 0.5) / float(size) * 2.0 - 1.0;
                vec3 d = from_face * vec3(tc, -1.0);          // the texel's ray, world
                g = cube_face(d);
                vec3 qg = mat3(u_face_view[6 * i + g]) * d;
                t = ivec2(floor((qg.xy / -qg.z * 0.5 + 0.5) * float(size)));
                along = -(mat3(u_face_view[6 * i + g]) * a).z;
            }
            lit += occluder_distance(i, g, t) + bias >= along ? 1.0 : 0.0;
        }
    }
    return lit / float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
}

float map_visibility(int i, vec3 p, vec3 n, vec3 to_eye) {
    vec4 light = u_map_light[i];
    if (light.w > 1.5) return 1.0;  // (a light that casts no shadows)
    vec3 to_light = light.w > 0.5 ? normalize(light.xyz - p) : light.xyz;
    n = dot(n, to_eye) < 0.0 ? -n : n;         // (the side the point was seen from)
    float facing = dot(n, to_light);
    float cos_t = clamp(abs(facing), 0.05, 1.0);
    float tan_t = sqrt(1.0 - cos_t * cos_t) / cos_t;
    // Past the depth bias's slope cap (tan 8: a surface within 7 degrees of edge-on to the
    // light) the rest of the slope is met by moving the point off its plane, out on the
    // side it was seen from, where a light it faces is: a texel's width times (1 +
    // PCF_RADIUS) times sin - 8 cos, which keeps the plane's own texels behind it at any
    // angle (it shaded itself in bands) and moves the point at most (1 + PCF_RADIUS)
    // texels (within a shadow's stated band). A light behind the surface lights none of it.
    bool cube = u_map_shape[i].x == 6;
    vec3 a = abs(p - light.xyz);
    float texel_width = 2.0 * (cube ? max(a.x, max(a.y, a.z)) : u_ortho[i].x)
                        / float(u_map_shape[i].y);
    float sin_t = sqrt(max(1.0 - facing * facing, 0.0));
    p += n * texel_width * (1.0 + float(PCF_RADIUS)) * max(sin_t - SLOPE_CAP * facing, 0.0) *
         float(facing > 0.0);
    if (cube) return cube_visibility(i, p, tan_t);
    int size = u_map_shape[i].y;
    vec4 q = u_face_view[6 * i] * vec4(p, 1.0);
    float dist = -q.z;                          // along the light's view axis
    vec2 uv = q.xy / u_ortho[i].xy * 0.5 + 0.5;
    float bias = texel_width * (1.0 + float(PCF_RADIUS)) * min(tan_t, SLOPE_CAP) + texel_width;
    vec2 at = uv * float(size) - 0.5;
    ivec2 base = ivec2(floor(at + 0.5));
    float lit = 0.0;
    for (int j = -PCF_RADIUS; j <= PCF_RADIUS; ++j) {
        for (int k = -PCF_RADIUS; k <= PCF_RADIUS; ++k) {
            lit += occluder_distance(i, 0, base + ivec2(k, j)) + bias >= dist ? 1.0 : 0.0;
        }
    }
    return lit / float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
}
#endif
