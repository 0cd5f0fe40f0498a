/* t_api.c -- config checks, footprints, bad input, callback failures. */
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

TEST(test_config_checks)
{
    irc_config cfg;
    size_t bytes;
    struct { const char *what; int want; } cases[64];
    int i, n = 0;
    sky_init();
#define CASE(field_set, code)                                               \
    do {                                                                    \
        cfg = scene_config(&sky, 0, 0, 0);                                  \
        field_set;                                                          \
        cases[n].what = #field_set;                                         \
        cases[n].want = code;                                               \
        CHECK(irc_footprint(&cfg, 16, &bytes) == code, "%s", #field_set);   \
        n++;                                                                \
    } while (0)
    CASE(cfg.trace = NULL, IRC_ERR_NULL);
    CASE(cfg.features = IRC_FEATURE_SH, IRC_OK);
    CASE(cfg.features = IRC_FEATURE_SH_GRADIENT, IRC_OK);
    CASE(cfg.features = IRC_FEATURE_SH | IRC_FEATURE_TRANSLATION, IRC_ERR_CONFIG);
    CASE(cfg.features = IRC_FEATURE_SH_GRADIENT | IRC_FEATURE_ROTATION, IRC_ERR_CONFIG);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.sh.bands = 6), IRC_ERR_CONFIG);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.sh.bands = 5), IRC_OK);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.sh.channels = 2), IRC_ERR_CONFIG);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.sh.channels = 1), IRC_OK);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.sh.power = -1.0f), IRC_ERR_CONFIG);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.sh.power = NAN), IRC_ERR_CONFIG);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.sh.power = 17.0f), IRC_ERR_CONFIG);
    CASE(cfg.sh.bands = 3, IRC_ERR_CONFIG);
    CASE(cfg.sh.power = 2.0f, IRC_ERR_CONFIG);
    /* the irradiance kind's fields in an SH config */
    CASE((cfg.features = IRC_FEATURE_SH, cfg.irr.leak_guard = IRC_OFF), IRC_ERR_CONFIG);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.irr.supersamples = 1), IRC_ERR_CONFIG);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.irr.max_pixels = 4.0f), IRC_ERR_CONFIG);
    CASE(cfg.features = IRC_FEATURE_VISIBILITY, IRC_OK);
    CASE(cfg.features = 1u << 20, IRC_ERR_CONFIG);
    CASE(cfg.accuracy = -1.0f, IRC_ERR_CONFIG);
    CASE(cfg.accuracy = 1e9f, IRC_ERR_CONFIG);
    CASE(cfg.accuracy = NAN, IRC_ERR_CONFIG);
    CASE(cfg.min_radius = -1.0f, IRC_ERR_CONFIG);
    CASE((cfg.min_radius = 2.0f, cfg.max_radius = 1.0f), IRC_ERR_CONFIG);
    CASE(cfg.irr.min_pixels = -1.0f, IRC_OK); /* no lower bound */
    CASE(cfg.irr.max_pixels = -INFINITY, IRC_ERR_CONFIG);
    CASE((cfg.irr.min_pixels = 40.0f, cfg.irr.max_pixels = 0.0f), IRC_OK); /* max defaults to 40 */
    CASE(cfg.irr.max_pixels = NAN, IRC_ERR_CONFIG);
    CASE(cfg.irr.min_pixels = INFINITY, IRC_ERR_CONFIG);
    CASE((cfg.irr.min_pixels = 4.0f, cfg.irr.max_pixels = 2.0f), IRC_ERR_CONFIG);
    CASE((cfg.irr.min_pixels = 4.0f, cfg.irr.max_pixels = 0.0f), IRC_OK);
    CASE((cfg.irr.min_pixels = 2.5f, cfg.irr.max_pixels = 15.0f), IRC_OK);
    CASE(cfg.irr.leak_guard = 3, IRC_ERR_CONFIG);
    CASE(cfg.irr.leak_guard = IRC_ON, IRC_OK);
    CASE(cfg.irr.leak_guard = IRC_OFF, IRC_OK);
    CASE(cfg.check_visibility = 3, IRC_ERR_CONFIG);
    CASE(cfg.check_visibility = IRC_ON, IRC_OK);
    CASE(cfg.clamp_neighbours = 3, IRC_ERR_CONFIG);
    CASE(cfg.clamp_neighbours = IRC_OFF, IRC_OK);
    CASE(cfg.no_wait = 2, IRC_ERR_CONFIG);
    CASE(cfg.no_wait = 1, IRC_OK);
    CASE(cfg.strata_theta = 2000, IRC_ERR_CONFIG);
    CASE((cfg.strata_theta = 1024, cfg.strata_phi = 4097), IRC_ERR_CONFIG);
    CASE((cfg.strata_theta = 1024, cfg.strata_phi = 4096), IRC_OK);
    CASE(cfg.max_batch = IRC_MAX_BATCH + 1, IRC_ERR_CONFIG);
    CASE(cfg.threads = IRC_MAX_THREADS + 1, IRC_ERR_CONFIG);
    CASE(cfg.evict = 7, IRC_ERR_CONFIG);
    CASE(cfg.accuracy = 0.0f, IRC_OK);
    CASE((cfg.strata_theta = 1, cfg.strata_phi = 1), IRC_OK);
    CASE((cfg.strata_theta = 256, cfg.strata_phi = 256), IRC_OK);
    /* The header's promises, one CASE each (TESTING.md, "The header's
     * promises"): SH with VISIBILITY; an irradiance field in an SH
     * config and an SH field in an irradiance one; the pixel counts
     * finite whichever sign; phi's own bound. */
    CASE(cfg.features = IRC_FEATURE_SH | IRC_FEATURE_VISIBILITY, IRC_ERR_CONFIG);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.irr.min_pixels = 2.0f), IRC_ERR_CONFIG);
    CASE((cfg.features = IRC_FEATURE_SH, cfg.irr.detail_pixels = -1.0f), IRC_ERR_CONFIG);
    CASE(cfg.sh.channels = 1, IRC_ERR_CONFIG);
    CASE(cfg.irr.min_pixels = NAN, IRC_ERR_CONFIG);
    CASE(cfg.irr.min_pixels = -INFINITY, IRC_ERR_CONFIG);
    CASE(cfg.irr.max_pixels = INFINITY, IRC_ERR_CONFIG);
    CASE(cfg.irr.full_pixels = -INFINITY, IRC_ERR_CONFIG);
    CASE(cfg.irr.detail_pixels = -INFINITY, IRC_ERR_CONFIG);
    CASE((cfg.strata_theta = 1, cfg.strata_phi = 4097), IRC_ERR_CONFIG);
    CHECK(n <= (int)(sizeof cases / sizeof cases[0]), "%d cases", n);
#undef CASE
    (void)cases;
    cfg = scene_config(&sky, 0, 0, 0);
    CHECK(irc_footprint(NULL, 16, &bytes) == IRC_ERR_NULL, "null cfg");
    CHECK(irc_footprint(&cfg, 16, NULL) == IRC_ERR_NULL, "null out");
    CHECK(irc_footprint(&cfg, 0, &bytes) == IRC_ERR_CONFIG, "zero records");
    CHECK(irc_footprint(&cfg, IRC_MAX_RECORDS + 1u, &bytes) == IRC_ERR_CONFIG,
          "records past IRC_MAX_RECORDS");
    /* Every library code has a text of its own: not the host-code text,
     * not the unknown-status text, and no two alike. */
    for (i = IRC_ERR_LAST; i <= IRC_DETAIL; i++) {
        int j;
        CHECK(irc_strerror(i) != NULL && *irc_strerror(i), "strerror %d", i);
        CHECK(strcmp(irc_strerror(i), irc_strerror(IRC_ERR_LAST - 1)) != 0 &&
                  strcmp(irc_strerror(i), irc_strerror(IRC_DETAIL + 1)) != 0,
              "strerror %d is a fallback: %s", i, irc_strerror(i));
        for (j = IRC_ERR_LAST; j < i; j++)
            CHECK(strcmp(irc_strerror(i), irc_strerror(j)) != 0, "strerror %d = %d", i, j);
    }
    CHECK(strcmp(irc_strerror(-1000), irc_strerror(IRC_ERR_LAST - 1)) == 0, "host codes");
    CHECK(strcmp(irc_strerror(1000), irc_strerror(-1000)) != 0, "unknown positive status");
}

/* A cache pays only for what it enables; the compile-time bound holds.
 * Bytes: 32 head, 16 per gradient, 8 for the Hessian's ellipse, 8 for the
 * leak guard with cfg.irr.leak_guard. */
TEST(test_footprints)
{
    static const uint32_t feats[] = {
        0, IRC_FEATURE_TRANSLATION, IRC_FEATURE_ROTATION,
        IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION,
        IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN, 0,
        IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN};
    static const int noguard[] = {0, 0, 0, 0, 0, 1, 1};
    static const size_t want[] = {40, 56, 56, 72, 80, 32, 72};
    size_t i, b0, b1;
    sky_init();
    for (i = 0; i < sizeof want / sizeof want[0]; i++) {
        irc_config cfg = scene_config(&sky, feats[i], 8, 16);
        irc_cache *c;
        irc_stats st;
        cfg.irr.leak_guard = noguard[i] ? IRC_OFF : IRC_ON;
        c = block_cache(&cfg, 1000, 0);
        CHECK(c && irc_cache_stats(c, &st) == IRC_OK, "stats");
        CHECK(st.record_bytes == want[i], "record bytes %zu, want %zu", st.record_bytes, want[i]);
        CHECK(st.bytes_total <= cfg.buffer_size, "total %zu of %zu", st.bytes_total, cfg.buffer_size);
        irc_footprint(&cfg, 1000, &b0);
        irc_footprint(&cfg, 2000, &b1);
        CHECK(b1 > b0, "footprint grows with records");
        block_free(&cfg);
    }
    {
        static const uint32_t recs[] = {1, 100, 100000};
        static const uint32_t str[][2] = {{1, 1}, {16, 64}, {256, 256}};
        size_t a, b, t;
        for (a = 0; a < 3; a++)
            for (b = 0; b < 3; b++)
                for (t = 1; t <= 64; t *= 8) {
                    irc_config cfg = scene_config(&sky, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION,
                                                  str[b][0], str[b][1]);
                    size_t bytes;
                    cfg.threads = (uint32_t)t;
                    cfg.max_batch = 4096;
                    cfg.evict = IRC_EVICT_CLOCK;
                    CHECK(irc_footprint(&cfg, recs[a], &bytes) == IRC_OK, "footprint");
                    CHECK(bytes <= IRC_FOOTPRINT_BOUND(cfg.features, recs[a], str[b][0] * str[b][1], t, 4096),
                          "bound %zu < %zu",
                          (size_t)IRC_FOOTPRINT_BOUND(cfg.features, recs[a], str[b][0] * str[b][1], t, 4096),
                          bytes);
                }
    }
}

/* What a zeroed config gives: both gradients (64-byte records: no leak
 * guard), neighbour clamping, and from the _px call reaches a R in [2.5,
 * 15] pixels; each can be asked away. */
TEST(test_defaults)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_stats st;
    irc_record r, back;
    const float n[3] = {0, 0, 1}, far[3] = {6, 6, 0}, under[3] = {0.1f, 0, 0};
    float rgb[3], w;
    int k;
    scene_sphere_plane(&s);
    for (k = 0; k < 2; k++) {
        memset(&cfg, 0, sizeof cfg);
        cfg.version = IRC_CONFIG_VERSION;
        cfg.trace = scene_trace;
        cfg.context = &s;
        cfg.strata_theta = 8;
        cfg.strata_phi = 32;
        if (k)
            cfg.features = IRC_FEATURE_NONE;
        c = block_cache(&cfg, 64, 0);
        CHECK(c && irc_cache_stats(c, &st) == IRC_OK, "init");
        if (!c) return;
        CHECK(st.record_bytes == (k ? 32u : 64u), "record bytes %zu", st.record_bytes);
        CHECK(irc_record_compute(c, far, n, &r, NULL) == IRC_OK &&
                  r.features == (k ? 0u : (uint32_t)(IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION)),
              "features %u", r.features);
        /* reach 15 pixels of 0.01: R = 15 x 0.01 / 0.2 where every ray
         * escapes (open sky: the record saw nothing that bounds it) */
        CHECK(irc_cache_lookup_or_compute_px(c, far, n, NULL, 0.01f, rgb, &w, NULL) == IRC_OK &&
                  irc_cache_record(c, 0, &back) == IRC_OK && fabsf(back.radius - 0.75f) < 1e-5f,
              "max: radius %g", (double)back.radius);
        /* no lower bound: under the sphere, with pixels of 1, the record
         * keeps its own radius (about 1, which a 2.5-pixel floor would
         * have lifted to 12.5), the plain call's */
        {
            float own = -1.0f;
            CHECK(irc_cache_clear(c) == IRC_OK &&
                      irc_cache_lookup_or_compute(c, under, n, rgb, &w, NULL) == IRC_OK &&
                      irc_cache_record(c, 0, &back) == IRC_OK && (own = back.radius) < 2.0f,
                  "plain: radius %g", (double)own);
            CHECK(irc_cache_clear(c) == IRC_OK &&
                      irc_cache_lookup_or_compute_px(c, under, n, NULL, 1.0f, rgb, &w, NULL) == IRC_OK &&
                      irc_cache_record(c, 0, &back) == IRC_OK && back.radius == own,
                  "min: radius %g, own %g", (double)back.radius, (double)own);
        }
        block_free(&cfg);
    }
    CHECK((cfg.features = IRC_FEATURE_NONE | IRC_FEATURE_TRANSLATION,
           irc_footprint(&cfg, 16, &st.bytes_total)) == IRC_ERR_CONFIG, "NONE with a gradient");
    /* clamping: a wide record beside a narrow one is held to 1 + 0.5 */
    for (k = 0; k < 2; k++) {
        memset(&cfg, 0, sizeof cfg);
        cfg.version = IRC_CONFIG_VERSION;
        cfg.trace = scene_trace;
        cfg.context = &s;
        cfg.clamp_neighbours = k ? IRC_OFF : IRC_DEFAULT;
        c = block_cache(&cfg, 8, 0);
        CHECK(c != NULL, "init");
        if (!c) return;
        disk_record(&r, 1.0f, 1.0f);
        CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
        r.p[0] = 0.5f;
        r.radius = 10.0f;
        CHECK(irc_cache_insert(c, &r) == IRC_OK && irc_cache_record(c, 1, &back) == IRC_OK &&
                  back.radius == (k ? 10.0f : 1.5f),
              "%s: radius %g", k ? "off" : "default", (double)back.radius);
        block_free(&cfg);
    }
    /* no pixel bounds: the floor's own radius under the sphere */
    memset(&cfg, 0, sizeof cfg);
    cfg.version = IRC_CONFIG_VERSION;
    cfg.trace = scene_trace;
    cfg.context = &s;
    cfg.strata_theta = 8;
    cfg.strata_phi = 32;
    cfg.irr.min_pixels = -1.0f;
    c = block_cache(&cfg, 8, 0);
    CHECK(c && irc_cache_lookup_or_compute_px(c, under, n, NULL, 1.0f, rgb, &w, NULL) == IRC_OK &&
              irc_cache_record(c, 0, &back) == IRC_OK && back.radius < 2.0f,
          "no bound: radius %g", c ? (double)back.radius : 0.0);
    block_free(&cfg);
}

/* Too small a block: IRC_ERR_NOMEM and not a byte written; any alignment
 * works. */
TEST(test_init_block)
{
    irc_config cfg;
    irc_cache *c;
    size_t bytes, off;
    unsigned char *mem;
    sky_init();
    cfg = scene_config(&sky, IRC_FEATURE_TRANSLATION, 8, 16);
    irc_footprint(&cfg, 100, &bytes);
    mem = malloc(bytes + 64);
    memset(mem, 0x5a, bytes + 64);
    cfg.buffer = mem;
    cfg.buffer_size = bytes - 1;
    CHECK(irc_init(&cfg, 100, &c) == IRC_ERR_NOMEM, "too small");
    for (off = 0; off < bytes + 64; off++)
        if (mem[off] != 0x5a)
            break;
    CHECK(off == bytes + 64, "block touched at %zu", off);
    cfg.buffer = NULL;
    cfg.buffer_size = bytes;
    CHECK(irc_init(&cfg, 100, &c) == IRC_ERR_NULL, "null buffer");
    CHECK(irc_init(&cfg, 100, NULL) == IRC_ERR_NULL, "null out");
    for (off = 1; off < 64; off += 7) {
        const float p[3] = {0.5f, 0, 0}, n[3] = {0, 0, 1};
        float rgb[3];
        cfg.buffer = mem + off;
        cfg.buffer_size = bytes;
        memset(mem, 0x5a, bytes + 64);
        CHECK(irc_init(&cfg, 100, &c) == IRC_OK, "init at offset %zu", off);
        CHECK(irc_cache_lookup_or_compute(c, p, n, rgb, NULL, NULL) == IRC_OK, "works at offset %zu", off);
        CHECK(mem[off - 1] == 0x5a && mem[off + bytes] == 0x5a, "stays inside at offset %zu", off);
        irc_fini(c);
    }
    free(mem);
}

/* Every rejected call leaves the block byte for byte as it was, and
 * nothing is written past it. */
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

/* Every port runs the same small workload to the same result. */
TEST(test_ports)
{
    const irc_port *ports[] = {&irc_port_posix, &irc_port_c11, &irc_port_none, NULL};
    float first[3] = {0, 0, 0};
    size_t i;
    for (i = 0; i < 4; i++) {
        irc_config cfg;
        irc_cache *c;
        float rgb[3], sum[3] = {0, 0, 0};
        unsigned long long st = 5;
        int k;
        sky_init();
        cfg = scene_config(&sky, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 16);
        cfg.port = ports[i];
        c = block_cache(&cfg, 256, GUARD);
        CHECK(c != NULL, "init with port %zu", i);
        if (!c) continue;
        for (k = 0; k < 300; k++) {
            float p[3] = {(float)(xrand(&st) * 4 - 2), (float)(xrand(&st) * 4 - 2), 0.0f};
            const float n[3] = {0, 0, 1};
            CHECK(irc_cache_lookup_or_compute(c, p, n, rgb, NULL, NULL) >= 0, "lookup");
            sum[0] += rgb[0];
        }
        if (i == 0)
            first[0] = sum[0];
        CHECK(sum[0] == first[0], "port %zu: %g vs %g", i, sum[0], first[0]);
        CHECK(irc_fini(c) == IRC_OK, "fini");
        CHECK(block_guard_ok(&cfg, GUARD), "guard");
        block_free(&cfg);
    }
}

/* The runtime version is the header's, and the number encodes the string
 * (each part below 100, so the encoding is one to one). */
TEST(test_version)
{
    unsigned a = 999, b = 999, c = 999;
    char tail = 0;
    CHECK(irc_version_number() == IRC_VERSION_NUMBER, "number %u", irc_version_number());
    CHECK(strcmp(irc_version_string(), IRC_VERSION_STRING) == 0, "string %s",
          irc_version_string());
    CHECK(sscanf(irc_version_string(), "%u.%u.%u%c", &a, &b, &c, &tail) == 3, "form %s",
          irc_version_string());
    CHECK(a == IRC_VERSION_MAJOR && b == IRC_VERSION_MINOR && c == IRC_VERSION_PATCH &&
              b < 100 && c < 100 && a * 10000 + b * 100 + c == irc_version_number(),
          "%u.%u.%u", a, b, c);
}
