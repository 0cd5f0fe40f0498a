/*
 * progress.c -- the cache in a progressive renderer: irc_progress, which
 * refines every record as the host's samples a pixel grow (the schedule
 * is progressive.c's), and irc_cache_lookup_pixel, which keeps a pixel's
 * answer in the host's irc_pixel so that the pixel's later samples reuse
 * it until the records refine, and refines a per-pixel detail estimate
 * instead of making it again.
 *
 * A path tracer calls its shading once a sample: 0.4's _px call then
 * looked up, probed and (near finer geometry) estimated per pixel at every
 * sample; a record was one fixed estimate, whose noise stopped the
 * image's error falling from some sample count on.  Here a pixel's work
 * is done once a level (log2 of the samples), and a record's rays follow
 * the samples.
 */
#include "../block/cache.h"
#include "../block/check.h"
#include "../block/slots.h"
#include "../irr/estimator.h"
#include "../store/lock.h"
#include "../store/lookup.h"
#include "../store/stats.h"
#include "../store/store.h"

/* A cache whose records can be refined: estimates on coarser grids
 * exist for every part of its records (kind_irr.c refuses the same
 * configs for full_pixels). */
static int irc__refinable(const irc_cache *c)
{
    return !(c->cfg.features & (IRC_FEATURE_VISIBILITY | IRC_FEATURE_HESSIAN)) &&
           c->cfg.irr.supersamples == 0u;
}

/* Record id taken from level `from` to `to` with k's slot. */
static int irc__refine_record(irc_cache *c, irc__call *k, uint32_t id, uint32_t from,
                              uint32_t to)
{
    irc_record rec;
    int st, a;
    c->kind->unpack(c, irc__rec_at(c, id), &rec);
    for (a = 0; a < 3; a++) {
        k->q.p[a] = rec.p[a];
        k->q.n[a] = rec.n[a];
    }
    k->rays = 0;
    rec.rays = rec.rays_used = 0;
    if ((st = irc__irr_refine(k, &rec, from, to)) < 0)
        return st;
    /* an estimate no check refuses keeps the record as it was */
    (void)irc__store_refresh(c, id, &rec);
    return IRC_OK;
}

/* Every record from level `from` to `to` with scratch slot `slot`; what
 * was cast into t. */
static int irc__refine_all(irc_cache *c, uint32_t slot, uint32_t from, uint32_t to, void *host,
                           irc__counts *t)
{
    irc__call k;
    uint32_t id, count = irc__st(c)->count;
    int st;
    IRC_MEMSET(&k, 0, sizeof k);
    k.c = c;
    k.slot = irc__slot(c, slot);
    k.host = host;
    k.progress = to + 1u;
    for (id = 0, st = IRC_OK; id < count && st >= 0; id++)
        if ((st = irc__refine_record(c, &k, id, from, to)) >= 0)
            t->add[IRC__C_RAYS] += k.rays;
    return st;
}

int irc_progress(irc_cache *c, uint32_t samples, void *host)
{
    irc__counts t;
    uint32_t level, old, from;
    int st = irc__enter(c, &irc__kind_irr);
    if (st < 0)
        return st;
    if (!irc__refinable(c))
        return IRC_ERR_UNSUPPORTED;
    if (irc__st(c)->pass_open)
        return IRC_ERR_STATE;
    level = irc__progress_level(c, samples) + 1u;
    old = irc__st(c)->progress;
    if (level == old)
        return IRC_OK;
    if (level < old && irc__st(c)->count)
        return IRC_ERR_RANGE;
    IRC_MEMSET(&t, 0, sizeof t);
    /* Records made before the cache was progressive have the configured
     * grid's rays: they join the schedule where it reaches them. */
    from = old ? old - 1u : irc__progress_full(c);
    if (irc__st(c)->count && from < level - 1u) {
        uint32_t slot;
        int waited;
        /* no slot (IRC_ERR_NESTED inside a callback, IRC_ERR_BUSY): the
         * cache as it was */
        if ((st = irc__slot_claim(c, &slot, &waited)) < 0)
            return st;
        st = irc__refine_all(c, slot, from, level - 1u, host, &t);
        irc__slot_release(c, slot);
    }
    /* Even after a callback's error: the records before it are refined,
     * and must not be again; those after keep their rays. */
    if (irc__write_lock(c) < 0)
        return IRC_ERR_PORT;
    irc__st(c)->progress = level;
    irc__write_unlock(c);
    irc__count_tally(c, &t);
    return st;
}

/* ------------------------------------------------------------------------ */

/* Within this many footprints of the point a pixel's answer was made for,
 * a sample reuses it: a pixel's samples lie within sqrt(2) of each other. */
#define IRC__PIXEL_REACH 2.0f
/* ... and with a normal within about 18 degrees of its normal. */
#define IRC__PIXEL_COS 0.95f

/* Whether the pixel's answer was made for a point near (p, n). */
static int irc__pixel_near(const irc_pixel_answer *px, const float p[3], const float n[3],
                           float footprint)
{
    const float f = IRC__PIXEL_REACH * (footprint > px->footprint ? footprint : px->footprint);
    float d2 = 0.0f, dn = 0.0f;
    int a;
    for (a = 0; a < 3; a++) {
        const float d = p[a] - px->p[a];
        d2 += d * d;
        dn += n[a] * px->n[a];
    }
    return d2 <= f * f && dn >= IRC__PIXEL_COS;
}

typedef struct irc__more {
    float e[3];
    uint32_t from, to;
} irc__more;

static int irc__more_run(irc__call *k, void *out)
{
    irc__more *m = (irc__more *)out;
    return irc__irr_refine_e(k, m->e, m->from, m->to);
}

/* A kept detail estimate taken from its level to the one a detail has in
 * the cache's level (progressive.c, irc__detail_level), at (p, n). */
static int irc__pixel_refine(irc_cache *c, irc_pixel_answer *px, const float p[3], const float n[3],
                             const float ng[3], void *host)
{
    irc__query q;
    irc__more m;
    irc__counts t;
    uint32_t rays;
    int st, waited, a;
    IRC_MEMSET(&q, 0, sizeof q);
    for (a = 0; a < 3; a++) {
        q.p[a] = p[a];
        q.n[a] = n[a];
        m.e[a] = px->e[a];
    }
    if ((st = irc__query_ground(&q, ng)) < 0)
        return st;
    m.from = px->level;
    m.to = irc__detail_level(c, irc__st(c)->progress - 1u);
    if ((st = irc__compute_at(c, &q, &m, host, irc__more_run, &rays, &waited)) < 0)
        return st;
    IRC_MEMSET(&t, 0, sizeof t);
    t.add[IRC__C_RAYS] = rays;
    t.add[IRC__C_LOOKUPS] = 1;
    t.add[IRC__C_DETAILS] = 1;
    t.add[IRC__C_WAITS] = waited != 0;
    irc__count_tally(c, &t);
    for (a = 0; a < 3; a++)
        px->e[a] = m.e[a];
    px->level = m.to;
    return IRC_DETAIL;
}

/* Answer i of the pixel, when it serves (p, n) now: IRC_MISS when not. */
static int irc__pixel_kept(irc_cache *c, irc_pixel_answer *px, const float p[3],
                           const float n[3], const float ng[3], float footprint, void *host)
{
    const uint32_t epoch = irc__st(c)->progress + 1u;
    int st;
    if (!px->epoch || !irc__pixel_near(px, p, n, footprint))
        return IRC_MISS;
    if (px->epoch == epoch)
        return px->status;
    /* A detail estimate gets the rays it lacks (a record's answer is
     * looked up again: its records have changed). */
    if (px->status != IRC_DETAIL || px->epoch < 2u || px->epoch > epoch)
        return IRC_MISS;
    if (px->level < irc__detail_level(c, epoch - 2u) &&
        (st = irc__pixel_refine(c, px, p, n, ng, host)) < 0)
        return st;
    px->epoch = epoch;
    return IRC_DETAIL;
}

/* A new answer at (p, n): the _px call, but where a kept answer near the
 * point was no detail, without its probes (the geometry around it has not
 * moved: they would find what they found) and answered by any record
 * within the lookups' reach (blend a R), not only within a R: a record
 * made for this pixel serves its next levels' samples, which land
 * anywhere in the pixel, instead of another being made beside it. */
static int irc__pixel_fresh(irc_cache *c, const irc_pixel *pixel, const float p[3],
                            const float n[3], const float ng[3], float footprint, float rgb[3],
                            float *w, void *host)
{
    irc__loc px;
    int i, st;
    for (i = 0; i < 2; i++) {
        const irc_pixel_answer *k = &pixel->kept[i];
        if (k->epoch && k->status != IRC_DETAIL && irc__pixel_near(k, p, n, footprint))
            break;
    }
    if (i == 2)
        return irc_cache_lookup_or_compute_px(c, p, n, ng, footprint, rgb, w, host);
    if ((st = irc__loc_open(c, &irc__kind_irr, p, n, ng, footprint, rgb, &px)) < 0)
        return st;
    px.loose = 1;
    return irc__loc_finish(c, &px, IRC_MISS, rgb, w, host);
}

int irc_cache_lookup_pixel(irc_cache *c, irc_pixel *pixel, const float p[3], const float n[3],
                           const float ng[3], float footprint, float rgb[3], float *weight,
                           void *host)
{
    irc_pixel_answer *px;
    irc__query q;
    float *un = q.n, w = 0.0f;
    int st = irc__enter(c, &irc__kind_irr), a, i;
    if (st < 0)
        return st;
    if (!pixel || !rgb)
        return IRC_ERR_NULL;
    /* the normal the point gathers around (n, or ng: irc__query_ground) */
    if ((st = irc__check_vec(p)) < 0 || (st = irc__check_normal(n, un)) < 0 ||
        (st = irc__query_ground(&q, ng)) < 0)
        return st;
    if (!irc__finite(footprint))
        return IRC_ERR_NONFINITE;
    if (footprint < 0.0f)
        return IRC_ERR_RANGE;
    for (i = 0; i < 2; i++) {
        px = &pixel->kept[i];
        if ((st = irc__pixel_kept(c, px, p, un, ng, footprint, host)) == IRC_MISS)
            continue;
        if (st < 0)
            return st;
        for (a = 0; a < 3; a++)
            rgb[a] = px->e[a];
        if (weight)
            *weight = px->weight;
        pixel->older = 1u - (uint32_t)i;
        return st;
    }
    if ((st = irc__pixel_fresh(c, pixel, p, un, ng, footprint, rgb, &w, host)) < 0)
        return st;
    px = &pixel->kept[pixel->older & 1u];
    for (a = 0; a < 3; a++) {
        px->p[a] = p[a];
        px->n[a] = un[a];
        px->e[a] = rgb[a];
    }
    px->weight = w;
    px->footprint = footprint;
    px->status = st;
    px->epoch = irc__st(c)->progress + 1u;
    px->level = 0; /* a new detail estimate's (progressive.c) */
    pixel->older = (pixel->older & 1u) ^ 1u;
    if (weight)
        *weight = w;
    return st;
}
