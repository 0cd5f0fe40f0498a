/*
 * outliers.c -- which records answer a cache render's worst pixels, and
 * why.  Renders SCENE's indirect term
 * kd/pi E with the demo's defaults at a, takes the reference that make
 * bench cached for it (build/bench/ref-...: two seeds, averaged, on its
 * lattice), and for the worst 1% of lattice pixels by squared error looks
 * at the records a lookup there uses:
 *   hidden:   the segment from the pixel's point to the record's crosses
 *             geometry (the record is out of the point's sight);
 *   below:    the point lies below the record's tangent plane by more than
 *             1% of the reach (a groove or crease the record cannot see);
 *   far:      the point is outside the record's reach a R (a neighbour's
 *             weight past its radius: should not happen);
 * and how far the record's own value is from the reference at the point.
 *   outliers SCENE REF1.exr REF2.exr [a] [--clamp 0|1] [--lattice S]
 * Prints counts over the worst pixels and over all lattice pixels, and the
 * twenty worst with their records.
 */
#define IRC_EXPERIMENTAL /* irc_cache_neighbours (irrcache.h) */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "image.h"
#include "render.h"

/* make bench's lattice: every STRIDE-th pixel from OFFSET (8 and 5 for
 * the real scenes, 4 and 3 for the shipped ones: --lattice 4) */
static int STRIDE = 8, OFFSET = 5;
#define PI 3.14159265358979323846

typedef struct why {
    int pixels, with_hidden, with_below, with_far, served;
} why;

static float dist3(const float a[3], const float b[3])
{
    float d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* The records a lookup at pixel (x, y) uses, classified; verbose prints
 * each. */
static void look(renderer *r, const cam_frame *cf, int x, int y, float a, double ref, why *w,
                 int verbose)
{
    const camera *c = &r->s->cam;
    float d[3], p[3], fp;
    uint32_t ids[64], n = 0, i;
    bvh_hit bh;
    surface sf;
    int hidden = 0, below = 0, far = 0;
    const float *n3;
    camera_ray(cf, c, x, y, d);
    if (!bvh_intersect(&r->b, cf->eye, d, 0.0f, 1e30f, &bh))
        return;
    surface_at(r->s, cf->eye, d, &bh, &sf);
    cache_point(&sf, p);
    n3 = gather_normal(&sf); /* the normal the render's lookup took */
    fp = camera_footprint(cf, c, d, bh.t, sf.ng);
    if (verbose)
        printf("    at (%.4g, %.4g, %.4g), normal (%.3f, %.3f, %.3f), footprint %.3g\n", p[0], p[1],
               p[2], n3[0], n3[1], n3[2], fp);
    irc_cache_neighbours(r->cache, p, n3, ids, 64, &n);
    for (i = 0; i < n && i < 64; i++) {
        irc_record rec;
        float len, off;
        int h, b, f;
        if (irc_cache_record(r->cache, ids[i], &rec) != IRC_OK)
            continue;
        len = dist3(p, rec.p);
        h = render_hidden(r, p, rec.p);
        off = (p[0] - rec.p[0]) * rec.n[0] + (p[1] - rec.p[1]) * rec.n[1] +
              (p[2] - rec.p[2]) * rec.n[2];
        b = off < -0.01f * a * rec.radius;
        f = len > a * rec.radius * 1.0001f;
        hidden |= h, below |= b, far |= f;
        if (verbose)
            printf("      record %u: %.1f px away, reach %.1f px, n.n_i %.3f, E_i %.3f (%+.0f%% of "
                   "the reference)%s%s%s\n",
                   ids[i], len / fp, a * rec.radius / fp,
                   rec.n[0] * n3[0] + rec.n[1] * n3[1] + rec.n[2] * n3[2],
                   (double)rec.e[0], 100.0 * (rec.e[0] - ref) / (ref > 0.0 ? ref : 1.0),
                   h ? ", hidden" : "", b ? ", below" : "", f ? ", far" : "");
    }
    w->pixels++;
    w->served += n > 0;
    w->with_hidden += hidden;
    w->with_below += below;
    w->with_far += far;
}

static int by_err(const void *a, const void *b)
{
    const double *x = (const double *)a, *y = (const double *)b;
    return (x[0] < y[0]) - (x[0] > y[0]);
}

int main(int argc, char **argv)
{
    scene s;
    renderer r;
    render_opts o;
    render_stats st;
    cam_frame cf;
    char err[512];
    float *img, *r1, *r2;
    double *errs, se = 0.0;
    int w1, h1, w2, h2, i, m = 0, n, top;
    float a = argc > 4 ? (float)atof(argv[4]) : 0.2f;
    why all = {0, 0, 0, 0, 0}, worst = {0, 0, 0, 0, 0};
    if (argc < 4 || scene_load(argv[1], &s, err, sizeof err) < 0 ||
        exr_read(argv[2], &w1, &h1, &r1, err, sizeof err) < 0 ||
        exr_read(argv[3], &w2, &h2, &r2, err, sizeof err) < 0 || w1 != w2 || h1 != h2) {
        fprintf(stderr, "usage: outliers SCENE REF1.exr REF2.exr [a] [--clamp 0|1]%s%s\n",
                argc >= 4 ? ": " : "", argc >= 4 ? err : "");
        return 2;
    }
    s.cam.width = w1;
    s.cam.height = h1;
    render_opts_defaults(&o);
    o.accuracy = a;
    o.show = SHOW_INDIRECT;
    o.light_samples = 1;
    o.seed = 7;
    o.threads = 2;
    o.max_records = 400000;
    for (i = 5; i + 1 < argc; i += 2)
        if (!strcmp(argv[i], "--clamp"))
            o.clamp_neighbours = atoi(argv[i + 1]) ? IRC_ON : IRC_OFF;
        else if (!strcmp(argv[i], "--lattice"))
            STRIDE = atoi(argv[i + 1]), OFFSET = STRIDE / 2 + 1;
    n = w1 * h1;
    img = calloc((size_t)n * 3, sizeof(float));
    errs = malloc(sizeof(double) * 2 * (size_t)n);
    if (!img || !errs || renderer_init(&r, &s, &o, err, sizeof err) < 0 ||
        render_image(&r, img, &st) < 0) {
        fprintf(stderr, "outliers: render failed\n");
        return 1;
    }
    for (i = 0; i < n; i++) {
        const int x = i % w1, y = i / w1;
        double e = 0.0;
        int k;
        if ((x - OFFSET) % STRIDE || (y - OFFSET) % STRIDE || x < OFFSET || y < OFFSET)
            continue;
        for (k = 0; k < 3; k++) {
            double ref = 0.5 * (r1[3 * i + k] + r2[3 * i + k]);
            e += (img[3 * i + k] - ref) * (img[3 * i + k] - ref);
        }
        se += e;
        errs[2 * m] = e;
        errs[2 * m + 1] = i;
        m++;
    }
    qsort(errs, (size_t)m, 2 * sizeof(double), by_err);
    { /* the same pixels looked up again in the finished cache */
        double se2 = 0.0, sr = 0.0;
        int misses = 0;
        camera_frame(&s.cam, &cf);
        for (i = 0; i < m; i++) {
            const int p = (int)errs[2 * i + 1];
            float d[3], q[3], e[3];
            double v, ref = 0.5 * (r1[3 * p] + r2[3 * p]);
            bvh_hit bh;
            surface sf;
            camera_ray(&cf, &s.cam, p % w1, p / w1, d);
            v = img[3 * p];
            if (bvh_intersect(&r.b, cf.eye, d, 0.0f, 1e30f, &bh)) {
                surface_at(&s, cf.eye, d, &bh, &sf);
                cache_point(&sf, q);
                if (irc_cache_lookup(r.cache, q, gather_normal(&sf), e, NULL) == IRC_OK)
                    v = sf.m->kd[0] / PI * e[0];
                else
                    misses++;
            }
            se2 += 3.0 * (v - ref) * (v - ref);
            sr += 3.0 * ref * ref;
        }
        printf("relative RMSE (first channel x 3) as rendered %.4f; looked up again in the "
               "finished cache %.4f (%d misses kept)\n", sqrt(se / sr), sqrt(se2 / sr), misses);
    }
    top = (m + 99) / 100;
    camera_frame(&s.cam, &cf);
    {
        double share = 0.0;
        for (i = 0; i < top; i++)
            share += errs[2 * i];
        printf("%s at a = %g: %llu records; the worst 1%% (%d pixels) hold %.0f%% of the squared "
               "error\n", argv[1], (double)a, (unsigned long long)st.records, top,
               se > 0.0 ? 100.0 * share / se : 0.0);
    }
    for (i = 0; i < m; i++) {
        const int p = (int)errs[2 * i + 1], x = p % w1, y = p / w1;
        const double ref = 0.5 * (r1[3 * p] + r2[3 * p]) / (0.6 / PI); /* E, grey 0.6 */
        if (i < 20) {
            printf("  pixel %d %d: cache %.4f, reference %.4f (kd/pi E)\n", x, y, img[3 * p],
                   0.5 * (r1[3 * p] + r2[3 * p]));
        }
        look(&r, &cf, x, y, a, ref, i < top ? &worst : &all, i < 20);
    }
    printf("worst 1%%: %d pixels, %d served by records: %d use a record hidden from them, %d one "
           "they lie below, %d one past its reach\n", worst.pixels, worst.served,
           worst.with_hidden, worst.with_below, worst.with_far);
    printf("the rest: %d pixels, %d served: %d hidden, %d below, %d past reach\n", all.pixels,
           all.served, all.with_hidden, all.with_below, all.with_far);
    renderer_free(&r);
    scene_free(&s);
    free(img);
    free(errs);
    free(r1);
    free(r2);
    return 0;
}
