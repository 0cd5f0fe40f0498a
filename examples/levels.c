/* levels.c -- two bounces with one cache a level, on several threads: the
 * callback of the first level's cache shades each hit with a lookup in the
 * second level's, passing the calling thread's host pointer on (irrcache.h,
 * "Several bounces").  Four threads, two scratch slots a cache: a thread
 * that holds a first-level slot waits only for a second-level one, whose
 * holders wait for nothing, so no deadlock.
 *
 * The scene is a furnace: the inside of the unit sphere, whose wall emits
 * radiance 1 and reflects half of what it receives.  The second level sees
 * emission only, E2 = pi; the first sees emission plus one bounce,
 * E1 = pi (1 + 0.5). */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"

#define WORKERS 4
#define PI 3.14159265358979f
#define ALBEDO 0.5f

typedef struct level {
    irc_cache *next; /* the next level's cache, NULL at the last */
} level;

static int trace(const irc_trace_args *a)
{
    const level *l = (const level *)a->context;
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        const float *o = a->rays[i].org, *d = a->rays[i].dir;
        irc_hit *h = &a->hits[i];
        float od = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
        float t = -2.0f * od > 1e-6f ? -2.0f * od : 1e-6f, p[3], n[3], e[3] = {0, 0, 0};
        int k;
        for (k = 0; k < 3; k++) {
            p[k] = o[k] + t * d[k];
            n[k] = -p[k]; /* the wall's inward normal */
        }
        /* Confirming rays need the distance only: no lookup for them. */
        if (l->next && !a->visibility_only &&
            irc_cache_lookup_or_compute(l->next, p, n, e, NULL, a->host) < 0)
            return -100; /* a host code: the record is dropped */
        h->status = IRC_RAY_HIT;
        h->dist = t;
        memcpy(h->normal, n, sizeof n);
        for (k = 0; k < 3; k++)
            h->radiance[k] = 1.0f + ALBEDO / PI * e[k];
    }
    return 0;
}

static irc_cache *make(level *l, void **block)
{
    irc_config cfg = IRC_CONFIG_INIT;
    irc_cache *c;
    size_t bytes;
    cfg.trace = trace;
    cfg.context = l;
    cfg.threads = 2; /* fewer slots than workers, at both levels */
    cfg.max_radius = 0.5f;
    cfg.strata_theta = 4; /* 64 rays a record: a furnace needs few */
    cfg.strata_phi = 16;
    if (irc_footprint(&cfg, 4096, &bytes) < 0 || !(*block = malloc(bytes)))
        return NULL;
    cfg.buffer = *block;
    cfg.buffer_size = bytes;
    return irc_init(&cfg, 4096, &c) == IRC_OK ? c : NULL;
}

typedef struct worker {
    irc_cache *top;
    int id, errors;
    double worst;
} worker;

static void *work(void *arg)
{
    worker *w = (worker *)arg;
    int i;
    for (i = w->id; i < 1000; i += WORKERS) { /* points spread over the wall */
        float z = -0.99f + 1.98f * (float)i / 1000.0f, r = sqrtf(1.0f - z * z);
        float p[3] = {r * cosf(2.4f * (float)i), r * sinf(2.4f * (float)i), z};
        float n[3] = {-p[0], -p[1], -p[2]}, rgb[3];
        double err;
        if (irc_cache_lookup_or_compute(w->top, p, n, rgb, NULL, w) < 0) {
            w->errors++;
            continue;
        }
        err = fabs(rgb[0] - PI * (1.0f + ALBEDO)) / (PI * (1.0f + ALBEDO));
        if (err > w->worst)
            w->worst = err;
    }
    return NULL;
}

int main(void)
{
    level l1, l2 = {NULL};
    void *b1 = NULL, *b2 = NULL;
    irc_stats s1, s2;
    worker ws[WORKERS];
    pthread_t th[WORKERS];
    int i, errors = 0;
    double worst = 0.0;
    if (!(l1.next = make(&l2, &b2))) /* the second level first: the first calls it */
        return fprintf(stderr, "level 2: no cache\n"), 1;
    irc_cache *top = make(&l1, &b1);
    if (!top)
        return fprintf(stderr, "level 1: no cache\n"), 1;
    for (i = 0; i < WORKERS; i++) {
        ws[i].top = top;
        ws[i].id = i;
        ws[i].errors = 0;
        ws[i].worst = 0.0;
        pthread_create(&th[i], NULL, work, &ws[i]);
    }
    for (i = 0; i < WORKERS; i++) {
        pthread_join(th[i], NULL);
        errors += ws[i].errors;
        worst = ws[i].worst > worst ? ws[i].worst : worst;
    }
    irc_cache_stats(top, &s1);
    irc_cache_stats(l1.next, &s2);
    printf("level 1: %llu records, level 2: %llu records (%llu not stored); %d errors, worst "
           "error %.3f%% (E1 = 1.5 pi)\n",
           (unsigned long long)s1.records, (unsigned long long)s2.records,
           (unsigned long long)(s1.not_stored + s2.not_stored), errors, 100.0 * worst);
    irc_fini(top);
    irc_fini(l1.next);
    free(b1);
    free(b2);
    return errors == 0 && worst < 0.01 && s1.not_stored + s2.not_stored == 0 ? 0 : 1;
}
