/*
 * detail.c -- per-pixel estimates where geometry is nearer than a record
 * can serve (cfg.irr.detail_pixels): V-Ray's "detail enhancement".
 *
 * A record interpolates what its hemisphere saw; a point closer to an edge
 * than any record sees what none of them did (a ceiling point 0.05 mm from
 * a light panel hung 0.1 mm below it sees the panel's dark back over a
 * third of its hemisphere; the records a few millimetres away do not).
 * The _px call can probe for such geometry with a few rays and answer
 * from the point's own hemisphere, not stored.  With the full grid: a
 * record within a pixel of such geometry would serve about that pixel
 * alone, so the estimate costs what the record would, and a coarser one
 * spreads per-pixel noise over every detail pixel (bench/notes.md,
 * "Detail computed per pixel").
 */
#include "../block/form.h"
#include "../block/check.h"
#include "../store/lookup.h"
#include "../store/stats.h"
#include "../store/trace.h"
#include "detail.h"
#include "estimator.h"

/* Probes at 60 degrees from n (sin^2 theta = 3/4: a wall at distance d
 * across the tangent plane is hit within d / cos 30 deg), 45 degrees apart
 * in azimuth. */
#define IRC__PROBES 8u

typedef struct irc__detail {
    float reach; /* a probe that hits within it makes the point detail */
    int near;
    float e[3];
} irc__detail;

static void irc__detail_dir(const irc__call *k, const float t1[3], const float t2[3], uint32_t i,
                           float d[3])
{
    static const float cs[IRC__PROBES] = {1.0f, 0.70710678f, 0.0f, -0.70710678f,
                                          -1.0f, -0.70710678f, 0.0f, 0.70710678f};
    const float st = 0.8660254f, x = st * cs[i], y = st * cs[(i + 6u) % IRC__PROBES];
    int a;
    for (a = 0; a < 3; a++)
        d[a] = x * t1[a] + y * t2[a] + 0.5f * k->q.n[a];
}

/* Casts the probes (stopping at the first that hits within reach). */
static int irc__detail_probe(irc__call *k, irc__detail *dt)
{
    irc_cache *c = k->c;
    irc_ray *rays = irc__slot_rays(c, k->slot);
    irc_hit *hits = (irc_hit *)(void *)(rays + c->cfg.max_batch);
    float t1[3], t2[3];
    uint32_t i = 0, j;
    irc__frame(k->q.n, t1, t2);
    dt->near = 0;
    while (i < IRC__PROBES && !dt->near) {
        const uint32_t left = IRC__PROBES - i;
        const uint32_t cnt = left < c->cfg.max_batch ? left : c->cfg.max_batch;
        int st;
        for (j = 0; j < cnt; j++) {
            IRC_MEMCPY(rays[j].org, k->q.p, sizeof rays[j].org);
            irc__detail_dir(k, t1, t2, i + j, rays[j].dir);
        }
        if ((st = irc__cast_visibility(k, rays, hits, cnt, IRC_VISIBILITY_PROBE)) < 0)
            return st;
        for (j = 0; j < cnt; j++) {
            if ((st = irc__visibility_hit(&hits[j])) < 0)
                return st;
            if (st && hits[j].dist <= dt->reach)
                dt->near = 1;
        }
        i += cnt;
    }
    return IRC_OK;
}

static int irc__detail_run(irc__call *k, void *out)
{
    irc__detail *dt = (irc__detail *)out;
    int st = irc__detail_probe(k, dt);
    if (st < 0 || !dt->near)
        return st;
    /* the configured grid's rays, or a progressive cache's level's */
    return k->progress ? irc__irr_progressive_e(k, dt->e) : irc__irr_estimate_on(k, 0u, dt->e);
}

int irc__detail_px(irc_cache *c, irc__loc *px, float rgb[3], void *host)
{
    irc__detail dt;
    uint32_t rays;
    int st, waited;
    if (!(px->footprint > 0.0f) || !(c->cfg.irr.detail_pixels > 0.0f))
        return IRC_MISS;
    dt.reach = c->cfg.irr.detail_pixels * px->footprint;
    st = irc__compute_at(c, &px->q, &dt, host, irc__detail_run, &rays, &waited);
    /* No slot (cfg.no_wait) or the caller's own (from inside its
     * callback): the plain path answers what records cover, as without
     * detail. */
    if (st == IRC_ERR_BUSY || st == IRC_ERR_NESTED)
        return IRC_MISS;
    if (st < 0)
        return st;
    px->tally.add[IRC__C_RAYS] += rays;
    if (!dt.near)
        return IRC_MISS;
    px->tally.add[IRC__C_LOOKUPS]++;
    px->tally.add[IRC__C_DETAILS]++;
    px->tally.add[IRC__C_WAITS] += waited != 0;
    rgb[0] = dt.e[0];
    rgb[1] = dt.e[1];
    rgb[2] = dt.e[2];
    return IRC_DETAIL;
}
