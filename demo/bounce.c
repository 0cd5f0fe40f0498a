/*
 * bounce.c -- what a ray cast for the cache (or for the reference) brings
 * back, bounce by bounce (bounce.h).  Radiance leaving a hit of bounce k
 * toward the ray's origin is
 *     emission (spheres only) + direct light + kd / pi * E_{k+1}
 * with E_{k+1} the hit's irradiance from bounces k+1 .. N: from the cache
 * of level k+1 (GATHER_CACHE, Radiance's -ab N), or from one
 * cosine-distributed ray whose hit is shaded the same way, E ~ pi L
 * (GATHER_PATH: a path with next-event estimation at every vertex, fixed
 * length, no Russian roulette; pbrt-v2's irradiance cache gathers so).
 * The last bounce has direct light only.  Indirect light at secondary
 * hits is Lambertian (kd): their Phong lobe reflects direct light only.
 * At every bounce E is gathered over the directions above the hit's
 * geometric surface (gather_normal, shade.h; cast, bounce.h).
 */
#include "bounce.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static uint64_t ray_key(const float o[3], const float d[3], uint64_t seed)
{
    uint32_t b[6];
    uint64_t h = hash64(seed ^ 0x5bd1e995u);
    int i;
    memcpy(b, o, 12);
    memcpy(b + 3, d, 12);
    for (i = 0; i < 6; i++)
        h = hash64(h ^ b[i]);
    return h;
}

/* A path's next direction from sf: cosine-distributed around n and
 * above the geometric surface, by rejection (the distribution the cache's
 * E at level + 1 averages over: its rays below fail and are left out). */
static void path_dir(const surface *sf, const float n[3], uint64_t key, float d[3])
{
    uint32_t t;
    for (t = 0; t < 8; t++) {
        cosine_dir(n, rnd(key, 2 * t), rnd(key, 2 * t + 1), d);
        if (dot3(d, sf->ng) > 0.0f)
            return;
    }
    cosine_dir(sf->ng, rnd(key, 2 * t), rnd(key, 2 * t + 1), d);
}

/* E at a hit of bounce `level` from the bounces beyond it, over the
 * directions above its surface, as at the camera's hits (render.c). */
static void beyond(const renderer *r, const surface *sf, int level, uint64_t key, float e[3],
                   tstate *ts)
{
    const float *n = gather_normal(sf), *outer = ts->under[level + 1];
    e[0] = e[1] = e[2] = 0.0f;
    ts->under[level + 1] = sf->ng;
    if (r->o.gather == GATHER_CACHE) {
        int was = clock_enter(ts, CLOCK_CACHE);
        /* The next level's record at the hit: a failure there (its own
         * callback's) leaves this bounce dark rather than aborting. */
        if (irc_cache_lookup_or_compute(r->deeper[level - 1], sf->p, n, e, NULL, ts) < 0)
            e[0] = e[1] = e[2] = 0.0f;
        clock_enter(ts, was);
    } else {
        irc_ray ray;
        irc_hit hit;
        int c;
        memcpy(ray.org, sf->p, sizeof ray.org);
        path_dir(sf, n, key, ray.dir);
        cast(r, &ray, &hit, 1, 1, level + 1, ts);
        for (c = 0; c < 3; c++)
            e[c] = (float)PI * hit.radiance[c];
    }
    ts->under[level + 1] = outer;
}

/* Radiance leaving a hit of bounce `level` toward the ray's origin:
 * direct light (secondary_samples light samples, default one), emission
 * only from spheres (emissive triangles are the sampled lights, whose
 * light the previous vertex counts as direct), and the bounces beyond. */
static void secondary(const renderer *r, const surface *sf, int prim, const float d[3],
                      uint64_t key, int level, float out[3], tstate *ts)
{
    int i;
    direct_light(&r->b, &r->l, sf, d, r->o.secondary_samples > 0 ? r->o.secondary_samples : 1,
                 key, out, &ts->rays);
    if (prim < 0) {
        float e[3];
        emitted(sf, e);
        for (i = 0; i < 3; i++)
            out[i] += e[i];
    }
    if (level < r->o.bounces) {
        float e[3];
        beyond(r, sf, level, hash64(key ^ 0x626f756eull), e, ts);
        for (i = 0; i < 3; i++)
            out[i] += sf->m->kd[i] / (float)PI * e[i];
    }
}

void cast(const renderer *r, const irc_ray *rays, irc_hit *hits, uint32_t count, int shade,
          int level, tstate *ts)
{
    int was = clock_enter(ts, CLOCK_TRACE);
    uint32_t i;
    const float *g = level >= 1 && level <= MAX_BOUNCES ? ts->under[level] : NULL;
    for (i = 0; i < count; i++) {
        const float *o = rays[i].org, *d = rays[i].dir;
        irc_hit *h = &hits[i];
        bvh_hit bh;
        if (g && dot3(d, g) <= 0.0f) {
            h->status = IRC_RAY_FAILED;
            continue;
        }
        ts->rays++;
        if (!bvh_intersect(&r->b, o, d, ray_offset(o), FLT_MAX, &bh)) {
            h->status = IRC_RAY_ESCAPED;
            env_radiance(&r->s->env, d, h->radiance);
        } else if (!shade) {
            h->status = IRC_RAY_HIT;
            h->dist = bh.t;
        } else {
            surface sf;
            surface_at(r->s, o, d, &bh, &sf);
            h->status = IRC_RAY_HIT;
            h->dist = bh.t;
            memcpy(h->normal, sf.ng, sizeof h->normal);
            secondary(r, &sf, bh.prim, d, ray_key(o, d, r->o.seed), level, h->radiance, ts);
        }
    }
    clock_enter(ts, was);
}

int clock_enter(tstate *ts, int region)
{
    double now = render_clock();
    int was = ts->region;
    if (was == CLOCK_TRACE)
        ts->trace_s += now - ts->mark;
    else if (was == CLOCK_CACHE)
        ts->cache_s += now - ts->mark;
    ts->mark = now;
    ts->region = region;
    return was;
}

int host_trace(const irc_trace_args *a)
{
    const level_ctx *l = (const level_ctx *)a->context;
    /* The thread's counters come as the call's host pointer. */
    tstate *ts = (tstate *)a->host;
    const float *g = NULL;
    /* Confirming rays run from the query toward records on its surface,
     * along it: they are not the hemisphere's. */
    if (a->visibility_only == IRC_VISIBILITY_CONFIRM && l->level <= MAX_BOUNCES) {
        g = ts->under[l->level];
        ts->under[l->level] = NULL;
    }
    ts->gathers += !a->visibility_only;
    cast(l->r, a->rays, a->hits, a->count, !a->visibility_only, l->level, ts);
    if (g)
        ts->under[l->level] = g;
    return 0;
}

int levels_init(renderer *r, const irc_config *base, float span, char *err, size_t n)
{
    int k;
    float a;
    uint32_t m, nn;
    const uint32_t div = r->o.level_strata > 0 ? (uint32_t)r->o.level_strata : 1u;
    irc_config first; /* the first level's a and strata as the library chose them */
    if (r->o.gather != GATHER_CACHE)
        return 0;
    if ((k = irc_cache_config(r->cache, &first)) < 0) {
        snprintf(err, n, "level 1 cache: %s", irc_strerror(k));
        return -1;
    }
    a = first.accuracy;
    m = first.strata_theta;
    nn = first.strata_phi;
    for (k = 2; k <= r->o.bounces; k++) {
        irc_config cfg = *base;
        size_t bytes;
        int st;
        a *= r->o.level_scale > 0.0f ? r->o.level_scale : 1.0f;
        r->ctx[k - 1].r = r;
        r->ctx[k - 1].level = k;
        cfg.context = &r->ctx[k - 1];
        cfg.accuracy = a > 4.0f ? 4.0f : a;
        /* deeper levels need E only */
        cfg.features &= ~(uint32_t)(IRC_FEATURE_SH | IRC_FEATURE_SH_GRADIENT);
        cfg.sh.bands = 0;
        /* Radiance's ambient resolution: a deeper level's lookups come
         * from hits anywhere, with no pixel to bound a record's size, so
         * radii are bounded by the scene's (span: 0.1 x the visible
         * diagonal), and damped levels take fewer rays (ambcomp.c scales
         * its divisions by the path's weight). */
        m = m / div >= 2u ? m / div : 2u;
        nn = nn / div >= 4u ? nn / div : 4u;
        cfg.strata_theta = m;
        cfg.strata_phi = nn;
        cfg.check_visibility = r->o.level_check_visibility ? IRC_ON : IRC_OFF;
        if (span > 0.0f) {
            cfg.max_radius = span;
            cfg.min_radius = r->o.level_min_radius > 0.0f ? r->o.level_min_radius * span : 0.0f;
        }
        cfg.buffer = NULL;
        cfg.buffer_size = 0;
        if ((st = irc_footprint(&cfg, r->o.max_records, &bytes)) < 0 ||
            !(r->deeper_block[k - 2] = malloc(bytes))) {
            snprintf(err, n, "level %d cache: %s", k, st < 0 ? irc_strerror(st) : "out of memory");
            return -1;
        }
        cfg.buffer = r->deeper_block[k - 2];
        cfg.buffer_size = bytes;
        if ((st = irc_init(&cfg, r->o.max_records, &r->deeper[k - 2])) < 0) {
            snprintf(err, n, "level %d cache: %s", k, irc_strerror(st));
            return -1;
        }
    }
    return 0;
}

void levels_free(renderer *r)
{
    int k;
    for (k = 0; k < MAX_BOUNCES; k++) {
        if (r->deeper[k])
            irc_fini(r->deeper[k]);
        free(r->deeper_block[k]);
    }
}
