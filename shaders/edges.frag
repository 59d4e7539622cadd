#version 330 core
// An edge's colour, unlit, where its point on the centre line is seen. Seen: no surface
// drawn before the edges is nearer there than the edge itself, judged in view depth against
// the 3x3 pixels around that point (the window depth the surfaces left, copied to
// u_scene_depth): the edge may be as far as the farthest of them, plus their spread (the
// surfaces' slope across a pixel: a concave edge lies behind the pixels beside it) and
// four steps of the depth buffer -- so the judgement holds at any near plane. A pixel of
// the 3x3 with nothing drawn makes the point seen (a silhouette).
uniform vec3 u_edge_color;
uniform sampler2D u_scene_depth;   // window depth in [0, 1] (1: nothing drawn)
uniform mat4 u_inverse_proj;       // clip -> view
uniform int u_hide;                // 1: hide what is behind the surfaces (depth test on)

noperspective in vec2 g_centre;
noperspective in float g_ndc_z;

layout(location = 0) out vec4 frag_color;

float view_depth(float ndc_z) {
    vec4 q = u_inverse_proj * vec4(0.0, 0.0, ndc_z, 1.0);
    return -q.z / q.w;
}

void main() {
    if (u_hide != 0) {
        ivec2 size = textureSize(u_scene_depth, 0);
        ivec2 c = ivec2(floor(g_centre));
        float far_w = 0.0, near_d = 1e30, far_d = -1e30;
        bool open = false;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                ivec2 p = clamp(c + ivec2(dx, dy), ivec2(0), size - 1);
                float w = texelFetch(u_scene_depth, p, 0).r;
                if (w >= 1.0) { open = true; continue; }
                float d = view_depth(2.0 * w - 1.0);
                far_w = max(far_w, w);
                near_d = min(near_d, d);
                far_d = max(far_d, d);
            }
        if (!open) {
            float step4 = view_depth(2.0 * min(far_w + 4.0 / 16777216.0, 1.0) - 1.0) - far_d;
            if (view_depth(g_ndc_z) > far_d + (far_d - near_d) + step4) discard;
        }
    }
    frag_color = vec4(u_edge_color, 1.0);
}
