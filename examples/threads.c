/* threads.c -- a multi-threaded host: more worker threads than the cache
 * has scratch slots, each passing its own state as the per-call host
 * pointer, so the callback knows its thread without thread-local storage.
 * The scene is minimal.c's: a black unit ball at (0, 0, 2) over a floor
 * under a uniform sky of radiance 1, where E = pi (1 - 1/d^3) on the floor
 * below the ball's centre at distance d. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#include "irrcache.h"

#define WORKERS 4
#define SLOTS 2

typedef struct worker {
    irc_cache *cache;
    int id;
    unsigned long rays;   /* this thread's own counter: no atomics needed */
    int errors, lookups;
    double worst;         /* largest relative error against the closed form */
} worker;

static int trace(const irc_trace_args *a)
{
    worker *w = (worker *)a->host; /* the thread that asked */
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
                h->radiance[k] = 0.0f;
            }
        } else {
            h->status = IRC_RAY_ESCAPED;
            h->radiance[0] = h->radiance[1] = h->radiance[2] = 1.0f;
        }
    }
    w->rays += a->count;
    return 0;
}

/* Each worker shades every WORKERS-th point of a 64 x 64 grid. */
static void *work(void *arg)
{
    worker *w = (worker *)arg;
    int i;
    for (i = w->id; i < 64 * 64; i += WORKERS) {
        const float p[3] = {-1.0f + (i % 64) / 32.0f, -1.0f + (i / 64) / 32.0f, 0.0f};
        const float n[3] = {0.0f, 0.0f, 1.0f};
        double d2 = p[0] * p[0] + p[1] * p[1] + 4.0;
        double exact = 3.14159265358979 * (1.0 - 2.0 / (d2 * sqrt(d2))), err;
        float rgb[3];
        int st = irc_cache_lookup_or_compute(w->cache, p, n, rgb, NULL, w);
        if (st < 0) {
            w->errors++;
            continue;
        }
        w->lookups++;
        err = fabs(rgb[0] - exact) / exact;
        if (err > w->worst)
            w->worst = err;
    }
    return NULL;
}

int main(void)
{
    irc_config cfg = IRC_CONFIG_INIT;
    irc_cache *cache;
    irc_stats s;
    worker ws[WORKERS];
    pthread_t th[WORKERS];
    size_t bytes;
    int i, st, errors = 0;
    double worst = 0.0;
    cfg.trace = trace;
    cfg.max_batch = 32;
    cfg.threads = SLOTS;           /* fewer slots than workers: misses wait */
    cfg.max_radius = 0.5f;
    if ((st = irc_footprint(&cfg, 4096, &bytes)) < 0)
        return fprintf(stderr, "%s\n", irc_strerror(st)), 1;
    cfg.buffer = malloc(bytes);
    cfg.buffer_size = bytes;
    if ((st = irc_init(&cfg, 4096, &cache)) < 0)
        return fprintf(stderr, "%s\n", irc_strerror(st)), 1;
    for (i = 0; i < WORKERS; i++) {
        ws[i].cache = cache;
        ws[i].id = i;
        ws[i].rays = 0;
        ws[i].errors = ws[i].lookups = 0;
        ws[i].worst = 0.0;
        pthread_create(&th[i], NULL, work, &ws[i]);
    }
    for (i = 0; i < WORKERS; i++) {
        pthread_join(th[i], NULL);
        printf("worker %d: %d lookups, %lu rays of its own, worst error %.2f%%\n", i,
               ws[i].lookups, ws[i].rays, 100.0 * ws[i].worst);
        errors += ws[i].errors;
        if (ws[i].worst > worst)
            worst = ws[i].worst;
    }
    irc_cache_stats(cache, &s);
    printf("%llu records, %llu computes, %llu waited for a slot, %llu rays, %llu not stored, "
           "%d errors\n",
           (unsigned long long)s.records, (unsigned long long)s.computes,
           (unsigned long long)s.waits, (unsigned long long)s.rays,
           (unsigned long long)s.not_stored, errors);
    irc_fini(cache);
    free(cfg.buffer);
    /* The per-thread counters add up to the cache's, and every lookup got
     * a value close to the closed form. */
    {
        unsigned long sum = 0;
        for (i = 0; i < WORKERS; i++)
            sum += ws[i].rays;
        return errors == 0 && sum == s.rays && s.not_stored == 0 && worst < 0.05 ? 0 : 1;
    }
}
