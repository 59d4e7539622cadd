// Colours on geometry (Mesh.colors, Mesh.face_colors): the notes' surface colour C where it
// varies over a mesh. A stage that lights a point sets g_surface_color to the C there
// before it lights it -- the vertex stage in Gouraud (C at the vertex) and flat shading
// (the polygon's one C, the mean of its corners), the fragment stage in Phong (C
// interpolated to the pixel) -- and the lighting constants that carry C (Ia ka C and
// Ip kd C, constants.glsl) are multiplied by it there: the formula's C is the mesh's
// colour times the material's. The colour's alpha multiplies the opacity
// (outputs.glsl: g_map_opacity). Compiled in only for meshes with colours (VERTEX_COLORS).
#ifndef SURFACE_COLOR_GLSL
#define SURFACE_COLOR_GLSL
#ifdef VERTEX_COLORS
vec3 g_surface_color = vec3(1.0);
#define SURFACE_C g_surface_color
#endif
#endif
