/*
 * hessian.c -- the occlusion-aware Hessian of irradiance from the samples
 * a record already cast (Schwarzhaupt, Jensen and Jarosz 2012; the
 * per-edge closed forms as Radiance's ambcomp.c evaluates them), and the
 * eigen-decomposition of its tangent-plane part.
 *
 * The hit points of neighbouring strata span triangles; each triangle
 * shines with the radiance of its farthest vertex (a triangle across a
 * silhouette belongs to what lies behind), so E(x) ~ sum_T L_T F_T(x), and
 * the Hessian is sum_T L_T H F_T(x).  A triangle's form factor is the sum
 * over its edges of (n.c) I1/(2 pi) (Lambert's formula, c = r0 x r1), whose
 * second derivatives in x have the closed forms below.  No ray is cast.
 */
#include "cache.h"
#include "sampler.h"
#include "estimator.h"
#include "strata.h"

#ifndef IRC_NO_HESSIAN

/* Escaped rays get a hit point this many times the record's farthest hit
 * away: far enough that their triangles' derivatives vanish, finite so
 * that the edges along a silhouette against the sky are formed. */
#define IRC__FAR 1e3f
/* Black occluders: every triangle's radiance is lifted by this fraction of
 * the record's mean radiance, so a black blocker against a black wall
 * still bends E (Radiance's ambcomp.c adds 1%). */
#define IRC__FLOOR 0.01f

/* One edge r0 -> r1 (relative to x) of a triangle shining with l: adds
 * l H F_e to h (the per-edge closed forms of Schwarzhaupt et al. 2012,
 * as ambcomp.c names their terms: I1, I2, J2, I3, J3, K3, g, M). */
static void irc__edge_hessian(const float r0[3], const float r1[3], const float n[3],
                              const float l[3], float h[3][6])
{
    float e[3], c[3], nxe[3], g[3], m[6], d00, d11, ee, cc, er0, er1, cs, i1, i2, j2, i3, j3,
        k3, nc, f[6];
    int i, ch;
    for (i = 0; i < 3; i++)
        e[i] = r1[i] - r0[i];
    irc__cross3(r0, r1, c);
    cc = irc__dot3(c, c);
    ee = irc__dot3(e, e);
    d00 = irc__dot3(r0, r0);
    d11 = irc__dot3(r1, r1);
    /* Degenerate edges (a point, or collinear with x) carry no form factor. */
    if (!(cc > 1e-24f * d00 * d11) || !(ee > 0.0f))
        return;
    er0 = irc__dot3(e, r0);
    er1 = irc__dot3(e, r1);
    /* I1 = angle(r0, r1)/|c| = atan(x)/(x r0.r1), x = |c|/(r0.r1): the
     * grid's edges span a few degrees, where the series in x^2 is exact
     * to 1e-8 (x < 1/4) and needs no square root or arc function; wider
     * ones take atan2, which stays accurate where acos of the cosine
     * loses half its digits. */
    cs = irc__dot3(r0, r1);
    if (cs > 0.0f && cc < 0.0625f * cs * cs) {
        float x2 = cc / (cs * cs);
        i1 = (1.0f - x2 * (1.0f / 3 - x2 * (1.0f / 5 - x2 * (1.0f / 7 - x2 * (1.0f / 9 -
              x2 * (1.0f / 11 - x2 / 13)))))) / cs;
    } else
        i1 = IRC_ATAN2F(IRC_SQRTF(cc), cs) / IRC_SQRTF(cc);
    i2 = (er1 / d11 - er0 / d00 + ee * i1) / (2.0f * cc);
    j2 = (0.5f * (1.0f / d00 - 1.0f / d11) - er0 * i2) / ee;
    i3 = (er1 / (d11 * d11) - er0 / (d00 * d00) + 3.0f * ee * i2) / (4.0f * cc);
    j3 = (0.25f * (1.0f / (d00 * d00) - 1.0f / (d11 * d11)) - er0 * i3) / ee;
    k3 = (i2 - d00 * i3 - 2.0f * er0 * j3) / ee;
    for (i = 0; i < 3; i++)
        g[i] = i2 * r0[i] + j2 * e[i];
    /* M = I3 r0 r0^T + J3 (r0 e^T + e r0^T) + K3 e e^T, packed xx xy xz yy yz zz */
    {
        static const int a[6] = {0, 0, 0, 1, 1, 2}, b[6] = {0, 1, 2, 1, 2, 2};
        irc__cross3(n, e, nxe);
        nc = irc__dot3(n, c);
        for (i = 0; i < 6; i++) {
            m[i] = i3 * r0[a[i]] * r0[b[i]] + j3 * (r0[a[i]] * e[b[i]] + e[a[i]] * r0[b[i]]) +
                   k3 * e[a[i]] * e[b[i]];
            f[i] = (nxe[a[i]] * g[b[i]] + g[a[i]] * nxe[b[i]] +
                    nc * (4.0f * m[i] - (a[i] == b[i] ? i2 : 0.0f))) / IRC_PI;
        }
    }
    /* E = pi sum L_T F_T, and the closed forms give -H F_e (Radiance's
     * comp_hessian returns the same sign). */
    for (ch = 0; ch < 3; ch++)
        for (i = 0; i < 6; i++)
            h[ch][i] -= IRC_PI * l[ch] * f[i];
}

/* A vertex of the grid: its hit point relative to x. */
typedef struct irc__vtx {
    float r[3];
} irc__vtx;

/* The grid the vertices come from. */
typedef struct irc__mesh {
    const irc__sample *s;
    const float *dirs, *nrm;
    float *depth;           /* each vertex's depth, once (irc__depths) */
    uint32_t m, n;
    float far, fill, floor_l;
} irc__mesh;

static irc__seen irc__hess_seen(const irc__mesh *g, uint32_t i)
{
    return irc__seen_at(g->dirs, g->nrm, i, g->s[i].d);
}

/* A hit beside an escaped stratum lies inside a silhouette, nearer than
 * the silhouette itself when the blocker is curved: its depth is the one
 * strata.c's rule gives from its inner neighbour, across from the escaped
 * one; a polygon's edge keeps its depth. */
static float irc__hess_silhouette(const irc__mesh *g, uint32_t j, uint32_t k, float d)
{
    static const int dj[4] = {0, 0, 1, -1}, dk[4] = {1, -1, 0, 0};
    int q;
    for (q = 0; q < 4; q++) {
        const int64_t out = irc__strata_at(g->m, g->n, (int64_t)j + dj[q], (int64_t)k + dk[q]);
        if (out >= 0 && !(g->s[out].d < HUGE_VALF)) {
            const int64_t in = irc__strata_at(g->m, g->n, (int64_t)j - dj[q], (int64_t)k - dk[q]);
            const irc__seen e = irc__hess_seen(g, j * g->n + k);
            irc__seen inner;
            if (in < 0)
                return d;
            inner = irc__hess_seen(g, (uint32_t)in);
            (void)irc__silhouette_depth(&e, &inner, &d);
            return d;
        }
    }
    return d;
}

/* Escaped strata lie at far, failed ones at the harmonic mean distance. */
/* Every vertex's depth, once: each vertex is read by the three edges it
 * starts and the cells around it, some fifteen times. */
static void irc__depths(const irc__mesh *g)
{
    uint32_t j, k;
    for (j = 0; j < g->m; j++)
        for (k = 0; k < g->n; k++) {
            float d = g->s[j * g->n + k].d;
            if (d != d)
                d = g->fill;
            else if (!(d < HUGE_VALF))
                d = g->far;
            else {
                d = irc__hess_silhouette(g, j, k, d);
            }
            g->depth[j * g->n + k] = d;
        }
}

static void irc__vertex(const irc__mesh *g, uint32_t j, uint32_t k, irc__vtx *v)
{
    uint32_t i = j * g->n + k;
    float d = g->depth[i];
    int q;
    for (q = 0; q < 3; q++)
        v->r[q] = d * g->dirs[3 * i + q];
}

/* The radiance a triangle of strata a, b, c shines with: its farthest
 * vertex's. */
static const float *irc__shine(const irc__mesh *g, uint32_t a, uint32_t b, uint32_t c)
{
    const float *d = g->depth;
    return g->s[d[a] >= d[b] && d[a] >= d[c] ? a : d[b] >= d[c] ? b : c].l;
}

/* Cell (j, k) of the grid, between rows j and j + 1 and columns k and
 * k + 1, holds triangles T1 = (V(j,k), V(j,k+1), V(j+1,k)) and T2 =
 * (V(j+1,k+1), V(j+1,k), V(j,k+1)); their radiances, or NULL outside. */
static void irc__cell(const irc__mesh *g, int64_t j, uint32_t k, const float **l1,
                      const float **l2)
{
    uint32_t a, b, c, d;
    if (j < 0 || j + 1 >= (int64_t)g->m) {
        *l1 = *l2 = NULL;
        return;
    }
    a = (uint32_t)j * g->n + k;
    b = (uint32_t)j * g->n + (k + 1) % g->n;
    c = a + g->n;
    d = b + g->n;
    *l1 = irc__shine(g, a, b, c);
    *l2 = irc__shine(g, d, c, b);
}

/* An edge p0 -> p1 shared by a triangle that has it in this orientation
 * (radiance la) and one that has it reversed (lb): sum_T L_T H F_T sums
 * each edge once with weight la - lb, and edges inside a region of one
 * radiance drop out. */
static void irc__shared_edge(const irc__mesh *g, const irc__vtx *p0, const irc__vtx *p1,
                             const float *la, const float *lb, const float n[3],
                             float h[3][6])
{
    float l[3];
    int ch, any = 0;
    for (ch = 0; ch < 3; ch++) {
        l[ch] = (la ? la[ch] + g->floor_l : 0.0f) - (lb ? lb[ch] + g->floor_l : 0.0f);
        any |= l[ch] != 0.0f;
    }
    if (any)
        irc__edge_hessian(p0->r, p1->r, n, l, h);
}

/* The three edges vertex (j, k) starts: along its row to (j, k+1), the
 * diagonal (j, k+1) -> (j+1, k), and down its column (j+1, k) -> (j, k). */
static void irc__vertex_edges(const irc__mesh *g, uint32_t j, uint32_t k, const float n[3],
                              float h[3][6])
{
    const float *l1, *l2, *up2, *left1, *left2, *dummy;
    irc__vtx a, b, c;
    irc__cell(g, j, k, &l1, &l2);
    irc__cell(g, (int64_t)j - 1, k, &dummy, &up2);
    irc__cell(g, j, (k + g->n - 1) % g->n, &left1, &left2);
    irc__vertex(g, j, k, &a);
    irc__vertex(g, j, (k + 1) % g->n, &b);
    irc__shared_edge(g, &a, &b, l1, up2, n, h);
    if (j + 1 < g->m) {
        irc__vertex(g, j + 1, k, &c);
        irc__shared_edge(g, &b, &c, l1, l2, n, h);
        irc__shared_edge(g, &c, &a, l1, left2, n, h);
    }
}

/* The Hessian of E at the record, per channel, packed xx xy xz yy yz zz in
 * world space, from the samples and directions of one hemisphere (failed
 * strata carry the mean radiance and the mean hit distance). */
void irc__hessian(const irc_cache *c, const irc__sample *s, const float *dirs,
                  const float n[3], float h[3][6])
{
    const uint32_t m = c->cfg.strata_theta, nphi = c->cfg.strata_phi;
    float far = 0.0f, mean = 0.0f, inv = 0.0f;
    uint32_t i, j, k, hits = 0;
    irc__mesh g;
    IRC_MEMSET(h, 0, 3 * 6 * sizeof(float));
    for (i = 0; i < m * nphi; i++) {
        if (s[i].d == s[i].d && s[i].d < HUGE_VALF) {
            if (s[i].d > far)
                far = s[i].d;
            inv += 1.0f / s[i].d;
            hits++;
        }
        mean += (s[i].l[0] + s[i].l[1] + s[i].l[2]) / 3.0f;
    }
    if (hits == 0 || m < 2 || nphi < 3)
        return;
    g.s = s;
    g.dirs = dirs;
    g.nrm = irc__slot_normals(c, s);
    g.m = m;
    g.n = nphi;
    g.fill = hits / inv;
    g.far = far * IRC__FAR;
    g.floor_l = IRC__FLOOR * mean / (m * nphi);
    g.depth = irc__slot_depths(c, s);
    irc__depths(&g);
    for (j = 0; j < m; j++)
        for (k = 0; k < nphi; k++)
            irc__vertex_edges(&g, j, k, n, h);
}

/* Eigen-decomposition of the symmetric 2x2 [[a, b], [b, c]]: l0 >= l1 in
 * |l| and the unit eigenvector (u[0], u[1]) of l0.  The angle comes from
 * atan2 of the signed entries (Radiance's slope from |l| rotates the
 * axes when the smaller eigenvalue is negative). */
void irc__eigen2(float a, float b, float c, float *l0, float *l1, float u[2])
{
    float mid = 0.5f * (a + c), half = 0.5f * (a - c), r = IRC_SQRTF(half * half + b * b);
    float la = mid + r, lb = mid - r, ang = 0.5f * IRC_ATAN2F(2.0f * b, a - c);
    /* ang is the direction of la; swap so that l0 is the larger in size */
    if (IRC_FABSF(lb) > IRC_FABSF(la)) {
        float t = la;
        la = lb;
        lb = t;
        ang += 0.5f * IRC_PI;
    }
    *l0 = la;
    *l1 = lb;
    u[0] = IRC_COSF(ang);
    u[1] = IRC_SINF(ang);
}

#else /* IRC_NO_HESSIAN: the Hessian left out of the build (util.h) */

typedef int irc__no_hessian; /* ISO C wants something in a file */

#endif
