/*
 * api_sh.c -- the SH cache's public calls (irrcache.h, "SH records"): each
 * drives the store (store.c) and the lookup (lookup.c) with the SH kind's
 * table (kind_sh.c).
 */
#include "../sh/shrec.h"
#include "../store/lookup.h"
#include "../store/store.h"

#ifndef IRC_NO_SH

int irc_sh_compute(irc_cache *c, const float p[3], const float n[3], irc_sh *out, void *host)
{
    return irc__compute(c, &irc__kind_sh, p, n, out, host, irc__kind_sh.compute, 1);
}

int irc_sh_insert(irc_cache *c, const irc_sh *rec)
{
    return irc__insert(c, &irc__kind_sh, rec);
}

int irc_sh_lookup(irc_cache *c, const float p[3], const float n[3], irc_sh *out,
                  float *weight)
{
    return irc__lookup(c, &irc__kind_sh, irc__kind_sh.lookup, p, n, out, weight);
}

int irc_sh_lookup_or_compute(irc_cache *c, const float p[3], const float n[3], irc_sh *out,
                             float *weight, void *host)
{
    return irc__lookup_or_compute(c, &irc__kind_sh, p, n, out, weight, host);
}

int irc_sh_record(irc_cache *c, uint32_t id, irc_sh *out)
{
    return irc__record_get(c, &irc__kind_sh, id, out);
}

#else /* IRC_NO_SH: the public calls are absent.c's */

typedef int irc__api_sh_absent; /* ISO C wants something in a file */

#endif
