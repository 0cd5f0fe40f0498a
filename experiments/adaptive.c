/*
 * adaptive.c -- the first-order paper's adaptive image sampling (Sec. 5)
 * on a scene, against the full render: three importance metrics on the
 * same sample budgets, each sample at a pixel centre shaded by the demo's
 * integrator (cache for E, the full render's light samples there), the
 * image rebuilt by Delaunay interpolation (experiments/sampling.c).
 *   gradient:  |grad I| at the sample, the image gradient of experiments/imgrad.c
 *              (Eq. 25-27: spatial, curvature-directional, view and
 *              indirect terms; IMG_GRADIENT_FAST), and its visibility
 *              term: where the lit side of a shadow edge meets the other,
 *              the luminance jump (Eq. 34's delta; adaptive.h, region);
 *   frequency: Durand et al.'s heuristic as the first-order paper quotes
 *              it, (1/gamma) 2 k z / (n0.v) Omega_rho, Omega_rho =
 *              sqrt(6 s) for a Phong exponent s (s = 1 for a diffuse
 *              surface), k the curvature without bumps;
 *   uniform:   the same importance everywhere.
 * Every metric splits object boundaries first.  Prints, per metric and
 * budget, the relative RMSE against the full render (sqrt(sum (a-b)^2 /
 * sum b^2)), its largest error on the bumpy sphere's pixels (material
 * "bumpy", if the scene has one), the time and the share spent on
 * gradients, twice: cold (the cache starts empty, as the full render's
 * did) and warm (the cache starts with the full render's records; the
 * full render is redone the same way), every time the least of three
 * runs.  Writes the reconstructions and the sample positions as PNGs to
 * build/adaptive-out/.  With --check it first compares the image gradient
 * (central, then the sampler's) with central differences of an image
 * rendered with one set of light samples for every pixel, direct and
 * indirect parts apart (--check-only: only that).  --light-samples sets
 * the pixel's light samples (16 by default; at most 256).  Everything
 * runs on one thread.
 *   adaptive SCENE [W H] [--check | --check-only] [--light-samples N]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "sampling.h"
#include "image.h"
#include "imgrad.h"

enum { M_GRADIENT, M_FREQUENCY, M_UNIFORM, M_COUNT };
static const char *const metric_name[M_COUNT] = {"gradient", "frequency", "uniform"};

typedef struct ctx {
    renderer *r;
    cam_frame cf;
    int metric;
    float gamma;       /* focal length, pixels */
    double grad_s, shade_s; /* in gradients; in image_point, gradients included */
    int error;
} ctx;

static int eval(void *vc, ad_sample *s)
{
    ctx *c = (ctx *)vc;
    img_point ip;
    const double t0 = render_clock();
    int k, st = image_point(c->r, &c->cf, s->x, s->y,
                                c->metric == M_GRADIENT ? IMG_GRADIENT_FAST : IMG_NO_GRADIENT, 0, &ip);
    c->shade_s += render_clock() - t0;
    if (st < 0)
        return c->error = st;
    for (k = 0; k < 3; k++)
        s->rgb[k] = ip.rgb[k];
    s->object = ip.object;
    c->grad_s += ip.grad_s;
    if (c->metric == M_GRADIENT) {
        /* Its visibility term: shadow edges' jumps (adaptive.h, region). */
        s->region = ip.lit;
        const float gx = lum3(ip.grad[0]), gy = lum3(ip.grad[1]);
        s->importance = sqrtf(gx * gx + gy * gy);
    } else if (c->metric == M_FREQUENCY) {
        const float omega = sqrtf(6.0f * (ip.exponent > 0.0f ? ip.exponent : 1.0f));
        s->importance = ip.object < 0 || ip.cos_view <= 0.0f
                            ? 0.0f
                            : 2.0f * ip.curvature * ip.depth / ip.cos_view * omega / c->gamma;
    } else {
        s->importance = 1.0f;
    }
    return 0;
}

static int light_samples; /* --light-samples: 0 keeps the renderer's */

/* Every time printed is the least of this many runs of the same work (the
 * machines are shared; the work and its results do not change). */
#define REPEAT 3

static int new_renderer(renderer *r, const scene *s)
{
    render_opts o;
    char err[256];
    render_opts_defaults(&o);
    if (light_samples > 0)
        o.light_samples = light_samples;
    if (renderer_init(r, s, &o, err, sizeof err) < 0) {
        fprintf(stderr, "adaptive: %s\n", err);
        return -1;
    }
    return 0;
}

/* Relative RMSE of a against b, and the largest |a - b| (luminance) over
 * the pixels of mask (all when NULL) over b's largest luminance. */
static double rel_rmse(const float *a, const float *b, int n, const unsigned char *mask,
                       double *worst)
{
    double num = 0.0, den = 0.0, top = 0.0, big = 0.0;
    int i;
    for (i = 0; i < 3 * n; i++) {
        num += ((double)a[i] - b[i]) * ((double)a[i] - b[i]);
        den += (double)b[i] * b[i];
    }
    for (i = 0; i < n; i++) {
        const double d = fabs((double)lum3(a + 3 * i) - lum3(b + 3 * i));
        if (lum3(b + 3 * i) > top)
            top = lum3(b + 3 * i);
        if ((!mask || mask[i]) && d > big)
            big = d;
    }
    *worst = top > 0.0 ? big / top : 0.0;
    return den > 0.0 ? sqrt(num / den) : 0.0;
}

/* The pixels whose centre sees material `name`. */
static unsigned char *material_mask(renderer *r, const cam_frame *cf, const char *name, int w,
                                    int h, int *count)
{
    unsigned char *m = calloc((size_t)w * (size_t)h, 1);
    int x, y;
    *count = 0;
    if (!m)
        return NULL;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            float d[3];
            bvh_hit bh;
            camera_ray(cf, &r->s->cam, x, y, d);
            if (bvh_intersect(&r->b, cf->eye, d, 0.0f, 1e30f, &bh)) {
                const int mat = bh.prim >= 0 ? r->s->tris[bh.prim].mat
                                             : r->s->spheres[-bh.prim - 1].mat;
                if (strcmp(r->s->mats[mat].name, name) == 0) {
                    m[y * w + x] = 1;
                    ++*count;
                }
            }
        }
    return m;
}

/* The samples as dots over a dimmed reconstruction. */
static void positions(const ad_sample *s, int n, const float *img, int w, int h, float *out)
{
    int i;
    for (i = 0; i < 3 * w * h; i++)
        out[i] = 0.25f * img[i];
    for (i = 0; i < n; i++) {
        int x = (int)s[i].x, y = (int)s[i].y;
        if (x >= w) x = w - 1;
        if (y >= h) y = h - 1;
        out[3 * (y * w + x)] = 4.0f;
        out[3 * (y * w + x) + 1] = 0.3f;
        out[3 * (y * w + x) + 2] = 0.1f;
    }
}

/* The full render's records (warm runs start from them). */
typedef struct snap {
    void *bytes;
    size_t size;
} snap;

/* A renderer whose cache starts empty, or (sn not NULL) holds sn's
 * records. */
static int fresh_renderer(renderer *r, const scene *s, const snap *sn)
{
    int st;
    if (new_renderer(r, s) < 0)
        return -1;
    if (sn && (st = irc_snapshot_read(r->cache, 0, sn->bytes, sn->size)) < 0) {
        fprintf(stderr, "adaptive: snapshot: %s\n", irc_strerror(st));
        renderer_free(r);
        return -1;
    }
    return 0;
}

/* The full render, its cache starting empty or holding sn's records:
 * the least time of REPEAT; keep (optional) gets the last renderer. */
static int full_render(const scene *s, const snap *sn, float *out, double *secs,
                       render_stats *st, renderer *keep)
{
    renderer own;
    int rep;
    *secs = HUGE_VAL;
    for (rep = 0; rep < REPEAT; rep++) {
        /* The last run renders in keep itself: a renderer may not be
         * copied (its levels' callback contexts, which the caches hold,
         * point into it). */
        renderer *r = keep && rep + 1 == REPEAT ? keep : &own;
        double t0, t;
        if (fresh_renderer(r, s, sn) < 0)
            return -1;
        t0 = render_clock();
        if (render_image(r, out, st) < 0) {
            renderer_free(r);
            return -1;
        }
        t = render_clock() - t0;
        if (t < *secs)
            *secs = t;
        if (r == &own)
            renderer_free(r);
    }
    return 0;
}

/* One metric at one budget, its cache starting empty (cold, as the full
 * render did) or, with warm, holding the full render's records (what a
 * frame costs once records exist: a previous frame's, a farm's), compared
 * with the full render redone from them. */
static int run(const scene *s, const char *tag, const float *full, double full_s,
               const snap *warm, const unsigned char *bumpy, int metric, double budget,
               float *img, float *dots)
{
    const int w = s->cam.width, h = s->cam.height;
    renderer own, *rr = &own;
    ctx c;
    irc_stats cs;
    ad_opts o = {0, 0, 8, 0.0, 1.0f, 1};
    ad_sample *smp = NULL;
    char path[512], err[256];
    double t0, t1, t2, rmse, worst, worst_b = 0.0, best = HUGE_VAL, grad_s = 0.0, shade_s = 0.0,
           sampler_s = 0.0, rebuild_s = 0.0;
    int n = 0, st, rep;
    o.width = w;
    o.height = h;
    o.budget = budget;
    for (rep = 0; rep < REPEAT; rep++) { /* the same work each time; the fastest kept */
        if (fresh_renderer(&own, s, warm) < 0)
            return -1;
        memset(&c, 0, sizeof c);
        c.r = rr;
        camera_frame(&s->cam, &c.cf);
        c.metric = metric;
        c.gamma = 0.5f * (float)h / c.cf.ty;
        free(smp);
        smp = NULL;
        t0 = render_clock();
        st = adaptive_sample(&o, eval, &c, &smp, &n);
        t2 = render_clock();
        if (st == 0)
            st = adaptive_reconstruct(smp, n, w, h, 0.5f, img);
        t1 = render_clock();
        if (st < 0) {
            fprintf(stderr, "adaptive: %s %s failed (%d)\n", tag, metric_name[metric], c.error);
            renderer_free(&own);
            free(smp);
            return -1;
        }
        if (t1 - t0 < best) {
            best = t1 - t0;
            grad_s = c.grad_s;
            shade_s = c.shade_s;
            sampler_s = t2 - t0 - c.shade_s;
            rebuild_s = t1 - t2;
        }
        if (rep + 1 < REPEAT)
            renderer_free(&own);
    }
    rmse = rel_rmse(img, full, w * h, NULL, &worst);
    if (bumpy)
        (void)rel_rmse(img, full, w * h, bumpy, &worst_b);
    irc_cache_stats(rr->cache, &cs);
    printf("%-10s %4.0f%% %s %6d samples  rel. RMSE %.4f  worst %.3f  bumpy worst %.3f  "
           "%6.2f s (full %.2f s: %.2fx), gradients %.3f s (%.1f%% of it, %.1f%% of full), "
           "%llu records; shading %.2f s, sampler %.2f s, reconstruction %.2f s\n",
           metric_name[metric], 100.0 * budget, warm ? "warm" : "cold", n, rmse, worst, worst_b,
           best, full_s, full_s / best, grad_s, 100.0 * grad_s / best, 100.0 * grad_s / full_s,
           (unsigned long long)cs.computes, shade_s, sampler_s, rebuild_s);
    if (warm) {
        free(smp);
        renderer_free(&own);
        return 0;
    }
    positions(smp, n, img, w, h, dots);
    snprintf(path, sizeof path, "build/adaptive-out/%s-%s-%02.0f.png", tag, metric_name[metric],
             100.0 * budget);
    png_write(path, w, h, img, 1.0f, err, sizeof err);
    snprintf(path, sizeof path, "build/adaptive-out/%s-%s-%02.0f-samples.png", tag,
             metric_name[metric], 100.0 * budget);
    png_write(path, w, h, dots, 1.0f, err, sizeof err);
    free(smp);
    renderer_free(&own);
    return 0;
}

/* Every metric at both budgets against the full render ref. */
static int all_runs(const scene *s, const char *tag, const float *ref, double ref_s,
                    const snap *warm, const unsigned char *bumpy, float *img, float *dots)
{
    static const double budgets[2] = {0.10, 0.17};
    int b, m;
    for (b = 0; b < 2; b++)
        for (m = 0; m < M_COUNT; m++)
            if (run(s, tag, ref, ref_s, warm, bumpy, m, budgets[b], img, dots) < 0)
                return -1;
    return 0;
}

/* Warm: the full render again, its cache holding r's records (the first
 * full render's), then every run the same way (records cost little in
 * either; pixels and gradients do). */
static int warm_runs(const scene *s, const char *tag, renderer *r, uint64_t first,
                     const unsigned char *bumpy, float *again, float *img, float *dots)
{
    snap sn = {NULL, 0};
    render_stats st;
    double again_s;
    int rc = -1;
    if (irc_snapshot_size(r->cache, &sn.size) == IRC_OK && (sn.bytes = malloc(sn.size)) &&
        irc_snapshot_write(r->cache, 0, sn.bytes, sn.size, NULL, NULL, NULL) == IRC_OK &&
        full_render(s, &sn, again, &again_s, &st, NULL) == 0) {
        printf("%s: full render from the first one's records %.2f s (%llu records added)\n",
               tag, again_s, (unsigned long long)(st.records - first));
        rc = all_runs(s, tag, again, again_s, &sn, bumpy, img, dots);
    }
    free(sn.bytes);
    return rc;
}

/* The image gradient against the image's differences: the full one, then
 * the sampler's; each part apart. */
static int checks(renderer *r, const cam_frame *cf, int w, int h)
{
    int i, k;
    for (i = 0; i < 2; i++) {
        grad_check g;
        if (image_gradient_check(r, cf, w, h, i ? IMG_GRADIENT_FAST : IMG_GRADIENT_PARTS, &g) <
            0)
            return -1;
        for (k = 0; k < 2; k++) {
            const grad_part *p = k ? &g.indirect : &g.direct;
            printf("gradient check, %s, %s part (%dx%d, %d pixels inside objects): relative "
                   "L2 error %.4f; per pixel (|grad| > 0.1 mean, %d pixels): median %.4f, "
                   "90th percentile %.4f\n", i ? "sampler's (fast)" : "central",
                   k ? "indirect" : "direct", w, h, p->pixels, p->l2, p->strong, p->median,
                   p->p90);
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    scene s;
    renderer r;
    render_stats st;
    cam_frame cf;
    char err[1024], tag[128], path[512];
    const char *base;
    float *full, *img, *dots, *again;
    unsigned char *bumpy;
    double full_s;
    uint64_t first;
    int w, h, nb = 0, do_check = 0, i, rc = 0;
    if (argc < 2) {
        fprintf(stderr, "usage: adaptive SCENE [W H] [--check | --check-only] "
                        "[--light-samples N]\n");
        return 2;
    }
    if (scene_load(argv[1], &s, err, sizeof err) < 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    for (i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--check") == 0)
            do_check = 1;
        if (strcmp(argv[i], "--check-only") == 0)
            do_check = 2;
        if (strcmp(argv[i], "--light-samples") == 0 && i + 1 < argc)
            light_samples = atoi(argv[++i]);
    }
    if (light_samples > 256) {
        fprintf(stderr, "adaptive: at most 256 light samples (imgrad.c)\n");
        return 2;
    }
    if (argc >= 4 && argv[2][0] != '-') {
        s.cam.width = atoi(argv[2]);
        s.cam.height = atoi(argv[3]);
    }
    w = s.cam.width;
    h = s.cam.height;
    base = strrchr(argv[1], '/') ? strrchr(argv[1], '/') + 1 : argv[1];
    snprintf(tag, sizeof tag, "%.*s", (int)(strcspn(base, ".")), base);
    if (light_samples > 0) /* its own PNGs */
        snprintf(tag + strlen(tag), sizeof tag - strlen(tag), "-ls%d", light_samples);
    mkdir("build", 0777);
    mkdir("build/adaptive-out", 0777);
    full = malloc(sizeof *full * 3 * (size_t)w * (size_t)h);
    img = malloc(sizeof *img * 3 * (size_t)w * (size_t)h);
    dots = malloc(sizeof *dots * 3 * (size_t)w * (size_t)h);
    again = malloc(sizeof *again * 3 * (size_t)w * (size_t)h);
    if (!full || !img || !dots || !again || full_render(&s, NULL, full, &full_s, &st, &r) < 0)
        return 1;
    first = st.records;
    printf("%s %dx%d, %d light samples: full render %.2f s (one thread, %llu records)\n", tag,
           w, h, r.o.light_samples, full_s, (unsigned long long)st.records);
    snprintf(path, sizeof path, "build/adaptive-out/%s-full.png", tag);
    png_write(path, w, h, full, 1.0f, err, sizeof err);
    camera_frame(&s.cam, &cf);
    bumpy = material_mask(&r, &cf, "bumpy", w, h, &nb);
    if (nb == 0) {
        free(bumpy);
        bumpy = NULL;
    }
    if (do_check && checks(&r, &cf, w, h) < 0)
        rc = 1;
    if (rc == 0 && do_check < 2 &&
        (all_runs(&s, tag, full, full_s, NULL, bumpy, img, dots) < 0 ||
         warm_runs(&s, tag, &r, first, bumpy, again, img, dots) < 0))
        rc = 1;
    renderer_free(&r);
    free(again);
    free(bumpy);
    free(full);
    free(img);
    free(dots);
    scene_free(&s);
    return rc;
}
