/* t_config.c -- a config that cannot be misread: the version field that
 * refuses initialisers written for other versions, and the resolved config
 * read back (irc_cache_config) against the header's documented rules. */
#define IRC_EXPERIMENTAL /* irc_join */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"
#include "test.h"

/* The positional initialisers of earlier versions compile against this
 * header only with a pointer-to-integer diagnostic (gcc, clang: on by
 * default); silenced here so that the refusal at run time can be held. */
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wint-conversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wmissing-braces"
#pragma GCC diagnostic ignored "-Wincompatible-pointer-types"
#endif
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wliteral-conversion"
#endif
static irc_config old_03(void)
{
    /* 0.3: trace, context, max_batch, features, accuracy, min_radius,
     * max_radius, ..., strata 2.5 x 15 read as 2 x 15 */
    irc_config c = {scene_trace, NULL, 64, 0, 0.2f, 0, 0, 2.5f, 15.0f};
    return c;
}

static irc_config old_04(tscene *s)
{
    /* 0.4: trace, context, max_batch, features, accuracy, min_radius,
     * max_radius, strata_theta, strata_phi, threads */
    irc_config c = {scene_trace, s, 1, 0, 0.2f, 0.0f, 0.0f, 16, 64, 1};
    return c;
}
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

/* Every call that takes a config refuses it and touches nothing (the
 * block; join's view is not read before the config is checked). */
static void refused(irc_config cfg, const char *what)
{
    unsigned char *block = (unsigned char *)malloc(1u << 20), *copy = (unsigned char *)malloc(1u << 20);
    irc_cache *c = NULL;
    size_t bytes = 7;
    if (!block || !copy) {
        free(block);
        free(copy);
        CHECK(0, "out of memory");
        return;
    }
    memset(block, 0xa5, 1u << 20);
    memcpy(copy, block, 1u << 20);
    cfg.buffer = block;
    cfg.buffer_size = 1u << 20;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_VERSION && bytes == 7, "%s: footprint",
          what);
    CHECK(irc_init(&cfg, 16, &c) == IRC_ERR_VERSION && !c, "%s: init", what);
    CHECK(irc_attach(&cfg, &c) == IRC_ERR_VERSION && !c, "%s: attach", what);
    {
        static double view[IRC_VIEW_BYTES / sizeof(double) + 1];
        CHECK(irc_join(&cfg, view, sizeof view, &c) == IRC_ERR_VERSION && !c, "%s: join", what);
    }
    CHECK(memcmp(block, copy, 1u << 20) == 0, "%s: block touched", what);
    free(block);
    free(copy);
}

TEST(test_config_version)
{
    tscene s;
    irc_config cfg = IRC_CONFIG_INIT, named = {.version = IRC_CONFIG_VERSION, .trace = scene_trace};
    size_t bytes;
    scene_sphere_plane(&s);
    refused(old_03(), "0.3 positional");
    refused(old_04(&s), "0.4 positional");
    memset(&cfg, 0, sizeof cfg);
    cfg.trace = scene_trace;
    refused(cfg, "zeroed");
    cfg.version = (uint32_t)sizeof cfg;
    refused(cfg, "sizeof");
    cfg.version = IRC_CONFIG_VERSION ^ 1u; /* another version of the struct */
    refused(cfg, "another size");
    /* the one way in, positional or by name */
    cfg = (irc_config)IRC_CONFIG_INIT;
    cfg.trace = scene_trace;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_OK, "IRC_CONFIG_INIT");
    CHECK(irc_footprint(&named, 16, &bytes) == IRC_OK, "designated");
    CHECK(irc_strerror(IRC_ERR_VERSION) && strstr(irc_strerror(IRC_ERR_VERSION), "config"),
          "the status names the config: %s", irc_strerror(IRC_ERR_VERSION));
}

/* What the header documents for a field left at 0 (irc_config's
 * comments), written out here rather than taken from the library. */
typedef struct {
    float a;          /* accuracy given (0: default) */
    uint32_t features;
    uint32_t m, n;    /* strata expected */
} rule_row;

static void check_defaults(const irc_config *r, const rule_row *row)
{
    const int sh = (row->features & (IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT)) != 0;
    const float a = row->a > 0.0f ? row->a : 0.2f;
    CHECK(r->version == IRC_CONFIG_VERSION, "version");
    CHECK(r->accuracy == a, "a %g: accuracy %g", (double)a, (double)r->accuracy);
    CHECK(r->strata_theta == row->m && r->strata_phi == row->n, "a %g features %u: %u x %u, want %u x %u",
          (double)a, row->features, r->strata_theta, r->strata_phi, row->m, row->n);
    CHECK(r->max_batch == 1 && r->threads == 1 && r->no_wait == 0 && r->evict == IRC_EVICT_NONE,
          "batch %u threads %u", r->max_batch, r->threads);
    CHECK(r->min_radius == 0.0f && r->max_radius == IRC_RADIUS_CAP, "radii %g %g",
          (double)r->min_radius, (double)r->max_radius);
    CHECK(r->port == irc_port_default && r->seed == 0, "port, seed");
    if (sh) {
        const uint32_t want = row->features & IRC_FEATURE_SH_GRADIENT
                                  ? (uint32_t)(IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT)
                                  : row->features;
        CHECK(r->features == want, "SH features %u", r->features);
        CHECK(r->clamp_neighbours == IRC_OFF && r->check_visibility == IRC_OFF, "SH switches %u %u",
              r->clamp_neighbours, r->check_visibility);
        CHECK(r->sh.bands == 3 && r->sh.channels == 3 && r->sh.power == 2.0f, "SH fields");
        CHECK(r->irr.blend == 0.0f && r->irr.max_pixels == 0.0f, "irradiance fields in SH");
        return;
    }
    CHECK(r->features == (row->features ? row->features
                                        : (uint32_t)(IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION)),
          "features %u", r->features);
    CHECK(r->clamp_neighbours == IRC_ON && r->check_visibility == IRC_ON, "switches %u %u",
          r->clamp_neighbours, r->check_visibility);
    CHECK(r->irr.leak_guard == IRC_OFF && r->irr.supersamples == 0, "guard %u", r->irr.leak_guard);
    CHECK(r->irr.blend == 2.0f, "blend %g", (double)r->irr.blend);
    CHECK(r->irr.min_pixels == -1.0f && r->irr.max_pixels == 15.0f, "pixels %g %g",
          (double)r->irr.min_pixels, (double)r->irr.max_pixels);
    CHECK(r->irr.detail_pixels == 0.5f && r->irr.full_pixels == -1.0f, "detail %g full %g",
          (double)r->irr.detail_pixels, (double)r->irr.full_pixels);
    CHECK(r->sh.bands == 0 && r->sh.channels == 0 && r->sh.power == 0.0f, "SH fields in irradiance");
}

/* Field by field: the struct has padding. */
static int same_config(const irc_config *a, const irc_config *b)
{
    return a->version == b->version && a->trace == b->trace && a->context == b->context &&
           a->max_batch == b->max_batch && a->features == b->features &&
           a->accuracy == b->accuracy && a->min_radius == b->min_radius &&
           a->max_radius == b->max_radius && a->strata_theta == b->strata_theta &&
           a->strata_phi == b->strata_phi && a->threads == b->threads &&
           a->no_wait == b->no_wait && a->evict == b->evict &&
           a->clamp_neighbours == b->clamp_neighbours &&
           a->check_visibility == b->check_visibility &&
           a->irr.supersamples == b->irr.supersamples && a->irr.leak_guard == b->irr.leak_guard &&
           a->irr.min_pixels == b->irr.min_pixels && a->irr.max_pixels == b->irr.max_pixels &&
           a->irr.full_pixels == b->irr.full_pixels &&
           a->irr.detail_pixels == b->irr.detail_pixels && a->irr.blend == b->irr.blend &&
           a->sh.bands == b->sh.bands && a->sh.channels == b->sh.channels &&
           a->sh.power == b->sh.power && a->seed == b->seed && a->port == b->port &&
           a->buffer == b->buffer && a->buffer_size == b->buffer_size;
}

/* Read back, the config makes the same cache: the same footprint and the
 * same config read back again. */
static void check_round_trip(irc_config *r, uint32_t records, size_t bytes, const char *what)
{
    irc_config again;
    irc_cache *c;
    size_t b2 = 0;
    CHECK(irc_footprint(r, records, &b2) == IRC_OK && b2 == bytes, "%s: footprint %zu, was %zu",
          what, b2, bytes);
    r->buffer = NULL;
    r->buffer_size = 0;
    c = block_cache(r, records, 0);
    CHECK(c && irc_cache_config(c, &again) == IRC_OK, "%s: init from read-back", what);
    if (!c)
        return;
    CHECK(again.buffer == r->buffer && again.buffer_size == r->buffer_size, "%s: block", what);
    CHECK(same_config(&again, r), "%s: read back twice differs", what);
    block_free(r);
}

TEST(test_config_read_back)
{
    /* strata: M = 8 from a = 0.375, 16 from 0.25, 32 from 0.125, 64 below
     * 0.125, 128 below 0.0625 (and smaller), N = 4 M; SH 16 x 64 */
    static const rule_row rows[] = {
        {0.0f, 0, 32, 128},    {0.45f, 0, 8, 32},     {0.375f, 0, 8, 32},
        {0.3f, 0, 16, 64},     {0.25f, 0, 16, 64},    {0.2f, 0, 32, 128},
        {0.125f, 0, 32, 128},  {0.1f, 0, 64, 256},    {0.0625f, 0, 64, 256},
        {0.05f, 0, 128, 512},  {0.001f, 0, 128, 512}, {0.2f, IRC_FEATURE_TRANSLATION, 32, 128},
        {0.4f, IRC_FEATURE_SH, 16, 64},               {0.0f, IRC_FEATURE_SH_GRADIENT, 16, 64},
        {0.2f, IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN, 32, 128}};
    tscene s;
    irc_config cfg, r;
    irc_cache *c;
    size_t bytes;
    unsigned i;
    scene_sphere_plane(&s);
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        cfg = (irc_config)IRC_CONFIG_INIT;
        cfg.trace = scene_trace;
        cfg.context = &s;
        cfg.accuracy = rows[i].a;
        cfg.features = rows[i].features;
        CHECK(irc_footprint(&cfg, 32, &bytes) == IRC_OK, "row %u", i);
        c = block_cache(&cfg, 32, 0);
        CHECK(c && irc_cache_config(c, &r) == IRC_OK, "row %u: read back", i);
        if (!c)
            continue;
        CHECK(r.trace == scene_trace && r.context == &s && r.buffer == cfg.buffer &&
                  r.buffer_size == cfg.buffer_size,
              "row %u: the host's pointers", i);
        check_defaults(&r, &rows[i]);
        block_free(&cfg);
        check_round_trip(&r, 32, bytes, "defaults");
    }
    /* What the host set, as it set it or as implied: bare records by
     * name, VISIBILITY with TRANSLATION, a batch no larger than the grid,
     * a default max_pixels no less than min_pixels, "none" as -1. */
    cfg = scene_config(&s, IRC_FEATURE_NONE, 4, 4);
    cfg.max_batch = 64;
    cfg.threads = 3;
    cfg.irr.leak_guard = IRC_ON;
    cfg.irr.min_pixels = 40.0f;
    cfg.irr.detail_pixels = -7.0f;
    cfg.irr.blend = 1.0f;
    cfg.max_radius = 9.0f;
    CHECK(irc_footprint(&cfg, 32, &bytes) == IRC_OK, "set");
    c = block_cache(&cfg, 32, 0);
    CHECK(c && irc_cache_config(c, &r) == IRC_OK, "set: read back");
    if (c) {
        CHECK(r.features == IRC_FEATURE_NONE && r.max_batch == 16 && r.threads == 3,
              "features %u batch %u threads %u", r.features, r.max_batch, r.threads);
        CHECK(r.irr.leak_guard == IRC_ON && r.clamp_neighbours == IRC_OFF &&
                  r.check_visibility == IRC_OFF, "switches as set");
        CHECK(r.irr.min_pixels == 40.0f && r.irr.max_pixels == 40.0f && r.irr.detail_pixels == -1.0f &&
                  r.irr.blend == 1.0f && r.max_radius == 9.0f,
              "pixels %g %g detail %g", (double)r.irr.min_pixels, (double)r.irr.max_pixels,
              (double)r.irr.detail_pixels);
        block_free(&cfg);
        check_round_trip(&r, 32, bytes, "set");
    }
    cfg = scene_config(&s, IRC_FEATURE_VISIBILITY, 4, 8);
    c = block_cache(&cfg, 8, 0);
    CHECK(c && irc_cache_config(c, &r) == IRC_OK &&
              r.features == (IRC_FEATURE_VISIBILITY | IRC_FEATURE_TRANSLATION),
          "VISIBILITY implies TRANSLATION: %u", c ? r.features : 0u);
    CHECK(!c || irc_cache_config(c, NULL) == IRC_ERR_NULL, "NULL out");
    CHECK(irc_cache_config(NULL, &r) == IRC_ERR_NULL, "NULL cache");
    if (c)
        block_free(&cfg);
}
