/*
 * config.c -- defaults, validation, and the layout of the caller's block.
 *
 * Layout, from the first 64-byte boundary of the block on:
 *   struct irc_cache | lock | scratch slots | records | next links | nodes |
 *   CLOCK bits (only with eviction)
 * Each part starts on a 64-byte boundary, so the footprint carries 63 bytes
 * of slack for a block of any alignment.
 */
#include "cache.h"

#define IRC__DEF_ACCURACY 0.2f
#define IRC__DEF_THETA 16u
#define IRC__DEF_PHI 64u
#define IRC__DEF_BANDS 3u
#define IRC__DEF_POWER 2.0f

typedef struct irc__layout {
    size_t lock, scratch, records, next, nodes, used, total;
    size_t slot_bytes;
    uint32_t rec_size, off_t, off_r, off_sh, off_shg, node_cap, samples;
} irc__layout;

const char *irc_strerror(int status)
{
    switch (status) {
    case IRC_OK: return "ok";
    case IRC_MISS: return "no record close enough";
    case IRC_NOT_STORED: return "computed, but the pool is full: not stored";
    case IRC_ERR_NULL: return "a required pointer is NULL";
    case IRC_ERR_CONFIG: return "a config field is out of range";
    case IRC_ERR_NONFINITE: return "a coordinate or value is NaN or infinite";
    case IRC_ERR_NORMAL: return "a normal is zero or not finite";
    case IRC_ERR_NOMEM: return "the block is smaller than irc_footprint() asks";
    case IRC_ERR_FULL: return "the record pool is full and eviction is off";
    case IRC_ERR_CALLBACK: return "the trace callback reported an invalid result";
    case IRC_ERR_NOSAMPLES: return "too few usable rays for a record";
    case IRC_ERR_BUSY: return "more concurrent computations than cfg.threads";
    case IRC_ERR_UNSUPPORTED: return "a call this cache's features do not serve";
    case IRC_ERR_PORT: return "the port could not initialise its lock";
    case IRC_ERR_RANGE: return "an index is past the end";
    default: return status < 0 ? "error from the trace callback" : "unknown status";
    }
}

int irc__check_vec(const float v[3])
{
    if (!v)
        return IRC_ERR_NULL;
    return irc__finite3(v) ? IRC_OK : IRC_ERR_NONFINITE;
}

/* Normalises in double after dividing by the largest component, so that a
 * normal made of denormals is still a direction and not a zero. */
int irc__check_normal(const float n[3], double unit[3])
{
    double m, len;
    int i;
    if (!n)
        return IRC_ERR_NULL;
    if (!irc__finite3(n))
        return IRC_ERR_NORMAL;
    m = fabs((double)n[0]);
    if (fabs((double)n[1]) > m) m = fabs((double)n[1]);
    if (fabs((double)n[2]) > m) m = fabs((double)n[2]);
    if (m == 0.0)
        return IRC_ERR_NORMAL;
    for (i = 0; i < 3; i++)
        unit[i] = (double)n[i] / m;
    len = IRC_SQRT(irc__dot3d(unit, unit));
    for (i = 0; i < 3; i++)
        unit[i] /= len;
    return IRC_OK;
}

static int irc__port_ok(const irc_port *p)
{
    return p->lock_init && p->lock_destroy && p->read_lock && p->read_unlock &&
           p->write_lock && p->write_unlock && p->load && p->store &&
           p->fetch_add && p->fetch_or && p->cas;
}

/* Copies cfg with defaults applied and checks every field. */
static int irc__config_resolve(const irc_config *in, irc_config *out)
{
    const uint32_t irr = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION |
                         IRC_FEATURE_VISIBILITY;
    const uint32_t sh = IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT;
    if (!in)
        return IRC_ERR_NULL;
    *out = *in;
    if (!out->trace)
        return IRC_ERR_NULL;
    if (out->features & ~(irr | sh))
        return IRC_ERR_CONFIG;
    /* Visibility gradients are how the translational gradient is made. */
    if (out->features & IRC_FEATURE_VISIBILITY)
        out->features |= IRC_FEATURE_TRANSLATION;
    if (out->features & IRC_FEATURE_SH_GRADIENT)
        out->features |= IRC_FEATURE_SH;
    if ((out->features & sh) && (out->features & irr))
        return IRC_ERR_CONFIG;
    if (out->features & IRC_FEATURE_SH) {
        if (out->sh_bands == 0) out->sh_bands = IRC__DEF_BANDS;
        if (out->sh_channels == 0) out->sh_channels = 3u;
        if (out->sh_power == 0.0f) out->sh_power = IRC__DEF_POWER;
        if (out->sh_bands > IRC_SH_MAX_BANDS ||
            (out->sh_channels != 1u && out->sh_channels != 3u) ||
            !(out->sh_power > 0.0f && out->sh_power <= 16.0f))
            return IRC_ERR_CONFIG;
    } else if (out->sh_bands || out->sh_channels || out->sh_power != 0.0f) {
        return IRC_ERR_CONFIG;
    }
    if (out->accuracy == 0.0f)
        out->accuracy = IRC__DEF_ACCURACY;
    if (!(out->accuracy > 0.0f && out->accuracy <= 10.0f))
        return IRC_ERR_CONFIG;
    if (!(out->min_radius >= 0.0f && out->min_radius < IRC_RADIUS_CAP))
        return IRC_ERR_CONFIG;
    if (out->max_radius == 0.0f || out->max_radius > IRC_RADIUS_CAP)
        out->max_radius = IRC_RADIUS_CAP;
    if (!(out->max_radius > out->min_radius))
        return IRC_ERR_CONFIG;
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
    if (out->threads == 0) out->threads = 1;
    if (out->threads > IRC_MAX_THREADS)
        return IRC_ERR_CONFIG;
    if (out->evict > IRC_EVICT_CLOCK)
        return IRC_ERR_CONFIG;
    if (!out->port)
        out->port = irc_port_default;
    if (!irc__port_ok(out->port))
        return IRC_ERR_CONFIG;
    return IRC_OK;
}

static size_t irc__up(size_t x)
{
    return (x + (IRC__ALIGN - 1)) & ~(size_t)(IRC__ALIGN - 1);
}

/* Index pool: the root plus one block of 8 children per 16 records.  A leaf
 * splits only when more than 8 records sit in it, so this suffices for
 * ordinary scenes; when it runs out, leaves simply grow longer (lookups stay
 * exact, only slower).  irc_stats reports the nodes used. */
static uint32_t irc__node_cap(uint32_t capacity)
{
    return 1u + 8u * (capacity / 16u + 8u);
}

static void irc__layout_of(const irc_config *cfg, uint32_t capacity,
                           irc__layout *l)
{
    size_t at = irc__up(sizeof(irc_cache)), geom = 0;
    l->rec_size = (uint32_t)sizeof(irc__rec);
    l->off_t = l->off_r = l->off_sh = l->off_shg = 0;
    l->samples = cfg->strata_theta * cfg->strata_phi;
    if (cfg->features & IRC_FEATURE_TRANSLATION) {
        l->off_t = l->rec_size;
        l->rec_size += (uint32_t)sizeof(irc__grad);
    }
    if (cfg->features & IRC_FEATURE_ROTATION) {
        l->off_r = l->rec_size;
        l->rec_size += (uint32_t)sizeof(irc__grad);
    }
    if (cfg->features & IRC_FEATURE_SH) {
        uint32_t k = cfg->sh_bands * cfg->sh_bands * cfg->sh_channels;
        l->off_sh = l->rec_size;
        l->rec_size += k * (uint32_t)sizeof(float);
        if (cfg->features & IRC_FEATURE_SH_GRADIENT) {
            l->off_shg = l->rec_size;
            l->rec_size += 3u * k * (uint32_t)sizeof(float);
        }
        l->samples *= 2u;
        geom = (size_t)l->samples * 6u * sizeof(float);
    }
    if (cfg->features & IRC_FEATURE_VISIBILITY)
        geom = (size_t)l->samples * (6u * sizeof(float) + 2u * sizeof(int32_t) +
                                     2u * sizeof(irc__cross)) +
               (size_t)cfg->strata_phi * (sizeof(int32_t) + sizeof(irc__cross));
    l->node_cap = irc__node_cap(capacity);
    l->slot_bytes = irc__up((size_t)l->samples * sizeof(irc__sample) +
                            (size_t)cfg->max_batch *
                                (sizeof(irc_ray) + sizeof(irc_hit)) +
                            (size_t)cfg->strata_theta * 2u * sizeof(double) + geom);
    l->lock = at;
    at += irc__up(cfg->port->lock_size ? cfg->port->lock_size : 1);
    l->scratch = at;
    at += (size_t)cfg->threads * l->slot_bytes;
    l->records = at;
    at += irc__up((size_t)capacity * l->rec_size);
    l->next = at;
    at += irc__up((size_t)capacity * sizeof(uint32_t));
    l->nodes = at;
    at += irc__up((size_t)l->node_cap * sizeof(irc__node));
    l->used = at;
    if (cfg->evict == IRC_EVICT_CLOCK)
        at += irc__up(((size_t)capacity + 63u) / 64u * sizeof(uint64_t));
    l->total = at;
}

int irc_footprint(const irc_config *cfg, uint32_t max_records, size_t *bytes)
{
    irc_config r;
    irc__layout l;
    int st;
    if (!bytes)
        return IRC_ERR_NULL;
    st = irc__config_resolve(cfg, &r);
    if (st < 0)
        return st;
    if (max_records == 0 || max_records > IRC_MAX_RECORDS)
        return IRC_ERR_CONFIG;
    /* Sizes are summed in size_t: refuse what would not fit it. */
    if ((double)max_records * 2048.0 + (double)r.threads * IRC_MAX_STRATA * 512.0 >
        (double)SIZE_MAX / 2.0)
        return IRC_ERR_CONFIG;
    irc__layout_of(&r, max_records, &l);
    *bytes = l.total + (IRC__ALIGN - 1);
    return IRC_OK;
}

int irc_init(const irc_config *cfg, uint32_t max_records, irc_cache **out)
{
    irc_config r;
    irc__layout l;
    unsigned char *base;
    irc_cache *c;
    size_t need;
    int st;
    if (!out)
        return IRC_ERR_NULL;
    st = irc_footprint(cfg, max_records, &need);
    if (st < 0)
        return st;
    if (!cfg->buffer)
        return IRC_ERR_NULL;
    if (cfg->buffer_size < need)
        return IRC_ERR_NOMEM;
    irc__config_resolve(cfg, &r);
    irc__layout_of(&r, max_records, &l);
    base = (unsigned char *)cfg->buffer;
    base += (IRC__ALIGN - ((uintptr_t)base & (IRC__ALIGN - 1))) & (IRC__ALIGN - 1);
    IRC_MEMSET(base, 0, l.total);
    c = (irc_cache *)(void *)base;
    c->capacity = max_records;
    c->cfg = r;
    c->port = r.port;
    c->rec_size = l.rec_size;
    c->off_t = l.off_t;
    c->off_r = l.off_r;
    c->off_sh = l.off_sh;
    c->off_shg = l.off_shg;
    c->strata = r.strata_theta * r.strata_phi;
    c->slot_samples = l.samples;
    c->keep_geom = (r.features & (IRC_FEATURE_VISIBILITY | IRC_FEATURE_SH)) != 0;
    if (r.features & IRC_FEATURE_SH) {
        c->sh_n = r.sh_bands * r.sh_bands;
        c->sh_ch = r.sh_channels;
    }
    c->node_cap = l.node_cap;
    c->slot_bytes = l.slot_bytes;
    c->total_bytes = l.total;
    c->lock = base + l.lock;
    c->scratch = base + l.scratch;
    c->records = base + l.records;
    c->next = (uint32_t *)(void *)(base + l.next);
    c->nodes = (irc__node *)(void *)(base + l.nodes);
    c->used = r.evict == IRC_EVICT_CLOCK ? (uint64_t *)(void *)(base + l.used) : NULL;
    irc__index_reset(c);
    if (c->port->lock_init(c->lock) < 0)
        return IRC_ERR_PORT;
    c->magic = IRC__MAGIC;
    *out = c;
    return IRC_OK;
}

int irc_fini(irc_cache *c)
{
    if (!c)
        return IRC_ERR_NULL;
    if (c->magic != IRC__MAGIC)
        return IRC_ERR_CONFIG;
    c->port->lock_destroy(c->lock);
    c->magic = 0;
    return IRC_OK;
}
