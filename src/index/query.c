/*
 * query.c -- the index's walks: a lookup follows the one path of nodes
 * that holds its point (index.c places a record in every node its reach
 * may serve from), and a range walk enters every node within a range of
 * a point, or within the reach of the records homed below it, taking
 * records at their homes.  Each hands over a superset of the records
 * asked for, which the caller tests exactly.
 *
 * The walks need no double and no cube centre: the point is turned once
 * into integers, 2^-IRC__FX root edges from the root's low corner, rounded
 * down exactly (the product of a float and a power of two is exact, and so
 * is its floor), so the path's octants are the integer's bits and a point
 * on a face shared by two cells takes the upper one, as index.c places.  A
 * node's low corner is an integer of the same units, and a node's relative
 * point, its cube's half edges from its centre, is the difference rounded
 * once to float.  On a single-precision FPU (Cortex-M4F) a double
 * operation is a library call.
 *
 * Exactness.  The integer point is the exact floor but where p's product
 * underflows (|p| below 2^-100 of the root), under a unit off.  At depth
 * d a half edge is 2^(57 - d) units; the scan widens its bound by
 * 2^(d - 32) steps of 4 / 65535 half edges and the children's test by
 * 2^(d - 46) child half edges, negligible above depth 30 and at the depth
 * limit a wider candidate set, never a narrower one.  A point farther than
 * 4 root edges from the root is clamped toward it per axis, which only
 * shortens its distance to anything inside the root's frame (every list's
 * references but the root's to records outside it, which are always
 * candidates); such a point's path is the root alone.
 */
#include "../block/cache.h"
#include "index.h"
#include "layout.h"

/* Four lanes in the compiler's vector types (GCC and Clang; no header)
 * where the target has SSE2 (every x86-64), unless IRC_NO_SIMD: the scalar
 * path is the one 32-bit and embedded builds run. */
#if (defined(__GNUC__) || defined(__clang__)) && defined(__SSE2__) && !defined(IRC_NO_SIMD)
#define IRC__VEC4 1
typedef float irc__v4f __attribute__((vector_size(16)));
typedef int32_t irc__v4i __attribute__((vector_size(16)));
typedef uint16_t irc__v4h __attribute__((vector_size(8)));
#endif

#define IRC__FX 58 /* fixed-point bits of the root's edge */

/* What a query asks for: records whose reach times scale may hold p, or,
 * with range >= 0, records within range of p.  The factors of the tests
 * at depth 0; a depth d multiplies them by 2^d. */
typedef struct irc__probe {
    int64_t p[3];  /* the point, fixed point from the root's low corner */
    float m;       /* scan: the bound's factor on an entry's rq */
    float f;       /* scan: the range in steps of the root's cube */
    float s;       /* children: reach to child half edges of the root */
    float g;       /* children: the range in child half edges of the root */
    irc__visit_fn fn;
    void *ud;
} irc__probe;

/* 2^k as a float, for k in [-126, 127], from its bits (weight.c's
 * irc__grad_scale also builds denormals; that test costs the walk 2%). */
static float irc__pow2f(int k)
{
    uint32_t bits = (uint32_t)(k + 127) << 23;
    float f;
    IRC_MEMCPY(&f, &bits, sizeof f);
    return f;
}

/* A depth-0 factor no smaller than 2^-100: rounding one from beyond
 * float's normal range down would narrow the tests (a range or reach
 * scale 2^-100 of a wide root's edge); a larger one only widens them, and
 * a factor times 2^d past FLT_MAX is infinite, which lets everything by. */
static float irc__factor(float x)
{
    return x > 0x1p-100f ? x : 0x1p-100f;
}

/* A float of magnitude below 2^63 to an integer, rounded down, from its
 * bits: on a 32-bit core the cast is a library call that goes through
 * double, and it truncates. */
static int64_t irc__to_int64(float x)
{
#if UINTPTR_MAX > 0xffffffffu
    /* a 64-bit core converts in one instruction, truncating: floored by
     * the comparison (exact: a truncated float below 2^24 is a float, and
     * one above is the float itself) */
    const int64_t t = (int64_t)x;
    return t - ((float)t > x);
#else
    uint32_t b;
    int64_t m, f = 0;
    int ex;
    IRC_MEMCPY(&b, &x, sizeof b);
    if (!(b & 0x7fffffffu))
        return 0;
    ex = (int)(b >> 23 & 0xffu) - 150; /* |x| = m 2^ex */
    m = (int64_t)((b & 0x7fffffu) | (b >> 23 & 0xffu ? 0x800000u : 0u));
    if (ex >= 0) {
        m <<= ex;
    } else if (ex > -24) {
        f = m & (((int64_t)1 << -ex) - 1);
        m >>= -ex;
    } else {
        f = m;
        m = 0;
    }
    return b >> 31 ? -m - (f != 0) : m;
#endif
}

/* The point's offset from the root's low corner in units.  lo is a float
 * within 34 half edges h = 2^E of the origin, -99 <= E <= 99
 * (irc__index_root_sane), so p and lo times 2^(57 - E) are exact floats,
 * below 2^62.1 where it matters (p's unless it underflows), lo's an
 * integer, and the floor of their difference is exact.  Clamped to [-4, 5] root edges from lo (file
 * comment), both bounds exact too. */
static int64_t irc__fixed(float p, float lo, int e)
{
    const int k = 57 - e;
    const float k0 = irc__pow2f(k / 2), k1 = irc__pow2f(k - k / 2);
    const float l = lo * k0 * k1, a = l - 0x1p60f, b = l + 0x1.4p60f;
    float x = p * k0 * k1;
    x = x < a ? a : x > b ? b : x;
    return irc__to_int64(x) - irc__to_int64(l);
}

static void irc__probe_set(const irc_cache *c, const float p[3], float range, float scale,
                           irc__visit_fn fn, void *ud, irc__probe *pr)
{
    const int ranged = range >= 0.0f;
    float inv_h; /* 1/h: a power of two */
    uint64_t bits;
    int i, e;
    /* h = 2^e, -99 <= e <= 99 (irc__index_root_sane) */
    IRC_MEMCPY(&bits, &irc__st(c)->root_h, sizeof bits);
    e = (int)(bits >> 52 & 0x7ffu) - 1023;
    for (i = 0; i < 3; i++)
        pr->p[i] = irc__fixed(p[i], (float)irc__st(c)->root_c[i] - irc__pow2f(e), e);
    /* The factors in float: their roundings (relative 2^-23 at most) lie
     * well inside the margins 1e-5 and 4e-6 each carries. */
    inv_h = irc__pow2f(-e);
    pr->m = ranged ? 0.0f : scale * (1.0f + 1e-5f);
    pr->f = ranged ? irc__factor(range * (16383.75f * (1.0f + 1e-5f)) * inv_h) : 0.0f;
    pr->s = ranged ? 0.0f : irc__factor(scale * (2.0f * (1.0f + 4e-6f)) * inv_h);
    pr->g = ranged ? irc__factor(range * (2.0f * (1.0f + 4e-6f)) * inv_h) : 0.0f;
    pr->fn = fn;
    pr->ud = ud;
}

/* The probe's point relative to the node of depth d with low corner lo,
 * in its half edges (2^(57 - d) units).  A 64-bit core converts the
 * offset to float at once, one rounding.  A 32-bit one, where that
 * conversion is a library call, goes through a 32-bit integer: the offset
 * floored to 2^-26 half edges (4.9e-4 steps of the scan, 3e-8 child half
 * edges: within what the tests' slack leaves) and clamped to 32 half
 * edges, which only shortens the distance to anything inside the node's
 * cube; the bias keeps the shift on a nonnegative value (|offset| < 2^61
 * units).  Either way the candidates are a superset of the same exact
 * set, so lookups answer the same. */
static void irc__rel(const irc__probe *pr, const int64_t lo[3], int d, float r[3])
{
    const int64_t half = (int64_t)1 << (IRC__FX - 1 - d);
    int i;
#if UINTPTR_MAX > 0xffffffffu
    const float unit = irc__pow2f(d - (IRC__FX - 1));
    for (i = 0; i < 3; i++)
        r[i] = (float)(pr->p[i] - lo[i] - half) * unit;
#else
    const int64_t bias = (int64_t)1 << 62, top = ((int64_t)1 << 31) - 1;
    const int sh = d < 31 ? 31 - d : 0;
    const float unit = irc__pow2f(sh + d - (IRC__FX - 1));
    for (i = 0; i < 3; i++) {
        int64_t v = (int64_t)(((uint64_t)(pr->p[i] - lo[i] - half + bias) >> sh) -
                              ((uint64_t)bias >> sh));
        v = v < -top ? -top : v > top ? top : v;
        r[i] = (float)(int32_t)v * unit;
    }
#endif
}

/* A list's test: the probe's point in the steps of the list's frame and
 * the bound's two factors (m rq + f steps: a reach times scale, or the
 * range); r3 is the point relative to the list's cube of depth d.  The
 * test admits a superset of the exact one: the reference's position is at
 * most sqrt(3)/2 steps off (the 1 added to the bound); the point's float
 * roundings, in r and in (r + 2) 16383.75, are within 0.01 steps while
 * |r| < 4 (the slack left by the 1), and relative ones beyond, covered
 * with the float rounding of the test itself by the 1e-5 relative margin;
 * the integer point's error by the 2^(d - 32) (file comment). */
typedef struct irc__steps {
    float b[3], m, f;
} irc__steps;

static const irc__steps *irc__steps_of(const float r3[3], int d, const irc__probe *pr,
                                        irc__steps *s)
{
    s->b[0] = (r3[0] + 2.0f) * 16383.75f;
    s->b[1] = (r3[1] + 2.0f) * 16383.75f;
    s->b[2] = (r3[2] + 2.0f) * 16383.75f;
    s->m = pr->m;
    s->f = pr->f * irc__pow2f(d) + 1.0f + irc__pow2f(d - 32);
    return s;
}

static int irc__passes(const irc__ref *e, const irc__steps *s)
{
    const float dx = s->b[0] - e->q[0], dy = s->b[1] - e->q[1], dz = s->b[2] - e->q[2],
                bound = (float)e->rq * s->m + s->f;
    return dx * dx + dy * dy + dz * dz <= bound * bound || e->rq == IRC__IX_ANY;
}

/* A lookup's list: hands over every record whose reference passes. */
static uint32_t irc__scan(const irc_cache *c, uint32_t r, const irc__steps *s,
                          const irc__probe *pr)
{
    uint32_t n = 0;
    const irc__ref *refs = irc__refs(c);
#ifdef IRC__VEC4
    /* The reference's four 16-bit fields converted at once; the same
     * operations in the same order as irc__passes. */
    const irc__v4f b = {s->b[0], s->b[1], s->b[2], 0.0f};
    for (; r != IRC__NIL; r = refs[r].next) {
        const irc__ref *e = &refs[r];
        irc__v4h qh;
        irc__v4f q, dv;
        float bound;
        IRC_MEMCPY(&qh, e, sizeof qh); /* the first 8 bytes: q[0..2], rq */
        q = __builtin_convertvector(__builtin_convertvector(qh, irc__v4i), irc__v4f);
        dv = b - q;
        dv *= dv;
        bound = q[3] * s->m + s->f;
        n++;
        if (dv[0] + dv[1] + dv[2] <= bound * bound || e->rq == IRC__IX_ANY)
            pr->fn(pr->ud, e->id & ~IRC__REF_HOME);
    }
#else
    for (; r != IRC__NIL; r = refs[r].next) {
        n++;
        if (irc__passes(&refs[r], s))
            pr->fn(pr->ud, refs[r].id & ~IRC__REF_HOME);
    }
#endif
    return n;
}

/* A range walk's list: its homes, which come first (cells.c), that pass. */
static uint32_t irc__scan_homes(const irc_cache *c, uint32_t r, const irc__steps *s,
                                const irc__probe *pr)
{
    uint32_t n = 0;
    const irc__ref *refs = irc__refs(c);
    for (; r != IRC__NIL && (refs[r].id & IRC__REF_HOME); r = refs[r].next) {
        n++;
        if (irc__passes(&refs[r], s))
            pr->fn(pr->ud, refs[r].id & ~IRC__REF_HOME);
    }
    return n;
}

/* The children of node n (depth d) a probe must enter, as bits by octant:
 * those whose cube lies within the subtree's reach (or the range) of p (a
 * record lies inside its node's cube, the root's list excepted, which is
 * always scanned).  Distances are in child half edges, in float: the
 * bound is widened by a relative 4e-6 (the roundings of the squares and
 * sums, about 1e-6), 1e-6 of a half edge (underflow of tiny terms) and
 * the integer point's 2^(d - 46), so the test admits a superset of the
 * exact one; a square too large for a float rejects only a child beyond
 * FLT_MAX half edges, which no reach below that passes either. */
static unsigned irc__children(const irc_cache *c, const irc__node *n, int d,
                              const float r3[3], const irc__probe *pr)
{
    const irc__node *ch = &irc__nodes(c)[n->child];
    const float up = irc__pow2f(d), s = pr->s * up,
                fixed = pr->g * up + 1e-6f + irc__pow2f(d - 46);
    float part[3][2], xy[4];
    unsigned mask = 0;
    int i;
    /* Squared distance from p to each child's cube, axis by axis, in child
     * half edges from the centre: child bit k of axis i spans [-2, 0]
     * (k = 0) or [0, 2].  With x's own rounding, x - 2 and -2 - x are
     * within 6e-7 half edges while |x| < 4 (inside the 1e-6), relatively
     * close beyond. */
    for (i = 0; i < 3; i++) {
        const float x = 2.0f * r3[i], lo = x > -2.0f - x ? x : -2.0f - x,
                    hi = -x > x - 2.0f ? -x : x - 2.0f;
        part[i][0] = lo > 0.0f ? lo * lo : 0.0f; /* outside [-2, 0] */
        part[i][1] = hi > 0.0f ? hi * hi : 0.0f; /* outside [0, 2] */
    }
    /* By the octant's low two bits (x, y), then z added per child; an
     * empty child's reach is -1, which its own test must not let by. */
    xy[0] = part[0][0] + part[1][0];
    xy[1] = part[0][1] + part[1][0];
    xy[2] = part[0][0] + part[1][1];
    xy[3] = part[0][1] + part[1][1];
#ifdef IRC__VEC4
    {
        /* The same operations on four children at once: the same masks. */
        const irc__v4f vs = {s, s, s, s}, vf = {fixed, fixed, fixed, fixed},
                       zero = {0.0f, 0.0f, 0.0f, 0.0f}, q = {xy[0], xy[1], xy[2], xy[3]};
        int h;
        for (h = 0; h < 2; h++) {
            const irc__v4f reach = {ch[4 * h].reach, ch[4 * h + 1].reach, ch[4 * h + 2].reach,
                                    ch[4 * h + 3].reach},
                           r = reach * vs + vf,
                           z = {part[2][h], part[2][h], part[2][h], part[2][h]}, d2 = q + z;
            const irc__v4i in = (reach >= zero) & (d2 <= r * r);
            mask |= (unsigned)__builtin_ia32_movmskps((irc__v4f)in) << (4 * h);
        }
    }
#else
#define IRC__CHILD(o)                                                         \
    do {                                                                      \
        float r = ch[o].reach * s + fixed, d2 = xy[(o) & 3] + part[2][(o) >> 2]; \
        mask |= ((unsigned)(ch[o].reach >= 0.0f) & (unsigned)(d2 <= r * r)) << (o); \
    } while (0)
    IRC__CHILD(0); IRC__CHILD(1); IRC__CHILD(2); IRC__CHILD(3);
    IRC__CHILD(4); IRC__CHILD(5); IRC__CHILD(6); IRC__CHILD(7);
#undef IRC__CHILD
#endif
    return mask;
}

/* The lowest set bit of a nonzero mask. */
static unsigned irc__first_bit(unsigned mask)
{
#if defined(__GNUC__) || defined(__clang__)
    return (unsigned)__builtin_ctz(mask);
#else
    unsigned b = 0;
    while (!(mask >> b & 1u))
        b++;
    return b;
#endif
}

/* Depth first, children in octant order, each node's list before its
 * children's (the order lookups sum in), with an explicit stack: a level's
 * block of children, the children still to enter and the octant taken
 * (6 bytes a level, in three arrays: no padding on a lookup's stack); the
 * current node's low corner is moved by its edge on the way down and back
 * on the way up. */
static uint32_t irc__descend(const irc_cache *c, const irc__probe *pr)
{
    uint32_t scanned = 0;
    uint32_t block[IRC__LEVELS + 1];
    uint8_t mask[IRC__LEVELS + 1], octs[IRC__LEVELS + 1];
    const irc__node *nodes = irc__nodes(c);
    int64_t lo[3] = {0, 0, 0};
    float r3[3];
    irc__steps st;
    int top = 0, i;
    irc__rel(pr, lo, 0, r3);
    if (nodes[0].head != IRC__NIL)
        scanned += irc__scan_homes(c, nodes[0].head, irc__steps_of(r3, 0, pr, &st), pr);
    if (!nodes[0].child)
        return scanned;
    block[0] = nodes[0].child;
    mask[0] = (uint8_t)irc__children(c, &nodes[0], 0, r3, pr);
    for (;;) {
        /* The children of mask[top] lie at depth top + 1. */
        const int64_t edge = (int64_t)1 << (IRC__FX - 1 - top);
        const irc__node *n;
        unsigned oct;
        if (!mask[top]) {
            if (top == 0)
                return scanned;
            top--;
            for (i = 0; i < 3; i++)
                lo[i] -= (octs[top] >> i & 1) ? edge * 2 : 0;
            continue;
        }
        oct = irc__first_bit(mask[top]);
        mask[top] = (uint8_t)(mask[top] & ~(1u << oct));
        n = &nodes[block[top] + oct];
        if (n->head == IRC__NIL && !n->child)
            continue;
        for (i = 0; i < 3; i++)
            lo[i] += (oct >> i & 1) ? edge : 0;
        irc__rel(pr, lo, top + 1, r3);
        if (n->head != IRC__NIL)
            scanned += irc__scan_homes(c, n->head, irc__steps_of(r3, top + 1, pr, &st), pr);
        IRC_ASSERT(!n->child || top < IRC__LEVELS);
        if (n->child && top < IRC__LEVELS) {
            octs[top] = (uint8_t)oct;
            top++;
            block[top] = n->child;
            mask[top] = (uint8_t)irc__children(c, n, top, r3, pr);
        } else {
            for (i = 0; i < 3; i++)
                lo[i] -= (oct >> i & 1) ? edge : 0;
        }
    }
}

/* What the walk relies on of a root, set or not (index.c's fitting and
 * growth keep it): a power-of-two half edge h no smaller than 2^-99 (the fit's floor
 * of 1e-30), a centre within 33 h of the origin (h >= |centre| / 32 when
 * fitted, half that ratio after each growth), and, below 2^100, a low
 * centre and low corner that are floats (a few bits over h's grid). */
int irc__root_ok(const double c[3], double h)
{
    int e, i;
    if (!(h >= 0x1p-99 && h <= 0x1p99) || IRC_FREXP(h, &e) != 0.5)
        return 0;
    for (i = 0; i < 3; i++) {
        const double lo = c[i] - h;
        if (!(IRC_FABS(c[i]) <= 33.0 * h) || (double)(float)lo != lo ||
            (double)(float)c[i] != c[i])
            return 0;
    }
    return 1;
}

int irc__index_root_sane(const irc_cache *c)
{
    const irc__state *h = irc__st(c);
    return irc__root_ok(h->root_c, h->root_h);
}

/* A lookup's walk: the lists of the nodes that hold the point, root first
 * (the order lookups sum in); a point outside the root meets the root's
 * list alone. */
static uint32_t irc__path(const irc_cache *c, const irc__probe *pr)
{
    const irc__node *nodes = irc__nodes(c), *n = &nodes[0];
    const int inside = ((pr->p[0] | pr->p[1] | pr->p[2]) >> IRC__FX) == 0;
    uint32_t scanned = 0;
    int d;
    for (d = 0;; d++) {
        const int sh = IRC__FX - 1 - d;
        if (n->head != IRC__NIL) {
            /* the node's low corner: the point's bits above its edge */
            const int64_t keep = ~(((int64_t)2 << sh) - 1);
            int64_t lo[3];
            float r3[3];
            irc__steps st;
            lo[0] = pr->p[0] & keep;
            lo[1] = pr->p[1] & keep;
            lo[2] = pr->p[2] & keep;
            if (!inside)
                lo[0] = lo[1] = lo[2] = 0;
            irc__rel(pr, lo, d, r3);
            scanned += irc__scan(c, n->head, irc__steps_of(r3, d, pr, &st), pr);
        }
        if (!n->child || !inside || d >= IRC__LEVELS)
            return scanned;
        n = &nodes[n->child + ((unsigned)(pr->p[0] >> sh & 1) | (unsigned)(pr->p[1] >> sh & 1) << 1 |
                               (unsigned)(pr->p[2] >> sh & 1) << 2)];
    }
}

uint32_t irc__index_query(const irc_cache *c, const float p[3], irc__visit_fn fn, void *ud)
{
    irc__probe pr;
    if (!irc__st(c)->root_set)
        return 0;
    irc__probe_set(c, p, -1.0f, 1.0f, fn, ud, &pr);
    return irc__path(c, &pr);
}

/* range >= 0: records within range of p; range < 0: records whose radius
 * R_i (reach / a) may hold p. */
void irc__index_range(const irc_cache *c, const float p[3], float range, irc__visit_fn fn,
                      void *ud)
{
    irc__probe pr;
    if (!irc__st(c)->root_set)
        return;
    irc__probe_set(c, p, range >= 0.0f ? range : -1.0f, 1.0f / c->reach_a, fn, ud, &pr);
    (void)irc__descend(c, &pr);
}
