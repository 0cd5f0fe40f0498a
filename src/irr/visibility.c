/*
 * visibility.c -- translational gradients from visibility discontinuities
 * (first-order paper, Sec. 6-7 and App. D).
 *
 * Moving the receiver by m moves every blocker's silhouette in direction
 * space: a silhouette point seen along w at distance D, where the blocked
 * region has unit outward normal nu (nu perpendicular to w, pointing to the
 * visible side), moves along nu at the rate -(m.nu)/D.  For a smooth blocker
 * nu is the blocker's normal at the tangent point (Eq. 44-46: its
 * alpha_u = -cos(alpha)/D and alpha_v = -(v.n)/(D c.n) are the two
 * components of this motion in the (theta, phi) chart); for a polygon it is
 * the normal of the edge's image (Eq. 72).  Integrating over the silhouette
 * by arc length s,
 *
 *     grad E . m = integral (L_vis - L_blk) cos(theta) (m.nu) / D ds,
 *
 * the sign of Eq. 35/37 (visible to blocked is positive) being the
 * orientation of nu.  In this form the weak singularity of the paper's
 * phi-integral (footnote 6: c.n -> 0 where a meridian is tangent to the
 * silhouette, an integrable (phi - phi0)^-1/2) does not arise: it is the
 * Jacobian dphi/ds, and arc length has none.
 *
 * The silhouette is found on the stratum grid: an edge between neighbouring
 * strata whose rays escape on one side and hit on the other, or hit at very
 * different depths, brackets it; bisection rays through the host's callback
 * narrow each bracket; marching squares over the grid's cells join the
 * crossings into segments (the cap above the first row is a fan of
 * triangles around one extra ray at the zenith); each segment is
 * integrated by the trapezoid rule.  Edges without a silhouette keep Krivanek's terms (gradient.c).
 */
#include "../block/form.h"
#include "../block/check.h"
#include "../sample/sampler.h"
#include "../sample/strata.h"
#include "../store/trace.h"
#include "estimator.h"

#ifndef IRC_NO_VISIBILITY

#define IRC__BISECT 14        /* rounds at most: a bracket shrinks 2^14-fold; at 16 it reaches
                                 float precision and hits near tangency turn random */
#ifndef IRC__VIS_BUDGET
#define IRC__VIS_BUDGET 0.3f   /* extra rays (zenith and bisection) per stratum at most */
#endif
#define IRC__DEPTH_JUMP 1.25f  /* a depth ratio above this may be an edge */
#define IRC__CONTINUOUS 0.02f  /* final brackets closer than this are one surface */
#define IRC__SMOOTH 0.2f       /* |n.w| below this: the blocker's own normal at a
                                  silhouette is the edge's (irc__segment) */

static int irc__escaped(const irc__sample *a)
{
    return !(a->d < HUGE_VALF);
}

/* One end of a grid edge: a stratum's sample (or the zenith ray's). */
typedef struct irc__pt {
    const irc__sample *s;
    const float *dir, *nrm;
} irc__pt;

static irc__pt irc__stratum(const irc_cache *c, const irc__sample *s, uint32_t i)
{
    irc__pt p;
    p.s = &s[i];
    p.dir = irc__slot_dirs(c, s) + 3u * i;
    p.nrm = irc__slot_normals(c, s) + 3u * i;
    return p;
}

/* Starts a crossing on the edge between a and b if it brackets a
 * silhouette: one side escapes, or the far side lies IRC__DEPTH_JUMP times
 * deeper.  ia, ib: the strata beyond a and b on the same grid line (s
 * NULL: none), the blocker's first hit before its side of the bracket.
 * Returns its index, or -1. */
static int32_t irc__vis_edge(irc_cache *c, irc__sample *s, irc__pt a, irc__pt b, irc__pt ia,
                         irc__pt ib, int netvis, uint32_t *count)
{
    irc__cross *x;
    irc__pt blk, vis, in;
    int k;
    if (a.s->d != a.s->d || b.s->d != b.s->d)
        return -1; /* a failed ray */
    if (irc__escaped(a.s) && irc__escaped(b.s))
        return -1;
    blk = a.s->d <= b.s->d ? a : b;
    vis = blk.s == a.s ? b : a;
    in = blk.s == a.s ? ia : ib;
    if (!irc__escaped(vis.s) && (netvis || vis.s->d < IRC__DEPTH_JUMP * blk.s->d))
        return -1; /* for net visibility every hit blocks */
    if (*count >= 2u * c->strata + c->cfg.strata_phi)
        return -1; /* cannot happen: one crossing per edge at most */
    x = &irc__slot_cross(c, s)[*count];
    for (k = 0; k < 3; k++) {
        x->wa[k] = blk.dir[k];
        x->wb[k] = vis.dir[k];
        x->la[k] = netvis ? 0.0f : blk.s->l[k];
        x->lb[k] = netvis ? 1.0f : vis.s->l[k];
        x->na[k] = blk.nrm[k];
    }
    x->da = x->dnear = blk.s->d;
    x->db = x->dfar = vis.s->d;
    x->dp = NAN;
    if (in.s && in.s->d < blk.s->d && in.s->d > 0.0f)
        for (k = 0, x->dp = in.s->d; k < 3; k++) {
            x->wp[k] = in.dir[k];
            x->np[k] = in.nrm[k];
        }
    x->ok = 1;
    return (int32_t)(*count)++;
}

/* Marks every grid edge: H (same row, k and k+1), V (rows j, j+1), and,
 * given the zenith ray, the spokes from it to the first row's strata. */
static uint32_t irc__find_edges(irc_cache *c, irc__sample *s, irc__pt zenith, int netvis)
{
    const uint32_t m = c->cfg.strata_theta, nphi = c->cfg.strata_phi;
    int32_t *h = irc__slot_edges(c, s), *v = h + c->strata, *z = v + c->strata;
    uint32_t j, k, count = 0;
    irc__pt none;
    none.s = NULL;
    for (j = 0; j < m; j++)
        for (k = 0; k < nphi; k++) {
            uint32_t i = j * nphi + k;
            irc__pt here = irc__stratum(c, s, i);
            h[i] = irc__vis_edge(c, s, here, irc__stratum(c, s, j * nphi + (k + 1) % nphi),
                            irc__stratum(c, s, j * nphi + (k + nphi - 1) % nphi),
                            irc__stratum(c, s, j * nphi + (k + 2) % nphi), netvis, &count);
            v[i] = j + 1 < m ? irc__vis_edge(c, s, here, irc__stratum(c, s, i + nphi),
                                         j > 0 ? irc__stratum(c, s, i - nphi) : none,
                                         j + 2 < m ? irc__stratum(c, s, i + 2 * nphi) : none,
                                         netvis, &count)
                             : -1;
        }
    for (k = 0; k < nphi; k++)
        z[k] = zenith.s ? irc__vis_edge(c, s, zenith, irc__stratum(c, s, k), none,
                                    m > 1 ? irc__stratum(c, s, nphi + k) : none, netvis, &count)
                        : -1;
    return count;
}

static void irc__mid(const float a[3], const float b[3], float out[3])
{
    float x = a[0] + b[0], y = a[1] + b[1], z = a[2] + b[2];
    float l = IRC_SQRTF(x * x + y * y + z * z);
    out[0] = x / l;
    out[1] = y / l;
    out[2] = z / l;
}

/* One answer to a bisection ray: it joins the blocker's side if it hits
 * nearer than the geometric mean of the two sides' depths (or, the far side
 * being sky, within four times the blocker's depth). */
static void irc__narrow(irc__cross *x, const irc_ray *r, const irc_hit *h, int netvis)
{
    float lim = x->dfar < HUGE_VALF ? IRC_SQRTF(x->dnear * x->dfar) : 4.0f * x->dnear;
    int k;
    if (h->status == IRC_RAY_FAILED)
        return;
    if (h->status == IRC_RAY_HIT && h->dist < lim) {
        float v[3];
        irc__check_normal(h->normal, v);
        for (k = 0; k < 3; k++) {
            x->wp[k] = x->wa[k];
            x->np[k] = x->na[k];
        }
        x->dp = x->da;
        for (k = 0; k < 3; k++) {
            x->wa[k] = r->dir[k];
            x->la[k] = netvis ? 0.0f : h->radiance[k];
            x->na[k] = v[k];
        }
        x->da = h->dist;
    } else {
        for (k = 0; k < 3; k++) {
            x->wb[k] = r->dir[k];
            x->lb[k] = netvis ? 1.0f : h->radiance[k];
        }
        x->db = h->status == IRC_RAY_HIT ? h->dist : HUGE_VALF;
    }
}

/* Where the silhouette lies in a crossing's final bracket, and its depth:
 * at a smooth blocker (strata.c's rule, from the last two blocker-side
 * hits) the depth extrapolated to |n.w| = 0, and the direction where
 * |n.w|^2, linear in the angle there, reaches 0, which a wide bracket
 * (few rounds) needs.  Otherwise the bracket's middle and the blocker's
 * hit depth. */
static void irc__silhouette(irc__cross *x)
{
    float nw, np, ab = 0.0f, pa = 0.0f, t;
    irc__seen e, in;
    int k;
    irc__mid(x->wa, x->wb, x->ws);
    x->ds = x->da;
    if (x->dp != x->dp)
        return;
    e.w = x->wa;
    e.n = x->na;
    e.d = x->da;
    in.w = x->wp;
    in.n = x->np;
    in.d = x->dp;
    if (!irc__silhouette_depth(&e, &in, &x->ds))
        return;
    for (k = 0; k < 3; k++) {
        ab += (x->wb[k] - x->wa[k]) * (x->wb[k] - x->wa[k]);
        pa += (x->wa[k] - x->wp[k]) * (x->wa[k] - x->wp[k]);
    }
    nw = irc__facing(x->wa, x->na);
    np = irc__facing(x->wp, x->np);
    /* nw^2 = K (eps_s - eps), eps along wp -> wa -> wb (chords for angles) */
    t = nw * nw * IRC_SQRTF(pa) / (np * np - nw * nw);
    if (t > IRC_SQRTF(ab))
        t = IRC_SQRTF(ab);
    {
        float w[3];
        for (k = 0; k < 3; k++)
            w[k] = (float)(x->wa[k] + (x->wb[k] - x->wa[k]) * t / IRC_SQRTF(ab));
        irc__mid(w, w, x->ws);
    }
}

/* Rounds over every crossing, batched through the callback: as many as
 * the budget of IRC__VIS_BUDGET rays a stratum allows (the zenith ray
 * taken), IRC__BISECT at most.  Hits are checked as the sampler checks
 * them. */
static int irc__bisect(irc__call *k, irc__sample *s, uint32_t count, int netvis)
{
    const float budget = IRC__VIS_BUDGET * k->c->strata - 1.0f;
    const uint32_t rounds = count == 0 || budget < count ? 0u
                            : budget >= (float)IRC__BISECT * count ? IRC__BISECT
                                                                    : (uint32_t)(budget / count);
    const irc_cache *c = k->c;
    irc__cross *x = irc__slot_cross(c, s);
    irc_ray *rb = irc__slot_rays(c, k->slot);
    irc_hit *hb = (irc_hit *)(void *)(rb + c->cfg.max_batch);
    uint32_t round, i0, i;
    for (round = 0; round < rounds; round++)
        for (i0 = 0; i0 < count; i0 += c->cfg.max_batch) {
            uint32_t cnt = count - i0 < c->cfg.max_batch ? count - i0 : c->cfg.max_batch;
            int st;
            for (i = 0; i < cnt; i++) {
                rb[i].org[0] = k->q.p[0];
                rb[i].org[1] = k->q.p[1];
                rb[i].org[2] = k->q.p[2];
                irc__mid(x[i0 + i].wa, x[i0 + i].wb, rb[i].dir);
            }
            if ((st = irc__cast(k, rb, hb, cnt)) < 0)
                return st;
            for (i = 0; i < cnt; i++) {
                irc__sample chk;
                if ((st = irc__accept_hit(&hb[i], &chk)) < 0)
                    return st;
                irc__narrow(&x[i0 + i], &rb[i], &hb[i], netvis);
            }
        }
    /* Both sides on one surface after all: a steep but continuous one. */
    for (i = 0; i < count; i++) {
        if (x[i].db < HUGE_VALF && x[i].db < x[i].da * (1.0f + IRC__CONTINUOUS))
            x[i].ok = 0;
        irc__silhouette(&x[i]);
    }
    return IRC_OK;
}

/* What a segment's integrand needs at one end: the crossing point X, the
 * weight q = (L_vis - L_blk) cos(theta)/D per channel, and for a smooth
 * blocker the silhouette's normal nu (its own normal there, n.X ~ 0). */
typedef struct irc__end {
    float x[3], q[3], nu[3], e[3];
    int smooth;
} irc__end;

static void irc__end_of(const irc__cross *c, const float n[3], int netvis, irc__end *o)
{
    float xf[3];
    float cs, nx = 0.0f, len = 0.0f, orient = 0.0f;
    int k;
    for (k = 0; k < 3; k++)
        xf[k] = c->ws[k];
    for (k = 0; k < 3; k++) {
        o->x[k] = xf[k];
        o->e[k] = c->wb[k] - c->wa[k];
        nx += c->na[k] * xf[k];
    }
    /* Irradiance weighs by cos(theta); net visibility (Eq. 47) does not. */
    cs = netvis ? 1.0f : irc__dot3(o->x, n);
    for (k = 0; k < 3; k++)
        o->q[k] = (c->lb[k] - c->la[k]) * (cs > 0.0f ? cs : 0.0f) / c->ds;
    o->smooth = IRC_FABSF(nx) < IRC__SMOOTH;
    for (k = 0; k < 3; k++) {
        o->nu[k] = c->na[k] - nx * o->x[k];
        len += o->nu[k] * o->nu[k];
        orient += o->nu[k] * o->e[k];
    }
    len = IRC_SQRTF(len) * (orient < 0.0f ? -1.0f : 1.0f);
    for (k = 0; k < 3; k++)
        o->nu[k] = len != 0.0f ? o->nu[k] / len : 0.0f;
}

/* Trapezoid rule over the segment between two crossings; the normal is the
 * blocker's own where both ends are smooth, else the chord's (a polygon
 * edge's image), turned toward the visible side. */
static void irc__segment(const irc__cross *c1, const irc__cross *c2, const float n[3],
                         int netvis, float g[3][3])
{
    irc__end a, b;
    float ch[3], len, nu[3], e[3], w, orient;
    int k, i;
    irc__end_of(c1, n, netvis, &a);
    irc__end_of(c2, n, netvis, &b);
    for (k = 0; k < 3; k++) {
        ch[k] = b.x[k] - a.x[k];
        e[k] = a.e[k] + b.e[k];
    }
    len = IRC_SQRTF(irc__dot3(ch, ch));
    if (len == 0.0f)
        return;
    if (!(a.smooth && b.smooth)) {
        float mid[3];
        for (k = 0; k < 3; k++)
            mid[k] = a.x[k] + b.x[k];
        irc__cross3(mid, ch, nu);
        w = IRC_SQRTF(irc__dot3(nu, nu));
        orient = irc__dot3(nu, e) < 0.0f ? -1.0f : 1.0f;
        for (k = 0; k < 3; k++)
            a.nu[k] = b.nu[k] = orient * nu[k] / w;
    }
    for (i = 0; i < 3; i++) {
        float v[3], vn;
        for (k = 0; k < 3; k++)
            v[k] = 0.5f * len * (a.q[i] * a.nu[k] + b.q[i] * b.nu[k]);
        vn = irc__dot3(v, n); /* only moves in the receiver's plane count */
        for (k = 0; k < 3; k++)
            g[i][k] += v[k] - vn * n[k];
    }
}

static const irc__cross *irc__at(const irc__cross *x, int32_t i)
{
    return i >= 0 && x[i].ok ? &x[i] : NULL;
}

/* Marching squares: a cell (strata j, j+1 by k, k+1) whose edges hold two
 * crossings holds one silhouette segment; four, two (the shorter pairing). */
static void irc__cells(irc_cache *c, irc__sample *s, const float n[3], int netvis,
                       float g[3][3])
{
    const uint32_t m = c->cfg.strata_theta, nphi = c->cfg.strata_phi;
    const int32_t *h = irc__slot_edges(c, s), *v = h + c->strata;
    const irc__cross *x = irc__slot_cross(c, s);
    uint32_t j, k;
    for (j = 0; j + 1 < m; j++)
        for (k = 0; k < nphi; k++) {
            const irc__cross *e[4], *f[4];
            int cnt = 0, i;
            e[0] = irc__at(x, h[j * nphi + k]);
            e[1] = irc__at(x, v[j * nphi + (k + 1) % nphi]);
            e[2] = irc__at(x, h[(j + 1) * nphi + k]);
            e[3] = irc__at(x, v[j * nphi + k]);
            for (i = 0; i < 4; i++)
                if (e[i])
                    f[cnt++] = e[i];
            if (cnt == 2) {
                irc__segment(f[0], f[1], n, netvis, g);
            } else if (cnt == 4) {
                float d01 = 0, d12 = 0;
                for (i = 0; i < 3; i++) {
                    d01 += (f[0]->wa[i] - f[1]->wa[i]) * (f[0]->wa[i] - f[1]->wa[i]) +
                           (f[2]->wa[i] - f[3]->wa[i]) * (f[2]->wa[i] - f[3]->wa[i]);
                    d12 += (f[1]->wa[i] - f[2]->wa[i]) * (f[1]->wa[i] - f[2]->wa[i]) +
                           (f[3]->wa[i] - f[0]->wa[i]) * (f[3]->wa[i] - f[0]->wa[i]);
                }
                irc__segment(f[0], d01 <= d12 ? f[1] : f[3], n, netvis, g);
                irc__segment(f[2], d01 <= d12 ? f[3] : f[1], n, netvis, g);
            }
        }
}

/* The cap above the first row: triangles (zenith, first-row stratum k,
 * stratum k+1), marched like the cells. */
static void irc__cap(irc_cache *c, irc__sample *s, const float n[3], int netvis,
                     float g[3][3])
{
    const uint32_t nphi = c->cfg.strata_phi;
    const int32_t *h = irc__slot_edges(c, s), *z = h + 2u * c->strata;
    const irc__cross *x = irc__slot_cross(c, s);
    uint32_t k;
    for (k = 0; k < nphi; k++) {
        const irc__cross *e[3], *f[3];
        int cnt = 0, i;
        e[0] = irc__at(x, z[k]);
        e[1] = irc__at(x, h[k]);
        e[2] = irc__at(x, z[(k + 1) % nphi]);
        for (i = 0; i < 3; i++)
            if (e[i])
                f[cnt++] = e[i];
        if (cnt == 2)
            irc__segment(f[0], f[1], n, netvis, g);
    }
}

/* Casts the zenith ray the cap's triangles share. */
static int irc__zenith(irc__call *call, irc__sample *out, float dir[3], float nrm[3])
{
    irc_ray *r = irc__slot_rays(call->c, call->slot);
    irc_hit *h = (irc_hit *)(void *)(r + call->c->cfg.max_batch);
    int k, st;
    for (k = 0; k < 3; k++) {
        r->org[k] = call->q.p[k];
        r->dir[k] = dir[k] = call->q.n[k];
        nrm[k] = 0.0f;
    }
    if ((st = irc__cast(call, r, h, 1)) < 0)
        return st;
    if ((st = irc__accept_hit(h, out)) < 0)
        return st;
    if (h->status == IRC_RAY_HIT) {
        float v[3];
        irc__check_normal(h->normal, v);
        for (k = 0; k < 3; k++)
            nrm[k] = v[k];
    }
    return IRC_OK;
}

/* Adds the silhouettes' share of the translational gradient to g and casts
 * the bisection rays (counted in *rays).  netvis: the gradient of the
 * visible solid angle (Eq. 48) instead, in g[0].  Returns IRC_OK or the
 * callback's error. */
int irc__grad_visibility(irc__call *k, int netvis, float g[3][3])
{
    irc_cache *c = k->c;
    const float *n = k->q.n;
    irc__sample *s = (irc__sample *)(void *)k->slot, top;
    irc__pt zenith;
    float zdir[3], znrm[3];
    uint32_t count;
    int st;
    if (c->cfg.strata_phi < 2 || c->cfg.strata_theta < 2)
        return IRC_OK;
    /* The zenith ray only when some silhouette is there to close. */
    zenith.s = NULL;
    if (irc__find_edges(c, s, zenith, netvis) == 0)
        return IRC_OK;
    if ((st = irc__zenith(k, &top, zdir, znrm)) < 0)
        return st;
    zenith.s = &top;
    zenith.dir = zdir;
    zenith.nrm = znrm;
    count = irc__find_edges(c, s, zenith, netvis);
    if ((st = irc__bisect(k, s, count, netvis)) < 0)
        return st;
    irc__cells(c, s, n, netvis, g);
    irc__cap(c, s, n, netvis, g);
    return IRC_OK;
}

/* Net visibility (Eq. 47, over 2 pi): each stratum's exact solid angle,
 * (2 pi/N)(cos theta_j- - cos theta_j+), weighs whether its ray escaped, so
 * no 1/cos(theta) weight from the cosine-weighted sampling enters. */
float irc__net_visibility(const irc_cache *c, const irc__sample *s)
{
    const uint32_t m = c->cfg.strata_theta, nphi = c->cfg.strata_phi;
    float vis = 0.0f, all = 0.0f;
    uint32_t j, k;
    for (j = 0; j < m; j++) {
        float w = IRC_SQRTF(1.0f - (float)j / m) - IRC_SQRTF(1.0f - (float)(j + 1) / m);
        for (k = 0; k < nphi; k++) {
            const irc__sample *a = &s[j * nphi + k];
            if (a->d != a->d)
                continue;
            all += w;
            if (irc__escaped(a))
                vis += w;
        }
    }
    return all > 0.0f ? vis / all : 0.0f;
}

#endif

