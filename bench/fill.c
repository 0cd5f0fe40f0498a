/*
 * fill.c -- what deterministic fills cost (make bench-fill): the demo's
 * Cornell box and fig5 scene rendered with records stored as threads make
 * them (--free-fill) and with fill passes (the default: 1,024 passes at
 * these widths), on 1 thread
 * and on every core, alternating, REPS times each; prints the median wall
 * time, records, rays, the indirect term's relative RMSE against a
 * brute-force reference on every 4th pixel, and whether repeated renders
 * came out bit-identical.  The ratio passes/free is the figure docs/DESIGN.md
 * quotes ("Fill passes: the same records whatever the threads"; target: at
 * most 1.10).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "render.h"

#define REPS 3
#define STRIDE 4

typedef struct fscene {
    const char *name, *path;
    int w, h;
} fscene;

static const fscene scenes[] = {
    {"cornell", "demo/scenes/cornell.scene", 512, 512},
    {"fig5", "demo/scenes/fig5.scene", 384, 288},
};

static int render(const scene *s, const render_opts *o, float *img, render_stats *st)
{
    renderer r;
    char err[256];
    int e;
    if (renderer_init(&r, s, o, err, sizeof err) < 0) {
        fprintf(stderr, "bench-fill: %s\n", err);
        return -1;
    }
    memset(img, 0, sizeof(float) * 3 * (size_t)s->cam.width * s->cam.height);
    e = render_image(&r, img, st);
    renderer_free(&r);
    return e < 0 ? -1 : 0;
}

/* sqrt(sum (a - b)^2 / sum b^2) over the reference's lattice. */
static double rel_rmse(const scene *s, const float *img, const float *ref)
{
    double se = 0.0, sr = 0.0;
    int x, y, k;
    for (y = 0; y < s->cam.height; y += STRIDE)
        for (x = 0; x < s->cam.width; x += STRIDE)
            for (k = 0; k < 3; k++) {
                size_t i = ((size_t)y * s->cam.width + x) * 3 + k;
                se += (img[i] - ref[i]) * (double)(img[i] - ref[i]);
                sr += ref[i] * (double)ref[i];
            }
    return sr > 0.0 ? sqrt(se / sr) : 0.0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* REPS renders of each fill, alternating; medians into wall[2]. */
static int compare(const scene *s, render_opts o, const float *ref, float *img, float *first,
                   double wall[2])
{
    double t[2][REPS];
    render_stats st[2];
    double err[2];
    int rep, f, same[2] = {1, 1};
    size_t bytes = sizeof(float) * 3 * (size_t)s->cam.width * s->cam.height;
    for (rep = 0; rep < REPS; rep++)
        for (f = 0; f < 2; f++) {
            o.free_fill = f;
            if (render(s, &o, img, &st[f]) < 0)
                return -1;
            t[f][rep] = st[f].wall;
            err[f] = rel_rmse(s, img, ref);
            if (rep == 0 && f == 0)
                memcpy(first, img, bytes);
            else if (f == 0)
                same[0] &= memcmp(first, img, bytes) == 0;
        }
    for (f = 0; f < 2; f++) {
        qsort(t[f], REPS, sizeof(double), cmp_double);
        wall[f] = t[f][REPS / 2];
        printf("  %d thread%s %-7s wall %6.2f s (median of %d)  records %6llu  rays %9llu  "
               "rel RMSE %.4f%s\n",
               o.threads, o.threads > 1 ? "s" : " ", f ? "free" : "passes", wall[f], REPS,
               (unsigned long long)st[f].records, (unsigned long long)st[f].rays, err[f],
               f ? "" : same[0] ? "  (every run identical)" : "  (runs DIFFER)");
    }
    printf("  %d thread%s passes / free: %.3f\n", o.threads, o.threads > 1 ? "s" : "",
           wall[0] / wall[1]);
    return same[0] ? 0 : -1;
}

int main(void)
{
    const int cores = (int)sysconf(_SC_NPROCESSORS_ONLN);
    size_t k;
    int bad = 0;
    printf("bench-fill: records stored as made (free) against fill passes (passes); "
           "a = 0.2, trans+rot, 16x64 strata, indirect term only\n");
    for (k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        const fscene *b = &scenes[k];
        scene s;
        render_opts o;
        render_stats st;
        char err[512];
        float *ref, *img, *first;
        double wall[2];
        int t;
        size_t n;
        if (scene_load(b->path, &s, err, sizeof err) < 0) {
            fprintf(stderr, "%s\n", err);
            return 1;
        }
        s.cam.width = b->w;
        s.cam.height = b->h;
        n = (size_t)b->w * b->h * 3;
        ref = malloc(n * sizeof(float));
        img = malloc(n * sizeof(float));
        first = malloc(n * sizeof(float));
        if (!ref || !img || !first)
            return 1;
        memset(&o, 0, sizeof o);
        o.threads = cores;
        o.show = SHOW_INDIRECT;
        o.light_samples = 1;
        o.seed = 7;
        o.mode = MODE_REFERENCE;
        o.ref_rays = 4096;
        o.stride = STRIDE;
        if (render(&s, &o, ref, &st) < 0)
            return 1;
        printf("%s %dx%d (reference: %d rays at every %dth pixel, %.1f s)\n", b->name, b->w,
               b->h, o.ref_rays, STRIDE, st.wall);
        o.mode = MODE_CACHE;
        o.stride = 0;
        o.features = IRC_FEATURE_TRANSLATION | IRC_FEATURE_ROTATION;
        o.accuracy = 0.2f;
        o.strata_m = 16;
        o.strata_n = 64;
        o.max_records = 400000;
        o.max_radius = -1.0f;
        for (t = 1; t <= cores; t = t < cores && 2 * t > cores ? cores : 2 * t) {
            o.threads = t;
            bad |= compare(&s, o, ref, img, first, wall) < 0;
        }
        free(ref);
        free(img);
        free(first);
        scene_free(&s);
    }
    return bad;
}
