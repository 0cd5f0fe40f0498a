/*
 * config.c -- the config's defaults and rules: zero in any field means its
 * default, and every field is checked against its documented range.
 */
#include "../base/kind.h"
#include "config.h"

#define IRC__DEF_ACCURACY 0.2f
/* Strata: 32 x 128 for irradiance records at the default a (coarser at
 * coarser a: irc__theta_for), whose noise is copied to every pixel they
 * serve (on the bench's corpus, without a pixel floor, 16 x 64 records
 * held the error at 2.5-5.5% at a = 0.2, and 32 x 128 halved it:
 * bench/notes.md, "The corpus"); 16 x 64 for SH records, whose two
 * hemispheres double the rays and were not measured so. */
#define IRC__DEF_THETA 32u
#define IRC__FINE_THETA 128u /* the rows' default at the finest a: 65,536 rays a record */
#define IRC__DEF_SH_THETA 16u
#define IRC__DEF_SH_PHI 64u
#define IRC__LOCK_MAX 4096u

int irc__port_ok(const irc_port *p)
{
    return p->lock_init && p->lock_destroy && p->read_lock && p->read_unlock &&
           p->write_lock && p->write_unlock && p->load && p->store &&
           p->fetch_add && p->fetch_or && p->cas && p->lock_size <= IRC__LOCK_MAX &&
           !p->owner == !p->owner_alive;
}

/* One rule for both radius limits: finite, within [0, IRC_RADIUS_CAP],
 * max above min; a max of 0 is the cap (the pixel bounds are the
 * irradiance kind's, kind_irr.c). */
static int irc__radii_resolve(irc_config *out)
{
    if (out->max_radius == 0.0f)
        out->max_radius = IRC__CAP;
    if (!(out->min_radius >= 0.0f && out->min_radius < IRC__CAP) ||
        !(out->max_radius > out->min_radius && out->max_radius <= IRC__CAP))
        return IRC_ERR_CONFIG;
    return IRC_OK;
}

/* An irradiance record's rows by default follow a, so that one knob sets
 * what a record costs: at a = 0.4, 0.3 and 0.2 the grids 8 x 32, 16 x 64
 * and 32 x 128 lay on the lower envelope of error against CPU time on two
 * Sponza views (bench/notes.md, "One knob"); each coarser grid has a
 * quarter of the rays and twice the noise, which coarser placement no
 * longer hides.  Below a = 0.125 the rows double each time a halves, to
 * IRC__FINE_THETA: at 32 x 128 the records' own noise stopped the error
 * (the atrium at a = 0.15 and 0.1: 0.0090 and 0.0086), where 64 x 256 at
 * a = 0.1 reached 0.0047 ("One knob"). */
static uint32_t irc__theta_for(float a)
{
    /* steps at binary fractions: a float a compares with them alike
     * where constants are evaluated wider (x87) */
    uint32_t m = IRC__DEF_THETA;
    float edge = 0.125f;
    if (a >= 0.25f)
        return a < 0.375f ? IRC__DEF_THETA / 2u : IRC__DEF_THETA / 4u;
    for (; a < edge && m < IRC__FINE_THETA; edge *= 0.5f)
        m *= 2u;
    return m;
}

static int irc__sampling_resolve(irc_config *out)
{
    const int sh = (out->features & (IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT)) != 0;
    const uint32_t m = sh ? IRC__DEF_SH_THETA : irc__theta_for(out->accuracy);
    if (out->strata_theta == 0) out->strata_theta = m;
    if (out->strata_phi == 0) out->strata_phi = sh ? IRC__DEF_SH_PHI : 4u * m;
    if (out->strata_theta > 1024u || out->strata_phi > 4096u ||
        out->strata_theta * out->strata_phi > IRC_MAX_STRATA)
        return IRC_ERR_CONFIG;
    if (out->max_batch == 0) out->max_batch = 1;
    if (out->max_batch > IRC_MAX_BATCH)
        return IRC_ERR_CONFIG;
    if (out->max_batch > out->strata_theta * out->strata_phi)
        out->max_batch = out->strata_theta * out->strata_phi;
    if (out->threads == 0) out->threads = 1;
    if (out->threads > IRC_MAX_THREADS || out->no_wait > 1u)
        return IRC_ERR_CONFIG;
    return IRC_OK;
}

/* The kind's own fields and features (irc__kind.resolve), then the
 * irc_switch fields, resolved to 0 (off) or 1 (on) after the kind has set
 * its defaults for those left at IRC_DEFAULT. */
static int irc__kind_resolve(const irc__kind *k, irc_config *out)
{
    int st;
    if (out->clamp_neighbours > IRC_OFF || out->check_visibility > IRC_OFF)
        return IRC_ERR_CONFIG;
#ifdef IRC_NO_SIGHT /* confirming rays left out (util.h): off by default */
    if (out->check_visibility == IRC_ON)
        return IRC_ERR_UNSUPPORTED;
    out->check_visibility = IRC_OFF;
#endif
    if ((st = k->resolve(out)) < 0)
        return st;
    out->clamp_neighbours = out->clamp_neighbours == IRC_ON;
    out->check_visibility = out->check_visibility == IRC_ON;
    return IRC_OK;
}

/* Copies cfg with defaults applied and checks every field. */
int irc__config_resolve(const irc_config *in, irc_config *out)
{
    const irc__kind *k;
    int st;
    if (!in)
        return IRC_ERR_NULL;
    if (in->version != IRC_CONFIG_VERSION)
        return IRC_ERR_VERSION;
    *out = *in;
    if (!out->trace)
        return IRC_ERR_NULL;
    /* Which kind: its features, and no other kind's fields. */
    if ((st = irc__kind_features(out->features)) < 0)
        return st;
    k = irc__kind_of(out->features);
    if (out->accuracy == 0.0f)
        out->accuracy = IRC__DEF_ACCURACY;
    if (!(out->accuracy > 0.0f && out->accuracy <= 10.0f))
        return IRC_ERR_CONFIG;
    if ((st = irc__kind_fields_alone(k, out)) < 0 || (st = irc__radii_resolve(out)) < 0 ||
        (st = irc__sampling_resolve(out)) < 0 || (st = irc__kind_resolve(k, out)) < 0)
        return st;
    if (out->evict > IRC_EVICT_CLOCK)
        return IRC_ERR_CONFIG;
    if (!out->port)
        out->port = irc_port_default;
    if (!irc__port_ok(out->port))
        return IRC_ERR_CONFIG;
    return IRC_OK;
}
