/* t_reach.c -- what a record reaches: ellipses, leak guard, gradients, pixel bounds. */
#include <math.h>
#include <string.h>

#include "irr/estimator.h"
#include "scenes.h"
#include "test.h"

/* A cache for records built by hand (a = 0.5, 4 x 4 strata that no test
 * casts), and a record at the origin facing +z with E e and radius rad. */
static irc_cache *hand_cache(tscene *s, irc_config *cfg, uint32_t features, irc_record *r,
                             float e, float rad)
{
    irc_cache *c;
    scene_init(s);
    *cfg = scene_config(s, features, 4, 4);
    cfg->accuracy = 0.5f;
    cfg->irr.blend = 1.0f; /* Ward's 1/e within a R, whose closed forms these tests write */
    cfg->irr.leak_guard = 1; /* kept for the guard's test; the others' records carry none */
    c = block_cache(cfg, 8, 0);
    disk_record(r, e, rad);
    return c;
}

/* A corner record (E = 1.55, |grad E| = 146, as a real render made one)
 * whose radius something else lifted (min_radius, the host): the gradient
 * is scaled down to the radius, so a lookup at the edge of reach stays
 * within E (1 + a) instead of extrapolating to 36.6 (0.1 did). */
TEST(test_gradient_within_reach)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_record r, back;
    const float q[3] = {0.24f, 0.0f, 0.0f}, n[3] = {0, 0, 1};
    float rgb[3], w;
    double g;
    int st;
    c = hand_cache(&s, &cfg, IRC_FEATURE_TRANSLATION, &r, 1.55f, 0.5f); /* reach 0.25 */
    CHECK(c != NULL, "init");
    if (!c) return;
    r.grad_t[0][0] = r.grad_t[1][0] = r.grad_t[2][0] = 146.0f;
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
    st = irc_cache_lookup(c, q, n, rgb, &w);
    printf("  lookup 0.24 from the record: %.3f (E 1.55, unclamped extrapolation %.2f)\n",
           rgb[0], 1.55 + 146.0 * 0.24);
    CHECK(st == IRC_OK && rgb[0] <= 1.55f * 1.5f + 1e-4f, "lookup %g", rgb[0]);
    CHECK(irc_cache_record(c, 0, &back) == IRC_OK, "read");
    g = sqrt((double)back.grad_t[0][0] * back.grad_t[0][0] + back.grad_t[0][1] * back.grad_t[0][1] +
             back.grad_t[0][2] * back.grad_t[0][2]);
    CHECK(fabs(g * 0.5 - 1.55) < 1e-3, "stored |grad| R = %g, want E", g * 0.5);
    /* A gradient already within reach is kept. */
    r.grad_t[0][0] = 2.0f;
    r.p[0] = 10.0f;
    CHECK(irc_cache_insert(c, &r) == IRC_OK && irc_cache_record(c, 1, &back) == IRC_OK, "second");
    CHECK(fabs(back.grad_t[0][0] - 2.0f) < 1e-3f, "kept %g", back.grad_t[0][0]);
    block_free(&cfg);
}

/* Ellipses a host builds (major radius 1 along x, minor 0.25, a = 0.5):
 * the weight is 1/e with e the distance on the ellipse, a lookup 0.4 along
 * the major axis is served and 0.2 across is not (a disk of 1 would take
 * both); read back gives the ellipse; a bad axis or minor radius is refused
 * and leaves the cache as it was; minor/major below 1/IRC_ANISOTROPY is
 * stored at 1/IRC_ANISOTROPY; the gradient is limited on the ellipse. */
TEST(test_ellipse_records)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_record r, back;
    irc_stats st;
    const float n[3] = {0, 0, 1}, along[3] = {0.4f, 0.0f, 0.0f}, across[3] = {0.0f, 0.2f, 0.0f},
                near[3] = {0.0f, 0.1f, 0.0f}, diag[3] = {0.2f, 0.08f, 0.0f};
    float rgb[3], w;
    c = hand_cache(&s, &cfg, IRC_FEATURE_TRANSLATION | IRC_FEATURE_HESSIAN, &r, 1.0f, 1.0f);
    CHECK(c != NULL, "init");
    if (!c) return;
    r.minor_radius = 0.25f;
    r.axis[0] = 2.0f;   /* not unit, and tilted out of the plane: projected */
    r.axis[2] = 0.5f;
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
    CHECK(irc_cache_lookup(c, along, n, rgb, &w) == IRC_OK && fabs(w - 1.0 / 0.4) < 1e-3,
          "along the major axis: weight %g, want %g", w, 1.0 / 0.4);
    CHECK(irc_cache_lookup(c, near, n, rgb, &w) == IRC_OK && fabs(w - 0.25 / 0.1) < 1e-3,
          "across: weight %g, want %g", w, 0.25 / 0.1);
    /* (0.2/1)^2 + (0.08/0.25)^2 = 0.1424: e = 0.3774 */
    CHECK(irc_cache_lookup(c, diag, n, rgb, &w) == IRC_OK &&
              fabs(w - 1.0 / sqrt(0.04 + 0.1024)) < 1e-3,
          "oblique: weight %g, want %g", w, 1.0 / sqrt(0.04 + 0.1024));
    CHECK(irc_cache_lookup(c, across, n, rgb, &w) == IRC_MISS, "0.2 across is beyond 0.5 x 0.25");
    CHECK(irc_cache_record(c, 0, &back) == IRC_OK, "read");
    CHECK(fabs(back.radius - 1.0f) < 1e-6f && fabs(back.minor_radius - 0.25f) < 1e-6f &&
              fabs(back.axis[0] - 1.0f) < 1e-3f && fabs(back.axis[1]) < 1e-3f &&
              fabs(back.axis[2]) < 1e-3f,
          "read back R %g r %g axis %g %g %g", back.radius, back.minor_radius, back.axis[0],
          back.axis[1], back.axis[2]);
    /* Refused, nothing stored: an axis along the normal, a negative or
     * non-finite minor radius, a non-finite axis. */
    r.p[0] = 5.0f;
    r.axis[0] = 0.0f;
    CHECK(irc_cache_insert(c, &r) == IRC_ERR_RANGE, "axis along n");
    r.axis[0] = 1.0f;
    r.minor_radius = -0.5f;
    CHECK(irc_cache_insert(c, &r) == IRC_ERR_RANGE, "negative minor radius");
    r.minor_radius = NAN;
    CHECK(irc_cache_insert(c, &r) == IRC_ERR_NONFINITE, "NaN minor radius");
    r.minor_radius = 0.25f;
    r.axis[1] = INFINITY;
    CHECK(irc_cache_insert(c, &r) == IRC_ERR_NONFINITE, "infinite axis");
    CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records == 1, "%llu records after refusals",
          (unsigned long long)st.records);
    /* minor/major 0.01 is stored as 1/IRC_ANISOTROPY; the gradient along
     * the minor axis (y) may reach E over the minor radius only */
    r.axis[1] = 0.0f;
    r.minor_radius = 0.01f;
    r.grad_t[0][1] = 8.0f; /* 8 x 0.25 = 2 > E = 1: scaled to 4 */
    r.grad_t[1][0] = 0.8f; /* along the major axis: 0.8 x 1 <= 1, kept */
    CHECK(irc_cache_insert(c, &r) == IRC_OK && irc_cache_record(c, 1, &back) == IRC_OK, "second");
    CHECK(fabs(back.minor_radius - 1.0f / IRC_ANISOTROPY) < 1e-6f, "minor %g, want %g",
          back.minor_radius, 1.0 / IRC_ANISOTROPY);
    CHECK(fabs(back.grad_t[0][1] - 4.0f) < 1e-3f && fabs(back.grad_t[1][0] - 0.8f) < 1e-4f,
          "gradients %g (want 4), %g (want 0.8)", back.grad_t[0][1], back.grad_t[1][0]);
    block_free(&cfg);
}

/* An axis of any finite length is a direction: near FLT_MAX its squared
 * length overflowed, and the packed axis came from 0/0 (a UBSan report in
 * the octahedral code; fuzz_api, corpus crash-ellipse-huge-axis); near
 * FLT_MIN it underflowed and the record was refused. */
TEST(test_ellipse_axis_range)
{
    /* in the plane: x, x, y (the fuzzer's: its square overflowed) */
    static const float axes[3][3] = {{3e38f, 0.0f, 3e38f}, {1e-38f, 0.0f, 1e-38f},
                                     {2.0f, 1.18e38f, 0.0f}};
    static const float want[3][2] = {{1.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_record r, back;
    int k;
    c = hand_cache(&s, &cfg, IRC_FEATURE_TRANSLATION | IRC_FEATURE_HESSIAN, &r, 1.0f, 1.0f);
    CHECK(c != NULL, "init");
    if (!c) return;
    r.minor_radius = 0.25f;
    for (k = 0; k < 3; k++) {
        int got;
        r.p[0] = 3.0f * (float)k;
        memcpy(r.axis, axes[k], sizeof r.axis);
        got = irc_cache_insert(c, &r);
        memset(&back, 0, sizeof back);
        CHECK(got == IRC_OK && irc_cache_record(c, (uint32_t)k, &back) == IRC_OK &&
                  fabs(back.axis[0] - want[k][0]) < 1e-3f && fabs(back.axis[1] - want[k][1]) < 1e-3f,
              "axis %g %g %g: status %d, read back %g %g %g", axes[k][0], axes[k][1], axes[k][2],
              got, back.axis[0], back.axis[1], back.axis[2]);
    }
    block_free(&cfg);
}

/* The leak guard by hand: irc__sector against atan2 away from sector
 * edges; a record (R 1, a 0.5: reach 0.5, n = z so t1 = x) whose sectors
 * 15, 0 and 1 (-22.5 to 45 degrees) say geometry at 5/15 of the reach
 * (nibble 10: inverse distance 3 reaches) serves a lookup when t times the
 * inverse distance, interpolated between the two nearest sector centres
 * (11.25 + 22.5 k degrees), stays within 1, t = distance / reach. */
TEST(test_leak_guard_by_hand)
{
    static const struct { double deg, dist; int ok; } q[] = {
        {11.25, 0.15, 1},  /* centre of 0: 0.3 x 3 = 0.9 */
        {11.25, 0.18, 0},  /* 0.36 x 3 = 1.08 */
        {0.0, 0.2, 0},     /* between 15 and 0, both 3: 1.2 */
        {33.75, 0.18, 0},  /* centre of 1: 1.08 */
        {45.0, 0.18, 1},   /* halfway to sector 2 (nothing): 0.36 x 1.5 */
        {56.25, 0.45, 1},  /* centre of 2 */
        {-11.25, 0.15, 1}, /* centre of 15: 0.9 */
        {-11.25, 0.2, 0},
        {-33.75, 0.2, 1},  /* centre of 14: nothing */
        {180.0, 0.4, 1}};
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_record r, back;
    const float n[3] = {0, 0, 1};
    float rgb[3], w;
    unsigned long long rng = 12345;
    int i, bad = 0;
    for (i = 0; i < 100000; i++) {
        double ang = 2.0 * TPI * xrand(&rng), pos = ang / (TPI / 8.0);
        if (fabs(pos - floor(pos + 0.5)) < 1e-6)
            continue;
        bad += irc__sector(cos(ang), sin(ang)) != (int)floor(pos) % 16;
    }
    CHECK(bad == 0, "%d directions in the wrong sector", bad);
    c = hand_cache(&s, &cfg, IRC_FEATURE_TRANSLATION, &r, 1.0f, 1.0f);
    CHECK(c != NULL, "init");
    if (!c) return;
    r.leak_guard = 10ull | 10ull << 4 | 10ull << 60;
    CHECK(irc_cache_insert(c, &r) == IRC_OK && irc_cache_record(c, 0, &back) == IRC_OK &&
              back.leak_guard == r.leak_guard, "guard stored");
    for (i = 0; i < (int)(sizeof q / sizeof q[0]); i++) {
        const double rad = q[i].deg * TPI / 180.0;
        const float p[3] = {(float)(q[i].dist * cos(rad)), (float)(q[i].dist * sin(rad)), 0.0f};
        int st = irc_cache_lookup(c, p, n, rgb, &w);
        CHECK(st == (q[i].ok ? IRC_OK : IRC_MISS), "lookup at %g degrees, %g: %d, want %s",
              q[i].deg, q[i].dist, st, q[i].ok ? "served" : "rejected");
    }
    block_free(&cfg);
}

/* The screen-space bound: with a footprint f, computed records have both
 * reaches a R in [min_pixels f, max_pixels f], so radii in [5 f / 0.5,
 * 10 f / 0.5] (here [10 f, 20 f] for f = 0.05
 * and 0.2: the floor's own radii, 1.2 under the sphere and more away from
 * it, meet both bounds), a lifted record's gradient stays within reach, footprint 0
 * is the plain call, and a bad footprint is refused with the cache as it
 * was. */
TEST(test_screen_bound)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_stats st0, st1;
    irc_record r;
    const float n[3] = {0, 0, 1};
    float rgb[3], w;
    uint32_t i, lifted = 0, capped = 0, free_r = 0;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION | IRC_FEATURE_HESSIAN,
                       8, 32);
    cfg.accuracy = 0.5f;
    cfg.irr.min_pixels = 5.0f;
    cfg.irr.max_pixels = 10.0f;
    c = block_cache(&cfg, 4096, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (i = 0; i < 400; i++) {
        const float p[3] = {(float)(i % 20) * 0.3f - 3.0f, (float)(i / 20) * 0.3f - 3.0f, 0.0f};
        const float fp = i < 200 ? 0.05f : 0.2f;
        CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, fp, rgb, &w, NULL) >= 0, "query %u", i);
    }
    CHECK(irc_cache_stats(c, &st0) == IRC_OK && st0.records > 10, "records %llu",
          (unsigned long long)st0.records);
    for (i = 0; i < st0.records; i++) {
        double lo, hi, g;
        int ch;
        CHECK(irc_cache_record(c, i, &r) == IRC_OK, "read %u", i);
        /* which footprint made it: the lower rows used 0.05 */
        lo = (r.p[1] < 0.0f ? 0.05 : 0.2) * 10.0;
        hi = 2.0 * lo;
        if (r.p[1] > -0.05f && r.p[1] < 0.05f)
            continue; /* the row at y = 0 was made by either */
        CHECK(r.minor_radius >= lo * (1 - 1e-6) && r.radius <= hi * (1 + 1e-6),
              "record %u at y %.2f: radii %g, %g outside [%g, %g]", i, r.p[1], r.minor_radius,
              r.radius, lo, hi);
        lifted += r.minor_radius <= lo * (1 + 1e-6);
        capped += r.radius >= hi * (1 - 1e-6);
        for (ch = 0; ch < 3; ch++) {
            g = sqrt((double)r.grad_t[ch][0] * r.grad_t[ch][0] + r.grad_t[ch][1] * r.grad_t[ch][1] +
                     r.grad_t[ch][2] * r.grad_t[ch][2]);
            CHECK(g * r.minor_radius <= r.e[ch] * (1 + 1e-3) + 1e-6, "|grad| r %g > E %g",
                  g * r.minor_radius, r.e[ch]);
        }
    }
    printf("  %llu records: %u lifted to min_pixels, %u capped at max_pixels\n",
           (unsigned long long)st0.records, lifted, capped);
    CHECK(lifted > 0 && capped > 0, "both bounds should bind on this floor");
    /* footprint 0: no pixel bound (a record under the sphere is smaller
     * than 10 x 0.2) */
    {
        const float p[3] = {0.05f, 0.05f, 0.0f};
        CHECK(irc_cache_clear(c) == IRC_OK &&
                  irc_cache_lookup_or_compute_px(c, p, n, NULL, 0.0f, rgb, &w, NULL) >= 0 &&
                  irc_cache_stats(c, &st0) == IRC_OK && irc_cache_record(c, 0, &r) == IRC_OK,
              "plain record");
        free_r = r.minor_radius < 2.0f;
        printf("  plain record under the sphere: radii %g, %g\n", r.minor_radius, r.radius);
        CHECK(free_r, "without a footprint the record keeps its own radius %g", r.minor_radius);
    }
    {
        const float p[3] = {7.0f, 7.0f, 0.0f};
        CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, -1.0f, rgb, &w, NULL) == IRC_ERR_RANGE,
              "negative footprint");
        CHECK(irc_cache_lookup_or_compute_px(c, p, n, NULL, NAN, rgb, &w, NULL) == IRC_ERR_NONFINITE,
              "NaN footprint");
        CHECK(irc_cache_stats(c, &st1) == IRC_OK && st1.records == st0.records &&
                  st1.computes == st0.computes,
              "refused calls changed the cache");
    }
    block_free(&cfg);
}

/* Safe defaults: with every radius field zero, the sphere-over-plane fill
 * (the fill 0.1 got wrong by 9-17% with 1-2 records) errs less as a
 * falls, no point stands far out from the fill's own error, and a record
 * that saw nothing (x = 1000) answers no lookup under the sphere. */
TEST(test_safe_defaults)
{
    static const float as[3] = {0.4f, 0.2f, 0.1f};
    tscene s;
    double last = 1e9;
    int ai;
    scene_sphere_plane(&s);
    for (ai = 0; ai < 3; ai++) {
        irc_config cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 0, 0);
        irc_cache *c;
        irc_stats st;
        double se = 0.0, sw = 0.0, worst = 0.0;
        int i, j, n = irc_t_quick ? 24 : 48;
        cfg.accuracy = as[ai];
        c = block_cache(&cfg, 20000, 0);
        CHECK(c != NULL, "init");
        if (!c) return;
        for (i = 0; i < n; i++)
            for (j = 0; j < n; j++) {
                const float p[3] = {(float)(-3.0 + 6.0 * (i + 0.37) / n),
                                    (float)(-3.0 + 6.0 * (j + 0.61) / n), 0.0f};
                const float nn[3] = {0, 0, 1};
                double q[3] = {p[0], p[1], 0.0}, want = sphere_plane_e(&s, q), err;
                float rgb[3];
                if (irc_cache_lookup_or_compute(c, p, nn, rgb, NULL, NULL) < 0) {
                    CHECK(0, "lookup failed");
                    continue;
                }
                err = fabs(rgb[0] - want) / want;
                se += err * err;
                sw += 1.0;
                if (err > worst)
                    worst = err;
            }
        irc_cache_stats(c, &st);
        se = sqrt(se / sw);
        printf("  a = %.1f: %llu records, relative RMSE %.4f, worst point %.4f (%.1fx)\n", as[ai],
               (unsigned long long)st.records, se, worst, worst / se);
        CHECK(se < last, "a = %.1f: RMSE %.4f not below %.4f", as[ai], se, last);
        CHECK(worst < 8.0 * se, "a = %.1f: a point %.1fx the RMSE", as[ai], worst / se);
        last = se;
        if (ai == 0) {
            /* a record that saw no geometry, far away, serves nothing here */
            irc_cache *far;
            irc_config fc = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 0, 0);
            const float at[3] = {1000.0f, 0.0f, 0.0f}, under[3] = {0.2f, 0.0f, 0.0f},
                        nn[3] = {0, 0, 1};
            irc_record r;
            float rgb[3], w;
            fc.accuracy = as[ai];
            far = block_cache(&fc, 4, 0);
            CHECK(far && irc_record_compute(far, at, nn, &r, NULL) == IRC_OK &&
                      irc_cache_insert(far, &r) == IRC_OK, "far record");
            CHECK(irc_cache_lookup(far, under, nn, rgb, &w) == IRC_MISS,
                  "the far record answered under the sphere: %g (R %g)", rgb[0], r.radius);
            block_free(&fc);
        }
        block_free(&cfg);
    }
}
