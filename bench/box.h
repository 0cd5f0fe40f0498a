/*
 * box.h -- the lookup workload bench/lookups.c and bench/anchor.c share:
 * trans+rot records on the six faces of a unit box, radii around those
 * that let a query find a few of them at a = 0.2, and queries in scanline
 * order (runs of 256 neighbours) or at random.
 */
#ifndef BENCH_BOX_H
#define BENCH_BOX_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"

static inline void box_point(int f, double u, double v, float p[3], float n[3])
{
    int axis = f % 3, side = f / 3, a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    p[axis] = (float)side;
    p[a1] = (float)u;
    p[a2] = (float)v;
    n[0] = n[1] = n[2] = 0.0f;
    n[axis] = side ? 1.0f : -1.0f;
}

/* The next of `count` records, drawn from *rng. */
static inline void box_record(unsigned long long *rng, uint32_t count, irc_record *r)
{
    const double reach = sqrt(36.0 / (3.14159265 * count));
    memset(r, 0, sizeof *r);
    box_point((int)(bench_xorshift(rng) * 6), bench_xorshift(rng), bench_xorshift(rng), r->p, r->n);
    r->e[0] = r->e[1] = r->e[2] = (float)(0.5 + bench_xorshift(rng));
    r->grad_t[0][0] = 0.1f;
    r->radius = (float)(reach / 0.2 * exp((bench_xorshift(rng) - 0.5) * 1.4));
}

static int box_no_trace(const irc_trace_args *a)
{
    (void)a;
    return -1;
}

/* A trans+rot cache for `count` records at a = 0.2, single-threaded, in
 * a block from malloc (cfg->buffer, the caller's to free); NULL when
 * count is 0 or too large. */
static inline irc_cache *box_cache(uint32_t count, irc_config *cfg)
{
    irc_cache *c;
    size_t bytes;
    memset(cfg, 0, sizeof *cfg);
    cfg->version = IRC_CONFIG_VERSION;
    cfg->trace = box_no_trace;
    cfg->accuracy = 0.2f;
    cfg->features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
    /* Ward's lookups within a R, the work pbrt-v2's anchor does
     * (bench/anchor.c); BENCH_BLEND=2 measures the default's blended ones */
    cfg->irr.blend = getenv("BENCH_BLEND") ? (float)atof(getenv("BENCH_BLEND")) : 1.0f;
    cfg->port = &irc_port_none;
    if (count == 0 || irc_footprint(cfg, count, &bytes) != IRC_OK ||
        !(cfg->buffer = malloc(bytes)))
        return NULL;
    cfg->buffer_size = bytes;
    if (irc_init(cfg, count, &c) != IRC_OK) {
        free(cfg->buffer);
        return NULL;
    }
    return c;
}

/* The i-th query (random order draws from *rng). */
static inline void box_query(int scanline, uint32_t i, unsigned long long *rng, float p[3],
                             float n[3])
{
    if (scanline)
        box_point((int)(i >> 8) % 6, (double)(i & 255) / 4096.0 + 0.3,
                  (double)((i >> 8) % 97) / 100.0, p, n);
    else
        box_point((int)(bench_xorshift(rng) * 6), bench_xorshift(rng), bench_xorshift(rng), p, n);
}

#endif
