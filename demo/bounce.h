/*
 * bounce.h -- the host side of the cache, level by level: the rays the
 * cache's callback casts and what their hits return (direct light, and
 * with several bounces the light of the bounces beyond, from the next
 * level's cache or from a path), and those levels' caches.  Internal to
 * the demo tracer (render.c and bounce.c).
 */
#ifndef DEMO_BOUNCE_H
#define DEMO_BOUNCE_H

#include "render.h"

/* A render thread's counters; its pointer is the host pointer of every
 * cache call the thread makes, so callbacks count into it too. */
typedef struct tstate {
    double trace_s, cache_s;  /* exclusive: a cache call's time inside a
                                 ray's shading, or a callback's inside a
                                 cache call, is counted once, where spent */
    double lookup_s, gather_s, pass_s; /* cache_s split: the camera hits'
                                 calls that sampled no hemisphere (lookups,
                                 with probes and confirming rays), those
                                 that did (records and detail estimates,
                                 inserts), and pass ends and begins */
    uint64_t rays, dropped;
    uint64_t gathers;         /* callbacks of hemisphere rays (not probes
                                 nor confirming rays): a record or detail
                                 estimate being sampled */
    double mark;              /* when the thread entered region */
    int region;               /* CLOCK_* */
    int final;                /* render.c: the final sweep's lookups */
    int detail;               /* render.c: the last _px call answered per
                                 pixel (a detail estimate) */
    const float *under[MAX_BOUNCES + 1]; /* level k's hit while its E is
                                 gathered: the geometric normal below which
                                 its rays fail (cast), or NULL */
} tstate;

enum { CLOCK_HOST, CLOCK_TRACE, CLOCK_CACHE };

/* Charges the time since the thread's last switch to the region it was
 * in and enters `region`; returns the region left, to enter again after. */
int clock_enter(tstate *ts, int region);

/* Casts count rays from the hits of bounce `level` (1: the camera's hit)
 * and writes what comes back along them: shade 0, the distances only (the
 * cache's confirming rays).  While ts->under[level] is set, a ray that
 * leaves below that geometric normal is not cast but IRC_RAY_FAILED: the
 * E sampled around a shading normal is that of the directions above the
 * surface (the library and reference_e leave failed rays out), not the
 * surface itself seen from 0 away, which made every such point a
 * per-pixel estimate and its records tiny. */
void cast(const renderer *r, const irc_ray *rays, irc_hit *hits, uint32_t count, int shade,
          int level, tstate *ts);

/* The callback of every level's cache (cfg.context: its level_ctx). */
int host_trace(const irc_trace_args *a);

/* The caches of levels 2 .. bounces (GATHER_CACHE): base's config with
 * the first level's accuracy x level_scale^(k-1) and strata /
 * level_strata^(k-1) (as r->cache resolved them), radii in
 * [level_min_radius x span, span], filled freely.  0, or -1 with err
 * set. */
int levels_init(renderer *r, const irc_config *base, float span, char *err, size_t n);
void levels_free(renderer *r);

#endif
