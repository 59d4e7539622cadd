// The leaves (solids/leaves.py): membership, gradient and boundaries along a ray, each
// kind's code compiled in only where the tree has that kind (IS, CSG_KINDS).

bool cone_contains(vec4 q, vec3 p) {
    float k = q.z * (q.y - p.y);
    return dot(p.xz, p.xz) <= k * k && p.y <= q.y && p.y >= -q.y;
}

// kinds: LEAF_SPHERE .. LEAF_HALFSPACE (solids/encoding.py LeafKind, injected)
bool leaf_contains(int kind, vec4 q, vec3 p) {
    if (IS(kind, LEAF_SPHERE)) return dot(p, p) <= q.x * q.x;
    if (IS(kind, LEAF_BOX)) return all(lessThanEqual(abs(p), q.xyz));
    if (IS(kind, LEAF_CYLINDER)) return dot(p.xz, p.xz) <= q.x * q.x && abs(p.y) <= q.y;
    if (IS(kind, LEAF_CONE)) return cone_contains(q, p);
    if (IS(kind, LEAF_TORUS)) {
        float w = length(p.xz) - q.x;
        return w * w + p.y * p.y <= q.y * q.y;
    }
    return dot(q.xyz, p) <= q.w;
}

vec3 leaf_gradient(int kind, vec4 q, vec3 p) {
    if (IS(kind, LEAF_SPHERE)) return p;
    if (IS(kind, LEAF_BOX)) {
        vec3 r = abs(p / q.xyz);
        return r.x >= r.y && r.x >= r.z ? vec3(sign(p.x), 0.0, 0.0) :
               r.y >= r.z ? vec3(0.0, sign(p.y), 0.0) : vec3(0.0, 0.0, sign(p.z));
    }
    float rho = length(p.xz);
    if (IS(kind, LEAF_CYLINDER)) {
        return abs(rho - q.x) <= abs(abs(p.y) - q.y) ? vec3(p.x, 0.0, p.z)
                                                       : vec3(0.0, sign(p.y), 0.0);
    }
    if (IS(kind, LEAF_CONE)) {
        float side = abs(rho - q.z * (q.y - p.y)), base = abs(p.y + q.y);
        vec3 radial = vec3(p.x, 0.0, p.z) / max(rho, 1e-30);
        return side <= base ? radial + vec3(0.0, q.z, 0.0) : vec3(0.0, -1.0, 0.0);
    }
    if (IS(kind, LEAF_TORUS)) return p - vec3(p.x, 0.0, p.z) * (q.x / max(rho, 1e-30));
    return q.xyz;
}

// a stable quadratic: the real roots of a t^2 + b t + c (t0 < t1), or false
bool quadratic(float a, float b, float c, out float t0, out float t1) {
    float disc = b * b - 4.0 * a * c;
    if (disc <= 0.0 || a == 0.0) return false;
    float s = sqrt(disc);
    float q = -0.5 * (b + (b < 0.0 ? -s : s));
    float r0 = q / a, r1 = q != 0.0 ? c / q : r0;
    t0 = min(r0, r1);
    t1 = max(r0, r1);
    return t0 < t1;
}

// The next four boundaries (t, leaf) after (t_cur, leaf_cur), in order, ties by leaf:
// ``bt`` their distances, ``bk`` their leaves (as floats; -1 an empty slot, INF its t). One
// pass over the leaves finds several events, so a ray crossing a few boundaries before
// its surface intersects each leaf once, not once an event.
void offer(float t, float k, float t_cur, float leaf_cur, inout vec4 bt, inout vec4 bk) {
    if (!(t > t_cur || (t == t_cur && k > leaf_cur))) return;
    // the slots the event goes before (a run to the end: the list is sorted)
    bvec4 less = bvec4(t < bt.x || (t == bt.x && k < bk.x), t < bt.y || (t == bt.y && k < bk.y),
                       t < bt.z || (t == bt.z && k < bk.z), t < bt.w || (t == bt.w && k < bk.w));
    bvec4 after_new = bvec4(false, less.xyz);  // slots that take their neighbour's event
    bt = mix(bt, mix(vec4(t), vec4(0.0, bt.xyz), after_new), less);
    bk = mix(bk, mix(vec4(k), vec4(0.0, bk.xyz), after_new), less);
}

// the sign of the torus's implicit function without cancellation: (rho - R)^2 + y^2 - r^2
float torus_g(vec4 q, vec3 o, vec3 d, float s) {
    vec3 p = o + s * d;
    float w = length(p.xz) - q.x;
    return w * w + p.y * p.y - q.y * q.y;
}

float torus_root(vec4 q, vec3 o, vec3 d, float a, float b, float ga) {
    for (int it = 0; it < 40; ++it) {
        float m = 0.5 * (a + b);
        if (m <= a || m >= b) break;
        if ((torus_g(q, o, d, m) < 0.0) == (ga < 0.0)) a = m; else b = m;
    }
    return 0.5 * (a + b);
}

// cut points of the depressed cubic s^3 + p s + r (up to 4, sorted; the rest INF): its
// real root where one is real (Cardano), and, where p < 0, the three of the trigonometric
// form with the cosine clamped -- the roots where three are real, and where float32 says
// one (two about to merge) the place of the pair. A cut too many only splits a monotone
// piece; a cut too few would leave two roots in one piece, seen as none.
void cubic_cuts(float p, float r, out float s[4]) {
    s[0] = INF; s[1] = INF; s[2] = INF; s[3] = INF;
    float p3 = p / 3.0, r2 = r / 2.0;
    float disc = r2 * r2 + p3 * p3 * p3;
    if (disc > 0.0) {
        float u = -r2 - (r2 >= 0.0 ? 1.0 : -1.0) * sqrt(disc);  // (no cancellation)
        float cu = sign(u) * pow(abs(u), 1.0 / 3.0);
        s[3] = cu != 0.0 ? cu - p3 / cu : 0.0;
    }
    if (p3 < 0.0) {
        float m = 2.0 * sqrt(-p3);
        float c = clamp(-r2 / (-p3 * sqrt(-p3)), -1.0, 1.0);
        float phi = acos(c) / 3.0;
        s[0] = m * cos(phi + 2.0943951);
        s[1] = m * cos(phi - 2.0943951);
        s[2] = m * cos(phi);
    } else if (disc <= 0.0) {
        s[0] = 0.0;  // (p = r = 0: the triple root)
    }
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            if (s[b] > s[b + 1]) { float x = s[b]; s[b] = s[b + 1]; s[b + 1] = x; }
}

// the torus's boundaries along o + t d (up to four; the rest INF)
vec4 torus_bounds(vec4 q, vec3 o, vec3 d) {
    vec4 out_t = vec4(INF);
    // centre the ray at its point nearest the torus's centre, unit direction: the quartic
    // is then s^4 + A s^2 + B s + C (no cubic term), its slope 4 s^3 + 2 A s + B
    float len = length(d);
    vec3 u = d / len;
    float s0 = -dot(o, u);
    vec3 c = o + s0 * u;
    // (the bounding sphere a little larger than R + r: where the line leaves it near the
    // outer equator, float32 would put its end on the surface, or inside, and lose a root)
    float big = (q.x + q.y) * 1.001, h2 = big * big - dot(c, c);
    if (h2 <= 0.0) return out_t;                   // misses the bounding sphere
    float h = sqrt(h2);
    float R2 = q.x * q.x;
    float k0 = dot(c, c) + R2 - q.y * q.y;
    float A = 2.0 * k0 - 4.0 * R2 * dot(u.xz, u.xz);
    float B = -8.0 * R2 * dot(c.xz, u.xz);
    float crit[4];
    cubic_cuts(A / 2.0, B / 4.0, crit);
    float cuts[6] = float[6](-h, INF, INF, INF, INF, h);
    for (int j = 0; j < 4; ++j) cuts[j + 1] = crit[j] >= INF * 0.5 ? INF : clamp(crit[j], -h, h);
    float a = cuts[0], ga = torus_g(q, c, u, a);
    int n = 0;
    for (int j = 1; j < 6; ++j) {
        float b = cuts[j];
        if (b >= INF * 0.5) continue;
        float gb = torus_g(q, c, u, b);
        if (b > a && (ga < 0.0) != (gb < 0.0)) {
            float s = torus_root(q, c, u, a, b, ga);
            out_t[n++] = (s + s0) / len;
        }
        if (b > a) { a = b; ga = gb; }
    }
    return out_t;
}

// leaf k's boundaries along ro + t rd (up to four; the rest INF); `kind` its kind (a
// constant where the caller knows it, so that only that kind's code is compiled in)
vec4 leaf_bounds_od(int kind, vec4 q, vec3 o, vec3 d);
vec4 leaf_bounds_as(int kind, int k, vec3 ro, vec3 rd) {
    vec4 m0 = csg_texel(8 * k), m1 = csg_texel(8 * k + 1), m2 = csg_texel(8 * k + 2);
    vec4 ro1 = vec4(ro, 1.0);
    return leaf_bounds_od(kind, leaf_param(k), vec3(dot(m0, ro1), dot(m1, ro1), dot(m2, ro1)),
                          vec3(dot(m0.xyz, rd), dot(m1.xyz, rd), dot(m2.xyz, rd)));
}

// the same along o + t d in the leaf's own frame (``q`` its sizes)
vec4 leaf_bounds_od(int kind, vec4 q, vec3 o, vec3 d) {
    vec4 out_t = vec4(INF);
    float t0, t1;
    if (IS(kind, LEAF_SPHERE)) {
        if (quadratic(dot(d, d), 2.0 * dot(o, d), dot(o, o) - q.x * q.x, t0, t1)) {
            out_t.xy = vec2(t0, t1);
        }
    } else if (IS(kind, LEAF_BOX)) {
        vec3 dd = mix(d, vec3(1e-30), equal(d, vec3(0.0)));
        vec3 a = (-q.xyz - o) / dd, b = (q.xyz - o) / dd;
        vec3 lo = min(a, b), hi = max(a, b);
        t0 = max(max(lo.x, lo.y), lo.z); t1 = min(min(hi.x, hi.y), hi.z);
        if (t0 < t1) {
            out_t.xy = vec2(t0, t1);
        }
    } else if (IS(kind, LEAF_CYLINDER)) {
        // the infinite cylinder's run (all of the line when it runs along the axis inside)
        // cut to the slab |y| <= h
        float lo = -INF, hi = INF;
        float a = dot(d.xz, d.xz), c = dot(o.xz, o.xz) - q.x * q.x;
        if (a > 0.0) {
            if (!quadratic(a, 2.0 * dot(o.xz, d.xz), c, lo, hi)) { lo = INF; hi = -INF; }
        } else if (c > 0.0) { lo = INF; hi = -INF; }
        if (d.y != 0.0) {
            float y0 = (-q.y - o.y) / d.y, y1 = (q.y - o.y) / d.y;
            lo = max(lo, min(y0, y1));
            hi = min(hi, max(y0, y1));
        } else if (abs(o.y) > q.y) { lo = INF; hi = -INF; }
        if (lo < hi) {
            out_t.xy = vec2(lo, hi);
        }
    } else if (IS(kind, LEAF_CONE)) {
        // the double cone rho^2 <= k^2 (apex - y)^2 gives a run (a > 0: the ray shallower
        // than the cone) or a run's complement (a < 0), one part in each nappe; the slab
        // |y| <= h keeps the lower nappe's
        float lo = -INF, hi = INF;
        if (d.y != 0.0) {
            float y0 = (-q.y - o.y) / d.y, y1 = (q.y - o.y) / d.y;
            lo = min(y0, y1);
            hi = max(y0, y1);
        } else if (abs(o.y) > q.y) { lo = INF; hi = -INF; }
        float k2 = q.z * q.z, w = q.y - o.y;
        float a = dot(d.xz, d.xz) - k2 * d.y * d.y;
        float b = 2.0 * (dot(o.xz, d.xz) + k2 * w * d.y), c = dot(o.xz, o.xz) - k2 * w * w;
        if (quadratic(a, b, c, t0, t1)) {
            if (a > 0.0) {
                lo = max(lo, t0);
                hi = min(hi, t1);
            } else {                           // the longer of the two parts in the slab
                float h0 = min(hi, t0), l1 = max(lo, t1);
                if (h0 - lo >= hi - l1) hi = h0; else lo = l1;
            }
        } else if (a == 0.0 && b != 0.0) {     // parallel to a generator: a half-line
            if (b > 0.0) hi = min(hi, -c / b); else lo = max(lo, -c / b);
        } else if (c > 0.0 || a > 0.0) {
            lo = INF; hi = -INF;               // (a < 0 and no root: inside all along)
        }
        if (lo < hi) {
            out_t.xy = vec2(lo, hi);
        }
    } else if (IS(kind, LEAF_TORUS)) {
        out_t = torus_bounds(q, o, d);
    } else {
        float nd = dot(q.xyz, d);
        if (nd != 0.0) out_t.x = (q.w - dot(q.xyz, o)) / nd;
    }
    return out_t;
}

// offer each of a leaf's boundaries
void offer4(vec4 t, int k, float t_cur, float leaf_cur, inout vec4 bt, inout vec4 bk) {
    float kf = float(k);
    offer(t.x, kf, t_cur, leaf_cur, bt, bk);
    offer(t.y, kf, t_cur, leaf_cur, bt, bk);
    offer(t.z, kf, t_cur, leaf_cur, bt, bk);
    offer(t.w, kf, t_cur, leaf_cur, bt, bk);
}
