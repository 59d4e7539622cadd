// A big mesh's polygon ids without copying its vertices to every triangle corner
// (render/gpu_mesh.py, render/passes/mesh.py): each triangle's polygon in an integer
// table, found by the triangle's number in the draw (gl_PrimitiveID, or gl_PrimitiveIDIn
// in a geometry stage) plus the draw's first triangle (a chunk's). POLYGON_FETCH: the
// fragment stage looks it up (the smooth modes); FLAT_FETCH: flat.geom does, once a
// triangle, with the polygon's normal and centroid from a second table.
#ifndef POLYGON_FETCH_GLSL
#define POLYGON_FETCH_GLSL
#if defined(POLYGON_FETCH) || defined(FLAT_FETCH)
#ifndef POLYGON_ROW_WIDTH  // (texels a row of the tables: render/gpu_mesh.py's)
#error "POLYGON_ROW_WIDTH comes from render/gpu_mesh.py"
#endif
uniform isampler2D u_polygons;               // triangle -> polygon
uniform int u_triangle_base;                 // the draw's first triangle

ivec2 table_texel(int i) { return ivec2(i % POLYGON_ROW_WIDTH, i / POLYGON_ROW_WIDTH); }

int polygon_of(int triangle) {
    return texelFetch(u_polygons, table_texel(triangle + u_triangle_base), 0).r;
}
#endif
#ifdef FLAT_FETCH
uniform sampler2D u_polygon_planes;          // per polygon: (Newell normal, 0), (centroid, 1)
vec3 polygon_normal(int polygon) { return texelFetch(u_polygon_planes, table_texel(2 * polygon), 0).xyz; }
vec3 polygon_centroid(int polygon) {
    return texelFetch(u_polygon_planes, table_texel(2 * polygon + 1), 0).xyz;
}
#endif
#endif
