/* t_normals.c -- both normals taken by the _px call: the shading normal
 * gathered around, the rays below the geometric surface never cast.  The
 * host here is the surface z = 0 itself: a ray leaving below it hits it
 * at once (what a tracer reports for a ray started on its own surface),
 * and is counted. */
#define IRC_EXPERIMENTAL /* irc_cache_lookup_pixel */
#include <math.h>
#include <string.h>

#include "scenes.h"
#include "test.h"

typedef struct {
    tscene s;
    unsigned below, cast, confirm_below;
} ground;

/* A uniform sky over z = 0: every ray above sees L; one below finds the
 * surface at 1e-6 (black). */
static int ground_trace(const irc_trace_args *a)
{
    ground *g = (ground *)a->context;
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        const float *d = a->rays[i].dir;
        irc_hit *h = &a->hits[i];
        g->cast++;
        if (d[2] <= 0.0f) {
            g->below += a->visibility_only != IRC_VISIBILITY_CONFIRM;
            g->confirm_below += a->visibility_only == IRC_VISIBILITY_CONFIRM;
            h->status = IRC_RAY_HIT;
            h->dist = 1e-6f;
            h->normal[0] = h->normal[1] = 0.0f;
            h->normal[2] = 1.0f;
            h->radiance[0] = h->radiance[1] = h->radiance[2] = 0.0f;
        } else {
            h->status = IRC_RAY_ESCAPED;
            h->radiance[0] = h->radiance[1] = h->radiance[2] = 1.0f;
        }
    }
    return 0;
}

static irc_cache *ground_cache(ground *g, irc_config *cfg)
{
    memset(g, 0, sizeof *g);
    *cfg = (irc_config)IRC_CONFIG_INIT;
    cfg->trace = ground_trace;
    cfg->context = g;
    cfg->strata_theta = 8;
    cfg->strata_phi = 32;
    cfg->max_radius = 1.0f;
    return block_cache(cfg, 64, 0);
}

/* A shading normal `deg` degrees from +z toward +x. */
static void tilted(double deg, float n[3])
{
    n[0] = (float)sin(deg * TPI / 180.0);
    n[1] = 0.0f;
    n[2] = (float)cos(deg * TPI / 180.0);
}

/* Tilted 40 degrees, with the geometric normal given (either side, any
 * length): no ray of the record or of the probes leaves below z = 0, and
 * E is pi L (every usable stratum sees the sky; the below ones are left
 * out); the record keeps the shading normal.  Without ng the host is
 * asked for the rays below, which find the surface: the record is dark
 * and tiny.  70 degrees apart: the point gathers around ng. */
TEST(test_normals_both)
{
    static const float ups[2][3] = {{0, 0, 1}, {0, 0, -3}};
    const float p[3] = {0, 0, 0};
    float n[3], rgb[3], w;
    ground g;
    irc_config cfg;
    irc_cache *c;
    irc_record r;
    int i;
    tilted(40.0, n);
    for (i = 0; i < 2; i++) {
        c = ground_cache(&g, &cfg);
        CHECK(c && irc_cache_lookup_or_compute_px(c, p, n, ups[i], 0.01f, rgb, &w, NULL) == IRC_OK,
              "ng %d: computed", i);
        CHECK(g.below == 0 && g.cast > 0, "ng %d: %u of %u rays cast below the surface", i,
              g.below, g.cast);
        CHECK(fabs(rgb[0] - TPI) < 1e-4 * TPI, "ng %d: E %g, want pi", i, rgb[0]);
        CHECK(c && irc_cache_record(c, 0, &r) == IRC_OK && fabsf(r.n[0] - n[0]) < 1e-3f &&
                  fabsf(r.n[2] - n[2]) < 1e-3f,
              "ng %d: the record's normal is the shading one", i);
        block_free(&cfg);
    }
    c = ground_cache(&g, &cfg);
    CHECK(c && irc_cache_lookup_or_compute_px(c, p, n, NULL, 0.01f, rgb, &w, NULL) >= 0 &&
              g.below > 0 && rgb[0] < 0.9 * TPI,
          "without ng: %u rays below, E %g", g.below, rgb[0]);
    block_free(&cfg);
    tilted(70.0, n);
    c = ground_cache(&g, &cfg);
    CHECK(c && irc_cache_lookup_or_compute_px(c, p, n, ups[0], 0.01f, rgb, &w, NULL) == IRC_OK &&
              irc_cache_record(c, 0, &r) == IRC_OK && fabsf(r.n[2] - 1.0f) < 1e-3f &&
              g.below == 0 && fabs(rgb[0] - TPI) < 1e-4 * TPI,
          "70 degrees apart: gathered around ng (normal z %g, %u below, E %g)", r.n[2], g.below,
          rgb[0]);
    block_free(&cfg);
}

/* A bad ng is refused before anything is cast or counted; the pixel
 * call takes ng as the _px call does. */
TEST(test_normals_refused)
{
    static const float zero[3] = {0, 0, 0}, nan3[3] = {0, NAN, 1}, up[3] = {0, 0, 1};
    const float p[3] = {0, 0, 0};
    float n[3], rgb[3] = {7, 7, 7}, w = 7;
    ground g;
    irc_config cfg;
    irc_cache *c = ground_cache(&g, &cfg);
    irc_stats st;
    irc_pixel px;
    tilted(40.0, n);
    CHECK(c && irc_cache_lookup_or_compute_px(c, p, n, zero, 0.01f, rgb, &w, NULL) == IRC_ERR_NORMAL &&
              irc_cache_lookup_or_compute_px(c, p, n, nan3, 0.01f, rgb, &w, NULL) == IRC_ERR_NORMAL,
          "zero or NaN ng");
    CHECK(c && irc_cache_stats(c, &st) == IRC_OK && st.lookups == 0 && st.records == 0 &&
              g.cast == 0 && rgb[0] == 7.0f && w == 7.0f,
          "refused: nothing cast, counted or written");
    memset(&px, 0, sizeof px);
    CHECK(c && irc_cache_lookup_pixel(c, &px, p, n, zero, 0.01f, rgb, &w, NULL) == IRC_ERR_NORMAL,
          "pixel: zero ng");
    CHECK(c && irc_cache_lookup_pixel(c, &px, p, n, up, 0.01f, rgb, &w, NULL) == IRC_OK &&
              g.below == 0 && fabs(rgb[0] - TPI) < 1e-4 * TPI,
          "pixel: %u below, E %g", g.below, rgb[0]);
    block_free(&cfg);
}
