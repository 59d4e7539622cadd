// A larger tree's walk from one leaf boundary to the next (see csg/layout.glsl).

#ifdef CSG_LEAF_LOOP
uniform int u_csg_kinds;               // first texel of the leaves listed by kind
uniform int u_csg_kind_start[7];       // where each kind's list starts (and the end)

// every leaf of one kind in turn: the loop's body is that kind's code alone (its
// boundaries: two, one for a half-space, four for a torus)
#define KIND_LOOP(n) \
    for (int j = u_csg_kind_start[n]; j < u_csg_kind_start[n + 1]; ++j) { \
        CSG_COUNT; \
        int k = int(csg_texel(u_csg_kinds + j).x); \
        vec4 t = leaf_bounds_as(n, k, ro, rd); \
        float kf = float(k); \
        offer(t.x, kf, t_cur, leaf_cur, bt, bk); \
        if (n != LEAF_HALFSPACE) offer(t.y, kf, t_cur, leaf_cur, bt, bk); \
        if (n == LEAF_TORUS) { \
            offer(t.z, kf, t_cur, leaf_cur, bt, bk); \
            offer(t.w, kf, t_cur, leaf_cur, bt, bk); \
        } \
    }

// a small tree: its leaves in turn, kind by kind (where each pass of a loop costs its
// whole body, as on a SIMD rasteriser, a hierarchy's inner nodes cost as much as its
// leaves, and a leaf as much as every kind's code)
void every_leaf_offer(vec3 ro, vec3 rd, float t_cur, float leaf_cur,
                      inout vec4 bt, inout vec4 bk) {
#if (CSG_KINDS & (1 << LEAF_SPHERE)) != 0
    KIND_LOOP(LEAF_SPHERE)
#endif
#if (CSG_KINDS & (1 << LEAF_BOX)) != 0
    KIND_LOOP(LEAF_BOX)
#endif
#if (CSG_KINDS & (1 << LEAF_CYLINDER)) != 0
    KIND_LOOP(LEAF_CYLINDER)
#endif
#if (CSG_KINDS & (1 << LEAF_CONE)) != 0
    KIND_LOOP(LEAF_CONE)
#endif
#if (CSG_KINDS & (1 << LEAF_TORUS)) != 0
    KIND_LOOP(LEAF_TORUS)
#endif
#if (CSG_KINDS & (1 << LEAF_HALFSPACE)) != 0
    KIND_LOOP(LEAF_HALFSPACE)
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
        CSG_COUNT;
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

// a boolean of the program (solids/encoding.py Op, injected) on its operands: y the
// earlier, x the later (on top)
bool apply_op(int code, bool x, bool y) {
    return code == OP_UNION ? x || y : code == OP_INTERSECTION ? x && y
         : code == OP_DIFFERENCE ? y && !x : x && !y;   // OP_DIFFERENCE_SWAPPED: x - y
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
        CSG_COUNT;
        int code = int(csg_texel(u_csg_program + j).x);
        bool x = (stack & 1u) != 0u, y = (stack & 2u) != 0u;
        stack = code >= 0 ? (stack << 1) | LEAF_BIT(max(code, 0))
                          : ((stack >> 2) << 1) | uint(apply_op(code, x, y));
    }
    return (stack & 1u) != 0u;
#endif
    for (int j = 0; j < ops;) {
        CSG_COUNT;
        vec4 e = csg_texel(u_csg_program + j);
        int r = int(e.y);
        while (r >= 0) {               // the largest subtree starting here the ray is not in
            CSG_COUNT;
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
            stack = (stack << 1) | (apply_op(code, x, y) ? 1u : 0u);
        }
        j++;
    }
    return (stack & 1u) != 0u;
}

// an event of the batch, with the tie rule (solids/tree.py TIE): a boundary within u_csg_tie
// of the one before joins its group; where a group ends, the surface if the tree's answer
// after it differs from the start's -- at the group's first t, of its lowest leaf
#define EVENT(c) \
    if (bk.c < 0.0 || bt.c - t_prev > u_csg_tie) { \
        if (group_open && tree_inside(u_csg_ops) != start) { \
            t_hit = group_t; \
            return int(group_leaf); \
        } \
        group_open = false; \
        if (bk.c < 0.0) return -1; \
    } \
    group_leaf = group_open ? min(group_leaf, bk.c) : bk.c; \
    group_t = group_open ? group_t : bt.c; \
    group_open = true; \
    t_prev = bt.c; \
    FLIP_LEAF(int(bk.c));

#ifndef CSG_SLOTS
// the first surface along ro + t rd, t > 0: (t, leaf), or leaf -1
int csg_first_hit(vec3 ro, vec3 rd, out float t_hit) {
    vec3 inv = 1.0 / mix(rd, vec3(1e-30), equal(rd, vec3(0.0)));
    CLEAR_LEAVES();
    // the leaves the ray starts in: only those whose boxes hold the start (none where no
    // leaf's box meets the near plane: the loop is then not run at all)
    for (int i = 0; i < u_csg_start;) {
        CSG_COUNT;
        vec4 a = csg_texel(u_csg_bvh + 2 * i), b = csg_texel(u_csg_bvh + 2 * i + 1);
        if (any(lessThan(ro, a.xyz)) || any(greaterThan(ro, b.xyz))) { i = int(a.w); continue; }
        int k = int(b.w);
        if (k >= 0 && leaf_contains(leaf_kind(k), leaf_param(k), to_leaf(k, vec4(ro, 1.0))))
            SET_LEAF(k);
        i++;
    }
    bool start = tree_inside(u_csg_start > 0 ? u_csg_ops : 0);
    float t_cur = 0.0, leaf_cur = -1.0;
    bool group_open = false;
    float group_t = 0.0, group_leaf = -1.0, t_prev = -INF;
    for (int step = 0; step < 4 * MAX_LEAVES; ++step) {
        CSG_COUNT;
        vec4 bt = vec4(INF), bk = vec4(-1.0);
#ifdef CSG_LEAF_LOOP
        every_leaf_offer(ro, rd, t_cur, leaf_cur, bt, bk);
#else
        for (int i = 0; i < u_csg_nodes;) {
            CSG_COUNT;
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
    return -1;  // (4 events a leaf at most: never reached with a group open)
}
#endif
