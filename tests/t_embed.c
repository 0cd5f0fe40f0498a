/* t_embed.c -- what an embedding host relies on, through the public header
 * only: a block copied to another address works after irc_attach, the
 * per-call host pointer and the record's position and normal reach the
 * callback, a miss always gets its value when host threads outnumber
 * scratch slots, and a full pool is counted. */
#define IRC_EXPERIMENTAL /* irc_occlusion_compute (irrcache.h) */
#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "irrcache.h"
#include "scenes.h"
#include "test.h"

static tscene sphere;

/* Fills a cache on a grid of the sphere-over-plane floor. */
static void fill_floor(irc_cache *c, int n, int sh)
{
    int i, j;
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            float p[3], nn[3] = {0, 0, 1}, rgb[3];
            irc_sh s;
            p[0] = (float)(-3.0 + 6.0 * i / (n - 1));
            p[1] = (float)(-3.0 + 6.0 * j / (n - 1));
            p[2] = 0.0f;
            if (sh)
                irc_sh_lookup_or_compute(c, p, (i + j) % 3 ? nn : NULL, &s, NULL, NULL);
            else
                irc_cache_lookup_or_compute(c, p, nn, rgb, NULL, NULL);
        }
}

/* Every lookup on a finer grid, bit for bit, and the stats. */
static int same_answers(irc_cache *a, irc_cache *b, int sh, int *looked)
{
    int i, j, diff = 0;
    irc_stats sa, sb;
    *looked = 0;
    for (i = 0; i < 40; i++)
        for (j = 0; j < 40; j++) {
            float p[3], nn[3] = {0.1f, 0.0f, 1.0f}, wa = -1, wb = -2;
            int st1, st2;
            p[0] = (float)(-3.2 + 6.4 * i / 39.0);
            p[1] = (float)(-3.2 + 6.4 * j / 39.0);
            p[2] = 0.01f;
            if (sh) {
                irc_sh ra, rb;
                const float *np = (i + j) % 2 ? nn : NULL;
                st1 = irc_sh_lookup(a, p, np, &ra, &wa);
                st2 = irc_sh_lookup(b, p, np, &rb, &wb);
                diff += st1 != st2 || wa != wb || memcmp(ra.c, rb.c, sizeof ra.c) != 0;
            } else {
                float ga[3], gb[3];
                st1 = irc_cache_lookup(a, p, nn, ga, &wa);
                st2 = irc_cache_lookup(b, p, nn, gb, &wb);
                diff += st1 != st2 || wa != wb || memcmp(ga, gb, sizeof ga) != 0;
            }
            *looked += st1 == IRC_OK;
        }
    irc_cache_stats(a, &sa);
    irc_cache_stats(b, &sb);
    diff += sa.records != sb.records || sa.index_nodes != sb.index_nodes;
    return diff;
}

static void relocate(uint32_t features, int sh)
{
    irc_config cfg = scene_config(&sphere, features, 8, 32), cc;
    irc_cache *c, *copy = NULL;
    static const size_t shifts[] = {1, 8, 13, 64, 4096 + 40};
    size_t k;
    cfg.max_radius = 0.4f;
    cfg.accuracy = 1.0f;
    c = block_cache(&cfg, 2000, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    fill_floor(c, 16, sh);
    for (k = 0; k < sizeof shifts / sizeof shifts[0]; k++) {
        unsigned char *mem = malloc(cfg.buffer_size + 8192);
        int looked = 0, st;
        memcpy(mem + shifts[k], cfg.buffer, cfg.buffer_size);
        cc = cfg;
        cc.buffer = mem + shifts[k];
        st = irc_attach(&cc, &copy);
        CHECK(st == IRC_OK, "attach at +%zu: %d", shifts[k], st);
        if (st == IRC_OK) {
            irc_stats s;
            float p[3] = {7.0f, 7.0f, 0.0f}, nn[3] = {0, 0, 1}, rgb[3];
            int d = same_answers(c, copy, sh, &looked);
            CHECK(d == 0, "+%zu: %d of 1600 lookups differ", shifts[k], d);
            CHECK(looked > 400, "only %d lookups answered: the test proves little", looked);
            /* The copy goes on as a cache of its own. */
            if (!sh) {
                irc_stats before;
                irc_cache_stats(c, &before);
                CHECK(irc_cache_lookup_or_compute(copy, p, nn, rgb, NULL, NULL) == IRC_OK, "compute");
                irc_cache_stats(copy, &s);
                CHECK(s.records == before.records + 1, "records %llu", (unsigned long long)s.records);
            }
            irc_fini(copy);
        }
        free(mem);
    }
    block_free(&cfg);
}

/* A filled block memcpy'd to addresses of every alignment class answers
 * every lookup as the original does, after irc_attach. */
TEST(test_relocate)
{
    irc_config cfg;
    unsigned char junk[4096];
    irc_cache *c;
    scene_sphere_plane(&sphere);
    relocate(IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 0);
    relocate(IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT, 1);
    /* What attach refuses, leaving the block as it was. */
    cfg = scene_config(&sphere, 0, 4, 4);
    memset(junk, 0x5a, sizeof junk);
    junk[0] = 8;
    cfg.buffer = junk;
    cfg.buffer_size = sizeof junk;
    CHECK(irc_attach(&cfg, &c) == IRC_ERR_CONFIG, "junk");
    CHECK(junk[0] == 8 && junk[100] == 0x5a, "junk changed");
    cfg.buffer_size = 16;
    CHECK(irc_attach(&cfg, &c) == IRC_ERR_NOMEM, "tiny");
    CHECK(irc_attach(NULL, &c) == IRC_ERR_NULL, "NULL cfg");
    {   /* a port missing an operation is refused as irc_init refuses it */
        irc_config f = scene_config(&sphere, 0, 4, 4);
        irc_port half = irc_port_none;
        irc_cache *cache = block_cache(&f, 100, 0);
        half.cas = NULL;
        f.port = &half;
        CHECK(cache && irc_attach(&f, &c) == IRC_ERR_CONFIG, "port without cas");
        block_free(&f);
    }
    {   /* irrcache.h's port rules: a lock of at most 4096 bytes, owner and
         * owner_alive both or neither */
        irc_config f = scene_config(&sphere, 0, 4, 4);
        irc_port big = irc_port_none, one = irc_port_posix;
        size_t bytes;
        big.lock_size = 4097;
        f.port = &big;
        CHECK(irc_footprint(&f, 100, &bytes) == IRC_ERR_CONFIG, "a lock of 4097 bytes");
        big.lock_size = 4096;
        CHECK(irc_footprint(&f, 100, &bytes) == IRC_OK, "a lock of 4096 bytes refused");
        one.owner_alive = NULL;
        f.port = &one;
        CHECK(!irc_port_posix.owner || irc_footprint(&f, 100, &bytes) == IRC_ERR_CONFIG,
              "owner without owner_alive");
    }
    cfg.buffer = NULL;
    CHECK(irc_attach(&cfg, &c) == IRC_ERR_NULL, "NULL buffer");
    {   /* a block cut short, and a closed one */
        irc_config f = scene_config(&sphere, 0, 4, 4);
        irc_cache *cache = block_cache(&f, 100, 0);
        f.buffer_size -= 70;
        CHECK(irc_attach(&f, &c) == IRC_ERR_NOMEM, "short block");
        f.buffer_size += 70;
        irc_fini(cache);
        CHECK(irc_attach(&f, &c) == IRC_ERR_CONFIG, "closed block");
        block_free(&f);
    }
}

typedef struct seen {
    void *want;
    int calls, bad_host, bad_pn;
    float p[3], n[3];
} seen;

static int checking_trace(const irc_trace_args *a)
{
    seen *s = (seen *)a->host;
    int k;
    if (!s)
        return scene_trace(a);
    s->calls++;
    s->bad_host += a->host != s->want;
    for (k = 0; k < 3; k++)
        s->bad_pn += a->p[k] != s->p[k] || fabsf(a->n[k] - s->n[k]) > 1e-6f ||
                     a->rays[0].org[k] != s->p[k];
    return scene_trace(a);
}

/* The pointer each call is given reaches every callback it causes, with
 * the record's position and unit normal. */
TEST(test_host_context)
{
    irc_config cfg = scene_config(&sphere, IRC_FEATURE_VISIBILITY, 8, 16);
    irc_config shc = scene_config(&sphere, IRC_FEATURE_SH, 8, 16);
    irc_cache *c, *s;
    float p[3] = {0.3f, -0.2f, 0.0f}, n[3] = {0.0f, 0.0f, 2.0f}, rgb[3];
    irc_record r;
    irc_occlusion o;
    irc_sh sh;
    seen a;
    scene_sphere_plane(&sphere);
    cfg.trace = shc.trace = checking_trace;
    cfg.max_batch = 5;
    c = block_cache(&cfg, 10, 0);
    s = block_cache(&shc, 10, 0);
    CHECK(c && s, "init");
    if (!c || !s) return;
    memset(&a, 0, sizeof a);
    a.want = &a;
    memcpy(a.p, p, sizeof p);
    a.n[2] = 1.0f;
    CHECK(irc_record_compute(c, p, n, &r, &a) == IRC_OK, "compute");
    CHECK(irc_occlusion_compute(c, p, n, &o, &a) == IRC_OK, "occlusion");
    CHECK(irc_cache_lookup_or_compute(c, p, n, rgb, NULL, &a) == IRC_OK, "lookup_or_compute");
    CHECK(irc_sh_compute(s, p, n, &sh, &a) == IRC_OK, "sh surface");
    a.n[2] = 0.0f;
    CHECK(irc_sh_lookup_or_compute(s, p, NULL, &sh, NULL, &a) == IRC_OK, "sh free point");
    printf("  %d callback calls\n", a.calls);
    CHECK(a.calls > 5 * 128 / 5, "calls %d", a.calls);
    CHECK(a.bad_host == 0, "%d calls saw another host pointer", a.bad_host);
    CHECK(a.bad_pn == 0, "%d calls saw another position or normal", a.bad_pn);
    block_free(&cfg);
    block_free(&shc);
}

/* ---- more host threads than scratch slots ---- */

typedef struct gate {
    pthread_mutex_t mu;
    int inside;     /* the slow thread is in its callback */
    int release;    /* it may leave */
} gate;

static gate g_gate;

static int slow_trace(const irc_trace_args *a)
{
    if (a->host == &g_gate) {
        pthread_mutex_lock(&g_gate.mu);
        g_gate.inside = 1;
        while (!g_gate.release) {
            pthread_mutex_unlock(&g_gate.mu);
            sched_yield();
            pthread_mutex_lock(&g_gate.mu);
        }
        pthread_mutex_unlock(&g_gate.mu);
    }
    return scene_trace(a);
}

typedef struct job {
    irc_cache *c;
    float x;
    void *host;
    int st;
} job;

static void *run_job(void *arg)
{
    job *j = (job *)arg;
    float p[3], n[3] = {0, 0, 1}, rgb[3];
    p[0] = j->x;
    p[1] = 0.0f;
    p[2] = 0.0f;
    j->st = irc_cache_lookup_or_compute(j->c, p, n, rgb, NULL, j->host);
    return NULL;
}

static int gate_state(int which)
{
    int v;
    pthread_mutex_lock(&g_gate.mu);
    v = which ? g_gate.release : g_gate.inside;
    pthread_mutex_unlock(&g_gate.mu);
    return v;
}

/* One slot, held by a thread stuck in its callback: a second thread's miss
 * waits for the slot and gets its value (or, with no_wait, IRC_ERR_BUSY at
 * once). */
static void one_slot(int no_wait)
{
    irc_config cfg = scene_config(&sphere, IRC_FEATURE_TRANSLATION, 4, 8);
    irc_cache *c;
    job slow, other;
    pthread_t ts, to;
    irc_stats s;
    cfg.max_radius = 0.5f;
    cfg.trace = slow_trace;
    cfg.no_wait = (uint32_t)no_wait;
    c = block_cache(&cfg, 10, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    memset(&g_gate, 0, sizeof g_gate);
    pthread_mutex_init(&g_gate.mu, NULL);
    slow.c = other.c = c;
    slow.x = 0.0f;
    other.x = 2.5f;
    slow.host = &g_gate;
    other.host = NULL;
    pthread_create(&ts, NULL, run_job, &slow);
    while (!gate_state(0))
        sched_yield();
    pthread_create(&to, NULL, run_job, &other);
    if (no_wait) {
        pthread_join(to, NULL);
    } else {
        /* Let the other thread reach its wait before the slot frees. */
        struct timespec ms = {0, 200000000};
        nanosleep(&ms, NULL);
    }
    pthread_mutex_lock(&g_gate.mu);
    g_gate.release = 1;
    pthread_mutex_unlock(&g_gate.mu);
    pthread_join(ts, NULL);
    if (!no_wait)
        pthread_join(to, NULL);
    irc_cache_stats(c, &s);
    CHECK(slow.st == IRC_OK, "slow thread: %d", slow.st);
    if (no_wait) {
        CHECK(other.st == IRC_ERR_BUSY, "no_wait: %d", other.st);
        CHECK(s.records == 1 && s.waits == 0, "records %llu waits %llu",
              (unsigned long long)s.records, (unsigned long long)s.waits);
    } else {
        CHECK(other.st == IRC_OK, "waiting thread: %d", other.st);
        CHECK(s.records == 2 && s.waits == 1, "records %llu waits %llu",
              (unsigned long long)s.records, (unsigned long long)s.waits);
    }
    pthread_mutex_destroy(&g_gate.mu);
    block_free(&cfg);
}

TEST(test_busy_waits)
{
    scene_sphere_plane(&sphere);
    one_slot(0);
    one_slot(1);
}

/* A full pool without eviction: each miss is computed, answered, not
 * stored, and counted. */
TEST(test_not_stored_counted)
{
    irc_config cfg = scene_config(&sphere, 0, 4, 8);
    irc_cache *c;
    irc_stats s;
    int i, ok = 0, ns = 0;
    scene_sphere_plane(&sphere);
    cfg.max_radius = 0.5f;
    c = block_cache(&cfg, 2, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (i = 0; i < 5; i++) {
        float p[3], n[3] = {0, 0, 1}, rgb[3] = {-1, -1, -1};
        int st;
        p[0] = 3.0f * (float)i;
        p[1] = p[2] = 0.0f;
        st = irc_cache_lookup_or_compute(c, p, n, rgb, NULL, NULL);
        ok += st == IRC_OK;
        ns += st == IRC_NOT_STORED && rgb[0] > 0.0f;
    }
    irc_cache_stats(c, &s);
    CHECK(ok == 2 && ns == 3, "ok %d, not stored %d", ok, ns);
    CHECK(s.not_stored == 3 && s.computes == 5 && s.records == 2,
          "stats: not_stored %llu computes %llu records %llu",
          (unsigned long long)s.not_stored, (unsigned long long)s.computes,
          (unsigned long long)s.records);
    block_free(&cfg);
}
