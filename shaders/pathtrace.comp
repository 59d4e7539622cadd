#version 430 core
// The path tracer as a compute kernel (render/passes/pathtrace.py, kernel="compute"): one
// invocation a pixel of the targets, 8x8 a group, running the fragment program's own pass
// (trace_integrator.glsl: the same sample stream, BVH walk and integrator) and storing the
// seven targets in images. On a GPU whose graphics units are few (a datacentre part runs
// fragment shaders on a sliver of the chip) this is the tracer that uses the whole device.
layout(local_size_x = 8, local_size_y = 8) in;
#include "trace_integrator.glsl"

uniform ivec2 u_target_size;  // the targets' size in pixels
// the seven targets written, in trace_pixel's order (their image units: the Python's
// Binding.TRACE_IMAGES on, set as these uniforms' values)
layout(rgba32f) writeonly uniform image2D out_state0;
layout(rgba32f) writeonly uniform image2D out_state1;
layout(rgba32f) writeonly uniform image2D out_state2;
layout(rgba32f) writeonly uniform image2D out_state3;
layout(rgba32f) writeonly uniform image2D out_sum;
layout(rgba32f) writeonly uniform image2D out_square;
layout(rgba32f) writeonly uniform image2D out_hit;

void main() {
    ivec2 at = ivec2(gl_GlobalInvocationID.xy);
    if (at.x >= u_target_size.x || at.y >= u_target_size.y) return;
    vec4 o[7];
    trace_pixel(at, o);
    imageStore(out_state0, at, o[0]);
    imageStore(out_state1, at, o[1]);
    imageStore(out_state2, at, o[2]);
    imageStore(out_state3, at, o[3]);
    imageStore(out_sum, at, o[4]);
    imageStore(out_square, at, o[5]);
    imageStore(out_hit, at, o[6]);
}
