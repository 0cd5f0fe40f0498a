/*
 * shgrad.c -- the samples of an SH record projected onto the real SH basis,
 * and the coefficients' translational gradients from the same samples
 * (SH-gradient paper, Eq. 6-13), with the silhouette singularity of the
 * surface-integral form taken over the strata grid.
 */
#include "../block/form.h"
#include "../sample/sampler.h"
#include "../sample/strata.h"
#include "shrec.h"

#ifndef IRC_NO_SH

/* The stratum grid the samples came from: one hemisphere (a surface
 * record) or two glued at the equator with the same azimuths (a free
 * point), rows of equal solid angle, cos(theta_j) = 1 - j/M. */
typedef struct irc__shgrid {
    const irc__sample *s;
    const float *dir, *nrm;
    const float *axis[2], *t1, *t2;
    uint32_t m, n, halves;
} irc__shgrid;

static int irc__hit(const irc__sample *x)
{
    return x->d == x->d && x->d < HUGE_VALF;
}

static irc__seen irc__shg_seen(const irc__shgrid *g, uint32_t i)
{
    return irc__seen_at(g->dir, g->nrm, i, g->s[i].d);
}

static int irc__shg_continuous(const irc__shgrid *g, uint32_t a, uint32_t b)
{
    const irc__seen va = irc__shg_seen(g, a), vb = irc__shg_seen(g, b);
    return irc__continuous(&va, &vb);
}

/* The depth where the surface of sample i ends, past i on the side away
 * from its neighbour o (strata.c's rule; without o, i's own). */
static float irc__shg_silhouette(const irc__shgrid *g, uint32_t i, int64_t o)
{
    const irc__seen e = irc__shg_seen(g, i);
    irc__seen in;
    float d;
    if (o < 0)
        return e.d;
    in = irc__shg_seen(g, (uint32_t)o);
    (void)irc__silhouette_depth(&e, &in, &d);
    return d;
}

/* The singular part of Eq. 11: with dA = dw r^2/(n.w) (Eq. 13) the term
 * y_i grad g / g carries n/(n.w), unbounded at silhouettes (1/sqrt of the
 * angle to them); sampled, it makes the gradient converge as the fourth
 * root of the ray count.  Its tangential part is -grad_w(1/r), so the
 * integral of -L y_i grad_w(1/r) is taken over the grid instead: through
 * each edge between strata, the difference of 1/r times the edge's length
 * and unit normal, shared by the two samples (their L y_i is applied by
 * the caller).  An edge across a silhouette is no difference of one
 * surface: the nearer side's 1/r runs on to the silhouette's depth
 * (irc__shg_silhouette), the farther side's surface continues behind.
 * w_out gets the vector for sample i. */
static void irc__shg_edge(const irc__shgrid *g, uint32_t i, int64_t o, int64_t back,
                      float len, const float nu[3], float w_out[3])
{
    float f, k;
    int c;
    if (o < 0 || !irc__hit(&g->s[i]) || g->s[o].d != g->s[o].d)
        return;
    if (irc__shg_continuous(g, i, (uint32_t)o))
        f = 0.5f * (1.0f / g->s[o].d - 1.0f / g->s[i].d);
    else if (!(g->s[o].d > g->s[i].d))
        return;
    else
        f = 1.0f / irc__shg_silhouette(g, i, back) - 1.0f / g->s[i].d;
    k = f * len;
    for (c = 0; c < 3; c++)
        w_out[c] += k * nu[c];
}

/* Sample index of row j (of rows 0..2M-1 counted from the first
 * hemisphere's pole across the equator), column k; -1 off the grid.  Once
 * per row: it divides. */
static int64_t irc__shg_at(const irc__shgrid *g, int64_t j, uint32_t k)
{
    uint32_t h;
    if (j < 0 || j >= (int64_t)(g->halves * g->m))
        return -1;
    h = (uint32_t)(j / g->m);
    j %= g->m;
    if (h)
        j = g->m - 1 - j;
    return (int64_t)h * g->m * g->n + j * g->n + k;
}

/* A row's geometry (cos theta at its two edges, their sines, its angular
 * height) and a column's (cos, sin of its left edge, centre, right edge):
 * the callers advance them by recurrence, so no stratum needs trig. */
typedef struct irc__shg_cell {
    float z0, z1, s0, s1, len;
    float cl, sl, cc, sc, cr, sr;
    const float *axis;
    int64_t row, up, dn; /* first sample of the row, of the rows toward the
                            pole and toward the horizon (-1: none) */
} irc__shg_cell;

/* The edge vector of the sample in column k of the row q describes. */
static void irc__edge_vector(const irc__shgrid *g, uint32_t k, const irc__shg_cell *q, float w[3])
{
    const float dphi = 2.0f * IRC_PI / g->n;
    const uint32_t i = (uint32_t)q->row + k, kl = k ? k - 1 : g->n - 1,
                   kr = k + 1 < g->n ? k + 1 : 0;
    const int64_t up = q->up < 0 ? -1 : q->up + k, dn = q->dn < 0 ? -1 : q->dn + k;
    float nu[3];
    int c;
    w[0] = w[1] = w[2] = 0.0f;
    /* Left and right: meridian edges, unit normals along -/+ e_phi. */
    for (c = 0; c < 3; c++)
        nu[c] = q->sl * g->t1[c] - q->cl * g->t2[c];
    if (g->n > 1)
        irc__shg_edge(g, i, q->row + kl, q->row + kr, q->len, nu, w);
    for (c = 0; c < 3; c++)
        nu[c] = -q->sr * g->t1[c] + q->cr * g->t2[c];
    if (g->n > 1)
        irc__shg_edge(g, i, q->row + kr, q->row + kl, q->len, nu, w);
    /* Toward the pole and toward the horizon (the other hemisphere's
     * equator row for a free point): arcs of constant theta. */
    for (c = 0; c < 3; c++)
        nu[c] = -(q->z0 * (q->cc * g->t1[c] + q->sc * g->t2[c]) - q->s0 * q->axis[c]);
    irc__shg_edge(g, i, up, dn, q->s0 * dphi, nu, w);
    for (c = 0; c < 3; c++)
        nu[c] = q->z1 * (q->cc * g->t1[c] + q->sc * g->t2[c]) - q->s1 * q->axis[c];
    irc__shg_edge(g, i, dn, up, q->s1 * dphi, nu, w);
    /* A hemisphere's surface integral (Eq. 11) ends at the horizon plane,
     * which moves with p along n: raised by h, it uncovers the strip of
     * surface below the new horizon, a solid angle h/r per unit of azimuth
     * at depth r (Leibniz's rule; tangential moves keep the plane).  So
     * the last row adds, along n, the arc's length over its depth; -L y_i
     * times it is d c_i/dn's share. */
    if (q->dn < 0 && g->halves == 1 && irc__hit(&g->s[i]))
        for (c = 0; c < 3; c++)
            w[c] += q->s1 * dphi / g->s[i].d * q->axis[c];
}

/* One sample's share of the coefficients and, with gradients, of Eq. 11
 * over the surface it hit, rewritten over solid angle with dA = dw r^2 /
 * (n.w) (Eq. 13): the regular part -dw L/r [grad_w y_i - 2 y_i w] here,
 * the singular part through the edge vector e (irc__shg_edge), -L y_i e.  w
 * is the stratum's direction, dw = 1 (the caller scales). */
static void irc__sh_add(const irc_cache *c, irc__shsum *a, const irc__sample *x,
                        const float w[3], const float *n, const float e[3])
{
    const int nc = (int)IRC__SH_N(c), nch = (int)IRC__SH_CH(c), bands = (int)c->cfg.sh.bands;
    const int grad = c->off[IRC__P_SH_GRAD] != 0;
    float y[IRC__NC], gy[IRC__NC][3], v[3 * IRC__NC], id;
    int ch, i, k;
    irc__sh_eval(bands, w, y, grad ? gy : NULL);
    for (ch = 0; ch < nch; ch++)
        for (i = 0; i < nc; i++)
            a->c[ch][i] += x->l[ch] * y[i];
    if (n)
        for (ch = 0; ch < 3; ch++)
            a->e[ch] += x->l[ch] * irc__dot3(w, n);
    if (!irc__hit(x))
        return;
    id = 1.0f / x->d;
    a->inv_d += id;
    if (!grad)
        return;
    /* One vector per sample, then a plain multiply-add per channel. */
    for (i = 0; i < nc; i++)
        for (k = 0; k < 3; k++)
            v[3 * i + k] = (gy[i][k] - 2.0f * y[i] * w[k]) * id + y[i] * e[k];
    for (ch = 0; ch < nch; ch++) {
        const float l = x->l[ch];
        for (i = 0; i < 3 * nc; i++)
            a->g[ch][i] -= l * v[i];
    }
}

static void irc__sh_accumulate(const irc_cache *c, const irc__shgrid *g, const float *n,
                               irc__shsum *a)
{
    const float dw = 2.0f * IRC_PI / c->strata, idw = 1.0f / dw, dphi = 2.0f * IRC_PI / g->n;
    const float cd = IRC_COSF(dphi), sd = IRC_SINF(dphi), ch = IRC_COSF(0.5f * dphi),
                 sh = IRC_SINF(0.5f * dphi);
    int64_t jj;
    uint32_t k;
    int q;
    for (jj = 0; jj < (int64_t)(g->halves * g->m); jj++) {
        const uint32_t j = jj < g->m ? (uint32_t)jj : g->m - 1 - (uint32_t)(jj - g->m);
        irc__shg_cell cell;
        cell.z0 = 1.0f - (float)j / g->m;
        cell.z1 = 1.0f - (j + 1.0f) / g->m;
        cell.s0 = IRC_SQRTF(1.0f - cell.z0 * cell.z0);
        cell.s1 = IRC_SQRTF(1.0f - cell.z1 * cell.z1);
        cell.len = IRC_ACOSF(cell.z1) - IRC_ACOSF(cell.z0);
        cell.cl = 1.0f;
        cell.sl = 0.0f;
        cell.axis = g->axis[jj < g->m ? 0 : 1];
        cell.row = irc__shg_at(g, jj, 0);
        cell.up = irc__shg_at(g, jj < g->m ? jj - 1 : jj + 1, 0);
        cell.dn = irc__shg_at(g, jj < g->m ? jj + 1 : jj - 1, 0);
        for (k = 0; k < g->n; k++) {
            const uint32_t i = (uint32_t)cell.row + k;
            float w[3], e[3] = {0, 0, 0};
            cell.cc = cell.cl * ch - cell.sl * sh;
            cell.sc = cell.sl * ch + cell.cl * sh;
            cell.cr = cell.cl * cd - cell.sl * sd;
            cell.sr = cell.sl * cd + cell.cl * sd;
            a->total++;
            if (g->s[i].d == g->s[i].d) {
                a->used++;
                for (q = 0; q < 3; q++)
                    w[q] = g->dir[3 * i + q];
                if (c->off[IRC__P_SH_GRAD]) {
                    irc__edge_vector(g, k, &cell, e);
                    for (q = 0; q < 3; q++)
                        e[q] *= idw;
                }
                irc__sh_add(c, a, &g->s[i], w, n, e);
            }
            cell.cl = cell.cr;
            cell.sl = cell.sr;
        }
    }
}

/* Samples one hemisphere (n given) or the sphere as two (n NULL: around
 * the world z axis, the lower one's frame the upper's with the axis
 * flipped, so columns meet at the equator) into a claimed slot and sums
 * them into *a. */
int irc__sh_sample(irc__call *k, irc__shsum *a)
{
    static const float up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
    irc_cache *c = k->c;
    const float *un = k->q.free ? NULL : k->q.n;
    float t1[3], t2[3];
    irc__shgrid g;
    irc__grid grid;
    uint32_t h;
    int st;
    g.s = (const irc__sample *)(const void *)k->slot;
    g.dir = irc__slot_dirs(c, g.s);
    g.nrm = irc__slot_normals(c, g.s);
    g.axis[0] = un ? un : up;
    g.axis[1] = down;
    g.t1 = t1;
    g.t2 = t2;
    g.m = c->cfg.strata_theta;
    g.n = c->cfg.strata_phi;
    g.halves = un ? 1u : 2u;
    irc__frame(g.axis[0], t1, t2);
    irc__grid_at(c, 0, &grid);
    for (h = 0; h < g.halves; h++) {
        st = irc__sample_hemisphere(k, &grid, g.axis[h], t1, t2, h * c->strata);
        if (st < 0)
            return st;
    }
    irc__sh_accumulate(c, &g, un, a);
    return IRC_OK;
}

#else /* IRC_NO_SH: SH records left out of the build (util.h) */

typedef int irc__no_shgrad; /* ISO C wants something in a file */

#endif
