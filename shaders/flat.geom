#version 330 core
// A big mesh's flat draw (FLAT_FETCH): its vertices are shared, so each triangle finds its
// polygon here, once (polygon_fetch.glsl: by its number in the draw), with the polygon's
// normal and centroid, and lights it as flat.vert lights a corner copy (flat_polygon.glsl):
// the same intensity, at a third of the vertices' memory. Outputs are undefined after each
// EmitVertex, so each corner sets them again.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
#include "transforms.glsl"
#include "lighting.glsl"
#include "polygon_fetch.glsl"
#include "flat_polygon.glsl"

in vec3 g_position_view[];
out vec3 v_position_view;
#ifdef TEXTURED
in vec2 g_uv[];
out vec2 v_uv;
#endif
#if defined(GLSHADE_AUX_OUTPUTS) || defined(SHADOW_RAYS_FORWARD)
flat out int v_polygon;
#endif

void main() {
    int polygon = polygon_of(gl_PrimitiveIDIn);
    vec3 normal = polygon_normal(polygon), middle = polygon_centroid(polygon);
    for (int i = 0; i < 3; ++i) {
        flat_polygon(normal, middle);
        v_position_view = g_position_view[i];
#ifdef TEXTURED
        v_uv = g_uv[i];
#endif
#if defined(GLSHADE_AUX_OUTPUTS) || defined(SHADOW_RAYS_FORWARD)
        v_polygon = polygon;
#endif
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
