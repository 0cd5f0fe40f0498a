/*
 * bounces.c -- make bench-bounces: scenes of several bounces of indirect
 * light (bench.h bscene.bounces), where the reference and brute force are
 * path tracing with next-event estimation at every vertex (N hemisphere
 * rays at the camera's hit, one path each beyond), against the cache at
 * the first level with path-traced gathers (pbrt-v2's way) and a cache at
 * every level (Radiance's -ab N).  Then the rule for deeper levels'
 * accuracy, strata and confirming rays, one setting changed at a time
 * from the demo's defaults at a = 0.2.
 */
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* The demo's settings for deeper levels (render_opts_defaults). */
static void level_defaults(render_opts *o)
{
    render_opts d;
    render_opts_defaults(&d);
    o->level_scale = d.level_scale;
    o->level_strata = d.level_strata;
    o->level_min_radius = d.level_min_radius;
    o->level_check_visibility = d.level_check_visibility;
}

static render_opts cache_opts(const ctx *c, int gather, double a)
{
    render_opts o = base_opts(c);
    o.mode = MODE_CACHE;
    o.features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
    o.accuracy = (float)a;
    o.strata_m = 16;
    o.strata_n = 64;
    o.gather = gather;
    level_defaults(&o);
    return o;
}

/* One deeper-level setting changed from the defaults, at a = 0.2. */
typedef struct variant {
    const char *name;
    float scale, min_radius;
    int strata, check;
} variant;

int bounce_sweep(ctx *c, const bscene *b, FILE *csv)
{
    static const int brute[] = {16, 64, 256, 1024};
    static const double as_def[] = {0.4, 0.2, 0.1};
    double as_set[8];
    const int n_set = bench_a_list(as_set, 8), na = n_set ? n_set : 3;
    const double *as = n_set ? as_set : as_def;
    static const variant vs[] = {
        {"levels-scale2", 2.0f, -1.0f, 0, -1}, {"levels-scale4", 4.0f, -1.0f, 0, -1},
        {"levels-strata1", 0.0f, -1.0f, 1, -1}, {"levels-minr0.125", 0.0f, 0.125f, 0, -1},
        {"levels-minr0.9", 0.0f, 0.9f, 0, -1}, {"levels-sight", 0.0f, -1.0f, 0, 1}};
    const int nb = c->quick ? 3 : 4, real = b->stride > 0;
    int i, m;
    for (i = 0; i < nb && wanted_method("brute"); i++) {
        render_opts o = base_opts(c);
        o.mode = MODE_REFERENCE;
        o.ref_rays = brute[i];
        o.stride = real ? c->stride : 0;
        o.stride_offset = lattice_offset(c);
        if (add_run(c, "brute", o.ref_rays, &o, b, csv) < 0)
            return -1;
    }
    /* The first level's error has a floor of record noise (a path per
     * gather ray): 32x128 records too, but on the real scenes, where the
     * error is not record noise (Sponza atrium, 2 bounces, a = 0.4:
     * 0.0709 in 436 s at 32x128, 0.0743 in 122 s at 16x64). */
    for (m = 0; m < 3; m++)
        for (i = 0; i < na && wanted_method(m == 2 ? "levels" : "first"); i++) {
            render_opts o = cache_opts(c, m == 2 ? GATHER_CACHE : GATHER_PATH, as[i]);
            if (m == 1 && (c->quick || real))
                break;
            o.strata_m <<= m == 1;
            o.strata_n <<= m == 1;
            if (add_run(c, m == 2 ? "levels" : "first", as[i], &o, b, csv) < 0)
                return -1;
        }
    for (i = 0; i < (int)(sizeof vs / sizeof vs[0]) && !c->quick && wanted_method("rule"); i++) {
        render_opts o = cache_opts(c, GATHER_CACHE, 0.2);
        if (vs[i].scale > 0.0f)
            o.level_scale = vs[i].scale;
        if (vs[i].min_radius >= 0.0f)
            o.level_min_radius = vs[i].min_radius;
        if (vs[i].strata > 0)
            o.level_strata = vs[i].strata;
        if (vs[i].check >= 0)
            o.level_check_visibility = vs[i].check;
        if (add_run(c, vs[i].name, 0.2, &o, b, csv) < 0)
            return -1;
    }
    return 0;
}
