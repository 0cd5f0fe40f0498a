/*
 * config.c -- the config's defaults and rules: zero in any field means its
 * default, and every field is checked against its documented range.
 */
#include "cache.h"

#define IRC__DEF_ACCURACY 0.2f
#define IRC__DEF_THETA 16u
#define IRC__DEF_PHI 64u
/* A record's reach a R in pixels at its point, from the _px call's
 * footprint (pbrt-v2's minimum and maximum pixel spacings). */
#define IRC__DEF_MIN_PIXELS 2.5f
#define IRC__DEF_MAX_PIXELS 15.0f
#define IRC__LOCK_MAX 4096u

int irc__port_ok(const irc_port *p)
{
    return p->lock_init && p->lock_destroy && p->read_lock && p->read_unlock &&
           p->write_lock && p->write_unlock && p->load && p->store &&
           p->fetch_add && p->fetch_or && p->cas && p->lock_size <= IRC__LOCK_MAX &&
           !p->owner == !p->owner_alive;
}

/* IRC_ERR_UNSUPPORTED for features this build leaves out (util.h:
 * IRC_NO_SH, IRC_NO_VISIBILITY, IRC_NO_HESSIAN), else IRC_OK. */
int irc__features_built(uint32_t features)
{
    uint32_t out = 0;
#ifdef IRC_NO_SH
    out |= IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT;
#endif
#ifdef IRC_NO_VISIBILITY
    out |= IRC_FEATURE_VISIBILITY;
#endif
#ifdef IRC_NO_HESSIAN
    out |= IRC_FEATURE_HESSIAN;
#endif
    return features & out ? IRC_ERR_UNSUPPORTED : IRC_OK;
}

/* The one place a config picks its kind (init, attach, the header's
 * check). */
const irc__kind *irc__kind_of(uint32_t features)
{
#ifndef IRC_NO_SH
    if (features & IRC_FEATURE_SH)
        return &irc__kind_sh;
#endif
    (void)features;
    return &irc__kind_irr;
}

uint32_t irc__kind_id_of(uint32_t features)
{
    return irc__kind_of(features) == &irc__kind_irr ? IRC__KIND_IRR : IRC__KIND_SH;
}

/* Which kind of record: SH excludes the irradiance gradients.  The kind
 * resolves its own fields (irc__kind.resolve). */
static int irc__features_resolve(irc_config *out)
{
    const uint32_t irr = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION |
                         IRC_FEATURE_VISIBILITY | IRC_FEATURE_HESSIAN;
    const uint32_t sh = IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT;
    /* Zero is the default, both gradients (every measured scene paid for
     * them); bare records are asked for by name, alone. */
    if (out->features == 0u)
        out->features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
    else if (out->features == IRC_FEATURE_NONE)
        out->features = 0u;
    if (out->features & ~(irr | sh))
        return IRC_ERR_CONFIG;
    if (irc__features_built(out->features) < 0)
        return IRC_ERR_UNSUPPORTED;
    /* Visibility gradients are how the translational gradient is made. */
    if (out->features & IRC_FEATURE_VISIBILITY)
        out->features |= IRC_FEATURE_TRANSLATION;
    if (out->features & IRC_FEATURE_SH_GRADIENT)
        out->features |= IRC_FEATURE_SH;
    if ((out->features & sh) && (out->features & irr))
        return IRC_ERR_CONFIG;
    return IRC_OK;
}

/* One rule for both radius limits: finite, within [0, IRC_RADIUS_CAP],
 * max above min; a max of 0 is the cap. */
static int irc__radii_resolve(irc_config *out)
{
    if (out->max_radius == 0.0f)
        out->max_radius = IRC__CAP;
    if (!(out->min_radius >= 0.0f && out->min_radius < IRC__CAP) ||
        !(out->max_radius > out->min_radius && out->max_radius <= IRC__CAP))
        return IRC_ERR_CONFIG;
    /* Pixel bounds: 0 the default, negative none (stored as 0); a default
     * maximum never falls below the host's minimum. */
    if (!(out->min_pixels > -IRC__CAP && out->min_pixels < IRC__CAP) ||
        !(out->max_pixels > -IRC__CAP && out->max_pixels < IRC__CAP))
        return IRC_ERR_CONFIG;
    if (out->min_pixels == 0.0f) out->min_pixels = IRC__DEF_MIN_PIXELS;
    if (out->max_pixels == 0.0f)
        out->max_pixels = out->min_pixels > IRC__DEF_MAX_PIXELS ? out->min_pixels
                                                                  : IRC__DEF_MAX_PIXELS;
    if (out->min_pixels < 0.0f) out->min_pixels = 0.0f;
    if (out->max_pixels < 0.0f) out->max_pixels = 0.0f;
    if (out->max_pixels > 0.0f && out->max_pixels < out->min_pixels)
        return IRC_ERR_CONFIG;
    return IRC_OK;
}

static int irc__sampling_resolve(irc_config *out)
{
    if (out->strata_theta == 0) out->strata_theta = IRC__DEF_THETA;
    if (out->strata_phi == 0) out->strata_phi = IRC__DEF_PHI;
    if (out->strata_theta > 1024u || out->strata_phi > 4096u ||
        out->strata_theta * out->strata_phi > IRC_MAX_STRATA)
        return IRC_ERR_CONFIG;
    if (out->max_batch == 0) out->max_batch = 1;
    if (out->max_batch > IRC_MAX_BATCH)
        return IRC_ERR_CONFIG;
    if (out->max_batch > out->strata_theta * out->strata_phi)
        out->max_batch = out->strata_theta * out->strata_phi;
    if (out->supersamples > out->strata_theta * out->strata_phi ||
        (out->supersamples && (out->features & (IRC_FEATURE_VISIBILITY | IRC_FEATURE_SH))))
        return IRC_ERR_CONFIG;
    if (out->threads == 0) out->threads = 1;
    if (out->threads > IRC_MAX_THREADS || out->no_wait > 1u)
        return IRC_ERR_CONFIG;
    return IRC_OK;
}

/* The irc_switch fields, resolved to 0 (off) or 1 (on), after the kind
 * has set its defaults for those left at IRC_DEFAULT (the leak guard paid
 * only between rooms: off for every kind). */
static int irc__switches_resolve(irc_config *out)
{
    int st;
    if (out->clamp_neighbours > IRC_OFF || out->leak_guard > IRC_OFF ||
        out->check_visibility > IRC_OFF)
        return IRC_ERR_CONFIG;
    if ((st = irc__kind_of(out->features)->resolve(out)) < 0)
        return st;
    out->clamp_neighbours = out->clamp_neighbours == IRC_ON;
    out->leak_guard = out->leak_guard == IRC_ON;
    out->check_visibility = out->check_visibility == IRC_ON;
    return IRC_OK;
}

/* Copies cfg with defaults applied and checks every field. */
int irc__config_resolve(const irc_config *in, irc_config *out)
{
    int st;
    if (!in)
        return IRC_ERR_NULL;
    *out = *in;
    if (!out->trace)
        return IRC_ERR_NULL;
    if ((st = irc__features_resolve(out)) < 0 || (st = irc__radii_resolve(out)) < 0 ||
        (st = irc__sampling_resolve(out)) < 0 || (st = irc__switches_resolve(out)) < 0)
        return st;
    if (out->accuracy == 0.0f)
        out->accuracy = IRC__DEF_ACCURACY;
    if (!(out->accuracy > 0.0f && out->accuracy <= 10.0f))
        return IRC_ERR_CONFIG;
    if (out->evict > IRC_EVICT_CLOCK)
        return IRC_ERR_CONFIG;
    if (!out->port)
        out->port = irc_port_default;
    if (!irc__port_ok(out->port))
        return IRC_ERR_CONFIG;
    return IRC_OK;
}
