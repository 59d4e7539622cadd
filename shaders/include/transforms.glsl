// Matrices shared by the vertex programs (column vectors: p_clip = u_proj u_model_view p).
uniform mat4 u_proj;
#ifdef INSTANCED  // (each instance's own, from its row: instances.glsl)
#include "instances.glsl"
#define u_model_view instance_model_view()
#define u_normal_view instance_normal_view()
#define u_normal_world instance_normal_world()
#else
uniform mat4 u_model_view;    // view times model, made once per model on the CPU
uniform mat3 u_normal_view;   // inverse transpose of u_model_view, upper 3x3
uniform mat3 u_normal_world;  // inverse transpose of the model matrix, upper 3x3
#endif
// (WORLD_NORMALS is defined for programs that output or show world-space normals: the
// others neither compute nor interpolate them)
