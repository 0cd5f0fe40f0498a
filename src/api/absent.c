/*
 * absent.c -- what stands in for the parts a build leaves out (util.h's
 * IRC_NO_* switches, or make LEAVE_OUT=...): the public calls of SH records
 * and of occlusion, each answering IRC_ERR_UNSUPPORTED, as on a cache
 * whose features do not serve it, after the handle checks every call
 * makes; the SH kind's table of features alone (kinds.c).  The files left out are
 * then empty or not compiled at all; nothing else of the library names
 * them.
 */
#include "../block/check.h"
#include "../irr/estimator.h"
#include "../sh/shrec.h"

#ifdef IRC_NO_SH
/* The SH kind's features alone, so that a config or a block asking for
 * them is unsupported rather than wrong (kinds.c); nothing reaches its
 * operations. */
const irc__kind irc__kind_sh = {
    .id = IRC__KIND_SH_ID,
    .features = IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT,
    .unbuilt = IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT,
    .cfg_at = (uint32_t)offsetof(irc_config, sh),
    .cfg_bytes = (uint32_t)sizeof(struct irc_config_sh)};

/* As on an irradiance cache: no cache of this build holds SH records. */
static int irc__no_sh(const irc_cache *c)
{
    const int st = irc__enter(c, NULL);
    return st < 0 ? st : IRC_ERR_UNSUPPORTED;
}

int irc_sh_compute(irc_cache *c, const float p[3], const float n[3], irc_sh *out, void *host)
{
    (void)p; (void)n; (void)out; (void)host;
    return irc__no_sh(c);
}

int irc_sh_insert(irc_cache *c, const irc_sh *rec)
{
    (void)rec;
    return irc__no_sh(c);
}

int irc_sh_lookup(irc_cache *c, const float p[3], const float n[3], irc_sh *out,
                  float *weight)
{
    (void)p; (void)n; (void)out; (void)weight;
    return irc__no_sh(c);
}

int irc_sh_lookup_or_compute(irc_cache *c, const float p[3], const float n[3], irc_sh *out,
                             float *weight, void *host)
{
    (void)p; (void)n; (void)out; (void)weight; (void)host;
    return irc__no_sh(c);
}

int irc_sh_record(irc_cache *c, uint32_t id, irc_sh *out)
{
    (void)id; (void)out;
    return irc__no_sh(c);
}

int irc_sh_glossy(const irc_sh *sh, const float r[3], float s, float rgb[3])
{
    (void)sh; (void)r; (void)s; (void)rgb;
    return IRC_ERR_UNSUPPORTED;
}

int irc_sh_irradiance(const irc_sh *sh, const float n[3], float rgb[3])
{
    (void)sh; (void)n; (void)rgb;
    return IRC_ERR_UNSUPPORTED;
}

int irc_sh_radiance(const irc_sh *sh, const float w[3], float rgb[3])
{
    (void)sh; (void)w; (void)rgb;
    return IRC_ERR_UNSUPPORTED;
}
#endif

#ifdef IRC_NO_VISIBILITY
int irc_occlusion_compute(irc_cache *c, const float p[3], const float n[3],
                          irc_occlusion *out, void *host)
{
    const int st = irc__enter(c, &irc__kind_irr);
    (void)p; (void)n; (void)out; (void)host;
    return st < 0 ? st : IRC_ERR_UNSUPPORTED;
}
#endif

#if !defined(IRC_NO_SH) && !defined(IRC_NO_VISIBILITY)
typedef int irc__nothing_absent; /* ISO C wants something in a file */
#endif
