#!/usr/bin/env bash
# Run a command on the GL a Mac has, simulated with Mesa: every context it makes is 4.1 core
# and exposes none of the ARB extensions that entered the core after 4.1 (no compute
# shaders, storage buffers, image load/store, atomic counters, 420pack, explicit uniform
# locations -- no layout(binding=) in a 4.1 program --, base instance, texture views ...).
# Mesa cannot hide a few (texture storage, direct state access, KHR_debug, program
# interface queries): a Mac lacks them too, so glshade calls none. The suite runs its GL
# tests once this way (make test).
set -euo pipefail
export MESA_GL_VERSION_OVERRIDE=4.1
export MESA_GLSL_VERSION_OVERRIDE=410
export MESA_EXTENSION_OVERRIDE="-GL_ARB_base_instance -GL_ARB_buffer_storage -GL_ARB_clear_texture -GL_ARB_clip_control -GL_ARB_compute_shader -GL_ARB_conservative_depth -GL_ARB_copy_image -GL_ARB_cull_distance -GL_ARB_derivative_control -GL_ARB_enhanced_layouts -GL_ARB_explicit_uniform_location -GL_ARB_framebuffer_no_attachments -GL_ARB_gl_spirv -GL_ARB_spirv_extensions -GL_ARB_shader_image_load_store -GL_ARB_shader_image_size -GL_ARB_shader_storage_buffer_object -GL_ARB_shader_atomic_counters -GL_ARB_shader_atomic_counter_ops -GL_ARB_shading_language_420pack -GL_ARB_shading_language_packing -GL_ARB_texture_storage_multisample -GL_ARB_texture_view -GL_ARB_multi_draw_indirect -GL_ARB_internalformat_query -GL_ARB_internalformat_query2 -GL_ARB_stencil_texturing -GL_ARB_texture_query_levels -GL_ARB_texture_buffer_range -GL_ARB_arrays_of_arrays -GL_ARB_ES3_compatibility -GL_ARB_ES3_1_compatibility -GL_ARB_ES3_2_compatibility -GL_ARB_query_buffer_object -GL_ARB_texture_barrier -GL_ARB_shader_draw_parameters -GL_ARB_indirect_parameters -GL_ARB_polygon_offset_clamp -GL_ARB_transform_feedback_instanced -GL_ARB_robust_buffer_access_behavior -GL_ARB_texture_mirror_clamp_to_edge -GL_ARB_shader_group_vote -GL_ARB_shader_ballot -GL_ARB_gpu_shader_int64 -GL_ARB_pipeline_statistics_query -GL_ARB_transform_feedback_overflow_query -GL_ARB_post_depth_coverage -GL_ARB_texture_filter_minmax -GL_ARB_shader_viewport_layer_array -GL_ARB_shader_clock -GL_ARB_conditional_render_inverted -GL_ARB_shader_texture_image_samples"
exec "$@"
