/* t_lookup.c -- weights, extrapolation, misses, full pools and eviction. */
#define IRC_EXPERIMENTAL /* irc_cache_lookup_gradient, irc_cache_neighbours */
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
    cfg.irr.blend = 1.0f; /* Ward's weight (the blended one: test_blend_mean) */
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

/* Lookups that blend past the placement reach (cfg.irr.blend = 2, a =
 * 0.2): every record within 2 a R counts, weighted (1 - t^2)^2 at t = e /
 * (2 a), written out here by hand; a lookup-or-compute computes where no
 * record lies within a R and answers its record (weight 1) blended with
 * those it found, reporting weight 0; with blend 1 the same point misses.
 * Values outside 1..4 are refused. */
static irc_cache *blend_cache(tscene *s, irc_config *cfg, float blend, const irc_record *a,
                              const irc_record *b)
{
    irc_cache *c;
    *cfg = scene_config(s, 0, 4, 4);
    cfg->accuracy = 0.2f;
    cfg->irr.blend = blend;
    cfg->check_visibility = IRC_OFF;
    c = block_cache(cfg, 8, 0);
    if (c && (irc_cache_insert(c, a) != IRC_OK || irc_cache_insert(c, b) != IRC_OK)) {
        block_free(cfg);
        return NULL;
    }
    return c;
}

TEST(test_blend_mean)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_record a = flat_record(0, 0, 0, 1.0f, 1.0f), b = flat_record(0.3f, 0, 0, 3.0f, 1.0f), r;
    const float n[3] = {0, 0, 1}, p[3] = {0.1f, 0, 0}, q[3] = {0, 0.25f, 0};
    float rgb[3], w;
    irc_stats st;
    double wa, wb, want, tb;
    static const float bad[] = {0.5f, -1.0f, 4.5f, NAN, INFINITY};
    size_t i;
    scene_sphere_plane(&s);
    c = blend_cache(&s, &cfg, 2.0f, &a, &b);
    CHECK(c != NULL, "init, blend 2");
    if (!c)
        return;
    /* e_a = 0.1, e_b = 0.2: t = 0.25 and 0.5 of the reach 0.4 */
    wa = (1.0 - 0.0625) * (1.0 - 0.0625);
    wb = 0.75 * 0.75;
    want = (wa * 1.0 + wb * 3.0) / (wa + wb);
    /* (the tolerances of test_weighted_mean: the stored normal's coding
     * moves e by ~1e-5) */
    CHECK(irc_cache_lookup(c, p, n, rgb, &w) == IRC_OK && fabs(rgb[0] - want) < 1e-4 * want &&
              fabs(w - (wa + wb)) < 1e-3 * (wa + wb),
          "blended lookup: %g (want %g), weight %g (want %g)", rgb[0], want, w, wa + wb);
    CHECK(irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL) == IRC_OK &&
              fabs(rgb[0] - want) < 1e-4 * want && irc_cache_stats(c, &st) == IRC_OK &&
              st.computes == 0,
          "a record within a R: a hit (%g, computes %llu)", rgb[0],
          (unsigned long long)st.computes);
    /* e_a = 0.25, e_b = sqrt(0.3^2 + 0.25^2): both past a R, within 2 a R */
    tb = sqrt(0.09 + 0.0625) / 0.4;
    wa = (1.0 - 0.625 * 0.625) * (1.0 - 0.625 * 0.625);
    wb = (1.0 - tb * tb) * (1.0 - tb * tb);
    /* One rule for both calls: no record within a R is a miss, where the
     * lookup-or-compute below computes; the lookup still hands over what
     * lies within blend a R */
    want = (wa * 1.0 + wb * 3.0) / (wa + wb);
    CHECK(irc_cache_lookup(c, q, n, rgb, &w) == IRC_MISS && fabs(rgb[0] - want) < 1e-4 * want &&
              fabs(w - (wa + wb)) < 1e-3 * (wa + wb),
          "no record within a R: a miss with the wider mean %g (want %g), weight %g", rgb[0],
          want, w);
    CHECK(irc_cache_lookup(c, p, n, rgb, &w) == IRC_OK, "a record within a R: a hit");
    CHECK(irc_cache_lookup_or_compute(c, q, n, rgb, &w, NULL) == IRC_OK && w == 0.0f &&
              irc_cache_stats(c, &st) == IRC_OK && st.computes == 1 && st.records == 3 &&
              irc_cache_record(c, 2, &r) == IRC_OK,
          "no record within a R: computed (weight %g, computes %llu)", w,
          (unsigned long long)st.computes);
    want = (wa * 1.0 + wb * 3.0 + 1.0 * r.e[0]) / (wa + wb + 1.0);
    CHECK(r.e[0] > 1.0f && fabs(rgb[0] - want) < 1e-4 * want,
          "the computed record blended: %g (want %g, its own E %g)", rgb[0], want, r.e[0]);
    block_free(&cfg);

    c = blend_cache(&s, &cfg, 1.0f, &a, &b);
    CHECK(c != NULL, "init, blend 1");
    if (!c)
        return;
    CHECK(irc_cache_lookup(c, q, n, rgb, &w) == IRC_MISS, "blend 1: beyond a R misses");
    block_free(&cfg);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        size_t bytes;
        cfg = scene_config(&s, 0, 4, 4);
        cfg.irr.blend = bad[i];
        CHECK(irc_footprint(&cfg, 8, &bytes) == IRC_ERR_CONFIG, "blend %g accepted", bad[i]);
    }
    cfg = scene_config(&s, IRC_FEATURE_SH, 4, 4);
    cfg.irr.blend = 2.0f;
    {
        size_t bytes;
        CHECK(irc_footprint(&cfg, 8, &bytes) == IRC_ERR_CONFIG, "blend in an SH cache accepted");
    }
}

/* The strata follow a when left 0 (one knob for a record's cost): one
 * record's rays are M x N = 4096, 1024, 256 at a = 0.2, 0.3, 0.4 (and at
 * a = 0.24, 0.25, 0.37, 0.375 either side of the steps), 16,384 below
 * a = 0.125 and 65,536 below 0.0625 and at any smaller a; strata given
 * are kept; SH records keep 16 x 64 whatever a. */
TEST(test_strata_follow_accuracy)
{
    static const struct { float a; uint32_t m, n, rays; } k[] = {
        {0.0f, 0, 0, 4096}, {0.2f, 0, 0, 4096}, {0.24f, 0, 0, 4096}, {0.25f, 0, 0, 1024},
        {0.3f, 0, 0, 1024}, {0.37f, 0, 0, 1024}, {0.375f, 0, 0, 256}, {0.4f, 0, 0, 256},
        {0.8f, 0, 0, 256}, {0.4f, 32, 128, 4096}, {0.2f, 8, 0, 8 * 128}, {0.4f, 0, 64, 8 * 64},
        /* below 0.125 the rows double as a halves, to 128 x 512 */
        {0.15f, 0, 0, 4096}, {0.125f, 0, 0, 4096}, {0.124f, 0, 0, 64 * 256},
        {0.1f, 0, 0, 64 * 256}, {0.0625f, 0, 0, 64 * 256}, {0.062f, 0, 0, 128 * 512},
        {0.001f, 0, 0, 128 * 512}, {0.1f, 0, 64, 64 * 64}};
    tscene s;
    size_t i;
    scene_sphere_plane(&s);
    for (i = 0; i < sizeof k / sizeof k[0]; i++) {
        irc_config cfg = scene_config(&s, 0, k[i].m, k[i].n);
        const float p[3] = {0.3f, 0.1f, 0.0f}, n[3] = {0, 0, 1};
        irc_record r;
        irc_stats st;
        irc_cache *c;
        cfg.accuracy = k[i].a;
        cfg.check_visibility = IRC_OFF;
        c = block_cache(&cfg, 4, 0);
        CHECK(c != NULL && irc_record_compute(c, p, n, &r, NULL) == IRC_OK &&
                  irc_cache_stats(c, &st) == IRC_OK && st.rays == k[i].rays,
              "a = %g, strata %ux%u given: %llu rays, want %u", k[i].a, k[i].m, k[i].n,
              c ? (unsigned long long)st.rays : 0ull, k[i].rays);
        if (c)
            block_free(&cfg);
    }
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

/* irc_cache_lookup_gradient with one record in reach: the weights cancel,
 * so dp and dn are the derivatives of the lookup itself, checked against
 * its central differences along x, y and two tilts of the normal; the
 * value and weight are the plain lookup's; a clamped channel has none. */
TEST(test_lookup_gradient_one)
{
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4);
    irc_cache *c;
    irc_record r = flat_record(1, 2, 3, 1.0f, 0.2f);
    const float p0[3] = {1.3f, 2.03f, 3.0f}, h = 1e-2f, th = 1e-2f;
    float n[3] = {0.05f, -0.03f, 1.0f}, rgb[3], ref[3], w, wref, len;
    irc_gradient g;
    int ch, k;
    cfg.accuracy = 10.0f;
    c = block_cache(&cfg, 8, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    r.grad_t[0][0] = 0.2f; r.grad_t[0][1] = -0.4f;
    r.grad_t[1][0] = -4.0f; /* green: capped at E/R = 5, below zero at 0.3 */
    r.grad_r[2][0] = 0.5f; r.grad_r[2][1] = 0.25f;
    r.grad_t[2][1] = 0.3f;
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
    len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (k = 0; k < 3; k++)
        n[k] /= len;
    CHECK(irc_cache_lookup_gradient(c, p0, n, rgb, &g, &w) == IRC_OK, "hit");
    CHECK(irc_cache_lookup(c, p0, n, ref, &wref) == IRC_OK, "plain hit");
    CHECK(memcmp(rgb, ref, sizeof rgb) == 0 && w == wref, "same value and weight as the lookup");
    CHECK(rgb[1] == 0.0f && g.dp[1][0] == 0.0f && g.dn[1][0] == 0.0f, "clamped green: no gradient");
    for (k = 0; k < 2; k++) { /* along x, then y */
        float pa[3], pb[3], ea[3], eb[3];
        memcpy(pa, p0, sizeof pa);
        memcpy(pb, p0, sizeof pb);
        pa[k] -= h;
        pb[k] += h;
        CHECK(irc_cache_lookup(c, pa, n, ea, &w) == IRC_OK && irc_cache_lookup(c, pb, n, eb, &w) == IRC_OK, "hits");
        for (ch = 0; ch < 3; ch++) {
            const float fd = (eb[ch] - ea[ch]) / (2.0f * h);
            CHECK(fabsf(g.dp[ch][k] - fd) < 1e-3f, "dE/dp channel %d axis %d: %g vs %g", ch, k, g.dp[ch][k], fd);
        }
    }
    for (k = 0; k < 2; k++) { /* the normal turned about x, then about y */
        float na[3], nb[3], dm[3] = {0, 0, 0}, ea[3], eb[3], t[3] = {0, 0, 0};
        int j;
        t[k] = 1.0f; /* dm = t x n: the turn's direction */
        dm[0] = t[1] * n[2] - t[2] * n[1];
        dm[1] = t[2] * n[0] - t[0] * n[2];
        dm[2] = t[0] * n[1] - t[1] * n[0];
        for (j = 0; j < 3; j++) { /* Rodrigues to first order plus the cos term */
            na[j] = n[j] * cosf(th) - dm[j] * sinf(th);
            nb[j] = n[j] * cosf(th) + dm[j] * sinf(th);
        }
        CHECK(irc_cache_lookup(c, p0, na, ea, &w) == IRC_OK && irc_cache_lookup(c, p0, nb, eb, &w) == IRC_OK, "hits");
        for (ch = 0; ch < 3; ch++) {
            const float fd = (eb[ch] - ea[ch]) / (2.0f * th),
                        an = g.dn[ch][0] * dm[0] + g.dn[ch][1] * dm[1] + g.dn[ch][2] * dm[2];
            CHECK(fabsf(an - fd) < 1e-3f, "dE/dn channel %d turn %d: %g vs %g", ch, k, an, fd);
        }
    }
    CHECK(fabsf(g.dn[2][0]) + fabsf(g.dn[2][1]) > 0.1f, "blue turns with the normal");
    block_free(&cfg);
}

/* On the sphere over the plane the gradient lookup tracks dE/dp in closed
 * form between records: each record's gradient is within 15% at 64 x 256
 * strata (test_sphere_over_plane), and the weighted mean of neighbours'
 * gradients adds the gradient's own change across a reach (a fraction
 * of 1/d here, d >= 2 from the sphere's centre).  Checked: the relative
 * vector error is below 0.25 at every point and its median below 0.10;
 * printed beside the error of central differences of irc_cache_lookup
 * (h = 0.02), which also carry the weights' derivatives. */
TEST(test_lookup_gradient_sphere)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    double err[24], fderr = 0.0;
    unsigned long long seed = 7;
    const float n[3] = {0, 0, 1};
    float rgb[3], w;
    int i, j, k, bad = 0;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 64, 256);
    c = block_cache(&cfg, 512, 0);
    CHECK(c != NULL, "init");
    if (!c) return;
    for (j = 0; j <= 24; j++)
        for (i = 0; i <= 24; i++) {
            const float p[3] = {-3.0f + 0.25f * (float)i, -3.0f + 0.25f * (float)j, 0.0f};
            CHECK(irc_cache_lookup_or_compute(c, p, n, rgb, &w, NULL) >= 0, "fill");
        }
    for (i = 0; i < 24; i++) {
        double q[3], g[3], e2 = 0.0, g2 = 0.0, f2 = 0.0;
        float p[3];
        irc_gradient gr;
        q[0] = -2.0 + 4.0 * xrand(&seed);
        q[1] = -2.0 + 4.0 * xrand(&seed);
        q[2] = 0.0;
        for (k = 0; k < 3; k++)
            p[k] = (float)q[k];
        sphere_plane_grad(&s, q, g);
        CHECK(irc_cache_lookup_gradient(c, p, n, rgb, &gr, &w) == IRC_OK, "hit at %g %g", q[0], q[1]);
        for (k = 0; k < 2; k++) {
            float pa[3], pb[3], ea[3], eb[3];
            double fd;
            memcpy(pa, p, sizeof pa);
            memcpy(pb, p, sizeof pb);
            pa[k] -= 0.02f;
            pb[k] += 0.02f;
            irc_cache_lookup(c, pa, n, ea, &w);
            irc_cache_lookup(c, pb, n, eb, &w);
            fd = (eb[0] - ea[0]) / 0.04;
            e2 += (gr.dp[0][k] - g[k]) * (gr.dp[0][k] - g[k]);
            f2 += (fd - g[k]) * (fd - g[k]);
            g2 += g[k] * g[k];
        }
        err[i] = sqrt(e2 / g2);
        fderr += sqrt(f2 / g2) / 24.0;
        bad += err[i] >= 0.25;
    }
    for (i = 1; i < 24; i++) /* insertion sort for the median */
        for (j = i; j > 0 && err[j - 1] > err[j]; j--) {
            const double t = err[j];
            err[j] = err[j - 1];
            err[j - 1] = t;
        }
    printf("  gradient lookup: median relative error %.3f, worst %.3f; differences of "
           "lookups: mean %.3f\n", 0.5 * (err[11] + err[12]), err[23], fderr);
    CHECK(bad == 0, "%d points off by 25%% or more (worst %.3f)", bad, err[23]);
    CHECK(0.5 * (err[11] + err[12]) < 0.10, "median %.3f", 0.5 * (err[11] + err[12]));
    block_free(&cfg);
}

/* Its errors and misses: NULL outputs, an SH cache, no record in reach. */
TEST(test_lookup_gradient_status)
{
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION, 4, 4), sh;
    irc_cache *c = block_cache(&cfg, 8, 0), *s;
    irc_record r = flat_record(0, 0, 0, 1.0f, 0.2f);
    const float p[3] = {5, 0, 0}, n[3] = {0, 0, 1};
    float rgb[3] = {1, 1, 1}, w = 1.0f;
    irc_gradient g;
    CHECK(c && irc_cache_insert(c, &r) == IRC_OK, "insert");
    if (!c) return;
    memset(&g, 0x7f, sizeof g);
    CHECK(irc_cache_lookup_gradient(c, p, n, rgb, &g, &w) == IRC_MISS, "miss");
    CHECK(rgb[0] == 0.0f && w == 0.0f && g.dp[0][0] == 0.0f && g.dn[2][2] == 0.0f, "zeros on a miss");
    CHECK(irc_cache_lookup_gradient(c, r.p, n, rgb, NULL, &w) == IRC_ERR_NULL, "NULL grad");
    CHECK(irc_cache_lookup_gradient(c, r.p, n, NULL, &g, &w) == IRC_ERR_NULL, "NULL rgb");
    CHECK(irc_cache_lookup_gradient(NULL, r.p, n, rgb, &g, &w) == IRC_ERR_NULL, "NULL cache");
    CHECK(irc_cache_lookup_gradient(c, r.p, n, rgb, &g, NULL) == IRC_OK, "weight optional");
    sh = scene_config(&dummy, IRC_FEATURE_SH, 4, 4);
    s = block_cache(&sh, 8, 0);
    CHECK(s && irc_cache_lookup_gradient(s, r.p, n, rgb, &g, &w) == IRC_ERR_UNSUPPORTED,
          "SH cache: unsupported");
    block_free(&sh);
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

/* Under an open sky every ray escapes: with the default radii such a
 * record gets the smallest radius (FLT_MIN) and must still serve its own
 * point, so repeated calls there make one record, not one each; in every
 * configuration of the record (bare, gradients, ellipses, defaults). */
TEST(test_open_sky_own_point)
{
    static const uint32_t feats[4] = {IRC_FEATURE_NONE, 0,
                                      IRC_FEATURE_TRANSLATION | IRC_FEATURE_HESSIAN,
                                      IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION};
    static const float pts[3][3] = {{0, 0, 0}, {3.25f, -1.5f, 0.75f}, {1e4f, 2e4f, -3e4f}};
    const float n[3] = {0.0f, 0.6f, 0.8f};
    tscene s;
    int f, i, k;
    scene_init(&s);
    s.sky_a[0] = s.sky_a[1] = s.sky_a[2] = 1.0f;
    for (f = 0; f < 4; f++) {
        irc_config cfg = scene_config(&s, feats[f], 4, 16);
        irc_cache *c;
        irc_stats st;
        if (f == 3) {
            cfg.clamp_neighbours = IRC_DEFAULT;
            cfg.check_visibility = IRC_DEFAULT;
        }
        c = block_cache(&cfg, 64, 0);
        CHECK(c != NULL, "init %d", f);
        if (!c) continue;
        for (i = 0; i < 3; i++)
            for (k = 0; k < 10; k++) {
                float rgb[3], w = -1.0f;
                CHECK(irc_cache_lookup_or_compute(c, pts[i], n, rgb, &w, NULL) == IRC_OK &&
                          (k == 0 ? w == 0.0f : w > 0.0f) && fabsf(rgb[0] - 3.14159265f) < 1e-3f,
                      "features %u, point %d, call %d: w %g, E %g", feats[f], i, k, (double)w,
                      (double)rgb[0]);
            }
        CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records == 3 && st.computes == 3,
              "features %u: %llu records, %llu computes", feats[f],
              (unsigned long long)st.records, (unsigned long long)st.computes);
        block_free(&cfg);
    }
}
