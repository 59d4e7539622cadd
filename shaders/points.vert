#version 330 core
// A point cloud's points (render/passes/points.py): each point's centre and radius in view
// space, handed to the geometry stage, which draws the quad that holds it on screen.
in vec3 in_position;
#ifdef POINT_RADII
in float in_radius;                 // model units
#endif
#ifdef POINT_COLORS
in vec3 in_color;
out vec3 g_color;
#endif
#ifdef POINT_NORMALS
in vec3 in_normal;
out vec3 g_normal;                  // view space, unit
uniform mat3 u_normal_view;         // model -> view (the placement's rotation)
#endif
uniform mat4 u_model_view;
uniform float u_radius;             // model units (every point's, without radii)
uniform float u_scale;              // the placement's scale: model units -> view units
out vec3 g_centre;
out float g_radius;
flat out int g_index;               // the point's number in its cloud

void main() {
    g_centre = (u_model_view * vec4(in_position, 1.0)).xyz;
#ifdef POINT_RADII
    g_radius = in_radius * u_scale;
#else
    g_radius = u_radius * u_scale;
#endif
#ifdef POINT_COLORS
    g_color = in_color;
#endif
#ifdef POINT_NORMALS
    g_normal = normalize(u_normal_view * in_normal);
#endif
    g_index = gl_VertexID;
}
