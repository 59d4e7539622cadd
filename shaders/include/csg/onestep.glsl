#ifdef CSG_SLOTS
// A small tree (at most CSG_SLOTS leaves, 4, 8 or 16, with its truth table): every leaf's
// runs along the whole line at once, then the surface in one step, with no walk. Each leaf
// occurs once in the tree, under an even or odd number of right operands of differences,
// so the tree's answer can only rise at its entries (even) or its exits (odd) -- and only
// fall at the others: the surface is the nearest of those boundaries (the others where the
// ray starts inside the solid) past the near plane after which the tree's answer differs
// from the start's, one candidate a leaf (two for a torus), each tested with a lookup in
// the table. The leaves' states just past a candidate come from comparing it with every
// run at once (four leaves to a vector), past its ties as in the walk (the tie rule). The rays come
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
    if (IS(kind, LEAF_HALFSPACE)) {                 // a half-space: before or after its crossing
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

#define HAS_TORUS ((CSG_KINDS & (1 << LEAF_TORUS)) != 0)

// The tie rule at a plane seen at a grazing angle. Two leaves' coincident faces are one
// plane computed through two frames, and where a ray crosses it moves with a frame's
// rounding over the cosine between the ray and the plane's normal: a ray grazing a face
// two leaves share found them apart (a box touching another along a face, intersected: a
// zero-thickness slab showed as a surface at grazing pixels). So two boundaries that are
// both planes (a box's faces, a half-space, a cylinder's or a cone's flat end) at the same
// angle to the ray -- one plane, or parallel ones -- are tied within the rule's length
// over their cosine (at most MAX_OBLIQUITY times it); other pairs keep the plain length,
// as the reference's walk does: a plane and a curved surface (whose cosine counts as 1:
// grazing it is a silhouette), and two planes that cross (grazing both near their common
// line, they are apart, and the nearer leaf is the surface).
#define MAX_OBLIQUITY 64.0
float plane_cosine(int s, int kind, float t) {
    if (!(t > -INF && t < INF)) return 1.0;
    vec3 d = v_slot_span[s];
    vec3 g = leaf_gradient(kind, u_csg_slot[4 * s + 3], v_slot_origin[s] + t * d);
    bool planar = IS(kind, LEAF_BOX) || IS(kind, LEAF_HALFSPACE) ||
        ((IS(kind, LEAF_CYLINDER) || IS(kind, LEAF_CONE)) && g.x == 0.0 && g.z == 0.0);
    float cosine = abs(dot(g, d)) / max(length(g) * length(d), 1e-30);
    return planar ? max(cosine, 1.0 / MAX_OBLIQUITY) : 1.0;
}

// the tie rule's lengths between a boundary whose cosine is ``c`` and four whose cosines
// are ``q``: widened where the two are parallel planes (equal cosines, to rounding)
vec4 tie_lengths(float tie, float c, vec4 q) {
    bvec4 parallel = lessThanEqual(abs(vec4(c) - q), 1e-4 * max(vec4(c), q));
    return tie / mix(vec4(1.0), max(vec4(c), q), parallel);
}

// the leaf states (as a number) of a group of four slots, with runs ``a``..``d``, at a
// point just past a candidate: a boundary is passed where it is below its threshold
// (``ta`` for the runs' entries, ``tb`` their exits, ``t`` a torus's second run: the
// candidate's t plus the tie rule's length, the pair's: its tied boundaries passed with it)
uint group_bits(vec4 ta, vec4 tb, vec4 t, vec4 a, vec4 b, vec4 c, vec4 d, uint shift) {
    uvec4 inside = uvec4(lessThan(a, ta)) & uvec4(greaterThanEqual(b, tb));
#if HAS_TORUS
    inside |= uvec4(lessThan(c, t)) & uvec4(greaterThanEqual(d, t));
#endif
    return (inside.x | (inside.y << 1u) | (inside.z << 2u) | (inside.w << 3u)) << shift;
}

// the lowest leaf of a group of four slots with a boundary tied with the surface at ``t``
// (its plane's cosine ``cosine``; the runs' ends' ``qa``, ``qb``)
float group_tied(vec4 leaf, float t, float tie, float cosine, vec4 a, vec4 b, vec4 c,
                 vec4 d, vec4 qa, vec4 qb) {
    bvec4 near = bvec4(uvec4(lessThanEqual(abs(a - t), tie_lengths(tie, cosine, qa))) |
                       uvec4(lessThanEqual(abs(b - t), tie_lengths(tie, cosine, qb))));
#if HAS_TORUS
    near = bvec4(uvec4(near) | uvec4(lessThanEqual(abs(c - t), vec4(tie))) |
                 uvec4(lessThanEqual(abs(d - t), vec4(tie))));
#endif
    vec4 l = mix(vec4(INF), leaf, near);
    return min(min(l.x, l.y), min(l.z, l.w));
}
#define TIED(g, K0, K1, K2, K3, A, B, C, D, QA, QB) \
    tied = min(tied, group_tied(u_csg_slot_leaf[g], t_best, tie, best_cosine, A, B, C, D, \
                                QA, QB));

#define GROUP_BITS(t, c, S, A, B, C, D, QA, QB, SHIFT) \
    group_bits(S(t, c, QA), S(t, c, QB), S(t, c, vec4(1.0)), A, B, C, D, SHIFT)
#if CSG_SLOTS == 4
#define GROUP_SUM(t, c, S) GROUP_BITS(t, c, S, A0, B0, C0, D0, QA0, QB0, 0u)
#elif CSG_SLOTS == 8
#define GROUP_SUM(t, c, S) (GROUP_BITS(t, c, S, A0, B0, C0, D0, QA0, QB0, 0u) | \
                            GROUP_BITS(t, c, S, A1, B1, C1, D1, QA1, QB1, 4u))
#else
#define GROUP_SUM(t, c, S) (GROUP_BITS(t, c, S, A0, B0, C0, D0, QA0, QB0, 0u) | \
                            GROUP_BITS(t, c, S, A1, B1, C1, D1, QA1, QB1, 4u) | \
                            GROUP_BITS(t, c, S, A2, B2, C2, D2, QA2, QB2, 8u) | \
                            GROUP_BITS(t, c, S, A3, B3, C3, D3, QA3, QB3, 12u))
#endif
// the thresholds for a candidate t (its plane's cosine ``cosine_at``) of boundaries whose
// cosines are ``q``: past its ties
#define UPTO(t, c, q) (vec4(t) + tie_lengths(tie, cosine_at, q))
// the start: the boundaries before t = 0 passed, none at it
#define BEFORE(t, c, q) vec4(0.0)

// candidate t of leaf c (its plane's cosine q): the surface if the answer after it
// differs from the start's
#define CANDIDATE(t, q, c, s, KIND) { \
    float tc_ = (t); \
    float cosine_at = (q); \
    if (tc_ >= 0.0 && tc_ < t_best && \
        table_inside(GROUP_SUM(tc_, float(c), UPTO)) != start) { \
        t_best = tc_; best = (c); best_cosine = cosine_at; csg_hit_slot = (s); \
        csg_hit_kind = (KIND); } }

// slot c (its runs a..dd, its run's ends' cosines qa, qb): its one candidate (two for a
// torus), the leaf's own number
#define SLOT_CANDIDATES(c, KIND, a, b, cc, dd, qa, qb) \
    if (KIND >= 0) { \
        int leaf_ = slot_leaf(c); \
        bool rises = (u_csg_slot_sign[(c) >> 2][(c) & 3] > 0.0) != start; \
        CANDIDATE(rises ? (a) : (b), rises ? (qa) : (qb), leaf_, c, KIND) \
        if (KIND == LEAF_TORUS) CANDIDATE(rises ? (cc) : (dd), 1.0, leaf_, c, KIND) \
    }

// slot s holds leaf slot_leaf(s), of kind CSG_KIND_s (-1: empty), the slots in kind order
#define SLOT(s, KIND, a, b, cc, dd, qa, qb) { \
    vec4 r_ = KIND >= 0 ? slot_runs_as(KIND, s) : vec4(INF); \
    a = r_.x; b = r_.y; cc = r_.z; dd = r_.w; \
    qa = KIND >= 0 ? plane_cosine(s, KIND, a) : 1.0; \
    qb = KIND >= 0 ? plane_cosine(s, KIND, b) : 1.0; }
#define GROUP(g, K0, K1, K2, K3, A, B, C, D, QA, QB) \
    vec4 A = vec4(INF), B = vec4(INF), C = vec4(INF), D = vec4(INF); \
    vec4 QA = vec4(1.0), QB = vec4(1.0); \
    SLOT(4 * g, K0, A.x, B.x, C.x, D.x, QA.x, QB.x) \
    SLOT(4 * g + 1, K1, A.y, B.y, C.y, D.y, QA.y, QB.y) \
    SLOT(4 * g + 2, K2, A.z, B.z, C.z, D.z, QA.z, QB.z) \
    SLOT(4 * g + 3, K3, A.w, B.w, C.w, D.w, QA.w, QB.w)
#define GROUP_CANDIDATES(g, K0, K1, K2, K3, A, B, C, D, QA, QB) \
    SLOT_CANDIDATES(4 * g, K0, A.x, B.x, C.x, D.x, QA.x, QB.x) \
    SLOT_CANDIDATES(4 * g + 1, K1, A.y, B.y, C.y, D.y, QA.y, QB.y) \
    SLOT_CANDIDATES(4 * g + 2, K2, A.z, B.z, C.z, D.z, QA.z, QB.z) \
    SLOT_CANDIDATES(4 * g + 3, K3, A.w, B.w, C.w, D.w, QA.w, QB.w)

// M(group, its four slots' kinds, its runs' four vectors, their ends' cosines) for each
// group of four slots
#define GROUP_0(M) M(0, CSG_KIND_0, CSG_KIND_1, CSG_KIND_2, CSG_KIND_3, A0, B0, C0, D0, QA0, QB0)
#define GROUP_1(M) M(1, CSG_KIND_4, CSG_KIND_5, CSG_KIND_6, CSG_KIND_7, A1, B1, C1, D1, QA1, QB1)
#define GROUPS_23(M) \
    M(2, CSG_KIND_8, CSG_KIND_9, CSG_KIND_10, CSG_KIND_11, A2, B2, C2, D2, QA2, QB2) \
    M(3, CSG_KIND_12, CSG_KIND_13, CSG_KIND_14, CSG_KIND_15, A3, B3, C3, D3, QA3, QB3)
#if CSG_SLOTS == 4
#define EACH_GROUP(M) GROUP_0(M)
#elif CSG_SLOTS == 8
#define EACH_GROUP(M) GROUP_0(M) GROUP_1(M)
#else
#define EACH_GROUP(M) GROUP_0(M) GROUP_1(M) GROUPS_23(M)
#endif

// the first surface along the pixel's ray (csg.vert's: ``ro`` + t ``rd``, the near plane to
// the far one), t >= 0: (t, leaf), or leaf -1; of the leaves tied there, the lowest
int csg_first_hit(vec3 ro, vec3 rd, out float t_hit) {
    float tie = u_csg_tie / length(rd);   // (t runs from the near plane to the far one)
    EACH_GROUP(GROUP)
    // the solid can hold the ray's start only where a leaf's box meets the near plane
    bool start = false;
    float cosine_at = 1.0;
    if (u_csg_start > 0)
        start = table_inside(GROUP_SUM(0.0, 0.0, BEFORE));
    float t_best = INF, best_cosine = 1.0;
    int best = -1;
    EACH_GROUP(GROUP_CANDIDATES)
    t_hit = t_best;
    if (best < 0) return -1;
    float tied = INF;
    EACH_GROUP(TIED)
    return int(min(tied, float(best)));
}
#endif
