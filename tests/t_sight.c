/* t_sight.c -- confirming rays (irc_config.check_visibility): a record
 * behind a wall stops serving the far side; one in sight serves as
 * before, for exactly one more ray; the callback's results are checked. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "irrcache.h"
#include "scenes.h"
#include "test.h"

/* The wall: x in [-0.1, 0.1], 10 wide, through the plane of the points
 * (z = 0) from below to height 1, under a uniform sky. */
typedef struct sight_host {
    tscene s;          /* first: scene_trace reads the context as a tscene */
    int vis_calls;     /* callback calls with visibility_only set */
    int vis_rays;
    int bad_args;      /* confirming calls whose p, n or rays were not the
                          query's and unit directions toward a record */
    float q[3];        /* the query the test makes next */
} sight_host;

static int sight_trace(const irc_trace_args *a)
{
    sight_host *h = (sight_host *)a->context;
    uint32_t i;
    if (a->visibility_only) {
        h->vis_calls++;
        h->vis_rays += (int)a->count;
        if (a->p[0] != h->q[0] || a->p[1] != h->q[1] || a->p[2] != h->q[2] || a->n[2] != 1.0f)
            h->bad_args++;
        for (i = 0; i < a->count; i++) {
            const float *d = a->rays[i].dir;
            if (memcmp(a->rays[i].org, h->q, sizeof h->q) ||
                fabsf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 1.0f) > 1e-6f)
                h->bad_args++;
        }
    }
    return scene_trace(a);
}

static irc_cache *sight_cache(sight_host *h, irc_config *cfg, uint32_t check, uint32_t batch)
{
    static const double lo[3] = {-0.1, -5.0, -1.0}, hi[3] = {0.1, 5.0, 1.0};
    memset(h, 0, sizeof *h);
    h->s.sky_a[0] = h->s.sky_a[1] = h->s.sky_a[2] = 1.0f;
    h->s.has_box = 1;
    memcpy(h->s.box_lo, lo, sizeof lo);
    memcpy(h->s.box_hi, hi, sizeof hi);
    *cfg = scene_config(&h->s, 0, 8, 32);
    cfg->trace = sight_trace;
    cfg->check_visibility = check;
    cfg->max_batch = batch;
    return block_cache(cfg, 16, 0);
}

/* A record at x, E = 0.5, reach 0.2 x 20 = 4: wide enough for every
 * query here. */
static int put(irc_cache *c, float x)
{
    irc_record r;
    disk_record(&r, 0.5f, 20.0f);
    r.p[0] = x;
    return irc_cache_insert(c, &r);
}

TEST(test_sight_wall)
{
    static const float n[3] = {0, 0, 1};
    sight_host h;
    irc_config cfg;
    irc_cache *c;
    irc_stats st;
    float rgb[3], w;
    int on;
    for (on = 0; on < 2; on++) {
        c = sight_cache(&h, &cfg, on ? IRC_DEFAULT : IRC_OFF, 4);
        CHECK(c && put(c, -1.0f) == IRC_OK, "init");
        if (!c) return;
        h.q[0] = 1.0f;
        CHECK(irc_cache_lookup_or_compute(c, h.q, n, rgb, &w, &h) == IRC_OK &&
                  irc_cache_stats(c, &st) == IRC_OK, "lookup");
        if (on) {
            /* by default the record behind the wall (E 0.5) is left out: a record of
             * its own, which sees more than half the sky (E > pi / 2) */
            CHECK(st.records == 2 && st.computes == 1 && w == 0.0f && rgb[0] > 1.5708f &&
                      rgb[0] < 3.1416f,
                  "on: %llu records, w %g, E %g", (unsigned long long)st.records, (double)w,
                  (double)rgb[0]);
            CHECK(h.vis_calls == 1 && h.vis_rays == 1 && h.bad_args == 0 &&
                      st.rays == 1 + 8 * 32,
                  "on: %d calls, %d rays, %d bad, %llu rays counted", h.vis_calls, h.vis_rays,
                  h.bad_args, (unsigned long long)st.rays);
        } else {
            CHECK(st.records == 1 && w > 0.0f && rgb[0] == 0.5f && h.vis_calls == 0,
                  "off: %llu records, w %g, E %g", (unsigned long long)st.records,
                  (double)w, (double)rgb[0]);
        }
        block_free(&cfg);
    }
}

/* Records in sight: the same answer, bit for bit, as without the check,
 * for one ray a record, in batches of max_batch. */
TEST(test_sight_clear)
{
    static const float n[3] = {0, 0, 1};
    static const float xs[5] = {2.0f, 3.5f, 1.2f, 4.0f, -0.5f};
    sight_host h;
    irc_config cfg;
    irc_cache *c;
    irc_stats st;
    float rgb[2][3], w[2];
    int on, i;
    for (on = 0; on < 2; on++) {
        c = sight_cache(&h, &cfg, on ? IRC_ON : IRC_OFF, 2);
        CHECK(c != NULL, "init");
        if (!c) return;
        for (i = 0; i < 5; i++) {
            irc_record r;
            disk_record(&r, 0.2f + 0.1f * (float)i, 20.0f);
            r.p[0] = xs[i];
            r.p[1] = 0.3f * (float)i;
            CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert %d", i);
        }
        h.q[0] = 2.5f;
        h.q[1] = 0.25f;
        /* the one at x = -0.5 lies behind the wall */
        CHECK(irc_cache_lookup_or_compute(c, h.q, n, rgb[on], &w[on], &h) == IRC_OK &&
                  irc_cache_stats(c, &st) == IRC_OK && st.records == 5,
              "lookup %d", on);
        if (on)
            CHECK(h.vis_rays == 5 && h.vis_calls == 3 && h.bad_args == 0 && st.rays == 5,
                  "%d rays in %d calls, %d bad", h.vis_rays, h.vis_calls, h.bad_args);
        block_free(&cfg);
    }
    CHECK(w[1] < w[0] && w[1] > 0.0f, "weights %g (off) %g (on)", (double)w[0], (double)w[1]);
    /* without the hidden record (E 0.6) the mean moves away from it */
    CHECK(rgb[1][0] != rgb[0][0], "same mean %g", (double)rgb[0][0]);
}

/* A bad confirming hit is IRC_ERR_CALLBACK, a host code passes through;
 * neither leaves anything in the cache. */
TEST(test_sight_callback)
{
    static const float n[3] = {0, 0, 1};
    static const unsigned kinds[3] = {FAIL_BAD_STATUS, FAIL_NAN_DIST, FAIL_ZERO_DIST};
    sight_host h;
    irc_config cfg;
    irc_cache *c;
    irc_stats st;
    float rgb[3] = {7, 7, 7}, w = 7;
    int i;
    for (i = 0; i < 4; i++) {
        c = sight_cache(&h, &cfg, IRC_ON, 1);
        CHECK(c && put(c, 2.0f) == IRC_OK, "init");
        if (!c) return;
        h.q[0] = 1.0f;
        if (i < 3) {
            h.s.fail_every = 1;
            h.s.fail_kind = kinds[i];
        } else {
            h.s.return_code = -77;
        }
        CHECK(irc_cache_lookup_or_compute(c, h.q, n, rgb, &w, &h) ==
                  (i < 3 ? IRC_ERR_CALLBACK : -77),
              "case %d", i);
        CHECK(irc_cache_stats(c, &st) == IRC_OK && st.records == 1 && st.computes == 0 &&
                  rgb[0] == 7.0f && w == 7.0f,
              "case %d: %llu records, out touched", i, (unsigned long long)st.records);
        block_free(&cfg);
    }
}

/* A lookup-or-compute that fails after its lookup has read records or
 * cast confirming rays leaves the block byte for byte as it was: the rays
 * are not counted, the records' CLOCK bits are not left set (found by
 * fuzz_callback and fuzz_api; their inputs are in both corpora as
 * crash-failed-call-changed-block).
 *   0: a record behind the wall, one confirming ray, then a compute whose
 *      second ray fails;
 *   1: a record whose gradient extrapolates past FLT_MAX at the query:
 *      the lookup reads it (CLOCK on) and fails with IRC_ERR_NONFINITE;
 *      so does a plain lookup there (fuzz_api on an SH cache, corpus
 *      crash-failed-lookup-use-bits).
 * Without the undoing, case 0 counted the ray and case 1 left the bit. */
TEST(test_sight_failure_unchanged)
{
    static const float n[3] = {0, 0, 1};
    sight_host h;
    irc_config cfg;
    irc_cache *c;
    unsigned char *before;
    float rgb[3], w;
    int i, st;
    for (i = 0; i < 2; i++) {
        memset(&h, 0, sizeof h);
        c = sight_cache(&h, &cfg, i == 0 ? IRC_ON : IRC_OFF, 4);
        CHECK(c != NULL, "init");
        if (!c) return;
        irc_fini(c); /* again, with CLOCK's bits, gradients, no lock */
        cfg.port = &irc_port_none;
        cfg.evict = IRC_EVICT_CLOCK;
        cfg.features = IRC_FEATURE_TRANSLATION;
        free(cfg.buffer);
        c = block_cache(&cfg, 16, 0);
        CHECK(c != NULL, "init");
        if (!c) return;
        if (i == 0) {
            CHECK(put(c, -1.0f) == IRC_OK, "insert");
            h.s.fail_every = 2;
            h.s.fail_kind = FAIL_BAD_STATUS;
        } else {
            irc_record r;
            disk_record(&r, 3.3e38f, 20.0f); /* the gradient packs to E/R */
            r.p[0] = -1.0f;
            r.grad_t[0][0] = r.grad_t[1][0] = r.grad_t[2][0] = 2e38f;
            CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
        }
        h.q[0] = 1.0f;
        before = malloc(cfg.buffer_size);
        CHECK(before != NULL, "malloc");
        if (!before) return;
        memcpy(before, cfg.buffer, cfg.buffer_size);
        st = irc_cache_lookup_or_compute(c, h.q, n, rgb, &w, &h);
        CHECK(st == (i == 0 ? IRC_ERR_CALLBACK : IRC_ERR_NONFINITE), "case %d: status %d", i, st);
        CHECK(memcmp(before, cfg.buffer, cfg.buffer_size) == 0,
              "case %d: the failed call changed the block", i);
        if (i == 1) { /* the plain lookup reads and fails the same way */
            st = irc_cache_lookup(c, h.q, n, rgb, &w);
            CHECK(st == IRC_ERR_NONFINITE && memcmp(before, cfg.buffer, cfg.buffer_size) == 0,
                  "a failed plain lookup changed the block (status %d)", st);
        }
        free(before);
        block_free(&cfg);
    }
}

/* A unit ball at the origin under a uniform sky, its rays lifted 1e-4
 * off the surface as hosts lift them (irc_ray.org). */
static int ball_trace(const irc_trace_args *a)
{
    int *vis_rays = (int *)a->context;
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        const float *d = a->rays[i].dir;
        float o[3], b, c, disc, t;
        int k;
        for (k = 0; k < 3; k++)
            o[k] = a->rays[i].org[k] + 1e-4f * a->n[k];
        b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
        c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1.0f;
        disc = b * b - c;
        t = disc > 0.0f ? -b - sqrtf(disc) : -1.0f;
        a->hits[i].status = t > 0.0f ? IRC_RAY_HIT : IRC_RAY_ESCAPED;
        a->hits[i].dist = t;
        for (k = 0; k < 3; k++) {
            a->hits[i].normal[k] = o[k] + t * d[k];
            a->hits[i].radiance[k] = t > 0.0f ? 0.0f : 1.0f;
        }
    }
    if (a->visibility_only)
        *vis_rays += (int)a->count;
    return 0;
}

/* On a ball a record 0.1 radians from the query lies 1.2e-3 under the
 * chord's start, twelve times the host's lift: a ray along the chord meets
 * the ball at once.  The record whose normal turns with the surface is in
 * sight (no record made: before, every lookup on a curved surface hid its
 * records and made one of its own); one at the same place whose normal is
 * the query's (the dip not explained: a record past a ledge) stays hidden. */
TEST(test_sight_convex)
{
    const float q[3] = {sinf(0.1f), 0.0f, cosf(0.1f)};
    irc_config cfg;
    irc_cache *c;
    irc_stats st;
    float rgb[3], w;
    int tilted, vis_rays;
    for (tilted = 0; tilted < 2; tilted++) {
        irc_record r;
        memset(&cfg, 0, sizeof cfg);
        cfg.version = IRC_CONFIG_VERSION;
        cfg.trace = ball_trace;
        cfg.context = &vis_rays;
        cfg.strata_theta = 4;
        cfg.strata_phi = 16;
        c = block_cache(&cfg, 16, 0);
        CHECK(c != NULL, "init");
        if (!c) return;
        disk_record(&r, 0.5f, 20.0f);
        r.p[2] = 1.0f; /* the ball's top, normal +z */
        if (tilted)
            memcpy(r.n, q, sizeof r.n);
        CHECK(irc_cache_insert(c, &r) == IRC_OK, "insert");
        vis_rays = 0;
        CHECK(irc_cache_lookup_or_compute(c, q, q, rgb, &w, NULL) == IRC_OK &&
                  irc_cache_stats(c, &st) == IRC_OK && vis_rays == 1,
              "lookup (%d confirming rays)", vis_rays);
        if (!tilted)
            CHECK(st.records == 1 && w > 0.0f && rgb[0] == 0.5f,
                  "the record on the ball was hidden: %llu records, w %g, E %g",
                  (unsigned long long)st.records, (double)w, (double)rgb[0]);
        else
            CHECK(st.records == 2 && w == 0.0f && rgb[0] > 3.0f,
                  "a dip the normals do not explain was let through: %llu records, w %g",
                  (unsigned long long)st.records, (double)w);
        block_free(&cfg);
    }
}
