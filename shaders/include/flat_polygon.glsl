// A polygon's flat shading, for flat.vert (each corner copy carries its polygon's normal and
// centroid) and flat.geom (a big mesh's triangle fetches them): the one intensity of the
// polygon, lit at its centroid with its unit Newell normal (the notes: N, L, R, V constant
// over the polygon), and the flat outputs that carry it (two-sided programs, TWO_SIDED,
// also light the back). The includer has transforms.glsl and lighting.glsl.
#ifndef FLAT_POLYGON_GLSL
#define FLAT_POLYGON_GLSL
#ifdef NOTES_TEXTURED
#ifdef SHADOW_MASK
flat out vec3 v_spec_terms_front[LIGHT_COUNT];  // (v_terms_*: ambient and diffuse)
#ifdef TWO_SIDED
flat out vec3 v_spec_terms_back[LIGHT_COUNT];
#endif
#else
flat out vec3 v_spec_front;
#ifdef TWO_SIDED
flat out vec3 v_spec_back;
#endif
#endif
#endif

flat out vec3 v_color_front;
#ifdef TWO_SIDED
flat out vec3 v_color_back;
#endif
#ifdef WORLD_NORMALS
flat out vec3 v_face_normal_world;
#endif
#ifdef SHADOW_MASK
flat out vec3 v_terms_front[LIGHT_COUNT];  // each light's term apart (v_color_*: ambient)
#ifdef TWO_SIDED
flat out vec3 v_terms_back[LIGHT_COUNT];
#endif
#endif


void flat_polygon(vec3 face_normal, vec3 face_centroid) {
    vec3 n = normalize(u_normal_view * face_normal);
    vec3 c = (u_model_view * vec4(face_centroid, 1.0)).xyz;
    vec3 v = view_dir(c);
#if defined(NOTES_TEXTURED) && defined(SHADOW_MASK)
    vec3 terms[LIGHT_COUNT], spec_terms[LIGHT_COUNT];
    v_color_front = light_terms_parts(c, n, v, terms, spec_terms);
    v_terms_front = terms;
    v_spec_terms_front = spec_terms;
#ifdef TWO_SIDED
    v_color_back = light_terms_parts(c, -n, v, terms, spec_terms);
    v_terms_back = terms;
    v_spec_terms_back = spec_terms;
#endif
#elif defined(NOTES_TEXTURED)
    v_color_front = light_parts(c, n, v, v_spec_front);
#ifdef TWO_SIDED
    v_color_back = light_parts(c, -n, v, v_spec_back);
#endif
#elif defined(SHADOW_MASK)
    vec3 terms[LIGHT_COUNT];
    v_color_front = light_terms(c, n, v, terms);
    v_terms_front = terms;
#ifdef TWO_SIDED
    v_color_back = light_terms(c, -n, v, terms);
    v_terms_back = terms;
#endif
#else
    v_color_front = light_intensity(c, n, v);
#ifdef TWO_SIDED
    v_color_back = light_intensity(c, -n, v);
#endif
#endif
#ifdef WORLD_NORMALS
    v_face_normal_world = u_normal_world * face_normal;
#endif
}
#endif
