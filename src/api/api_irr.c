/*
 * api_irr.c -- the irradiance cache's public calls (irrcache.h): each
 * checks its arguments and drives the store (store.c) and the lookup
 * (lookup.c) with the irradiance kind's table (kind_irr.c); the _px call
 * first answers points near finer geometry per pixel (detail.c).
 */
#include "../irr/detail.h"
#include "../irr/estimator.h"
#include "../store/lookup.h"
#include "../store/store.h"

int irc_record_compute(irc_cache *c, const float p[3], const float n[3], irc_record *out,
                       void *host)
{
    return irc__compute(c, &irc__kind_irr, p, n, out, host, irc__kind_irr.compute, 1);
}

int irc_cache_insert(irc_cache *c, const irc_record *rec)
{
    return irc__insert(c, &irc__kind_irr, rec);
}

int irc_cache_lookup(irc_cache *c, const float p[3], const float n[3], float rgb[3],
                     float *weight)
{
    return irc__lookup(c, &irc__kind_irr, irc__kind_irr.lookup, p, n, rgb, weight);
}

int irc_cache_lookup_gradient(irc_cache *c, const float p[3], const float n[3], float rgb[3],
                              irc_gradient *grad, float *weight)
{
    irc__grad_out o;
    o.rgb = rgb;
    o.grad = grad;
    return irc__lookup(c, &irc__kind_irr, &irc__irr_grad_lookup, p, n, rgb && grad ? &o : NULL,
                       weight);
}

int irc_cache_lookup_or_compute(irc_cache *c, const float p[3], const float n[3],
                                float rgb[3], float *weight, void *host)
{
    return irc_cache_lookup_or_compute_px(c, p, n, NULL, 0.0f, rgb, weight, host);
}

int irc_cache_lookup_or_compute_px(irc_cache *c, const float p[3], const float n[3],
                                   const float ng[3], float footprint, float rgb[3],
                                   float *weight, void *host)
{
    irc__loc px;
    int st = irc__loc_open(c, &irc__kind_irr, p, n, ng, footprint, rgb, &px);
    if (st < 0)
        return st;
    st = irc__detail_px(c, &px, rgb, host);
    return irc__loc_finish(c, &px, st, rgb, weight, host);
}

int irc_cache_record(irc_cache *c, uint32_t id, irc_record *out)
{
    return irc__record_get(c, &irc__kind_irr, id, out);
}
