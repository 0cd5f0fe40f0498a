/* t_api.c -- config checks, footprints, defaults, the block, ports, the version. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
