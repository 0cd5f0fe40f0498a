/* t_detail.c -- records that cost what they serve (cfg.irr.full_pixels):
 * the _px call samples a coarse grid first and refines it, keeping its
 * rays, so that a refined record holds exactly one sample in every stratum
 * of the finer grid; a record serving few pixels stays coarse and still
 * meets the closed form; the plain call and the switch's off position
 * keep the full grid. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"
#include "scenes.h"
#include "test.h"

/* Counts, per stratum of an M x N grid around +z, the directions the
 * callback was asked to cast.  For n = +z the library's frame is t1 = +x,
 * t2 = +y (Duff et al.), so stratum (j, k) holds sin^2(theta) in [j/M,
 * (j+1)/M) and phi = atan2(y, x) in [2 pi k/N, 2 pi (k+1)/N). */
typedef struct detail_host {
    tscene s;           /* first: scene_trace reads the context as a tscene */
    uint32_t m, n;
    uint32_t *count;    /* m * n */
    uint32_t rays, outside;
} detail_host;

static int detail_trace(const irc_trace_args *a)
{
    detail_host *h = (detail_host *)a->context;
    uint32_t i;
    for (i = 0; i < a->count && !a->visibility_only; i++) {
        const float *d = a->rays[i].dir;
        double s2 = (double)d[0] * d[0] + (double)d[1] * d[1], phi = atan2(d[1], d[0]);
        long j, k;
        if (phi < 0.0)
            phi += 2.0 * TPI;
        j = (long)floor(s2 * h->m);
        k = (long)floor(phi / (2.0 * TPI) * h->n);
        h->rays++;
        if (j < 0 || j >= (long)h->m || k < 0 || k >= (long)h->n || d[2] <= 0.0f)
            h->outside++;
        else
            h->count[j * (long)h->n + k]++;
    }
    return scene_trace(a);
}

static irc_cache *detail_cache(detail_host *h, irc_config *cfg, float full_pixels)
{
    memset(h, 0, sizeof *h);
    scene_sphere_plane(&h->s);
    h->m = 16;
    h->n = 64;
    h->count = calloc(16 * 64, sizeof *h->count);
    *cfg = scene_config(&h->s, 0, 16, 64);
    cfg->trace = detail_trace;
    cfg->max_batch = 48; /* batches that straddle rows and levels */
    cfg->irr.min_pixels = -1.0f;
    cfg->irr.max_pixels = -1.0f;
    cfg->check_visibility = IRC_OFF;
    cfg->irr.full_pixels = full_pixels;
    cfg->irr.detail_pixels = -1.0f; /* the probes are not the grid's rays */
    return block_cache(cfg, 64, 0);
}

/* A record whose radius spans many pixels is refined to the configured
 * grid: 1,024 rays, one in each of the 16 x 64 strata.  Without the
 * refinement's placement (a pilot sample put in the wrong finer stratum,
 * or its rays cast again) some stratum holds two or none. */
TEST(test_detail_refined_strata)
{
    detail_host h;
    irc_config cfg;
    irc_cache *c = detail_cache(&h, &cfg, 32.0f);
    const float p[3] = {0.3f, -0.2f, 0.0f}, n[3] = {0, 0, 1};
    float rgb[3], w;
    uint32_t i, empty = 0, twice = 0;
    double e;
    CHECK(c != NULL, "init");
    if (!c) {
        free(h.count);
        return;
    }
    /* footprint 1e-4: a radius of ~1 spans ~10^4 pixels */
    CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, 1e-4f, rgb, &w, &h) == IRC_OK && w == 0.0f,
          "compute");
    for (i = 0; i < h.m * h.n; i++) {
        empty += h.count[i] == 0;
        twice += h.count[i] > 1;
    }
    CHECK(h.rays == 1024 && h.outside == 0 && empty == 0 && twice == 0,
          "rays %u (1024), outside %u, empty strata %u, doubled %u", h.rays, h.outside, empty,
          twice);
    {
        const double pd[3] = {p[0], p[1], p[2]};
        e = sphere_plane_e(&h.s, pd);
    }
    CHECK(fabs(rgb[0] - e) < 0.01 * e, "E %g, closed form %g", rgb[0], e);
    block_free(&cfg);
    free(h.count);
}

/* The same record with the switch off: the full grid sampled at once (the
 * same count, other draws); the plain call (no pixel) and the default
 * likewise. */
TEST(test_detail_full_grid_paths)
{
    detail_host h;
    irc_config cfg;
    irc_cache *c = detail_cache(&h, &cfg, -1.0f);
    const float p[3] = {0.3f, -0.2f, 0.0f}, n[3] = {0, 0, 1};
    float rgb[3], w;
    CHECK(c != NULL, "init");
    if (!c) {
        free(h.count);
        return;
    }
    uint32_t i, empty = 0, twice = 0;
    CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, 10.0f, rgb, &w, &h) == IRC_OK &&
              h.rays == 1024, "off: %u rays", h.rays);
    for (i = 0; i < h.m * h.n; i++) {
        empty += h.count[i] == 0;
        twice += h.count[i] > 1;
    }
    CHECK(empty == 0 && twice == 0, "full grid: empty strata %u, doubled %u", empty, twice);
    block_free(&cfg);
    free(h.count);
    c = detail_cache(&h, &cfg, 32.0f);
    CHECK(c != NULL && irc_cache_lookup_or_compute(c, p, n, rgb, &w, &h) == IRC_OK &&
              h.rays == 1024, "plain call: %u rays", h.rays);
    block_free(&cfg);
    free(h.count);
    /* the default (0) is off: a record 2 pixels wide still takes 1,024 */
    c = detail_cache(&h, &cfg, 0.0f);
    CHECK(c != NULL && irc_cache_lookup_or_compute_px(c, p, n, NULL, 0.5f, rgb, &w, &h) == IRC_OK &&
              h.rays == 1024, "default: %u rays", h.rays);
    block_free(&cfg);
    free(h.count);
}

/* Records under the sphere (radius ~1.2) with a footprint of 0.5 span a
 * few pixels: they stay on the coarsest grid, 4 x 16 (64 rays, a
 * sixteenth), and their irradiance still meets the closed form on average
 * (the estimator is unbiased on any grid): the mean relative error of 100
 * records within four standard errors of their own spread. */
TEST(test_detail_coarse_records)
{
    detail_host h;
    irc_config cfg;
    irc_cache *c = detail_cache(&h, &cfg, 32.0f);
    const float n[3] = {0, 0, 1};
    double sum = 0.0, sum2 = 0.0, mean, sd;
    uint32_t i, coarse = 0, total = 100;
    CHECK(c != NULL, "init");
    if (!c) {
        free(h.count);
        return;
    }
    for (i = 0; i < total; i++) {
        const float p[3] = {(float)(i % 10) * 0.05f - 0.25f, (float)(i / 10) * 0.05f - 0.25f, 0.0f};
        const double pd[3] = {p[0], p[1], 0.0};
        float rgb[3], w;
        irc_record r;
        double e = sphere_plane_e(&h.s, pd), rel;
        CHECK(irc_cache_clear(c) == IRC_OK, "clear");
        h.rays = 0;
        CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, 0.5f, rgb, &w, &h) == IRC_OK, "compute");
        CHECK(irc_cache_record(c, 0, &r) == IRC_OK, "record");
        if (h.rays == 64) {
            /* its radius below full_pixels / 2 = 16 pixels of 0.5, with room
             * for the pilot's noise */
            CHECK(r.minor_radius < 16.0f * 0.5f, "coarse record's radius %g", r.minor_radius);
            coarse++;
        }
        CHECK(h.rays == 64 || h.rays == 256 || h.rays == 1024, "rays %u", h.rays);
        rel = rgb[0] / e - 1.0;
        sum += rel;
        sum2 += rel * rel;
    }
    mean = sum / total;
    sd = sqrt((sum2 / total - mean * mean) / (total - 1));
    printf("  %u of %u records on the coarsest grid; mean relative error %+.4f, its sd %.4f\n",
           coarse, total, mean, sd);
    CHECK(coarse == total, "only %u coarse records", coarse);
    CHECK(fabs(mean) < 4.0 * sd + 1e-4, "biased: %+.4f (sd %.4f)", mean, sd);
    block_free(&cfg);
    free(h.count);
}

/* full_pixels and detail_pixels must be finite; negative means off. */
TEST(test_detail_config)
{
    tscene s;
    irc_config cfg;
    size_t bytes;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, 0, 0, 0);
    cfg.irr.full_pixels = INFINITY;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_CONFIG, "inf accepted");
    cfg.irr.full_pixels = NAN;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_CONFIG, "nan accepted");
    cfg.irr.full_pixels = -3.0f;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_OK, "negative refused");
    cfg.irr.detail_pixels = INFINITY;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_CONFIG, "detail inf accepted");
    cfg.irr.detail_pixels = NAN;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_CONFIG, "detail nan accepted");
    cfg.irr.detail_pixels = -2.0f;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_OK, "detail negative refused");
    cfg = scene_config(&s, IRC_FEATURE_SH, 0, 0);
    cfg.irr.full_pixels = 8.0f;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_CONFIG, "an SH cache took an irradiance field");
    /* "Finite": every finite pixel count, FLT_MAX too */
    cfg = scene_config(&s, 0, 0, 0);
    cfg.irr.full_pixels = FLT_MAX;
    cfg.irr.detail_pixels = 1e38f;
    cfg.irr.min_pixels = 1e30f;
    cfg.irr.max_pixels = FLT_MAX;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_OK, "finite pixel counts >= 2^100 refused");
    cfg.irr.min_pixels = -FLT_MAX;
    cfg.irr.full_pixels = -FLT_MAX;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_OK, "-FLT_MAX refused");
    cfg.irr.min_pixels = 1e38f; /* both past the cap, max below min */
    cfg.irr.max_pixels = 1e35f;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_CONFIG, "max_pixels < min_pixels accepted");
    {
        /* past the cap acts as the cap: a floor of 1e38 pixels of 1e-30
         * gives the reach of IRC_RADIUS_CAP pixels (R = 6.3 at a = 0.2),
         * not 5e8 */
        static const float floors[2] = {1e38f, IRC_RADIUS_CAP};
        const float p[3] = {0.5f, 0.25f, 0.0f}, n[3] = {0, 0, 1};
        float radius[2] = {0, 0}, rgb[3], w;
        int k;
        for (k = 0; k < 2; k++) {
            irc_cache *c;
            irc_record rec;
            cfg = scene_config(&s, 0, 8, 32);
            cfg.irr.min_pixels = floors[k];
            cfg.irr.max_pixels = -1.0f; /* unbounded: the floor alone decides */
            cfg.irr.detail_pixels = -1.0f;
            c = block_cache(&cfg, 16, 0);
            CHECK(c && irc_cache_lookup_or_compute_px(c, p, n, NULL, 1e-30f, rgb, &w, NULL) == IRC_OK &&
                      irc_cache_record(c, 0, &rec) == IRC_OK,
                  "floor %g", (double)floors[k]);
            radius[k] = c ? rec.radius : 0.0f;
            block_free(&cfg);
        }
        CHECK(radius[0] == radius[1] && radius[0] > 5.0f && radius[0] < 8.0f,
              "radius %g with 1e38, %g with the cap", (double)radius[0], (double)radius[1]);
    }
    /* full_pixels: "Not with VISIBILITY, HESSIAN or supersamples" */
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN, 0, 0);
    cfg.irr.full_pixels = 8.0f;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_CONFIG, "full_pixels with HESSIAN accepted");
    cfg.irr.full_pixels = -1.0f;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_OK, "full_pixels off with HESSIAN refused");
    cfg = scene_config(&s, IRC_FEATURE_VISIBILITY, 0, 0);
    cfg.irr.full_pixels = 8.0f;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_CONFIG, "full_pixels with VISIBILITY accepted");
    cfg = scene_config(&s, 0, 0, 0);
    cfg.irr.full_pixels = 8.0f;
    cfg.irr.supersamples = 4;
    CHECK(irc_footprint(&cfg, 16, &bytes) == IRC_ERR_CONFIG, "full_pixels with supersamples accepted");
}
