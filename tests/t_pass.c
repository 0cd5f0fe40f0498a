/* t_pass.c -- fill passes: lookups of a pass see the cache frozen, its
 * records join in one canonical order, so any order of queries, on any
 * number of threads, adds the same records; passes never evict; calls a
 * pass forbids are refused and change nothing. */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"
#include "scenes.h"
#include "test.h"

#define GRID 40

static irc_cache *pass_cache(tscene *s, irc_config *cfg, uint32_t cap, uint32_t evict)
{
    scene_sphere_plane(s);
    *cfg = scene_config(s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    cfg->max_radius = 4.0f;
    cfg->evict = evict;
    cfg->threads = 4;
    return block_cache(cfg, cap, 0);
}

/* Query i of a GRID x GRID lattice on the plane under the sphere. */
static void query(int i, float p[3])
{
    p[0] = (float)(i % GRID) * 6.0f / GRID - 3.0f;
    p[1] = (float)(i / GRID) * 6.0f / GRID - 3.0f;
    p[2] = 0.0f;
}

typedef struct share {
    irc_cache *c;
    const int *order;
    int first, step, n, fail;
} share;

/* Queries order[first], order[first + step], ... of one pass. */
static void *fill_part(void *arg)
{
    share *k = (share *)arg;
    const float up[3] = {0, 0, 1};
    int i;
    for (i = k->first; i < k->n; i += k->step) {
        float p[3], rgb[3], w;
        query(k->order[i], p);
        if (irc_cache_lookup_or_compute(k->c, p, up, rgb, &w, NULL) < 0)
            k->fail = 1;
    }
    return NULL;
}

/* Three passes (every 4th point of the lattice, every 2nd, all) with the
 * queries of each in the given order on `threads` threads (freely, with
 * no irc_pass_begin/end, when use_passes is 0); the snapshot of the
 * result into *snap (malloc'd). */
static size_t passes_fill(int threads, const int *order, int use_passes, unsigned char **snap)
{
    tscene s;
    irc_config cfg;
    irc_cache *c = pass_cache(&s, &cfg, 4096, IRC_EVICT_NONE);
    int pass, lv[GRID * GRID], fail = 0;
    size_t bytes = 0;
    *snap = NULL;
    if (!c)
        return 0;
    for (pass = 0; pass < 3; pass++) {
        pthread_t th[4];
        share k[4];
        int i, n = 0, t;
        const int s4 = 4 >> pass;
        for (i = 0; i < GRID * GRID; i++)
            if ((order[i] % GRID) % s4 == 0 && (order[i] / GRID) % s4 == 0)
                lv[n++] = order[i];
        CHECK(!use_passes || irc_pass_begin(c) == IRC_OK, "begin");
        for (t = 0; t < threads; t++) {
            k[t].c = c;
            k[t].order = lv;
            k[t].first = t;
            k[t].step = threads;
            k[t].n = n;
            k[t].fail = 0;
            pthread_create(&th[t], NULL, fill_part, &k[t]);
        }
        for (t = 0; t < threads; t++) {
            pthread_join(th[t], NULL);
            fail |= k[t].fail;
        }
        CHECK(!use_passes || irc_pass_end(c, NULL) == IRC_OK, "end");
    }
    CHECK(!fail, "a lookup failed");
    if (irc_snapshot_size(c, &bytes) == IRC_OK && (*snap = malloc(bytes)) != NULL)
        CHECK(irc_snapshot_write(c, 7u, *snap, bytes, NULL, NULL, NULL) == IRC_OK, "write");
    block_free(&cfg);
    return bytes;
}

/* Forward order on 1 thread, reversed on 2, shuffled on 4: one snapshot,
 * byte for byte.  The same queries filled freely in two orders give other
 * records (the test would not notice a pass that did nothing). */
TEST(test_pass_order_free)
{
    int fwd[GRID * GRID], rev[GRID * GRID], mix[GRID * GRID], i;
    unsigned char *a, *b, *m;
    size_t na, nb, nm;
    uint64_t x = 88172645463325252ull;
    for (i = 0; i < GRID * GRID; i++) {
        fwd[i] = mix[i] = i;
        rev[i] = GRID * GRID - 1 - i;
    }
    for (i = GRID * GRID - 1; i > 0; i--) {
        int j, t;
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        j = (int)(x % (uint64_t)(i + 1));
        t = mix[i], mix[i] = mix[j], mix[j] = t;
    }
    na = passes_fill(1, fwd, 1, &a);
    nb = passes_fill(2, rev, 1, &b);
    nm = passes_fill(4, mix, 1, &m);
    CHECK(a && b && m && na > 48 + 4 + 10 * 64, "snapshots: %zu bytes", na);
    CHECK(a && b && na == nb && memcmp(a, b, na) == 0, "reversed on 2 threads differs");
    CHECK(a && m && na == nm && memcmp(a, m, na) == 0, "shuffled on 4 threads differs");
    free(a);
    free(b);
    free(m);
    na = passes_fill(1, fwd, 0, &a);
    nb = passes_fill(1, rev, 0, &b);
    CHECK(a && b && (na != nb || memcmp(a, b, na) != 0), "free fills agree: a weak test");
    free(a);
    free(b);
}

/* Within a pass a miss's record is not seen: the same query misses again
 * (and computes the same record, kept once), an inserted record is not
 * seen, the record count stands still; after the pass both are there. */
TEST(test_pass_frozen)
{
    tscene s;
    irc_config cfg;
    irc_cache *c = pass_cache(&s, &cfg, 64, IRC_EVICT_NONE);
    const float p[3] = {2.5f, 0.5f, 0.0f}, q[3] = {-2.5f, 0.5f, 0.0f}, up[3] = {0, 0, 1};
    float rgb[3], w = -1.0f;
    irc_record r;
    irc_stats st;
    uint32_t added = 0;
    CHECK(c != NULL, "init");
    if (!c) return;
    CHECK(irc_pass_begin(c) == IRC_OK, "begin");
    CHECK(irc_cache_lookup_or_compute(c, p, up, rgb, &w, NULL) == IRC_OK && w == 0.0f, "miss");
    CHECK(irc_cache_lookup(c, p, up, rgb, &w) == IRC_MISS, "a pass's record was seen");
    CHECK(irc_cache_lookup_or_compute(c, p, up, rgb, &w, NULL) == IRC_OK && w == 0.0f,
          "second miss");
    CHECK(irc_record_compute(c, q, up, &r, NULL) == IRC_OK && irc_cache_insert(c, &r) == IRC_OK,
          "insert");
    CHECK(irc_cache_lookup(c, q, up, rgb, &w) == IRC_MISS, "an inserted record was seen");
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records == 0 && st.computes == 3, "records %u",
          (unsigned)st.records);
    CHECK(irc_pass_end(c, &added) == IRC_OK && added == 2, "added %u, not 2", (unsigned)added);
    /* at its own point: Ward's 1/e past 1/a, or the blend's (1 - t^2)^2 at
     * t ~ 0 (the coded normal's 1e-5) */
    CHECK(irc_cache_lookup(c, p, up, rgb, &w) == IRC_OK && w > 0.99f, "p after the pass (%g)", w);
    CHECK(irc_cache_lookup(c, q, up, rgb, &w) == IRC_OK && w > 0.99f, "q after the pass (%g)", w);
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records == 2 && st.inserts == 2, "count");
    block_free(&cfg);
}

/* A pass fills the free slots and then stores nothing, with CLOCK on too
 * (evicting would change what the pass's lookups see). */
TEST(test_pass_full)
{
    tscene s;
    irc_config cfg;
    irc_cache *c = pass_cache(&s, &cfg, 12, IRC_EVICT_CLOCK);
    const float up[3] = {0, 0, 1};
    irc_stats st;
    uint32_t added = 0;
    int i, ok = 0, not_stored = 0;
    CHECK(c != NULL, "init");
    if (!c) return;
    for (i = 0; i < 5; i++) { /* 5 records before the pass */
        float p[3] = {-3.0f + 1.5f * i, -3.0f, 0.0f}, rgb[3];
        CHECK(irc_cache_lookup_or_compute(c, p, up, rgb, NULL, NULL) == IRC_OK, "before");
    }
    CHECK(irc_pass_begin(c) == IRC_OK, "begin");
    for (i = 0; i < 10; i++) {
        float p[3] = {-3.0f + 0.6f * i, 3.0f, 0.0f}, rgb[3];
        int r = irc_cache_lookup_or_compute(c, p, up, rgb, NULL, NULL);
        ok += r == IRC_OK;
        not_stored += r == IRC_NOT_STORED;
    }
    CHECK(ok == 7 && not_stored == 3, "%d stored, %d not", ok, not_stored);
    {
        /* An insert that finds no room in the pass fails and changes
         * nothing (it counted its attempt in the block: fuzz_api, corpus
         * crash-pass-insert-full). */
        irc_record r;
        unsigned char *copy = malloc(cfg.buffer_size);
        disk_record(&r, 1.0f, 1.0f);
        CHECK(copy != NULL, "malloc");
        if (copy) {
            memcpy(copy, cfg.buffer, cfg.buffer_size);
            CHECK(irc_cache_insert(c, &r) == IRC_ERR_FULL &&
                      memcmp(copy, cfg.buffer, cfg.buffer_size) == 0,
                  "a full pass's insert changed the block");
            free(copy);
        }
    }
    CHECK(irc_pass_end(c, &added) == IRC_OK && added == 7, "added %u", (unsigned)added);
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records == 12 && st.evictions == 0 &&
              st.not_stored == 3,
          "records %u evictions %u not stored %u", (unsigned)st.records, (unsigned)st.evictions,
          (unsigned)st.not_stored);
    block_free(&cfg);
}

/* Begin twice, end without a pass, and clear, read or merge during one:
 * IRC_ERR_STATE, the cache unchanged; then the pass ends normally. */
TEST(test_pass_state)
{
    tscene s;
    irc_config cfg;
    irc_cache *c = pass_cache(&s, &cfg, 64, IRC_EVICT_NONE);
    const float p[3] = {1.0f, 1.0f, 0.0f}, up[3] = {0, 0, 1};
    unsigned char snap[48 + 4 + 64 * 64];
    size_t n = 0;
    float rgb[3], w;
    uint32_t added = 9;
    irc_stats st;
    CHECK(c != NULL, "init");
    if (!c) return;
    CHECK(irc_pass_end(c, &added) == IRC_ERR_STATE && added == 9, "end without a pass");
    CHECK(irc_cache_lookup_or_compute(c, p, up, rgb, &w, NULL) == IRC_OK, "fill");
    CHECK(irc_snapshot_write(c, 1u, snap, sizeof snap, NULL, NULL, &n) == IRC_OK, "write");
    CHECK(irc_pass_begin(c) == IRC_OK && irc_pass_begin(c) == IRC_ERR_STATE, "begin twice");
    CHECK(irc_cache_clear(c) == IRC_ERR_STATE, "clear in a pass");
    CHECK(irc_snapshot_read(c, 1u, snap, n) == IRC_ERR_STATE, "read in a pass");
    CHECK(irc_merge(c, 1u, snap, n) == IRC_ERR_STATE, "merge in a pass");
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records == 1, "records %u",
          (unsigned)st.records);
    CHECK(irc_cache_lookup(c, p, up, rgb, &w) == IRC_OK, "the record survives");
    CHECK(irc_pass_end(c, &added) == IRC_OK && added == 0, "end: %u", (unsigned)added);
    CHECK(irc_pass_begin(NULL) == IRC_ERR_NULL && irc_pass_end(NULL, NULL) == IRC_ERR_NULL,
          "NULL");
    block_free(&cfg);
}

/* Read locks taken, by a port that counts them. */
static int read_locks;

static int counting_read_lock(void *lock)
{
    read_locks++;
    return irc_port_none.read_lock(lock);
}

/* Lookups outside a pass take the read lock; inside one, where nothing the
 * index holds can change until irc_pass_end, they take none, and answer
 * as before. */
TEST(test_pass_lock_free)
{
    tscene s;
    irc_config cfg;
    irc_port port = irc_port_none;
    irc_cache *c;
    const float up[3] = {0, 0, 1};
    float out[2][16][4];
    int i, k, before;
    memset(out, 0, sizeof out);
    port.read_lock = counting_read_lock;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    cfg.port = &port;
    c = block_cache(&cfg, 256, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (k = 0; k < 2; k++) { /* fill, then the same queries hit */
        before = read_locks;
        for (i = 0; i < 16; i++) {
            float p[3];
            query(i * 97 % (GRID * GRID), p);
            out[0][i][3] = (float)irc_cache_lookup_or_compute(c, p, up, out[0][i], NULL, NULL);
        }
        CHECK(read_locks - before == 16, "free fill: %d read locks for 16 lookups",
              read_locks - before);
    }
    CHECK(irc_pass_begin(c) == IRC_OK, "begin");
    before = read_locks;
    for (i = 0; i < 16; i++) {
        float p[3];
        query(i * 97 % (GRID * GRID), p);
        out[1][i][3] = (float)irc_cache_lookup_or_compute(c, p, up, out[1][i], NULL, NULL);
    }
    CHECK(read_locks == before, "in a pass: %d read locks", read_locks - before);
    CHECK(memcmp(out[0], out[1], sizeof out[0]) == 0, "a pass's lookups answer otherwise");
    CHECK(irc_pass_end(c, NULL) == IRC_OK, "end");
    block_free(&cfg);
}
