/* t_levels.c -- several bounces: one cache per level, each level's
 * callback looking up the next (irrcache.h, "Several bounces"), against
 * the closed form inside a uniformly emitting sphere; and the failure
 * mode of calling back into the cache that is computing. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "irrcache.h"
#include "test.h"

#define PI_F 3.14159265358979f
#define LEVELS 3

/* The inside of the unit sphere: every surface emits le and reflects
 * diffusely with albedo rho.  Radiance leaving a hit is le plus rho / pi
 * times the irradiance there, which the next level's cache gives (none:
 * the last level sees emission only).  So level k of L sees
 * E_k = pi le (1 + rho + ... + rho^(L-k)). */
typedef struct level {
    irc_cache *self, *next;
    float le, rho;
    int nest;       /* call back into self (the failure mode) */
    int nest_depth; /* nested calls open now: bounded, so that a library
                       that let them through cannot recurse without end */
    int deepest;    /* and the most that were ever open */
    int nest_total; /* nested calls made (bounded too) */
    int nested_status;
    int failures;   /* next-level calls that failed */
} level;

static void hit_sphere(const float o[3], const float d[3], float *t, float h[3])
{
    float od = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
    int k;
    *t = -2.0f * od > 1e-6f ? -2.0f * od : 1e-6f;
    for (k = 0; k < 3; k++)
        h[k] = o[k] + *t * d[k];
}

static int sphere_trace(const irc_trace_args *a)
{
    level *l = (level *)a->context;
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        float t, h[3], n[3], e[3] = {0, 0, 0}, len;
        int k, st;
        hit_sphere(a->rays[i].org, a->rays[i].dir, &t, h);
        len = sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        for (k = 0; k < 3; k++)
            n[k] = -h[k] / len;
        if (a->visibility_only) {
            /* confirming rays: distance only, no lookup */
        } else if (l->nest && i == 0 && l->nest_depth < 8 && l->nest_total++ < 32) {
            if (++l->nest_depth > l->deepest)
                l->deepest = l->nest_depth;
            l->nested_status = irc_cache_lookup_or_compute(l->self, h, n, e, NULL, a->host);
            l->nest_depth--;
        } else if (l->next) {
            st = irc_cache_lookup_or_compute(l->next, h, n, e, NULL, a->host);
            if (st < 0)
                __atomic_fetch_add(&l->failures, 1, __ATOMIC_RELAXED);
        }
        a->hits[i].status = IRC_RAY_HIT;
        a->hits[i].dist = t;
        memcpy(a->hits[i].normal, n, sizeof n);
        for (k = 0; k < 3; k++)
            a->hits[i].radiance[k] = l->le + l->rho / PI_F * e[k];
    }
    return 0;
}

static irc_cache *make(level *l, const irc_port *port, uint32_t slots, int no_wait, void **block)
{
    irc_config cfg;
    irc_cache *c = NULL;
    size_t bytes;
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = sphere_trace;
    cfg.context = l;
    cfg.port = port;
    cfg.threads = slots;
    cfg.no_wait = (uint32_t)no_wait;
    cfg.strata_theta = 4;
    cfg.strata_phi = 16;
    cfg.max_radius = 0.3f;
    if (irc_footprint(&cfg, 4096, &bytes) != IRC_OK || !(*block = malloc(bytes)))
        return NULL;
    cfg.buffer = *block;
    cfg.buffer_size = bytes;
    if (irc_init(&cfg, 4096, &c) != IRC_OK) {
        free(*block);
        *block = NULL;
        return NULL;
    }
    l->self = c;
    return c;
}

static uint32_t records(irc_cache *c)
{
    irc_stats s;
    return irc_cache_stats(c, &s) == IRC_OK ? s.records : 0xffffffffu;
}

/* Levels chained through their callbacks match the closed form at every
 * level (a wrong level's cache, or a nested call refused, would not). */
TEST(test_levels_closed_form)
{
    level l[LEVELS];
    void *blocks[LEVELS];
    int k, q;
    memset(l, 0, sizeof l);
    for (k = LEVELS - 1; k >= 0; k--) {
        l[k].le = 1.0f;
        l[k].rho = 0.5f;
        l[k].next = k + 1 < LEVELS ? l[k + 1].self : NULL;
        CHECK(make(&l[k], &irc_port_posix, 1, 0, &blocks[k]) != NULL, "level %d", k);
    }
    for (q = 0; q < 40; q++) {
        /* points all over the sphere, each level's closed form */
        float th = 0.37f * (float)q, z = -0.95f + 0.047f * (float)q, s = sqrtf(1.0f - z * z);
        float p[3], n[3], e[3];
        p[0] = s * cosf(th); p[1] = s * sinf(th); p[2] = z;
        for (k = 0; k < 3; k++)
            n[k] = -p[k];
        for (k = 0; k < LEVELS; k++) {
            float want = PI_F * (k == 0 ? 1.75f : k == 1 ? 1.5f : 1.0f);
            int st = irc_cache_lookup_or_compute(l[k].self, p, n, e, NULL, NULL);
            CHECK(st >= 0 && fabsf(e[0] - want) < 2e-3f * want && e[0] == e[2],
                  "level %d at %d: status %d, E %g, closed form %g", k, q, st, e[0], want);
        }
    }
    for (k = 0; k < LEVELS; k++) {
        CHECK(l[k].failures == 0, "level %d: %d next-level calls failed", k, l[k].failures);
        irc_fini(l[k].self);
        free(blocks[k]);
    }
}

/* A callback that calls back into its own cache gets IRC_ERR_NESTED at
 * once, whatever the port and however many slots are free: it neither
 * waits for its own slot (one slot) nor recurses into the free ones. */
TEST(test_levels_nested_refused)
{
    const irc_port *ports[] = {&irc_port_posix, &irc_port_c11, &irc_port_none};
    const uint32_t slots[] = {1, 4};
    int pi, si;
    for (pi = 0; pi < 3; pi++)
        for (si = 0; si < 2; si++) {
            level l;
            void *block = NULL;
            float p[3] = {0, 0, -1}, n[3] = {0, 0, 1}, e[3];
            int st;
            memset(&l, 0, sizeof l);
            l.le = 1.0f;
            l.nest = 1;
            l.nested_status = 12345;
            /* no_wait: a library that did not see the nesting answers BUSY
             * with one slot rather than hanging this test */
            if (!make(&l, ports[pi], slots[si], 1, &block)) {
                CHECK(0, "%s: init", ports[pi]->name);
                continue;
            }
            st = irc_cache_lookup_or_compute(l.self, p, n, e, NULL, NULL);
            CHECK(st == IRC_OK && fabsf(e[0] - PI_F) < 1e-3f, "%s/%u: outer %d, E %g",
                  ports[pi]->name, slots[si], st, e[0]);
            CHECK(l.nested_status == IRC_ERR_NESTED && l.deepest == 1,
                  "%s/%u slots: nested call %d (%s), depth %d", ports[pi]->name, slots[si],
                  l.nested_status, irc_strerror(l.nested_status), l.deepest);
            CHECK(records(l.self) == 1, "%s/%u: %u records", ports[pi]->name, slots[si],
                  records(l.self));
            irc_fini(l.self);
            free(block);
        }
}

/* A cycle through two caches (A's callback -> B, B's -> A) is nesting
 * too: B's callback gets IRC_ERR_NESTED from A. */
TEST(test_levels_cycle_refused)
{
    level a, b;
    void *ba = NULL, *bb = NULL;
    float p[3] = {0, 0, -1}, n[3] = {0, 0, 1}, e[3];
    int st;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    a.le = b.le = 1.0f;
    a.rho = b.rho = 0.5f;
    CHECK(make(&a, &irc_port_posix, 2, 1, &ba) && make(&b, &irc_port_posix, 2, 1, &bb), "init");
    a.next = b.self;
    b.next = a.self;
    st = irc_cache_lookup_or_compute(a.self, p, n, e, NULL, NULL);
    /* B's rays all fail into A; B's record then sees le alone, A's sees
     * le + rho / pi * (pi le) */
    CHECK(st == IRC_OK && fabsf(e[0] - 1.5f * PI_F) < 2e-3f * PI_F, "A: %d, E %g", st, e[0]);
    CHECK(b.failures > 0 && a.failures == 0, "B's calls into A refused: %d", b.failures);
    CHECK(records(a.self) == 1, "A keeps its one record: %u", records(a.self));
    irc_fini(a.self);
    irc_fini(b.self);
    free(ba);
    free(bb);
}

#define LTHREADS 4
typedef struct lworker {
    irc_cache *top;
    uint32_t seed;
    int bad;
    volatile int done;
} lworker;

static float unit(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)(*s >> 8) / 16777216.0f;
}

/* A random point on the sphere (below its top cap) and the inward
 * normal there. */
static void sphere_point(uint32_t *seed, float p[3], float n[3])
{
    float z = -1.0f + 1.9f * unit(seed);
    float th = 6.283f * unit(seed), s = sqrtf(1.0f - z * z);
    int k;
    p[0] = s * cosf(th); p[1] = s * sinf(th); p[2] = z;
    for (k = 0; k < 3; k++)
        n[k] = -p[k];
}

static void *level_worker(void *arg)
{
    lworker *w = (lworker *)arg;
    int i;
    for (i = 0; i < (irc_t_quick ? 40 : 200); i++) {
        float p[3], n[3], e[3];
        sphere_point(&w->seed, p, n);
        if (irc_cache_lookup_or_compute(w->top, p, n, e, NULL, NULL) < 0 ||
            fabsf(e[0] - 1.5f * PI_F) > 3e-3f * PI_F)
            w->bad++;
    }
    __atomic_store_n(&w->done, 1, __ATOMIC_RELEASE);
    return NULL;
}

/* Waits up to a minute for LTHREADS workers' done flags (at stride bytes
 * apart from the first); a hang aborts with what, so that it fails the
 * test instead of hanging make test. */
static void watchdog(const volatile int *first, size_t stride, const char *what)
{
    int k, waited = 0, all = 0;
    while (!all && waited < 600) {
        all = 1;
        for (k = 0; k < LTHREADS; k++)
            all &= __atomic_load_n((const volatile int *)(const void *)((const char *)first +
                                                                         (size_t)k * stride),
                                   __ATOMIC_ACQUIRE);
        if (!all) {
            struct timespec ts = {0, 100000000L};
            nanosleep(&ts, NULL);
            waited++;
        }
    }
    if (!all) {
        CHECK(0, "%s: not done after a minute", what);
        fflush(stdout);
        abort();
    }
}

/* More host threads than slots at both levels (4 threads, one slot a
 * cache): a thread holding level 1's slot waits for level 2's, whose
 * holders wait for nothing, so all finish.  A hang fails the test after
 * a minute instead of hanging make test. */
TEST(test_levels_threads)
{
    level l[2];
    void *blocks[2] = {NULL, NULL};
    lworker w[LTHREADS];
    pthread_t th[LTHREADS];
    int k;
    memset(l, 0, sizeof l);
    memset(w, 0, sizeof w);
    for (k = 1; k >= 0; k--) {
        l[k].le = 1.0f;
        l[k].rho = 0.5f;
        l[k].next = k == 0 ? l[1].self : NULL;
        CHECK(make(&l[k], &irc_port_posix, 1, 0, &blocks[k]) != NULL, "level %d", k);
    }
    for (k = 0; k < LTHREADS; k++) {
        w[k].top = l[0].self;
        w[k].seed = 17u + (uint32_t)k;
        CHECK(pthread_create(&th[k], NULL, level_worker, &w[k]) == 0, "thread %d", k);
    }
    watchdog(&w[0].done, sizeof w[0], "two levels, 4 threads, 1 slot each");
    for (k = 0; k < LTHREADS; k++) {
        pthread_join(th[k], NULL);
        CHECK(w[k].bad == 0, "thread %d: %d lookups wrong or failed", k, w[k].bad);
    }
    CHECK(l[0].failures == 0 && l[1].failures == 0, "next-level failures %d", l[0].failures);
    for (k = 0; k < 2; k++) {
        irc_fini(l[k].self);
        free(blocks[k]);
    }
}

/* A cycle of two caches (A's callback -> B, B's -> A) driven by several
 * host threads at once, each starting at A or B.  A thread's call back
 * into a cache it is computing in gets IRC_ERR_NESTED; two threads can
 * each hold the last slot of one cache and wait for the other's, so the
 * header asks a cycle for as many slots a cache as host threads call it:
 * then a waiting thread always finds a slot no thread of the cycle holds,
 * and all finish (a watchdog aborts after a minute), every answer within
 * half of one bounce (pi le) and one and a half times all of them (pi le /
 * (1 - rho)): records lie between the two, and their gradients, fitted to
 * neighbours filled in racing orders, extrapolate up to a few tenths of E
 * beyond (3.02 against pi was seen); with one slot
 * and no_wait the calls that would wait return IRC_ERR_BUSY instead, and
 * all finish too. */
typedef struct cworker {
    irc_cache *start;
    uint32_t seed;
    int bad, busy, bad_st;
    float bad_e;
    volatile int done;
} cworker;

static void *cycle_worker(void *arg)
{
    cworker *w = (cworker *)arg;
    int i;
    for (i = 0; i < (irc_t_quick ? 30 : 120); i++) {
        float p[3], n[3], e[3];
        int st;
        sphere_point(&w->seed, p, n);
        st = irc_cache_lookup_or_compute(w->start, p, n, e, NULL, NULL);
        if (st == IRC_ERR_BUSY)
            w->busy++;
        else if (st < 0 || !(e[0] >= 0.5f * PI_F && e[0] <= 3.0f * PI_F)) {
            w->bad++;
            w->bad_st = st;
            w->bad_e = e[0];
        }
    }
    __atomic_store_n(&w->done, 1, __ATOMIC_RELEASE);
    return NULL;
}

TEST(test_levels_cycle_threads)
{
    int round;
    for (round = 0; round < 2; round++) {
        const uint32_t slots = round == 0 ? LTHREADS : 1;
        const int no_wait = round == 1;
        level a, b;
        void *ba = NULL, *bb = NULL;
        cworker w[LTHREADS];
        pthread_t th[LTHREADS];
        int k, busy = 0;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        memset(w, 0, sizeof w);
        a.le = b.le = 1.0f;
        a.rho = b.rho = 0.5f;
        if (!make(&a, &irc_port_posix, slots, no_wait, &ba) ||
            !make(&b, &irc_port_posix, slots, no_wait, &bb)) {
            CHECK(0, "init");
            return;
        }
        a.next = b.self;
        b.next = a.self;
        for (k = 0; k < LTHREADS; k++) {
            w[k].start = k & 1 ? b.self : a.self;
            w[k].seed = 101u + (uint32_t)k;
            CHECK(pthread_create(&th[k], NULL, cycle_worker, &w[k]) == 0, "thread %d", k);
        }
        watchdog(&w[0].done, sizeof w[0],
                 slots == 1 ? "a cycle of two caches, 4 threads, 1 slot each, no_wait"
                            : "a cycle of two caches, 4 threads, 4 slots each");
        for (k = 0; k < LTHREADS; k++) {
            pthread_join(th[k], NULL);
            busy += w[k].busy;
            CHECK(w[k].bad == 0, "%u slots, thread %d: %d lookups wrong or failed (the last: %d, E %g)",
                  (unsigned)slots, k, w[k].bad, w[k].bad_st, (double)w[k].bad_e);
        }
        CHECK(no_wait || busy == 0, "%d busy with slots to spare", busy);
        CHECK(a.failures + b.failures > 0, "no call back into a computing cache was refused");
        printf("  %u slots a cache%s: %d top-level calls busy, %d calls inside callbacks "
               "refused\n",
               (unsigned)slots, no_wait ? " (no_wait)" : "", busy, a.failures + b.failures);
        irc_fini(a.self);
        irc_fini(b.self);
        free(ba);
        free(bb);
    }
}
