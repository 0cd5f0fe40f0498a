/*
 * kind_irr.c -- the irradiance record kind: its packed form (gradients per
 * channel in the tangent frame of the stored normal), its check, the
 * Ward-Heckbert weight and gradient extrapolation as the store's table,
 * and the irradiance calls, thin wrappers over the store.
 */
#include "../block/form.h"
#include "../block/check.h"
#include "../block/octa.h"
#include "../irr/weight.h"
#include "../store/walk.h"
#include "estimator.h"

/* Each channel's 2D vector as int16 mantissas with the channel's own
 * exponent: 2^ex is the smallest power of two with |v| < 2^(ex + 15) for
 * both components, so the larger keeps at least 14 bits (relative
 * precision 2^-14 per channel, whatever the other channels hold). */
static void irc__grad_pack(const float g[3][3], const float t1[3], const float t2[3],
                           irc__grad *out)
{
    int ch, i;
    for (ch = 0; ch < 3; ch++) {
        float gi[3], v[2], big, q;
        int e = 0;
        gi[0] = g[ch][0]; gi[1] = g[ch][1]; gi[2] = g[ch][2];
        v[0] = irc__dot3(gi, t1);
        v[1] = irc__dot3(gi, t2);
        big = IRC_FABSF(v[0]) > IRC_FABSF(v[1]) ? IRC_FABSF(v[0]) : IRC_FABSF(v[1]);
        if (big > 0.0f)
            IRC_FREXPF(big, &e);
        e -= 15;
        /* The int8 range reaches 2^-128: smaller gradients lose bits, as
         * float denormals do. */
        if (e < -128) e = -128;
        if (e > 127) e = 127;
        out->ex[ch] = (int8_t)e;
        for (i = 0; i < 2; i++) {
            q = IRC_FLOORF(IRC_LDEXPF(v[i], -e) + 0.5f);
            out->g[2 * ch + i] = (int16_t)(q > 32767.0f ? 32767.0f : q < -32767.0f ? -32767.0f : q);
        }
    }
    out->unused = 0;
}

static void irc__grad_unpack(const irc__grad *in, const float t1[3], const float t2[3],
                             float g[3][3])
{
    int ch, k;
    for (ch = 0; ch < 3; ch++) {
        float s = irc__grad_scale(in, ch), a = in->g[2 * ch] * s, b = in->g[2 * ch + 1] * s;
        for (k = 0; k < 3; k++)
            g[ch][k] = (float)(a * t1[k] + b * t2[k]);
    }
}

/* A host's ellipse: minor/major in (0, 1] and the major axis projected on
 * the tangent plane; q = 1 (a disk) when minor_radius is 0 or not below
 * radius.  Returns 0, or -1 when the axis has no tangent direction. */
static int irc__ellipse(const irc_record *r, const float un[3], float *q, float axis[3])
{
    float len, m = 0.0f;
    int k;
    *q = 1.0f;
    axis[0] = axis[1] = axis[2] = 0.0f;
    if (!(r->minor_radius > 0.0f) || !(r->minor_radius < r->radius))
        return 0;
    *q = r->minor_radius / r->radius;
    if (*q < 1.0f / IRC_ANISOTROPY)
        *q = 1.0f / IRC_ANISOTROPY;
    for (k = 0; k < 3; k++) {
        axis[k] = r->axis[k];
        if (IRC_FABSF(axis[k]) > m)
            m = IRC_FABSF(axis[k]);
    }
    /* An axis whose squared length would overflow or underflow float is
     * scaled to a largest component of 1 first; any other is left as it
     * is, so its record is the same bits as before. */
    if (m > 1e18f || (m < 1e-18f && m > 0.0f))
        for (k = 0; k < 3; k++)
            axis[k] /= m;
    m = IRC_FABSF(axis[0]) + IRC_FABSF(axis[1]) + IRC_FABSF(axis[2]);
    len = irc__dot3(axis, un);
    for (k = 0; k < 3; k++)
        axis[k] -= len * un[k];
    len = IRC_SQRTF(irc__dot3(axis, axis));
    if (!(len > 1e-6f * m))
        return -1;
    for (k = 0; k < 3; k++)
        axis[k] /= len;
    return 0;
}

static int irc__irr_check(const irc_cache *c, const void *rec, float un[3])
{
    const irc_record *r = (const irc_record *)rec;
    float q, axis[3], t1[3], t2[3];
    int st, ch;
    (void)c;
    if ((st = irc__check_vec(r->p)) < 0 || (st = irc__check_normal(r->n, un)) < 0)
        return st;
    if (!irc__finite3(r->e) || !irc__finite(r->radius) || !irc__finite(r->minor_radius) ||
        !irc__finite3(r->axis))
        return IRC_ERR_NONFINITE;
    /* Gradients are stored in the normal's tangent frame (irc__grad_pack):
     * a finite one whose components there pass float would be stored as
     * another. */
    irc__oct_frame(irc__oct_encode(un), t1, t2);
    for (ch = 0; ch < 3; ch++)
        if (!irc__finite3(r->grad_t[ch]) || !irc__finite3(r->grad_r[ch]) ||
            !irc__finite(irc__dot3(r->grad_t[ch], t1)) ||
            !irc__finite(irc__dot3(r->grad_t[ch], t2)) ||
            !irc__finite(irc__dot3(r->grad_r[ch], t1)) || !irc__finite(irc__dot3(r->grad_r[ch], t2)))
            return IRC_ERR_NONFINITE;
    if (!(r->radius > 0.0f) || r->minor_radius < 0.0f || r->e[0] < 0.0f || r->e[1] < 0.0f ||
        r->e[2] < 0.0f || irc__ellipse(r, un, &q, axis) < 0)
        return IRC_ERR_RANGE;
    return IRC_OK;
}

/* The translational gradient stays within the record's reach: whatever set
 * the radius (the record's own estimate, min_radius, the host), the
 * largest change over the ellipse, sqrt((g.u)^2 R^2 + |g - (g.u)u|^2 (q
 * R)^2) for major axis u, stays within e[c], so extrapolation changes E by
 * at most a fraction a at the edge of reach (Radiance caps its gradients
 * the same way).  A radius lifted past E/|grad E| would otherwise
 * extrapolate far past E. */
static void irc__grad_limit(const irc_record *in, float r, float q, const float u[3],
                            float g[3][3])
{
    int ch, k;
    for (ch = 0; ch < 3; ch++) {
        /* In units of the largest component m: squares of gradients near
         * FLT_MAX would overflow float. */
        float m = 0.0f, len = 0.0f, gu = 0.0f, s;
        for (k = 0; k < 3; k++) {
            g[ch][k] = in->grad_t[ch][k];
            if (IRC_FABSF(g[ch][k]) > m)
                m = IRC_FABSF(g[ch][k]);
        }
        if (!(m > 0.0f))
            continue;
        for (k = 0; k < 3; k++) {
            len += (g[ch][k] / m) * (g[ch][k] / m);
            gu += (g[ch][k] / m) * u[k];
        }
        s = IRC_SQRTF(gu * gu + (len - gu * gu) * q * q) * r;
        if (s * m > in->e[ch])
            for (k = 0; k < 3; k++)
                g[ch][k] = g[ch][k] / m * (in->e[ch] / s);
    }
}

static void irc__irr_pack(const irc_cache *c, const void *rec, const float un[3], void *dst)
{
    const irc_record *in = (const irc_record *)rec;
    unsigned char *b = (unsigned char *)dst;
    irc__rec *r = (irc__rec *)dst;
    float t1[3], t2[3], q, axis[3];
    float g[3][3];
    int ch;
    IRC_MEMSET(dst, 0, c->rec_size);
    for (ch = 0; ch < 3; ch++) {
        r->p[ch] = in->p[ch];
        r->e[ch] = in->e[ch];
    }
    r->r = in->radius < FLT_MIN ? FLT_MIN : in->radius > IRC__CAP ? IRC__CAP : in->radius;
    r->n = irc__oct_encode(un);
    irc__oct_frame(r->n, t1, t2);
    (void)irc__ellipse(in, un, &q, axis); /* checked */
    if (!c->off[IRC__P_ELLIPSE])
        q = 1.0f;
    else {
        irc__aniso *a = (irc__aniso *)(void *)(b + c->off[IRC__P_ELLIPSE]);
        a->q = q;
        a->axis = q < 1.0f ? irc__oct_encode(axis) : 0u;
    }
#ifndef IRC_NO_GUARD
    if (c->off[IRC__P_GUARD])
        IRC_MEMCPY(b + c->off[IRC__P_GUARD], &in->leak_guard, sizeof in->leak_guard);
#endif
    if (c->off[IRC__P_GRAD_T]) {
        irc__grad_limit(in, r->r, q, axis, g);
        irc__grad_pack((const float(*)[3])g, t1, t2, (irc__grad *)(void *)(b + c->off[IRC__P_GRAD_T]));
    }
    if (c->off[IRC__P_GRAD_R])
        irc__grad_pack(in->grad_r, t1, t2, (irc__grad *)(void *)(b + c->off[IRC__P_GRAD_R]));
}

static void irc__irr_unpack(const irc_cache *c, const void *src, void *rec)
{
    const unsigned char *b = (const unsigned char *)src;
    const irc__rec *r = (const irc__rec *)src;
    irc_record *out = (irc_record *)rec;
    float t1[3], t2[3];
    int ch;
    IRC_MEMSET(out, 0, sizeof *out);
    for (ch = 0; ch < 3; ch++) {
        out->p[ch] = r->p[ch];
        out->e[ch] = r->e[ch];
    }
    out->radius = out->minor_radius = r->r;
    if (c->off[IRC__P_ELLIPSE]) {
        const irc__aniso *a = (const irc__aniso *)(const void *)(b + c->off[IRC__P_ELLIPSE]);
        if (a->q < 1.0f) {
            out->minor_radius = a->q * r->r;
            irc__oct_decode(a->axis, out->axis);
        }
    }
#ifndef IRC_NO_GUARD
    if (c->off[IRC__P_GUARD])
        IRC_MEMCPY(&out->leak_guard, b + c->off[IRC__P_GUARD], sizeof out->leak_guard);
#endif
    out->mean_dist = NAN; /* not stored */
    irc__oct_decode(r->n, out->n);
    irc__oct_frame(r->n, t1, t2);
    out->features = c->cfg.features;
    if (c->off[IRC__P_GRAD_T])
        irc__grad_unpack((const irc__grad *)(const void *)(b + c->off[IRC__P_GRAD_T]), t1, t2, out->grad_t);
    if (c->off[IRC__P_GRAD_R])
        irc__grad_unpack((const irc__grad *)(const void *)(b + c->off[IRC__P_GRAD_R]), t1, t2, out->grad_r);
}

static int irc__irr_weigh(const irc_cache *c, const irc__rec *r, const irc__query *q,
                          float *w, float ni[3])
{
    return irc__weigh(c, r, q->p, q->n, 1, w, ni);
}

/* The accumulator: the weighted mean of E per channel so far and its
 * total weight, updated as m += (w / W)(v - m) (West 1979).  A sum of w v
 * in float would overflow for records near FLT_MAX whose extrapolated
 * mean does not; v >= 0, so v - m stays finite. */
static void irc__irr_begin(const irc_cache *c, void *acc)
{
    float *a = (float *)acc;
    (void)c;
    a[0] = a[1] = a[2] = a[3] = 0.0f;
}

/* Returns the blend factor w / W, which the gradient lookup's means take
 * too. */
static float irc__irr_mean(float *a, float w, const float v[3])
{
    float f;
    int ch;
    a[3] += w;
    f = w / a[3];
    for (ch = 0; ch < 3; ch++)
        a[ch] += f * (v[ch] - a[ch]);
    return f;
}

static void irc__irr_accumulate(const irc_cache *c, const irc__rec *r, const irc__query *q,
                                float w, const float ni[3], void *acc)
{
    float v[3];
    irc__extrapolate(c, r, ni, q->p, q->n, v);
    (void)irc__irr_mean((float *)acc, w, v);
}

static int irc__irr_finish(const irc_cache *c, const irc__query *q, const void *acc,
                           float w, void *out)
{
    const float *a = (const float *)acc;
    float *rgb = (float *)out;
    int ch;
    (void)c;
    (void)q;
    for (ch = 0; ch < 3; ch++)
        rgb[ch] = w > 0.0f ? a[ch] : 0.0f;
    /* Records with irradiance and gradients near FLT_MAX can extrapolate
     * past it. */
    if (!irc__finite3(rgb))
        return IRC_ERR_NONFINITE;
    return w > 0.0f ? IRC_OK : IRC_MISS;
}

static void irc__irr_answer(const irc_cache *c, const void *rec, void *out)
{
    const irc_record *r = (const irc_record *)rec;
    float *rgb = (float *)out;
    (void)c;
    rgb[0] = r->e[0];
    rgb[1] = r->e[1];
    rgb[2] = r->e[2];
}

/* The computed record, at its own point (t = 0 of the blended weight),
 * taken into the neighbours' mean that out holds, of weight w: the
 * lookup's own accumulator, one record more. */
static void irc__irr_mix_in(const irc_cache *c, const void *rec, void *out, float w)
{
    float *rgb = (float *)out, a[4];
    (void)c;
    IRC_MEMCPY(a, rgb, 3 * sizeof(float));
    a[3] = w;
    (void)irc__irr_mean(a, irc__biweight(0.0f), ((const irc_record *)rec)->e);
    IRC_MEMCPY(rgb, a, 3 * sizeof(float));
}

static const irc__acc irc__irr_lookup;

/* irc__irr_accumulate's weight and value taken at once (weight.c) */
static float irc__irr_take(const irc_cache *c, const irc__rec *r, const irc__query *q,
                           void *acc)
{
    float v[3];
    const float w = irc__weigh_extrapolate(c, r, q->p, q->n, v);
    if (w > 0.0f)
        (void)irc__irr_mean((float *)acc, w, v);
    return w;
}

static const irc__acc irc__irr_plain;

/* Records with an ellipse or a guard take the general path. */
static int irc__irr_find(irc_cache *c, const irc__query *q, void *out, float *weight)
{
    float acc[4];
    const int plain = !c->off[IRC__P_ELLIPSE] && !c->off[IRC__P_GUARD];
    return irc__lookup_once(c, plain ? &irc__irr_plain : &irc__irr_lookup, q, out, weight, acc);
}

/* The gradient lookup: the same records and weights; its accumulator is
 * the value's (running means of E, then the weight) and the answer's
 * gradient, whose fields hold the running means of the records' dE/dp
 * and dE/dn (irc__extrapolate_grad). */
typedef struct irc__grad_acc {
    float m[4];
    irc_gradient *grad;
} irc__grad_acc;

static void irc__irrg_begin(const irc_cache *c, void *acc)
{
    irc__grad_acc *a = (irc__grad_acc *)acc;
    irc__irr_begin(c, a->m);
    IRC_MEMSET(a->grad, 0, sizeof *a->grad);
}

static void irc__irrg_accumulate(const irc_cache *c, const irc__rec *r, const irc__query *q,
                                 float w, const float ni[3], void *acc)
{
    irc__grad_acc *a = (irc__grad_acc *)acc;
    float v[3];
    irc__extrapolate(c, r, ni, q->p, q->n, v);
    irc__extrapolate_grad(c, r, ni, v, irc__irr_mean(a->m, w, v), a->grad);
}

static int irc__irrg_finish(const irc_cache *c, const irc__query *q, const void *acc,
                            float w, void *out)
{
    const irc__grad_acc *a = (const irc__grad_acc *)acc;
    const irc_gradient *g = a->grad;
    int ch, st = irc__irr_finish(c, q, a->m, w, ((irc__grad_out *)out)->rgb);
    for (ch = 0; ch < 3 && st == IRC_OK; ch++)
        if (!irc__finite3(g->dp[ch]) || !irc__finite3(g->dn[ch]))
            st = IRC_ERR_NONFINITE;
    return st;
}

/* The estimator's record, checked as an inserted one is: finite radiances
 * can still sum past FLT_MAX, and such a record is refused here, before
 * anything is counted. */
static int irc__irr_make(irc__call *k, void *rec)
{
    float un[3];
    /* a progressive cache's records follow its level (progressive.c) */
    int st = k->progress ? irc__irr_progressive(k, (irc_record *)rec) : irc__irr_compute(k, rec);
    return st < 0 ? st : irc__irr_check(k->c, rec, un);
}

/* An irradiance record's parts: the gradients (six int16 mantissas and
 * three int8 exponents and a pad byte each), the ellipse (axis code and
 * minor/major), the leak guard (16 nibbles). */
static uint32_t irc__irr_parts(const irc_config *cfg, irc__recpart *out)
{
    static const irc__recpart grad_t = {IRC__P_GRAD_T, 2, 1, IRC__SANE_ANY, 12, sizeof(irc__grad)},
                           grad_r = {IRC__P_GRAD_R, 2, 1, IRC__SANE_ANY, 12, sizeof(irc__grad)},
                           ellipse = {IRC__P_ELLIPSE, 4, 4, IRC__SANE_ELLIPSE, 0, sizeof(irc__aniso)},
                           guard = {IRC__P_GUARD, 8, 8, IRC__SANE_ANY, 0, sizeof(uint64_t)};
    uint32_t n = 0;
    if (cfg->features & IRC_FEATURE_TRANSLATION)
        out[n++] = grad_t;
    if (cfg->features & IRC_FEATURE_ROTATION)
        out[n++] = grad_r;
    if (cfg->features & IRC_FEATURE_HESSIAN)
        out[n++] = ellipse;
    if (cfg->irr.leak_guard)
        out[n++] = guard;
    return n;
}

/* Its features: zero is the default, both gradients (every measured
 * scene paid for them); bare records are asked for by name, alone.
 * Visibility gradients are how the translational gradient is made. */
static int irc__irr_features(irc_config *cfg)
{
    if (cfg->features == 0u)
        cfg->features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
    else if (cfg->features == IRC_FEATURE_NONE)
        cfg->features = 0u;
    else if (cfg->features & IRC_FEATURE_NONE)
        return IRC_ERR_CONFIG;
    if (cfg->features & IRC_FEATURE_VISIBILITY)
        cfg->features |= IRC_FEATURE_TRANSLATION;
    return IRC_OK;
}

/* Neighbour clamping and confirming rays paid for irradiance records on
 * the real scenes: on unless asked off; the leak guard paid only between
 * rooms: off.  Super-samples follow the first rays, which visibility
 * gradients read as they were. */
/* cfg.irr.full_pixels by default: off.  On the Sponza atrium (a = 0.2,
 * 16 x 64) coarse records cost their noise on every pixel they serve:
 * relative RMSE 0.0342 -> 0.087 with 32, 0.079 with 8 and a 1-pixel
 * floor (bench/notes.md, "Records that cost what they serve"). */
#define IRC__DEF_FULL_PIXELS (-1.0f)
/* cfg.irr.detail_pixels by default: half a pixel.  On the Cornell box it
 * cut the error 8x (a ceiling row beside the light's edge); on six real
 * views the error stayed within 7% for 0.77-0.99x the time (bench/notes.md,
 * "Detail computed per pixel"). */
#define IRC__DEF_DETAIL_PIXELS 0.5f

/* cfg.irr.blend by default, and its bound.  On three Sponza views (320 x
 * 240, a = 0.3, 16 x 64, one thread, paired) blend 2 cut the relative
 * RMSE 6-13% and the 99th percentile 20-35% for 0.4% more rays (more
 * confirming rays a lookup); 3 cut the atrium's a little more, with more
 * bias (bench/notes.md, "Noise and bias").  A reach four times the
 * placement's already averages some 16 times the records. */
#define IRC__DEF_BLEND 2.0f
#define IRC__BLEND_MAX 4.0f

/* A record's reach a R in pixels at its point, from the _px call's
 * footprint (pbrt-v2's maximum pixel spacing; its 2.5-pixel minimum cost
 * 2.5-3.7x the error on four of six corpus views: none). */
#define IRC__DEF_MIN_PIXELS (-1.0f)
#define IRC__DEF_MAX_PIXELS 15.0f

/* A count of pixels in the irradiance config: finite; 0 takes def, and a
 * negative value (off, or that side unbounded) is kept as -1, the one
 * encoding of "none" every pixel count of the config resolves to. */
static int irc__pixels_resolve(float *v, float def)
{
    if (!(*v >= -FLT_MAX && *v <= FLT_MAX))
        return IRC_ERR_CONFIG;
    if (*v == 0.0f)
        *v = def;
    if (*v < 0.0f)
        *v = -1.0f;
    return IRC_OK;
}

/* A count past IRC__CAP bounds nothing a radius can reach: held there, so
 * that its products with a footprint stay where 2^100's do. */
static void irc__pixels_cap(float *v)
{
    if (*v > IRC__CAP)
        *v = IRC__CAP;
}

static int irc__irr_resolve(irc_config *cfg)
{
    const uint32_t strata = cfg->strata_theta * cfg->strata_phi;
#ifdef IRC_NO_SUPERSAMPLE
    if (cfg->irr.supersamples)
        return IRC_ERR_UNSUPPORTED;
#endif
#ifdef IRC_NO_GUARD
    if (cfg->irr.leak_guard == IRC_ON)
        return IRC_ERR_UNSUPPORTED;
#endif
    if (irc__irr_features(cfg) < 0 || cfg->irr.leak_guard > IRC_OFF ||
        cfg->irr.supersamples > strata ||
        (cfg->irr.supersamples && (cfg->features & IRC_FEATURE_VISIBILITY)))
        return IRC_ERR_CONFIG;
    if (irc__pixels_resolve(&cfg->irr.full_pixels, IRC__DEF_FULL_PIXELS) < 0 ||
        irc__pixels_resolve(&cfg->irr.detail_pixels, IRC__DEF_DETAIL_PIXELS) < 0 ||
        irc__pixels_resolve(&cfg->irr.min_pixels, IRC__DEF_MIN_PIXELS) < 0 ||
        irc__pixels_resolve(&cfg->irr.max_pixels, cfg->irr.min_pixels > IRC__DEF_MAX_PIXELS
                                                      ? cfg->irr.min_pixels
                                                      : IRC__DEF_MAX_PIXELS) < 0)
        return IRC_ERR_CONFIG;
    if (cfg->irr.blend == 0.0f)
        cfg->irr.blend = IRC__DEF_BLEND;
    if (!(cfg->irr.blend >= 1.0f && cfg->irr.blend <= IRC__BLEND_MAX))
        return IRC_ERR_CONFIG;
    /* a default maximum never falls below the host's minimum */
    if (cfg->irr.max_pixels > 0.0f && cfg->irr.max_pixels < cfg->irr.min_pixels)
        return IRC_ERR_CONFIG;
    irc__pixels_cap(&cfg->irr.min_pixels);
    irc__pixels_cap(&cfg->irr.max_pixels);
    irc__pixels_cap(&cfg->irr.full_pixels);
    irc__pixels_cap(&cfg->irr.detail_pixels);
    /* Coarser grids for small records move strata that visibility
     * gradients, the Hessian and super-samples read as first cast
     * (irradiance.c, irc__pilot_level). */
    if (cfg->irr.full_pixels > 0.0f &&
        ((cfg->features & (IRC_FEATURE_VISIBILITY | IRC_FEATURE_HESSIAN)) || cfg->irr.supersamples))
        return IRC_ERR_CONFIG;
    irc__switch_defaults(cfg, IRC_ON, IRC_ON);
    cfg->irr.leak_guard = cfg->irr.leak_guard == IRC_ON;
    return IRC_OK;
}

/* The scratch the estimators read (kind.h, IRC__S_*): the gradients'
 * inverse distances and rows (gradient.c); directions and hit normals for
 * the visibility gradients and the Hessian; the strata's edges and their
 * crossings (visibility.c); rows of vertices and triangle radiances
 * (hessian.c), over the rays' and the gradients' bytes (kind.h). */
static void irc__irr_scratch(const irc_config *cfg, irc__scratch *s)
{
    const uint32_t f = cfg->features, strata = cfg->strata_theta * cfg->strata_phi;
    const uint64_t edges = 2u * (uint64_t)strata + cfg->strata_phi;
    s->samples = strata;
    s->keep_geom = (f & (IRC_FEATURE_VISIBILITY | IRC_FEATURE_HESSIAN)) != 0;
    if (f & (IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION))
        s->bytes[IRC__S_INV] = irc__gscratch_floats(strata, cfg->strata_phi) * sizeof(float);
    if (s->keep_geom)
        s->bytes[IRC__S_DIRS] = s->bytes[IRC__S_NORMALS] = (uint64_t)strata * 3u * sizeof(float);
    if (f & IRC_FEATURE_VISIBILITY) {
        s->bytes[IRC__S_EDGES] = edges * sizeof(int32_t);
        s->bytes[IRC__S_CROSS] = edges * sizeof(irc__cross);
    }
    if (f & IRC_FEATURE_HESSIAN) {
        const uint64_t need = irc__hscratch_floats(cfg->strata_theta, cfg->strata_phi) *
                              sizeof(float),
                       reuse = irc__rays_bytes(cfg) + s->bytes[IRC__S_INV];
        s->bytes[IRC__S_HESS] = need > reuse ? need - reuse : 0u;
    }
}

static int irc__irrg_find(irc_cache *c, const irc__query *q, void *out, float *weight);

/* Only irc_cache_lookup_gradient uses it: the kind's records, summed with
 * their gradients' extrapolation. */
const irc__acc irc__irr_grad_lookup = {.weigh = irc__irr_weigh,
    .begin = irc__irrg_begin,
    .accumulate = irc__irrg_accumulate,
    .finish = irc__irrg_finish,
    .find = irc__irrg_find};

static int irc__irrg_find(irc_cache *c, const irc__query *q, void *out, float *weight)
{
    irc__grad_acc acc;
    acc.grad = ((irc__grad_out *)out)->grad;
    return irc__lookup_once(c, &irc__irr_grad_lookup, q, out, weight, &acc);
}

static const irc__acc irc__irr_lookup = {.weigh = irc__irr_weigh,
    .begin = irc__irr_begin,
    .accumulate = irc__irr_accumulate,
    .finish = irc__irr_finish,
    .find = irc__irr_find};
static const irc__acc irc__irr_plain = {.weigh = irc__irr_weigh,
    .begin = irc__irr_begin,
    .accumulate = irc__irr_accumulate,
    .finish = irc__irr_finish,
    .find = irc__irr_find,
    .take = irc__irr_take};

/* The bits this build leaves out (util.h). */
#if defined(IRC_NO_VISIBILITY) && defined(IRC_NO_HESSIAN)
#define IRC__IRR_UNBUILT (IRC_FEATURE_VISIBILITY | IRC_FEATURE_HESSIAN)
#elif defined(IRC_NO_VISIBILITY)
#define IRC__IRR_UNBUILT IRC_FEATURE_VISIBILITY
#elif defined(IRC_NO_HESSIAN)
#define IRC__IRR_UNBUILT IRC_FEATURE_HESSIAN
#else
#define IRC__IRR_UNBUILT 0u
#endif

/* Lookups reach blend a R when they blend wider (weight.c), and a record
 * at a R weighs what the biweight gives it there. */
static void irc__irr_reach(const irc_config *cfg, float *reach_a, float *w_inner)
{
    if (cfg->irr.blend > 1.0f) {
        *reach_a = cfg->accuracy * cfg->irr.blend;
        *w_inner = irc__biweight(1.0f / cfg->irr.blend);
    }
}

/* The inverse of irc__irr_features and of the leak guard's switch. */
static void irc__irr_publish(irc_config *cfg)
{
    if (cfg->features == 0u)
        cfg->features = IRC_FEATURE_NONE;
    cfg->irr.leak_guard = cfg->irr.leak_guard ? IRC_ON : IRC_OFF;
}

const irc__kind irc__kind_irr = {
    .id = IRC__KIND_IRR_ID,
    .features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_VISIBILITY |
                IRC_FEATURE_HESSIAN | IRC_FEATURE_NONE,
    .unbuilt = IRC__IRR_UNBUILT,
    .record_bytes = (uint32_t)sizeof(irc_record),
    .cfg_at = (uint32_t)offsetof(irc_config, irr),
    .cfg_bytes = (uint32_t)sizeof(struct irc_config_irr),
    .resolve = irc__irr_resolve,
    .parts = irc__irr_parts,
    .scratch = irc__irr_scratch,
    .compute = irc__irr_make,
    .check = irc__irr_check,
    .pack = irc__irr_pack,
    .unpack = irc__irr_unpack,
    .answer = irc__irr_answer,
    .mix_in = irc__irr_mix_in,
    .publish = irc__irr_publish,
    .reach = irc__irr_reach,
    .lookup = &irc__irr_lookup};
