/*
 * record.c -- a record from the stratified samples: irradiance, harmonic
 * mean distance, gradients, radius; and the packed form the cache stores.
 */
#include "cache.h"

/* Failed strata take the mean radiance of the usable ones: the irradiance is
 * then the mean over usable strata, and a uniform scene keeps a zero
 * rotational gradient.  Their distance stays NaN, so no translational
 * boundary term touches them. */
static void irc__fill_failed(irc__sample *s, uint32_t total, uint32_t used)
{
    double sum[3] = {0, 0, 0};
    uint32_t i;
    int c;
    if (used == total)
        return;
    for (i = 0; i < total; i++)
        if (s[i].d == s[i].d)
            for (c = 0; c < 3; c++)
                sum[c] += s[i].l[c];
    for (i = 0; i < total; i++)
        if (s[i].d != s[i].d)
            for (c = 0; c < 3; c++)
                s[i].l[c] = (float)(sum[c] / used);
}

static double irc__nearer(float a, float b)
{
    return a < b ? (double)a : (double)b;
}

/* Translational gradient, the stratified form of Krivanek et al. 2005: the
 * radiance difference across every boundary between neighbouring strata
 * times the rate at which the boundary sweeps solid angle, using the nearer
 * of the two hit distances.  Rows: theta_j- = asin(sqrt(j/M)); a boundary
 * between rows j-1 and j in column k moves along u_k with weight
 * (2 pi/N) cos^2(theta_j-) sin(theta_j-) / d.  Columns: the boundary at
 * phi = 2 pi k/N moves along v_k- with weight
 * cos(theta_j) (cos theta_j- - cos theta_j+) / (sin(theta_j) d), theta_j the
 * row's centre.  Unlike one open implementation, the boundary between rows
 * 0 and 1 is included. */
static void irc__grad_trans(const irc_cache *c, const irc__sample *s,
                            const double t1[3], const double t2[3], double g[3][3])
{
    const uint32_t m = c->cfg.strata_theta, nphi = c->cfg.strata_phi;
    double *row = irc__slot_rows(c, s);
    /* With visibility gradients, edges holding a silhouette are left to
     * visibility.c; the others keep these terms. */
    const int vis = (c->cfg.features & IRC_FEATURE_VISIBILITY) != 0;
    const int32_t *eh = vis ? irc__slot_edges(c, s) : NULL, *ev = vis ? eh + c->strata : NULL;
    const irc__cross *x = vis ? irc__slot_cross(c, s) : NULL;
    uint32_t j, k;
    int ch, i;
    /* The boundary weights depend on the row only: once per row, into the
     * slot, so a stratum costs two divisions. */
    for (j = 0; j < m; j++) {
        double s2lo = (double)j / m, s2hi = (double)(j + 1) / m, s2c = (j + 0.5) / m;
        row[2 * j] = (2.0 * IRC_PI / nphi) * (1.0 - s2lo) * IRC_SQRT(s2lo);
        row[2 * j + 1] = IRC_SQRT(1.0 - s2c) * (IRC_SQRT(1.0 - s2lo) - IRC_SQRT(1.0 - s2hi)) /
                         IRC_SQRT(s2c);
    }
    for (ch = 0; ch < 3; ch++)
        g[ch][0] = g[ch][1] = g[ch][2] = 0.0;
    for (k = 0; k < nphi; k++) {
        double phc = 2.0 * IRC_PI * (k + 0.5) / nphi, phb = 2.0 * IRC_PI * k / nphi;
        double uk[3], vk[3], ru[3] = {0, 0, 0}, rv[3] = {0, 0, 0};
        for (i = 0; i < 3; i++) {
            uk[i] = IRC_COS(phc) * t1[i] + IRC_SIN(phc) * t2[i];
            vk[i] = -IRC_SIN(phb) * t1[i] + IRC_COS(phb) * t2[i];
        }
        for (j = 0; j < m; j++) {
            const irc__sample *a = &s[j * nphi + k];
            const irc__sample *left = &s[j * nphi + (k + nphi - 1) % nphi];
            double d;
            if (j > 0 && !(vis && ev[(j - 1) * nphi + k] >= 0 && x[ev[(j - 1) * nphi + k]].ok)) {
                const irc__sample *below = &s[(j - 1) * nphi + k];
                d = irc__nearer(a->d, below->d);
                if (d == d && d < HUGE_VAL) {
                    double w = row[2 * j] / d;
                    for (ch = 0; ch < 3; ch++)
                        ru[ch] += w * ((double)a->l[ch] - below->l[ch]);
                }
            }
            d = irc__nearer(a->d, left->d);
            if (vis) {
                int32_t e = eh[j * nphi + (k + nphi - 1) % nphi];
                if (e >= 0 && x[e].ok)
                    d = HUGE_VAL;
            }
            if (nphi > 1 && d == d && d < HUGE_VAL) {
                double w = row[2 * j + 1] / d;
                for (ch = 0; ch < 3; ch++)
                    rv[ch] += w * ((double)a->l[ch] - left->l[ch]);
            }
        }
        for (ch = 0; ch < 3; ch++)
            for (i = 0; i < 3; i++)
                g[ch][i] += ru[ch] * uk[i] + rv[ch] * vk[i];
    }
}

/* Rotational gradient (Ward-Heckbert 1992): grad_r = integral of
 * L(w) (n x w) dw, so that E(n') ~ E + (n x n').grad_r.  With n x w =
 * sin(theta) v(phi), each stratum's share is integrated exactly over the
 * stratum instead of sampled with tan(theta_j) as in the paper's estimator:
 * the horizon row's 1/cos(theta) otherwise gives the estimate a heavy tail.
 * Row weight W_j = integral of sin^2(theta) dtheta over row j; column vector
 * V_k = integral of v(phi) dphi = (cos phi_k+1 - cos phi_k, sin phi_k+1 -
 * sin phi_k), a fixed rotation-and-scale of (cos phi_k, sin phi_k), so the
 * boundary angles advance by recurrence and no stratum needs a trig call. */
static void irc__grad_rot(const irc_cache *c, const irc__sample *s,
                          const double t1[3], const double t2[3], double g[3][3])
{
    const uint32_t m = c->cfg.strata_theta, nphi = c->cfg.strata_phi;
    const double dphi = 2.0 * IRC_PI / nphi, cd = IRC_COS(dphi), sd = IRC_SIN(dphi);
    double acc[3][2] = {{0, 0}, {0, 0}, {0, 0}}, th0 = 0.0, sc0 = 0.0;
    uint32_t j, k;
    int ch, i;
    for (j = 0; j < m; j++) {
        double s1 = (double)(j + 1) / m, th1 = IRC_ASIN(IRC_SQRT(s1));
        double sc1 = IRC_SQRT(s1 * (1.0 - s1)); /* sin(2 theta)/2 */
        double w = 0.5 * (th1 - th0) - 0.5 * (sc1 - sc0), cp = 1.0, sp = 0.0;
        for (k = 0; k < nphi; k++) {
            const irc__sample *a = &s[j * nphi + k];
            double t;
            for (ch = 0; ch < 3; ch++) {
                acc[ch][0] += w * a->l[ch] * cp;
                acc[ch][1] += w * a->l[ch] * sp;
            }
            t = cp * cd - sp * sd;
            sp = sp * cd + cp * sd;
            cp = t;
        }
        th0 = th1;
        sc0 = sc1;
    }
    for (ch = 0; ch < 3; ch++) {
        /* V_k = [[cd - 1, -sd], [sd, cd - 1]] (cos phi_k, sin phi_k) */
        double a = (cd - 1.0) * acc[ch][0] - sd * acc[ch][1];
        double b = sd * acc[ch][0] + (cd - 1.0) * acc[ch][1];
        for (i = 0; i < 3; i++)
            g[ch][i] = a * t1[i] + b * t2[i];
    }
}

void irc__record_build(const irc_cache *c, const irc__sample *s,
                       const double n[3], const double t1[3],
                       const double t2[3], double gvis[3][3], irc_record *out)
{
    const uint32_t total = c->strata;
    double sum[3] = {0, 0, 0}, inv = 0.0, hm, r, g[3][3];
    uint32_t i, used = 0;
    int ch, k;

    for (i = 0; i < total; i++) {
        if (s[i].d != s[i].d)
            continue;
        used++;
        inv += 1.0 / (double)s[i].d;
        for (ch = 0; ch < 3; ch++)
            sum[ch] += s[i].l[ch];
    }
    IRC_MEMSET(out, 0, sizeof *out);
    irc__fill_failed((irc__sample *)s, total, used);
    for (ch = 0; ch < 3; ch++) {
        out->e[ch] = (float)(IRC_PI * sum[ch] / used);
        out->n[ch] = (float)n[ch];
    }
    hm = inv > 0.0 ? used / inv : HUGE_VAL;
    r = hm;
    if (c->cfg.features & IRC_FEATURE_TRANSLATION) {
        irc__grad_trans(c, s, t1, t2, g);
        for (ch = 0; ch < 3; ch++)
            for (k = 0; k < 3; k++)
                g[ch][k] += gvis ? gvis[ch][k] : 0.0;
        for (ch = 0; ch < 3; ch++) {
            double len = IRC_SQRT(irc__dot3d(g[ch], g[ch]));
            /* R <= E/|grad E| per channel: the record's reach ends where
             * its first-order extrapolation would change E by 100%. */
            if (len > 0.0 && out->e[ch] / len < r)
                r = out->e[ch] / len;
            for (k = 0; k < 3; k++)
                out->grad_t[ch][k] = (float)g[ch][k];
        }
    }
    if (c->cfg.features & IRC_FEATURE_ROTATION) {
        irc__grad_rot(c, s, t1, t2, g);
        for (ch = 0; ch < 3; ch++)
            for (k = 0; k < 3; k++)
                out->grad_r[ch][k] = (float)g[ch][k];
    }
    if (r < c->cfg.min_radius) r = c->cfg.min_radius;
    if (r > c->cfg.max_radius) r = c->cfg.max_radius;
    if (r < FLT_MIN) r = FLT_MIN;
    out->radius = (float)r;
    out->mean_dist = hm > FLT_MAX ? HUGE_VALF : (float)hm;
    out->features = c->cfg.features;
    out->rays = total;
    out->rays_used = used;
}

/* Claims a free scratch slot (index in *t), or IRC_ERR_BUSY. */
int irc__slot_claim(irc_cache *c, uint32_t *t)
{
    for (;;) {
        uint64_t busy = c->port->load(&c->slots_busy);
        uint32_t i;
        for (i = 0; i < c->cfg.threads && (busy >> i & 1u); i++)
            ;
        if (i == c->cfg.threads)
            return IRC_ERR_BUSY;
        if (c->port->cas(&c->slots_busy, busy, busy | (1ull << i))) {
            *t = i;
            return IRC_OK;
        }
    }
}

/* Zeroes the slot, so that a failed call leaves the block as it was and no
 * samples outlive it, and releases it through the acq_rel CAS, so that its
 * next owner sees this thread's writes as done (a relaxed add would not). */
void irc__slot_release(irc_cache *c, uint32_t t)
{
    uint64_t busy;
    IRC_MEMSET(c->scratch + (size_t)t * c->slot_bytes, 0, c->slot_bytes);
    do
        busy = c->port->load(&c->slots_busy);
    while (!c->port->cas(&c->slots_busy, busy, busy & ~(1ull << t)));
}

/* What every sampling call starts with: check the query, claim a scratch
 * slot, sample the hemisphere into it.  On failure no slot is held. */
int irc__sample_at(irc_cache *c, const float p[3], const float n[3], const void *out,
                   double un[3], double t1[3], double t2[3], uint32_t *t)
{
    uint32_t used = 0;
    unsigned char *slot;
    int st;
    if (!c || !out)
        return IRC_ERR_NULL;
    if (c->magic != IRC__MAGIC)
        return IRC_ERR_CONFIG;
    if (c->sh_n)
        return IRC_ERR_UNSUPPORTED;
    if ((st = irc__check_vec(p)) < 0 || (st = irc__check_normal(n, un)) < 0)
        return st;
    if ((st = irc__slot_claim(c, t)) < 0)
        return st;
    slot = c->scratch + (size_t)*t * c->slot_bytes;
    irc__frame(un, t1, t2);
    st = irc__sample_hemisphere(c, slot, p, un, t1, t2, 0, &used);
    if (st < 0)
        irc__slot_release(c, *t);
    return st;
}

int irc_record_compute(irc_cache *c, const float p[3], const float n[3],
                       irc_record *out)
{
    double un[3], t1[3], t2[3], gvis[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    uint32_t t, extra = 0;
    unsigned char *slot;
    int st = irc__sample_at(c, p, n, out, un, t1, t2, &t);
    if (st < 0)
        return st;
    slot = c->scratch + (size_t)t * c->slot_bytes;
    if (c->cfg.features & IRC_FEATURE_VISIBILITY)
        st = irc__grad_visibility(c, slot, p, un, 0, gvis, &extra);
    if (st == IRC_OK) {
        irc__record_build(c, (const irc__sample *)(void *)slot, un, t1, t2,
                          (c->cfg.features & IRC_FEATURE_VISIBILITY) ? gvis : NULL, out);
        out->rays += extra;
        out->p[0] = p[0];
        out->p[1] = p[1];
        out->p[2] = p[2];
        /* Finite radiances can still sum past FLT_MAX: such a record is
         * refused here, before anything is counted. */
        st = irc__record_check(out);
    }
    irc__slot_release(c, t);
    if (st < 0)
        return st;
    irc__count_compute(c, c->strata + (uint64_t)extra);
    return IRC_OK;
}

/* Octahedral normal encoding, 16 bits a coordinate: worst error ~5e-5 rad. */
uint32_t irc__oct_encode(const double n[3])
{
    double l1 = fabs(n[0]) + fabs(n[1]) + fabs(n[2]);
    double x = n[0] / l1, y = n[1] / l1;
    uint32_t qx, qy;
    if (n[2] < 0.0) {
        double ox = (1.0 - fabs(y)) * (x >= 0.0 ? 1.0 : -1.0);
        double oy = (1.0 - fabs(x)) * (y >= 0.0 ? 1.0 : -1.0);
        x = ox;
        y = oy;
    }
    qx = (uint32_t)floor((x * 0.5 + 0.5) * 65535.0 + 0.5);
    qy = (uint32_t)floor((y * 0.5 + 0.5) * 65535.0 + 0.5);
    /* All ones is IRC__FREE; its neighbour is as good a normal. */
    return (qx | qy << 16) == IRC__FREE ? IRC__FREE - 1u : qx | qy << 16;
}

/* Decoded in float: lookups decode every accepted record's normal. */
void irc__oct_decode(uint32_t code, float out[3])
{
    float x = (float)(code & 0xffffu) * (2.0f / 65535.0f) - 1.0f;
    float y = (float)(code >> 16) * (2.0f / 65535.0f) - 1.0f;
    float z = 1.0f - fabsf(x) - fabsf(y), inv;
    if (z < 0.0f) {
        float ox = (1.0f - fabsf(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        float oy = (1.0f - fabsf(x)) * (y >= 0.0f ? 1.0f : -1.0f);
        x = ox;
        y = oy;
    }
    inv = 1.0f / IRC_SQRTF(x * x + y * y + z * z);
    out[0] = x * inv;
    out[1] = y * inv;
    out[2] = z * inv;
}

static void irc__frame_of(uint32_t code, double t1[3], double t2[3])
{
    float nf[3];
    double n[3];
    irc__oct_decode(code, nf);
    n[0] = nf[0]; n[1] = nf[1]; n[2] = nf[2];
    irc__frame(n, t1, t2);
}

static void irc__grad_pack(float g[3][3], const double t1[3], const double t2[3],
                           irc__grad *out)
{
    double v[6], big = 0.0;
    int i;
    for (i = 0; i < 3; i++) {
        double gi[3];
        gi[0] = g[i][0]; gi[1] = g[i][1]; gi[2] = g[i][2];
        v[2 * i] = irc__dot3d(gi, t1);
        v[2 * i + 1] = irc__dot3d(gi, t2);
    }
    for (i = 0; i < 6; i++)
        if (fabs(v[i]) > big)
            big = fabs(v[i]);
    out->scale = (float)(big / 32767.0);
    for (i = 0; i < 6; i++) {
        /* A denormal scale is rounded coarsely: the quotient may pass
         * 32767, so it is clamped. */
        double q = out->scale > 0.0f ? floor(v[i] / out->scale + 0.5) : 0.0;
        out->g[i] = (int16_t)(q > 32767.0 ? 32767.0 : q < -32767.0 ? -32767.0 : q);
    }
}

static void irc__grad_unpack(const irc__grad *in, const double t1[3],
                             const double t2[3], float g[3][3])
{
    int ch, k;
    for (ch = 0; ch < 3; ch++) {
        double a = in->g[2 * ch] * (double)in->scale;
        double b = in->g[2 * ch + 1] * (double)in->scale;
        for (k = 0; k < 3; k++)
            g[ch][k] = (float)(a * t1[k] + b * t2[k]);
    }
}

int irc__record_check(const irc_record *r)
{
    double un[3];
    int st, ch;
    if ((st = irc__check_vec(r->p)) < 0)
        return st;
    if ((st = irc__check_normal(r->n, un)) < 0)
        return st;
    if (!irc__finite3(r->e) || !irc__finite(r->radius))
        return IRC_ERR_NONFINITE;
    for (ch = 0; ch < 3; ch++)
        if (!irc__finite3(r->grad_t[ch]) || !irc__finite3(r->grad_r[ch]))
            return IRC_ERR_NONFINITE;
    if (!(r->radius > 0.0f) || r->e[0] < 0.0f || r->e[1] < 0.0f || r->e[2] < 0.0f)
        return IRC_ERR_RANGE;
    return IRC_OK;
}

void irc__record_pack(const irc_cache *c, const irc_record *in, void *dst)
{
    unsigned char *b = (unsigned char *)dst;
    irc__rec *r = (irc__rec *)dst;
    double un[3], t1[3], t2[3];
    float g[3][3];
    int ch;
    irc__check_normal(in->n, un);
    IRC_MEMSET(dst, 0, c->rec_size);
    for (ch = 0; ch < 3; ch++) {
        r->p[ch] = in->p[ch];
        r->e[ch] = in->e[ch];
    }
    r->r = in->radius < FLT_MIN ? FLT_MIN : in->radius > IRC_RADIUS_CAP ? IRC_RADIUS_CAP : in->radius;
    r->n = irc__oct_encode(un);
    irc__frame_of(r->n, t1, t2);
    if (c->off_t) {
        IRC_MEMCPY(g, in->grad_t, sizeof g);
        irc__grad_pack(g, t1, t2, (irc__grad *)(void *)(b + c->off_t));
    }
    if (c->off_r) {
        IRC_MEMCPY(g, in->grad_r, sizeof g);
        irc__grad_pack(g, t1, t2, (irc__grad *)(void *)(b + c->off_r));
    }
}

void irc__record_unpack(const irc_cache *c, const void *src, irc_record *out)
{
    const unsigned char *b = (const unsigned char *)src;
    const irc__rec *r = (const irc__rec *)src;
    double t1[3], t2[3];
    int ch;
    IRC_MEMSET(out, 0, sizeof *out);
    for (ch = 0; ch < 3; ch++) {
        out->p[ch] = r->p[ch];
        out->e[ch] = r->e[ch];
    }
    out->radius = r->r;
    out->mean_dist = NAN; /* not stored */
    irc__oct_decode(r->n, out->n);
    irc__frame_of(r->n, t1, t2);
    out->features = c->cfg.features;
    if (c->off_t)
        irc__grad_unpack((const irc__grad *)(const void *)(b + c->off_t), t1, t2, out->grad_t);
    if (c->off_r)
        irc__grad_unpack((const irc__grad *)(const void *)(b + c->off_r), t1, t2, out->grad_r);
}
