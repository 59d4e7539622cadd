#version 330 core
// An edge's colour, unlit, where its point on the centre line is seen. The pixel holding
// that point decides, from the window depth the surfaces left there (copied to
// u_scene_depth):
// - nothing drawn there: seen (a silhouette against the background);
// - one of the edge's own faces drawn there: seen, be the edge convex or concave. Its depth
//   lies within OWN_REACH pixel footprints of the edge's (a surface far off in the face's
//   plane is another) and on the plane of that face's triangle beside the edge: at the
//   pixel centre for a single-sampled depth buffer (to within the buffer's rounding and a
//   fiftieth of the plane's spread over the pixel: another surface crossing just in front
//   of the edge is not taken for its face), anywhere over the pixel's square for a
//   multisampled one, whose copy may hold any of its samples (a face seen nearly edge-on
//   spans many depths there: a surface that close in front of the edge is taken for it);
// - another surface: seen where it is no nearer than the edge (a silhouette in front of a
//   farther surface), hidden where it is nearer.
// No constant bias, no look at the neighbouring pixels (a neighbour across a silhouette says
// nothing about this point): the judgement holds at any near plane, inside a scene or out.
uniform vec3 u_edge_color;
uniform sampler2D u_scene_depth;   // window depth in [0, 1] (1: nothing drawn)
uniform mat4 u_inverse_proj;       // clip -> view
uniform vec2 u_viewport_origin;    // pixels
uniform vec2 u_viewport_size;      // pixels
uniform int u_hide;                // 1: hide what is behind the surfaces (depth test on)
uniform int u_centre_depth;        // 1: the depth copy is single-sampled (the pixel centre's)

noperspective in vec2 g_centre;
noperspective in float g_ndc_z;
flat in vec4 g_plane_a;
flat in vec4 g_plane_b;

layout(location = 0) out vec4 frag_color;

// how far from the edge's depth, in the pixel's footprint at that depth, its own face may
// be found: faces up to atan(4) = 76 degrees from the line of sight
const float OWN_REACH = 4.0;

vec3 unproject(vec2 window, float ndc_z) {
    vec2 ndc = (window - u_viewport_origin) / u_viewport_size * 2.0 - 1.0;
    vec4 q = u_inverse_proj * vec4(ndc, ndc_z, 1.0);
    return q.xyz / q.w;
}

float view_depth(float ndc_z) {
    vec4 q = u_inverse_proj * vec4(0.0, 0.0, ndc_z, 1.0);
    return -q.z / q.w;
}

// The view depths a plane takes over the pixel square around ``centre`` (its four
// corners' rays; the plane is flat, so they bound it): (min, max), or an empty range for a
// degenerate face or a plane seen edge-on.
vec2 plane_depths(vec4 plane, vec2 centre) {
    vec2 range = vec2(1e38, -1e38);
    if (dot(plane.xyz, plane.xyz) < 0.25) return range;
    for (int i = 0; i < 4; ++i) {
        vec2 corner = centre + 0.5 * vec2((i & 1) == 0 ? -1.0 : 1.0, i < 2 ? -1.0 : 1.0);
        vec3 p0 = unproject(corner, -1.0), p1 = unproject(corner, 1.0);
        float along = dot(plane.xyz, p1 - p0);
        if (abs(along) < 1e-30) return vec2(1e38, -1e38);
        vec3 hit = p0 + (plane.w - dot(plane.xyz, p0)) / along * (p1 - p0);
        range = vec2(min(range.x, -hit.z), max(range.y, -hit.z));
    }
    return range;
}

// The view depth of a plane along the ray through window point ``at`` (1e38: none).
float plane_depth_at(vec4 plane, vec2 at) {
    if (dot(plane.xyz, plane.xyz) < 0.25) return 1e38;
    vec3 p0 = unproject(at, -1.0), p1 = unproject(at, 1.0);
    float along = dot(plane.xyz, p1 - p0);
    if (abs(along) < 1e-30) return 1e38;
    return -(p0 + (plane.w - dot(plane.xyz, p0)) / along * (p1 - p0)).z;
}

// Whether depth ``d`` at the pixel centre lies on ``plane`` there: within ``slack`` and a
// fiftieth of the plane's ``range`` of depths over the pixel.
bool on_plane_at_centre(vec4 plane, vec2 range, vec2 centre, float d, float slack) {
    float at = plane_depth_at(plane, centre);
    return at < 1e37 && abs(d - at) <= slack + 0.02 * max(range.y - range.x, 0.0);
}

void main() {
    if (u_hide != 0) {
        ivec2 size = textureSize(u_scene_depth, 0);
        ivec2 c = clamp(ivec2(floor(g_centre)), ivec2(0), size - 1);
        float w = texelFetch(u_scene_depth, c, 0).r;
        if (w < 1.0) {
            float d = view_depth(2.0 * w - 1.0);
            // four steps of the 24-bit depth buffer there: its own rounding
            float step4 = view_depth(2.0 * min(w + 4.0 / 16777216.0, 1.0) - 1.0) - d;
            vec2 centre = vec2(c) + 0.5;
            float edge_d = view_depth(g_ndc_z);
            float footprint = length(unproject(centre + vec2(1.0, 0.0), g_ndc_z)
                                     - unproject(centre, g_ndc_z));
            vec2 a = plane_depths(g_plane_a, centre), b = plane_depths(g_plane_b, centre);
            bool own = abs(d - edge_d) <= OWN_REACH * footprint + step4;
            if (u_centre_depth != 0) {
                own = own && (on_plane_at_centre(g_plane_a, a, centre, d, step4) ||
                              on_plane_at_centre(g_plane_b, b, centre, d, step4));
            } else {
                own = own && ((d >= a.x - step4 && d <= a.y + step4) ||
                              (d >= b.x - step4 && d <= b.y + step4));
            }
            if (!own && d + step4 < edge_d) discard;
        }
    }
    frag_color = vec4(u_edge_color, 1.0);
}
