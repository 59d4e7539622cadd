// CSG by ray casting with the tree as data (glshade/render/csg.py writes it). A float texture
// holds, for each leaf, its world -> leaf matrix, its normal matrix (negated under a
// difference's right side), sizes and kind; a bounding-volume hierarchy over the leaves'
// world boxes (pre-order, each node with the index past its subtree); the truth table of a
// tree of at most 14 leaves; and the tree as a post-order program for a stack of bits.
//
// A tree of at most 14 leaves (CSG_SLOTS) is cast in one step: see the CSG_SLOTS section.
// A larger one walks. Along the pixel's ray the state of every leaf (inside or not) is
// kept in a bit set. The walk: find the next leaf boundary after the current one (the
// hierarchy skips leaves whose box the ray misses or meets only beyond the best so far);
// flip that leaf's bit; run the
// tree on the bits (a small tree: one lookup in its truth table; else its program, skipping
// subtrees the ray is in none of the leaves of); the first boundary where the tree's answer
// changes is the surface. One pass over the leaves yields the next four boundaries in order.
// Ties (coincident faces) go by leaf order: the left operand's face shows.
// Leaf boundaries are exact: closed-form roots, the torus's quartic split at the roots of its
// derivative (a cubic, in closed form) into monotone pieces, each root bracketed and refined
// by bisection on a sign computed without cancellation.
// Built per size class and per set of leaf kinds (CSG_KINDS): on a SIMD rasteriser a branch
// no pixel takes still runs, so only the kinds present are compiled in (see csg.py); the
// one-step cast per count of leaves of each kind (CSG_KIND_0 ..: each slot's kind).

const float INF = 1e30;
#ifndef CSG_WORDS
#define CSG_WORDS 32                   // words of leaf bits: 32 leaves each (csg.py picks)
#endif
const int MAX_LEAVES = 32 * CSG_WORDS;
#ifndef CSG_KINDS
#define CSG_KINDS 63                   // the leaf kinds the program serves, a bit each
#endif
// Why: on a SIMD rasteriser (llvmpipe) a branch no pixel takes still runs, masked, so a
// kind's code costs every leaf visit unless the program is built without it.
#define IS(kind, n) ((CSG_KINDS & (1 << (n))) != 0 && (kind) == (n))

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
uniform int u_csg_start;               // the nodes to look through for the leaves a ray
                                       // starts in: 0 where none can hold a ray's start
uniform int u_csg_ops;                 // tree program codes
uniform int u_csg_bvh;                 // first texel of the hierarchy
uniform int u_csg_program;             // first texel of the program (code, first record)
uniform int u_csg_records;             // first texel of the skip records
                                       // (end position, first leaf, last leaf, next)
uniform int u_csg_table;               // first texel of the truth table (16 bits a
                                       // component), or -1: the tree runs as its program

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

bool cone_contains(vec4 q, vec3 p) {
    float k = q.z * (q.y - p.y);
    return dot(p.xz, p.xz) <= k * k && p.y <= q.y && p.y >= -q.y;
}

// kinds: 0 sphere, 1 box, 2 cylinder, 3 cone, 4 torus, 5 half-space
bool leaf_contains(int kind, vec4 q, vec3 p) {
    if (IS(kind, 0)) return dot(p, p) <= q.x * q.x;
    if (IS(kind, 1)) return all(lessThanEqual(abs(p), q.xyz));
    if (IS(kind, 2)) return dot(p.xz, p.xz) <= q.x * q.x && abs(p.y) <= q.y;
    if (IS(kind, 3)) return cone_contains(q, p);
    if (IS(kind, 4)) {
        float w = length(p.xz) - q.x;
        return w * w + p.y * p.y <= q.y * q.y;
    }
    return dot(q.xyz, p) <= q.w;
}

vec3 leaf_gradient(int kind, vec4 q, vec3 p) {
    if (IS(kind, 0)) return p;
    if (IS(kind, 1)) {
        vec3 r = abs(p / q.xyz);
        return r.x >= r.y && r.x >= r.z ? vec3(sign(p.x), 0.0, 0.0) :
               r.y >= r.z ? vec3(0.0, sign(p.y), 0.0) : vec3(0.0, 0.0, sign(p.z));
    }
    float rho = length(p.xz);
    if (IS(kind, 2)) {
        return abs(rho - q.x) <= abs(abs(p.y) - q.y) ? vec3(p.x, 0.0, p.z)
                                                       : vec3(0.0, sign(p.y), 0.0);
    }
    if (IS(kind, 3)) {
        float side = abs(rho - q.z * (q.y - p.y)), base = abs(p.y + q.y);
        vec3 radial = vec3(p.x, 0.0, p.z) / max(rho, 1e-30);
        return side <= base ? radial + vec3(0.0, q.z, 0.0) : vec3(0.0, -1.0, 0.0);
    }
    if (IS(kind, 4)) return p - vec3(p.x, 0.0, p.z) * (q.x / max(rho, 1e-30));
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

// the torus's boundaries along o + t d (up to four; the rest INF)
vec4 torus_bounds(vec4 q, vec3 o, vec3 d) {
    vec4 out_t = vec4(INF);
    // centre the ray at its point nearest the torus's centre, unit direction: the quartic
    // is then s^4 + A s^2 + B s + C (no cubic term), its slope 4 s^3 + 2 A s + B
    float len = length(d);
    vec3 u = d / len;
    float s0 = -dot(o, u);
    vec3 c = o + s0 * u;
    float big = q.x + q.y, h2 = big * big - dot(c, c);
    if (h2 <= 0.0) return out_t;                   // misses the bounding sphere
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
    int n = 0;
    for (int j = 1; j < 5; ++j) {
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
    if (IS(kind, 0)) {
        if (quadratic(dot(d, d), 2.0 * dot(o, d), dot(o, o) - q.x * q.x, t0, t1)) {
            out_t.xy = vec2(t0, t1);
        }
    } else if (IS(kind, 1)) {
        vec3 dd = mix(d, vec3(1e-30), equal(d, vec3(0.0)));
        vec3 a = (-q.xyz - o) / dd, b = (q.xyz - o) / dd;
        vec3 lo = min(a, b), hi = max(a, b);
        t0 = max(max(lo.x, lo.y), lo.z); t1 = min(min(hi.x, hi.y), hi.z);
        if (t0 < t1) {
            out_t.xy = vec2(t0, t1);
        }
    } else if (IS(kind, 2)) {
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
    } else if (IS(kind, 3)) {
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
    } else if (IS(kind, 4)) {
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

#ifdef CSG_LEAF_LOOP
uniform int u_csg_kinds;               // first texel of the leaves listed by kind
uniform int u_csg_kind_start[7];       // where each kind's list starts (and the end)

// every leaf of one kind in turn: the loop's body is that kind's code alone (its
// boundaries: two, one for a half-space, four for a torus)
#define KIND_LOOP(n) \
    for (int j = u_csg_kind_start[n]; j < u_csg_kind_start[n + 1]; ++j) { \
        int k = int(csg_texel(u_csg_kinds + j).x); \
        vec4 t = leaf_bounds_as(n, k, ro, rd); \
        float kf = float(k); \
        offer(t.x, kf, t_cur, leaf_cur, bt, bk); \
        if (n != 5) offer(t.y, kf, t_cur, leaf_cur, bt, bk); \
        if (n == 4) { \
            offer(t.z, kf, t_cur, leaf_cur, bt, bk); \
            offer(t.w, kf, t_cur, leaf_cur, bt, bk); \
        } \
    }

// a small tree: its leaves in turn, kind by kind (where each pass of a loop costs its
// whole body, as on a SIMD rasteriser, a hierarchy's inner nodes cost as much as its
// leaves, and a leaf as much as every kind's code)
void every_leaf_offer(vec3 ro, vec3 rd, float t_cur, float leaf_cur,
                      inout vec4 bt, inout vec4 bk) {
#if (CSG_KINDS & 1) != 0
    KIND_LOOP(0)
#endif
#if (CSG_KINDS & 2) != 0
    KIND_LOOP(1)
#endif
#if (CSG_KINDS & 4) != 0
    KIND_LOOP(2)
#endif
#if (CSG_KINDS & 8) != 0
    KIND_LOOP(3)
#endif
#if (CSG_KINDS & 16) != 0
    KIND_LOOP(4)
#endif
#if (CSG_KINDS & 32) != 0
    KIND_LOOP(5)
#endif
}
#endif

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

bool tree_inside(int ops) {
    uint stack = 0u;
#if CSG_WORDS == 1
    // a small tree: its value for the leaves' bits is one lookup in its table (a loop
    // rather than an if, so a SIMD rasteriser skips the rest when every pixel returned)
    for (int once = u_csg_table >= 0 ? 0 : 1; once < 1; ++once) {
        uint word = leaf_bits0 >> 4u;
        vec4 texel = csg_texel(u_csg_table + int(word >> 2u));
        uint chunk = uint(texel[int(word & 3u)]);
        return ((chunk >> (leaf_bits0 & 15u)) & 1u) != 0u;
    }
#endif
#ifdef CSG_LEAF_LOOP
    // a small tree: every position in turn (skipping would cost more than it saves)
    for (int j = 0; j < ops; ++j) {
        int code = int(csg_texel(u_csg_program + j).x);
        bool x = (stack & 1u) != 0u, y = (stack & 2u) != 0u;
        bool v = code == -1 ? x || y : code == -2 ? x && y
               : code == -3 ? y && !x : x && !y;   // -3: y - x, -4: x - y
        stack = code >= 0 ? (stack << 1) | LEAF_BIT(max(code, 0)) : ((stack >> 2) << 1) | uint(v);
    }
    return (stack & 1u) != 0u;
#endif
    for (int j = 0; j < ops;) {
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

// an event of the batch: flip its leaf's bit; the surface if the tree's answer changes
#define EVENT(c) \
    if (bk.c < 0.0) return -1; \
    FLIP_LEAF(int(bk.c)); \
    if (tree_inside(u_csg_ops) != start) { t_hit = bt.c; return int(bk.c); }

#ifdef CSG_SLOTS
// A small tree (at most CSG_SLOTS leaves, 4, 8 or 16, with its truth table): every leaf's
// runs along the whole line at once, then the surface in one step, with no walk. Each leaf
// occurs once in the tree, under an even or odd number of right operands of differences,
// so the tree's answer can only rise at its entries (even) or its exits (odd) -- and only
// fall at the others: the surface is the nearest of those boundaries (the others where the
// ray starts inside the solid) past the near plane after which the tree's answer differs
// from the start's, one candidate a leaf (two for a torus), each tested with a lookup in
// the table. The leaves' states just after a candidate come from comparing it with every
// run at once (four leaves to a vector), ties by leaf order as in the walk. The rays come
// interpolated from the vertex stage, in each slot's frame (csg.vert). Each slot's code is
// unrolled here, its kind a constant (CSG_KIND_s), so its runs stay in registers and no
// code of another kind runs: no loops at all (on llvmpipe a loop costs more than the
// straight code it would skip).

// slot s: its leaf's world -> leaf rows and sizes, u_csg_slot[4 s .. 4 s + 3] (read at
// indices the compiler knows: plain loads; the rows for the hit's normal), its leaf's
// number and sign by groups of four
uniform vec4 u_csg_slot[4 * CSG_SLOTS];
noperspective in vec3 v_slot_origin[CSG_SLOTS];  // each slot's ray (csg.vert)
noperspective in vec3 v_slot_span[CSG_SLOTS];
int csg_hit_slot, csg_hit_kind;        // the slot of csg_first_hit's surface, its kind
uniform vec4 u_csg_slot_leaf[CSG_SLOTS / 4];
uniform vec4 u_csg_slot_sign[CSG_SLOTS / 4];   // +1: counts positively in the tree
int slot_leaf(int s) { return int(u_csg_slot_leaf[s >> 2][s & 3]); }

// slot s's runs [x, y) and [z, w) along the pixel's whole line (empty: INF, INF)
vec4 slot_runs_as(int kind, int s) {
    vec4 q = u_csg_slot[4 * s + 3];
    vec3 o = v_slot_origin[s], d = v_slot_span[s];
    if (IS(kind, 5)) {                 // a half-space: before or after its crossing
        float nd = dot(q.xyz, d), t = (q.w - dot(q.xyz, o)) / nd;
        return nd > 0.0 ? vec4(-INF, t, INF, INF) : nd < 0.0 ? vec4(t, INF, INF, INF)
             : dot(q.xyz, o) <= q.w ? vec4(-INF, INF, INF, INF) : vec4(INF);
    }
    return leaf_bounds_od(kind, q, o, d);  // (a torus: its two runs)
}

// the truth table in slot order, 32 bits a word
uniform uint u_csg_slot_table[CSG_SLOTS == 16 ? 512 : CSG_SLOTS == 8 ? 8 : 1];
bool table_inside(uint bits) {
    return ((u_csg_slot_table[bits >> 5u] >> (bits & 31u)) & 1u) != 0u;
}

#define HAS_TORUS ((CSG_KINDS & 16) != 0)

// the leaf states (as a number) of a group of four slots, with runs ``a``..``d``, at a
// point just after ``t``: a boundary is passed where it is below ``t`` -- per slot, t
// itself or the next float above it, where the walk would have passed a boundary at t
// (leaves numbered up to the candidate's: ties go by leaf order)
uint group_bits(vec4 t, vec4 a, vec4 b, vec4 c, vec4 d, uint shift) {
    uvec4 inside = uvec4(lessThan(a, t)) & uvec4(greaterThanEqual(b, t));
#if HAS_TORUS
    inside |= uvec4(lessThan(c, t)) & uvec4(greaterThanEqual(d, t));
#endif
    return (inside.x | (inside.y << 1u) | (inside.z << 2u) | (inside.w << 3u)) << shift;
}

#if CSG_SLOTS == 4
#define GROUP_SUM(t, c, S) group_bits(S(0, t, c), A0, B0, C0, D0, 0u)
#elif CSG_SLOTS == 8
#define GROUP_SUM(t, c, S) (group_bits(S(0, t, c), A0, B0, C0, D0, 0u) | \
                            group_bits(S(1, t, c), A1, B1, C1, D1, 4u))
#else
#define GROUP_SUM(t, c, S) (group_bits(S(0, t, c), A0, B0, C0, D0, 0u) | \
                            group_bits(S(1, t, c), A1, B1, C1, D1, 4u) | \
                            group_bits(S(2, t, c), A2, B2, C2, D2, 8u) | \
                            group_bits(S(3, t, c), A3, B3, C3, D3, 12u))
#endif
// group g's thresholds for a candidate t of leaf c: the next float above t for the slots
// whose leaves are numbered at most c (t >= 0 here), t for the others
#define UPTO(g, t, c) mix(vec4(t), vec4(uintBitsToFloat(floatBitsToUint(t) + 1u)), \
                          lessThanEqual(u_csg_slot_leaf[g], vec4(c)))
// the start: the boundaries before t = 0 passed, none at it
#define BEFORE(g, t, c) vec4(0.0)

// candidate t of leaf c: the surface if the answer after it differs from the start's
#define CANDIDATE(t, c, s, KIND) { \
    float tc_ = (t); \
    if (tc_ >= 0.0 && tc_ < t_best && \
        table_inside(GROUP_SUM(tc_, float(c), UPTO)) != start) { \
        t_best = tc_; best = (c); csg_hit_slot = (s); csg_hit_kind = (KIND); } }

// slot c (its runs a..dd): its one candidate (two for a torus), the leaf's own number
#define SLOT_CANDIDATES(c, KIND, a, b, cc, dd) \
    if (KIND >= 0) { \
        int leaf_ = slot_leaf(c); \
        bool rises = (u_csg_slot_sign[(c) >> 2][(c) & 3] > 0.0) != start; \
        CANDIDATE(rises ? (a) : (b), leaf_, c, KIND) \
        if (KIND == 4) CANDIDATE(rises ? (cc) : (dd), leaf_, c, KIND) \
    }

// slot s holds leaf slot_leaf(s), of kind CSG_KIND_s (-1: empty), the slots in kind order
#define SLOT(s, KIND, a, b, cc, dd) { \
    vec4 r_ = KIND >= 0 ? slot_runs_as(KIND, s) : vec4(INF); \
    a = r_.x; b = r_.y; cc = r_.z; dd = r_.w; }
#define GROUP(g, K0, K1, K2, K3, A, B, C, D) \
    vec4 A = vec4(INF), B = vec4(INF), C = vec4(INF), D = vec4(INF); \
    SLOT(4 * g, K0, A.x, B.x, C.x, D.x) SLOT(4 * g + 1, K1, A.y, B.y, C.y, D.y) \
    SLOT(4 * g + 2, K2, A.z, B.z, C.z, D.z) SLOT(4 * g + 3, K3, A.w, B.w, C.w, D.w)
#define GROUP_CANDIDATES(g, K0, K1, K2, K3, A, B, C, D) \
    SLOT_CANDIDATES(4 * g, K0, A.x, B.x, C.x, D.x) \
    SLOT_CANDIDATES(4 * g + 1, K1, A.y, B.y, C.y, D.y) \
    SLOT_CANDIDATES(4 * g + 2, K2, A.z, B.z, C.z, D.z) \
    SLOT_CANDIDATES(4 * g + 3, K3, A.w, B.w, C.w, D.w)

// M(group, its four slots' kinds, its runs' four vectors) for each group of four slots
#define GROUP_0(M) M(0, CSG_KIND_0, CSG_KIND_1, CSG_KIND_2, CSG_KIND_3, A0, B0, C0, D0)
#define GROUP_1(M) M(1, CSG_KIND_4, CSG_KIND_5, CSG_KIND_6, CSG_KIND_7, A1, B1, C1, D1)
#define GROUPS_23(M) M(2, CSG_KIND_8, CSG_KIND_9, CSG_KIND_10, CSG_KIND_11, A2, B2, C2, D2) \
    M(3, CSG_KIND_12, CSG_KIND_13, CSG_KIND_14, CSG_KIND_15, A3, B3, C3, D3)
#if CSG_SLOTS == 4
#define EACH_GROUP(M) GROUP_0(M)
#elif CSG_SLOTS == 8
#define EACH_GROUP(M) GROUP_0(M) GROUP_1(M)
#else
#define EACH_GROUP(M) GROUP_0(M) GROUP_1(M) GROUPS_23(M)
#endif

// the first surface along the pixel's ray (csg.vert's: ``ro`` + t ``rd``, the near plane to
// the far one), t >= 0: (t, leaf), or leaf -1
int csg_first_hit(vec3 ro, vec3 rd, out float t_hit) {
    EACH_GROUP(GROUP)
    // the solid can hold the ray's start only where a leaf's box meets the near plane
    bool start = false;
    if (u_csg_start > 0)
        start = table_inside(GROUP_SUM(0.0, 0.0, BEFORE));
    float t_best = INF;
    int best = -1;
    EACH_GROUP(GROUP_CANDIDATES)
    t_hit = t_best;
    return best;
}
#else
// the first surface along ro + t rd, t > 0: (t, leaf), or leaf -1
int csg_first_hit(vec3 ro, vec3 rd, out float t_hit) {
    vec3 inv = 1.0 / mix(rd, vec3(1e-30), equal(rd, vec3(0.0)));
    CLEAR_LEAVES();
    // the leaves the ray starts in: only those whose boxes hold the start (none where no
    // leaf's box meets the near plane: the loop is then not run at all)
    for (int i = 0; i < u_csg_start;) {
        vec4 a = csg_texel(u_csg_bvh + 2 * i), b = csg_texel(u_csg_bvh + 2 * i + 1);
        if (any(lessThan(ro, a.xyz)) || any(greaterThan(ro, b.xyz))) { i = int(a.w); continue; }
        int k = int(b.w);
        if (k >= 0 && leaf_contains(leaf_kind(k), leaf_param(k), to_leaf(k, vec4(ro, 1.0))))
            SET_LEAF(k);
        i++;
    }
    bool start = tree_inside(u_csg_start > 0 ? u_csg_ops : 0);
    float t_cur = 0.0, leaf_cur = -1.0;
    for (int step = 0; step < 4 * MAX_LEAVES; ++step) {
        vec4 bt = vec4(INF), bk = vec4(-1.0);
#ifdef CSG_LEAF_LOOP
        every_leaf_offer(ro, rd, t_cur, leaf_cur, bt, bk);
#else
        for (int i = 0; i < u_csg_nodes;) {
            vec4 a = csg_texel(u_csg_bvh + 2 * i), b = csg_texel(u_csg_bvh + 2 * i + 1);
            float t0, t1;
            if (!box_span(ro, inv, a.xyz, b.xyz, t0, t1) || t1 < t_cur || t0 > bt.w) {
                i = int(a.w);
                continue;
            }
            int k = int(b.w);
            if (k >= 0) offer4(leaf_bounds_as(leaf_kind(k), k, ro, rd), k, t_cur, leaf_cur,
                               bt, bk);
            i++;
        }
#endif
        // the events in order: the first where the tree's answer changes is the surface
        EVENT(x) EVENT(y) EVENT(z) EVENT(w)
        t_cur = bt.w;
        leaf_cur = bk.w;
    }
    return -1;
}
#endif

// the surface's normal at p (world), outward from the solid
vec3 csg_normal(int k, vec3 p) {
#ifdef CSG_SLOTS
    // (from the hit's slot: its rows are the world -> leaf map, whose transpose takes a
    // gradient back to world; the sign is the caller's: it turns the normal to the eye)
    int s = csg_hit_slot;
    vec4 m0 = u_csg_slot[4 * s], m1 = u_csg_slot[4 * s + 1], m2 = u_csg_slot[4 * s + 2];
    vec4 p1 = vec4(p, 1.0);
    vec3 g = leaf_gradient(csg_hit_kind, u_csg_slot[4 * s + 3],
                           vec3(dot(m0, p1), dot(m1, p1), dot(m2, p1)));
    return g.x * m0.xyz + g.y * m1.xyz + g.z * m2.xyz;
#else
    return normal_to_world(k, leaf_gradient(leaf_kind(k), leaf_param(k),
                                            to_leaf(k, vec4(p, 1.0))));
#endif
}
