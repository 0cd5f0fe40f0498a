/*
 * kind_sh.c -- the SH record kind (IRC_FEATURE_SH): from the estimator's
 * sums (shgrad.c) to a record, its packed form and check, the weights and
 * the extrapolation of Eq. 14-16 as the store's table, and the SH calls,
 * thin wrappers over the store.
 */
#include "../block/form.h"
#include "../block/check.h"
#include "../block/octa.h"
#include "../irr/estimator.h"
#include "../store/walk.h"
#include "shrec.h"

#ifndef IRC_NO_SH

/* Cap on a free-point weight: a query on a record gives 1/0. */
#define IRC__SH_W_MAX 1e6f

/* The record from the sums: each usable sample stands for 2 pi/(M N)
 * steradians, scaled by total/used when some rays failed. */
static void irc__sh_finish(const irc_cache *c, const irc__shsum *a, irc_sh *out)
{
    const float dw = 2.0f * IRC_PI / c->strata * ((float)a->total / a->used);
    float hm = a->inv_d > 0.0f ? a->used / a->inv_d : HUGE_VALF, r = hm;
    uint32_t ch, i, k;
    out->bands = c->cfg.sh.bands;
    out->channels = IRC__SH_CH(c);
    out->features = c->cfg.features;
    out->rays = a->total;
    out->rays_used = a->used;
    for (ch = 0; ch < 3; ch++)
        out->e[ch] = (float)(dw * a->e[ch]);
    for (ch = 0; ch < IRC__SH_CH(c); ch++) {
        float len;
        for (i = 0; i < IRC__SH_N(c); i++) {
            out->c[ch][i] = (float)(dw * a->c[ch][i]);
            for (k = 0; k < 3; k++)
                out->grad[ch][i][k] = (float)(dw * a->g[ch][3 * i + k]);
        }
        /* R <= |c_0|/|grad c_0|: where first-order extrapolation would
         * change the mean radiance by 100%. */
        len = dw * IRC_SQRTF(irc__dot3(a->g[ch], a->g[ch]));
        if (len > 0.0f && dw * IRC_FABSF(a->c[ch][0]) / len < r)
            r = dw * IRC_FABSF(a->c[ch][0]) / len;
    }
    if (r < c->cfg.min_radius) r = c->cfg.min_radius;
    if (r > c->cfg.max_radius) r = c->cfg.max_radius;
    if (r < FLT_MIN) r = FLT_MIN;
    out->radius = r;
}

static int irc__sh_check(const irc_cache *c, const void *rec, float un[3])
{
    const irc_sh *r = (const irc_sh *)rec;
    uint32_t ch, i;
    int st;
    if ((st = irc__check_vec(r->p)) < 0)
        return st;
    un[0] = un[1] = un[2] = 0.0f;
    if ((r->n[0] != 0.0f || r->n[1] != 0.0f || r->n[2] != 0.0f) &&
        (st = irc__check_normal(r->n, un)) < 0)
        return st;
    if (r->bands != c->cfg.sh.bands || r->channels != IRC__SH_CH(c))
        return IRC_ERR_RANGE;
    if (!irc__finite3(r->e) || !irc__finite(r->radius))
        return IRC_ERR_NONFINITE;
    for (ch = 0; ch < IRC__SH_CH(c); ch++)
        for (i = 0; i < IRC__SH_N(c); i++)
            if (!irc__finite(r->c[ch][i]) || !irc__finite3(r->grad[ch][i]))
                return IRC_ERR_NONFINITE;
    return r->radius > 0.0f && r->e[0] >= 0.0f && r->e[1] >= 0.0f && r->e[2] >= 0.0f
               ? IRC_OK : IRC_ERR_RANGE;
}

static void irc__sh_pack(const irc_cache *c, const void *rec, const float un[3], void *out)
{
    const irc_sh *in = (const irc_sh *)rec;
    unsigned char *dst = (unsigned char *)out;
    irc__rec *r = (irc__rec *)out;
    float *cf = (float *)(void *)(dst + c->off[IRC__P_SH]);
    float *gf = c->off[IRC__P_SH_GRAD] ? (float *)(void *)(dst + c->off[IRC__P_SH_GRAD]) : NULL;
    uint32_t ch, i, k;
    IRC_MEMSET(dst, 0, c->rec_size);
    for (k = 0; k < 3; k++) {
        r->p[k] = in->p[k];
        r->e[k] = in->e[k];
    }
    r->r = in->radius > IRC__CAP ? IRC__CAP : in->radius;
    r->n = un[0] == 0.0f && un[1] == 0.0f && un[2] == 0.0f ? IRC__FREE : irc__oct_encode(un);
    for (ch = 0; ch < IRC__SH_CH(c); ch++)
        for (i = 0; i < IRC__SH_N(c); i++) {
            *cf++ = in->c[ch][i];
            if (gf)
                for (k = 0; k < 3; k++)
                    *gf++ = in->grad[ch][i][k];
        }
}

static void irc__sh_unpack(const irc_cache *c, const void *rec, void *dst)
{
    const unsigned char *src = (const unsigned char *)rec;
    const irc__rec *r = (const irc__rec *)rec;
    irc_sh *out = (irc_sh *)dst;
    const float *cf = (const float *)(const void *)(src + c->off[IRC__P_SH]);
    const float *gf = c->off[IRC__P_SH_GRAD] ? (const float *)(const void *)(src + c->off[IRC__P_SH_GRAD]) : NULL;
    uint32_t ch, i, k;
    IRC_MEMSET(out, 0, sizeof *out);
    for (k = 0; k < 3; k++) {
        out->p[k] = r->p[k];
        out->e[k] = r->e[k];
    }
    if (r->n != IRC__FREE)
        irc__oct_decode(r->n, out->n);
    out->radius = r->r;
    out->bands = c->cfg.sh.bands;
    out->channels = IRC__SH_CH(c);
    out->features = c->cfg.features;
    for (ch = 0; ch < IRC__SH_CH(c); ch++)
        for (i = 0; i < IRC__SH_N(c); i++) {
            out->c[ch][i] = *cf++;
            if (gf)
                for (k = 0; k < 3; k++)
                    out->grad[ch][i][k] = *gf++;
        }
}

/* What lets SH borrow the irradiance kind's weight: its parts are
 * numbered below the ellipse's and the guard's. */
typedef char irc__sh_parts_below[(int)IRC__P_SH_GRAD < (int)IRC__P_ELLIPSE ? 1 : -1];

/* Surface records: Ward-Heckbert (weight.c).  Free points: (R_j/d)^b
 * within a R_j (Eq. 16 made scale-free). */
static int irc__sh_weigh(const irc_cache *c, const irc__rec *r, const irc__query *q,
                         float *w, float ni[3])
{
    float dx = q->p[0] - r->p[0], dy = q->p[1] - r->p[1],
           dz = q->p[2] - r->p[2], d, ra = irc__reach(c, r->r);
    if (!q->free)
        /* the irradiance kind's weight, through its table: its ellipse
         * and guard parts (2 and 3) are none in an SH block, whose kind
         * numbers two parts (shrec.h) */
        return irc__kind_irr.lookup->weigh(c, r, q, w, ni);
    if (r->n != IRC__FREE)
        return 0;
    d = IRC_SQRTF(dx * dx + dy * dy + dz * dz);
    if (!(d < ra || d == 0.0f)) /* its own point always (irc__within_reach) */
        return 0;
    *w = d * IRC__SH_W_MAX > r->r ? IRC_POWF(r->r / d, c->cfg.sh.power) : IRC__SH_W_MAX;
    if (*w > IRC__SH_W_MAX)
        *w = IRC__SH_W_MAX;
    return 1;
}

/* A lookup's running sums: coefficients, their gradients, E. */
typedef struct irc__sh_acc {
    float c[3][IRC__NC], g[3][IRC__NC][3], e[3];
} irc__sh_acc;

static void irc__sh_begin(const irc_cache *c, void *acc)
{
    (void)c;
    IRC_MEMSET(acc, 0, sizeof(irc__sh_acc));
}

/* Eq. 15: each accepted record extrapolated to p (Eq. 14), weighted. */
static void irc__sh_gather(const irc_cache *c, const irc__rec *r, const irc__query *q,
                               float w, const float ni[3], void *acc)
{
    irc__sh_acc *a = (irc__sh_acc *)acc;
    const unsigned char *b = (const unsigned char *)r;
    const float *cf = (const float *)(const void *)(b + c->off[IRC__P_SH]);
    const float *gf = c->off[IRC__P_SH_GRAD] ? (const float *)(const void *)(b + c->off[IRC__P_SH_GRAD]) : NULL;
    float d[3];
    uint32_t ch, i, k;
    (void)ni;
    for (k = 0; k < 3; k++) {
        d[k] = q->p[k] - r->p[k];
        a->e[k] += w * r->e[k];
    }
    for (ch = 0; ch < IRC__SH_CH(c); ch++)
        for (i = 0; i < IRC__SH_N(c); i++) {
            float v = *cf++;
            if (gf) {
                for (k = 0; k < 3; k++) {
                    v += gf[k] * d[k];
                    a->g[ch][i][k] += w * gf[k];
                }
                gf += 3;
            }
            a->c[ch][i] += w * v;
        }
}

static void irc__sh_blank(const irc_cache *c, const irc__query *q, irc_sh *out)
{
    uint32_t k;
    IRC_MEMSET(out, 0, sizeof *out);
    out->bands = c->cfg.sh.bands;
    out->channels = IRC__SH_CH(c);
    out->features = c->cfg.features;
    for (k = 0; k < 3; k++) {
        out->p[k] = q->p[k];
        out->n[k] = q->n[k];
    }
}

static int irc__sh_end(const irc_cache *c, const irc__query *q, const void *acc, float w,
                       void *dst)
{
    const irc__sh_acc *a = (const irc__sh_acc *)acc;
    irc_sh *out = (irc_sh *)dst;
    uint32_t ch, i, k;
    int st;
    irc__sh_blank(c, q, out);
    if (!(w > 0.0f))
        return IRC_MISS;
    for (k = 0; k < 3; k++)
        out->e[k] = (float)(a->e[k] / w);
    st = irc__finite3(out->e) ? IRC_OK : IRC_ERR_NONFINITE;
    for (ch = 0; ch < IRC__SH_CH(c); ch++)
        for (i = 0; i < IRC__SH_N(c); i++) {
            out->c[ch][i] = (float)(a->c[ch][i] / w);
            for (k = 0; k < 3; k++)
                out->grad[ch][i][k] = (float)(a->g[ch][i][k] / w);
            /* Huge gradients far from their record can overflow float. */
            if (!irc__finite(out->c[ch][i]) || !irc__finite3(out->grad[ch][i]))
                st = IRC_ERR_NONFINITE;
        }
    return st;
}

static void irc__sh_answer(const irc_cache *c, const void *rec, void *out)
{
    (void)c;
    *(irc_sh *)out = *(const irc_sh *)rec;
}

static int irc__sh_compute(irc__call *k, void *rec)
{
    irc_cache *c = k->c;
    irc_sh *out = (irc_sh *)rec;
    irc__shsum a;
    float un[3];
    int st, i;
    IRC_MEMSET(&a, 0, sizeof a);
    if ((st = irc__sh_sample(k, &a)) < 0)
        return st;
    IRC_MEMSET(out, 0, sizeof *out);
    irc__sh_finish(c, &a, out);
    for (i = 0; i < 3; i++) {
        out->p[i] = k->q.p[i];
        out->n[i] = k->q.n[i];
    }
    /* Finite radiances can still sum past FLT_MAX. */
    return irc__sh_check(c, out, un);
}

static const irc__acc irc__sh_lookup;

static int irc__sh_find(irc_cache *c, const irc__query *q, void *out, float *weight)
{
    irc__sh_acc acc;
    return irc__lookup_once(c, &irc__sh_lookup, q, out, weight, &acc);
}

/* An SH record's parts: the coefficients c[channel][i], then with
 * SH_GRADIENT their gradients grad[channel][i][x, y, z], floats. */
static uint32_t irc__sh_parts(const irc_config *cfg, irc__recpart *out)
{
    const uint32_t k = cfg->sh.bands * cfg->sh.bands * cfg->sh.channels;
    irc__recpart p;
    uint32_t n = 0;
    p.w1 = p.w2 = 4;
    p.sane = IRC__SANE_FINITE;
    p.lead = 0;
    p.id = IRC__P_SH;
    p.bytes = k * (uint32_t)sizeof(float);
    out[n++] = p;
    if (cfg->features & IRC_FEATURE_SH_GRADIENT) {
        p.id = IRC__P_SH_GRAD;
        p.bytes = 3u * k * (uint32_t)sizeof(float);
        out[n++] = p;
    }
    return n;
}

/* The SH fields' defaults: L = 3, RGB, the glossy lobe's power 2.  Neither
 * neighbour clamping nor confirming rays was measured for SH records: off
 * unless asked on. */
static int irc__sh_resolve(irc_config *cfg)
{
    if (cfg->features & IRC_FEATURE_SH_GRADIENT)
        cfg->features |= IRC_FEATURE_SH;
    if (cfg->sh.bands == 0) cfg->sh.bands = 3u;
    if (cfg->sh.channels == 0) cfg->sh.channels = 3u;
    if (cfg->sh.power == 0.0f) cfg->sh.power = 2.0f;
    if (cfg->sh.bands > IRC_SH_MAX_BANDS || (cfg->sh.channels != 1u && cfg->sh.channels != 3u) ||
        !(cfg->sh.power > 0.0f && cfg->sh.power <= 16.0f))
        return IRC_ERR_CONFIG;
    irc__switch_defaults(cfg, IRC_OFF, IRC_OFF);
    return IRC_OK;
}

/* Free points sample two hemispheres (the sphere); the estimator reads
 * each sample's direction and hit normal. */
static void irc__sh_scratch(const irc_config *cfg, irc__scratch *s)
{
    s->samples = 2u * cfg->strata_theta * cfg->strata_phi;
    s->keep_geom = 1;
    s->bytes[IRC__S_DIRS] = s->bytes[IRC__S_NORMALS] = (uint64_t)s->samples * 3u * sizeof(float);
}

static const irc__acc irc__sh_lookup = {.weigh = irc__sh_weigh,
    .begin = irc__sh_begin,
    .accumulate = irc__sh_gather,
    .finish = irc__sh_end,
    .find = irc__sh_find};

const irc__kind irc__kind_sh = {
    .id = IRC__KIND_SH_ID,
    .features = IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT,
    .free_points = 1,
    .uniform = 1,
    .record_bytes = (uint32_t)sizeof(irc_sh),
    .cfg_at = (uint32_t)offsetof(irc_config, sh),
    .cfg_bytes = (uint32_t)sizeof(struct irc_config_sh),
    .snap_at = {(uint32_t)offsetof(irc_config, sh.bands),
                (uint32_t)offsetof(irc_config, sh.channels)},
    .resolve = irc__sh_resolve,
    .parts = irc__sh_parts,
    .scratch = irc__sh_scratch,
    .compute = irc__sh_compute,
    .check = irc__sh_check,
    .pack = irc__sh_pack,
    .unpack = irc__sh_unpack,
    .answer = irc__sh_answer,
    .lookup = &irc__sh_lookup};

#else /* IRC_NO_SH: the public calls and the kind's table are absent.c's */

typedef int irc__kind_sh_absent; /* ISO C wants something in a file */

#endif
