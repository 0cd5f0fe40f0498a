/*
 * irradiance.c -- the irradiance record's estimator: irradiance, harmonic
 * mean distance, radius and leak guard from the stratified samples of one
 * hemisphere; the gradients come from gradient.c.
 */
#include "../block/form.h"
#include "../block/octa.h"
#include "../sample/sampler.h"
#include "estimator.h"

/* Failed strata take the mean radiance of the usable ones: the irradiance is
 * then the mean over usable strata, and a uniform scene keeps a zero
 * rotational gradient.  Their distance stays NaN, so no translational
 * boundary term touches them. */
static void irc__fill_failed(irc__sample *s, uint32_t total, uint32_t used, const float mean[3])
{
    uint32_t i;
    int c;
    if (used == total)
        return;
    for (i = 0; i < total; i++)
        if (s[i].d != s[i].d)
            for (c = 0; c < 3; c++)
                s[i].l[c] = mean[c];
}

#ifndef IRC_NO_HESSIAN
/* One channel's Hessian on the tangent plane, t^T H t', from the packed
 * xx xy xz yy yz zz: a = t1 H t1, b = t1 H t2, d = t2 H t2. */
static void irc__tangent_hessian(const float h[6], const float t1[3], const float t2[3],
                                 float *a, float *b, float *d)
{
    static const int ix[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
    int x, y;
    *a = *b = *d = 0.0f;
    for (x = 0; x < 3; x++)
        for (y = 0; y < 3; y++) {
            *a += t1[x] * h[ix[x][y]] * t1[y];
            *b += t1[x] * h[ix[x][y]] * t2[y];
            *d += t2[x] * h[ix[x][y]] * t2[y];
        }
}

/* With IRC_FEATURE_HESSIAN: the Hessian into out->hessian, and the ellipse
 * at whose edge the second-order term reaches the accuracy target.  A
 * record extrapolated to first order errs by 1/2 |k| d^2 at distance d
 * along a tangent direction of curvature k = t^T H t; a lookup reaches
 * d = a R, so R = sqrt(2 E / |k|) keeps that error at a^2 E at the edge of
 * reach (Schwarzhaupt et al.'s max-error rule, relative to E).  The axes are the
 * eigenvectors of the channel whose larger eigenvalue relative to its E is
 * largest (1/2 atan2, signed entries: no division by a vanishing
 * off-diagonal); each radius is the smallest over channels of that
 * channel's curvature along the axis.  rad[0] is the minor radius (across
 * the axis of strongest curvature), rad[1] the major, along axis. */
static void irc__hessian_radii(const irc_cache *c, const irc__sample *s, const float n[3],
                               const float t1[3], const float t2[3], irc_record *out,
                               float rad[2], float axis[3])
{
    float h[3][6], tq[3][3], best = -1.0f, u[2] = {1.0f, 0.0f}, v[2];
    int ch, i, k;
    irc__hessian(c, s, irc__slot_dirs(c, s), n, h);
    for (ch = 0; ch < 3; ch++) {
        float l0, l1, w[2];
        for (i = 0; i < 6; i++)
            out->hessian[ch][i] = h[ch][i];
        irc__tangent_hessian(h[ch], t1, t2, &tq[ch][0], &tq[ch][1], &tq[ch][2]);
        irc__eigen2(tq[ch][0], tq[ch][1], tq[ch][2], &l0, &l1, w);
        if (out->e[ch] > 0.0f && IRC_FABSF(l0) / out->e[ch] > best) {
            best = IRC_FABSF(l0) / out->e[ch];
            u[0] = w[0];
            u[1] = w[1];
        }
    }
    v[0] = -u[1];
    v[1] = u[0];
    rad[0] = rad[1] = HUGE_VALF;
    for (ch = 0; ch < 3; ch++) {
        const float *t = tq[ch], *dir[2];
        dir[0] = u;
        dir[1] = v;
        for (k = 0; k < 2; k++) {
            float cu = IRC_FABSF(t[0] * dir[k][0] * dir[k][0] +
                                 2.0f * t[1] * dir[k][0] * dir[k][1] +
                                 t[2] * dir[k][1] * dir[k][1]);
            if (out->e[ch] > 0.0f && cu > 0.0f && IRC_SQRTF(2.0f * out->e[ch] / cu) < rad[k])
                rad[k] = IRC_SQRTF(2.0f * out->e[ch] / cu);
        }
    }
    /* Another channel may curve more along v than the chosen one along u. */
    if (rad[1] < rad[0]) {
        float t = rad[0];
        rad[0] = rad[1];
        rad[1] = t;
        v[0] = u[0];
        v[1] = u[1];
    }
    for (i = 0; i < 3; i++)
        axis[i] = v[0] * t1[i] + v[1] * t2[i];
}

#endif

typedef struct irc__totals {
    float sum[3];     /* radiance over the usable strata */
    float inv;        /* 1/d over the strata that hit */
    float far;        /* the farthest hit */
    uint32_t used, hits;
} irc__totals;

/* One pass over the samples for the estimator's sums, row by row (a row's
 * sums in float, then the rows': the roundings grow with N + M, not M N). */
static void irc__totals_of(const irc__grid *g, const irc__sample *s, irc__totals *t)
{
    const uint32_t m = g->m, nphi = g->nphi;
    uint32_t j, k;
    IRC_MEMSET(t, 0, sizeof *t);
    for (j = 0; j < m; j++) {
        const irc__sample *row = s + j * nphi;
        float l0 = 0.0f, l1 = 0.0f, l2 = 0.0f, inv = 0.0f;
        for (k = 0; k < nphi; k++) {
            const float d = row[k].d;
            if (d != d)
                continue;
            t->used++;
            l0 += row[k].l[0];
            l1 += row[k].l[1];
            l2 += row[k].l[2];
            if (d < HUGE_VALF) {
                t->hits++;
                inv += 1.0f / d;
                if (d > t->far)
                    t->far = d;
            }
        }
        t->sum[0] += l0;
        t->sum[1] += l1;
        t->sum[2] += l2;
        t->inv += inv;
    }
}

/* Ward's split-sphere radius, the harmonic mean hit distance, made safe
 * without a scene size: over the rays that hit.  Ward's form counts an
 * escaped ray as a hit at infinity, so a record that saw a blocker in a
 * tenth of its rays and sky in the rest got ten times the blocker's
 * distance, and one that saw only sky an infinite radius (a record 1000
 * away then answered lookups under the blocker).  The distance to what the
 * record saw is the scale at which what it saw changes.  A record that hit
 * nothing has no scale: it takes the host's max_radius if the host set
 * one, else the _px call's largest reach (irc__radii), else the smallest
 * radius (it then serves lookups at its own point only). */
static float irc__split_sphere(const irc_cache *c, const irc__totals *t, float *far)
{
    *far = t->far;
    if (t->hits == 0)
        return *far = c->cfg.max_radius < IRC__CAP ? c->cfg.max_radius : 0.0f;
    return (float)t->hits / t->inv;
}

#ifndef IRC_NO_GUARD
/* The leak guard (irc_record.leak_guard): per sector of the stored
 * normal's frame, the nearest hit seen at a grazing angle (rows with
 * sin^2 theta >= 1/2, cosine-weighted strata: a wall, not a ceiling), as
 * its horizontal distance d sin(theta) over the reach a R(phi) in that
 * direction (the ellipse's).  Row and column centres stand for the
 * jittered directions; the distance is rounded down, the safe way. */
static uint64_t irc__leak_guard(const irc_cache *c, const irc__grid *g, const irc__sample *s,
                                const float un[3], const float t1[3], const float t2[3],
                                const irc_record *rec)
{
    const uint32_t m = g->m, nphi = g->nphi;
    const float *cc = g->tab, *sc = cc + irc__pad4(nphi),
                inv_m = 1.0f / (float)m;
    float o1[3], o2[3], near[16], ax[2] = {0.0f, 0.0f}, q = 1.0f, w[3];
    uint32_t j, k;
    uint64_t mask = 0;
    int i;
    irc__oct_frame(irc__oct_encode(un), o1, o2);
    for (i = 0; i < 16; i++)
        near[i] = 1.0f;
    if (rec->minor_radius < rec->radius) {
        float a3[3] = {rec->axis[0], rec->axis[1], rec->axis[2]};
        q = rec->minor_radius / rec->radius;
        ax[0] = irc__dot3(a3, o1);
        ax[1] = irc__dot3(a3, o2);
    }
    for (k = 0; k < nphi; k++) {
        /* The column's centre direction, its cosine and sine from the
         * gradients' table (gradient.c). */
        float x, y, cu, inv_reach;
        int sec;
        for (i = 0; i < 3; i++)
            w[i] = cc[k] * t1[i] + sc[k] * t2[i];
        x = irc__dot3(w, o1);
        y = irc__dot3(w, o2);
        sec = irc__sector(x, y);
        cu = x * ax[0] + y * ax[1];
        inv_reach = IRC_SQRTF(cu * cu + (1.0f - cu * cu) / (q * q)) /
                    irc__reach(c, rec->radius);
        for (j = m / 2; j < m; j++) {
            const irc__sample *a = &s[j * nphi + k];
            float f;
            if (!(a->d < HUGE_VALF)) /* escaped or failed */
                continue;
            f = a->d * IRC_SQRTF(((float)j + 0.5f) * inv_m) * inv_reach;
            if (f < near[sec])
                near[sec] = f;
        }
    }
    for (i = 0; i < 16; i++)
        if (near[i] < 1.0f)
            mask |= (uint64_t)(15 - (int)IRC_FLOORF(15.0f * near[i])) << (4 * i);
    return mask;
}

#endif

/* The record's radii: r (the split sphere, or E/|grad E|) for a disk, or
 * with HESSIAN the ellipse; then the screen-space bound (footprint fp) and
 * the host's world bounds. */
static void irc__radii(const irc_cache *c, const irc__sample *s, const float n[3],
                       const float t1[3], const float t2[3], float r, float far, float fp,
                       irc_record *out)
{
    float rad[2], axis[3] = {0.0f, 0.0f, 0.0f};
    int k;
    rad[0] = rad[1] = r;
#ifndef IRC_NO_HESSIAN
    if (c->cfg.features & IRC_FEATURE_HESSIAN) {
        /* With a gradient the second-order term decides alone: E/|grad E|
         * and the split sphere are dropped, and the farthest hit (the
         * scale of what the record saw) bounds both radii.  Without one,
         * the first-order error is still there and the split sphere
         * bounds them as before.  (At equal record counts on the Cornell
         * box the split-sphere bound cost 1.7x in RMSE, 4 x the harmonic
         * mean 1.1x; the max-error law sqrt(2E/|l|) beat laws in |l|^-1/3
         * and |l|^-1/4, and ellipses beat disks by 1.14-1.31x.) */
        const float cap = c->cfg.features & IRC_FEATURE_TRANSLATION ? far : r;
        irc__hessian_radii(c, s, n, t1, t2, out, rad, axis);
        for (k = 0; k < 2; k++)
            if (rad[k] > cap)
                rad[k] = cap;
        if (rad[1] > IRC_ANISOTROPY * rad[0])
            rad[1] = IRC_ANISOTROPY * rad[0];
    }
#else
    (void)s; (void)n; (void)t1; (void)t2;
#endif
    /* The pixel bounds hold the reach a R, as pbrt-v2's spacings hold a
     * record's extent: records then lie 2.5-15 pixels apart whatever a.  A
     * record that saw nothing (every ray escaped: open sky; far is then 0
     * unless max_radius stood in) is as wide as they allow. */
    fp /= c->cfg.accuracy;
    if (far == 0.0f && fp > 0.0f && c->cfg.irr.max_pixels > 0.0f)
        rad[0] = rad[1] = IRC__CAP;
    for (k = 0; k < 2; k++) {
        if (rad[k] < c->cfg.irr.min_pixels * fp) rad[k] = c->cfg.irr.min_pixels * fp;
        if (c->cfg.irr.max_pixels > 0.0f && fp > 0.0f && rad[k] > c->cfg.irr.max_pixels * fp)
            rad[k] = c->cfg.irr.max_pixels * fp;
        if (rad[k] < c->cfg.min_radius) rad[k] = c->cfg.min_radius;
        if (rad[k] > c->cfg.max_radius) rad[k] = c->cfg.max_radius;
        if (rad[k] < FLT_MIN) rad[k] = FLT_MIN;
    }
    out->radius = rad[1];
    out->minor_radius = rad[0];
    if (out->minor_radius < out->radius)
        for (k = 0; k < 3; k++)
            out->axis[k] = axis[k];
    else
        out->minor_radius = out->radius;
}

/* Not inlined: its locals (and the Hessian's and the leak guard's) would
 * otherwise sit under the visibility gradient's calls. */
static IRC__NOINLINE void irc__record_build(const irc_cache *c, const irc__grid *grid,
                       const irc__sample *s, const float n[3], const float t1[3],
                       const float t2[3], float gvis[3][3], float fp, irc_record *out)
{
    const uint32_t total = grid->strata;
    float mean[3], hm, far, r, g[3][3], gr[3][3];
    const uint32_t f = c->cfg.features;
    irc__totals t;
    uint32_t used;
    int ch, k;

    irc__totals_of(grid, s, &t);
    used = t.used;
    IRC_MEMSET(out, 0, sizeof *out);
    for (ch = 0; ch < 3; ch++) {
        mean[ch] = t.sum[ch] / (float)used;
        out->e[ch] = IRC_PI * t.sum[ch] / (float)used;
        out->n[ch] = n[ch];
    }
    irc__fill_failed((irc__sample *)s, total, used, mean);
    hm = irc__split_sphere(c, &t, &far);
    r = hm;
    if (f & (IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION))
        irc__gradients(c, grid, s, mean, t1, t2, (f & IRC_FEATURE_TRANSLATION) ? g : NULL,
                       (f & IRC_FEATURE_ROTATION) ? gr : NULL);
    if (f & IRC_FEATURE_TRANSLATION) {
        for (ch = 0; ch < 3; ch++)
            for (k = 0; k < 3; k++)
                g[ch][k] += gvis ? gvis[ch][k] : 0.0f;
        for (ch = 0; ch < 3; ch++) {
            float len = IRC_SQRTF(irc__dot3(g[ch], g[ch]));
            /* R <= E/|grad E| per channel: the record's reach ends where
             * its first-order extrapolation would change E by 100%. */
            if (len > 0.0f && out->e[ch] / len < r)
                r = out->e[ch] / len;
            for (k = 0; k < 3; k++)
                out->grad_t[ch][k] = g[ch][k];
        }
    }
    if (f & IRC_FEATURE_ROTATION)
        for (ch = 0; ch < 3; ch++)
            for (k = 0; k < 3; k++)
                out->grad_r[ch][k] = gr[ch][k];
    irc__radii(c, s, n, t1, t2, r, far, fp, out);
#ifndef IRC_NO_GUARD /* else no record has a guard (kind_irr.c) */
    if (c->off[IRC__P_GUARD])
        out->leak_guard = irc__leak_guard(c, grid, s, n, t1, t2, out);
#endif
    out->mean_dist = hm;
    out->features = c->cfg.features;
    out->rays = total;
    out->rays_used = used;
}

/* Records that cost what they serve.  A record's rays are spread over
 * the pixels it serves: about (a R / f)^2 of them for reach a R and pixel
 * width f, and its noise is copied to each, so a record serving few pixels
 * pays as much a pixel as per-pixel sampling and buys no less noise.  The
 * _px call (footprint f > 0) can sample the coarsest grid first (a
 * sixteenth of the rays at two levels), take that pilot's radius R within
 * the pixel bounds, and refine (irc__refine: the pilot's rays are kept)
 * one level at a time while R / f reaches cfg.irr.full_pixels / 2^level:
 * rays grow with the served area (R / f)^2, up to the configured grid
 * when R / f >= full_pixels.  Configs refuse it with visibility
 * gradients or the Hessian (they read every stratum's direction, which a
 * refinement would have to move too) and with super-samples
 * (kind_irr.c). */
static uint32_t irc__pilot_level(const irc__call *k)
{
    const irc_cache *c = k->c;
    if (!(k->footprint > 0.0f) || !(c->cfg.irr.full_pixels > 0.0f))
        return 0;
    return irc__grid_levels(c->cfg.strata_theta, c->cfg.strata_phi) - 1u;
}

/* Whether the pilot on grid g, whose record is *pilot (its radius within
 * the pixel bounds: the pixels it will serve), should be refined: that
 * radius in pixels against the level's share of full_pixels. */
static int irc__wants_finer(const irc__call *k, const irc__grid *g, const irc_record *pilot)
{
    const float rp = pilot->minor_radius / k->footprint;
    return rp * (float)(1u << g->level) >= k->c->cfg.irr.full_pixels;
}

int irc__irr_on_grid(irc__call *k, uint32_t level, irc_record *out)
{
    float t1[3], t2[3];
    irc__grid g;
    int st;
    irc__grid_at(k->c, level, &g);
    if ((st = irc__hemisphere(k, &g, t1, t2, 0u)) < 0)
        return st;
    irc__record_build(k->c, &g, (const irc__sample *)(void *)k->slot, k->q.n, t1, t2, NULL,
                      k->footprint, out);
    out->p[0] = k->q.p[0];
    out->p[1] = k->q.p[1];
    out->p[2] = k->q.p[2];
    return IRC_OK;
}

int irc__irr_compute(irc__call *k, void *rec)
{
    irc_cache *c = k->c;
    irc_record *out = (irc_record *)rec;
    const irc__sample *s = (const irc__sample *)(void *)k->slot;
    float t1[3], t2[3], gvis[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const int vis = (c->cfg.features & IRC_FEATURE_VISIBILITY) != 0;
    const uint32_t top = irc__pilot_level(k);
    irc__grid g, finer;
    int st;
    irc__grid_at(c, top, &g);
    if ((st = irc__hemisphere(k, &g, t1, t2, g.level ? 0u : c->cfg.irr.supersamples)) < 0)
        return st;
    while (g.level > 0) {
        irc__record_build(c, &g, s, k->q.n, t1, t2, NULL, k->footprint, out);
        if (!irc__wants_finer(k, &g, out))
            break;
        irc__grid_at(c, g.level - 1u, &finer);
        if ((st = irc__refine(k, top, &g, &finer, t1, t2)) < 0)
            return st;
        g = finer;
    }
#ifndef IRC_NO_VISIBILITY
    if (vis && (st = irc__grad_visibility(k, 0, gvis)) < 0)
        return st;
#endif
    irc__record_build(c, &g, s, k->q.n, t1, t2, vis ? gvis : NULL, k->footprint, out);

    out->rays = k->rays;
    out->p[0] = k->q.p[0];
    out->p[1] = k->q.p[1];
    out->p[2] = k->q.p[2];
    return IRC_OK;
}

int irc__irr_estimate_on(irc__call *k, uint32_t level, float e[3])
{
    irc__grid g;
    irc__totals t;
    float t1[3], t2[3];
    int st, ch;
    irc__grid_at(k->c, level, &g);
    if ((st = irc__hemisphere(k, &g, t1, t2, 0u)) < 0)
        return st;
    irc__totals_of(&g, (const irc__sample *)(void *)k->slot, &t);
    for (ch = 0; ch < 3; ch++)
        e[ch] = IRC_PI * t.sum[ch] / (float)t.used;
    /* radiances near FLT_MAX sum past it: refused as such a record is */
    return irc__finite3(e) ? IRC_OK : IRC_ERR_NONFINITE;
}
