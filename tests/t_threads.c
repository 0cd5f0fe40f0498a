/* t_threads.c -- concurrent use (run under ThreadSanitizer by make test)
 * and determinism across thread counts. */
#define IRC_EXPERIMENTAL /* irc_cache_neighbours (irrcache.h) */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "block/cache.h" /* internals on purpose: stored bytes and index compared */
#include "index/index.h"
#include "index/layout.h"
#include "scenes.h"
#include "test.h"

#define NTHREADS 4

typedef struct worker {
    irc_cache *c;
    unsigned long long seed;
    int ops, errors;
} worker;

static void *stress_main(void *arg)
{
    worker *w = (worker *)arg;
    int i;
    for (i = 0; i < w->ops; i++) {
        float p[3], rgb[3], wt;
        const float n[3] = {0, 0, 1};
        uint32_t ids[16], cnt;
        irc_stats st;
        irc_record r;
        int s;
        p[0] = (float)(xrand(&w->seed) * 6 - 3);
        p[1] = (float)(xrand(&w->seed) * 6 - 3);
        p[2] = 0.0f;
        switch (i % 4) {
        case 0:
        case 1:
            s = irc_cache_lookup_or_compute(w->c, p, n, rgb, &wt, NULL);
            break;
        case 2:
            s = irc_cache_neighbours(w->c, p, n, ids, 16, &cnt);
            break;
        default:
            s = irc_cache_stats(w->c, &st);
            if (s == IRC_OK)
                s = irc_cache_record(w->c, (uint32_t)(xrand(&w->seed) * st.capacity), &r);
            break;
        }
        if (s < 0 || (i % 4 < 2 && !(rgb[0] > 0.0f)))
            w->errors++;
    }
    return NULL;
}

static void stress(const irc_port *port, const char *name)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    pthread_t th[NTHREADS];
    worker w[NTHREADS];
    irc_stats st;
    int i, errors = 0, ops = irc_t_quick ? 5000 : 20000;
    scene_init(&s);
    s.sky_a[0] = s.sky_a[1] = s.sky_a[2] = 1.0f;
    s.has_sphere = 1;
    s.centre[2] = 1.0;
    s.radius = 0.5;
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 8);
    cfg.port = port;
    cfg.threads = NTHREADS;
    cfg.evict = IRC_EVICT_CLOCK;
    cfg.max_radius = 0.5f; /* many small records: the pool fills and evicts */
    c = block_cache(&cfg, 300, 64);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (i = 0; i < NTHREADS; i++) {
        w[i].c = c;
        w[i].seed = (unsigned long long)i * 7777 + 1;
        w[i].ops = ops;
        w[i].errors = 0;
        pthread_create(&th[i], NULL, stress_main, &w[i]);
    }
    for (i = 0; i < NTHREADS; i++) {
        pthread_join(th[i], NULL);
        errors += w[i].errors;
    }
    irc_cache_stats(c, &st);
    printf("  %s: %llu lookups, %llu hits, %llu inserts, %llu evictions\n", name,
           (unsigned long long)st.lookups, (unsigned long long)st.hits,
           (unsigned long long)st.inserts, (unsigned long long)st.evictions);
    CHECK(errors == 0, "%d calls failed", errors);
    CHECK(st.records == 300 && st.evictions > 0, "the pool filled and evicted");
    CHECK(st.lookups == (uint64_t)NTHREADS * ops / 2, "lookups counted %llu",
          (unsigned long long)st.lookups);
    CHECK(st.inserts == st.computes && st.inserts == st.lookups - st.hits, "inserts %llu",
          (unsigned long long)st.inserts);
    CHECK(block_guard_ok(&cfg, 64), "guard");
    irc_fini(c);
    block_free(&cfg);
}

TEST(test_threads_stress)
{
    stress(&irc_port_posix, "posix");
    stress(&irc_port_c11, "c11");
}

/* Determinism: one thread, and two threads computing alternate queries and
 * inserting in list order, build byte-identical records. */
typedef struct det {
    irc_cache *c;
    const float (*pts)[3];
    int first, count;
    volatile int *turn; /* guarded by mu */
    pthread_mutex_t *mu;
    int errors;
} det;

static void *det_main(void *arg)
{
    det *d = (det *)arg;
    int i;
    for (i = d->first; i < d->count; i += 2) {
        const float n[3] = {0.0f, 0.0f, 1.0f};
        irc_record r;
        int mine = 0;
        if (irc_record_compute(d->c, d->pts[i], n, &r, NULL) != IRC_OK)
            d->errors++;
        while (!mine) {
            pthread_mutex_lock(d->mu);
            if (*d->turn == i) {
                if (irc_cache_insert(d->c, &r) != IRC_OK)
                    d->errors++;
                ++*d->turn;
                mine = 1;
            }
            pthread_mutex_unlock(d->mu);
        }
    }
    return NULL;
}

TEST(test_threads_determinism)
{
    enum { NPTS = 120 };
    static float pts[NPTS][3];
    irc_cache *cache[2];
    irc_config cfg[2];
    tscene s;
    unsigned long long st = 31;
    int i, k;
    scene_init(&s);
    s.sky_a[0] = 1.0f; s.sky_a[1] = 0.5f; s.sky_a[2] = 0.25f;
    s.has_sphere = 1;
    s.centre[2] = 1.5;
    s.radius = 0.7;
    for (i = 0; i < NPTS; i++) {
        pts[i][0] = (float)(xrand(&st) * 4 - 2);
        pts[i][1] = (float)(xrand(&st) * 4 - 2);
        pts[i][2] = 0.0f;
    }
    for (k = 0; k < 2; k++) {
        cfg[k] = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
        cfg[k].threads = 2;
        cfg[k].seed = 77;
        cache[k] = block_cache(&cfg[k], NPTS, 0);
        CHECK(cache[k] != NULL, "init");
        if (!cache[k]) return;
    }
    /* One thread: compute and insert in list order. */
    for (i = 0; i < NPTS; i++) {
        const float n[3] = {0.0f, 0.0f, 1.0f};
        irc_record r;
        CHECK(irc_record_compute(cache[0], pts[i], n, &r, NULL) == IRC_OK, "compute");
        CHECK(irc_cache_insert(cache[0], &r) == IRC_OK, "insert");
    }
    /* Two threads: each computes every other query, inserts in list order. */
    {
        pthread_t th[2];
        det d[2];
        pthread_mutex_t mu = PTHREAD_MUTEX_INITIALIZER;
        volatile int turn = 0;
        for (i = 0; i < 2; i++) {
            d[i].c = cache[1];
            d[i].pts = (const float(*)[3])pts;
            d[i].first = i;
            d[i].count = NPTS;
            d[i].turn = &turn;
            d[i].mu = &mu;
            d[i].errors = 0;
            pthread_create(&th[i], NULL, det_main, &d[i]);
        }
        for (i = 0; i < 2; i++)
            pthread_join(th[i], NULL);
        CHECK(d[0].errors + d[1].errors == 0, "errors");
    }
    for (i = 0; i < NPTS; i++) {
        irc_record a, b;
        CHECK(irc_cache_record(cache[0], (uint32_t)i, &a) == IRC_OK &&
              irc_cache_record(cache[1], (uint32_t)i, &b) == IRC_OK, "read");
        CHECK(memcmp(&a, &b, sizeof a) == 0, "record %d differs", i);
    }
    CHECK(memcmp(irc__rec_at(cache[0], 0), irc__rec_at(cache[1], 0),
                 (size_t)NPTS * cache[0]->rec_size) == 0,
          "stored records differ byte for byte");
    CHECK(memcmp(irc__nodes(cache[0]), irc__nodes(cache[1]),
                 (size_t)irc__st(cache[0])->nodes_used * sizeof(irc__node)) == 0 &&
          irc__st(cache[0])->nodes_used == irc__st(cache[1])->nodes_used, "index differs");
    for (k = 0; k < 2; k++)
        block_free(&cfg[k]);
}
