// Matrices shared by the vertex programs (column vectors: p_clip = u_proj u_view u_model p).
uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_proj;
uniform mat3 u_normal_view;   // inverse transpose of (u_view u_model), upper 3x3
uniform mat3 u_normal_world;  // inverse transpose of u_model, upper 3x3
// (WORLD_NORMALS is defined for programs that output or show world-space normals: the
// others neither compute nor interpolate them)
