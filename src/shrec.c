/*
 * shrec.c -- SH records: the samples projected onto the real SH basis, the
 * coefficients' translational gradients from the same samples (SH-gradient
 * paper, Eq. 6-13), the packed form, and the SH calls (compute, insert,
 * lookup by Eq. 14-16, read back).
 */
#include "cache.h"

#define IRC__NC (IRC__SH_MAX_BANDS * IRC__SH_MAX_BANDS)
/* Cap on a free-point weight: a query on a record gives 1/0. */
#define IRC__SH_W_MAX 1e6

/* Sums over the samples, in double. */
typedef struct irc__shsum {
    double c[3][IRC__NC];
    double g[3][3 * IRC__NC]; /* d c_i / dp at [3 i + k] */
    double e[3];
    double inv_d;
    uint32_t used, total;
} irc__shsum;

/* The stratum grid the samples came from: one hemisphere (a surface
 * record) or two glued at the equator with the same azimuths (a free
 * point), rows of equal solid angle, cos(theta_j) = 1 - j/M. */
typedef struct irc__grid {
    const irc__sample *s;
    const float *dir, *nrm;
    const double *axis[2], *t1, *t2;
    uint32_t m, n, halves;
} irc__grid;

static int irc__hit(const irc__sample *x)
{
    return x->d == x->d && x->d < HUGE_VALF;
}

/* |n.w| at sample i: 1 facing the ray, 0 grazing (a silhouette). */
static double irc__facing(const irc__grid *g, uint32_t i)
{
    const float *w = g->dir + 3 * i, *n = g->nrm + 3 * i;
    return fabs((double)w[0] * n[0] + (double)w[1] * n[1] + (double)w[2] * n[2]);
}

/* Whether neighbouring samples a and b lie on one continuous surface:
 * both hits, normals alike and facing the same way, and a depth change no
 * larger than a surface seen at that slant makes over the angle between
 * them (twice over). */
static int irc__continuous(const irc__grid *g, uint32_t a, uint32_t b)
{
    const float *wa = g->dir + 3 * a, *wb = g->dir + 3 * b;
    const float *na = g->nrm + 3 * a, *nb = g->nrm + 3 * b;
    double sa, sb, dw, da = g->s[a].d, db = g->s[b].d, big, slant;
    int k;
    if (!irc__hit(&g->s[a]) || !irc__hit(&g->s[b]))
        return 0;
    sa = (double)na[0] * wa[0] + (double)na[1] * wa[1] + (double)na[2] * wa[2];
    sb = (double)nb[0] * wb[0] + (double)nb[1] * wb[1] + (double)nb[2] * wb[2];
    if ((sa < 0.0) != (sb < 0.0) ||
        (double)na[0] * nb[0] + (double)na[1] * nb[1] + (double)na[2] * nb[2] < 0.5)
        return 0;
    for (dw = 0.0, k = 0; k < 3; k++)
        dw += ((double)wa[k] - wb[k]) * ((double)wa[k] - wb[k]);
    big = da > db ? da : db;
    slant = fabs(sa) > fabs(sb) ? fabs(sa) : fabs(sb);
    return fabs(da - db) * slant <= 2.0 * IRC_SQRT(dw) * big;
}

/* The depth where the surface of sample i ends, past i on the side away
 * from its neighbour o.  At a smooth silhouette |n.w| falls to 0 there and
 * both |n.w|^2 and the depth's shortfall from the silhouette's depth go
 * as the angle to it, so when |n.w|^2, extrapolated from o through i,
 * reaches 0 within one stratum past i, the depth is extrapolated linearly
 * in |n.w| to |n.w| = 0.  Otherwise (an edge of the surface itself, a
 * polygon's outline) the edge's depth is i's. */
static double irc__silhouette_depth(const irc__grid *g, uint32_t i, int64_t o)
{
    double d = g->s[i].d, fi, fo, ds;
    if (o < 0 || !irc__continuous(g, i, (uint32_t)o))
        return d;
    fi = irc__facing(g, i);
    fo = irc__facing(g, (uint32_t)o);
    if (!(fo * fo >= 1.25 * fi * fi) || !(g->s[o].d < d))
        return d;
    ds = d + fi * (d - g->s[o].d) / (fo - fi);
    return ds < 2.0 * d ? ds : 2.0 * d;
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
 * (irc__silhouette_depth), the farther side's surface continues behind.
 * w_out gets the vector for sample i. */
static void irc__edge(const irc__grid *g, uint32_t i, int64_t o, int64_t back,
                      double len, const double nu[3], double w_out[3])
{
    double f, k;
    int c;
    if (o < 0 || !irc__hit(&g->s[i]) || g->s[o].d != g->s[o].d)
        return;
    if (irc__continuous(g, i, (uint32_t)o))
        f = 0.5 * (1.0 / g->s[o].d - 1.0 / g->s[i].d);
    else if (!(g->s[o].d > g->s[i].d))
        return;
    else
        f = 1.0 / irc__silhouette_depth(g, i, back) - 1.0 / g->s[i].d;
    k = f * len;
    for (c = 0; c < 3; c++)
        w_out[c] += k * nu[c];
}

/* Sample index of row j (of rows 0..2M-1 counted from the first
 * hemisphere's pole across the equator), column k; -1 off the grid.  Once
 * per row: it divides. */
static int64_t irc__at(const irc__grid *g, int64_t j, uint32_t k)
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
typedef struct irc__cell {
    double z0, z1, s0, s1, len;
    double cl, sl, cc, sc, cr, sr;
    const double *axis;
    int64_t row, up, dn; /* first sample of the row, of the rows toward the
                            pole and toward the horizon (-1: none) */
} irc__cell;

/* The edge vector of the sample in column k of the row q describes. */
static void irc__edge_vector(const irc__grid *g, uint32_t k, const irc__cell *q, double w[3])
{
    const double dphi = 2.0 * IRC_PI / g->n;
    const uint32_t i = (uint32_t)q->row + k, kl = k ? k - 1 : g->n - 1,
                   kr = k + 1 < g->n ? k + 1 : 0;
    const int64_t up = q->up < 0 ? -1 : q->up + k, dn = q->dn < 0 ? -1 : q->dn + k;
    double nu[3];
    int c;
    w[0] = w[1] = w[2] = 0.0;
    /* Left and right: meridian edges, unit normals along -/+ e_phi. */
    for (c = 0; c < 3; c++)
        nu[c] = q->sl * g->t1[c] - q->cl * g->t2[c];
    if (g->n > 1)
        irc__edge(g, i, q->row + kl, q->row + kr, q->len, nu, w);
    for (c = 0; c < 3; c++)
        nu[c] = -q->sr * g->t1[c] + q->cr * g->t2[c];
    if (g->n > 1)
        irc__edge(g, i, q->row + kr, q->row + kl, q->len, nu, w);
    /* Toward the pole and toward the horizon (the other hemisphere's
     * equator row for a free point): arcs of constant theta. */
    for (c = 0; c < 3; c++)
        nu[c] = -(q->z0 * (q->cc * g->t1[c] + q->sc * g->t2[c]) - q->s0 * q->axis[c]);
    irc__edge(g, i, up, dn, q->s0 * dphi, nu, w);
    for (c = 0; c < 3; c++)
        nu[c] = q->z1 * (q->cc * g->t1[c] + q->sc * g->t2[c]) - q->s1 * q->axis[c];
    irc__edge(g, i, dn, up, q->s1 * dphi, nu, w);
}

/* One sample's share of the coefficients and, with gradients, of Eq. 11
 * over the surface it hit, rewritten over solid angle with dA = dw r^2 /
 * (n.w) (Eq. 13): the regular part -dw L/r [grad_w y_i - 2 y_i w] here,
 * the singular part through the edge vector e (irc__edge), -L y_i e.  w
 * is the stratum's direction, dw = 1 (the caller scales). */
static void irc__sh_add(const irc_cache *c, irc__shsum *a, const irc__sample *x,
                        const double w[3], const double *n, const double e[3])
{
    const int nc = (int)c->sh_n, nch = (int)c->sh_ch, bands = (int)c->cfg.sh_bands;
    const int grad = c->off_shg != 0;
    double y[IRC__NC], gy[IRC__NC][3], v[3 * IRC__NC];
    int ch, i, k;
    irc__sh_eval(bands, w, y, grad ? gy : NULL);
    for (ch = 0; ch < nch; ch++)
        for (i = 0; i < nc; i++)
            a->c[ch][i] += x->l[ch] * y[i];
    if (n)
        for (ch = 0; ch < 3; ch++)
            a->e[ch] += x->l[ch] * irc__dot3d(w, n);
    if (!irc__hit(x))
        return;
    a->inv_d += 1.0 / x->d;
    if (!grad)
        return;
    /* One vector per sample, then a plain multiply-add per channel. */
    for (i = 0; i < nc; i++)
        for (k = 0; k < 3; k++)
            v[3 * i + k] = (gy[i][k] - 2.0 * y[i] * w[k]) / x->d + y[i] * e[k];
    for (ch = 0; ch < nch; ch++) {
        const double l = x->l[ch];
        for (i = 0; i < 3 * nc; i++)
            a->g[ch][i] -= l * v[i];
    }
}

static void irc__sh_accumulate(const irc_cache *c, const irc__grid *g, const double *n,
                               irc__shsum *a)
{
    const double dw = 2.0 * IRC_PI / c->strata, dphi = 2.0 * IRC_PI / g->n;
    const double cd = IRC_COS(dphi), sd = IRC_SIN(dphi), ch = IRC_COS(0.5 * dphi),
                 sh = IRC_SIN(0.5 * dphi);
    int64_t jj;
    uint32_t k;
    int q;
    for (jj = 0; jj < (int64_t)(g->halves * g->m); jj++) {
        const uint32_t j = jj < g->m ? (uint32_t)jj : g->m - 1 - (uint32_t)(jj - g->m);
        irc__cell cell;
        cell.z0 = 1.0 - (double)j / g->m;
        cell.z1 = 1.0 - (j + 1.0) / g->m;
        cell.s0 = IRC_SQRT(1.0 - cell.z0 * cell.z0);
        cell.s1 = IRC_SQRT(1.0 - cell.z1 * cell.z1);
        cell.len = IRC_ACOS(cell.z1) - IRC_ACOS(cell.z0);
        cell.cl = 1.0;
        cell.sl = 0.0;
        cell.axis = g->axis[jj < g->m ? 0 : 1];
        cell.row = irc__at(g, jj, 0);
        cell.up = irc__at(g, jj < g->m ? jj - 1 : jj + 1, 0);
        cell.dn = irc__at(g, jj < g->m ? jj + 1 : jj - 1, 0);
        for (k = 0; k < g->n; k++) {
            const uint32_t i = (uint32_t)cell.row + k;
            double w[3], e[3] = {0, 0, 0};
            cell.cc = cell.cl * ch - cell.sl * sh;
            cell.sc = cell.sl * ch + cell.cl * sh;
            cell.cr = cell.cl * cd - cell.sl * sd;
            cell.sr = cell.sl * cd + cell.cl * sd;
            a->total++;
            if (g->s[i].d == g->s[i].d) {
                a->used++;
                for (q = 0; q < 3; q++)
                    w[q] = g->dir[3 * i + q];
                if (c->off_shg) {
                    irc__edge_vector(g, k, &cell, e);
                    for (q = 0; q < 3; q++)
                        e[q] /= dw;
                }
                irc__sh_add(c, a, &g->s[i], w, n, e);
            }
            cell.cl = cell.cr;
            cell.sl = cell.sr;
        }
    }
}

/* The record from the sums: each usable sample stands for 2 pi/(M N)
 * steradians, scaled by total/used when some rays failed. */
static void irc__sh_finish(const irc_cache *c, const irc__shsum *a, irc_sh *out)
{
    const double dw = 2.0 * IRC_PI / c->strata * ((double)a->total / a->used);
    double hm = a->inv_d > 0.0 ? a->used / a->inv_d : HUGE_VAL, r = hm;
    uint32_t ch, i, k;
    out->bands = c->cfg.sh_bands;
    out->channels = c->sh_ch;
    out->features = c->cfg.features;
    out->rays = a->total;
    out->rays_used = a->used;
    for (ch = 0; ch < 3; ch++)
        out->e[ch] = (float)(dw * a->e[ch]);
    for (ch = 0; ch < c->sh_ch; ch++) {
        double len;
        for (i = 0; i < c->sh_n; i++) {
            out->c[ch][i] = (float)(dw * a->c[ch][i]);
            for (k = 0; k < 3; k++)
                out->grad[ch][i][k] = (float)(dw * a->g[ch][3 * i + k]);
        }
        /* R <= |c_0|/|grad c_0|: where first-order extrapolation would
         * change the mean radiance by 100%. */
        len = dw * IRC_SQRT(irc__dot3d(a->g[ch], a->g[ch]));
        if (len > 0.0 && dw * fabs(a->c[ch][0]) / len < r)
            r = dw * fabs(a->c[ch][0]) / len;
    }
    if (r < c->cfg.min_radius) r = c->cfg.min_radius;
    if (r > c->cfg.max_radius) r = c->cfg.max_radius;
    if (r < FLT_MIN) r = FLT_MIN;
    out->radius = (float)r;
}

static int irc__sh_check(const irc_cache *c, const irc_sh *r, double un[3])
{
    uint32_t ch, i;
    int st;
    if ((st = irc__check_vec(r->p)) < 0)
        return st;
    un[0] = un[1] = un[2] = 0.0;
    if ((r->n[0] != 0.0f || r->n[1] != 0.0f || r->n[2] != 0.0f) &&
        (st = irc__check_normal(r->n, un)) < 0)
        return st;
    if (r->bands != c->cfg.sh_bands || r->channels != c->sh_ch)
        return IRC_ERR_RANGE;
    if (!irc__finite3(r->e) || !irc__finite(r->radius))
        return IRC_ERR_NONFINITE;
    for (ch = 0; ch < c->sh_ch; ch++)
        for (i = 0; i < c->sh_n; i++)
            if (!irc__finite(r->c[ch][i]) || !irc__finite3(r->grad[ch][i]))
                return IRC_ERR_NONFINITE;
    return r->radius > 0.0f && r->e[0] >= 0.0f && r->e[1] >= 0.0f && r->e[2] >= 0.0f
               ? IRC_OK : IRC_ERR_RANGE;
}

static void irc__sh_pack(const irc_cache *c, const irc_sh *in, const double un[3],
                         unsigned char *dst)
{
    irc__rec *r = (irc__rec *)(void *)dst;
    float *cf = (float *)(void *)(dst + c->off_sh);
    float *gf = c->off_shg ? (float *)(void *)(dst + c->off_shg) : NULL;
    uint32_t ch, i, k;
    IRC_MEMSET(dst, 0, c->rec_size);
    for (k = 0; k < 3; k++) {
        r->p[k] = in->p[k];
        r->e[k] = in->e[k];
    }
    r->r = in->radius > IRC_RADIUS_CAP ? IRC_RADIUS_CAP : in->radius;
    r->n = un[0] == 0.0 && un[1] == 0.0 && un[2] == 0.0 ? IRC__FREE : irc__oct_encode(un);
    for (ch = 0; ch < c->sh_ch; ch++)
        for (i = 0; i < c->sh_n; i++) {
            *cf++ = in->c[ch][i];
            if (gf)
                for (k = 0; k < 3; k++)
                    *gf++ = in->grad[ch][i][k];
        }
}

static void irc__sh_unpack(const irc_cache *c, const unsigned char *src, irc_sh *out)
{
    const irc__rec *r = (const irc__rec *)(const void *)src;
    const float *cf = (const float *)(const void *)(src + c->off_sh);
    const float *gf = c->off_shg ? (const float *)(const void *)(src + c->off_shg) : NULL;
    uint32_t ch, i, k;
    IRC_MEMSET(out, 0, sizeof *out);
    for (k = 0; k < 3; k++) {
        out->p[k] = r->p[k];
        out->e[k] = r->e[k];
    }
    if (r->n != IRC__FREE)
        irc__oct_decode(r->n, out->n);
    out->radius = r->r;
    out->bands = c->cfg.sh_bands;
    out->channels = c->sh_ch;
    out->features = c->cfg.features;
    for (ch = 0; ch < c->sh_ch; ch++)
        for (i = 0; i < c->sh_n; i++) {
            out->c[ch][i] = *cf++;
            if (gf)
                for (k = 0; k < 3; k++)
                    out->grad[ch][i][k] = *gf++;
        }
}

static int irc__check_sh(const irc_cache *c)
{
    int st = irc__check_cache(c);
    if (st < 0)
        return st;
    return c->sh_n ? IRC_OK : IRC_ERR_UNSUPPORTED;
}

/* Samples one hemisphere (n given) or the sphere as two (n NULL: around
 * the world z axis, the lower one's frame the upper's with the axis
 * flipped, so columns meet at the equator) into a claimed slot and sums
 * them into *a. */
static int irc__sh_sample(irc_cache *c, unsigned char *slot, const float p[3],
                          const double *un, irc__shsum *a)
{
    static const double up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
    double t1[3], t2[3];
    irc__grid g;
    uint32_t used, h;
    int st;
    g.s = (const irc__sample *)(const void *)slot;
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
    for (h = 0; h < g.halves; h++) {
        st = irc__sample_hemisphere(c, slot, p, g.axis[h], t1, t2, h * c->strata, &used);
        if (st < 0)
            return st;
    }
    irc__sh_accumulate(c, &g, un, a);
    return IRC_OK;
}

int irc_sh_compute(irc_cache *c, const float p[3], const float n[3], irc_sh *out)
{
    irc__shsum a;
    irc_sh rec;
    double un[3];
    uint32_t t;
    int st, k;
    if ((st = irc__check_sh(c)) < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    if ((st = irc__check_vec(p)) < 0 || (n && (st = irc__check_normal(n, un)) < 0))
        return st;
    if ((st = irc__slot_claim(c, &t)) < 0)
        return st;
    IRC_MEMSET(&a, 0, sizeof a);
    st = irc__sh_sample(c, c->scratch + (size_t)t * c->slot_bytes, p, n ? un : NULL, &a);
    irc__slot_release(c, t);
    if (st < 0)
        return st;
    IRC_MEMSET(&rec, 0, sizeof rec);
    irc__sh_finish(c, &a, &rec);
    for (k = 0; k < 3; k++) {
        rec.p[k] = p[k];
        rec.n[k] = n ? (float)un[k] : 0.0f;
    }
    /* Finite radiances can still sum past FLT_MAX. */
    if ((st = irc__sh_check(c, &rec, un)) < 0)
        return st;
    *out = rec;
    c->port->fetch_add(&c->ctr[IRC__C_COMPUTES], 1);
    c->port->fetch_add(&c->ctr[IRC__C_RAYS], a.total);
    return IRC_OK;
}

int irc_sh_insert(irc_cache *c, const irc_sh *rec)
{
    unsigned char packed[32 + IRC__NC * 3 * 4 * 4];
    double un[3];
    int st;
    if ((st = irc__check_sh(c)) < 0)
        return st;
    if (!rec)
        return IRC_ERR_NULL;
    if ((st = irc__sh_check(c, rec, un)) < 0)
        return st;
    irc__sh_pack(c, rec, un, packed);
    return irc__store(c, packed);
}

typedef struct irc__shacc {
    irc_cache *c;
    const float *p, *n;
    double w, c_[3][IRC__NC], g[3][IRC__NC][3], e[3];
} irc__shacc;

/* Surface records: Ward-Heckbert (weight.c).  Free points: (R_j/d)^b
 * within a R_j (Eq. 16 made scale-free). */
static int irc__sh_weigh(const irc_cache *c, const irc__rec *r, const float p[3],
                         const float n[3], double *w)
{
    double dx = (double)p[0] - r->p[0], dy = (double)p[1] - r->p[1],
           dz = (double)p[2] - r->p[2], d, ra = (double)c->cfg.accuracy * r->r;
    float ni[3];
    if (n)
        return irc__weigh(c, r, p, n, w, ni);
    if (r->n != IRC__FREE)
        return 0;
    d = IRC_SQRT(dx * dx + dy * dy + dz * dz);
    if (!(d < ra))
        return 0;
    *w = d * IRC__SH_W_MAX > r->r ? pow(r->r / d, c->cfg.sh_power) : IRC__SH_W_MAX;
    if (*w > IRC__SH_W_MAX)
        *w = IRC__SH_W_MAX;
    return 1;
}

/* Eq. 15: each accepted record extrapolated to p (Eq. 14), weighted. */
static void irc__sh_visit(void *ud, uint32_t id)
{
    irc__shacc *a = (irc__shacc *)ud;
    irc_cache *c = a->c;
    for (; id != IRC__NIL; id = c->next[id]) {
        const irc__rec *r = irc__rec_at(c, id);
        const unsigned char *b = (const unsigned char *)r;
        const float *cf = (const float *)(const void *)(b + c->off_sh);
        const float *gf = c->off_shg ? (const float *)(const void *)(b + c->off_shg) : NULL;
        double w, d[3];
        uint32_t ch, i, k;
        if (!irc__within_reach(c, r, a->p) || !irc__sh_weigh(c, r, a->p, a->n, &w))
            continue;
        for (k = 0; k < 3; k++) {
            d[k] = (double)a->p[k] - r->p[k];
            a->e[k] += w * r->e[k];
        }
        for (ch = 0; ch < c->sh_ch; ch++)
            for (i = 0; i < c->sh_n; i++) {
                double v = *cf++;
                if (gf) {
                    for (k = 0; k < 3; k++) {
                        v += gf[k] * d[k];
                        a->g[ch][i][k] += w * gf[k];
                    }
                    gf += 3;
                }
                a->c_[ch][i] += w * v;
            }
        a->w += w;
        irc__mark_used(c, id);
    }
}

static int irc__sh_lookup(irc_cache *c, const float p[3], const float n[3],
                          irc_sh *out, float *weight)
{
    irc__shacc a;
    double un[3];
    float nf[3];
    uint32_t ch, i, k;
    int st;
    if ((st = irc__check_sh(c)) < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    if ((st = irc__check_vec(p)) < 0 || (n && (st = irc__check_normal(n, un)) < 0))
        return st;
    IRC_MEMSET(&a, 0, sizeof a);
    for (k = 0; k < 3; k++)
        nf[k] = n ? (float)un[k] : 0.0f;
    a.c = c;
    a.p = p;
    a.n = n ? nf : NULL;
    c->port->read_lock(c->lock);
    irc__index_query(c, p, irc__sh_visit, &a);
    c->port->read_unlock(c->lock);
    IRC_MEMSET(out, 0, sizeof *out);
    out->bands = c->cfg.sh_bands;
    out->channels = c->sh_ch;
    out->features = c->cfg.features;
    for (k = 0; k < 3; k++) {
        out->p[k] = p[k];
        out->n[k] = nf[k];
    }
    if (weight)
        *weight = (float)a.w;
    if (!(a.w > 0.0))
        return IRC_MISS;
    for (k = 0; k < 3; k++)
        out->e[k] = (float)(a.e[k] / a.w);
    st = irc__finite3(out->e) ? IRC_OK : IRC_ERR_NONFINITE;
    for (ch = 0; ch < c->sh_ch; ch++)
        for (i = 0; i < c->sh_n; i++) {
            out->c[ch][i] = (float)(a.c_[ch][i] / a.w);
            for (k = 0; k < 3; k++)
                out->grad[ch][i][k] = (float)(a.g[ch][i][k] / a.w);
            if (!irc__finite(out->c[ch][i]) || !irc__finite3(out->grad[ch][i]))
                st = IRC_ERR_NONFINITE;
        }
    /* Huge gradients far from their record can overflow float. */
    return st;
}

int irc_sh_lookup(irc_cache *c, const float p[3], const float n[3], irc_sh *out,
                  float *weight)
{
    int st = irc__sh_lookup(c, p, n, out, weight);
    if (st < 0)
        return st;
    c->port->fetch_add(&c->ctr[IRC__C_LOOKUPS], 1);
    if (st == IRC_OK)
        c->port->fetch_add(&c->ctr[IRC__C_HITS], 1);
    return st;
}

int irc_sh_lookup_or_compute(irc_cache *c, const float p[3], const float n[3],
                             irc_sh *out, float *weight)
{
    irc_sh rec;
    int st = irc__sh_lookup(c, p, n, out, weight), ins;
    if (st < 0)
        return st;
    if (st == IRC_OK) {
        c->port->fetch_add(&c->ctr[IRC__C_LOOKUPS], 1);
        c->port->fetch_add(&c->ctr[IRC__C_HITS], 1);
        return IRC_OK;
    }
    if ((st = irc_sh_compute(c, p, n, &rec)) < 0)
        return st;
    ins = irc_sh_insert(c, &rec);
    if (ins < 0 && ins != IRC_ERR_FULL)
        return ins;
    c->port->fetch_add(&c->ctr[IRC__C_LOOKUPS], 1);
    *out = rec;
    if (weight)
        *weight = 0.0f;
    return ins == IRC_ERR_FULL ? IRC_NOT_STORED : IRC_OK;
}

int irc_sh_record(irc_cache *c, uint32_t id, irc_sh *out)
{
    int st = irc__check_sh(c);
    if (st < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    if (id >= c->capacity)
        return IRC_ERR_RANGE;
    c->port->read_lock(c->lock);
    st = id < c->count ? IRC_OK : IRC_MISS;
    if (st == IRC_OK)
        irc__sh_unpack(c, (const unsigned char *)irc__rec_at(c, id), out);
    c->port->read_unlock(c->lock);
    return st;
}
