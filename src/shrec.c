/*
 * shrec.c -- SH records: from the sums (shgrad.c) to a record, its packed
 * form, and the SH calls (compute, insert, lookup by Eq. 14-16, read
 * back).
 */
#include "cache.h"

/* Cap on a free-point weight: a query on a record gives 1/0. */
#define IRC__SH_W_MAX 1e6

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

/* What compute and lookup check first: an SH cache, an output, a finite
 * point, and a usable normal when one is given (unit in un). */
static int irc__sh_query(const irc_cache *c, const float p[3], const float *n, const void *out,
                         double un[3])
{
    int st;
    if ((st = irc__check_sh(c)) < 0)
        return st;
    if (!out)
        return IRC_ERR_NULL;
    if ((st = irc__check_vec(p)) < 0 || (n && (st = irc__check_normal(n, un)) < 0))
        return st;
    return IRC_OK;
}


int irc_sh_compute(irc_cache *c, const float p[3], const float n[3], irc_sh *out)
{
    irc__shsum a;
    irc_sh rec;
    double un[3];
    uint32_t t;
    int st, k;
    if ((st = irc__sh_query(c, p, n, out, un)) < 0)
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
    irc__count_compute(c, a.total);
    return IRC_OK;
}

int irc_sh_insert(irc_cache *c, const irc_sh *rec)
{
    /* The largest record (32 + 25 x 3 x 4 x 4 bytes), aligned as a record. */
    union { irc__rec head; float f[8 + IRC__NC * 3 * 4]; } packed;
    double un[3];
    int st;
    if ((st = irc__check_sh(c)) < 0)
        return st;
    if (!rec)
        return IRC_ERR_NULL;
    if ((st = irc__sh_check(c, rec, un)) < 0)
        return st;
    irc__sh_pack(c, rec, un, (unsigned char *)&packed);
    return irc__store(c, &packed);
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
    if ((st = irc__sh_query(c, p, n, out, un)) < 0)
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
    return irc__count_lookup(c, irc__sh_lookup(c, p, n, out, weight));
}

int irc_sh_lookup_or_compute(irc_cache *c, const float p[3], const float n[3],
                             irc_sh *out, float *weight)
{
    irc_sh rec;
    int st = irc__sh_lookup(c, p, n, out, weight);
    if (st != IRC_MISS)
        return irc__count_lookup(c, st);
    if ((st = irc_sh_compute(c, p, n, &rec)) < 0)
        return st;
    if ((st = irc__count_miss(c, irc_sh_insert(c, &rec))) < 0)
        return st;
    *out = rec;
    if (weight)
        *weight = 0.0f;
    return st;
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
