/*
 * occlusion.c -- irc_occlusion_compute: a hemisphere's net visibility and
 * its gradient from the silhouettes (visibility.c), without a record.
 */
#include "../block/form.h"
#include "../block/check.h"
#include "../irr/estimator.h"
#include "../sample/sampler.h"
#include "../store/lookup.h"

#ifndef IRC_NO_VISIBILITY

static int irc__occlusion(irc__call *k, void *dst)
{
    irc_occlusion *out = (irc_occlusion *)dst;
    float t1[3], t2[3], g[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    irc__grid grid;
    int st, i;
    irc__grid_at(k->c, 0, &grid);
    if ((st = irc__hemisphere(k, &grid, t1, t2, k->c->cfg.irr.supersamples)) < 0)
        return st;
    out->visible = irc__net_visibility(k->c, (const irc__sample *)(void *)k->slot);
    if ((st = irc__grad_visibility(k, 1, g)) < 0)
        return st;
    for (i = 0; i < 3; i++)
        out->grad[i] = (float)(g[0][i] / (2.0f * IRC_PI));
    out->rays = k->rays;
    return IRC_OK;
}

int irc_occlusion_compute(irc_cache *c, const float p[3], const float n[3],
                          irc_occlusion *out, void *host)
{
    int st = irc__enter(c, &irc__kind_irr);
    if (st < 0)
        return st;
    if (!(c->cfg.features & IRC_FEATURE_VISIBILITY))
        return IRC_ERR_UNSUPPORTED;
    return irc__compute(c, &irc__kind_irr, p, n, out, host, irc__occlusion, 0);
}

#else /* IRC_NO_VISIBILITY: the public call is absent.c's */

typedef int irc__occlusion_absent; /* ISO C wants something in a file */

#endif
