/*
 * trace.c -- the host's trace callback, called from one place: every ray
 * the library casts (records' hemispheres, visibility bisections, per-pixel
 * probes, confirming rays) goes through irc__cast.
 */
#include "../block/form.h"
#include "trace.h"

/* One call of the host's callback: every ray cast goes through here, so
 * the host always sees the same arguments (its per-call pointer, the
 * record's position and normal) and the same checks apply.  Returns
 * IRC_OK or a negative code (the callback's own, passed through). */
static int irc__cast_run(irc__call *k, irc_ray *rays, irc_hit *hits, uint32_t count)
{
    const irc_cache *c = k->c;
    irc_trace_args args;
    uint32_t i;
    int st;
    args.context = c->cfg.context;
    args.host = k->host;
    for (i = 0; i < 3; i++) {
        args.p[i] = k->q.p[i];
        args.n[i] = k->q.n[i];
    }
    args.rays = rays;
    args.hits = hits;
    args.count = count;
    args.visibility_only = k->visibility_only;
    for (i = 0; i < count; i++)
        hits[i].status = -1;
    st = c->cfg.trace(&args);
    if (st > 0)
        return IRC_ERR_CALLBACK;
    k->rays += count;
    return st;
}

/* A ray below the query's geometric surface would find that surface at
 * a distance near 0, which no estimate can tell from geometry within
 * reach: it fails uncast (IRC_RAY_FAILED, left out as the host's failed
 * rays are), and the rays between such ones go to the host in runs, in
 * their order.  Confirming rays, which run along the surface toward
 * records on it, are cast whatever their direction. */
int irc__cast(irc__call *k, irc_ray *rays, irc_hit *hits, uint32_t count)
{
    const float *g = k->q.g;
    uint32_t i = 0, j;
    int st;
    if (!k->q.under || k->visibility_only == IRC_VISIBILITY_CONFIRM)
        return irc__cast_run(k, rays, hits, count);
    while (i < count) {
        for (j = i; j < count && irc__dot3(rays[j].dir, g) > 0.0f; j++)
            ;
        if (j > i && (st = irc__cast_run(k, rays + i, hits + i, j - i)) < 0)
            return st;
        for (i = j; i < count && irc__dot3(rays[i].dir, g) <= 0.0f; i++)
            hits[i].status = IRC_RAY_FAILED;
    }
    return IRC_OK;
}

int irc__cast_visibility(irc__call *k, irc_ray *rays, irc_hit *hits, uint32_t count,
                         uint32_t why)
{
    int st;
    k->visibility_only = why;
    st = irc__cast(k, rays, hits, count);
    k->visibility_only = 0;
    return st;
}

int irc__visibility_hit(const irc_hit *h)
{
    if (h->status < IRC_RAY_HIT || h->status > IRC_RAY_FAILED)
        return IRC_ERR_CALLBACK;
    if (h->status != IRC_RAY_HIT)
        return 0;
    return h->dist > 0.0f && h->dist <= FLT_MAX ? 1 : IRC_ERR_CALLBACK;
}
