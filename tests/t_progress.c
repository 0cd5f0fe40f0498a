/* t_progress.c -- progressive caches: a record's rays follow the schedule
 * (counted), its noise falls as 1/sqrt(rays) against a closed form, the
 * refinement is the same at any thread count, a pixel's answer is kept
 * until the records refine and a kept detail estimate gets exactly the
 * rays it lacks; calls that cannot be taken are refused and change
 * nothing. */
#define IRC_EXPERIMENTAL /* irc_progress, irc_cache_lookup_pixel (irrcache.h) */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"
#include "irr/estimator.h"
#include "scenes.h"
#include "test.h"

/* The tests' sample counts are written for a schedule whose records reach
 * the configured grid at 256 samples; Q scales them to the library's. */
#define Q (IRC__PROGRESS_FULL / 256u)

/* A sky whose radiance along each ray is a hash of its direction's bits,
 * uniform in [0, 2): mean 1, so E = pi exactly, and no two rays alike (no
 * smoothness for the strata to exploit: the variance of a mean of r rays
 * is 1/(3 r) per ray's radiance, exactly). */
static int noisy_trace(const irc_trace_args *a)
{
    tscene *s = (tscene *)a->context;
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        uint64_t h = 0x9e3779b97f4a7c15ull;
        uint32_t b[3];
        int k;
        memcpy(b, a->rays[i].dir, sizeof b);
        for (k = 0; k < 3; k++) {
            h ^= b[k];
            h *= 0xff51afd7ed558ccdull;
            h ^= h >> 33;
        }
        a->hits[i].status = IRC_RAY_ESCAPED;
        for (k = 0; k < 3; k++)
            a->hits[i].radiance[k] = (float)((double)(h >> 11) * 0x1p-53 * 2.0);
    }
    if (s->fail_every && ++s->calls == s->fail_every)
        return -77;
    return 0;
}

/* 8 x 32 strata: the coarsest grid is 4 x 16, T0 = 64 rays; level(s) =
 * max(0, 2 + log2(s / Q) - 8). */
static irc_cache *noisy_cache(tscene *s, irc_config *cfg, uint32_t batch)
{
    scene_init(s);
    *cfg = scene_config(s, 0, 8, 32);
    cfg->trace = noisy_trace;
    cfg->max_batch = batch;
    cfg->max_radius = 1.0f;
    cfg->clamp_neighbours = IRC_OFF;
    return block_cache(cfg, 64, 0);
}

#define NPTS 48

static void noisy_point(int i, float p[3])
{
    p[0] = (float)(i % 8) * 3.0f;
    p[1] = (float)(i / 8) * 3.0f;
    p[2] = 0.0f;
}

/* The rays a record holds at each level are T0 2^l (closed form of the
 * schedule), and its irradiance's RMS error over NPTS points falls with
 * them as 1/sqrt(rays) (variance 1/(3 r) of a mean of uniforms on [0, 2),
 * times pi^2 for E). */
TEST(test_progress_rays_and_noise)
{
    static const uint32_t samples[4] = {1, 128 * Q, 512 * Q, 4096 * Q};
    static const uint32_t rays[4] = {64, 128, 512, 4096};
    const float up[3] = {0, 0, 1};
    double rms[4];
    int l;
    for (l = 0; l < 4; l++) {
        tscene s;
        irc_config cfg;
        irc_cache *c = noisy_cache(&s, &cfg, 0);
        double se = 0.0;
        int i, rays_ok = 1;
        CHECK(c != NULL, "cache");
        if (!c)
            return;
        CHECK(irc_progress(c, samples[l], NULL) == IRC_OK, "progress %u", samples[l]);
        for (i = 0; i < NPTS; i++) {
            irc_record r;
            float p[3];
            noisy_point(i, p);
            if (irc_record_compute(c, p, up, &r, NULL) != IRC_OK) {
                rays_ok = 0;
                continue;
            }
            rays_ok &= r.rays == rays[l];
            se += (r.e[0] - TPI) * (r.e[0] - TPI);
        }
        CHECK(rays_ok, "a record at %u samples casts %u rays", samples[l], rays[l]);
        rms[l] = sqrt(se / NPTS);
        /* the expected RMS is pi / sqrt(3 r); 48 points: within 35% */
        CHECK(fabs(rms[l] / (TPI / sqrt(3.0 * rays[l])) - 1.0) < 0.35,
              "RMS %.5f at %u rays, expected %.5f", rms[l], rays[l], TPI / sqrt(3.0 * rays[l]));
        block_free(&cfg);
    }
    CHECK(rms[3] < rms[0] / 5.0, "noise from 64 to 4096 rays: %.5f -> %.5f", rms[0], rms[3]);
}

/* Stored records refined by irc_progress: each gets exactly the rays it
 * lacked (the cache's ray counter), and their errors against E = pi fall
 * as for records made at that level; a record made at a level and one
 * refined to it differ only by the refinement's draws at the stored
 * (quantized) normal. */
TEST(test_progress_refines_stored)
{
    tscene s;
    irc_config cfg;
    irc_cache *c = noisy_cache(&s, &cfg, 0);
    const float up[3] = {0, 0, 1};
    irc_stats a, b;
    double se0 = 0.0, se1 = 0.0;
    int i;
    CHECK(c != NULL, "cache");
    if (!c)
        return;
    CHECK(irc_progress(c, 1 * Q, NULL) == IRC_OK, "progress");
    for (i = 0; i < NPTS; i++) {
        float p[3], rgb[3], w;
        noisy_point(i, p);
        CHECK(irc_cache_lookup_or_compute(c, p, up, rgb, &w, NULL) == IRC_OK, "compute %d", i);
        se0 += (rgb[0] - TPI) * (rgb[0] - TPI);
    }
    CHECK(irc_cache_stats(c, &a) == IRC_OK && a.records == NPTS, "%llu records",
          (unsigned long long)a.records);
    CHECK(irc_progress(c, 4095 * Q, NULL) == IRC_OK, "refine");
    CHECK(irc_cache_stats(c, &b) == IRC_OK, "stats");
    CHECK(b.rays - a.rays == (uint64_t)NPTS * (2048 - 64), "refinement cast %llu rays",
          (unsigned long long)(b.rays - a.rays));
    for (i = 0; i < NPTS; i++) {
        irc_record r;
        CHECK(irc_cache_record(c, (uint32_t)i, &r) == IRC_OK, "record %d", i);
        se1 += (r.e[0] - TPI) * (r.e[0] - TPI);
    }
    se0 = sqrt(se0 / NPTS);
    se1 = sqrt(se1 / NPTS);
    CHECK(se1 < se0 / 3.5 && fabs(se1 / (TPI / sqrt(3.0 * 2048)) - 1.0) < 0.35,
          "stored records' RMS %.5f -> %.5f (expected %.5f)", se0, se1, TPI / sqrt(3.0 * 2048));
    /* the same samples again: nothing to do */
    CHECK(irc_progress(c, 2048 * Q, NULL) == IRC_OK && irc_cache_stats(c, &a) == IRC_OK &&
              a.rays == b.rays, "no refinement within a level");
    block_free(&cfg);
}

/* Refusals change nothing: samples that fall back in a cache with
 * records, a pass open, SH and visibility caches. */
TEST(test_progress_refused)
{
    tscene s;
    irc_config cfg, sh, vis;
    irc_cache *c = noisy_cache(&s, &cfg, 0), *d;
    const float up[3] = {0, 0, 1}, p[3] = {0, 0, 0};
    unsigned char *copy;
    float rgb[3], w;
    CHECK(c != NULL, "cache");
    if (!c)
        return;
    CHECK(irc_progress(c, 512 * Q, NULL) == IRC_OK, "progress");
    CHECK(irc_cache_lookup_or_compute(c, p, up, rgb, &w, NULL) == IRC_OK, "compute");
    copy = malloc(cfg.buffer_size);
    if (copy) {
        memcpy(copy, cfg.buffer, cfg.buffer_size);
        CHECK(irc_progress(c, 4 * Q, NULL) == IRC_ERR_RANGE, "fall back with records");
        CHECK(irc_pass_begin(c) == IRC_OK, "begin");
        memcpy(copy, cfg.buffer, cfg.buffer_size);
        CHECK(irc_progress(c, 1024 * Q, NULL) == IRC_ERR_STATE, "in a pass");
        CHECK(block_same(&cfg, copy, c), "a refused call changed the block");
        CHECK(irc_pass_end(c, NULL) == IRC_OK, "end");
        free(copy);
    }
    CHECK(irc_cache_clear(c) == IRC_OK && irc_progress(c, 4 * Q, NULL) == IRC_OK,
          "an empty cache starts again");
    CHECK(irc_progress(NULL, 4, NULL) == IRC_ERR_NULL, "NULL cache");
    block_free(&cfg);

    scene_init(&s);
    sh = scene_config(&s, IRC_FEATURE_SH, 0, 0);
    if ((d = block_cache(&sh, 16, 0)) != NULL) {
        CHECK(irc_progress(d, 4 * Q, NULL) == IRC_ERR_UNSUPPORTED, "SH records");
        block_free(&sh);
    }
    vis = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_VISIBILITY, 8, 32);
    if ((d = block_cache(&vis, 16, 0)) != NULL) {
        CHECK(irc_progress(d, 4 * Q, NULL) == IRC_ERR_UNSUPPORTED, "visibility gradients");
        block_free(&vis);
    }
}

/* A callback that fails in the middle of a refinement: the code comes
 * back, the records before it are refined and those after are not, and
 * the cache is at the new level (a later call refines nobody twice). */
TEST(test_progress_callback_fails)
{
    tscene s;
    irc_config cfg;
    /* 64 rays a trace call: level 0 -> 1 is one call a record */
    irc_cache *c = noisy_cache(&s, &cfg, 64);
    const float up[3] = {0, 0, 1};
    irc_record before[8], after;
    irc_stats a, b;
    int i, changed = 0, kept = 0;
    CHECK(c != NULL, "cache");
    if (!c)
        return;
    CHECK(irc_progress(c, 1 * Q, NULL) == IRC_OK, "progress");
    for (i = 0; i < 8; i++) {
        float p[3], rgb[3], w;
        noisy_point(i, p);
        CHECK(irc_cache_lookup_or_compute(c, p, up, rgb, &w, NULL) == IRC_OK, "compute");
        CHECK(irc_cache_record(c, (uint32_t)i, &before[i]) == IRC_OK, "read");
    }
    s.calls = 0;
    s.fail_every = 4; /* the 4th record's */
    CHECK(irc_cache_stats(c, &a) == IRC_OK, "stats");
    CHECK(irc_progress(c, 128 * Q, NULL) == -77, "the callback's code");
    s.fail_every = 0;
    CHECK(irc_cache_stats(c, &b) == IRC_OK && b.rays == a.rays + 3 * 64,
          "rays of the refined records: %llu", (unsigned long long)(b.rays - a.rays));
    for (i = 0; i < 8; i++) {
        CHECK(irc_cache_record(c, (uint32_t)i, &after) == IRC_OK, "read");
        if (i < 3)
            changed += after.e[0] != before[i].e[0];
        else
            kept += after.e[0] == before[i].e[0];
    }
    CHECK(changed == 3 && kept == 5, "refined %d of 3, kept %d of 5", changed, kept);
    CHECK(irc_progress(c, 128 * Q, NULL) == IRC_OK && irc_cache_stats(c, &a) == IRC_OK &&
              a.rays == b.rays, "the level was taken: nothing refined twice");
    block_free(&cfg);
}

typedef struct part {
    irc_cache *c;
    int first, step, fail;
} part;

static void *fill_part(void *arg)
{
    part *k = (part *)arg;
    const float up[3] = {0, 0, 1};
    int i;
    for (i = k->first; i < 400; i += k->step) {
        float p[3] = {(float)(i % 20) * 0.3f - 3.0f, (float)(i / 20) * 0.3f - 3.0f, 0.0f}, rgb[3];
        if (irc_cache_lookup_or_compute(k->c, p, up, rgb, NULL, NULL) < 0)
            k->fail = 1;
    }
    return NULL;
}

/* A progressive cache filled in passes on 1 and 3 threads, refined twice:
 * the same snapshot, byte for byte. */
static size_t threaded_fill(int threads, unsigned char **snap)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    size_t bytes = 0;
    int t, pass, fail = 0;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    cfg.max_radius = 4.0f;
    cfg.threads = 3;
    *snap = NULL;
    if (!(c = block_cache(&cfg, 2048, 0)))
        return 0;
    CHECK(irc_progress(c, 16 * Q, NULL) == IRC_OK, "progress");
    for (pass = 0; pass < 2; pass++) {
        pthread_t th[3];
        part k[3];
        CHECK(irc_pass_begin(c) == IRC_OK, "begin");
        for (t = 0; t < threads; t++) {
            k[t].c = c;
            k[t].first = t;
            k[t].step = threads;
            k[t].fail = 0;
            pthread_create(&th[t], NULL, fill_part, &k[t]);
        }
        for (t = 0; t < threads; t++) {
            pthread_join(th[t], NULL);
            fail |= k[t].fail;
        }
        CHECK(irc_pass_end(c, NULL) == IRC_OK, "end");
        CHECK(irc_progress(c, (pass ? 1024 : 256) * Q, NULL) == IRC_OK, "refine");
    }
    CHECK(!fail, "a lookup failed");
    if (irc_snapshot_size(c, &bytes) == IRC_OK && (*snap = malloc(bytes)) != NULL)
        CHECK(irc_snapshot_write(c, 7u, *snap, bytes, NULL, NULL, NULL) == IRC_OK, "write");
    block_free(&cfg);
    return bytes;
}

TEST(test_progress_threads)
{
    unsigned char *a, *b;
    size_t na = threaded_fill(1, &a), nb = threaded_fill(3, &b);
    CHECK(na > 48 && na == nb && a && b && memcmp(a, b, na) == 0,
          "1 and 3 threads: %zu and %zu bytes, %s", na, nb,
          a && b && na == nb && !memcmp(a, b, na) ? "same" : "different");
    free(a);
    free(b);
}

/* A progressive render of a 16 x 16 "image" (points on the plane under
 * the sphere, jittered within their pixel by the pixel's own random
 * numbers): each iteration a pass, every pixel one irc_cache_lookup_pixel
 * call, then irc_progress; the pixels' sums after 12 iterations, bit for
 * bit the same on 1, 2 and 4 threads (3 scratch slots). */
#define IMG 16
typedef struct rpart {
    irc_cache *c;
    irc_pixel *pix;
    double *sum;
    int first, step, iter, fail;
} rpart;

static void *render_part(void *arg)
{
    rpart *k = (rpart *)arg;
    const float up[3] = {0, 0, 1};
    int i;
    for (i = k->first; i < IMG * IMG; i += k->step) {
        unsigned long long st = 0x9e3779b97f4a7c15ull * (unsigned long long)(i + 1) +
                                (unsigned long long)k->iter;
        float p[3], rgb[3];
        p[0] = ((float)(i % IMG) + (float)xrand(&st)) * 0.25f - 2.0f;
        p[1] = ((float)(i / IMG) + (float)xrand(&st)) * 0.25f - 2.0f;
        p[2] = 0.0f;
        if (irc_cache_lookup_pixel(k->c, &k->pix[i], p, up, NULL, 0.25f, rgb, NULL, NULL) < 0)
            k->fail = 1;
        else
            k->sum[i] += rgb[0] + rgb[1] + rgb[2];
    }
    return NULL;
}

static int render_threads(int threads, double *sum)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    static irc_pixel pix[IMG * IMG];
    int it, t, fail = 0;
    scene_sphere_plane(&s);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    cfg.max_radius = 4.0f;
    cfg.threads = 3;
    memset(pix, 0, sizeof pix);
    memset(sum, 0, sizeof(double) * IMG * IMG);
    if (!(c = block_cache(&cfg, 4096, 0)))
        return -1;
    fail |= irc_progress(c, 0, NULL) < 0;
    for (it = 0; it < 12 && !fail; it++) {
        pthread_t th[4];
        rpart k[4];
        fail |= irc_pass_begin(c) < 0;
        for (t = 0; t < threads; t++) {
            k[t].c = c, k[t].pix = pix, k[t].sum = sum;
            k[t].first = t, k[t].step = threads, k[t].iter = it, k[t].fail = 0;
            pthread_create(&th[t], NULL, render_part, &k[t]);
        }
        for (t = 0; t < threads; t++) {
            pthread_join(th[t], NULL);
            fail |= k[t].fail;
        }
        fail |= irc_pass_end(c, NULL) < 0;
        /* 32 samples an iteration as far as the schedule goes: a new level
         * at iterations 2, 4 and 8 */
        fail |= irc_progress(c, 32u * Q * (uint32_t)(it + 1), NULL) < 0;
    }
    block_free(&cfg);
    return fail ? -1 : 0;
}

TEST(test_progress_image_threads)
{
    static double one[IMG * IMG], two[IMG * IMG], four[IMG * IMG];
    int ok = render_threads(1, one) == 0 && render_threads(2, two) == 0 &&
             render_threads(4, four) == 0;
    CHECK(ok, "a render failed");
    CHECK(ok && !memcmp(one, two, sizeof one) && !memcmp(one, four, sizeof one),
          "1, 2 and 4 threads: the images differ");
    CHECK(one[0] > 0.0 && one[IMG * IMG - 1] > 0.0, "an image of light");
}

/* irc_cache_lookup_pixel: a kept answer serves the pixel's nearby points
 * with no lookup until the cache refines; a point 3 footprints away, or
 * on another surface, is looked up; a kept detail estimate gets exactly
 * the rays it lacks; bad input changes nothing. */
TEST(test_pixel_kept)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_pixel px, copy;
    const float up[3] = {0, 0, 1}, wall[3] = {-1, 0, 0};
    const double lo[3] = {0.1, -0.2, 0.0}, hi[3] = {0.5, 0.2, 0.3};
    float p[3] = {-2.0f, 0.0f, 0.0f}, rgb[3], rgb2[3], w;
    irc_stats a, b;
    int st;
    scene_sphere_plane(&s);
    s.has_box = 1; /* a box standing on the plane beside the origin */
    memcpy(s.box_lo, lo, sizeof lo);
    memcpy(s.box_hi, hi, sizeof hi);
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    cfg.max_radius = 4.0f;
    cfg.check_visibility = IRC_OFF; /* a lookup casts no ray: probes counted alone */
    if (!(c = block_cache(&cfg, 256, 0)))
        return;
    memset(&px, 0, sizeof px);
    CHECK(irc_progress(c, 4 * Q, NULL) == IRC_OK, "progress");
    CHECK(irc_cache_lookup_pixel(c, &px, p, up, NULL, 0.01f, rgb, &w, NULL) == IRC_OK, "first");
    irc_cache_stats(c, &a);
    p[0] += 0.015f; /* within 2 footprints */
    st = irc_cache_lookup_pixel(c, &px, p, up, NULL, 0.01f, rgb2, &w, NULL);
    irc_cache_stats(c, &b);
    CHECK(st == IRC_OK && b.lookups == a.lookups && !memcmp(rgb, rgb2, sizeof rgb),
          "kept: status %d, %llu lookups more", st, (unsigned long long)(b.lookups - a.lookups));
    p[0] += 0.03f; /* 4.5 footprints from the first */
    CHECK(irc_cache_lookup_pixel(c, &px, p, up, NULL, 0.01f, rgb2, &w, NULL) == IRC_OK, "moved");
    irc_cache_stats(c, &a);
    CHECK(a.lookups == b.lookups + 1, "a point 4.5 footprints away is looked up");
    /* a point on another surface (the box's side) takes the other answer;
     * both then serve without lookups */
    {
        float q[3] = {0.1f, 0.0f, 0.15f};
        CHECK(irc_cache_lookup_pixel(c, &px, q, wall, NULL, 0.01f, rgb2, &w, NULL) >= 0, "wall");
        irc_cache_stats(c, &b);
        CHECK(irc_cache_lookup_pixel(c, &px, p, up, NULL, 0.01f, rgb2, &w, NULL) >= 0 &&
                  irc_cache_lookup_pixel(c, &px, q, wall, NULL, 0.01f, rgb2, &w, NULL) >= 0 &&
                  irc_cache_stats(c, &a) == IRC_OK && a.lookups == b.lookups,
              "two surfaces: %llu lookups more", (unsigned long long)(a.lookups - b.lookups));
    }
    /* refined: looked up again, without the 8 probes (the point was no
     * detail), so with no ray at all */
    CHECK(irc_progress(c, 128 * Q, NULL) == IRC_OK, "refine");
    irc_cache_stats(c, &b);
    CHECK(irc_cache_lookup_pixel(c, &px, p, up, NULL, 0.01f, rgb2, &w, NULL) == IRC_OK &&
              irc_cache_stats(c, &a) == IRC_OK && a.lookups == b.lookups + 1 &&
              a.rays == b.rays,
          "after a refinement the next sample looks up: %llu lookups, %llu rays",
          (unsigned long long)(a.lookups - b.lookups), (unsigned long long)(a.rays - b.rays));
    /* bad input: an error, *pixel as it was */
    memcpy(&copy, &px, sizeof px);
    p[1] = NAN;
    CHECK(irc_cache_lookup_pixel(c, &px, p, up, NULL, 0.01f, rgb2, &w, NULL) == IRC_ERR_NONFINITE &&
              !memcmp(&copy, &px, sizeof px), "NaN point");
    p[1] = 0.0f;
    CHECK(irc_cache_lookup_pixel(c, NULL, p, up, NULL, 0.01f, rgb2, &w, NULL) == IRC_ERR_NULL, "NULL");
    CHECK(irc_cache_lookup_pixel(c, &px, p, up, NULL, -1.0f, rgb2, &w, NULL) == IRC_ERR_RANGE &&
              !memcmp(&copy, &px, sizeof px), "negative footprint");

    /* A detail point: the box's wall within half a footprint of the
     * origin (footprint 1).  At level 1 (128 samples) a new estimate is
     * level 0's, 64 rays after the probes; kept; at level 2 (256) a kept
     * one is taken to level 2 - top = 1 (top = 1 for 8 x 32): exactly the
     * 64 rays it lacks (128 - 64) and no probe. */
    {
        const float o[3] = {0.0f, 0.0f, 0.0f};
        irc_pixel d;
        memset(&d, 0, sizeof d);
        irc_cache_stats(c, &a);
        CHECK(irc_cache_lookup_pixel(c, &d, o, up, NULL, 1.0f, rgb, &w, NULL) == IRC_DETAIL, "detail");
        irc_cache_stats(c, &b);
        CHECK(b.details == a.details + 1 && b.rays - a.rays <= 64 + 8 && b.rays - a.rays > 64,
              "a new detail at level 1: %llu rays", (unsigned long long)(b.rays - a.rays));
        CHECK(irc_cache_lookup_pixel(c, &d, o, up, NULL, 1.0f, rgb2, &w, NULL) == IRC_DETAIL &&
                  irc_cache_stats(c, &a) == IRC_OK && a.rays == b.rays &&
                  !memcmp(rgb, rgb2, sizeof rgb),
              "kept detail");
        CHECK(irc_progress(c, 256 * Q, NULL) == IRC_OK, "refine");
        irc_cache_stats(c, &a);
        CHECK(irc_cache_lookup_pixel(c, &d, o, up, NULL, 1.0f, rgb2, &w, NULL) == IRC_DETAIL, "again");
        irc_cache_stats(c, &b);
        CHECK(b.rays - a.rays == 64 && memcmp(rgb, rgb2, sizeof rgb) != 0,
              "a kept detail refined with %llu rays (64 lacked)",
              (unsigned long long)(b.rays - a.rays));
    }
    block_free(&cfg);
}

/* A progressive _px record reaches a pixel at least (a R >= footprint:
 * a smaller one serves its own point alone, and every level's samples
 * would make another beside it), where a plain cache's is the
 * geometry's; and a kept answer's point looked up again after a
 * refinement takes a record within blend a R rather than making one. */
TEST(test_progress_pixel_records)
{
    tscene s;
    irc_config cfg;
    irc_cache *c;
    irc_pixel px;
    irc_record r;
    irc_stats a, b;
    const float up[3] = {0, 0, 1};
    float p[3] = {0.3f, 0.0f, 0.0f}, rgb[3], w, d;
    int prog;
    scene_sphere_plane(&s);
    for (prog = 0; prog < 2; prog++) {
        cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
        cfg.accuracy = 0.2f;
        cfg.max_radius = 100.0f;
        if (!(c = block_cache(&cfg, 64, 0)))
            return;
        CHECK(!prog || irc_progress(c, 4 * Q, NULL) == IRC_OK, "progress");
        CHECK(irc_cache_lookup_or_compute_px(c, p, up, NULL, 2.0f, rgb, &w, NULL) == IRC_OK &&
                  irc_cache_record(c, 0, &r) == IRC_OK, "a record");
        CHECK(prog ? r.radius >= 2.0f / 0.2f * 0.9999f : r.radius < 10.0f,
              "%s: R %.3f against footprint / a = 10", prog ? "progressive" : "plain", r.radius);
        block_free(&cfg);
    }
    cfg = scene_config(&s, IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION, 8, 32);
    cfg.accuracy = 0.2f;
    cfg.max_radius = 100.0f;
    if (!(c = block_cache(&cfg, 64, 0)))
        return;
    memset(&px, 0, sizeof px);
    CHECK(irc_progress(c, 4 * Q, NULL) == IRC_OK, "progress");
    CHECK(irc_cache_lookup_pixel(c, &px, p, up, NULL, 1e-3f, rgb, &w, NULL) == IRC_OK &&
              irc_cache_record(c, 0, &r) == IRC_OK, "the pixel's record");
    CHECK(irc_progress(c, 128 * Q, NULL) == IRC_OK, "refine");
    irc_cache_stats(c, &a);
    d = 1.5f * 0.2f * r.radius; /* past a R, within blend a R = 2 a R */
    p[0] += d;
    CHECK(irc_cache_lookup_pixel(c, &px, p, up, NULL, d, rgb, &w, NULL) == IRC_OK && w > 0.0f,
          "answered from the record: weight %g", w);
    irc_cache_stats(c, &b);
    CHECK(b.computes == a.computes && b.lookups == a.lookups + 1,
          "%llu records made for the pixel's next level", (unsigned long long)(b.computes - a.computes));
    block_free(&cfg);
}
