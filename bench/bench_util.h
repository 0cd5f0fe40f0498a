/*
 * bench_util.h -- what the benchmark drivers share: a monotonic clock, a
 * xorshift generator (bench/lookups.c's checksums depend on its sequence),
 * and the host whose rays cost almost nothing, so that a record's time is
 * the library's own.
 */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <math.h>
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

/* A cosine-distributed direction about the unit normal n from (u, v) in
 * [0, 1)^2, in Frisvad's frame (made safe at n.z = -1): the path tracers'
 * bounces (bench/host_scene.h, bench/pathtracer.c). */
static inline void bench_cosine_dir(const float n[3], float u, float v, float d[3])
{
    const float s = sqrtf(u), phi = 6.28318530717959f * v;
    float t[3], b[3];
    int k;
    if (n[2] < -0.9999f) {
        t[0] = 0.0f, t[1] = -1.0f, t[2] = 0.0f;
        b[0] = -1.0f, b[1] = 0.0f, b[2] = 0.0f;
    } else {
        const float a = 1.0f / (1.0f + n[2]), c = -n[0] * n[1] * a;
        t[0] = 1.0f - n[0] * n[0] * a, t[1] = c, t[2] = -n[0];
        b[0] = c, b[1] = 1.0f - n[1] * n[1] * a, b[2] = -n[1];
    }
    for (k = 0; k < 3; k++)
        d[k] = s * cosf(phi) * t[k] + s * sinf(phi) * b[k] + sqrtf(1.0f - u) * n[k];
}

#endif
