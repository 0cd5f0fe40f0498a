/*
 * weight.c -- whether a record counts at a query, with what weight, and the
 * value it extrapolates there.
 */
#include "cache.h"

/* A record in front of the query's surface by more than this fraction of
 * its radius is rejected: relative to R_i so the test does not change with
 * the scene's units. */
#define IRC__BEHIND_TOL 0.05
/* Cap on a weight: a query exactly on a record gives 1/0. */
#define IRC__W_MAX 1e6

/* A guard nibble as the inverse of the distance it records, in reaches:
 * 0 for nothing seen, 15/(15 - v) else (v = 15, a hit at the record
 * itself, as 1/30 of the reach). */
static double irc__guard_inv(uint64_t g, int sector)
{
    uint32_t v = (uint32_t)(g >> (4 * sector)) & 15u;
    return v == 0 ? 0.0 : v == 15 ? 30.0 : 15.0 / (15.0 - v);
}

/* Whether the leak guard rejects a lookup at offset (dx, dy, dz) and t of
 * the reach from the record.  Each sector's nibble stands for the
 * direction at its centre, and the inverse distance is interpolated
 * between the two nearest centres: a straight wall's is a cosine of the
 * angle, which the sectors' minimum would cut short along the wall (a
 * record 10 from a wall would serve only 26 along it). */
static int irc__guarded(const irc__rec *r, uint32_t off, const float ni[3], double dx,
                        double dy, double dz, double t)
{
    uint64_t g;
    double nd[3], t1[3], t2[3], x, y, u, f;
    int i0;
    uint64_t top = 0;
    IRC_MEMCPY(&g, (const unsigned char *)r + off, sizeof g);
    if (!g || t <= 0.0)
        return 0;
    /* Most lookups lie well inside the nearest hit: no frame, no atan2. */
    for (i0 = 0; i0 < 16; i0++)
        if ((g >> (4 * i0) & 15u) > top)
            top = g >> (4 * i0) & 15u;
    if (t * irc__guard_inv(top, 0) <= 1.0)
        return 0;
    nd[0] = ni[0]; nd[1] = ni[1]; nd[2] = ni[2];
    irc__frame(nd, t1, t2);
    x = dx * t1[0] + dy * t1[1] + dz * t1[2];
    y = dx * t2[0] + dy * t2[1] + dz * t2[2];
    u = IRC_ATAN2(y, x) * (8.0 / IRC_PI) + 15.5; /* sector centres at whole u */
    i0 = (int)u;
    f = u - i0;
    return t * ((1.0 - f) * irc__guard_inv(g, i0 % 16) + f * irc__guard_inv(g, (i0 + 1) % 16)) >
           1.0;
}

/* Ward-Heckbert weight w = 1 / (|p - p_i|/R_i + sqrt(1 - n.n_i)), accepted
 * when w > 1/a.  n must be unit length.  Returns 1 and sets *w and the
 * record's decoded normal ni when the record counts, else 0. */
int irc__weigh(const irc_cache *c, const irc__rec *r, const float p[3],
               const float n[3], double *w, float ni[3])
{
    const double a = c->cfg.accuracy, rad = r->r;
    double dx = (double)p[0] - r->p[0], dy = (double)p[1] - r->p[1],
           dz = (double)p[2] - r->p[2];
    double d2 = dx * dx + dy * dy + dz * dz, nn, e;
    if (d2 >= a * a * rad * rad || r->n == IRC__FREE)
        return 0;
    irc__oct_decode(r->n, ni);
    nn = (double)n[0] * ni[0] + (double)n[1] * ni[1] + (double)n[2] * ni[2];
    if (nn <= 0.0)
        return 0;
    if (0.5 * (dx * (n[0] + ni[0]) + dy * (n[1] + ni[1]) + dz * (n[2] + ni[2])) <
        -IRC__BEHIND_TOL * rad)
        return 0;
    if (c->off_a) {
        /* An ellipse (Schwarzhaupt et al. 2012): the distance along the
         * major axis u over R, the rest over the minor radius q R, so a
         * disk (q = 1) is the plain distance. */
        const irc__aniso *an = (const irc__aniso *)(const void *)((const unsigned char *)r +
                                                                  c->off_a);
        if (an->q < 1.0f) {
            float u[3];
            double du;
            irc__oct_decode(an->axis, u);
            du = dx * u[0] + dy * u[1] + dz * u[2];
            d2 = du * du + (d2 - du * du) / ((double)an->q * an->q);
            if (d2 >= a * a * rad * rad)
                return 0;
        }
    }
    e = IRC_SQRT(d2) / rad;
    if (c->off_g && irc__guarded(r, c->off_g, ni, dx, dy, dz, e / a))
        return 0;
    e += IRC_SQRT(nn < 1.0 ? 1.0 - nn : 0.0);
    if (!(e < a))
        return 0;
    *w = e > 1.0 / IRC__W_MAX ? 1.0 / e : IRC__W_MAX;
    return 1;
}

/* 2^ex[ch] built from its bits: exact, no libm call per record. */
double irc__grad_scale(const irc__grad *g, int ch)
{
    uint64_t bits = (uint64_t)(g->ex[ch] + 1023) << 52;
    double s;
    IRC_MEMCPY(&s, &bits, sizeof s);
    return s;
}

static double irc__grad_dot(const irc__grad *g, int ch, double a, double b)
{
    return (g->g[2 * ch] * a + g->g[2 * ch + 1] * b) * irc__grad_scale(g, ch);
}

/* E_i + (p - p_i).grad_t + (n_i x n).grad_r, each gradient stored in the
 * tangent frame of the decoded normal, clamped at 0 per channel. */
void irc__extrapolate(const irc_cache *c, const irc__rec *r, const float ni[3],
                      const float p[3], const float n[3], double out[3])
{
    const unsigned char *b = (const unsigned char *)r;
    double t1[3], t2[3], nd[3];
    int ch;
    for (ch = 0; ch < 3; ch++)
        out[ch] = r->e[ch];
    if (!c->off_t && !c->off_r)
        return;
    nd[0] = ni[0]; nd[1] = ni[1]; nd[2] = ni[2];
    irc__frame(nd, t1, t2);
    if (c->off_t) {
        const irc__grad *g = (const irc__grad *)(const void *)(b + c->off_t);
        double d[3], da, db;
        d[0] = (double)p[0] - r->p[0];
        d[1] = (double)p[1] - r->p[1];
        d[2] = (double)p[2] - r->p[2];
        da = irc__dot3d(d, t1);
        db = irc__dot3d(d, t2);
        for (ch = 0; ch < 3; ch++)
            out[ch] += irc__grad_dot(g, ch, da, db);
    }
    if (c->off_r) {
        const irc__grad *g = (const irc__grad *)(const void *)(b + c->off_r);
        double q[3], x[3], da, db;
        q[0] = n[0]; q[1] = n[1]; q[2] = n[2];
        irc__cross3d(nd, q, x);
        da = irc__dot3d(x, t1);
        db = irc__dot3d(x, t2);
        for (ch = 0; ch < 3; ch++)
            out[ch] += irc__grad_dot(g, ch, da, db);
    }
    for (ch = 0; ch < 3; ch++)
        if (!(out[ch] > 0.0))
            out[ch] = 0.0;
}
