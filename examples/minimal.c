/* minimal.c -- the smallest host: a black ball over an open floor under a
 * uniform sky, one trace callback, one cache, lookups along a line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "irrcache.h"

/* Written for 0.5: another minor changes the config and what it costs. */
#if IRC_VERSION_MAJOR != 0 || IRC_VERSION_MINOR != 5
#error "written for irrcache 0.5 (CHANGES.md, Upgrading)"
#endif

/* Cast each ray against a black unit ball centred at (0, 0, 2). */
static int trace(const irc_trace_args *a)
{
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        const float *o = a->rays[i].org, *d = a->rays[i].dir;
        irc_hit *h = &a->hits[i];
        float oc[3] = {o[0], o[1], o[2] - 2.0f};
        float b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
        float c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - 1.0f;
        float disc = b * b - c, t = -b - sqrtf(disc > 0.0f ? disc : 0.0f);
        int k;
        if (disc > 0.0f && t > 0.0f) {
            h->status = IRC_RAY_HIT;
            h->dist = t;
            for (k = 0; k < 3; k++) {
                h->normal[k] = oc[k] + t * d[k];
                h->radiance[k] = 0.0f;           /* black */
            }
        } else {
            h->status = IRC_RAY_ESCAPED;
            h->radiance[0] = h->radiance[1] = h->radiance[2] = 1.0f; /* sky */
        }
    }
    return 0;
}

int main(void)
{
    irc_config cfg = IRC_CONFIG_INIT;
    irc_cache *cache;
    size_t bytes;
    int i, st;
    /* Linked against the shared library: the one loaded must be the ABI
     * this file was compiled for (major.minor while the major is 0). */
    if (irc_version_number() / 100 != IRC_VERSION_NUMBER / 100)
        return fprintf(stderr, "irrcache %s loaded, %s expected\n", irc_version_string(),
                       IRC_VERSION_STRING), 1;
    cfg.trace = trace;
    cfg.max_batch = 64;
    cfg.max_radius = 4.0f;  /* rays that escape count as infinitely far */
    if ((st = irc_footprint(&cfg, 1000, &bytes)) < 0)
        return fprintf(stderr, "%s\n", irc_strerror(st)), 1;
    cfg.buffer = malloc(bytes);              /* the host's memory, any kind */
    cfg.buffer_size = bytes;
    if ((st = irc_init(&cfg, 1000, &cache)) < 0)
        return fprintf(stderr, "%s\n", irc_strerror(st)), 1;
    for (i = 0; i <= 8; i++) {
        const float p[3] = {0.25f * i, 0.0f, 0.0f}, n[3] = {0.0f, 0.0f, 1.0f};
        float rgb[3], w;
        double d2 = p[0] * p[0] + 4.0, exact = 3.14159265 * (1.0 - 2.0 / (d2 * sqrt(d2)));
        st = irc_cache_lookup_or_compute(cache, p, n, rgb, &w, NULL);
        if (st < 0)
            return fprintf(stderr, "%s\n", irc_strerror(st)), 1;
        if (st == IRC_NOT_STORED) /* valid, but the pool is full: size it up */
            fprintf(stderr, "pool full\n");
        printf("x = %.2f  E = %.4f  exact %.4f  %s\n", p[0], rgb[0], exact,
               w > 0.0f ? "(interpolated)" : "(new record)");
    }
    irc_fini(cache);
    free(cfg.buffer);
    return 0;
}
