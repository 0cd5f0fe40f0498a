/*
 * weight.c -- whether a record counts at a query, with what weight, and the
 * value it extrapolates there.
 */
#include "../block/form.h"
#include "../block/octa.h"
#include "estimator.h"
#include "../sample/sampler.h"
#include "weight.h"

/* A square root rounded to float.  Where float is evaluated wider
 * (FLT_EVAL_METHOD 2: x87) sqrtf may hand back its wide result (glibc's
 * i386 sqrtf does), which the compiler takes for a float and rounds only
 * where it happens to spill it: the plain and the fused weigh paths would
 * then differ in the weight's last bit.  The volatile store rounds it at
 * one place; elsewhere it compiles to the plain call. */
static inline float irc__sqrtf(float x)
{
#if FLT_EVAL_METHOD != 0
    volatile float r = IRC_SQRTF(x);
    return r;
#else
    return IRC_SQRTF(x);
#endif
}

/* A record in front of the query's surface by more than this fraction of
 * its radius is rejected: relative to R_i so the test does not change with
 * the scene's units. */
#define IRC__BEHIND_TOL 0.05f
/* Cap on a weight: a query exactly on a record gives 1/0. */
#define IRC__W_MAX 1e6f

#ifndef IRC_NO_GUARD
/* A guard nibble as the inverse of the distance it records, in reaches:
 * 0 for nothing seen, 15/(15 - v) else (v = 15, a hit at the record
 * itself, as 1/30 of the reach). */
static float irc__guard_inv(uint64_t g, int sector)
{
    uint32_t v = (uint32_t)(g >> (4 * sector)) & 15u;
    return v == 0 ? 0.0f : v == 15 ? 30.0f : 15.0f / (15.0f - v);
}

/* Whether the leak guard rejects a lookup at offset (dx, dy, dz) and t of
 * the reach from the record.  Each sector's nibble stands for the
 * direction at its centre, and the inverse distance is interpolated
 * between the two nearest centres: a straight wall's is a cosine of the
 * angle, which the sectors' minimum would cut short along the wall (a
 * record 10 from a wall would serve only 26 along it). */
static int irc__guarded(const irc__rec *r, uint32_t off, const float ni[3], float dx,
                        float dy, float dz, float t)
{
    uint64_t g;
    float t1[3], t2[3], x, y, u, f;
    int i0;
    uint64_t top = 0;
    IRC_MEMCPY(&g, (const unsigned char *)r + off, sizeof g);
    if (!g || t <= 0.0f)
        return 0;
    /* Most lookups lie well inside the nearest hit: no frame, no atan2. */
    for (i0 = 0; i0 < 16; i0++)
        if ((g >> (4 * i0) & 15u) > top)
            top = g >> (4 * i0) & 15u;
    if (t * irc__guard_inv(top, 0) <= 1.0f)
        return 0;
    irc__frame(ni, t1, t2);
    x = dx * t1[0] + dy * t1[1] + dz * t1[2];
    y = dx * t2[0] + dy * t2[1] + dz * t2[2];
    u = IRC_ATAN2F(y, x) * (8.0f / IRC_PI) + 15.5f; /* sector centres at whole u */
    i0 = (int)u;
    f = u - i0;
    return t * ((1.0f - f) * irc__guard_inv(g, i0 % 16) + f * irc__guard_inv(g, (i0 + 1) % 16)) >
           1.0f;
}

#endif

/* Whether a record at offset d = p - p_i, its decoded normal ni, may
 * serve a query with normal n: facing it, and not in front of its surface
 * by more than IRC__BEHIND_TOL of R_i. */
IRC__PER_RECORD int irc__faces(const float d[3], const float n[3], const float ni[3], float rad)
{
    if (n[0] * ni[0] + n[1] * ni[1] + n[2] * ni[2] <= 0.0f)
        return 0;
    return !(0.5f * (d[0] * (n[0] + ni[0]) + d[1] * (n[1] + ni[1]) + d[2] * (n[2] + ni[2])) <
             -IRC__BEHIND_TOL * rad);
}

/* sqrt(1 - n.n_i) as |n - n_i|/sqrt(2), equal for unit normals: in float,
 * 1 - n.n_i of nearly equal normals is all rounding (an ulp of n moved the
 * weight by 3e-4), the difference is not. */
IRC__PER_RECORD float irc__normal_term(const float n[3], const float ni[3])
{
    const float ex = n[0] - ni[0], ey = n[1] - ni[1], ez = n[2] - ni[2];
    return irc__sqrtf(0.5f * (ex * ex + ey * ey + ez * ez));
}

float irc__biweight(float t)
{
    const float u = 1.0f - t * t;
    return u * u;
}

/* The weight of a record at Ward distance e (< reach_a).  Ward-Heckbert's
 * 1/e, capped; or, when lookups blend wider than they place
 * (cfg.irr.blend > 1), the biweight (1 - t^2)^2 of t = e / (blend a):
 * bounded where 1/e is not, so a point next to one record still averages
 * its neighbours' (Ward's weight hands the nearest record nearly all of
 * it), and zero at the reach's edge, so no pixel jumps where a record
 * starts to count. */
static inline float irc__weight_of(const irc_cache *c, float e)
{
    if (c->w_inner > 0.0f)
        return irc__biweight(e / c->reach_a);
    return e > 1.0f / IRC__W_MAX ? 1.0f / e : IRC__W_MAX;
}

/* Ward-Heckbert weight w = 1 / (|p - p_i|/R_i + sqrt(1 - n.n_i)), accepted
 * when w > 1/a (a: the lookup's reach over R, reach_a; blended lookups
 * weigh with irc__weight_of).  n must be unit length.  Returns 1 and sets
 * *w and the record's decoded normal ni when the record counts, else 0. */
int irc__weigh(const irc_cache *c, const irc__rec *r, const float p[3],
               const float n[3], int shaped, float *w, float ni[3])
{
    const float a = c->reach_a, rad = r->r;
    const float d[3] = {p[0] - r->p[0], p[1] - r->p[1], p[2] - r->p[2]};
    float d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], e;
    if (!(d2 < a * a * rad * rad || d2 == 0.0f) || r->n == IRC__FREE)
        return 0; /* its own point always (irc__within_reach) */
    irc__oct_decode_inline(r->n, ni);
    if (!irc__faces(d, n, ni, rad))
        return 0;
    if (shaped && c->off[IRC__P_ELLIPSE]) {
        /* An ellipse (Schwarzhaupt et al. 2012): the distance along the
         * major axis u over R, the rest over the minor radius q R, so a
         * disk (q = 1) is the plain distance. */
        const irc__aniso *an = (const irc__aniso *)(const void *)((const unsigned char *)r +
                                                                  c->off[IRC__P_ELLIPSE]);
        if (an->q < 1.0f) {
            float u[3];
            float du;
            irc__oct_decode(an->axis, u);
            du = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
            d2 = du * du + (d2 - du * du) / (an->q * an->q);
            if (!(d2 < a * a * rad * rad || d2 == 0.0f))
                return 0;
        }
    }
    e = irc__sqrtf(d2) / rad;
#ifndef IRC_NO_GUARD
    if (shaped && c->off[IRC__P_GUARD] &&
        irc__guarded(r, c->off[IRC__P_GUARD], ni, d[0], d[1], d[2], e / a))
        return 0;
#endif
    e += irc__normal_term(n, ni);
    if (!(e < a))
        return 0;
    *w = irc__weight_of(c, e);
    return 1;
}

/* 2^ex[ch] built from its bits: exact, no libm call per record.  ex is
 * at least -128, below float's normal range (2^-126): those two are
 * denormals, still exact. */
float irc__grad_scale(const irc__grad *g, int ch)
{
    const int e = g->ex[ch];
    uint32_t bits = e >= -126 ? (uint32_t)(e + 127) << 23 : 1u << (e + 149);
    float s;
    IRC_MEMCPY(&s, &bits, sizeof s);
    return s;
}

static float irc__grad_dot(const irc__grad *g, int ch, float a, float b)
{
    return (g->g[2 * ch] * a + g->g[2 * ch + 1] * b) * irc__grad_scale(g, ch);
}

/* E_i + d.grad_t + (n_i x n).grad_r at offset d = p - p_i, each gradient
 * stored in the tangent frame of the decoded normal, clamped at 0 per
 * channel. */
IRC__PER_RECORD void irc__extrapolate_at(const irc_cache *c, const irc__rec *r,
                                          const float ni[3], const float d[3],
                                          const float n[3], float out[3])
{
    const unsigned char *b = (const unsigned char *)r;
    const uint32_t ot = c->off[IRC__P_GRAD_T], orot = c->off[IRC__P_GRAD_R];
    float t1[3], t2[3];
    int ch;
    for (ch = 0; ch < 3; ch++)
        out[ch] = r->e[ch];
    if (!ot && !orot)
        return;
    irc__frame(ni, t1, t2);
    if (ot) {
        const irc__grad *g = (const irc__grad *)(const void *)(b + ot);
        const float da = irc__dot3(d, t1), db = irc__dot3(d, t2);
        for (ch = 0; ch < 3; ch++)
            out[ch] += irc__grad_dot(g, ch, da, db);
    }
    if (orot) {
        const irc__grad *g = (const irc__grad *)(const void *)(b + orot);
        float x[3], da, db;
        irc__cross3(ni, n, x);
        da = irc__dot3(x, t1);
        db = irc__dot3(x, t2);
        for (ch = 0; ch < 3; ch++)
            out[ch] += irc__grad_dot(g, ch, da, db);
    }
    for (ch = 0; ch < 3; ch++)
        if (!(out[ch] > 0.0f))
            out[ch] = 0.0f;
}

void irc__extrapolate(const irc_cache *c, const irc__rec *r, const float ni[3],
                      const float p[3], const float n[3], float out[3])
{
    const float d[3] = {p[0] - r->p[0], p[1] - r->p[1], p[2] - r->p[2]};
    irc__extrapolate_at(c, r, ni, d, n, out);
}

/* irc__within_reach, irc__weigh and irc__extrapolate in one, for records
 * with neither ellipse nor leak guard: the same operations in the same
 * order, so the same weight and value to the bit, without three calls,
 * the distance taken twice and the normal decoded out of line.  Returns
 * the weight, 0 for a record that does not count; out gets its value. */
float irc__weigh_extrapolate(const irc_cache *c, const irc__rec *r, const float p[3],
                             const float n[3], float out[3])
{
    const float a = c->reach_a, rad = r->r, ra = irc__reach(c, rad);
    const float d[3] = {p[0] - r->p[0], p[1] - r->p[1], p[2] - r->p[2]};
    const float d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    float ni[3], e;
    if (!((d2 < ra * ra && d2 < a * a * rad * rad) || d2 == 0.0f) || r->n == IRC__FREE)
        return 0.0f;
    irc__oct_decode_inline(r->n, ni);
    if (!irc__faces(d, n, ni, rad))
        return 0.0f;
    /* two statements, as irc__weigh's: where float is evaluated wider the
     * assignment rounds the distance term, and one expression would not */
    e = irc__sqrtf(d2) / rad;
    e += irc__normal_term(n, ni);
    if (!(e < a))
        return 0.0f;
    irc__extrapolate_at(c, r, ni, d, n, out);
    return irc__weight_of(c, e);
}

/* The record's derivatives of its extrapolated value val (irc__extrapolate's)
 * blended into running means with factor f (m += f (v - m)): g->dp[ch]
 * along p (grad_t itself) and g->dn[ch] along n (grad_r x n_i, since (n_i
 * x n).grad_r = n.(grad_r x n_i)); a channel clamped at 0 blends in
 * zeros.  The means live in the caller's answer, the derivatives are
 * made one at a time: the lookup's stack stays within make size's bound. */
void irc__extrapolate_grad(const irc_cache *c, const irc__rec *r, const float ni[3],
                           const float val[3], float f, irc_gradient *g)
{
    const unsigned char *b = (const unsigned char *)r;
    float t1[3], t2[3], v[3];
    int ch, k;
    irc__frame(ni, t1, t2);
    for (ch = 0; ch < 3; ch++) {
        const int live = val[ch] > 0.0f;
        for (k = 0; k < 3; k++) {
            v[k] = c->off[IRC__P_GRAD_T] && live ? irc__grad_dot((const irc__grad *)(const void *)(b + c->off[IRC__P_GRAD_T]),
                                                    ch, t1[k], t2[k])
                                    : 0.0f;
            g->dp[ch][k] += f * (v[k] - g->dp[ch][k]);
        }
        for (k = 0; k < 3; k++)
            v[k] = c->off[IRC__P_GRAD_R] && live ? irc__grad_dot((const irc__grad *)(const void *)(b + c->off[IRC__P_GRAD_R]),
                                                    ch, t1[k], t2[k])
                                    : 0.0f;
        for (k = 0; k < 3; k++) /* (v x n_i)[k] */
            g->dn[ch][k] += f * (v[(k + 1) % 3] * ni[(k + 2) % 3] -
                                 v[(k + 2) % 3] * ni[(k + 1) % 3] - g->dn[ch][k]);
    }
}
