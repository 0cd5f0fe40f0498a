/*
 * bench_util.h -- what the benchmark drivers share: a monotonic clock, a
 * xorshift generator (bench/lookups.c's checksums depend on its sequence),
 * and the host whose rays cost almost nothing, so that a record's time is
 * the library's own.
 */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <time.h>

#include "irrcache.h"

static inline double bench_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static inline double bench_xorshift(unsigned long long *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

/* A sky that brightens toward +z, every tenth ray hitting a wall at
 * distance 1. */
static inline int bench_cheap_trace(const irc_trace_args *a)
{
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        irc_hit *h = &a->hits[i];
        float l = 1.0f + a->rays[i].dir[2];
        if (i % 10 == 0) {
            h->status = IRC_RAY_HIT;
            h->dist = 1.0f;
            h->normal[0] = 1.0f;
            h->normal[1] = h->normal[2] = 0.0f;
            l *= 0.25f;
        } else {
            h->status = IRC_RAY_ESCAPED;
        }
        h->radiance[0] = h->radiance[1] = h->radiance[2] = l;
    }
    return 0;
}

#endif
