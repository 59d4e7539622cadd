// CSG by ray casting with the tree as data (glshade/render/csg.py writes it): one program
// for every tree. A float texture holds, for each leaf, its world -> leaf matrix, its normal
// matrix (negated under a difference's right side), sizes and kind; a bounding-volume
// hierarchy over the leaves' world boxes (pre-order, each node with the index past its
// subtree); and the tree as a post-order program for a stack of bits.
//
// Along the pixel's ray the state of every leaf (inside or not) is kept in a bit set. The
// walk: find the next leaf boundary after the current one (the hierarchy skips leaves whose
// box the ray misses or meets only beyond the best so far); flip that leaf's bit; run the
// tree program on the bits (skipping subtrees the ray is in none of the leaves of); the first boundary where the tree's answer changes is the
// surface. Ties (coincident faces) go by leaf order: the left operand's face shows.
// Leaf boundaries are exact: closed-form roots, the torus's quartic split at the roots of its
// derivative (a cubic, in closed form) into monotone pieces, each root bracketed and refined
// by bisection on a sign computed without cancellation.

const float INF = 1e30;
#ifndef CSG_WORDS
#define CSG_WORDS 32                   // words of leaf bits: 32 leaves each (csg.py picks)
#endif
const int MAX_LEAVES = 32 * CSG_WORDS;

#ifdef CSG_BLOCK
// a small tree: the data in a uniform block (a plain load per read, where a texture read
// costs a sampler's work)
layout(std140) uniform CsgData { vec4 csg_data[CSG_BLOCK]; };
vec4 csg_texel(int i) { return csg_data[i]; }
#else
uniform sampler2D u_csg;               // RGBA32F, 64 texels a row
vec4 csg_texel(int i) { return texelFetch(u_csg, ivec2(i & 63, i >> 6), 0); }
#endif
uniform int u_csg_nodes;               // hierarchy nodes
uniform int u_csg_ops;                 // tree program codes
uniform int u_csg_bvh;                 // first texel of the hierarchy
uniform int u_csg_program;             // first texel of the program (code, first record)
uniform int u_csg_records;             // first texel of the skip records
                                       // (end position, first leaf, last leaf, next)

// leaf k: texels 8k .. 8k+7: inverse rows 0-2, normal matrix rows 3-5 (kind in 3.w),
// params 6
vec3 to_leaf(int k, vec4 p) {
    return vec3(dot(csg_texel(8 * k), p), dot(csg_texel(8 * k + 1), p),
                dot(csg_texel(8 * k + 2), p));
}
vec3 normal_to_world(int k, vec3 n) {
    return vec3(dot(csg_texel(8 * k + 3).xyz, n), dot(csg_texel(8 * k + 4).xyz, n),
                dot(csg_texel(8 * k + 5).xyz, n));
}
vec4 leaf_param(int k) { return csg_texel(8 * k + 6); }
int leaf_kind(int k) { return int(csg_texel(8 * k + 3).w); }

// kinds: 0 sphere, 1 box, 2 cylinder, 3 cone, 4 torus, 5 half-space
bool leaf_contains(int kind, vec4 q, vec3 p) {
    if (kind == 0) return dot(p, p) <= q.x * q.x;
    if (kind == 1) return all(lessThanEqual(abs(p), q.xyz));
    if (kind == 2) return dot(p.xz, p.xz) <= q.x * q.x && abs(p.y) <= q.y;
    if (kind == 3) {
        float k = q.z * (q.y - p.y);
        return dot(p.xz, p.xz) <= k * k && p.y <= q.y && p.y >= -q.y;
    }
    if (kind == 4) {
        float w = length(p.xz) - q.x;
        return w * w + p.y * p.y <= q.y * q.y;
    }
    return dot(q.xyz, p) <= q.w;
}

vec3 leaf_gradient(int kind, vec4 q, vec3 p) {
    if (kind == 0) return p;
    if (kind == 1) {
        vec3 r = abs(p / q.xyz);
        return r.x >= r.y && r.x >= r.z ? vec3(sign(p.x), 0.0, 0.0) :
               r.y >= r.z ? vec3(0.0, sign(p.y), 0.0) : vec3(0.0, 0.0, sign(p.z));
    }
    float rho = length(p.xz);
    if (kind == 2) {
        return abs(rho - q.x) <= abs(abs(p.y) - q.y) ? vec3(p.x, 0.0, p.z)
                                                       : vec3(0.0, sign(p.y), 0.0);
    }
    if (kind == 3) {
        float side = abs(rho - q.z * (q.y - p.y)), base = abs(p.y + q.y);
        vec3 radial = vec3(p.x, 0.0, p.z) / max(rho, 1e-30);
        return side <= base ? radial + vec3(0.0, q.z, 0.0) : vec3(0.0, -1.0, 0.0);
    }
    if (kind == 4) return p - vec3(p.x, 0.0, p.z) * (q.x / max(rho, 1e-30));
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

// the next boundary (t, leaf) after (t_cur, leaf_cur) and before (best, best_leaf)
void offer(float t, int k, float t_cur, int leaf_cur, inout float best, inout int best_leaf) {
    bool after = t > t_cur || (t == t_cur && k > leaf_cur);
    bool before = t < best || (t == best && k < best_leaf);
    if (after && before) { best = t; best_leaf = k; }
}

// the boundary of a convex leaf between its candidate parameters: the inside run
void convex_run(int kind, vec4 q, vec3 o, vec3 d, float c[4], out float lo, out float hi) {
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 3; ++b)
            if (c[b] > c[b + 1]) { float s = c[b]; c[b] = c[b + 1]; c[b + 1] = s; }
    lo = INF; hi = -INF;
    float edges[6] = float[6](-INF, c[0], c[1], c[2], c[3], INF);
    for (int s = 0; s < 5; ++s) {
        float a = edges[s], b = edges[s + 1];
        if (a >= INF * 0.5 || b <= -INF * 0.5 || a == b) continue;
        float m = a <= -INF * 0.5 ? b - 1.0 : (b >= INF * 0.5 ? a + 1.0 : 0.5 * (a + b));
        if (leaf_contains(kind, q, o + m * d)) { lo = min(lo, a); hi = max(hi, b); }
    }
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

// real roots of the depressed cubic s^3 + p s + r (up to 3, sorted; the rest INF)
void cubic_roots(float p, float r, out float s[3]) {
    s[0] = INF; s[1] = INF; s[2] = INF;
    float p3 = p / 3.0, r2 = r / 2.0;
    float disc = r2 * r2 + p3 * p3 * p3;
    if (disc > 0.0) {
        float u = -r2 - (r2 >= 0.0 ? 1.0 : -1.0) * sqrt(disc);  // (no cancellation)
        float cu = sign(u) * pow(abs(u), 1.0 / 3.0);
        s[0] = cu != 0.0 ? cu - p3 / cu : 0.0;
    } else {
        float m = 2.0 * sqrt(max(-p3, 0.0));
        float c = p3 < 0.0 ? clamp(-r2 / (-p3 * sqrt(-p3)), -1.0, 1.0) : 1.0;
        float phi = acos(c) / 3.0;
        s[0] = m * cos(phi + 2.0943951);
        s[1] = m * cos(phi - 2.0943951);
        s[2] = m * cos(phi);
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b)
                if (s[b] > s[b + 1]) { float x = s[b]; s[b] = s[b + 1]; s[b + 1] = x; }
    }
}

void torus_offer(int k, vec4 q, vec3 o, vec3 d, float t_cur, int leaf_cur,
                 inout float best, inout int best_leaf) {
    // centre the ray at its point nearest the torus's centre, unit direction: the quartic
    // is then s^4 + A s^2 + B s + C (no cubic term), its slope 4 s^3 + 2 A s + B
    float len = length(d);
    vec3 u = d / len;
    float s0 = -dot(o, u);
    vec3 c = o + s0 * u;
    float big = q.x + q.y, h2 = big * big - dot(c, c);
    if (h2 <= 0.0) return;                         // misses the bounding sphere
    float h = sqrt(h2);
    float R2 = q.x * q.x;
    float k0 = dot(c, c) + R2 - q.y * q.y;
    float A = 2.0 * k0 - 4.0 * R2 * dot(u.xz, u.xz);
    float B = -8.0 * R2 * dot(c.xz, u.xz);
    float crit[3];
    cubic_roots(A / 2.0, B / 4.0, crit);
    float cuts[5] = float[5](-h, INF, INF, INF, h);
    for (int j = 0; j < 3; ++j) cuts[j + 1] = clamp(crit[j], -h, h);
    float a = cuts[0], ga = torus_g(q, c, u, a);
    for (int j = 1; j < 5; ++j) {
        float b = cuts[j];
        if (b >= INF * 0.5) continue;
        float gb = torus_g(q, c, u, b);
        if (b > a && (ga < 0.0) != (gb < 0.0)) {
            float s = torus_root(q, c, u, a, b, ga);
            offer((s + s0) / len, k, t_cur, leaf_cur, best, best_leaf);
        }
        if (b > a) { a = b; ga = gb; }
    }
}

void leaf_offer(int k, vec3 ro, vec3 rd, float t_cur, int leaf_cur,
                inout float best, inout int best_leaf) {
    int kind = leaf_kind(k);
    vec4 q = leaf_param(k);
    vec4 m0 = csg_texel(8 * k), m1 = csg_texel(8 * k + 1), m2 = csg_texel(8 * k + 2);
    vec4 ro1 = vec4(ro, 1.0);
    vec3 o = vec3(dot(m0, ro1), dot(m1, ro1), dot(m2, ro1));
    vec3 d = vec3(dot(m0.xyz, rd), dot(m1.xyz, rd), dot(m2.xyz, rd));
    float t0, t1;
    if (kind == 0) {
        if (quadratic(dot(d, d), 2.0 * dot(o, d), dot(o, o) - q.x * q.x, t0, t1)) {
            offer(t0, k, t_cur, leaf_cur, best, best_leaf);
            offer(t1, k, t_cur, leaf_cur, best, best_leaf);
        }
    } else if (kind == 1) {
        vec3 dd = mix(d, vec3(1e-30), equal(d, vec3(0.0)));
        vec3 a = (-q.xyz - o) / dd, b = (q.xyz - o) / dd;
        vec3 lo = min(a, b), hi = max(a, b);
        t0 = max(max(lo.x, lo.y), lo.z); t1 = min(min(hi.x, hi.y), hi.z);
        if (t0 < t1) {
            offer(t0, k, t_cur, leaf_cur, best, best_leaf);
            offer(t1, k, t_cur, leaf_cur, best, best_leaf);
        }
    } else if (kind == 2 || kind == 3) {
        float c[4] = float[4](INF, INF, INF, INF);
        if (kind == 2) {
            if (quadratic(dot(d.xz, d.xz), 2.0 * dot(o.xz, d.xz), dot(o.xz, o.xz) - q.x * q.x,
                          t0, t1)) { c[0] = t0; c[1] = t1; }
        } else {
            float k2 = q.z * q.z, w = q.y - o.y;
            if (quadratic(dot(d.xz, d.xz) - k2 * d.y * d.y, 2.0 * (dot(o.xz, d.xz) + k2 * w * d.y),
                          dot(o.xz, o.xz) - k2 * w * w, t0, t1)) { c[0] = t0; c[1] = t1; }
        }
        if (d.y != 0.0) { c[2] = (-q.y - o.y) / d.y; c[3] = (q.y - o.y) / d.y; }
        convex_run(kind, q, o, d, c, t0, t1);
        if (t0 < t1) {
            if (t0 > -INF * 0.5) offer(t0, k, t_cur, leaf_cur, best, best_leaf);
            if (t1 < INF * 0.5) offer(t1, k, t_cur, leaf_cur, best, best_leaf);
        }
    } else if (kind == 4) {
        torus_offer(k, q, o, d, t_cur, leaf_cur, best, best_leaf);
    } else {
        float nd = dot(q.xyz, d);
        if (nd != 0.0) offer((q.w - dot(q.xyz, o)) / nd, k, t_cur, leaf_cur, best, best_leaf);
    }
}

bool box_span(vec3 ro, vec3 inv, vec3 lo, vec3 hi, out float t0, out float t1) {
    vec3 a = (lo - ro) * inv, b = (hi - ro) * inv;
    vec3 mn = min(a, b), mx = max(a, b);
    t0 = max(max(mn.x, mn.y), mn.z);
    t1 = min(min(mx.x, mx.y), mx.z);
    return t0 <= t1;
}

#if CSG_WORDS == 1
uint leaf_bits0;
#define LEAF_BIT(k) ((leaf_bits0 >> uint(k)) & 1u)
#define SET_LEAF(k) leaf_bits0 |= 1u << uint(k)
#define FLIP_LEAF(k) leaf_bits0 ^= 1u << uint(k)
#define CLEAR_LEAVES() leaf_bits0 = 0u
#else
uint leaf_bits[CSG_WORDS];
#define LEAF_BIT(k) ((leaf_bits[(k) >> 5] >> uint((k) & 31)) & 1u)
#define SET_LEAF(k) leaf_bits[(k) >> 5] |= 1u << uint((k) & 31)
#define FLIP_LEAF(k) leaf_bits[(k) >> 5] ^= 1u << uint((k) & 31)
#define CLEAR_LEAVES() for (int w = 0; w < CSG_WORDS; ++w) leaf_bits[w] = 0u
#endif

// is the ray inside any of the leaves first .. last?
bool any_inside(int first, int last) {
    for (int w = first >> 5; w <= (last >> 5); ++w) {
        int a = max(first - 32 * w, 0), b = min(last - 32 * w, 31);
        uint mask = (b - a == 31 ? 0xffffffffu : ((1u << uint(b - a + 1)) - 1u)) << uint(a);
#if CSG_WORDS == 1
        if ((leaf_bits0 & mask) != 0u) return true;
#else
        if ((leaf_bits[w] & mask) != 0u) return true;
#endif
    }
    return false;
}

bool tree_inside() {
    uint stack = 0u;
    for (int j = 0; j < u_csg_ops;) {
        vec4 e = csg_texel(u_csg_program + j);
        int r = int(e.y);
        while (r >= 0) {               // the largest subtree starting here the ray is not in
            vec4 rec = csg_texel(u_csg_records + r);
            if (!any_inside(int(rec.y), int(rec.z))) break;
            r = int(rec.w);
        }
        if (r >= 0) {                  // skipped: it is empty along the ray here
            stack <<= 1;
            j = int(csg_texel(u_csg_records + r).x) + 1;
            continue;
        }
        int code = int(e.x);
        if (code >= 0) {
            stack = (stack << 1) | LEAF_BIT(code);
        } else {
            bool x = (stack & 1u) != 0u, y = (stack & 2u) != 0u;
            stack >>= 2;
            bool v = code == -1 ? x || y : code == -2 ? x && y
                   : code == -3 ? y && !x : x && !y;   // -3: y - x, -4: x - y
            stack = (stack << 1) | (v ? 1u : 0u);
        }
        j++;
    }
    return (stack & 1u) != 0u;
}

// the first surface along ro + t rd, t > 0: (t, leaf), or leaf -1
int csg_first_hit(vec3 ro, vec3 rd, out float t_hit) {
    vec3 inv = 1.0 / mix(rd, vec3(1e-30), equal(rd, vec3(0.0)));
    CLEAR_LEAVES();
    // the leaves the ray starts in: only those whose boxes hold the start
    for (int i = 0; i < u_csg_nodes;) {
        vec4 a = csg_texel(u_csg_bvh + 2 * i), b = csg_texel(u_csg_bvh + 2 * i + 1);
        if (any(lessThan(ro, a.xyz)) || any(greaterThan(ro, b.xyz))) { i = int(a.w); continue; }
        int k = int(b.w);
        if (k >= 0 && leaf_contains(leaf_kind(k), leaf_param(k), to_leaf(k, vec4(ro, 1.0))))
            SET_LEAF(k);
        i++;
    }
    bool start = tree_inside();
    float t_cur = 0.0;
    int leaf_cur = -1;
    for (int step = 0; step < 4 * MAX_LEAVES; ++step) {
        float best = INF;
        int best_leaf = -1;
        for (int i = 0; i < u_csg_nodes;) {
            vec4 a = csg_texel(u_csg_bvh + 2 * i), b = csg_texel(u_csg_bvh + 2 * i + 1);
            float t0, t1;
            if (!box_span(ro, inv, a.xyz, b.xyz, t0, t1) || t1 < t_cur || t0 > best) {
                i = int(a.w);
                continue;
            }
            int k = int(b.w);
            if (k >= 0) leaf_offer(k, ro, rd, t_cur, leaf_cur, best, best_leaf);
            i++;
        }
        if (best_leaf < 0) return -1;
        FLIP_LEAF(best_leaf);
        if (tree_inside() != start) { t_hit = best; return best_leaf; }
        t_cur = best;
        leaf_cur = best_leaf;
    }
    return -1;
}

// the surface's normal at p (world), outward from the solid
vec3 csg_normal(int k, vec3 p) {
    return normal_to_world(k, leaf_gradient(leaf_kind(k), leaf_param(k),
                                            to_leaf(k, vec4(p, 1.0))));
}
