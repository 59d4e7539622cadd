// Wide lines built as geometry (GL core profiles promise no line width above 1): a
// segment's quad on screen, for the polylines (lines.geom) and the edge overlay
// (edges.geom) alike. Clip coordinates in, window pixels for the shape, NDC out.
#ifndef WIDE_LINES_GLSL
#define WIDE_LINES_GLSL

// Clip the segment a-b (clip coordinates) to the near plane (z >= -w, GL's clip volume):
// false when it lies wholly before it. Clipping in clip space is linear, so the cut point
// is the segment's own point there.
bool clip_near(inout vec4 a, inout vec4 b) {
    float da = a.z + a.w, db = b.z + b.w;
    if (da < 0.0 && db < 0.0) return false;
    if (da < 0.0) a = mix(a, b, da / (da - db));
    if (db < 0.0) b = mix(b, a, db / (db - da));
    return true;
}

vec2 to_window(vec4 clip, vec2 origin, vec2 size) {
    return (clip.xy / clip.w * 0.5 + 0.5) * size + origin;
}

vec2 to_ndc(vec2 window, vec2 origin, vec2 size) {
    return (window - origin) / size * 2.0 - 1.0;
}

// The four corners (window pixels) of the quad about segment a-b: ``half_width`` either
// side of it, reaching ``reach_a`` beyond a and ``reach_b`` beyond b along it -- in strip
// order (a's two, then b's). A segment of no length on screen gets a square about a.
void segment_quad(vec2 a, vec2 b, float half_width, float reach_a, float reach_b,
                  out vec2 corners[4]) {
    vec2 along = b - a;
    float len = length(along);
    vec2 u = len > 0.0 ? along / len : vec2(1.0, 0.0);
    vec2 n = vec2(-u.y, u.x) * half_width;
    corners[0] = a - u * reach_a + n;
    corners[1] = a - u * reach_a - n;
    corners[2] = b + u * reach_b + n;
    corners[3] = b + u * reach_b - n;
}
#endif
