// Two-sided surfaces, for fragment programs: the back of a surface faces the viewer, so
// its normals are turned around (gl_FrontFacing is the triangle's winding as drawn).

void face_viewer(inout vec3 n_view, inout vec3 n_world) {
    if (!gl_FrontFacing) {
        n_view = -n_view;
        n_world = -n_world;
    }
}
