/*
 * gradient.c -- the irradiance record's translational and rotational
 * gradients, both from one pass over the strata.
 *
 * Every angle the two estimators need depends on the configuration only
 * (the strata's boundaries and centres), so the sines, cosines and row
 * weights sit in a table made once at irc_init (sample/grid.c): a
 * record costs no transcendental call here, one float division a stratum
 * (its inverse hit distance, shared by its two boundaries) and a few
 * multiply-adds.
 */
#include "../block/form.h"
#include "../sample/grid.h"
#include "../sample/sampler.h"
#include "estimator.h"

/* The row loops' lanes: four where the target has 4-wide SIMD, three on
 * a scalar FPU (irc__row_coeffs, irc__row_sum). */
#if defined(__SSE__) || defined(__ARM_NEON) || defined(__ALTIVEC__) || defined(__wasm_simd128__)
#define IRC__LANES 4
#else
#define IRC__LANES 3
#endif

static const float *irc__gtab_rows(const irc__grid *g)
{
    return g->tab + 4u * irc__pad4(g->nphi);
}

/* Inverse hit distances, one per stratum, into the slot: 0 for a ray that
 * escaped, NaN for a failed one (whose stratum then keeps NaN, below).
 * Float: the gradient is stored in 16-bit mantissas, and float division
 * is the cheap one.  A denormal distance's inverse is capped, not inf. */
static void irc__inverse_depths(const irc__grid *g, const irc__sample *restrict s,
                                float *restrict inv)
{
    uint32_t i;
    int q;
    for (i = 0; i + 4 <= g->strata; i += 4) {
        const irc__sample *s4 = s + i;
        float x[4], *o4 = inv + i;
        for (q = 0; q < 4; q++)
            x[q] = 1.0f / s4[q].d;
        for (q = 0; q < 4; q++)
            o4[q] = x[q] > FLT_MAX ? FLT_MAX : x[q];
    }
    for (; i < g->strata; i++) {
        float x = 1.0f / s[i].d;
        inv[i] = x > FLT_MAX ? FLT_MAX : x;
    }
}

/* The weight of the boundary between a stratum and its neighbour, from
 * their inverse distances: 1/min(d_a, d_b) = max(1/d_a, 1/d_b).  The
 * neighbour's NaN (a failed ray) drops the boundary; the stratum's own NaN
 * keeps it at the neighbour's distance, with the failed stratum's filled-in
 * radiance (irradiance.c, irc__fill_failed) -- the rule this estimator has
 * always had.  An escaped pair (both 0) adds nothing. */
static inline float irc__grad_edge(float ia, float ib)
{
    float x = ia > ib ? ia : ib;
    return x > 0.0f ? x : 0.0f;
}

/* With visibility gradients, a boundary holding a silhouette is left to
 * visibility.c (its weight here is 0). */
typedef struct irc__vis_edges {
    const int32_t *eh, *ev;
    const irc__cross *x;
} irc__vis_edges;

static int irc__grad_silhouette(const irc__vis_edges *v, const int32_t *e, uint32_t i)
{
    return v->x && e[i] >= 0 && v->x[e[i]].ok;
}

/* The boundary weights of row j: below[k] for the boundary to row j - 1 (0
 * in row 0), left[k] for the boundary to column k - 1 (column N - 1 for
 * k = 0; left[N] repeats left[0]). */
static void irc__row_weights(const irc__grid *g, const irc__vis_edges *v, uint32_t j,
                             const float *restrict inv, float *restrict below,
                             float *restrict left)
{
    const uint32_t nphi = g->nphi;
    const float *rw = irc__gtab_rows(g);
    const float *ia = inv + j * nphi, *ib = j ? ia - nphi : ia;
    const float U = j ? rw[3 * j] : 0.0f, V = rw[3 * j + 1];
    uint32_t k;
    int q;
    for (k = 0; k + 4 <= nphi; k += 4) {
        const float *a4 = ia + k, *b4 = ib + k;
        float *w4 = below + k;
        for (q = 0; q < 4; q++)
            w4[q] = U * irc__grad_edge(a4[q], b4[q]);
    }
    for (; k < nphi; k++)
        below[k] = U * irc__grad_edge(ia[k], ib[k]);
    left[0] = V * irc__grad_edge(ia[0], ia[nphi - 1]);
    for (k = 1; k + 4 <= nphi; k += 4) {
        const float *a4 = ia + k;
        float *w4 = left + k;
        for (q = 0; q < 4; q++)
            w4[q] = V * irc__grad_edge(a4[q], a4[q - 1]);
    }
    for (; k < nphi; k++)
        left[k] = V * irc__grad_edge(ia[k], ia[k - 1]);
    if (v->x)
        for (k = 0; k < nphi; k++) {
            if (j > 0 && irc__grad_silhouette(v, v->ev, (j - 1) * nphi + k))
                below[k] = 0.0f;
            if (irc__grad_silhouette(v, v->eh, j * nphi + (k ? k - 1 : nphi - 1)))
                left[k] = 0.0f;
        }
    left[nphi] = left[0];
}

/* Each boundary adds w (L_a - L_b) times its direction (u_k for a row
 * boundary, v_k for a column boundary); gathered by stratum, a stratum's
 * radiance is multiplied by the signed sum of its own four boundaries'
 * weighted directions (alpha along t1, beta along t2): its boundary below
 * (+), the one above (the row above's below, -), its left boundary (+)
 * and its right one (column k + 1's left, -).  So a stratum costs one
 * multiply-add per channel and axis.  up: the row above's below weights
 * (zero in the top row). */
static void irc__row_coeffs(const irc__grid *g, const float *restrict below,
                            const float *restrict up, const float *restrict left,
                            float *restrict alpha, float *restrict beta)
{
    const uint32_t nphi = g->nphi, np = irc__pad4(nphi);
    const float *cc = g->tab, *sc = cc + np, *cb = sc + np, *sb = cb + np;
    uint32_t k;
    int q;
#if IRC__LANES == 4
    for (k = 0; k < nphi; k += 4) { /* the padding takes the last block's tail */
        const float *bw = below + k, *uw = up + k, *lw = left + k, *c0 = cc + k, *s0 = sc + k,
                    *c1 = cb + k, *s1 = sb + k;
        float *al = alpha + k, *be = beta + k;
        for (q = 0; q < 4; q++) {
            const float wu = bw[q] - uw[q];
            al[q] = wu * c0[q] - lw[q] * s1[q] + lw[q + 1] * s1[q + 1];
            be[q] = wu * s0[q] + lw[q] * c1[q] - lw[q + 1] * c1[q + 1];
        }
    }
#else
    /* A scalar FPU: column k + 1's left terms are carried to the next
     * column, two products a stratum fewer. */
    float ls = left[0] * sb[0], lc = left[0] * cb[0];
    (void)q;
    for (k = 0; k < nphi; k++) {
        const float wu = below[k] - up[k], ns = left[k + 1] * sb[k + 1],
                    nc = left[k + 1] * cb[k + 1];
        alpha[k] = wu * cc[k] - ls + ns;
        beta[k] = wu * sc[k] + lc - nc;
        ls = ns;
        lc = nc;
    }
#endif
}

/* One row's sums, a lane per channel.  A sample is 16 bytes (three
 * radiances and the distance): with 4-wide SIMD the loop runs four lanes
 * and the distance's rides along, computed and dropped; a scalar FPU (a
 * Cortex-M4F) computes every lane it is given, so there it runs three,
 * and the twelve sums stay in registers.  The radiances are taken
 * relative to ref (the mean): every sum here is one of radiance times
 * coefficients whose total is zero (over the sphere for the boundaries,
 * over each row for the cosines), so a constant changes nothing but would
 * cancel: in bench/records.c's scene the largest change against sums
 * in double was 1.5e-4 of the translational gradient's length (2.9e-4 of
 * the rotational's) without it, 1.6e-5 (1.1e-4) with it (bench/notes.md, "Where
 * the record time goes"). */
typedef struct irc__row_sums {
    float t1[4], t2[4]; /* translational, along t1 and t2 */
    float c[4], s[4];   /* the radiance times cos phi_b and sin phi_b */
} irc__row_sums;

static void irc__row_sum(const irc__grid *g, const irc__sample *a, const float *alpha,
                         const float *beta, const float ref[4], irc__row_sums *o)
{
    const uint32_t nphi = g->nphi, np = irc__pad4(nphi);
    const float *cb = g->tab + 2u * np, *sb = cb + np;
    float t1[4] = {0, 0, 0, 0}, t2[4] = {0, 0, 0, 0}, sc[4] = {0, 0, 0, 0},
          ss[4] = {0, 0, 0, 0};
    uint32_t k;
    int ch;
#if IRC__LANES == 4
    for (k = 0; k < nphi; k++) {
        float l[4];
        const float al = alpha[k], be = beta[k], ck = cb[k], sk = sb[k];
        IRC_MEMCPY(l, &a[k], sizeof l);
        for (ch = 0; ch < 4; ch++) {
            l[ch] -= ref[ch];
            t1[ch] += l[ch] * al;
            t2[ch] += l[ch] * be;
            sc[ch] += l[ch] * ck;
            ss[ch] += l[ch] * sk;
        }
    }
#else
    /* Three lanes written out: a compiler optimising for size keeps a loop
     * over them, and its sums in memory. */
#define IRC__LANE(ch)                                                         \
    do {                                                                      \
        const float l = a[k].l[ch] - ref[ch];                                 \
        t1[ch] += l * al;                                                     \
        t2[ch] += l * be;                                                     \
        sc[ch] += l * ck;                                                     \
        ss[ch] += l * sk;                                                     \
    } while (0)
    (void)ch;
    for (k = 0; k < nphi; k++) {
        const float al = alpha[k], be = beta[k], ck = cb[k], sk = sb[k];
        IRC__LANE(0);
        IRC__LANE(1);
        IRC__LANE(2);
    }
#undef IRC__LANE
#endif
    IRC_MEMCPY(o->t1, t1, sizeof t1);
    IRC_MEMCPY(o->t2, t2, sizeof t2);
    IRC_MEMCPY(o->c, sc, sizeof sc);
    IRC_MEMCPY(o->s, ss, sizeof ss);
}

/* gt: translational gradient (NULL: not wanted), gr: rotational (NULL: not
 * wanted), each in world space, per channel; mean: the mean radiance of
 * the samples.  Translational: the radiance
 * difference across every boundary between neighbouring strata times the
 * boundary's weight (the boundary between rows 0 and 1 included), summed
 * along each column's directions u_k = (cos phi_c, sin phi_c) and v_k =
 * (-sin phi_b, cos phi_b) in the frame t1, t2.  Rotational: grad_r =
 * integral of L(w) (n x w) dw with n x w = sin(theta) v(phi).  Rows are
 * taken top down, so that a row's boundary above is already known. */
void irc__gradients(const irc_cache *c, const irc__grid *g, const irc__sample *s,
                    const float mean[3], const float t1[3], const float t2[3], float gt[3][3],
                    float gr[3][3])
{
    const uint32_t m = g->m, nphi = g->nphi, np = irc__pad4(nphi);
    const float *rw = irc__gtab_rows(g);
    float *inv = irc__slot_inv(c, s), *below = inv + g->strata, *up = below + np,
          *left = up + np, *alpha = left + np, *beta = alpha + np, *t;
    float tr[3][2] = {{0, 0}, {0, 0}, {0, 0}}, ro[3][2] = {{0, 0}, {0, 0}, {0, 0}};
    irc__vis_edges v = {NULL, NULL, NULL};
    irc__row_sums o;
    const float ref[4] = {mean[0], mean[1], mean[2], 0.0f};
    uint32_t j;
    int ch, i;
    if (c->cfg.features & IRC_FEATURE_VISIBILITY) {
        v.eh = irc__slot_edges(c, s);
        v.ev = v.eh + c->strata;
        v.x = irc__slot_cross(c, s);
    }
    irc__inverse_depths(g, s, inv);
    IRC_MEMSET(below, 0, 5u * np * sizeof(float)); /* the padding included */
    for (j = m; j-- > 0;) {
        irc__row_weights(g, &v, j, inv, below, left);
        irc__row_coeffs(g, below, up, left, alpha, beta);
        irc__row_sum(g, s + j * nphi, alpha, beta, ref, &o);
        t = up; /* this row's boundaries below are the next row's above */
        up = below;
        below = t;
        for (ch = 0; ch < 3; ch++) {
            tr[ch][0] += o.t1[ch];
            tr[ch][1] += o.t2[ch];
            ro[ch][0] += rw[3 * j + 2] * o.c[ch];
            ro[ch][1] += rw[3 * j + 2] * o.s[ch];
        }
    }
    for (ch = 0; ch < 3; ch++) {
        const float cm1 = rw[3 * m], sd = rw[3 * m + 1];
        const float a = cm1 * ro[ch][0] - sd * ro[ch][1], b = sd * ro[ch][0] + cm1 * ro[ch][1];
        for (i = 0; i < 3; i++) {
            if (gt)
                gt[ch][i] = tr[ch][0] * t1[i] + tr[ch][1] * t2[i];
            if (gr)
                gr[ch][i] = a * t1[i] + b * t2[i];
        }
    }
}
