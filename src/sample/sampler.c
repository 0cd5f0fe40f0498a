/*
 * sampler.c -- stratified cosine-weighted hemisphere sampling through the
 * host's trace callback, and the query-keyed random numbers behind it.
 *
 * Stratum (j, k), j < M rows in theta and k < N columns in phi, takes
 * sin^2(theta) = (j + u1)/M and phi = 2 pi (k + u2)/N: every stratum carries
 * the same cosine-weighted measure pi/(MN).
 */
#include "../block/form.h"
#include "../block/check.h"
#include "../store/trace.h"
#include "sampler.h"

/* splitmix64's finaliser: a bijective 64-bit mix. */
static uint64_t irc__mix(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

static uint32_t irc__bits(float f)
{
    uint32_t u;
    f += 0.0f; /* -0 and +0 are one query */
    IRC_MEMCPY(&u, &f, sizeof u);
    return u;
}

/* A call's seed: the config's for a point's first estimate, and for its
 * k-th refinement (progressive.c) the config's mixed with k, so that every
 * estimate of a point is independent of the others and of the threads. */
static uint64_t irc__seed_of(const irc__call *k)
{
    const uint64_t s = k->c->cfg.seed;
    return k->draw ? irc__mix(s ^ (0x726566696e65ull + (uint64_t)k->draw)) : s;
}

/* The record's random numbers depend on nothing but the query and the seed,
 * so a record is the same whichever thread computes it, and when. */
irc__rng irc__rng_for(const float p[3], const float n[3], uint64_t seed)
{
    irc__rng r;
    uint64_t h = irc__mix(seed ^ 0x9e3779b97f4a7c15ull);
    int i;
    for (i = 0; i < 3; i++)
        h = irc__mix(h ^ ((uint64_t)irc__bits(p[i]) << 32 | irc__bits(n[i])));
    r.key = h;
    return r;
}

static int irc__nonneg3(const float v[3])
{
    uint32_t u[3];
    IRC_MEMCPY(u, v, sizeof u);
    /* A finite float with the sign bit clear has bits below +inf's: one
     * integer comparison a component.  -0 and what is refused take the
     * float comparisons (which fail for NaN). */
    if (u[0] < 0x7f800000u && u[1] < 0x7f800000u && u[2] < 0x7f800000u)
        return 1;
    return v[0] >= 0.0f && v[0] <= FLT_MAX && v[1] >= 0.0f && v[1] <= FLT_MAX &&
           v[2] >= 0.0f && v[2] <= FLT_MAX;
}

/* Checks one hit and turns it into a sample.  Returns 1 usable, 0 failed
 * (the host said so), or IRC_ERR_CALLBACK. */
int irc__accept_hit(const irc_hit *h, irc__sample *s)
{
    switch (h->status) {
    case IRC_RAY_HIT:
        if (!(h->dist > 0.0f && h->dist <= FLT_MAX) || !irc__finite3(h->normal) ||
            (h->normal[0] == 0.0f && h->normal[1] == 0.0f && h->normal[2] == 0.0f))
            return IRC_ERR_CALLBACK;
        s->d = h->dist;
        break;
    case IRC_RAY_ESCAPED:
        s->d = HUGE_VALF;
        break;
    case IRC_RAY_FAILED:
        s->l[0] = s->l[1] = s->l[2] = 0.0f;
        s->d = NAN;
        return 0;
    default:
        return IRC_ERR_CALLBACK;
    }
    if (!irc__nonneg3(h->radiance))
        return IRC_ERR_CALLBACK;
    s->l[0] = h->radiance[0];
    s->l[1] = h->radiance[1];
    s->l[2] = h->radiance[2];
    return 1;
}

/* What every direction of one hemisphere shares, in float (the ray is
 * float): the frame, 1/M, the column width, and the columns' boundary
 * angles from the block's table (gradient.c, irc__gtab_fill), so that a
 * ray costs no division and, with N >= 8, no trigonometric call. */
typedef struct irc__dirs {
    float t1[3], t2[3], n[3];
    float inv_m, dphi;
    const float *cb, *sb; /* cos and sin of 2 pi k/N */
    uint32_t nphi;
    int uniform;
    irc__rng rng;
} irc__dirs;

static void irc__dirs_init(const irc_cache *c, const irc__grid *gr, const float n[3],
                           const float t1[3], const float t2[3], const irc__rng *rng,
                           irc__dirs *g)
{
    const uint32_t np = irc__pad4(gr->nphi);
    int i;
    for (i = 0; i < 3; i++) {
        g->t1[i] = t1[i];
        g->t2[i] = t2[i];
        g->n[i] = n[i];
    }
    g->inv_m = (float)(1.0f / gr->m);
    g->dphi = (float)(2.0f * IRC_PI / gr->nphi);
    g->cb = gr->tab + 2u * np;
    g->sb = g->cb + np;
    g->nphi = gr->nphi;
    g->uniform = c->kind->uniform;
    g->rng = *rng;
    /* A coarser grid's draws are its own: level 0's stay what they were. */
    if (gr->level)
        g->rng.key = irc__mix(g->rng.key ^ (0x6c6576656cull + gr->level));
}

/* Stratum (j, k)'s two uniform numbers in [0, 1): 24 bits each, exact in
 * float, so 2 u is exact and its floor says which half the sample lies
 * in (irc__refine). */
static void irc__stratum_uv(const irc__dirs *g, uint32_t j, uint32_t k, float *u1, float *u2)
{
    const uint64_t h = irc__mix(g->rng.key + (uint64_t)(j * g->nphi + k + 1) *
                                                 0x9e3779b97f4a7c15ull);
    *u1 = (float)(h >> 40) * (1.0f / 16777216.0f);
    *u2 = (float)(h >> 8 & 0xffffffu) * (1.0f / 16777216.0f);
}

/* Stratum (j, k)'s direction.  Rows are Ward's cosine-weighted sin^2(theta)
 * = (j + u1)/M, or for SH records equal solid angle, cos(theta) = 1 -
 * (j + u1)/M; phi = 2 pi k/N + delta with delta = u2 2 pi/N, turned from
 * the column's boundary by delta's sine and cosine: for N >= 8 delta <=
 * pi/4, where Taylor series to delta^9 and delta^10 are within 2e-9 (float
 * rounding dominates); for fewer columns the library calls. */
static void irc__direction(const irc__dirs *g, uint32_t j, uint32_t k, float dir[3])
{
    float u1, u2, d, d2, s2, st, ct, sd, cd, cp, sp;
    int i;
    irc__stratum_uv(g, j, k, &u1, &u2);
    d = u2 * g->dphi;
    d2 = d * d;
    if (g->uniform) {
        ct = 1.0f - ((float)j + u1) * g->inv_m;
        s2 = (1.0f - ct) * (1.0f + ct);
        st = IRC_SQRTF(s2);
    } else {
        s2 = ((float)j + u1) * g->inv_m;
        st = IRC_SQRTF(s2);
        ct = IRC_SQRTF(1.0f - s2);
    }
    if (g->nphi >= 8) {
        /* Horner in products: a division by a constant is not one. */
        sd = d * (1.0f - d2 * (1.0f / 6.0f) *
                             (1.0f - d2 * (1.0f / 20.0f) *
                                         (1.0f - d2 * (1.0f / 42.0f) *
                                                     (1.0f - d2 * (1.0f / 72.0f)))));
        cd = 1.0f - d2 * 0.5f *
                        (1.0f - d2 * (1.0f / 12.0f) *
                                    (1.0f - d2 * (1.0f / 30.0f) *
                                                (1.0f - d2 * (1.0f / 56.0f) *
                                                            (1.0f - d2 * (1.0f / 90.0f)))));
    } else {
        sd = IRC_SINF(d);
        cd = IRC_COSF(d);
    }
    cp = g->cb[k] * cd - g->sb[k] * sd;
    sp = g->sb[k] * cd + g->cb[k] * sd;
    for (i = 0; i < 3; i++)
        dir[i] = st * (cp * g->t1[i] + sp * g->t2[i]) + ct * g->n[i];
}

/* Visibility gradients and SH records need each stratum's direction and the
 * unit normal of what it hit (left 0 for escaped rays). */
static void irc__keep_geometry(const irc_cache *c, const irc__sample *s, uint32_t i,
                               const float dir[3], const irc_hit *h)
{
    float *d = irc__slot_dirs(c, s) + 3u * i, *nn = irc__slot_normals(c, s) + 3u * i;
    int k;
    for (k = 0; k < 3; k++)
        d[k] = dir[k];
    if (h->status == IRC_RAY_HIT) {
        float v[3];
        irc__check_normal(h->normal, v);
        for (k = 0; k < 3; k++)
            nn[k] = v[k];
    }
}

/* Fills the slot's samples first + j * N + k for every stratum of the
 * hemisphere around n, casting rays in batches of cfg.max_batch (the
 * estimators count the usable ones again as they sum them).  Returns
 * IRC_OK, IRC_ERR_NOSAMPLES (fewer than half usable), or a negative code
 * (the callback's own, passed through). */
int irc__sample_hemisphere(irc__call *k, const irc__grid *gr, const float n[3],
                           const float t1[3], const float t2[3], uint32_t first)
{
    irc_cache *c = k->c;
    irc__sample *base = (irc__sample *)(void *)k->slot, *out = base + first;
    const uint32_t m = gr->m, nphi = gr->nphi;
    const uint32_t total = m * nphi, batch = c->cfg.max_batch;
    irc_ray *rays = irc__slot_rays(c, k->slot);
    irc_hit *hits = (irc_hit *)(void *)(rays + batch);
    irc__rng rng;
    irc__dirs g;
    uint32_t s0, i, good = 0, j = 0, col = 0;
    int st;

    rng = irc__rng_for(k->q.p, n, irc__seed_of(k));
    irc__dirs_init(c, gr, n, t1, t2, &rng, &g);
    for (s0 = 0; s0 < total; s0 += batch) {
        uint32_t cnt = total - s0 < batch ? total - s0 : batch;
        for (i = 0; i < cnt; i++) {
            rays[i].org[0] = k->q.p[0];
            rays[i].org[1] = k->q.p[1];
            rays[i].org[2] = k->q.p[2];
            irc__direction(&g, j, col, rays[i].dir);
            if (++col == nphi) { /* strata in row order: s = j N + k */
                col = 0;
                j++;
            }
        }
        if ((st = irc__cast(k, rays, hits, cnt)) < 0)
            return st;
        for (i = 0; i < cnt; i++) {
            st = irc__accept_hit(&hits[i], &out[s0 + i]);
            if (st < 0)
                return st;
            good += (uint32_t)st;
            if (c->keep_geom)
                irc__keep_geometry(c, base, first + s0 + i, rays[i].dir, &hits[i]);
        }
    }
    return good * 2u < total || good == 0 ? IRC_ERR_NOSAMPLES : IRC_OK;
}

#ifndef IRC_NO_SUPERSAMPLE
/* How much the radiance changes around stratum i: the spread (largest
 * minus smallest, in the sum of the channels) of its four neighbours'
 * samples (the next and previous row and column, phi wrapping), its own
 * left out.  So whether a stratum is chosen never depends on its own
 * sample, which then stays an unbiased part of its mean (a choice by the
 * stratum's own difference from its neighbours kept the dark first
 * samples of strata half in a sunlit patch and replaced the bright ones:
 * -1.8% on the Sponza atrium).  0 with fewer than two usable neighbours. */
static float irc__contrast(const irc__sample *s, uint32_t m, uint32_t nphi, uint32_t i)
{
    const uint32_t j = i / nphi, k = i % nphi;
    const uint32_t nb[4] = {j ? i - nphi : i, j + 1 < m ? i + nphi : i,
                            k ? i - 1 : i + nphi - 1, k + 1 < nphi ? i + 1 : i + 1 - nphi};
    float lo = 0.0f, hi = 0.0f;
    int q, n = 0;
    for (q = 0; q < 4; q++) {
        const irc__sample *b = &s[nb[q]];
        float l;
        if (nb[q] == i || b->d != b->d)
            continue;
        l = b->l[0] + b->l[1] + b->l[2];
        lo = n == 0 || l < lo ? l : lo;
        hi = n == 0 || l > hi ? l : hi;
        n++;
    }
    return n >= 2 ? hi - lo : 0.0f;
}

#define IRC__SS_BINS 64u

/* The histogram bin of contrast ct, of the largest `most`. */
static uint32_t irc__ss_bin(float ct, float most)
{
    const uint32_t b = (uint32_t)(ct / most * (float)(IRC__SS_BINS - 1));
    return b < IRC__SS_BINS ? b : IRC__SS_BINS - 1;
}

/* The contrast above which (with the first `*room` strata of the bin at
 * it, in row order) cfg.irr.supersamples strata lie: a histogram of the
 * contrasts over [0, the largest], so no per-stratum memory is needed. */
static uint32_t irc__ss_threshold(const irc__sample *s, uint32_t m, uint32_t nphi,
                                  uint32_t want, float *top, uint32_t *room)
{
    uint32_t hist[IRC__SS_BINS], i, b, above = 0;
    float most = 0.0f;
    for (i = 0; i < m * nphi; i++) {
        float ct = irc__contrast(s, m, nphi, i);
        most = ct > most ? ct : most;
    }
    *top = most;
    IRC_MEMSET(hist, 0, sizeof hist);
    for (i = 0; i < m * nphi && most > 0.0f; i++) {
        float ct = irc__contrast(s, m, nphi, i);
        if (ct > 0.0f && s[i].d == s[i].d)
            hist[irc__ss_bin(ct, most)]++;
    }
    for (b = IRC__SS_BINS; b-- > 0;) {
        if (above + hist[b] >= want) {
            *room = want - above;
            return b;
        }
        above += hist[b];
    }
    *room = hist[0];
    return 0;
}

/* Merges the batch's extra samples into their strata: the mean of the two
 * (the first did not choose its stratum, so the mean is unbiased), the
 * distance the nearer. */
static int irc__ss_merge(irc__sample *s, const uint32_t *at, const irc_hit *hits, uint32_t cnt)
{
    uint32_t q;
    int st;
    for (q = 0; q < cnt; q++) {
        irc__sample x, *o = &s[at[q]];
        if ((st = irc__accept_hit(&hits[q], &x)) < 0)
            return st;
        if (st == 0)
            continue; /* failed: the stratum keeps its one sample */
        o->l[0] = 0.5f * (o->l[0] + x.l[0]);
        o->l[1] = 0.5f * (o->l[1] + x.l[1]);
        o->l[2] = 0.5f * (o->l[2] + x.l[2]);
        o->d = x.d < o->d ? x.d : o->d;
    }
    return IRC_OK;
}

/* One more jittered ray (another random draw) into each of the `extra`
 * strata whose neighbours differ most.  The strata are
 * chosen first, all from the first samples (marked by their distance's
 * sign, the one bit a sample has spare), then sampled in batches.
 * Returns IRC_OK or a negative code (the callback's own). */
int irc__supersample(irc__call *k, const irc__grid *gr, const float n[3], const float t1[3],
                     const float t2[3], uint32_t extra)
{
    const irc_cache *c = k->c;
    irc__sample *s = (irc__sample *)(void *)k->slot;
    const uint32_t m = gr->m, nphi = gr->nphi;
    const uint32_t total = m * nphi, batch = c->cfg.max_batch < 64u ? c->cfg.max_batch : 64u;
    irc_ray *rays = irc__slot_rays(c, k->slot);
    irc_hit *hits = (irc_hit *)(void *)(rays + c->cfg.max_batch);
    uint32_t at[64], i, cnt = 0, room, bin;
    float most;
    irc__rng rng = irc__rng_for(k->q.p, n, irc__seed_of(k));
    irc__dirs g;
    int st;
    bin = irc__ss_threshold(s, m, nphi, extra, &most, &room);
    if (!(most > 0.0f))
        return IRC_OK;
    for (i = 0; i < total; i++) {
        const float ct = irc__contrast(s, m, nphi, i);
        const uint32_t b = ct > 0.0f ? irc__ss_bin(ct, most) : 0u;
        if (!(ct > 0.0f) || s[i].d != s[i].d || b < bin || (b == bin && room == 0))
            continue;
        room -= b == bin;
        s[i].d = -s[i].d; /* chosen */
    }
    rng.key = irc__mix(rng.key ^ 0x73757065727321ull); /* the second draw's */
    irc__dirs_init(c, gr, n, t1, t2, &rng, &g);
    for (i = 0; i < total; i++) {
        if (!(s[i].d < 0.0f))
            continue;
        s[i].d = -s[i].d;
        at[cnt] = i;
        rays[cnt].org[0] = k->q.p[0];
        rays[cnt].org[1] = k->q.p[1];
        rays[cnt].org[2] = k->q.p[2];
        irc__direction(&g, i / nphi, i % nphi, rays[cnt].dir);
        if (++cnt < batch)
            continue;
        if ((st = irc__cast(k, rays, hits, cnt)) < 0 || (st = irc__ss_merge(s, at, hits, cnt)) < 0)
            return st;
        cnt = 0;
    }
    if (cnt && ((st = irc__cast(k, rays, hits, cnt)) < 0 || (st = irc__ss_merge(s, at, hits, cnt)) < 0))
        return st;
    return IRC_OK;
}

#endif /* IRC_NO_SUPERSAMPLE */

int irc__hemisphere(irc__call *k, const irc__grid *g, float t1[3], float t2[3],
                    uint32_t extra)
{
    int st;
    irc__frame(k->q.n, t1, t2);
    st = irc__sample_hemisphere(k, g, k->q.n, t1, t2, 0);
#ifndef IRC_NO_SUPERSAMPLE /* else no config asks for any (kind_irr.c) */
    if (st == IRC_OK && extra)
        st = irc__supersample(k, g, k->q.n, t1, t2, extra);
#else
    (void)extra;
#endif
    return st;
}

/* A stratum of the finer grid still to be sampled: no radiance a host may
 * report is negative. */
#define IRC__EMPTY (-1.0f)

/* Where in stratum (j, k) of grid level lv the sample it holds lies, as
 * (u1, u2) in [0, 1)^2, after refinements from the pilot's level top
 * (d[l]: level l's draws).  A stratum's sample is the draw of its
 * coarsest ancestor whose sample fell into it, carried down: at each
 * refinement a sample at (u1, u2) goes to the child half [2 u1 >= 1],
 * [2 u2 >= 1] and sits at 2 u - that child there.  Where the carried
 * sample went to a sibling, the stratum at that level was sampled afresh
 * with its own level's draw. */
static void irc__held_uv(const irc__dirs *d, uint32_t top, uint32_t lv, uint32_t j,
                         uint32_t k, float *u1, float *u2)
{
    uint32_t l = top;
    for (;;) {
        uint32_t m;
        irc__stratum_uv(&d[l], j >> (l - lv), k >> (l - lv), u1, u2);
        for (m = l; m > lv; m--) {
            const uint32_t a = 2.0f * *u1 >= 1.0f, b = 2.0f * *u2 >= 1.0f;
            if (a != ((j >> (m - 1u - lv)) & 1u) || b != ((k >> (m - 1u - lv)) & 1u))
                break;
            *u1 = 2.0f * *u1 - (float)a;
            *u2 = 2.0f * *u2 - (float)b;
        }
        if (m == lv)
            return;
        l = m - 1u; /* sampled afresh at level m - 1 */
    }
}

/* Moves each sample of the coarser grid (level from->level) to the finer
 * stratum it lies in (row 2J + [2 u1 >= 1], column 2K + [2 u2 >= 1]) and
 * marks the other three of its block empty.  From the last sample down: a
 * block's strata all lie at or after its coarse sample's index, so
 * nothing yet to move is overwritten. */
static void irc__spread(irc__sample *s, const irc__dirs *d, uint32_t top, const irc__grid *from,
                        const irc__grid *to)
{
    uint32_t i = from->strata;
    while (i-- > 0) {
        const uint32_t jc = i / from->nphi, kc = i % from->nphi;
        const irc__sample keep = s[i];
        float u1, u2;
        uint32_t a, b;
        irc__held_uv(d, top, from->level, jc, kc, &u1, &u2);
        for (a = 0; a < 2; a++)
            for (b = 0; b < 2; b++)
                s[(2u * jc + a) * to->nphi + 2u * kc + b].l[0] = IRC__EMPTY;
        a = 2.0f * u1 >= 1.0f;
        b = 2.0f * u2 >= 1.0f;
        s[(2u * jc + a) * to->nphi + 2u * kc + b] = keep;
    }
}

/* Fills the empty strata from index *at on with the batch's cnt hits, in
 * the order their rays were made. */
static int irc__fill_empty(irc__sample *s, uint32_t *at, const irc_hit *hits, uint32_t cnt)
{
    uint32_t q;
    for (q = 0; q < cnt; (*at)++) {
        int st;
        if (s[*at].l[0] != IRC__EMPTY)
            continue;
        if ((st = irc__accept_hit(&hits[q++], &s[*at])) < 0)
            return st;
    }
    return IRC_OK;
}

int irc__refine(irc__call *k, uint32_t top, const irc__grid *from, const irc__grid *to,
                const float t1[3], const float t2[3])
{
    irc_cache *c = k->c;
    irc__sample *s = (irc__sample *)(void *)k->slot;
    const uint32_t batch = c->cfg.max_batch;
    irc_ray *rays = irc__slot_rays(c, k->slot);
    irc_hit *hits = (irc_hit *)(void *)(rays + batch);
    const irc__rng rng = irc__rng_for(k->q.p, k->q.n, irc__seed_of(k));
    irc__dirs d[IRC__GRIDS];
    irc__grid gl;
    uint32_t i, cnt = 0, at = 0, used = 0;
    int st;
    for (i = to->level; i <= top; i++) {
        irc__grid_at(c, i, &gl);
        irc__dirs_init(c, &gl, k->q.n, t1, t2, &rng, &d[i]);
    }
    irc__spread(s, d, top, from, to);
    for (i = 0; i < to->strata; i++) {
        if (s[i].l[0] != IRC__EMPTY)
            continue;
        rays[cnt].org[0] = k->q.p[0];
        rays[cnt].org[1] = k->q.p[1];
        rays[cnt].org[2] = k->q.p[2];
        irc__direction(&d[to->level], i / to->nphi, i % to->nphi, rays[cnt].dir);
        if (++cnt < batch)
            continue;
        if ((st = irc__cast(k, rays, hits, cnt)) < 0 ||
            (st = irc__fill_empty(s, &at, hits, cnt)) < 0)
            return st;
        cnt = 0;
    }
    if (cnt && ((st = irc__cast(k, rays, hits, cnt)) < 0 ||
                (st = irc__fill_empty(s, &at, hits, cnt)) < 0))
        return st;
    for (i = 0; i < to->strata; i++)
        used += s[i].d == s[i].d;
    return used * 2u < to->strata || used == 0 ? IRC_ERR_NOSAMPLES : IRC_OK;
}
