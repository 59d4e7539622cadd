// Instances of one mesh drawn by one instanced call (render/passes/mesh.py, Scene.add's
// ``instances``): each instance's row of u_instances holds what a model's uniforms hold
// for a separate draw -- the same float32 values, so the picture is the same to the byte:
// texels 0-3 the model-view matrix's columns, 4-6 the view normal matrix's, 7-9 the world
// normal matrix's, 10 (first polygon id as bits, Ia ka C), then Ip kd C per light. The
// vertex stage reads its instance from gl_InstanceID and hands it to the fragment stage.
#ifndef INSTANCES_GLSL
#define INSTANCES_GLSL
#ifdef INSTANCED
#define INSTANCE_ROW_WIDTH 4096        // texels a row of the texture (render/passes/mesh.py)
uniform sampler2D u_instances;
uniform int u_instance_stride;         // texels an instance
#ifdef GLSHADE_VERTEX_STAGE
flat out int v_instance;
#define INSTANCE gl_InstanceID
#else
flat in int v_instance;
#define INSTANCE v_instance
#endif

vec4 instance_texel(int j) {
    int n = INSTANCE * u_instance_stride + j;
    return texelFetch(u_instances, ivec2(n % INSTANCE_ROW_WIDTH, n / INSTANCE_ROW_WIDTH), 0);
}
mat4 instance_model_view() {
    return mat4(instance_texel(0), instance_texel(1), instance_texel(2), instance_texel(3));
}
mat3 instance_normal_view() {
    return mat3(instance_texel(4).xyz, instance_texel(5).xyz, instance_texel(6).xyz);
}
mat3 instance_normal_world() {
    return mat3(instance_texel(7).xyz, instance_texel(8).xyz, instance_texel(9).xyz);
}
int instance_face_base() { return floatBitsToInt(instance_texel(10).x); }
vec3 instance_ambient() { return instance_texel(10).yzw; }
vec3 instance_diffuse(int i) { return instance_texel(11 + i).xyz; }
#endif
#endif
