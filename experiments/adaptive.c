/*
 * adaptive.c -- the first-order paper's adaptive image sampling (Sec. 5)
 * on a scene, against the full render: three importance metrics on the
 * same sample budgets, each sample shaded by the demo's integrator (cache
 * for E, the full render's light samples), the image rebuilt by Delaunay
 * interpolation (demo/adaptive.c).
 *   gradient:  |grad I| at the sample, the image gradient of demo/imgrad.c
 *              (Eq. 25-27: spatial, curvature-directional, view and
 *              indirect terms);
 *   frequency: Durand et al.'s heuristic as the first-order paper quotes
 *              it, (1/gamma) 2 k z / (n0.v) Omega_rho, Omega_rho =
 *              sqrt(6 s) for a Phong exponent s (s = 1 for a diffuse
 *              surface), k the curvature without bumps;
 *   uniform:   the same importance everywhere.
 * Every metric splits object boundaries first.  Prints, per metric and
 * budget, the relative RMSE against the full render (sqrt(sum (a-b)^2 /
 * sum b^2)), its largest error on the bumpy sphere's pixels (material
 * "bumpy", if the scene has one), the wall time and the share spent on
 * gradients, and writes the reconstructions and the sample positions as
 * PNGs to build/adaptive-out/.  With --check it first compares the image
 * gradient with central differences of an image rendered with one set of
 * light samples for every pixel (--check-only: only that).  Everything
 * runs on one thread.
 *   adaptive SCENE [W H] [--check | --check-only]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "adaptive.h"
#include "image.h"
#include "imgrad.h"

enum { M_GRADIENT, M_FREQUENCY, M_UNIFORM, M_COUNT };
static const char *const metric_name[M_COUNT] = {"gradient", "frequency", "uniform"};

typedef struct ctx {
    renderer *r;
    cam_frame cf;
    int metric;
    float gamma;       /* focal length, pixels */
    double grad_s;
    int error;
} ctx;

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int eval(void *vc, ad_sample *s)
{
    ctx *c = (ctx *)vc;
    img_point ip;
    int k, st = image_point(c->r, &c->cf, s->x, s->y, c->metric == M_GRADIENT, 0, &ip);
    if (st < 0)
        return c->error = st;
    for (k = 0; k < 3; k++)
        s->rgb[k] = ip.rgb[k];
    s->object = ip.object;
    c->grad_s += ip.grad_s;
    if (c->metric == M_GRADIENT) {
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

static int new_renderer(renderer *r, const scene *s)
{
    render_opts o;
    char err[256];
    render_opts_defaults(&o);
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

static int run(const scene *s, const char *tag, const float *full, double full_s,
               const unsigned char *bumpy, int metric, double budget, float *img, float *dots)
{
    const int w = s->cam.width, h = s->cam.height;
    renderer r;
    ctx c;
    irc_stats cs;
    ad_opts o = {0, 0, 8, 0.0, 1.0f};
    ad_sample *smp = NULL;
    char path[512], err[256];
    double t0, t1, rmse, worst, worst_b = 0.0;
    int n = 0, st;
    if (new_renderer(&r, s) < 0)
        return -1;
    memset(&c, 0, sizeof c);
    c.r = &r;
    camera_frame(&s->cam, &c.cf);
    c.metric = metric;
    c.gamma = 0.5f * (float)h / c.cf.ty;
    o.width = w;
    o.height = h;
    o.budget = budget;
    t0 = seconds();
    st = adaptive_sample(&o, eval, &c, &smp, &n);
    if (st == 0)
        st = adaptive_reconstruct(smp, n, w, h, 0.5f, img);
    t1 = seconds();
    if (st < 0) {
        fprintf(stderr, "adaptive: %s %s failed (%d)\n", tag, metric_name[metric], c.error);
        renderer_free(&r);
        free(smp);
        return -1;
    }
    rmse = rel_rmse(img, full, w * h, NULL, &worst);
    if (bumpy)
        (void)rel_rmse(img, full, w * h, bumpy, &worst_b);
    irc_cache_stats(r.cache, &cs);
    printf("%-10s %4.0f%% %6d samples  rel. RMSE %.4f  worst %.3f  bumpy worst %.3f  "
           "%7.2f s (full %.2f s: %.2fx), gradients %.3f s (%.1f%%), %llu records\n",
           metric_name[metric], 100.0 * budget, n, rmse, worst, worst_b, t1 - t0, full_s,
           full_s / (t1 - t0), c.grad_s, 100.0 * c.grad_s / (t1 - t0),
           (unsigned long long)cs.computes);
    positions(smp, n, img, w, h, dots);
    snprintf(path, sizeof path, "build/adaptive-out/%s-%s-%02.0f.png", tag, metric_name[metric],
             100.0 * budget);
    png_write(path, w, h, img, 1.0f, err, sizeof err);
    snprintf(path, sizeof path, "build/adaptive-out/%s-%s-%02.0f-samples.png", tag,
             metric_name[metric], 100.0 * budget);
    png_write(path, w, h, dots, 1.0f, err, sizeof err);
    free(smp);
    renderer_free(&r);
    return 0;
}

int main(int argc, char **argv)
{
    static const double budgets[2] = {0.10, 0.17};
    scene s;
    renderer r;
    render_stats st;
    cam_frame cf;
    char err[1024], tag[128], path[512];
    const char *base;
    float *full, *img, *dots;
    unsigned char *bumpy;
    double t0, full_s;
    int w, h, m, b, nb = 0, do_check = 0, i, rc = 0;
    if (argc < 2) {
        fprintf(stderr, "usage: adaptive SCENE [W H] [--check | --check-only]\n");
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
    }
    if (argc >= 4 && argv[2][0] != '-') {
        s.cam.width = atoi(argv[2]);
        s.cam.height = atoi(argv[3]);
    }
    w = s.cam.width;
    h = s.cam.height;
    base = strrchr(argv[1], '/') ? strrchr(argv[1], '/') + 1 : argv[1];
    snprintf(tag, sizeof tag, "%.*s", (int)(strcspn(base, ".")), base);
    mkdir("build", 0777);
    mkdir("build/adaptive-out", 0777);
    full = malloc(sizeof *full * 3 * (size_t)w * (size_t)h);
    img = malloc(sizeof *img * 3 * (size_t)w * (size_t)h);
    dots = malloc(sizeof *dots * 3 * (size_t)w * (size_t)h);
    if (!full || !img || !dots || new_renderer(&r, &s) < 0)
        return 1;
    t0 = seconds();
    if (render_image(&r, full, &st) < 0)
        return 1;
    full_s = seconds() - t0;
    printf("%s %dx%d: full render %.2f s (one thread, %llu records)\n", tag, w, h, full_s,
           (unsigned long long)st.records);
    snprintf(path, sizeof path, "build/adaptive-out/%s-full.png", tag);
    png_write(path, w, h, full, 1.0f, err, sizeof err);
    camera_frame(&s.cam, &cf);
    bumpy = material_mask(&r, &cf, "bumpy", w, h, &nb);
    if (nb == 0) {
        free(bumpy);
        bumpy = NULL;
    }
    if (do_check) {
        grad_check g;
        if (image_gradient_check(&r, &cf, w, h, &g) < 0)
            rc = 1;
        else
            printf("gradient check (%dx%d, %d pixels inside objects): relative L2 error %.4f; "
                   "per pixel (|grad| > 0.1 mean, %d pixels): median %.4f, 90th percentile "
                   "%.4f\n", w, h, g.pixels, g.l2, g.strong, g.median, g.p90);
    }
    renderer_free(&r);
    for (b = 0; b < 2 && rc == 0 && do_check < 2; b++)
        for (m = 0; m < M_COUNT && rc == 0; m++)
            if (run(&s, tag, full, full_s, bumpy, m, budgets[b], img, dots) < 0)
                rc = 1;
    free(bumpy);
    free(full);
    free(img);
    free(dots);
    scene_free(&s);
    return rc;
}
