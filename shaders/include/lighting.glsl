// The lighting model of the course notes, in one place for every program:
//   I = Ia ka + sum over lights ( Ip kd max(L.N, 0) + Ip ks max(R.V, 0)^n ),  R = 2 (L.N) N - L
// with no specular term from a light behind the surface (L.N <= 0). Ambient and diffuse
// multiply the material colour; specular multiplies the light's colour. All vectors are
// unit length and in view space.

#define MAX_LIGHTS 8

uniform vec3 u_ambient;                      // Ia (colour times intensity)
uniform vec3 u_material_color;
uniform float u_ka;
uniform float u_kd;
uniform float u_ks;
uniform float u_shininess;                   // n
uniform int u_light_count;
uniform vec4 u_light_pos_view[MAX_LIGHTS];   // w = 1: point light; w = 0: direction TO light
uniform vec3 u_light_color[MAX_LIGHTS];      // Ip (colour times intensity)
uniform vec3 u_light_attenuation[MAX_LIGHTS];  // (constant, linear, quadratic)
uniform bool u_orthographic;

// Unit vector from the point towards the eye: along +z everywhere for an orthographic camera.
vec3 view_dir(vec3 p_view) {
    return u_orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-p_view);
}

vec3 light_intensity(vec3 p_view, vec3 n_view, vec3 v_view) {
    vec3 color = u_ambient * u_ka * u_material_color;
    for (int i = 0; i < u_light_count; ++i) {
        vec4 lp = u_light_pos_view[i];
        vec3 to_light = lp.xyz - p_view * lp.w;
        float dist = length(to_light);
        vec3 l = to_light / max(dist, 1e-30);
        vec3 att = u_light_attenuation[i];
        float k = 1.0 / max(att.x + att.y * dist * lp.w + att.z * dist * dist * lp.w, 1e-30);
        float ln = dot(l, n_view);
        if (ln <= 0.0) {
            continue;  // light behind the surface: no diffuse, no specular
        }
        vec3 r = 2.0 * ln * n_view - l;
        float rv = max(dot(r, v_view), 0.0);
        float spec = rv > 0.0 ? pow(rv, u_shininess) : 0.0;
        color += k * u_light_color[i] * (u_kd * ln * u_material_color + u_ks * spec);
    }
    return color;
}
