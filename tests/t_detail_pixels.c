/* t_detail_pixels.c -- per-pixel detail (cfg.irr.detail_pixels) beside a black wall. */
#include <math.h>
#include <string.h>

#include "irrcache.h"
#include "scenes.h"
#include "test.h"

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
