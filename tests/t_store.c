/* t_store.c -- the store's contracts that 0.1 broke: footprint arithmetic
 * and its compile-time bounds, consistent radius limits, per-channel
 * gradient precision, and an index that stays a tree where users put
 * their scenes (centred on the origin, one far outlier first).  The index
 * test counts candidates through the internal query on purpose (cache.h);
 * everything else uses the public header. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "block/cache.h" /* internals on purpose: candidates the index hands over */
#include "index/index.h"
#include "index/layout.h"
#include "scenes.h"
#include "test.h"

static tscene dummy;

/* Every config of a grid that includes VISIBILITY and SH: the compile-time
 * bound of its kind is at least what irc_footprint() asks. */
TEST(test_footprint_bounds)
{
    static const uint32_t feats[] = {
        0, IRC_FEATURE_TRANSLATION, IRC_FEATURE_ROTATION,
        IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, IRC_FEATURE_VISIBILITY,
        IRC_FEATURE_VISIBILITY | IRC_FEATURE_ROTATION,
        IRC_FEATURE_HESSIAN | IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, IRC_FEATURE_SH,
        IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT};
    static const uint32_t strata[][2] = {{1, 1}, {2, 3}, {1, 4096}, {16, 64}, {32, 128}, {64, 256}, {1024, 4096}};
    static const uint32_t threads[] = {1, 3, 64}, batches[] = {1, 7, 4096}, recs[] = {1, 17, 100000};
    uint32_t fi, si, ti, bi, ri, bands, ch, checked = 0, low = 0, wrapped = 0;
    for (fi = 0; fi < sizeof feats / sizeof feats[0]; fi++)
        for (si = 0; si < 7; si++)
            for (ti = 0; ti < 3; ti++)
                for (bi = 0; bi < 3; bi++)
                    for (ri = 0; ri < 3; ri++)
                        for (bands = 1; bands <= 5; bands++)
                            for (ch = 1; ch <= 3; ch += 2) {
                                irc_config cfg = scene_config(&dummy, feats[fi], strata[si][0],
                                                              strata[si][1]);
                                size_t need = 0, bound;
                                uint32_t s = strata[si][0] * strata[si][1];
                                int sh = (feats[fi] & IRC_FEATURE_SH) != 0;
                                if (!sh && (bands > 1 || ch > 1))
                                    continue;
                                cfg.threads = threads[ti];
                                cfg.max_batch = batches[bi];
                                if (sh) {
                                    cfg.sh.bands = bands;
                                    cfg.sh.channels = ch;
                                }
                                if (irc_footprint(&cfg, recs[ri], &need) != IRC_OK)
                                    continue;
                                bound = sh ? IRC_SH_FOOTPRINT_BOUND(recs[ri], bands, ch, s, threads[ti],
                                                                    batches[bi])
                                           : IRC_FOOTPRINT_BOUND(feats[fi], recs[ri], s, threads[ti],
                                                                 batches[bi]);
                                /* A 32-bit size_t wraps a bound over 4 GiB: no
                                 * static block that size exists there. */
                                if ((double)threads[ti] * s * 432.0 > (double)SIZE_MAX) {
                                    wrapped++;
                                    continue;
                                }
                                checked++;
                                if (bound < need) {
                                    if (low < 5)
                                        printf("  bound %zu < footprint %zu (features %u, %ux%u, "
                                               "%u threads, batch %u, %u records, L %u ch %u)\n",
                                               bound, need, feats[fi], strata[si][0], strata[si][1],
                                               threads[ti], batches[bi], recs[ri], bands, ch);
                                    low++;
                                }
                            }
    printf("  %u configs, %u bounds below the footprint (%u over SIZE_MAX skipped)\n", checked,
           low, wrapped);
    CHECK(checked > 1500, "only %u configs were checked", checked);
    CHECK(low == 0, "%u bounds below irc_footprint()", low);
}

/* The footprint's overflow guard uses the configured strata: on a 32-bit
 * size_t every ordinary config fits (0.1 refused them all). */
TEST(test_footprint_size_t)
{
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 0, 0);
    size_t need = 0;
    printf("  size_t is %u bits\n", (unsigned)(sizeof(size_t) * 8));
    CHECK(irc_footprint(&cfg, 100000, &need) == IRC_OK, "default config, 1e5 records");
    CHECK(need > 100000u * 64u && need < 100000u * 400u, "footprint %zu", need);
    /* What does not fit a 32-bit size_t is refused, not wrapped. */
    cfg.threads = 64;
    cfg.strata_theta = 1024;
    cfg.strata_phi = 4096;
    cfg.features |= IRC_FEATURE_VISIBILITY;
    if (sizeof(size_t) == 4)
        CHECK(irc_footprint(&cfg, IRC_MAX_RECORDS, &need) == IRC_ERR_CONFIG, "huge config on 32 bits");
    else
        CHECK(irc_footprint(&cfg, IRC_MAX_RECORDS, &need) == IRC_OK && need / 65536u / 65536u > 0,
              "huge config on 64 bits: %zu", need);
}

/* min_radius and max_radius follow one rule: finite, within
 * [0, IRC_RADIUS_CAP], max > min, max 0 meaning the cap. */
TEST(test_radius_limits)
{
    static const struct { float lo, hi; int st; } cases[] = {
        {0.0f, 0.0f, IRC_OK}, {0.5f, 1.0f, IRC_OK}, {0.0f, IRC_RADIUS_CAP, IRC_OK},
        {(float)INFINITY, 0.0f, IRC_ERR_CONFIG}, {0.0f, (float)INFINITY, IRC_ERR_CONFIG},
        {(float)NAN, 0.0f, IRC_ERR_CONFIG}, {0.0f, (float)NAN, IRC_ERR_CONFIG},
        {-1.0f, 0.0f, IRC_ERR_CONFIG}, {0.0f, -1.0f, IRC_ERR_CONFIG},
        {2.0f, 1.0f, IRC_ERR_CONFIG}, {1.0f, 1.0f, IRC_ERR_CONFIG},
        {IRC_RADIUS_CAP, 0.0f, IRC_ERR_CONFIG}, {0.0f, 2e30f, IRC_ERR_CONFIG}};
    size_t i, need;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        irc_config cfg = scene_config(&dummy, 0, 0, 0);
        int st;
        cfg.min_radius = cases[i].lo;
        cfg.max_radius = cases[i].hi;
        st = irc_footprint(&cfg, 10, &need);
        CHECK(st == cases[i].st, "min %g max %g: %d, want %d", cases[i].lo, cases[i].hi, st,
              cases[i].st);
    }
}

/* A channel 1e4 times dimmer than another keeps its own gradient's
 * relative precision (0.1 shared one scale: 12% lost). */
TEST(test_gradient_channels)
{
    irc_config cfg = scene_config(&dummy, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 4, 4);
    irc_cache *c = block_cache(&cfg, 4, 0);
    static const double scale[3] = {1.0, 1e-4, 3e-9};
    irc_record r, back;
    double worst = 0.0;
    int ch, k, which;
    CHECK(c != NULL, "init");
    if (!c) return;
    memset(&r, 0, sizeof r);
    r.n[0] = 0.3f; r.n[1] = -0.5f; r.n[2] = 0.8f;
    r.radius = 0.5f; /* |grad_t| R < e: stored as given */
    for (ch = 0; ch < 3; ch++) {
        r.e[ch] = (float)scale[ch];
        for (k = 0; k < 3; k++) {
            /* tangent to the normal, so nothing is lost to the projection */
            static const float t[3] = {0.8f, 0.0f, -0.3f};
            r.grad_t[ch][k] = (float)(scale[ch] * t[k] * (1.0 + 0.37 * ch));
            r.grad_r[ch][k] = (float)(scale[ch] * t[k] * (2.0 - 0.5 * ch));
        }
    }
    CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
    CHECK(irc_cache_record(c, 0, &back) == IRC_OK, "read");
    for (which = 0; which < 2; which++)
        for (ch = 0; ch < 3; ch++) {
            const float *g = which ? r.grad_r[ch] : r.grad_t[ch];
            const float *b = which ? back.grad_r[ch] : back.grad_t[ch];
            double num = 0.0, den = 0.0, rel;
            for (k = 0; k < 3; k++) {
                num += ((double)b[k] - g[k]) * ((double)b[k] - g[k]);
                den += (double)g[k] * g[k];
            }
            rel = sqrt(num / den);
            if (rel > worst)
                worst = rel;
        }
    printf("  worst relative gradient error over 3 channels (1, 1e-4, 3e-9): %.2e\n", worst);
    /* The normal's quantisation (~5e-5 rad) rotates the frame; the
     * mantissa's own step is 2^-14 of the channel's largest component. */
    CHECK(worst < 2e-4, "worst %.3g", worst);
    block_free(&cfg);
}

static void ignore_candidate(void *ud, uint32_t id)
{
    (void)ud;
    (void)id;
}

/* Index entries a lookup scans, on average, over a grid of queries
 * on a floor of n x n records of spacing 1 centred at (ox, 0, oz), with an
 * optional far outlier inserted first. */
static double candidates(irc_cache *c, uint32_t n, double ox, int outlier)
{
    irc_record r;
    uint64_t scanned = 0;
    uint32_t i, j, q = 0;
    memset(&r, 0, sizeof r);
    irc_cache_clear(c);
    r.n[1] = 1.0f;
    r.e[0] = r.e[1] = r.e[2] = 1.0f;
    if (outlier) {
        r.p[0] = (float)(ox + 1e5);
        r.p[1] = -3e4f;
        r.radius = 0.8f;
        irc_cache_insert(c, &r);
    }
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            r.p[0] = (float)(ox + i - 0.5 * n + 0.25);
            r.p[1] = 0.0f;
            r.p[2] = (float)(j - 0.5 * n + 0.25);
            r.radius = (float)(1.5 + 0.5 * ((i * 7 + j * 3) % 5));
            irc_cache_insert(c, &r);
        }
    for (i = 0; i < n; i += 7)
        for (j = 0; j < n; j += 7) {
            float p[3];
            p[0] = (float)(ox + i - 0.5 * n + 0.6);
            p[1] = 0.0f;
            p[2] = (float)(j - 0.5 * n + 0.6);
            scanned += irc__index_query(c, p, ignore_candidate, NULL);
            q++;
        }
    {
        irc_stats s;
        irc_cache_stats(c, &s);
        printf("  nodes %llu of %llu\n", (unsigned long long)s.index_nodes,
               (unsigned long long)s.index_nodes_max);
    }
    return (double)scanned / q;
}

/* The same floor centred on the origin, moved 1000 away, and each with a
 * far outlier first: candidates per lookup stay those of a tree (0.1 fell
 * back to scanning lists: about 72x more at the origin). */
TEST(test_index_origin)
{
    irc_config cfg = scene_config(&dummy, 0, 4, 4);
    const uint32_t n = irc_t_quick ? 60 : 126;
    irc_cache *c = block_cache(&cfg, n * n + 1, 0);
    double at0, away, at0_out, away_out;
    CHECK(c != NULL, "init");
    if (!c) return;
    at0 = candidates(c, n, 0.0, 0);
    away = candidates(c, n, 1000.0, 0);
    at0_out = candidates(c, n, 0.0, 1);
    away_out = candidates(c, n, 1000.0, 1);
    printf("  %u records; entries scanned per lookup: at the origin %.1f, 1000 away %.1f, "
           "with an outlier first %.1f and %.1f\n", n * n, at0, away, at0_out, away_out);
    /* A record reaches 0.2 * 3.5 at most: a lookup's true neighbours are a
     * handful; a tree hands over a few dozen, a list thousands. */
    CHECK(at0 < 60.0, "at the origin: %.1f candidates", at0);
    CHECK(away < 60.0, "away: %.1f candidates", away);
    CHECK(at0_out < 60.0, "outlier first, at the origin: %.1f", at0_out);
    CHECK(away_out < 60.0, "outlier first, away: %.1f", away_out);
    block_free(&cfg);
}
