/* t_lookup.c -- weights, extrapolation, misses, full pools and eviction. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"
#include "scenes.h"
#include "test.h"

static tscene dummy;

static irc_record flat_record(float x, float y, float z, float e, float radius)
{
    irc_record r;
    memset(&r, 0, sizeof r);
    r.p[0] = x; r.p[1] = y; r.p[2] = z;
    r.n[2] = 1.0f;
    r.e[0] = r.e[1] = r.e[2] = e;
    r.radius = radius;
    return r;
}

/* Two records, no gradients: the lookup is sum w_i E_i / sum w_i with
 * w_i = 1/(|p - p_i|/R_i + sqrt(1 - n.n_i)), written out here by hand. */
TEST(test_weighted_mean)
{
    irc_config cfg = scene_config(&dummy, 0, 4, 4);
    irc_cache *c;
    irc_record a = flat_record(0, 0, 0, 1.0f, 1.0f), b = flat_record(0.1f, 0, 0, 3.0f, 0.2f);
    float p[3] = {0.04f, 0.03f, 0.0f}, n[3] = {0.1f, 0.0f, 1.0f}, rgb[3], w;
    double nn, wa, wb, want;
    cfg.accuracy = 0.5f;
    c = block_cache(&cfg, 8, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    CHECK(irc_cache_insert(c, &a) == IRC_OK && irc_cache_insert(c, &b) == IRC_OK, "insert");
    nn = 1.0 / sqrt(1.01);
    wa = 1.0 / (sqrt(0.04 * 0.04 + 0.03 * 0.03) / 1.0 + sqrt(1.0 - nn));
    wb = 1.0 / (sqrt(0.06 * 0.06 + 0.03 * 0.03) / 0.2 + sqrt(1.0 - nn));
    want = (wa * 1.0 + wb * 3.0) / (wa + wb);
    CHECK(irc_cache_lookup(c, p, n, rgb, &w) == IRC_OK, "lookup hits");
    CHECK(fabs(rgb[0] - want) < 1e-4 * want, "value %g vs %g", rgb[0], want);
    CHECK(fabs(w - (wa + wb)) < 1e-3 * (wa + wb), "weight %g vs %g", w, wa + wb);
    /* Acceptance: a record counts only while d/R + sqrt(1 - n.n) < a. */
    p[0] = -0.49f; p[1] = 0.0f; n[0] = 0.0f;
    CHECK(irc_cache_lookup(c, p, n, rgb, &w) == IRC_OK && fabs(rgb[0] - 1.0f) < 1e-6, "only a");
    p[0] = -0.51f;
    CHECK(irc_cache_lookup(c, p, n, rgb, &w) == IRC_MISS && rgb[0] == 0.0f && w == 0.0f, "miss");
    /* A record facing away never counts. */
    p[0] = 0.0f; n[2] = -1.0f;
    CHECK(irc_cache_lookup(c, p, n, rgb, &w) == IRC_MISS, "facing away");
    block_free(&cfg);
}

/* The "behind" test: a record in front of the query's surface by more than
 * 0.05 R_i is rejected, at every scale. */
TEST(test_behind_relative)
{
    static const float scales[] = {1e-4f, 1.0f, 1e4f};
    size_t i;
    for (i = 0; i < 3; i++) {
        float s = scales[i], rgb[3], w;
        irc_config cfg = scene_config(&dummy, 0, 4, 4);
        irc_cache *c = block_cache(&cfg, 8, 0);
        irc_record r = flat_record(0, 0, 0, 2.0f, 1.0f * s);
        const float n[3] = {0, 0, 1};
        float p_in[3] = {0.1f * s, 0, -0.04f * s}, p_out[3] = {0.1f * s, 0, -0.06f * s};
        CHECK(c && irc_cache_insert(c, &r) == IRC_OK, "insert");
        CHECK(irc_cache_lookup(c, p_in, n, rgb, &w) == IRC_OK, "0.04 R below: kept (scale %g)", s);
        CHECK(irc_cache_lookup(c, p_out, n, rgb, &w) == IRC_MISS, "0.06 R below: rejected (scale %g)", s);
        block_free(&cfg);
    }
}

/* Extrapolation: E + (p - p_i).grad_t + (n_i x n).grad_r, and the clamp
 * at zero. */
TEST(test_extrapolation)
{
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4);
    irc_cache *c;
    /* |grad_t| R <= E for every channel (so stored as given), a reach of
     * 2 for the green channel to extrapolate below zero */
    irc_record r = flat_record(1, 2, 3, 1.0f, 0.2f);
    float p[3] = {1.5f, 1.75f, 3.0f}, n[3] = {0, 0, 1}, rgb[3], w;
    double th = 0.1, want;
    cfg.accuracy = 10.0f;
    c = block_cache(&cfg, 8, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    r.grad_t[0][0] = 0.2f; r.grad_t[0][1] = -0.4f;   /* red */
    r.grad_t[1][0] = -4.0f;                          /* green: goes negative */
    r.grad_r[2][0] = 0.5f; r.grad_r[2][1] = 0.25f;   /* blue */
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
    CHECK(irc_cache_lookup(c, p, n, rgb, &w) == IRC_OK, "hit");
    want = 1.0 + 0.5 * 0.2 + (-0.25) * (-0.4);
    CHECK(fabs(rgb[0] - want) < 1e-4, "translation: %g vs %g", rgb[0], want);
    CHECK(rgb[1] == 0.0f, "clamped at zero: %g", rgb[1]);
    CHECK(fabs(rgb[2] - 1.0f) < 1e-4, "no rotation, blue unchanged: %g", rgb[2]);
    /* Tilt the query normal about x: n = (0, -sin, cos); n_i x n = (sin, 0, 0)
     * to first order, so blue gains 0.5 sin(th). */
    p[0] = 1.0f; p[1] = 2.0f;
    n[1] = (float)-sin(th); n[2] = (float)cos(th);
    CHECK(irc_cache_lookup(c, p, n, rgb, &w) == IRC_OK, "hit");
    want = 1.0 + 0.5 * sin(th);
    CHECK(fabs(rgb[2] - want) < 1e-4, "rotation: %g vs %g", rgb[2], want);
    block_free(&cfg);
}

/* A record read at its own position and normal returns its own E, up to
 * the stored normal's quantization (5e-5 rad times the rotational
 * gradient). */
TEST(test_lookup_or_compute)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_stats st;
    const float p[3] = {0.3f, 0.2f, 0.0f}, n[3] = {0, 0, 1};
    float rgb[3], rgb2[3], w;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    c = block_cache(&cfg, 1, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    CHECK(irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL) == IRC_OK && w == 0.0f, "computed");
    CHECK(irc_cache_lookup_or_compute(c, p, n, rgb2, &w, NULL) == IRC_OK && w > 0.0f, "then found");
    CHECK(fabs(rgb2[0] - rgb[0]) <= 1e-4f * rgb[0], "same value %g %g", rgb[0], rgb2[0]);
    /* Pool of one: the next miss is computed but not stored. */
    {
        const float far[3] = {50.0f, 0, 0};
        CHECK(irc_cache_lookup_or_compute(c, far, n, rgb, &w, NULL) == IRC_NOT_STORED, "not stored");
        CHECK(irc_cache_lookup(c, p, n, rgb2, &w) == IRC_OK, "lookups go on when full");
    }
    irc_cache_stats(c, &st);
    CHECK(st.records == 1 && st.computes == 2 && st.lookups == 4 && st.hits == 2,
          "stats %llu %llu %llu %llu", (unsigned long long)st.records,
          (unsigned long long)st.computes, (unsigned long long)st.lookups,
          (unsigned long long)st.hits);
    CHECK(st.rays == 2u * 8u * 32u, "rays %llu", (unsigned long long)st.rays);
    block_free(&cfg);
}

/* Full pool without eviction: IRC_ERR_FULL and the block unchanged. */
TEST(test_full_no_evict)
{
    irc_config cfg = scene_config(&dummy, 0, 4, 4);
    irc_cache *c = block_cache(&cfg, 3, 0);
    irc_record r = flat_record(0, 0, 0, 1.0f, 1.0f);
    unsigned char *copy;
    int i;
    CHECK(c != NULL, "init");
    if (!c) return;
    for (i = 0; i < 3; i++) {
        r.p[0] = (float)i * 10.0f;
        CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert %d", i);
    }
    copy = malloc(cfg.buffer_size);
    memcpy(copy, cfg.buffer, cfg.buffer_size);
    r.p[0] = 99.0f;
    CHECK(irc_cache_insert(c, &r) == IRC_ERR_FULL, "full");
    CHECK(memcmp(copy, cfg.buffer, cfg.buffer_size) == 0, "block unchanged");
    free(copy);
    block_free(&cfg);
}

/* CLOCK eviction: the pool stays at capacity, records used by lookups
 * since the hand passed survive, and the index stays exact. */
TEST(test_evict_clock)
{
    irc_config cfg = scene_config(&dummy, 0, 4, 4);
    irc_cache *c;
    irc_record r = flat_record(0, 0, 0, 1.0f, 1.0f), back;
    irc_stats st;
    const float n[3] = {0, 0, 1};
    float rgb[3], w;
    uint32_t i, ids[8], cnt;
    cfg.evict = IRC_EVICT_CLOCK;
    c = block_cache(&cfg, 4, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (i = 0; i < 4; i++) {
        r.p[0] = (float)i * 10.0f;
        r.e[0] = (float)i;
        CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
    }
    /* Use record 0 (at x = 0): it gets a second chance; record 1 goes. */
    {
        const float p0[3] = {0, 0, 0};
        CHECK(irc_cache_lookup(c, p0, n, rgb, &w) == IRC_OK, "use record 0");
    }
    r.p[0] = 100.0f;
    r.e[0] = 100.0f;
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert with eviction");
    irc_cache_stats(c, &st);
    CHECK(st.records == 4 && st.evictions == 1, "records %llu evictions %llu",
          (unsigned long long)st.records, (unsigned long long)st.evictions);
    CHECK(irc_cache_record(c, 0, &back) == IRC_OK && back.e[0] == 0.0f, "record 0 kept");
    CHECK(irc_cache_record(c, 1, &back) == IRC_OK && back.e[0] == 100.0f, "slot 1 replaced");
    {
        const float p1[3] = {10, 0, 0}, pn[3] = {100, 0, 0};
        CHECK(irc_cache_lookup(c, p1, n, rgb, &w) == IRC_MISS, "evicted record gone from the index");
        CHECK(irc_cache_neighbours(c, pn, n, ids, 8, &cnt) == IRC_OK && cnt == 1 && ids[0] == 1,
              "new record found");
    }
    /* Long run in bounded memory. */
    for (i = 0; i < 1000; i++) {
        r.p[0] = (float)(i % 37) * 3.0f;
        r.p[1] = (float)(i / 37) * 3.0f;
        CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert %u", i);
    }
    irc_cache_stats(c, &st);
    CHECK(st.records == 4 && st.evictions == 1001, "evictions %llu", (unsigned long long)st.evictions);
    block_free(&cfg);
}
