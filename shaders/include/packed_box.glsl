// A packed child's box (geometry/bvh.py, packed_children): its corners in 16-bit steps of
// the root's box, rounded outwards -- the hierarchies of the path tracer (pathtrace.frag)
// and of the exact shadow rays (shadow_trace.glsl) alike.
#ifndef PACKED_BOX_GLSL
#define PACKED_BOX_GLSL
uniform uvec4 u_root;              // the root, packed as a child
uniform vec3 u_qbase;              // a corner q (in steps) lies at u_qbase + q u_qstep
uniform vec3 u_qstep;

// where o + t d (``inv`` = 1 / d) enters child ``c``'s box for t in [t_min, t_max];
// negative where it misses
float packed_box_entry(uvec4 c, vec3 o, vec3 inv, float t_min, float t_max) {
    vec3 lo = u_qbase + vec3(uvec3(c.x & 0xFFFFu, c.x >> 16, c.y & 0xFFFFu)) * u_qstep;
    vec3 hi = u_qbase + vec3(uvec3(c.y >> 16, c.z & 0xFFFFu, c.z >> 16)) * u_qstep;
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    float near = max(max(tn.x, tn.y), max(tn.z, t_min));
    float far = min(min(tf.x, tf.y), min(tf.z, t_max));
    return near <= far ? near : -1.0;
}
#endif
