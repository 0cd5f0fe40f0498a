/* t_bad_input.c -- bad input, failing callbacks, sums past float: refused, block unchanged. */
#define IRC_EXPERIMENTAL /* irc_cache_neighbours (irrcache.h) */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "block/cache.h" /* internals on purpose: a busy slot, no_wait */
#include "scenes.h"
#include "test.h"

#define GUARD 256

static tscene sky;

static void sky_init(void)
{
    scene_sphere_plane(&sky);
}

/* "n any length > 0" (irc_record_compute, and every call that takes a
 * normal): n scaled by a power of two (exact, whatever its size) gives the
 * same record, bit for bit, as the unit normal; scaled by another factor
 * (the scaled n is rounded, so the unit normal may move by an ulp and the
 * record's random numbers with it), a record of the same normal. */
TEST(test_normal_any_length)
{
    static const float scales[] = {2.0f, 0x1p120f, 0x1p-120f, 0x1p127f, 1e-38f, 3e38f};
    const float p[3] = {0.5f, 0.25f, 0.0f}, unit[3] = {0.0f, 0.6f, 0.8f};
    irc_config cfg;
    irc_cache *c;
    irc_record want, got;
    unsigned i;
    int k, ch;
    sky_init();
    cfg = scene_config(&sky, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 16);
    c = block_cache(&cfg, 16, 0);
    CHECK(c && irc_record_compute(c, p, unit, &want, NULL) == IRC_OK, "unit normal");
    if (!c) return;
    for (i = 0; i < sizeof scales / sizeof scales[0]; i++) {
        float n[3];
        int same = 1;
        for (k = 0; k < 3; k++)
            n[k] = unit[k] * scales[i];
        CHECK(irc_record_compute(c, p, n, &got, NULL) == IRC_OK, "n x %g", (double)scales[i]);
        if (i >= 4) { /* not a power of two */
            for (k = 0; k < 3; k++)
                same &= fabsf(got.n[k] - want.n[k]) < 1e-6f;
            CHECK(same, "n x %g: normal %g %g %g", (double)scales[i], (double)got.n[0],
                  (double)got.n[1], (double)got.n[2]);
            continue;
        }
        for (k = 0; k < 3; k++) {
            same &= got.e[k] == want.e[k] && got.n[k] == want.n[k];
            for (ch = 0; ch < 3; ch++)
                same &= got.grad_t[ch][k] == want.grad_t[ch][k] &&
                        got.grad_r[ch][k] == want.grad_r[ch][k];
        }
        same &= got.radius == want.radius;
        CHECK(same, "n x %g: another record (E %g against %g)", (double)scales[i],
              (double)got.e[0], (double)want.e[0]);
    }
    block_free(&cfg);
}

/* Every rejected call leaves the block byte for byte as it was, and
 * nothing is written past it. */
TEST(test_bad_input_unchanged)
{
    const float nanv = NAN, inf = INFINITY;
    const float good_p[3] = {0.5f, 0.25f, 0.0f}, good_n[3] = {0, 0, 1};
    const float bad_p[][3] = {{nanv, 0, 0}, {0, inf, 0}, {0, 0, -inf}};
    const float bad_n[][3] = {{0, 0, 0}, {nanv, 0, 1}, {0, inf, 1}, {-0.0f, 0.0f, -0.0f}};
    irc_config cfg;
    irc_cache *c;
    irc_record rec;
    unsigned char *copy;
    float rgb[3], w;
    uint32_t ids[4], cnt;
    size_t i;
    sky_init();
    cfg = scene_config(&sky, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 16);
    cfg.evict = IRC_EVICT_CLOCK;
    c = block_cache(&cfg, 64, GUARD);
    CHECK(c != NULL, "init");
    if (!c) return;
    CHECK(irc_cache_lookup_or_compute(c, good_p, good_n, rgb, &w, NULL) == IRC_OK, "seed one record");
    CHECK(irc_record_compute(c, good_p, good_n, &rec, NULL) == IRC_OK, "a good record");
    copy = malloc(cfg.buffer_size);
    memcpy(copy, cfg.buffer, cfg.buffer_size);
#define SAME(call, code)                                                          \
    do {                                                                          \
        int st_ = (call);                                                         \
        CHECK(st_ == (code), "%s returned %d (%s)", #call, st_, irc_strerror(st_)); \
        CHECK(block_same(&cfg, copy, c), "%s changed the block", #call);                 \
    } while (0)
    for (i = 0; i < 3; i++) {
        SAME(irc_cache_lookup(c, bad_p[i], good_n, rgb, &w), IRC_ERR_NONFINITE);
        SAME(irc_cache_lookup_or_compute(c, bad_p[i], good_n, rgb, &w, NULL), IRC_ERR_NONFINITE);
        SAME(irc_record_compute(c, bad_p[i], good_n, &rec, NULL), IRC_ERR_NONFINITE);
        SAME(irc_cache_neighbours(c, bad_p[i], good_n, ids, 4, &cnt), IRC_ERR_NONFINITE);
    }
    for (i = 0; i < 4; i++) {
        SAME(irc_cache_lookup(c, good_p, bad_n[i], rgb, &w), IRC_ERR_NORMAL);
        SAME(irc_cache_lookup_or_compute(c, good_p, bad_n[i], rgb, &w, NULL), IRC_ERR_NORMAL);
        SAME(irc_record_compute(c, good_p, bad_n[i], &rec, NULL), IRC_ERR_NORMAL);
    }
    SAME(irc_cache_lookup(NULL, good_p, good_n, rgb, &w), IRC_ERR_NULL);
    SAME(irc_cache_lookup(c, NULL, good_n, rgb, &w), IRC_ERR_NULL);
    SAME(irc_cache_lookup(c, good_p, NULL, rgb, &w), IRC_ERR_NULL);
    SAME(irc_cache_lookup(c, good_p, good_n, NULL, &w), IRC_ERR_NULL);
    SAME(irc_cache_insert(c, NULL), IRC_ERR_NULL);
    SAME(irc_record_compute(c, good_p, good_n, NULL, NULL), IRC_ERR_NULL);
    SAME(irc_cache_record(c, 64, &rec), IRC_ERR_RANGE);
    SAME(irc_cache_neighbours(c, good_p, good_n, NULL, 4, &cnt), IRC_ERR_NULL);
    SAME(irc_cache_stats(c, NULL), IRC_ERR_NULL);
    {
        irc_record bad = rec;
        bad.e[1] = nanv;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_NONFINITE);
        bad = rec;
        bad.grad_t[2][0] = inf;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_NONFINITE);
        bad = rec;
        bad.radius = 0.0f;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_RANGE);
        bad = rec;
        bad.radius = -1.0f;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_RANGE);
        bad = rec;
        bad.n[0] = bad.n[1] = bad.n[2] = 0.0f;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_NORMAL);
        bad = rec;
        bad.p[2] = nanv;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_NONFINITE);
        /* "every field it stores finite": each of them */
        bad = rec;
        bad.radius = inf;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_NONFINITE);
        bad = rec;
        bad.radius = nanv;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_NONFINITE);
        bad = rec;
        bad.minor_radius = nanv;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_NONFINITE);
        bad = rec;
        bad.axis[1] = inf;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_NONFINITE);
        bad = rec;
        bad.grad_r[1][2] = -inf;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_NONFINITE);
        bad = rec;
        bad.e[2] = -1.0f;
        SAME(irc_cache_insert(c, &bad), IRC_ERR_RANGE);
        /* what it does not store is not read: a record read back has
         * mean_dist NaN, and inserts as it is */
        bad = rec;
        bad.mean_dist = nanv;
        bad.hessian[0][0] = inf;
        CHECK(irc_cache_insert(c, &bad) == IRC_OK, "mean_dist and the Hessian were read");
        memcpy(copy, cfg.buffer, cfg.buffer_size); /* the block as it now is */
    }
    /* A cache handle that is not one. */
    {
        unsigned char junk[sizeof(irc_cache)];
        memset(junk, 0, sizeof junk);
        SAME(irc_cache_lookup((irc_cache *)(void *)junk, good_p, good_n, rgb, &w), IRC_ERR_CONFIG);
    }
    /* All scratch slots busy. */
    {
        /* internals on purpose: the slot taken and the cache told not to
         * wait, which is the only way a compute reports busy */
        uint64_t *own = irc__slot_owner(c, 0), was = *own;
        *own = (uint64_t)getpid(); /* alive: nothing to take over */
        c->cfg.no_wait = 1;
        memcpy(copy, cfg.buffer, cfg.buffer_size);
        SAME(irc_record_compute(c, good_p, good_n, &rec, NULL), IRC_ERR_BUSY);
        SAME(irc_cache_lookup_or_compute(c, good_n, good_n, rgb, &w, NULL), IRC_ERR_BUSY);
        *own = was;
        c->cfg.no_wait = 0;
    }
#undef SAME
    CHECK(block_guard_ok(&cfg, GUARD), "guard bytes");
    free(copy);
    block_free(&cfg);
}

/* A callback reporting nonsense: an error status, no record, and the block
 * as it was. */
TEST(test_callback_failures)
{
    static const struct { unsigned kind, every; int want; } cases[] = {
        {FAIL_NEG_DIST, 5, IRC_ERR_CALLBACK},    {FAIL_NAN_DIST, 5, IRC_ERR_CALLBACK},
        {FAIL_ZERO_DIST, 5, IRC_ERR_CALLBACK},   {FAIL_INF_RADIANCE, 5, IRC_ERR_CALLBACK},
        {FAIL_NAN_RADIANCE, 5, IRC_ERR_CALLBACK}, {FAIL_NEG_RADIANCE, 5, IRC_ERR_CALLBACK},
        {FAIL_ZERO_NORMAL, 5, IRC_ERR_CALLBACK}, {FAIL_BAD_STATUS, 5, IRC_ERR_CALLBACK},
        {FAIL_UNTOUCHED, 5, IRC_ERR_CALLBACK},   {FAIL_INF_DIST, 5, IRC_ERR_CALLBACK},
        {FAIL_NAN_NORMAL, 5, IRC_ERR_CALLBACK},  {FAIL_RAY, 1, IRC_ERR_NOSAMPLES},
        {FAIL_RAY, 3, IRC_OK}};
    const float p[3] = {0.5f, 0.25f, 0.0f}, n[3] = {0, 0, 1};
    size_t i;
    uint32_t batch;
    for (batch = 1; batch <= 64; batch *= 64) {
        for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
            irc_config cfg;
            irc_cache *c;
            unsigned char *copy;
            irc_record rec;
            float rgb[3], w;
            int st;
            sky_init();
            cfg = scene_config(&sky, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 16);
            cfg.max_batch = batch;
            c = block_cache(&cfg, 8, GUARD);
            copy = malloc(cfg.buffer_size);
            memcpy(copy, cfg.buffer, cfg.buffer_size);
            sky.fail_kind = cases[i].kind;
            sky.fail_every = cases[i].every;
            st = irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
            CHECK(st == cases[i].want, "kind %u batch %u: %d (%s)", cases[i].kind, batch, st,
                  irc_strerror(st));
            if (cases[i].want < 0)
                CHECK(memcmp(copy, cfg.buffer, cfg.buffer_size) == 0, "kind %u changed the block",
                      cases[i].kind);
            else
                CHECK(irc_cache_record(c, 0, &rec) == IRC_OK && rec.e[0] > 0.0f &&
                      fabs(rgb[0] - rec.e[0]) < 1e-6f * rec.e[0], "one failed ray in three: a record");
            CHECK(block_guard_ok(&cfg, GUARD), "guard");
            free(copy);
            block_free(&cfg);
        }
    }
    /* The host's own negative code comes back unchanged; positive is bad. */
    {
        irc_config cfg;
        irc_cache *c;
        irc_record rec;
        sky_init();
        cfg = scene_config(&sky, 0, 4, 4);
        c = block_cache(&cfg, 8, 0);
        sky.return_code = -4242;
        CHECK(irc_record_compute(c, p, n, &rec, NULL) == -4242, "host code passed through");
        sky.return_code = 3;
        CHECK(irc_record_compute(c, p, n, &rec, NULL) == IRC_ERR_CALLBACK, "positive return");
        block_free(&cfg);
    }
}

/* Radiances finite but near FLT_MAX sum past it: the record is refused
 * (IRC_ERR_NONFINITE), nothing counted, the block unchanged.  Found by
 * fuzz/fuzz_api.c (corpus entry crash-overflow-counted). */
TEST(test_overflow_radiance)
{
    const float p[3] = {0.5f, 0.25f, 0.0f}, n[3] = {0, 0, 1};
    irc_config cfg;
    irc_cache *c;
    irc_record rec;
    unsigned char *copy;
    float rgb[3], w;
    int st;
    sky_init();
    sky.sky_a[0] = 3e38f;
    cfg = scene_config(&sky, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 16);
    c = block_cache(&cfg, 8, GUARD);
    copy = malloc(cfg.buffer_size);
    memcpy(copy, cfg.buffer, cfg.buffer_size);
    st = irc_record_compute(c, p, n, &rec, NULL);
    CHECK(st == IRC_ERR_NONFINITE, "compute: %d", st);
    st = irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL);
    CHECK(st == IRC_ERR_NONFINITE, "lookup_or_compute: %d", st);
    CHECK(memcmp(copy, cfg.buffer, cfg.buffer_size) == 0, "block changed");
    sky.sky_a[0] = 1e30f; /* large but summable: a record, E by the closed form */
    {
        const double pd[3] = {0.5, 0.25, 0.0};
        double want = sphere_plane_e(&sky, pd);
        CHECK(irc_record_compute(c, p, n, &rec, NULL) == IRC_OK && fabs(rec.e[0] - want) < 0.01 * want,
              "1e30 sky: E %g, closed form %g", rec.e[0], want);
    }
    free(copy);
    block_free(&cfg);
}
