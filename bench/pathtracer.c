/*
 * pathtracer.c -- the cache in a progressive path tracer on real geometry:
 * the demo's scenes (Sponza views) traced by the bench's fast backend
 * (Embree when installed, else the demo's BVH), one sample a pixel at a
 * time over the frame, measured at 4, 16, 64, 256 and 1,024 samples a
 * pixel against the same tracer's own light-sampled path tracing at equal
 * relative RMSE.
 *
 * The light transport, the same in every mode: a path of three vertices
 * x1 (the camera's hit), x2, x3, each with next-event estimation D(x) (the
 * demo's direct_light: the sun's shadow ray and the area lights, one
 * sample, Lambert + Phong), emission at x1, cosine-sampled Lambert
 * bounces (weight kd) between them, the environment where a bounce
 * escapes.  So a pixel is Le(x1) + D(x1) + kd1 [env | D(x2) + kd2 [env |
 * D(x3)]]; the modes differ in who estimates what:
 *   path    all of it by one path a sample;
 *   second  the first bounce traced a sample, the rest at x2 read from a
 *           cache: kd2 / pi E(x2), E gathered from D at the hits and the
 *           environment (the _px call with the bounce's footprint,
 *           PT_SPREAD (0.1) x its length, records at least that wide,
 *           no detail estimates: the first bounce blurs them), with
 *           irc_progress after every iteration;
 *   first   the cache at x1 (irc_cache_lookup_pixel, an irc_pixel a pixel,
 *           the pinhole's footprint, irc_progress): its records' rays
 *           return D(x2) + kd2 [env | D(x3)], one path each.
 * Errors are against path tracing at ref samples (its own random numbers),
 * with the reference's own noise taken out as in bench/progressive.c;
 * speed-up at equal error likewise (one thread's CPU time; the table and
 * CSV are bench/progress_report.h's).  traced: every
 * ray the tracer cast (the callback's included); cache_rays: the rays the
 * library asked for (irc_stats), each of which costs the first hit's
 * callback about four.
 *
 * PT_DEPTH=k makes paths of k vertices (the caches' rays then return
 * paths of k - 2 or k - 3 more vertices).
 *
 * Usage: bench_pathtracer SCENE [width height samples ref_samples]
 * (default 160 120 1024 4096).  PT_MODES=second,first chooses the cache
 * modes; PT_A=a the knob; PT_SPREAD the second vertex's footprint over
 * the bounce's length; PT_MIN_PIXELS the first hit's cfg.irr.min_pixels.
 * Prints the backend.
 */
#define _POSIX_C_SOURCE 200809L
#define IRC_EXPERIMENTAL /* irc_progress, irc_cache_lookup_pixel */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "progress_report.h"
#include "bvh.h"
#include "camera.h"
#include "irrcache.h"
#include "scene.h"
#include "shade.h"

#define PT_PI 3.14159265358979f
enum { PATH, SECOND, FIRST, MODES };
static const char *const mode_name[MODES] = {"path", "second", "first"};

typedef struct pt {
    scene s;
    bvh b;
    lights l;
    cam_frame cf;
    int w, h, pixel;
    unsigned long long rng;
    uint64_t key, rays;
    double t_trace; /* monotonic seconds inside the caches' callbacks */
} pt;

static float urand(pt *p) { return (float)bench_xorshift(&p->rng); }

/* A 64-bit mix (splitmix64's finalizer): direct_light's keys. */
static uint64_t mix64(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* The nearest surface along (o, d): 1 and *sf, or 0. */
static int hit_at(pt *p, const float o[3], const float d[3], surface *sf)
{
    bvh_hit bh;
    p->rays++;
    if (!bvh_intersect(&p->b, o, d, ray_offset(o), FLT_MAX, &bh))
        return 0;
    surface_at(&p->s, o, d, &bh, sf);
    return 1;
}

/* D(sf) toward -d: next-event estimation, one light sample and the sun. */
static void next_event(pt *p, const surface *sf, const float d[3], float out[3])
{
    direct_light(&p->b, &p->l, sf, d, 1, mix64(p->key++), out, &p->rays);
}

/* A cosine-distributed direction about sf's gather normal; 0 when it
 * leaves below the geometric surface (the path ends there). */
static int bounce(pt *p, const surface *sf, float d[3])
{
    const float u = urand(p), v = urand(p);
    bench_cosine_dir(gather_normal(sf), u, v, d);
    return dot3(d, sf->ng) > 0.0f;
}

/* Radiance arriving back along a bounce from sf: env on escape, else D at
 * the hit plus, with more > 0, kd x one more bounce's. */
static void beyond(pt *p, const surface *sf, int more, float out[3])
{
    float d[3], o[3], l[3];
    surface nx;
    int k;
    out[0] = out[1] = out[2] = 0.0f;
    if (!bounce(p, sf, d))
        return;
    for (k = 0; k < 3; k++)
        o[k] = sf->p[k];
    if (!hit_at(p, o, d, &nx)) {
        env_radiance(&p->s.env, d, out);
        return;
    }
    next_event(p, &nx, d, out);
    if (more <= 0)
        return;
    beyond(p, &nx, more - 1, l);
    for (k = 0; k < 3; k++)
        out[k] += nx.m->kd[k] * l[k];
}

/* The caches' callback: the first-hit cache's rays return D + kd x one
 * more bounce (context: the level, 1 or 2); the second vertex's D. */
typedef struct level {
    pt *p;
    int more;
} level;

static int trace_cb(const irc_trace_args *a)
{
    const level *lv = (const level *)a->context;
    pt *p = lv->p;
    double t0 = bench_now();
    uint32_t i;
    for (i = 0; i < a->count; i++) {
        irc_hit *h = &a->hits[i];
        bvh_hit bh;
        p->rays++;
        if (!bvh_intersect(&p->b, a->rays[i].org, a->rays[i].dir, ray_offset(a->rays[i].org),
                           FLT_MAX, &bh)) {
            h->status = IRC_RAY_ESCAPED;
            env_radiance(&p->s.env, a->rays[i].dir, h->radiance);
            continue;
        }
        h->status = IRC_RAY_HIT;
        h->dist = bh.t;
        if (!a->visibility_only) {
            surface sf;
            float l[3];
            int k;
            surface_at(&p->s, a->rays[i].org, a->rays[i].dir, &bh, &sf);
            memcpy(h->normal, sf.ng, sizeof h->normal);
            next_event(p, &sf, a->rays[i].dir, h->radiance);
            if (lv->more > 0) {
                beyond(p, &sf, lv->more - 1, l);
                for (k = 0; k < 3; k++)
                    h->radiance[k] += sf.m->kd[k] * l[k];
            }
        }
    }
    p->t_trace += bench_now() - t0;
    return 0;
}

/* Path vertices (PT_DEPTH, default 3): x1 .. x_depth, each with NEE. */
static int depth(void)
{
    static int d = 0;
    if (!d) {
        d = getenv("PT_DEPTH") ? atoi(getenv("PT_DEPTH")) : 3;
        d = d < 3 ? 3 : d > 16 ? 16 : d;
    }
    return d;
}

static float second_spread(void)
{
    static float s = -1.0f;
    if (s < 0.0f)
        s = getenv("PT_SPREAD") ? (float)atof(getenv("PT_SPREAD")) : 0.1f;
    return s;
}

/* One sample through image point (x, y), added to acc. */
static int sample(pt *p, irc_cache *c, irc_pixel *pix, int mode, float x, float y, double *acc,
                  double *lib)
{
    float d[3], l[3], e[3], q[3], fp;
    surface x1;
    int k, st = 0;
    double t0, tr;
    camera_ray_at(&p->cf, &p->s.cam, x, y, d);
    if (!hit_at(p, p->cf.eye, d, &x1)) {
        env_radiance(&p->s.env, d, l);
        for (k = 0; k < 3; k++)
            acc[k] += l[k];
        return 0;
    }
    emitted(&x1, l);
    for (k = 0; k < 3; k++)
        acc[k] += l[k];
    next_event(p, &x1, d, l);
    for (k = 0; k < 3; k++)
        acc[k] += l[k];
    if (mode == PATH) {
        beyond(p, &x1, depth() - 2, l);
        for (k = 0; k < 3; k++)
            acc[k] += x1.m->kd[k] * l[k];
        return 0;
    }
    t0 = bench_now();
    tr = p->t_trace;
    if (mode == FIRST) {
        float t = 0.0f;
        for (k = 0; k < 3; k++)
            t += (x1.p[k] - p->cf.eye[k]) * d[k];
        fp = camera_footprint(&p->cf, &p->s.cam, d, t, x1.ng);
        cache_point(&x1, q);
        st = irc_cache_lookup_pixel(c, &pix[p->pixel], q, gather_normal(&x1), NULL, fp, e, NULL, p);
        if (st >= 0)
            for (k = 0; k < 3; k++)
                acc[k] += x1.m->kd[k] / PT_PI * e[k];
    } else {
        float d2[3], o[3];
        surface x2;
        if (!bounce(p, &x1, d2))
            return 0;
        for (k = 0; k < 3; k++)
            o[k] = x1.p[k];
        if (!hit_at(p, o, d2, &x2)) {
            env_radiance(&p->s.env, d2, l);
            for (k = 0; k < 3; k++)
                acc[k] += x1.m->kd[k] * l[k];
            return 0;
        }
        next_event(p, &x2, d2, l);
        t0 = bench_now();
        tr = p->t_trace;
        cache_point(&x2, q);
        /* the footprint after a diffuse bounce: the lobe a sample stands
         * for, about SECOND_SPREAD radians wide at the bounce's length */
        for (fp = 0.0f, k = 0; k < 3; k++)
            fp += (x2.p[k] - x1.p[k]) * (x2.p[k] - x1.p[k]);
        fp = second_spread() * sqrtf(fp);
        st = irc_cache_lookup_or_compute_px(c, q, gather_normal(&x2), NULL, fp, e, NULL, p);
        if (st >= 0)
            for (k = 0; k < 3; k++)
                acc[k] += x1.m->kd[k] * (l[k] + x2.m->kd[k] / PT_PI * e[k]);
    }
    *lib += bench_now() - t0 - (p->t_trace - tr);
    return st < 0 ? st : 0;
}

static int render(pt *p, irc_cache *c, int mode, int spp, const float *ref, point *pts)
{
    const int n = p->w * p->h;
    double *acc = calloc((size_t)n * 3, sizeof(double)), lib = 0.0, spent = 0.0, t0;
    irc_pixel *pix = calloc((size_t)n, sizeof(irc_pixel));
    int s, i, q = 0, failed = 0;
    if (!acc || !pix)
        return -1;
    t0 = cpu_now();
    for (s = 0; s < spp && !failed; s++) {
        for (i = 0; i < n && !failed; i++) {
            p->pixel = i;
            failed = sample(p, c, pix, mode, (float)(i % p->w) + urand(p),
                            (float)(i / p->w) + urand(p), &acc[3 * i], &lib) < 0;
        }
        if (c) {
            double u = bench_now(), tr = p->t_trace;
            failed |= irc_progress(c, (uint32_t)s + 1u, p) < 0;
            lib += bench_now() - u - (p->t_trace - tr);
        }
        while (q < CHECKS && check_spp[q] == s + 1) {
            double u = cpu_now();
            checkpoint(&pts[q], u - t0 - spent, lib, n, acc, s + 1, ref, c);
            pts[q].traced = p->rays;
            spent += cpu_now() - u;
            q++;
        }
    }
    free(acc);
    free(pix);
    return failed ? -1 : 0;
}

static void reference(pt *p, int ref_spp, float *ref)
{
    int i, s, k;
    double lib = 0.0;
    for (i = 0; i < p->w * p->h; i++) {
        double acc[3] = {0, 0, 0};
        for (s = 0; s < ref_spp; s++)
            (void)sample(p, NULL, NULL, PATH, (float)(i % p->w) + urand(p),
                         (float)(i / p->w) + urand(p), acc, &lib);
        for (k = 0; k < 3; k++)
            ref[3 * i + k] = (float)(acc[k] / ref_spp);
    }
}

static int wanted(int mode)
{
    const char *m = getenv("PT_MODES");
    return !m || strstr(m, mode_name[mode]) != NULL;
}

/* One cache run (mode SECOND or FIRST) with the library's defaults but
 * the knob; 0 or -1. */
static int cache_run(pt *p, int mode, int spp, const float *ref, point *pts)
{
    irc_config cfg = IRC_CONFIG_INIT;
    level lv;
    irc_cache *c = NULL;
    size_t bytes;
    /* room for the records of the whole scene (the second vertex's) or of
     * the frame's small details: a full pool computes without storing */
    const uint32_t max = (uint32_t)(p->w * p->h) * 4u + 200000u;
    int rc;
    lv.p = p;
    lv.more = depth() - (mode == FIRST ? 2 : 3);
    cfg.trace = trace_cb;
    cfg.context = &lv;
    cfg.accuracy = getenv("PT_A") ? (float)atof(getenv("PT_A")) : 0.0f;
    if (mode == FIRST && getenv("PT_MIN_PIXELS"))
        cfg.irr.min_pixels = (float)atof(getenv("PT_MIN_PIXELS"));
    if (mode == SECOND) {
        /* After a diffuse bounce a record need be no finer than the
         * bounce's footprint (the _px call's bound a R >= min_pixels x
         * footprint), and no point needs its own estimate. */
        cfg.irr.min_pixels = 1.0f;
        cfg.irr.detail_pixels = -1.0f;
    }
    if (irc_footprint(&cfg, max, &bytes) < 0 || !(cfg.buffer = malloc(bytes)))
        return -1;
    cfg.buffer_size = bytes;
    if (irc_init(&cfg, max, &c) < 0 || irc_progress(c, 0, p) < 0) {
        free(cfg.buffer);
        return -1;
    }
    rc = render(p, c, mode, spp, ref, pts);
    {
        irc_stats st;
        if (irc_cache_stats(c, &st) == IRC_OK)
            printf("%s: block %.1f MB for %u records (%llu used, %zu bytes each)%s\n",
                   mode_name[mode], (double)bytes / 1048576.0, max,
                   (unsigned long long)st.records, st.record_bytes,
                   mode == FIRST ? "; irc_pixel store 120 bytes a pixel" : "");
    }
    irc_fini(c);
    free(cfg.buffer);
    return rc;
}

int main(int argc, char **argv)
{
    static pt p;
    static point pts[MODES][CHECKS];
    int spp = 1024, ref_spp = 4096, mode, failed = 0;
    char err[256];
    float *ref;
    double t0;
    setvbuf(stdout, NULL, _IOLBF, 0); /* lines as they come: runs are long */
    if (argc != 2 && argc != 6)
        return fprintf(stderr, "usage: bench_pathtracer SCENE [width height samples ref]\n"), 2;
    if (scene_load(argv[1], &p.s, err, sizeof err) < 0)
        return fprintf(stderr, "%s\n", err), 1;
    p.w = argc == 6 ? atoi(argv[2]) : 160;
    p.h = argc == 6 ? atoi(argv[3]) : 120;
    if (argc == 6) {
        spp = atoi(argv[4]);
        ref_spp = atoi(argv[5]);
    }
    if (p.w <= 0 || p.h <= 0 || spp <= 0 || ref_spp <= 0)
        return fprintf(stderr, "bad size or samples\n"), 2;
    p.s.cam.width = p.w;
    p.s.cam.height = p.h;
    camera_frame(&p.s.cam, &p.cf);
    if (bvh_build(&p.b, &p.s) < 0 || lights_build(&p.l, &p.s) < 0)
        return fprintf(stderr, "out of memory\n"), 1;
#ifdef BENCH_EMBREE
    if (bvh_embree(&p.b, err, sizeof err) < 0)
        return fprintf(stderr, "%s\n", err), 1;
#endif
    if (!(ref = malloc(sizeof(float) * 3 * (size_t)p.w * (size_t)p.h)))
        return 1;
    p.rng = 0x2545f4914f6cdd1dull;
    p.key = 1ull << 62;
    t0 = cpu_now();
    reference(&p, ref_spp, ref);
    printf("%s %s %dx%d (%s), progressive to %d samples a pixel; reference: path tracing "
           "at %d (%.1f s)\n",
           irc_version_string(), argv[1], p.w, p.h,
#ifdef BENCH_EMBREE
           "Embree",
#else
           "the demo's BVH",
#endif
           spp, ref_spp, cpu_now() - t0);
    for (mode = PATH; mode < MODES; mode++) {
        if (mode != PATH && !wanted(mode))
            continue;
        p.rng = 0x9e3779b97f4a7c15ull + (unsigned long long)mode;
        p.key = (uint64_t)mode << 56;
        p.rays = 0;
        p.t_trace = 0.0;
        if ((mode == PATH ? render(&p, NULL, PATH, spp, ref, pts[PATH])
                          : cache_run(&p, mode, spp, ref, pts[mode])) < 0) {
            printf("%s failed\n", mode_name[mode]);
            failed = 1;
        }
    }
    denoise(pts, MODES, ref_spp);
    report(mode_name, pts, MODES, getenv("PT_CSV"));
    free(ref);
    lights_free(&p.l);
    bvh_free(&p.b);
    scene_free(&p.s);
    return failed;
}
