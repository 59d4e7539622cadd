// CSG by Roth's ray casting, for fragment programs: each leaf gives its boundary events
// along the ray in its own frame (enter/leave, outward normal, leaf id); the boolean
// nodes merge two sorted event lists and keep the events where the result changes. The
// tree itself is generated code (glshade/render/csg.py): one array of events per node,
// sized from the leaves below it, so no event is ever dropped. The same rules as the
// numpy reference (glshade/geometry/solids.py).

struct Ev { float t; int kind; vec3 n; int leaf; };
const float INF = 1e30;

uniform mat4 u_leaf_inverse[LEAVES];   // world -> the leaf's frame
uniform mat3 u_leaf_normal[LEAVES];    // the leaf's normals -> world (inverse transpose),
                                       // negated for a leaf a difference subtracts
uniform vec4 u_leaf_param[LEAVES];     // sizes, per kind (see csg.py)

Ev pad_event() { return Ev(INF, 0, vec3(0.0), -1); }

Ev event(float t, int kind, vec3 n_local, int i) {
    return Ev(t, kind, u_leaf_normal[i] * n_local, i);
}

// a stable quadratic: the real roots of a t^2 + b t + c, or false
bool quadratic(float a, float b, float c, out float t0, out float t1) {
    float disc = b * b - 4.0 * a * c;
    if (disc <= 0.0 || a == 0.0) return false;
    float s = sqrt(disc);
    float q = -0.5 * (b + (b < 0.0 ? -s : s));
    float r0 = q / a, r1 = c / q;
    t0 = min(r0, r1);
    t1 = max(r0, r1);
    return true;
}

void leaf_sphere(int i, vec3 o, vec3 d, out Ev e[2]) {
    e[0] = pad_event(); e[1] = pad_event();
    float r = u_leaf_param[i].x, t0, t1;
    if (quadratic(dot(d, d), 2.0 * dot(o, d), dot(o, o) - r * r, t0, t1)) {
        e[0] = event(t0, 1, o + t0 * d, i);
        e[1] = event(t1, -1, o + t1 * d, i);
    }
}

void leaf_box(int i, vec3 o, vec3 d, out Ev e[2]) {
    e[0] = pad_event(); e[1] = pad_event();
    vec3 h = u_leaf_param[i].xyz;
    vec3 dd = mix(d, vec3(1e-30), equal(d, vec3(0.0)));
    vec3 a = (-h - o) / dd, b = (h - o) / dd;
    vec3 lo = min(a, b), hi = max(a, b);
    float t0 = max(max(lo.x, lo.y), lo.z), t1 = min(min(hi.x, hi.y), hi.z);
    if (t0 < t1) {
        vec3 n0 = t0 == lo.x ? vec3(-sign(dd.x), 0.0, 0.0) :
                  t0 == lo.y ? vec3(0.0, -sign(dd.y), 0.0) : vec3(0.0, 0.0, -sign(dd.z));
        vec3 n1 = t1 == hi.x ? vec3(sign(dd.x), 0.0, 0.0) :
                  t1 == hi.y ? vec3(0.0, sign(dd.y), 0.0) : vec3(0.0, 0.0, sign(dd.z));
        e[0] = event(t0, 1, n0, i);
        e[1] = event(t1, -1, n1, i);
    }
}

// cylinder (param: radius, half height) and cone (param: radius, apex height, r / height)
bool inside_round(int kind, int i, vec3 p) {
    vec4 q = u_leaf_param[i];
    float rho2 = dot(p.xz, p.xz);
    if (kind == 0) return rho2 <= q.x * q.x && abs(p.y) <= q.y;
    float k = q.z * (q.y - p.y);
    return rho2 <= k * k && p.y <= q.y && p.y >= -q.y;
}

vec3 gradient_round(int kind, int i, vec3 p) {
    vec4 q = u_leaf_param[i];
    float rho = length(p.xz);
    if (kind == 0) {
        return abs(rho - q.x) <= abs(abs(p.y) - q.y) ? vec3(p.x, 0.0, p.z)
                                                       : vec3(0.0, sign(p.y), 0.0);
    }
    float side = abs(rho - q.z * (q.y - p.y)), base = abs(p.y + q.y);
    vec3 radial = vec3(p.x, 0.0, p.z) / max(rho, 1e-30);
    return side <= base ? radial + vec3(0.0, q.z, 0.0) : vec3(0.0, -1.0, 0.0);
}

// a convex leaf: candidate parameters sorted, the inside run of segments between them
void convex4(int kind, int i, vec3 o, vec3 d, float c[4], out Ev e[2]) {
    e[0] = pad_event(); e[1] = pad_event();
    for (int a = 0; a < 4; ++a)          // sort the four candidates
        for (int b = 0; b < 3; ++b)
            if (c[b] > c[b + 1]) { float s = c[b]; c[b] = c[b + 1]; c[b + 1] = s; }
    float lo = INF, hi = -INF;
    float edges[6] = float[6](-INF, c[0], c[1], c[2], c[3], INF);
    for (int s = 0; s < 5; ++s) {
        float a = edges[s], b = edges[s + 1];
        if (a >= INF * 0.5 || b <= -INF * 0.5 || a == b) continue;
        float m = a <= -INF * 0.5 ? b - 1.0 : (b >= INF * 0.5 ? a + 1.0 : 0.5 * (a + b));
        if (inside_round(kind, i, o + m * d)) { lo = min(lo, a); hi = max(hi, b); }
    }
    if (lo < hi) {
        e[0] = event(lo, 1, gradient_round(kind, i, o + lo * d), i);
        e[1] = event(hi, -1, gradient_round(kind, i, o + hi * d), i);
    }
}

void leaf_cylinder(int i, vec3 o, vec3 d, out Ev e[2]) {
    vec4 q = u_leaf_param[i];
    float c[4] = float[4](INF, INF, INF, INF), t0, t1;
    if (quadratic(dot(d.xz, d.xz), 2.0 * dot(o.xz, d.xz), dot(o.xz, o.xz) - q.x * q.x, t0,
                  t1)) { c[0] = t0; c[1] = t1; }
    if (d.y != 0.0) { c[2] = (-q.y - o.y) / d.y; c[3] = (q.y - o.y) / d.y; }
    convex4(0, i, o, d, c, e);
}

void leaf_cone(int i, vec3 o, vec3 d, out Ev e[2]) {
    vec4 q = u_leaf_param[i];
    float k2 = q.z * q.z, u = q.y - o.y, t0, t1;
    float c[4] = float[4](INF, INF, INF, INF);
    if (quadratic(dot(d.xz, d.xz) - k2 * d.y * d.y, 2.0 * (dot(o.xz, d.xz) + k2 * u * d.y),
                  dot(o.xz, o.xz) - k2 * u * u, t0, t1)) { c[0] = t0; c[1] = t1; }
    if (d.y != 0.0) { c[2] = (-q.y - o.y) / d.y; c[3] = (q.y - o.y) / d.y; }
    convex4(1, i, o, d, c, e);
}

// torus (param: R, r): the quartic's sign changes bracketed by steps through the bounding
// sphere, refined by bisection
float torus_f(vec4 q, vec3 p) {
    float k = dot(p, p) + q.x * q.x - q.y * q.y;
    return k * k - 4.0 * q.x * q.x * dot(p.xz, p.xz);
}

void leaf_torus(int i, vec3 o, vec3 d, out Ev e[4]) {
    for (int k = 0; k < 4; ++k) e[k] = pad_event();
    vec4 q = u_leaf_param[i];
    float b0, b1, big = q.x + q.y;
    if (!quadratic(dot(d, d), 2.0 * dot(o, d), dot(o, o) - big * big, b0, b1)) return;
    const int STEPS = 96;
    float step = (b1 - b0) / float(STEPS), t = b0, f = torus_f(q, o + t * d);
    int n = 0;
    for (int s = 1; s <= STEPS && n < 4; ++s) {
        float t2 = b0 + float(s) * step, f2 = torus_f(q, o + t2 * d);
        if ((f < 0.0) != (f2 < 0.0)) {
            float a = t, b = t2;
            for (int it = 0; it < 30; ++it) {
                float m = 0.5 * (a + b);
                if ((torus_f(q, o + m * d) < 0.0) == (f < 0.0)) a = m; else b = m;
            }
            float r = 0.5 * (a + b);
            vec3 p = o + r * d;
            vec3 g = p - vec3(p.x, 0.0, p.z) * (q.x / max(length(p.xz), 1e-30));
            e[n] = event(r, f2 < 0.0 ? 1 : -1, g, i);
            n++;
        }
        t = t2; f = f2;
    }
}

void leaf_halfspace(int i, vec3 o, vec3 d, out Ev e[2]) {
    e[0] = pad_event(); e[1] = pad_event();
    vec4 q = u_leaf_param[i];   // normal, offset: inside where n . p <= offset
    float nd = dot(q.xyz, d), no = dot(q.xyz, o);
    if (nd == 0.0) {
        if (no <= q.w) { e[0] = event(-INF, 1, q.xyz, i); e[1] = event(INF * 0.99, -1, q.xyz, i); }
        return;
    }
    float t = (q.w - no) / nd;
    if (nd < 0.0) { e[0] = event(t, 1, q.xyz, i); e[1] = event(INF * 0.99, -1, q.xyz, i); }
    else { e[0] = event(-INF, 1, q.xyz, i); e[1] = event(t, -1, q.xyz, i); }
}
