/* t_sh_lookup.c -- SH lookups by hand, bad input, record bytes; lookups past float. */
#define IRC_EXPERIMENTAL /* irc_cache_lookup_gradient (irrcache.h) */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "scenes.h"

static irc_sh hand_record(float x, float y, float z, float r, int free, float base)
{
    irc_sh h;
    int ch, i, k;
    memset(&h, 0, sizeof h);
    h.p[0] = x; h.p[1] = y; h.p[2] = z;
    if (!free)
        h.n[2] = 1.0f;
    h.radius = r;
    h.bands = 2;
    h.channels = 3;
    for (ch = 0; ch < 3; ch++)
        for (i = 0; i < 4; i++) {
            h.c[ch][i] = base + 0.1f * ch - 0.05f * i;
            for (k = 0; k < 3; k++)
                h.grad[ch][i][k] = 0.01f * (float)(k + 1) * (i % 2 ? -1.0f : 1.0f) + 0.002f * ch;
        }
    return h;
}

/* Eq. 14-16 by hand: free-point records weighed (R/d)^b within a R and
 * extrapolated; surface records by Ward-Heckbert; neither kind seen by the
 * other's lookups. */
TEST(test_sh_lookup_by_hand)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_sh rec[4], out;
    float q[3] = {0.3f, 0.2f, 0.1f}, n[3] = {0, 0, 1}, w;
    double sw = 0.0, want[3][4] = {{0}}, worst = 0.0;
    int j, ch, i, k;
    scene_init(&s);
    cfg = sh_config(&s, IRC_FEATURE_SH_GRADIENT, 4, 8, 2);
    cfg.accuracy = 1.0f;
    cfg.sh.power = 3.0f;
    c = block_cache(&cfg, 8, 0);
    CHECK(c != NULL, "init");
    rec[0] = hand_record(0, 0, 0, 1.0f, 1, 1.0f);
    rec[1] = hand_record(1, 0, 0, 2.0f, 1, 2.0f);
    rec[2] = hand_record(3, 3, 3, 1.0f, 1, 5.0f);  /* out of reach */
    rec[3] = hand_record(0.2f, 0.1f, 0, 1.0f, 0, 9.0f); /* a surface record */
    for (j = 0; j < 4; j++)
        CHECK(irc_sh_insert(c, &rec[j]) == IRC_OK, "insert %d", j);
    for (j = 0; j < 2; j++) {
        double d[3], dist, wj;
        for (k = 0; k < 3; k++)
            d[k] = (double)q[k] - rec[j].p[k];
        dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        wj = pow(rec[j].radius / dist, 3.0);
        sw += wj;
        for (ch = 0; ch < 3; ch++)
            for (i = 0; i < 4; i++)
                want[ch][i] += wj * (rec[j].c[ch][i] + rec[j].grad[ch][i][0] * d[0] +
                                     rec[j].grad[ch][i][1] * d[1] + rec[j].grad[ch][i][2] * d[2]);
    }
    CHECK(irc_sh_lookup(c, q, NULL, &out, &w) == IRC_OK, "free lookup");
    for (ch = 0; ch < 3; ch++)
        for (i = 0; i < 4; i++)
            worst = fmax(worst, fabs(out.c[ch][i] - want[ch][i] / sw));
    CHECK(worst < 1e-5 && fabs(w - sw) < 1e-4 * sw, "free: %.3e, weight %g vs %g", worst, w, sw);
    /* The surface lookup sees record 3 only: one record, so its own
     * extrapolation. */
    CHECK(irc_sh_lookup(c, q, n, &out, &w) == IRC_OK, "surface lookup");
    worst = 0.0;
    for (ch = 0; ch < 3; ch++)
        for (i = 0; i < 4; i++) {
            double v = rec[3].c[ch][i];
            for (k = 0; k < 3; k++)
                v += rec[3].grad[ch][i][k] * ((double)q[k] - rec[3].p[k]);
            worst = fmax(worst, fabs(out.c[ch][i] - v));
        }
    {
        double d = sqrt(0.1 * 0.1 + 0.1 * 0.1 + 0.1 * 0.1);
        CHECK(worst < 1e-5 && fabs(w - 1.0 / d) < 1e-3 / d, "surface: %.3e, weight %g", worst, w);
    }
    {
        float far[3] = {10, 10, 10};
        CHECK(irc_sh_lookup(c, far, NULL, &out, &w) == IRC_MISS && w == 0.0f && out.c[0][0] == 0.0f,
              "miss");
    }
    block_free(&cfg);
}

/* Bad input gives the documented status and leaves the block as it was. */
TEST(test_sh_bad_input)
{
    tscene s;
    irc_config cfg, icfg;
    irc_cache *c, *ic;
    irc_sh good, bad, out;
    irc_record r;
    unsigned char *copy;
    float p[3] = {0, 0, 0}, n[3] = {0, 0, 1}, rgb[3], nanp[3] = {NAN, 0, 0};
    scene_init(&s);
    cfg = sh_config(&s, IRC_FEATURE_SH_GRADIENT, 4, 8, 2);
    c = block_cache(&cfg, 1, 64);
    icfg = scene_config(&s, 0, 4, 8);
    ic = block_cache(&icfg, 4, 0);
    CHECK(c && ic, "init");
    good = hand_record(0, 0, 0, 1.0f, 0, 1.0f);
    CHECK(irc_sh_insert(c, &good) == IRC_OK, "insert");
    copy = malloc(cfg.buffer_size);
    memcpy(copy, cfg.buffer, cfg.buffer_size);
    /* Every byte but the port's lock object (glibc's rwlock keeps phase
     * bits that a lock-unlock pair need not restore). */
#define SAME() CHECK(block_same(&cfg, copy, c), "block changed")
    bad = good; bad.bands = 3;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_RANGE, "bands"); SAME();
    bad = good; bad.channels = 1;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_RANGE, "channels"); SAME();
    bad = good; bad.radius = 0.0f;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_RANGE, "radius"); SAME();
    bad = good; bad.e[1] = -1.0f;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_RANGE, "negative e"); SAME();
    bad = good; bad.radius = -1.0f;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_RANGE, "negative radius"); SAME();
    bad = good; bad.e[0] = NAN;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_NONFINITE, "NaN e"); SAME();
    bad = good; bad.radius = INFINITY;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_NONFINITE, "infinite radius"); SAME();
    bad = good; bad.p[1] = -INFINITY;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_NONFINITE, "infinite p"); SAME();
    bad = good; bad.c[2][3] = INFINITY;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_NONFINITE, "coefficient"); SAME();
    bad = good; bad.grad[1][0][2] = NAN;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_NONFINITE, "gradient"); SAME();
    bad = good; bad.n[0] = NAN;
    CHECK(irc_sh_insert(c, &bad) == IRC_ERR_NORMAL, "normal"); SAME();
    CHECK(irc_sh_insert(c, &good) == IRC_ERR_FULL, "full"); SAME();
    CHECK(irc_sh_insert(c, NULL) == IRC_ERR_NULL, "null"); SAME();
    CHECK(irc_sh_lookup(c, nanp, NULL, &out, NULL) == IRC_ERR_NONFINITE, "NaN query"); SAME();
    CHECK(irc_sh_lookup(c, p, NULL, NULL, NULL) == IRC_ERR_NULL, "null out"); SAME();
    CHECK(irc_sh_record(c, 1, &out) == IRC_ERR_RANGE, "range"); SAME();
    CHECK(irc_record_compute(c, p, n, &r, NULL) == IRC_ERR_UNSUPPORTED, "irradiance call"); SAME();
    CHECK(irc_cache_lookup(c, p, n, rgb, NULL) == IRC_ERR_UNSUPPORTED, "irradiance lookup"); SAME();
    CHECK(irc_cache_insert(c, &r) == IRC_ERR_UNSUPPORTED, "irradiance insert"); SAME();
    CHECK(irc_cache_record(c, 0, &r) == IRC_ERR_UNSUPPORTED, "irradiance record"); SAME();
    CHECK(irc_sh_compute(ic, p, n, &out, NULL) == IRC_ERR_UNSUPPORTED, "SH call on irradiance cache");
    CHECK(irc_sh_lookup(ic, p, n, &out, NULL) == IRC_ERR_UNSUPPORTED, "SH lookup");
    s.fail_every = 1;
    s.fail_kind = FAIL_RAY;
    CHECK(irc_sh_compute(c, p, NULL, &out, NULL) == IRC_ERR_NOSAMPLES, "no samples"); SAME();
    s.fail_kind = FAIL_NAN_RADIANCE;
    CHECK(irc_sh_compute(c, p, n, &out, NULL) == IRC_ERR_CALLBACK, "NaN radiance"); SAME();
    s.fail_kind = FAIL_ZERO_NORMAL;
    CHECK(irc_sh_compute(c, p, n, &out, NULL) == IRC_ERR_CALLBACK, "zero normal"); SAME();
    s.fail_every = 0;
    s.return_code = -4242;
    CHECK(irc_sh_lookup_or_compute(c, n, n, &out, NULL, NULL) == -4242, "host code"); SAME();
    s.return_code = 0;
    CHECK(irc_sh_lookup_or_compute(c, n, n, &out, NULL, NULL) == IRC_NOT_STORED, "not stored");
    CHECK(block_guard_ok(&cfg, 64), "guard");
#undef SAME
    free(copy);
    block_free(&cfg);
    block_free(&icfg);
}

/* Bytes per record: 32 + 4 L^2 channels, + 12 L^2 channels with gradients. */
TEST(test_sh_footprint)
{
    tscene s;
    uint32_t l, ch, g;
    scene_init(&s);
    for (l = 1; l <= 5; l++)
        for (ch = 1; ch <= 3; ch += 2)
            for (g = 0; g < 2; g++) {
                irc_config cfg = sh_config(&s, g ? IRC_FEATURE_SH_GRADIENT : IRC_FEATURE_SH, 4, 8, l);
                irc_cache *c;
                irc_stats st;
                cfg.sh.channels = ch;
                c = block_cache(&cfg, 4, 0);
                CHECK(c && irc_cache_stats(c, &st) == IRC_OK, "stats");
                if (c)
                    CHECK(st.record_bytes == 32u + 4u * l * l * ch * (g ? 4u : 1u),
                          "L %u ch %u grad %u: %zu bytes", l, ch, g, st.record_bytes);
                block_free(&cfg);
            }
}

/* Found by the fuzzer: a record inserted with negative irradiance came
 * back from a lookup without gradients unclamped (now IRC_ERR_RANGE at
 * insert), and records near FLT_MAX can extrapolate past it (now
 * IRC_ERR_NONFINITE from the lookup, the block untouched). */
TEST(test_insert_range_overflow)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_record r;
    float q[3] = {0.15f, 0, 0}, n[3] = {0, 0, 1}, rgb[3], w;
    scene_init(&s);
    cfg = scene_config(&s, 0, 4, 8);
    c = block_cache(&cfg, 4, 0);
    memset(&r, 0, sizeof r);
    r.n[2] = 1.0f;
    r.radius = 1.0f;
    r.e[0] = -0.6875f;
    CHECK(c && irc_cache_insert(c, &r) == IRC_ERR_RANGE, "negative irradiance");
    CHECK(irc_cache_lookup(c, q, n, rgb, &w) == IRC_MISS, "nothing stored");
    block_free(&cfg);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION, 4, 8);
    c = block_cache(&cfg, 4, 0);
    r.e[0] = 3e38f;
    r.grad_t[0][0] = 3e38f;
    r.features = IRC_FEATURE_TRANSLATION;
    CHECK(c && irc_cache_insert(c, &r) == IRC_OK, "insert");
    CHECK(irc_cache_lookup(c, q, n, rgb, &w) == IRC_ERR_NONFINITE, "overflow");
    q[0] = -0.15f;
    CHECK(irc_cache_lookup(c, q, n, rgb, &w) == IRC_OK && rgb[0] <= 3.4028235e38f, "below");
    /* irc_cache_lookup_gradient: "IRC_ERR_NONFINITE also for a gradient
     * that overflows float" (the gradient at the record grows past float
     * where the value does not) */
    block_free(&cfg);
    {
        irc_gradient g;
        const float tilted[3] = {0.0f, 0.70710678f, 0.70710678f};
        cfg = scene_config(&s, IRC_FEATURE_ROTATION, 4, 8);
        c = block_cache(&cfg, 4, 0);
        memset(&r, 0, sizeof r);
        r.n[1] = r.n[2] = 0.70710678f;
        r.radius = 1.0f;
        r.e[0] = 1e38f;
        r.grad_r[0][1] = 3e38f;
        r.grad_r[0][2] = -3e38f;
        r.features = IRC_FEATURE_ROTATION;
        q[0] = 0.0f;
        /* finite, but past float in the record's tangent frame, where it
         * is stored: refused, not stored as another gradient */
        CHECK(c && irc_cache_insert(c, &r) == IRC_ERR_NONFINITE, "a gradient past float stored");
        CHECK(c && irc_cache_lookup_gradient(c, q, tilted, rgb, &g, &w) == IRC_MISS, "stored");
        r.grad_r[0][1] = 1.7e38f;
        r.grad_r[0][2] = -1.7e38f;
        CHECK(c && irc_cache_insert(c, &r) == IRC_OK, "a gradient within float refused");
        CHECK(c && irc_cache_lookup_gradient(c, q, tilted, rgb, &g, &w) == IRC_OK &&
                  fabsf(g.dn[0][0] / 2.4041630e38f - 1.0f) < 1e-3f,
              "stored as %g, not 2.404e38", (double)g.dn[0][0]);
        block_free(&cfg);
        /* Two records at one point with opposite gradients near FLT_MAX:
         * each is finite, and the blend's running mean steps past float
         * (3e38 - -3e38) where float arithmetic is float: the answer is
         * IRC_ERR_NONFINITE, never an infinite gradient with IRC_OK (x87
         * holds the step in a wider register and may answer the finite
         * mean).  (E is as large: a stored gradient is bounded by E over
         * the radius.) */
        cfg = scene_config(&s, IRC_FEATURE_TRANSLATION, 4, 8);
        c = block_cache(&cfg, 4, 0);
        memset(&r, 0, sizeof r);
        r.n[2] = 1.0f;
        r.radius = 1.0f;
        r.e[0] = 3e38f;
        r.features = IRC_FEATURE_TRANSLATION;
        r.grad_t[0][0] = 3e38f;
        CHECK(c && irc_cache_insert(c, &r) == IRC_OK, "first record");
        CHECK(c && irc_cache_lookup_gradient(c, r.p, n, rgb, &g, &w) == IRC_OK &&
                  fabsf(rgb[0] / 3e38f - 1.0f) < 1e-5f && fabsf(g.dp[0][0] / 3e38f - 1.0f) < 1e-3f,
              "one record: its own value %g and gradient %g", (double)rgb[0], (double)g.dp[0][0]);
        r.grad_t[0][0] = -3e38f;
        CHECK(c && irc_cache_insert(c, &r) == IRC_OK, "second record");
        {
            const int st = c ? irc_cache_lookup_gradient(c, r.p, n, rgb, &g, &w) : IRC_ERR_NULL;
            /* 0: float arithmetic in float, where the step overflows */
            const int wide = FLT_EVAL_METHOD != 0;
            int ch, k, finite = 1;
            for (ch = 0; ch < 3; ch++)
                for (k = 0; k < 3; k++)
                    finite &= isfinite(g.dp[ch][k]) && isfinite(g.dn[ch][k]);
            CHECK(st == IRC_ERR_NONFINITE || (wide && st == IRC_OK && finite),
                  "a blended gradient past float: %d", st);
        }
        CHECK(c && irc_cache_lookup(c, r.p, n, rgb, &w) == IRC_OK &&
                  fabsf(rgb[0] / 3e38f - 1.0f) < 1e-5f,
              "the value alone is finite");
        block_free(&cfg);
    }
    {
        /* irc_sh_lookup: "IRC_ERR_NONFINITE when an extrapolation
         * overflows float" */
        irc_sh sr;
        irc_sh out;
        cfg = scene_config(&s, IRC_FEATURE_SH_GRADIENT, 4, 8);
        cfg.sh.bands = 2;
        c = block_cache(&cfg, 4, 0);
        memset(&sr, 0, sizeof sr);
        sr.n[2] = 1.0f;
        sr.radius = 1.0f;
        sr.bands = 2;
        sr.channels = 3;
        sr.c[0][0] = 3e38f;
        sr.grad[0][0][0] = 3e38f;
        q[0] = 0.15f;
        CHECK(c && irc_sh_insert(c, &sr) == IRC_OK, "SH insert");
        CHECK(c && irc_sh_lookup(c, q, n, &out, &w) == IRC_ERR_NONFINITE, "SH overflow");
        block_free(&cfg);
    }
}
