// Matrices shared by the vertex programs (column vectors: p_clip = u_proj u_model_view p).
uniform mat4 u_model_view;    // view times model, made once per model on the CPU
uniform mat4 u_proj;
uniform mat3 u_normal_view;   // inverse transpose of u_model_view, upper 3x3
uniform mat3 u_normal_world;  // inverse transpose of the model matrix, upper 3x3
// (WORLD_NORMALS is defined for programs that output or show world-space normals: the
// others neither compute nor interpolate them)
