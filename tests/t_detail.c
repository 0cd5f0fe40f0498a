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

/* Intersects the ray from the origin through (x, y, 1) with the plane
 * through q of normal m. */
static void on_plane(double x, double y, const double q[3], const double m[3], double out[3])
{
    const double d[3] = {x, y, 1.0};
    double t = (q[0] * m[0] + q[1] * m[1] + q[2] * m[2]) / (d[0] * m[0] + d[1] * m[1] + d[2] * m[2]);
    int i;
    for (i = 0; i < 3; i++)
        out[i] = t * d[i];
}

/* irc_pixel_footprint against the area a pixel really covers: a camera at
 * the origin looking along +z, pixels of width s on the plane z = 1; the
 * pixel's corners cast onto the tilted surface span |dp/dx x dp/dy|, whose
 * square root is the footprint (differences of 1e-3 pixels, so the
 * parallelogram is the pixel's to 1e-3).  Then the grazing clamp, the
 * sign of n, and the refusals. */
TEST(test_pixel_footprint)
{
    const float eye[3] = {0, 0, 0}, fwd[3] = {0, 0, 2}, s = 0.004f;
    float fp = -1.0f, worst = 0.0f;
    int i;
    for (i = 0; i < 200; i++) {
        /* pixels across a 70-degree view, surfaces tilted up to 80 degrees */
        const double x = -0.7 + 1.4 * ((i * 37) % 200) / 200.0, y = -0.5 + (i % 20) / 20.0;
        const double dist = 0.5 + 0.1 * i, h = 1e-3 * s, len = sqrt(x * x + y * y + 1.0);
        const double tilt = 1.4 * ((i * 13) % 100) / 100.0, az = 0.7 * i;
        double m[3], q[3], a[3], b[3], c0[3], u[3], v[3], w[3], area, back[3];
        float p[3], n[3];
        int k;
        for (k = 0; k < 3; k++)
            back[k] = -(k == 0 ? x : k == 1 ? y : 1.0) / len;
        /* the normal: the direction back to the eye turned by tilt */
        {
            double t1[3] = {back[1], -back[0], 0.0}, l1 = sqrt(t1[0] * t1[0] + t1[1] * t1[1]);
            double t2[3];
            for (k = 0; k < 3; k++)
                t1[k] /= l1;
            t2[0] = back[1] * t1[2] - back[2] * t1[1];
            t2[1] = back[2] * t1[0] - back[0] * t1[2];
            t2[2] = back[0] * t1[1] - back[1] * t1[0];
            for (k = 0; k < 3; k++)
                m[k] = cos(tilt) * back[k] + sin(tilt) * (cos(az) * t1[k] + sin(az) * t2[k]);
        }
        for (k = 0; k < 3; k++)
            q[k] = -back[k] * dist;
        on_plane(x, y, q, m, c0);
        on_plane(x + h, y, q, m, a);
        on_plane(x, y + h, q, m, b);
        for (k = 0; k < 3; k++) {
            u[k] = (a[k] - c0[k]) / 1e-3;
            v[k] = (b[k] - c0[k]) / 1e-3;
            p[k] = (float)c0[k];
            n[k] = (float)(i % 2 ? m[k] : -m[k]); /* either side */
        }
        w[0] = u[1] * v[2] - u[2] * v[1];
        w[1] = u[2] * v[0] - u[0] * v[2];
        w[2] = u[0] * v[1] - u[1] * v[0];
        area = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        CHECK(irc_pixel_footprint(eye, fwd, s, p, n, &fp) == IRC_OK, "call %d", i);
        if (fabs(fp / sqrt(area) - 1.0) > worst)
            worst = (float)fabs(fp / sqrt(area) - 1.0);
    }
    printf("  200 pixels: worst relative difference from the cast pixel %.2e\n", worst);
    CHECK(worst < 2e-3, "footprint off by %g", worst);
    {
        /* grazing: |d.n| = 0.01 gives the footprint of 0.05 */
        const float p[3] = {0, 0, 5}, n1[3] = {0, 0.99995f, 0.01f}, n2[3] = {0, 0.99875f, 0.05f};
        float f1, f2;
        CHECK(irc_pixel_footprint(eye, fwd, s, p, n1, &f1) == IRC_OK &&
                  irc_pixel_footprint(eye, fwd, s, p, n2, &f2) == IRC_OK &&
                  fabsf(f1 / f2 - 1.0f) < 1e-3f,
              "grazing %g against %g", f1, f2);
    }
    {
        const float p[3] = {0, 0, 5}, n[3] = {0, 0, 1}, behind[3] = {0, 0, -5}, zero[3] = {0, 0, 0};
        const float bad[3] = {0, NAN, 5};
        fp = 7.0f;
        CHECK(irc_pixel_footprint(NULL, fwd, s, p, n, &fp) == IRC_ERR_NULL, "null eye");
        CHECK(irc_pixel_footprint(eye, fwd, s, p, n, NULL) == IRC_ERR_NULL, "null out");
        CHECK(irc_pixel_footprint(eye, fwd, s, bad, n, &fp) == IRC_ERR_NONFINITE, "nan p");
        CHECK(irc_pixel_footprint(eye, fwd, INFINITY, p, n, &fp) == IRC_ERR_NONFINITE, "inf angle");
        CHECK(irc_pixel_footprint(eye, fwd, s, p, zero, &fp) == IRC_ERR_NORMAL, "zero normal");
        CHECK(irc_pixel_footprint(eye, fwd, 0.0f, p, n, &fp) == IRC_ERR_RANGE, "zero angle");
        CHECK(irc_pixel_footprint(eye, zero, s, p, n, &fp) == IRC_ERR_RANGE, "zero forward");
        CHECK(irc_pixel_footprint(eye, fwd, s, eye, n, &fp) == IRC_ERR_RANGE, "p at eye");
        CHECK(irc_pixel_footprint(eye, fwd, s, behind, n, &fp) == IRC_ERR_RANGE, "behind");
        CHECK(irc_pixel_footprint(eye, NULL, s, p, n, &fp) == IRC_ERR_NULL, "null forward");
        CHECK(irc_pixel_footprint(eye, fwd, s, NULL, n, &fp) == IRC_ERR_NULL, "null p");
        CHECK(irc_pixel_footprint(eye, fwd, s, p, NULL, &fp) == IRC_ERR_NULL, "null n");
        CHECK(irc_pixel_footprint(bad, fwd, s, p, n, &fp) == IRC_ERR_NONFINITE, "nan eye");
        CHECK(irc_pixel_footprint(eye, bad, s, p, n, &fp) == IRC_ERR_NONFINITE, "nan forward");
        CHECK(irc_pixel_footprint(eye, fwd, NAN, p, n, &fp) == IRC_ERR_NONFINITE, "nan angle");
        CHECK(irc_pixel_footprint(eye, fwd, s, p, bad, &fp) == IRC_ERR_NORMAL, "nan normal");
        CHECK(irc_pixel_footprint(eye, fwd, -s, p, n, &fp) == IRC_ERR_RANGE, "negative angle");
        CHECK(fp == 7.0f, "a refused call wrote %g", fp);
    }
}

/* The header's "forward (any length)" and any n not zero: scaling forward
 * or n by any finite non-zero factor, and moving p and the eye together
 * by any finite amount, leaves the footprint as it was; p k times farther
 * along the same ray gives k times the footprint, until float overflows
 * (IRC_ERR_NONFINITE then, nothing written). */
TEST(test_pixel_footprint_lengths)
{
    const float eye[3] = {0, 0, 0}, fwd[3] = {0.1f, 0.2f, 2.0f}, s = 0.004f;
    const float p[3] = {0.5f, -0.3f, 4.0f}, n[3] = {0.2f, 0.3f, -0.9f};
    static const float scales[] = {1e-38f, 1e-30f, 1e-19f, 1e-10f, 1e10f, 1e19f, 1e30f, 1.5e38f};
    float base, fp;
    unsigned i;
    int k;
    CHECK(irc_pixel_footprint(eye, fwd, s, p, n, &base) == IRC_OK && base > 0.0f, "base call");
    for (i = 0; i < sizeof scales / sizeof scales[0]; i++) {
        float f2[3], n2[3];
        for (k = 0; k < 3; k++) {
            f2[k] = fwd[k] * scales[i];
            n2[k] = n[k] * scales[i];
        }
        fp = -1.0f;
        CHECK(irc_pixel_footprint(eye, f2, s, p, n, &fp) == IRC_OK && fabsf(fp / base - 1.0f) < 1e-5f,
              "forward x %g: %g against %g", (double)scales[i], (double)fp, (double)base);
        fp = -1.0f;
        CHECK(irc_pixel_footprint(eye, fwd, s, p, n2, &fp) == IRC_OK && fabsf(fp / base - 1.0f) < 1e-5f,
              "n x %g: %g against %g", (double)scales[i], (double)fp, (double)base);
    }
    {
        /* p and the eye far from the origin, and p far from the eye */
        const float far_eye[3] = {1e25f, -1e25f, 3e25f};
        float fp_far = -1.0f, p2[3], p3[3], e3[3];
        for (k = 0; k < 3; k++) {
            p2[k] = p[k] * 1e30f;
            e3[k] = -1e38f * fwd[k] / fwd[2];
            p3[k] = 1e38f * fwd[k] / fwd[2];
        }
        CHECK(irc_pixel_footprint(eye, fwd, s, p2, n, &fp_far) == IRC_OK &&
                  fabsf(fp_far / (base * 1e30f) - 1.0f) < 1e-5f,
              "p at 1e30: %g against %g", (double)fp_far, (double)base * 1e30);
        for (k = 0; k < 3; k++)
            p2[k] = far_eye[k] + p[k] * 1e22f;
        CHECK(irc_pixel_footprint(far_eye, fwd, s, p2, n, &fp_far) == IRC_OK &&
                  fabsf(fp_far / (base * 1e22f) - 1.0f) < 1e-3f,
              "eye at 1e25: %g against %g", (double)fp_far, (double)base * 1e22);
        /* 2e38 from the eye along forward: finite; pixel_angle 1e3 makes
         * the footprint overflow */
        fp = 7.0f;
        CHECK(irc_pixel_footprint(e3, fwd, s, p3, n, &fp) == IRC_OK && fp > 0.0f && fp < FLT_MAX,
              "p 2e38 from the eye: %g", (double)fp);
        fp = 7.0f;
        CHECK(irc_pixel_footprint(e3, fwd, 1e3f, p3, n, &fp) == IRC_ERR_NONFINITE && fp == 7.0f,
              "overflowing footprint");
    }
}

/* The header's rule for a point seen through a flat mirror: the unfolded
 * path gives the footprint the point would have if the mirror image were
 * seen directly.  Camera at the origin along +z (tilted), a mirror in the
 * plane z = 5 facing the camera, a surface point p in front of it at z =
 * 3 (its image p' at z = 7).  With forward reflected the two agree; with
 * forward = d the footprint is wider by at most 1/(d0.f)^(3/2). */
TEST(test_pixel_footprint_mirror)
{
    const float eye[3] = {0, 0, 0}, fwd[3] = {0.1f, -0.05f, 1.0f}, s = 0.003f;
    const float img[3] = {0.8f, 0.5f, 7.0f}, n_img[3] = {0.3f, -0.2f, -0.93f};
    float p[3], n[3], d[3], d0[3], eye2[3], fwd_r[3], direct, folded, along_d, len0, len1, L, dn;
    int k;
    /* the mirror image of p' and n' across z = 5 */
    for (k = 0; k < 3; k++) {
        p[k] = img[k];
        n[k] = n_img[k];
        fwd_r[k] = fwd[k];
    }
    p[2] = 10.0f - img[2];
    n[2] = -n_img[2];
    fwd_r[2] = -fwd[2];
    /* the camera ray hits the mirror at t0; the reflected ray reaches p */
    len0 = 5.0f / img[2];
    for (k = 0; k < 3; k++)
        d0[k] = img[k];
    L = sqrtf(d0[0] * d0[0] + d0[1] * d0[1] + d0[2] * d0[2]); /* |p' - eye| */
    len1 = L * (1.0f - len0);
    for (k = 0; k < 3; k++) {
        const float hit = img[k] * len0;
        d[k] = (p[k] - hit) / len1;
    }
    for (k = 0; k < 3; k++)
        eye2[k] = p[k] - L * d[k];
    CHECK(irc_pixel_footprint(eye, fwd, s, img, n_img, &direct) == IRC_OK, "direct");
    CHECK(irc_pixel_footprint(eye2, fwd_r, s, p, n, &folded) == IRC_OK, "folded");
    CHECK(irc_pixel_footprint(eye2, d, s, p, n, &along_d) == IRC_OK, "along d");
    CHECK(fabsf(folded / direct - 1.0f) < 1e-4f, "unfolded %g against direct %g", (double)folded,
          (double)direct);
    dn = (d0[0] * fwd[0] + d0[1] * fwd[1] + d0[2] * fwd[2]) /
         (L * sqrtf(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]));
    CHECK(along_d >= direct * (1.0f - 1e-5f) && along_d <= direct / (dn * sqrtf(dn)) * (1.0f + 1e-4f),
          "forward = d: %g outside [%g, %g]", (double)along_d, (double)direct,
          (double)(direct / (dn * sqrtf(dn))));
}

/* Per-pixel detail (cfg.irr.detail_pixels) in the box-plane scene made a
 * wall: a black slab 0.5 high along y standing on z = 0 at x in [0, 0.2],
 * under a uniform sky.  Beside its face, E = pi (1 - F) with F the face's
 * form factor (box_plane_e), falling toward pi/2 at the face.  One hand
 * record at x = -0.3 with a reach over everything stands for the records
 * a renderer makes a few pixels from the wall. */
static irc_cache *wall_cache(tscene *s, irc_config *cfg, float detail, uint32_t batch,
                             irc_trace_fn trace)
{
    static const double lo[3] = {0.0, -5.0, 0.0}, hi[3] = {0.2, 5.0, 0.5};
    const double at[3] = {-0.3, 0.0, 0.0};
    irc_record r;
    irc_cache *c;
    scene_box_plane(s);
    memcpy(s->box_lo, lo, sizeof lo);
    memcpy(s->box_hi, hi, sizeof hi);
    *cfg = scene_config(s, 0, 16, 64);
    cfg->check_visibility = IRC_OFF;
    cfg->max_batch = batch;
    cfg->irr.detail_pixels = detail;
    if (trace)
        cfg->trace = trace;
    c = block_cache(cfg, 16, 0);
    if (!c)
        return NULL;
    disk_record(&r, (float)box_plane_e(s, at), 2.0f);
    r.p[0] = -0.3f;
    if (irc_cache_insert(c, &r) != IRC_OK) {
        block_free(cfg);
        return NULL;
    }
    return c;
}

/* 32 _px calls at distance delta from the wall (footprint 0.01): the mean
 * of their errors against the closed form (*mean) over its standard error,
 * and the largest weight reported. */
static double wall_z(irc_cache *c, const tscene *s, double delta, double *wmax, int *bad,
                     double *mean, int *details)
{
    const float n[3] = {0, 0, 1};
    double sum = 0.0, sq = 0.0, m, var;
    int i;
    *wmax = 0.0;
    *bad = 0;
    *details = 0;
    for (i = 0; i < 32; i++) {
        const float p[3] = {(float)-delta, -0.5f + (float)i / 32.0f, 0.0f};
        const double q[3] = {p[0], p[1], 0.0};
        float rgb[3], w = -1.0f;
        double d;
        const int st = irc_cache_lookup_or_compute_px(c, p, n, NULL, 0.01f, rgb, &w, NULL);
        if (st != IRC_OK && st != IRC_DETAIL)
            (*bad)++;
        *details += st == IRC_DETAIL;
        d = rgb[0] - box_plane_e(s, q);
        sum += d;
        sq += d * d;
        if (w > *wmax)
            *wmax = w;
    }
    *mean = m = sum / 32.0;
    var = (sq / 32.0 - m * m) / 31.0;
    return var > 0.0 ? m / sqrt(var) : (m == 0.0 ? 0.0 : 1e9);
}

/* Near the wall (the probe toward it hits within 4 pixels) the _px call
 * answers from the point's own 16 x 64 strata: unbiased against the closed
 * form, weight 0, nothing stored; farther out the record answers.  With
 * detail off the record (0.79 above the truth at the wall) and records
 * computed among the calls answer, more than 0.25 (16% of E) above the
 * truth on average: what the switch is for. */
TEST(test_detail_pixels_wall)
{
    tscene s;
    irc_config cfg;
    irc_stats st;
    irc_cache *c = wall_cache(&s, &cfg, 4.0f, 8, NULL);
    double z, wmax, mean;
    int bad, details;
    CHECK(c != NULL, "init");
    if (!c)
        return;
    z = wall_z(c, &s, 0.005, &wmax, &bad, &mean, &details);
    CHECK(bad == 0 && details == 32, "%d calls failed, %d of 32 said IRC_DETAIL", bad, details);
    CHECK(fabs(z) < 4.0, "near the wall: mean error %.2f standard errors from pi (1 - F)", z);
    CHECK(wmax == 0.0, "a detail answer reported weight %g", wmax);
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records == 1 && st.computes == 0,
          "detail answers stored or computed records (%llu, %llu)",
          (unsigned long long)st.records, (unsigned long long)st.computes);
    /* 32 calls of 8 probes (one batch) and 16 x 64 strata each */
    CHECK(st.rays == 32u * (8u + 1024u), "rays %llu", (unsigned long long)st.rays);
    CHECK(st.lookups == 32 && st.hits == 0 && st.details == 32, "lookups %llu, hits %llu, "
          "details %llu", (unsigned long long)st.lookups, (unsigned long long)st.hits,
          (unsigned long long)st.details);
    /* 0.2 from the face: the probe hits at 0.23, beyond 4 x 0.01 */
    z = wall_z(c, &s, 0.2, &wmax, &bad, &mean, &details);
    CHECK(bad == 0 && wmax > 0.0 && details == 0,
          "away from the wall the record did not answer (weight %g, %d details)", wmax, details);
    block_free(&cfg);

    c = wall_cache(&s, &cfg, -1.0f, 8, NULL);
    CHECK(c != NULL, "init (off)");
    if (!c)
        return;
    z = wall_z(c, &s, 0.005, &wmax, &bad, &mean, &details);
    CHECK(bad == 0 && wmax > 0.0 && mean > 0.25 && details == 0,
          "off: the record should answer at the wall, far above the truth (mean error %.3f, "
          "weight %g)", mean, wmax);
    block_free(&cfg);
}

/* With one ray a trace call, probes stop at the first that hits (the one
 * toward the wall comes first): 1 + 1,024 rays.  A callback error in a probe
 * returns as a record's would, nothing counted; a negative footprint is
 * refused before any probe; an estimate past FLT_MAX is refused; a call
 * that fails after its probes counts none of them.  The zero config's
 * reach is half a pixel. */
TEST(test_detail_pixels_calls)
{
    tscene s;
    irc_config cfg;
    irc_stats st;
    irc_cache *c = wall_cache(&s, &cfg, 4.0f, 1, NULL);
    const float p[3] = {-0.005f, 0.0f, 0.0f}, n[3] = {0, 0, 1};
    float rgb[3] = {7, 7, 7}, w;
    CHECK(c != NULL, "init");
    if (!c)
        return;
    CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, 0.01f, rgb, &w, NULL) == IRC_DETAIL, "call");
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.rays == 1025, "rays %llu",
          (unsigned long long)st.rays);
    s.return_code = -77;
    CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, 0.01f, rgb, &w, NULL) == -77,
          "the host's error lost");
    s.return_code = 0;
    CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, -0.01f, rgb, &w, NULL) == IRC_ERR_RANGE,
          "negative footprint");
    CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, NAN, rgb, &w, NULL) == IRC_ERR_NONFINITE,
          "NaN footprint");
    CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, INFINITY, rgb, &w, NULL) == IRC_ERR_NONFINITE,
          "infinite footprint");
    /* negative and not finite: not finite comes first (irrcache.h) */
    CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, -INFINITY, rgb, &w, NULL) == IRC_ERR_NONFINITE,
          "-inf footprint");
    /* a sky so bright that 1,024 strata sum past FLT_MAX: refused, as a
     * record of it would be */
    s.sky_a[0] = s.sky_a[1] = s.sky_a[2] = 3e37f;
    CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, 0.01f, rgb, &w, NULL) == IRC_ERR_NONFINITE,
          "an estimate past float answered");
    s.sky_a[0] = s.sky_a[1] = s.sky_a[2] = 1.0f;
    /* x = -1: no probe hits within reach and the record does not reach, so
     * a record is computed, and its first ray (the 9th) is refused: the
     * call fails, and its 8 probes are counted nowhere */
    {
        const float far[3] = {-1.0f, 0.0f, 0.0f};
        s.fail_every = 9;
        s.fail_kind = FAIL_BAD_STATUS;
        s.calls = 0;
        CHECK(irc_cache_lookup_or_compute_px(c, far, n, NULL, 0.01f, rgb, &w, NULL) ==
                  IRC_ERR_CALLBACK,
              "a refused ray after the probes");
        s.fail_every = 0;
    }
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.rays == 1025 && st.lookups == 1 &&
              st.records == 1,
          "refused calls counted (rays %llu, lookups %llu)", (unsigned long long)st.rays,
          (unsigned long long)st.lookups);
    block_free(&cfg);

    /* The default, half a pixel (0.005 here): the probe toward the wall
     * hits at 0.00115 from x = -0.001 (detail: 1 + 1,024 rays) and at
     * 0.0115 from x = -0.01 (all 8 probes, then the record answers). */
    c = wall_cache(&s, &cfg, 0.0f, 1, NULL);
    CHECK(c != NULL, "init (default)");
    if (!c)
        return;
    {
        const float near[3] = {-0.001f, 0.0f, 0.0f}, off[3] = {-0.01f, 0.0f, 0.0f};
        CHECK(irc_cache_lookup_or_compute_px(c, near, n, NULL, 0.01f, rgb, &w, NULL) == IRC_DETAIL &&
                  irc_cache_stats(c, &st) == IRC_OK && st.rays == 1025 && w == 0.0f,
              "default, near: rays %llu, weight %g", (unsigned long long)st.rays, w);
        CHECK(irc_cache_lookup_or_compute_px(c, off, n, NULL, 0.01f, rgb, &w, NULL) == IRC_OK &&
                  irc_cache_stats(c, &st) == IRC_OK && st.rays == 1025 + 8 && w > 0.0f,
              "default, a pixel off: rays %llu, weight %g", (unsigned long long)st.rays, w);
    }
    block_free(&cfg);
}

/* The probes reach the callback flagged (visibility_only =
 * IRC_VISIBILITY_PROBE: only status and dist read), so a host need not
 * shade them: one that writes NaN normals and radiances for them gets
 * the same detail answer, and the estimate's own rays come unflagged. */
static struct {
    uint32_t probe_calls, probe_rays, other_flag, plain_rays;
} probe_seen;

static int probe_trace(const irc_trace_args *a)
{
    uint32_t i;
    const int st = scene_trace(a);
    if (a->visibility_only == IRC_VISIBILITY_PROBE) {
        probe_seen.probe_calls++;
        probe_seen.probe_rays += a->count;
        for (i = 0; i < a->count; i++) {
            a->hits[i].normal[0] = a->hits[i].normal[1] = a->hits[i].normal[2] = NAN;
            a->hits[i].radiance[0] = a->hits[i].radiance[1] = a->hits[i].radiance[2] = NAN;
        }
    } else if (a->visibility_only) {
        probe_seen.other_flag++;
    } else {
        probe_seen.plain_rays += a->count;
    }
    return st;
}

TEST(test_detail_probes_flagged)
{
    tscene s;
    irc_config cfg;
    const float near[3] = {-0.001f, 0.0f, 0.0f}, off[3] = {-0.01f, 0.0f, 0.0f}, n[3] = {0, 0, 1};
    float rgb[3], w = -1.0f;
    irc_cache *c = wall_cache(&s, &cfg, 0.0f, 8, probe_trace);
    memset(&probe_seen, 0, sizeof probe_seen);
    CHECK(c != NULL, "init");
    if (!c)
        return;
    /* near the wall: 8 probes in one flagged call, then 16 x 64 plain rays */
    CHECK(irc_cache_lookup_or_compute_px(c, near, n, NULL, 0.01f, rgb, &w, NULL) == IRC_DETAIL &&
              w == 0.0f && rgb[0] > 0.0f && rgb[0] < 4.0f,
          "near: weight %g, E %g", w, rgb[0]);
    CHECK(probe_seen.probe_calls == 1 && probe_seen.probe_rays == 8 &&
              probe_seen.plain_rays == 1024 && probe_seen.other_flag == 0,
          "near: %u flagged calls of %u rays, %u plain rays, %u other flags",
          probe_seen.probe_calls, probe_seen.probe_rays, probe_seen.plain_rays,
          probe_seen.other_flag);
    /* a pixel off: the probes alone, flagged, then the record answers */
    memset(&probe_seen, 0, sizeof probe_seen);
    CHECK(irc_cache_lookup_or_compute_px(c, off, n, NULL, 0.01f, rgb, &w, NULL) == IRC_OK && w > 0.0f,
          "off: weight %g", w);
    CHECK(probe_seen.probe_rays == 8 && probe_seen.plain_rays == 0,
          "off: %u flagged rays, %u plain", probe_seen.probe_rays, probe_seen.plain_rays);
    block_free(&cfg);
}

/* A _px call from inside the cache's own callback, at a point its record
 * covers: the probes cannot take a slot (IRC_ERR_NESTED), so the record
 * answers, as it would without detail. */
typedef struct nest_host {
    tscene s; /* first: scene_trace reads the context as a tscene */
    irc_cache *c;
    int status, depth;
} nest_host;

static int nest_trace(const irc_trace_args *a)
{
    nest_host *h = (nest_host *)a->context;
    if (h->depth == 0) {
        const float p[3] = {-0.3f, 0.1f, 0.0f}, n[3] = {0, 0, 1};
        float rgb[3], w;
        h->depth = 1;
        h->status = irc_cache_lookup_or_compute_px(h->c, p, n, NULL, 0.01f, rgb, &w, NULL);
    }
    return scene_trace(a);
}

TEST(test_detail_pixels_nested)
{
    nest_host h;
    irc_config cfg;
    irc_cache *c;
    const float q[3] = {-1.5f, 0.0f, 0.0f}, n[3] = {0, 0, 1};
    float rgb[3], w;
    memset(&h, 0, sizeof h);
    /* the context is &h.s, which is &h */
    c = wall_cache(&h.s, &cfg, 4.0f, 8, nest_trace);
    CHECK(c != NULL, "init");
    if (!c)
        return;
    h.c = c;
    h.status = 1;
    CHECK(irc_cache_lookup_or_compute_px(c, q, n, NULL, 0.01f, rgb, &w, &h) == IRC_OK, "outer call");
    CHECK(h.status == IRC_OK, "the nested call at a covered point returned %d", h.status);
    block_free(&cfg);
}
